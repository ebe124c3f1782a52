# gnuplot lattice_stability.gp (in results/crm_settling): beds released from the lattice at h/d0 1.2 and 1.4
set terminal pngcairo size 900,520 font ",11"
set output "lattice_stability.png"
set datafile separator ","
set logscale y
set yrange [1e-4:0.3]
set xlabel "time after release [s]"
set ylabel "rms particle speed [m/s]"
set title "Beds released from the lattice: h/d0 1.2 (Wendland C2) bursts, 1.4 stays at rest"
set grid
set key top left
plot "bed_2.85m_d0.06.csv" every ::2 using 1:3 with lines lw 2 lc rgb "#d62728" title "2.85 m deep, 0.06 m, h/d0 1.2", \
     "bed_0.96m_d0.03.csv" every ::2 using 1:3 with lines lw 2 lc rgb "#ff7f0e" title "0.96 m deep, 0.03 m, h/d0 1.2", \
     "bed_2.85m_d0.06_h1.4.csv" every ::2 using 1:3 with lines lw 2 lc rgb "#1f77b4" title "2.85 m deep, 0.06 m, h/d0 1.4", \
     "bed_0.96m_d0.03_h1.4.csv" every ::2 using 1:3 with lines lw 2 lc rgb "#17becf" title "0.96 m deep, 0.03 m, h/d0 1.4", \
     "bed_2.85m_d0.02_h1.4_gpu.csv" every ::2 using 1:3 with lines lw 2 lc rgb "#2ca02c" title "2.85 m deep, 0.02 m, h/d0 1.4 (GPU)"
