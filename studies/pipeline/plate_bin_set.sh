#!/usr/bin/env bash
# Does the calibrated SCM set depend on the plate bin? Runs both plates of the pipeline (0.2 and 0.3 m
# to 0.2 m) in CRM in the rigs' bin (walls 13.5 radii away over 3 x (max sinkage + 2.5 radii); docs/
# decisions.md "Plate bin") and in one 1.5x wider and deeper, calibrates a set on each pair of plate
# curves with the same annulus curves, and compares the two sets (plate_bin_set_compare.py). A bin
# 1.02x (another bed of the same bin, run by hand with --bin-scale 1.02 into OUT/bin_1.02) gives the
# scatter between single runs, and is calibrated and compared too when it is there.
# The 0.3 m plate's 1.5x bin is 24 M particles at 0.03 m (about 12 H100-minutes), so the default
# spacing is 0.04 m, where all four runs fit one 10-minute call.
# Usage: [SPACING=0.04] plate_bin_set.sh crm OUT [TERRACAL=build/terracal] [extra CRM options, e.g. --device cuda]
#        plate_bin_set.sh calibrate OUT [TERRACAL=build/terracal] [SHEAR=results/pipeline_bevameter_2022/bevameter/shear.csv]
set -euo pipefail
stage=${1:?crm or calibrate}; out=${2:?output folder}; bin=${3:-build/terracal}; shift $(( $# < 3 ? $# : 3 ))
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
case "$stage" in
  crm)
    for s in 1 1.5; do
      [ -f "$out/bin_$s/plate.csv" ] && continue
      t0=$SECONDS
      "$bin" bevameter --solver crm --soil "$here/bevameter_soil_2022.json" \
        --test plate --plates 0.2,0.3 --max-sinkage 0.2 --spacing "${SPACING:-0.04}" --bin-scale "$s" --no-plots \
        --out "$out/bin_$s" "$@" > "$out/bin_$s.log" 2>&1 || { echo "bin $s failed: $out/bin_$s.log"; exit 1; }
      echo "bin $s: $((SECONDS - t0)) s" | tee -a "$out/wall.txt"
    done
    ;;
  calibrate)
    shear=${1:-$here/../../results/pipeline_bevameter_2022/bevameter/shear.csv}
    for s in 1 1.5 1.02; do
      [ -f "$out/bin_$s/plate.csv" ] || continue
      "$bin" calibrate --plate "$out/bin_$s/plate.csv" --shear "$shear" --out "$out/set_$s" \
        > "$out/set_$s.log" 2>&1 || { echo "calibration of bin $s: exit $? ($out/set_$s.log)"; }
    done
    for s in 1.5 1.02; do
      [ -f "$out/set_$s/scm_params.json" ] || continue
      python3 "$here/plate_bin_set_compare.py" "$out/set_1/scm_params.json" "$out/set_$s/scm_params.json" \
        "$out/bin_1/plate.csv" "$out/bin_$s/plate.csv" | sed "s/1.5x bin/bin x $s/g" | tee "$out/comparison_$s.md"
    done
    ;;
  *) echo "stage must be crm or calibrate, not '$stage'" >&2; exit 2 ;;
esac
