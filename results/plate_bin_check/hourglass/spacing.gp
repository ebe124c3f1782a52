# The 0.3 m plate's loading leg in the checked bin at three spacings, without and with hourglass_damping
set terminal pngcairo size 1000,650 font ",11"
set output "spacing.png"
set termoption noenhanced
set datafile separator ","
set key top left
set xlabel "sinkage [m]"
set ylabel "plate force [kN]"
set title "0.3 m plate, bevameter study soil (2022), 0.1 m/s: spacing with and without hourglass_damping (alpha 0.4)"
set grid
ld(f) = sprintf("< awk -F, 'NR==1 || $4==\"load\"' %s", f)
plot ld("r0.3_d0.04.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#f4a582" t "0.04 m", \
     ld("../both_0.03/new/scale_1/plate.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#d6604d" t "0.03 m", \
     ld("../both_0.02/r0.3_scale_1.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#b2182b" t "0.02 m", \
     ld("r0.3_d0.04_hg0.4.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#92c5de" t "0.04 m, hourglass_damping", \
     ld("r0.3_d0.03_hg0.4.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#4393c3" t "0.03 m, hourglass_damping", \
     ld("r0.3_d0.02_hg0.4.csv") u 2:($3/1000) w l lw 1.5 lc rgb "#2166ac" t "0.02 m, hourglass_damping"
