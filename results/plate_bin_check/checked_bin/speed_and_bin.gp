# Session 9: the plates in the checked bin (walls 13.5 radii over 3x (sinkage + 2.5 r)), hourglass_damping 0.4, 0.03 m:
# the plate speed (0.1, 0.05, 0.025 m/s) and the 1.5x bin
set terminal pngcairo size 1200,550 font ",11"
set output "speed_and_bin.png"
set termoption noenhanced
set datafile separator ","
set key top left
set xlabel "sinkage [m]"
set ylabel "plate force [kN]"
set grid
ld(f) = sprintf("< awk -F, 'NR==1 || $4==\"load\"' %s", f)
set multiplot layout 1,2
set title "0.2 m plate: speed"
plot ld("r0.2_d0.03_scale_1.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#b2182b" t "0.1 m/s", \
     ld("r0.2_d0.03_v0.05.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#4393c3" t "0.05 m/s", \
     ld("r0.2_d0.03_v0.025.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#2166ac" t "0.025 m/s"
set title "0.3 m plate: speed and bin"
plot ld("r0.3_d0.03_scale_1.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#b2182b" t "0.1 m/s, checked bin", \
     ld("r0.3_d0.03_scale_1.5.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#1b7837" t "0.1 m/s, bin 1.5x", \
     ld("r0.3_d0.03_v0.05.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#4393c3" t "0.05 m/s, checked bin"
unset multiplot
