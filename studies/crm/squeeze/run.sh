#!/usr/bin/env bash
# Runs the squeeze scenes of results/crm_squeeze on the GPU:
#   studies/crm/squeeze/run.sh OUT [TERRACAL]
# A run that goes bad stops with exit 1 (the run's checks); its bodies.csv and summary.json stay.
set -uo pipefail
out=${1:?output folder}; bin=${2:-./build/terracal}
here=$(dirname "$0")
mkdir -p "$out"
run() {  # name spacing radius duration
  bash "$here/scene.sh" "$2" "$3" "$4" > "$out/$1.json"
  "$bin" crm --scene "$out/$1.json" --out "$out/$1" --device cuda --record-every 20 > "$out/$1.log" 2>&1
  echo "$1: exit $? $(tail -n 1 "$out/$1.log" | cut -c 1-200)"
}
run d02_r03 0.02 0.3 2.2
run d01_r03 0.01 0.3 2.1
run d01_r02 0.01 0.2 2.1
run d005_r03 0.005 0.3 2.1
