#!/usr/bin/env bash
# On the device machine: calibrate-rom on the four pipeline-rom training references with the GPU
# batch, at the given sampler settings, each run timed; logs under $OUT. Usage (from the bundle):
#   device_rom_calibration.sh BIN_DIR REF_DIR "label:args" ...
set -u
bin=$1 refs=$2
shift 2
r="$refs/accel,$refs/step_left,$refs/step_right,$refs/dlc"
for spec in "$@"; do
  label=${spec%%:*} args=${spec#*:}
  start=$(date +%s%N)
  # shellcheck disable=SC2086
  timeout 240 "$bin/terracal" calibrate-rom --vehicle hmmwv --reference "$r" --no-plots --out "/tmp/cal_$label" \
    $args > "$OUT/cal_$label.log" 2>&1
  rc=$?
  end=$(date +%s%N)
  echo "$label ($args): rc $rc, $(( (end - start) / 1000000 )) ms" | tee -a "$OUT/summary.txt"
  tail -2 "$OUT/cal_$label.log" | cut -c1-300 | tee -a "$OUT/summary.txt"
done
