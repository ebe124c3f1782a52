#!/usr/bin/env bash
# Does any Janosi k, with the set's Ke given, bring pull and torque within 10 % at both loads? Takes the
# sets of run.sh (joint_scaled, the plates' Ke) and elastic_sweep.sh (Ke 8e6 and 4e7), sets their k to
# each value of a grid, runs the time-stepping SCM wheel at both loads and tabulates the RMSE in % of
# CRM's range (pull / torque / sinkage).
# Usage: studies/wheel_calibration/elastic_k_grid.sh path/to/terracal results/wheel_calibration_2022
set -euo pipefail
exe=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
grid="$out/elastic_sweep/k_grid"
mkdir -p "$grid"
for base in joint_scaled elastic_sweep/ke_8e6 elastic_sweep/ke_4e7; do
  for k in 0.015 0.025 0.035 0.045 0.06; do
    name="$(basename "$base")_k$k"
    python3 - "$out/$base/scm_params.json" "$k" "$grid/$name.json" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
p["Soil parameters"]["Janosi shear coefficient"] = float(sys.argv[2])
p.pop("Posterior", None)
p.pop("Fit", None)
json.dump(p, open(sys.argv[3], "w"), indent=1)
PY
    for mass in 108 162; do
      wheel="$here/../campaign/wheel.json"; [ $mass = 162 ] && wheel="$here/wheel_162kg.json"
      "$exe" wheel --terrain scm --scm "$grid/$name.json" --scm-effects damping --scm-effects slip_sinkage \
        --wheel "$wheel" --slips 0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8 --duration 6 --no-plots \
        --out "$grid/scm_${name}_${mass}kg" > "$grid/scm_${name}_${mass}kg.log" 2>&1
    done
  done
done
python3 "$here/elastic_sweep.py" "$out" --k-grid > "$grid/table.md"
cat "$grid/table.md"
