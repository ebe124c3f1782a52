#!/usr/bin/env bash
# The run-length check of the plate: the CRM plate pushed at several speeds (each halving
# doubles the test's duration) in the rigs' bin, and the change of the loading leg from each speed
# to the next, measured as the bin check measures it (curve_change.awk beside this file).
# Usage: [SPACING=0.03] [PLATE=0.3] plate_speed_check.sh OUT [TERRACAL=build/terracal] [SPEEDS="0.1 0.05 0.025"]
#          [extra options...]
set -euo pipefail
out=${1:?output folder}; bin=${2:-build/terracal}; speeds=${3:-0.1 0.05 0.025}; shift $(( $# < 3 ? $# : 3 ))
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
for v in $speeds; do
  [ -f "$out/v$v/plate.csv" ] && continue
  "$bin" bevameter --solver crm --soil "$here/bevameter_soil_2022.json" --test plate --plates "${PLATE:-0.3}" \
    --max-sinkage 0.2 --spacing "${SPACING:-0.03}" --plate-speed "$v" --no-plots --out "$out/v$v" "$@" \
    > "$out/v$v.log" 2>&1
done
force_at() { awk -F, -v z="$2" 'NR > 1 && ($4 == "load" || $4 == "reload") && $2 >= z - 1e-4 { print $3; exit }' "$1"; }
{
  echo "| plate speed [m/s] | F(0.05 m) [N] | F(0.1 m) [N] | F(0.2 m) [N] |" \
    "change of the loading leg from the previous speed |"
  echo "|---|---|---|---|---|"
  prev=""
  for v in $speeds; do
    f="$out/v$v/plate.csv"
    c=$([ -n "$prev" ] && [ -f "$f" ] && awk -F, -f "$here/curve_change.awk" "$out/v$prev/plate.csv" "$f" || echo "-")
    echo "| $v | $(force_at "$f" 0.05 2>/dev/null) | $(force_at "$f" 0.1 2>/dev/null)" \
      "| $(force_at "$f" 0.2 2>/dev/null) | $c |"
    prev=$v
  done
} | tee "$out/table.md"
