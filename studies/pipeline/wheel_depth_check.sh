#!/usr/bin/env bash
# Is the CRM wheel's bin effect (4.6 % deeper sinkage in the 1.5x bin; results/plate_bin_check)
# a matter of the bed's depth? The pipeline's wheel (0.47 m, 0.25 m, 108 kg, 1 rad/s) at slip 0.4,
# 3 s, 0.02 m spacing, on the 2022 soil, in the rigs' bin, in beds 1.5x and 2x as deep (same width and
# length), and in the 1.5x bin; SEEDS jittered realisations each (jitter 0.1 of the spacing).
# CASES overrides the list (name:options ...).
# Usage: [SEEDS="20222 20223"] [CASES="..."] studies/pipeline/wheel_depth_check.sh TERRACAL OUT [cuda|cpu]
set -uo pipefail
exe=${1:?terracal binary}; out=${2:?output folder}; device=${3:-cuda}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
wheel="$here/../scm_vs_wong_reece/wheel.json"
default_cases=("rigs:--bin-scale 1" "depth1.5:--bin-depth-scale 1.5" "depth2:--bin-depth-scale 2"
               "bin1.5:--bin-scale 1.5")
if [ -n "${CASES:-}" ]; then IFS=';' read -r -a cases <<< "$CASES"; else cases=("${default_cases[@]}"); fi
for case in "${cases[@]}"; do
  name=${case%%:*}; opts=${case#*:}
  for seed in ${SEEDS:-20222 20223}; do
    "$exe" wheel --terrain crm --soil "$here/bevameter_soil_2022.json" --wheel "$wheel" --slips 0.4 --duration 3 \
      --spacing 0.02 --device "$device" --settle-jitter 0.1 --settle-seed "$seed" $opts --cache "$out/bed_cache" \
      --no-plots \
      --out "$out/${name}_$seed" > "$out/${name}_$seed.log" 2>&1 || echo "$name $seed failed" >> "$out/failed.txt"
    echo "$name $seed $(tail -n 1 "$out/${name}_$seed/wheel.csv" 2>/dev/null)" \
      "$(grep -o 'soil [0-9.]* m deep' "$out/${name}_$seed.log" | head -1)" >> "$out/summary.txt"
  done
done
rm -rf "$out/bed_cache"
cat "$out/summary.txt"
