# gnuplot h1.4.gp (in results/plate_bin_check/h1.4): the seventh study's plate curves and held plates
set terminal pngcairo size 1400,480 font ",11"
set output "h1.4.png"
set datafile separator ","
set multiplot layout 1,3
set grid
set xlabel "sinkage [m]"; set ylabel "force [N]"; set key top left
set title "0.2 m plate, 0.03 m, h/d0 1.4"
plot "r0.2_d0.03_v0.1.csv" u 2:3 w l lw 2 t "0.1 m/s", "r0.2_d0.03_v0.05.csv" u 2:3 w l lw 2 t "0.05 m/s", \
     "r0.2_d0.03_v0.1_scale_1.5.csv" u 2:3 w l lw 2 dt 2 t "0.1 m/s, bin 1.5x"
set title "0.3 m plate, 0.03 m, h/d0 1.4"
plot "r0.3_d0.03_v0.1.csv" u 2:3 w l lw 2 t "0.1 m/s", "r0.3_d0.03_v0.05.csv" u 2:3 w l lw 2 t "0.05 m/s"
set title "0.2 m plate pushed 0.08 m, then held (t > 0.8 s)"
set xlabel "time after the plate started [s]"; set key top right
plot for [v in "base slow hg2 av0.5 xsph fs0.5 cfl0.15 h1.2"] "hold.csv" u (strcol(1) eq v ? $2 : NaN):3 w l lw 1.5 t v
unset multiplot
