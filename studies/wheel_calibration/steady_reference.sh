#!/usr/bin/env bash
# The wheel study against CRM rows that have reached a steady state: the 9 s CRM runs of slips 0.4-0.8
# in OUT/crm_9s (made on a GPU: `terracal wheel --terrain crm --soil studies/pipeline/bevameter_soil_2022.json
# --device cuda --spacing 0.02 --duration 9` with the 108 kg wheel at slips 0.4,0.6,0.8 and 0.7, and the
# 162 kg wheel at 0.8 and 0.6,0.7) replace the 3 s rows; the scaled-law joint calibration is redone on the
# steady calibration rows and its SCM wheel run at both loads; then every set's RMSE against both.
# Usage: studies/wheel_calibration/steady_reference.sh path/to/terracal results/wheel_calibration_2022
# (after run.sh and elastic_sweep.sh).
set -euo pipefail
exe=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
src="$here/../../results/pipeline_bevameter_2022"
python3 "$here/steady_reference.py" "$out" > /dev/null  # writes data/crm_*kg_steady.csv
awk -F, 'NR == 1 || $1 == "0.1" || $1 == "0.3" || $1 == "0.5" || $1 == "0.7"' "$out/data/crm_108kg_steady.csv" \
  > "$out/data/wheel_calibration_steady.csv"
[ -f "$out/joint_scaled_steady/scm_params.json" ] || "$exe" calibrate --plate "$src/bevameter/plate.csv" \
  --shear "$src/bevameter/shear.csv" --wheel "$out/data/wheel_calibration_steady.csv" \
  --wheel-spec "$here/../campaign/wheel.json" --annulus-law scaled --no-plots --out "$out/joint_scaled_steady" \
  > "$out/joint_scaled_steady.log" 2>&1
for mass in 108 162; do
  wheel="$here/../campaign/wheel.json"; [ $mass = 162 ] && wheel="$here/wheel_162kg.json"
  "$exe" wheel --terrain scm --scm "$out/joint_scaled_steady/scm_params.json" --scm-effects damping \
    --scm-effects slip_sinkage --wheel "$wheel" --slips 0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8 --duration 6 --no-plots \
    --out "$out/scm_joint_scaled_steady_${mass}kg" > "$out/scm_joint_scaled_steady_${mass}kg.log" 2>&1
done
python3 "$here/steady_reference.py" "$out" > "$out/steady_reference.md"
cat "$out/steady_reference.md"
