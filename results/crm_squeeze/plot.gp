# gnuplot plot.gp: force_sinkage.png from force_sinkage.csv
set terminal pngcairo size 1200,520 font ",11"
set output "force_sinkage.png"
set datafile separator ","
set multiplot layout 1,2
set xlabel "sinkage below the surface [m] (floor at 0.2 m)"
set ylabel "plate force [kN]"
set key top left
set grid
set xrange [0:0.2]
set yrange [0:400]
set title "fixed density cap 1.5 rho0, spacing 0.01 m, r = 0.3 m (H100)"
plot "< grep fixed_cap_d01_cfl0.3, force_sinkage.csv" u 7:($8/1000) w l lw 2 t "cfl 0.3", \
     "< grep fixed_cap_d01_cfl0.15, force_sinkage.csv" u 7:($8/1000) w l lw 2 t "cfl 0.15", \
     "< grep fixed_cap_d01_cfl0.075, force_sinkage.csv" u 7:($8/1000) w l lw 2 t "cfl 0.075"
set title "density cap 1.5 rho0 exp(p/K), cfl 0.3, r = 0.3 m unless named (H100)"
plot "< grep pressure_cap_d02, force_sinkage.csv" u 7:($8/1000) w l lw 2 t "0.02 m", \
     "< grep pressure_cap_d01, force_sinkage.csv" u 7:($8/1000) w l lw 2 t "0.01 m", \
     "< grep pressure_cap_d01_r0.2, force_sinkage.csv" u 7:($8/1000) w l lw 2 t "0.01 m, r = 0.2 m", \
     "< grep pressure_cap_d005, force_sinkage.csv" u 7:($8/1000) w l lw 2 t "0.005 m"
unset multiplot
