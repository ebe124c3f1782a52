#!/usr/bin/env bash
# Every ROM model x integrator setting against the 24-DOF model at CVODES rtol 1e-10, on the ISO
# 3888-1 double lane change and the ISO 7401 step steer: `terracal study accuracy-cost --solver rom`
# with the specs rom_grid_dlc.json and rom_grid_step_steer.json. Usage: studies/study/rom_grid.sh BIN
# [OUT=results/rom_accuracy_cost]. The studies run in /tmp/terracal_study/rom_grid/<manoeuvre>; the
# report, its CSV and plot and the spec as run are copied into OUT/<manoeuvre>/.
set -uo pipefail
cd "$(dirname "$0")/../.."
source studies/study/run_study.sh
bin=${1:?terracal program}
out=${2:-results/rom_accuracy_cost}
for m in dlc step_steer; do
  # One run at a time: the wall times are the comparison.
  OMP_NUM_THREADS=1 run_study "$bin" accuracy-cost rom studies/study/rom_grid_$m.json /tmp/terracal_study/rom_grid/$m \
    "$out/$m"
done
