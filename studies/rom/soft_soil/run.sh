#!/usr/bin/env bash
# The ROMs' deformable_terrain effect against the full vehicle on SCM dry sand: a wheel table of the
# full vehicle's SCM wheel (the HMMWV's tire radius, HMMWV_RigidTire's width), then a straight
# acceleration and a constant-steer turn driven by the full vehicle on SCM and on rigid ground; the
# 11- and 18-DOF ROMs replay each run's inputs.txt on the table and on rigid ground.
# Usage: studies/rom/soft_soil/run.sh [OUT=results/rom_soft_soil]   (about 3 minutes on one core)
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=${1:-results/rom_soft_soil}
here=studies/rom/soft_soil
scm=studies/bevameter_cost/dry_sand_scm.json
T=./build/terracal
mkdir -p "$out/runs"
runs=$out/runs
$T wheel-table --scm $scm --wheel $here/hmmwv_wheel.json --grid 0.02 --loads 2000,4000,6000,8000,10000 \
  --slips 0,0.05,0.1,0.2,0.3,0.5,0.8 --slip-angles 0,0.05,0.1,0.2,0.3 --duration 3 --out "$runs/dry_sand_table.h5" \
  2> "$runs/wheel_table.log" | tee "$runs/wheel_table.txt"
for m in accel turn; do
  for ground in scm rigid; do
    extra=""; [ $ground = scm ] && extra="--scm $scm"
    $T vehicle --vehicle hmmwv --terrain $ground $extra --maneuver $here/$m.json --no-plots \
      --out "$runs/full_${m}_$ground" 2> "$runs/full_${m}_$ground.log"
    v0=$(awk -F, 'NR == 2 { print $8 }' "$runs/full_${m}_$ground/trajectory.csv")
    table=""; [ $ground = scm ] && table="--terrain-table $runs/dry_sand_table.h5"
    for model in 11dof 18dof; do
      $T rom --model $model --vehicle hmmwv --inputs "$runs/full_${m}_$ground/inputs.txt" --initial-speed "$v0" \
        $table --no-plots --out "$runs/rom_${model}_${m}_$ground" 2> /dev/null
      if [ $ground = scm ]; then  # what leaving the soil out costs: the same inputs on rigid ground
        $T rom --model $model --vehicle hmmwv --inputs "$runs/full_${m}_$ground/inputs.txt" --initial-speed "$v0" \
          --no-plots --out "$runs/rom_${model}_${m}_scm_as_rigid" 2> /dev/null
      fi
    done
  done
done
python3 $here/compare.py "$out"
