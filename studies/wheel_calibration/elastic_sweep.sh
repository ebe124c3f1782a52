#!/usr/bin/env bash
# The set's elastic stiffness against the wheel: the joint calibration with the annulus's law scaled
# (as run.sh's joint_scaled), but with the set's Ke given (`calibrate --elastic-stiffness`) instead of
# the plates' unload fit, and the time-stepping SCM wheel with each set at both loads. SCM's rut
# springs back by Ke: the softer it is, the more the rim's rear carries and the less motion
# resistance the wheel meets at low slip.
# Usage: studies/wheel_calibration/elastic_sweep.sh path/to/terracal results/wheel_calibration_2022
# (after run.sh, whose data/ and joint_scaled sweeps it reuses); writes OUT/elastic_sweep/.
set -euo pipefail
exe=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
src="$here/../../results/pipeline_bevameter_2022"
sweep="$out/elastic_sweep"
mkdir -p "$sweep"
slips=0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8
for ke in 3e6 4e6 8e6 1.6e7 4e7; do
  fit="$sweep/ke_$ke"
  [ -f "$fit/scm_params.json" ] || "$exe" calibrate --plate "$src/bevameter/plate.csv" \
    --shear "$src/bevameter/shear.csv" --wheel "$out/data/wheel_calibration.csv" \
    --wheel-spec "$here/../campaign/wheel.json" --annulus-law scaled --elastic-stiffness $ke --no-plots \
    --out "$fit" > "$fit.log" 2>&1
  for mass in 108 162; do
    wheel="$here/../campaign/wheel.json"; [ $mass = 162 ] && wheel="$here/wheel_162kg.json"
    "$exe" wheel --terrain scm --scm "$fit/scm_params.json" --scm-effects damping --scm-effects slip_sinkage \
      --wheel "$wheel" --slips $slips --duration 6 --no-plots --out "$sweep/scm_ke_${ke}_${mass}kg" \
      > "$sweep/scm_ke_${ke}_${mass}kg.log" 2>&1
  done
done
python3 "$here/elastic_sweep.py" "$out" > "$sweep/table.md"
cat "$sweep/table.md"
