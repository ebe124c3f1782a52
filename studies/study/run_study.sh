# Sourced by the study scripts: run_study BIN STUDY SOLVER SPEC WORK DEST runs `terracal study` (SPEC ''
# for the default spec) in WORK, a campaign folder (run again, it goes on where it stopped), logs to
# /tmp/terracal_study_<name>.log, and copies the report, its CSV and plot and the spec as run into DEST.
run_study() {
  local bin=$1 study=$2 solver=$3 spec=$4 work=$5 dest=$6 start log
  log=/tmp/terracal_study_$(echo "$work" | tr '/' '_').log
  start=$(date +%s)
  "$bin" study "$study" --solver "$solver" ${spec:+--spec "$spec"} --out "$work" > "$log" 2>&1
  echo "$solver $study${spec:+ ($spec)}: exit $? in $(( $(date +%s) - start )) s"
  mkdir -p "$dest"
  cp "$work"/report.md "$work"/spec.json "$work"/*.csv "$dest"/
  cp "$work"/*.png "$dest"/ 2>/dev/null || echo "  (no plot: gnuplot missing)"
}
