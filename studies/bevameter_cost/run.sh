#!/usr/bin/env bash
# What accuracy costs in time for the bevameter. The plate test (r = 0.2 m to
# 0.2 m sinkage) on CRM at several particle spacings and on SCM at several grid sizes; the plate
# force at fixed sinkages and the wall time of each run. Usage:
#   studies/bevameter_cost/run.sh TERRACAL OUT [cuda|cpu] [CRM spacings] [SCM grids]
# then studies/bevameter_cost/table.sh OUT writes OUT/table.md and OUT/cost.png.
set -euo pipefail
exe=${1:?terracal binary}; out=${2:?output folder}; device=${3:-cuda}
spacings=${4:-"0.04 0.03 0.02 0.015"}; grids=${5:-"0.04 0.02 0.01 0.005 0.0025"}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
for s in $spacings; do
  "$exe" bevameter --solver crm --soil "$here/../pipeline/bevameter_soil_2022.json" \
    --test plate --plates 0.2 --max-sinkage 0.2 \
    --spacing "$s" --device "$device" --cache "$out/bed_cache" --no-plots --out "$out/crm_$s"
done
# The SCM set the CRM curves calibrate to at the finest spacing is what SCM should reproduce; the
# cost study of SCM uses the analytic-law check instead: its own set, several grids.
for g in $grids; do
  "$exe" bevameter --solver scm --scm "$here/dry_sand_scm.json" --test plate --plates 0.2 --max-sinkage 0.2 \
    --grid "$g" --scm-effects none --no-plots --out "$out/scm_$g"
done
