# gnuplot wall_markers.gp -> wall_markers.png (run in this folder)
set terminal pngcairo size 1500,520 font ",11"
set output "wall_markers.png"
set datafile separator ","
set multiplot layout 1,3
set grid
set key top left
set xlabel "sinkage [m]"; set ylabel "plate force [kN]"
set title "0.2 m plate, 0.03 m spacing: loading legs"
plot "r0.2_d0.03_v0.1.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 lc rgb "#1f77b4" t "wall, 0.1 m/s", \
     "r0.2_d0.03_v0.05.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 dt 2 lc rgb "#1f77b4" t "wall, 0.05 m/s", \
     "r0.2_d0.03_v0.1_scale_1.5.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 1 lc rgb "#2ca02c" t "wall, 0.1 m/s, bin 1.5x", \
     "../h1.4/r0.2_d0.03_v0.1.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 lc rgb "#d62728" t "mirror, 0.1 m/s", \
     "../h1.4/r0.2_d0.03_v0.05.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 dt 2 lc rgb "#d62728" t "mirror, 0.05 m/s"
set title "0.3 m plate, 0.03 m spacing: loading legs"
plot "r0.3_d0.03_v0.1.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 lc rgb "#1f77b4" t "wall, 0.1 m/s", \
     "r0.3_d0.03_v0.05.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 dt 2 lc rgb "#1f77b4" t "wall, 0.05 m/s", \
     "../h1.4/r0.3_d0.03_v0.1.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 lc rgb "#d62728" t "mirror, 0.1 m/s", \
     "../h1.4/r0.3_d0.03_v0.05.csv" u 2:(strcol(4) eq "unload" ? 1/0 : $3/1000) w l lw 2 dt 2 lc rgb "#d62728" t "mirror, 0.05 m/s"
set title "0.2 m plate pushed 0.08 m, then held (from 0.8 s)"
set xlabel "time [s]"; set key top right
plot "hold.csv" u 2:(strcol(1) eq "wall" ? $3/1000 : 1/0) w l lw 2 lc rgb "#1f77b4" t "wall", \
     "hold.csv" u 2:(strcol(1) eq "mirror" ? $3/1000 : 1/0) w l lw 2 lc rgb "#d62728" t "mirror"
unset multiplot
