#!/usr/bin/env bash
# The ROM accuracy-cost study: runs rom_accuracy_cost (one core) and draws accuracy_cost.png.
# Usage: studies/rom/accuracy_cost.sh [OUT=results/rom_accuracy_cost]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-results/rom_accuracy_cost}
OMP_NUM_THREADS=1 ./build/rom_accuracy_cost "$out" > /dev/null
cd "$out"
gnuplot <<'GP'
set terminal pngcairo noenhanced size 1400,560 font 'Sans,11'
set output 'accuracy_cost.png'
set datafile separator ','
set logscale xy
set grid
set key outside right
set xlabel 'wall time for the run [s] (one core)'
set ylabel 'yaw rate RMS error / reference RMS'
set multiplot layout 1,2
do for [i=1:2] {
  name = i == 1 ? 'iso3888_1 at 15 m/s' : 'step steer at 20 m/s'
  set title name.' (reference: 24-DOF, CVODES rtol 1e-10)'
  plot for [m in "11dof 18dof 24dof"] for [integ in "half-implicit cvodes"] \
    'accuracy_cost.csv' using (strcol(1) eq name && strcol(2) eq m && strcol(3) eq integ ? $5 : NaN):7 \
    with linespoints lw 2 pt (integ eq 'cvodes' ? 6 : 7) title m.' '.integ
}
unset multiplot
GP
echo "written: $out/accuracy_cost.csv, table.md, accuracy_cost.png"
