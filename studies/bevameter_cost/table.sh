#!/usr/bin/env bash
# Tabulates the runs of run.sh: plate force at sinkages 0.05, 0.10, 0.15, 0.20 m (load or reload
# past the unload cycle), wall time, and the error against the reference (the finest CRM spacing
# for CRM; Bekker's law of the SCM set for SCM). Writes OUT/table.md and OUT/cost.png.
set -euo pipefail
out=${1:?output folder}
force_at() {  # plate.csv, sinkage -> force on the virgin curve (rows that reach a new deepest sinkage),
  # interpolated linearly between the rows around it; empty if the curve ends more than 1 mm short
  awk -F, -v z="$2" 'NR > 1 && $2 > deep { if ($2 >= z && deep > 0) {
                         printf "%.6g\n", f + ($3 - f) * (z - deep) / ($2 - deep); done = 1; exit }
                                             deep = $2; f = $3 }
                     END { if (!done && deep >= z - 1e-3) printf "%.6g\n", f }' "$1"
}
wall_of() { grep -o '"plate_wall_seconds": *[0-9.e+-]*' "$1/run.json" | sed 's/.*: *//' | xargs printf '%.3g'; }
bekker() { awk -v z="$1" 'BEGIN { r = 0.2; printf "%.6g", 3.14159265358979 * r * r * (990 / r + 1528430) * z ^ 1.1 }'; }
zs="0.05 0.1 0.15 0.2"
crm=$(ls -d "$out"/crm_* 2>/dev/null | sort -t_ -k2 -g || true)
finest=$(ls -d "$out"/crm_* 2>/dev/null | sort -t_ -k2 -g | head -1 || true)
{
  echo "| model | resolution [m] | wall [s] | F(0.05) [N] | F(0.10) | F(0.15) | F(0.20) | largest error |"
  echo "|---|---|---|---|---|---|---|---|"
  for d in $(ls -d "$out"/crm_* 2>/dev/null | sort -t_ -k2 -gr) ; do
    res=${d##*_}; row="| CRM | $res | $(wall_of "$d") |"; worst=0
    for z in $zs; do
      f=$(force_at "$d/plate.csv" "$z"); ref=$(force_at "$finest/plate.csv" "$z"); row="$row $f |"
      worst=$(awk -v a="$f" -v b="$ref" -v w="$worst" \
        'BEGIN { e = (a - b) / b; if (e < 0) e = -e; print (e > w ? e : w) }')
    done
    echo "$row $(awk -v w="$worst" 'BEGIN { printf "%.1f %% vs finest", 100 * w }') |"
    echo "crm $res $(wall_of "$d") $worst" >> "$out/.points"
  done
  for d in $(ls -d "$out"/scm_* 2>/dev/null | sort -t_ -k2 -gr); do
    res=${d##*_}; row="| SCM | $res | $(wall_of "$d") |"; worst=0
    for z in $zs; do
      f=$(force_at "$d/plate.csv" "$z"); ref=$(bekker "$z"); row="$row $f |"
      worst=$(awk -v a="$f" -v b="$ref" -v w="$worst" \
        'BEGIN { e = (a - b) / b; if (e < 0) e = -e; print (e > w ? e : w) }')
    done
    echo "$row $(awk -v w="$worst" 'BEGIN { printf "%.2f %% vs Bekker", 100 * w }') |"
    echo "scm $res $(wall_of "$d") $worst" >> "$out/.points"
  done
} > "$out/table.md"
awk '$1 == "crm"' "$out/.points" > "$out/crm.dat"
awk '$1 == "scm"' "$out/.points" > "$out/scm.dat"
rm -f "$out/.points"
if command -v gnuplot > /dev/null; then
  (cd "$out" && gnuplot -e "set terminal pngcairo noenhanced size 800,520 font 'Sans,11'; set output 'cost.png';
    set logscale xy; set grid; set key left top at graph 0.22, graph 0.98 Left reverse;
    set xlabel 'wall time [s]'; set ylabel 'largest relative error of the plate force';
    set title 'Plate test (r = 0.2 m): accuracy against cost';
    plot 'crm.dat' using 3:(\$4 > 0 ? \$4 : 1e-4):2 with linespoints pt 7 lw 2
           title 'CRM (vs finest spacing; labels = spacing)',
         '' using 3:(\$4 > 0 ? \$4 : 1e-4):2 with labels offset 1,1 notitle,
         'scm.dat' using 3:4 with linespoints pt 5 lw 2 title 'SCM (vs Bekker; labels = grid)',
         '' using 3:4:2 with labels offset 1,-1 notitle")
fi
cat "$out/table.md"
