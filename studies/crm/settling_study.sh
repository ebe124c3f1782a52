#!/usr/bin/env bash
# How long a CRM bed takes to come to rest after its release from the lattice (results/crm_settling):
# beds 0.96 m and 2.85 m deep (the plate bins of results/plate_bin_check) at 0.06 m, and 0.96 m at
# 0.03 m, on the CPU; then a plot of the rms particle speed against time.
# Usage: studies/crm/settling_study.sh [OUT=results/crm_settling] [PROBE=build/crm_settle_probe]
#   (about 16 min on 2 cores)
set -euo pipefail
out=${1:-results/crm_settling}; probe=${2:-build/crm_settle_probe}
mkdir -p "$out"
run() { [ -f "$out/$1" ] || { "$probe" "${@:2}" > "$out/$1.tmp" && mv "$out/$1.tmp" "$out/$1"; }; }
# h/d0 1.2, where the lattice is unstable (docs/decisions.md, "Smoothing length"): the lattice bursts.
run bed_0.96m_d0.06.csv 0.96 0.06 1.5 1.5 0 cpu 0 h:1.2
run bed_2.85m_d0.06.csv 2.85 0.06 1.5 1.5 0 cpu 0 h:1.2
run bed_0.96m_d0.03.csv 0.96 0.03 1.5 1.0 0 cpu 0 h:1.2
# The same beds started 0.1 spacing off the lattice (settle_jitter 0.1).
run bed_0.96m_d0.06_jitter0.1.csv 0.96 0.06 1.5 1.5 0 cpu 0.1 h:1.2
run bed_2.85m_d0.06_jitter0.1.csv 2.85 0.06 1.5 1.0 0 cpu 0.1 h:1.2
# h/d0 1.4, the default: the lattice is stable (the 0.02 m bed of
# lattice_stability.png ran on a GPU: crm_settle_probe 2.85 0.02 1.5 0.8 0 cuda 0 h:1.4).
run bed_2.85m_d0.06_h1.4.csv 2.85 0.06 1.5 0.8 0 cpu 0 h:1.4
run bed_0.96m_d0.03_h1.4.csv 0.96 0.03 1.5 1.0 0 cpu 0 h:1.4
command -v gnuplot > /dev/null || { echo "gnuplot missing: no plot"; exit 0; }
gnuplot <<GP
set terminal pngcairo size 900,520 font ",11"
set output "$out/settling.png.tmp"
set datafile separator ","
set logscale y
set xlabel "time after release [s]"
set ylabel "rms particle speed [m/s]"
set title "CRM bed released from the lattice: the burst, and the 0.3 s that settling waits"
set grid
set arrow from 0.3, graph 0 to 0.3, graph 1 nohead dt 2 lc rgb "gray40"
set label "end of the default settling (0.3 s)" at 0.32, graph 0.95 tc rgb "gray30"
plot "$out/bed_0.96m_d0.06.csv" every ::2 using 1:3 with lines lw 2 title "0.96 m deep, 0.06 m", \
     "$out/bed_2.85m_d0.06.csv" every ::2 using 1:3 with lines lw 2 title "2.85 m deep, 0.06 m", \
     "$out/bed_0.96m_d0.03.csv" every ::2 using 1:3 with lines lw 2 title "0.96 m deep, 0.03 m", \
     "$out/bed_0.96m_d0.06_jitter0.1.csv" every ::2 using 1:3 with lines lw 2 dt 2 \
       title "0.96 m deep, 0.06 m, jitter 0.1", \
     "$out/bed_2.85m_d0.06_jitter0.1.csv" every ::2 using 1:3 with lines lw 2 dt 2 \
       title "2.85 m deep, 0.06 m, jitter 0.1"
GP
mv "$out/settling.png.tmp" "$out/settling.png"
[ -f "$out/bed_2.85m_d0.02_h1.4_gpu.csv" ] && [ -f "$out/lattice_stability.gp" ] \
  && (cd "$out" && gnuplot lattice_stability.gp) || true
