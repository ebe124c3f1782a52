#!/usr/bin/env bash
# The bin-size check of the plate: how far the walls and the floor must be for the 0.3 m plate's loading
# curve to stop moving. Runs the plate in CRM at several bin scales (1 = the bin the rigs use:
# walls 13.5 radii away over 3 x (max sinkage + 2.5 radii) of soil, docs/decisions.md "Plate bin"; the
# earlier bin had 9 radii and 2x; pass --plate-wall-radii 3 --plate-depth-scale 1 to start from the earliest bin, as
# results/plate_bin_check's first study does) and prints
# the change of the loading leg between each scale and the next, measured as the pipeline's bin
# check does (rigs::curve_change: the second curve read at the first one's sinkages, in five parts;
# the largest difference of the parts' means over the largest mean).
# A scale W:D scales the walls by W and the depth by D (to tell which of the two the curve feels).
# Usage: [SPACING=0.02] [PLATE=0.3] plate_bin_check.sh OUT [TERRACAL=build/terracal] [SCALES="1 1.5 2 2.25"]
#          [extra options...]
set -euo pipefail
out=${1:?output folder}; bin=${2:-build/terracal}; scales=${3:-1 1.5 2 2.25}; shift $(( $# < 3 ? $# : 3 ))
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
tag() { echo "scale_${1/:/_d}"; }  # no ':' in file names
for s in $scales; do
  [ -f "$out/$(tag "$s")/plate.csv" ] && continue
  w=${s%%:*}; d=${s#*:}
  "$bin" bevameter --solver crm --soil "$here/bevameter_soil_2022.json" --test plate --plates "${PLATE:-0.3}" \
    --max-sinkage 0.2 --spacing "${SPACING:-0.02}" --bin-scale "$w" --bin-depth-scale "$d" --no-plots \
    --out "$out/$(tag "$s")" "$@" > "$out/$(tag "$s").log" 2>&1
done
change() { awk -F, -f "$here/curve_change.awk" "$1" "$2"; }  # as rigs::curve_change measures it
force_at() { awk -F, -v z="$2" 'NR > 1 && ($4 == "load" || $4 == "reload") && $2 >= z - 1e-4 { print $3; exit }' "$1"; }
{
  echo "| bin scale | bin | F(0.1 m) [N] | F(0.2 m) [N] | change of the loading leg from the previous scale |"
  echo "|---|---|---|---|---|"
  prev=""
  for s in $scales; do
    t=$(tag "$s")
    p=$(grep -o 'CRM bin [0-9.]* x [0-9.]* m, soil [0-9.]* m deep' "$out/$t.log" 2>/dev/null | head -1 |
      sed 's/CRM bin //' || true)
    c=$([ -n "$prev" ] && change "$out/$(tag "$prev")/plate.csv" "$out/$t/plate.csv" || echo "-")
    echo "| $s | ${p:-?} | $(force_at "$out/$t/plate.csv" 0.1) | $(force_at "$out/$t/plate.csv" 0.2) | $c |"
    prev=$s
  done
} | tee "$out/table.md"
