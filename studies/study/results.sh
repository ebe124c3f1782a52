#!/usr/bin/env bash
# Regenerates results/study_<solver>/<study>/ from the default specs: `studies/study/results.sh BIN
# SOLVER...` (BIN: the terracal program; SOLVER: scm, wong-reece, crm, rom, vehicle). The studies run in
# /tmp/terracal_study/<solver>/<study> (campaigns: run again, they go on where they stopped); the
# report, its CSV and plot and the spec as run are copied into results/.
set -uo pipefail
cd "$(dirname "$0")/../.."
source studies/study/run_study.sh
bin=${1:?terracal program}; shift
for solver in "$@"; do
  studies="accuracy-cost stability effects"
  case "$solver" in wong-reece|vehicle) studies="accuracy-cost stability" ;; esac  # no effects to switch
  for study in $studies; do
    run_study "$bin" "$study" "$solver" "" /tmp/terracal_study/$solver/$study "results/study_${solver//-/_}/$study"
  done
done
