#!/usr/bin/env bash
# The bin-size and run-length checks of the annulus: how far the walls and the floor must be, and whether the torque
# curve depends on how long the test lasts. Runs the 0.15-0.20 m annulus under LOAD (default the
# pipeline's heaviest, 1962 N) in CRM, as gpu_validation.sh does (0.02 m unless SPACING, step 1e-4 s, 0.5 s
# settling), once per case W:D:RATE:ANGLE (walls scaled by W, bed depth by D, turned at RATE rad/s to
# ANGLE rad; 1:1:1:0.6 is the rigs' bin). Then annulus_summary.py OUT compares the curves as the
# pipeline's checks do (rigs::curve_change).
# Usage: [LOAD=1962] [SPACING=0.02] [SETTLE=0.5] [DEVICE=cuda] annulus_bin_check.sh OUT [TERRACAL=build/terracal]
#          [CASES="1:1:1:0.6 1.5:1.5:1:0.6 ..."] [extra options...]
set -euo pipefail
out=${1:?output folder}; bin=${2:-build/terracal}
cases=${3:-1:1:1:0.6 1.5:1.5:1:0.6 2.25:2.25:1:0.6 1:1.5:1:0.6 1.5:1:1:0.6 1:1:0.667:0.6 1:1:1:0.9}
shift $(( $# < 3 ? $# : 3 ))
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
for c in $cases; do
  IFS=: read -r w d rate angle <<< "$c"
  tag="w${w}_d${d}_r${rate}_a${angle}"
  [ -f "$out/$tag/shear.csv" ] && continue
  "$bin" bevameter --solver crm --soil "$here/bevameter_soil_2022.json" --test shear --shear-loads "${LOAD:-1962}" \
    --spacing "${SPACING:-0.02}" --shear-step 1e-4 --shear-settle "${SETTLE:-0.5}" \
    --shear-rate "$rate" --shear-angle "$angle" \
    --bin-scale "$w" --bin-depth-scale "$d" --device "${DEVICE:-cuda}" --no-plots --out "$out/$tag" "$@" \
    > "$out/$tag.log" 2>&1 ||
    echo "case $c failed (see $out/$tag.log)"
done
