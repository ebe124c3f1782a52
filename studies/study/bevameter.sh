#!/usr/bin/env bash
# What accuracy costs in time for the bevameter: `terracal study accuracy-cost --solver SOLVER` on the
# plate rig (spec studies/study/bevameter.json: a 0.2 m plate to 0.2 m; SCM grids 0.04 ... 0.0025 m, CRM
# spacings 0.04, 0.03, 0.02 m), and for SCM the effects study. Usage: studies/study/bevameter.sh BIN
# SOLVER... [OUT=results/bevameter_cost]. Work in /tmp/terracal_study/bevameter_<solver>/<study>; the
# report, its CSV and plot and the spec as run are copied into OUT/study_<solver>/<study>/.
set -uo pipefail
cd "$(dirname "$0")/../.."
source studies/study/run_study.sh
bin=${1:?terracal program}; shift
out=results/bevameter_cost
for solver in "$@"; do
  studies="accuracy-cost"
  [ "$solver" = scm ] && studies="accuracy-cost effects"  # CRM's effects runs are at the finest spacing: hours
  for study in $studies; do
    run_study "$bin" "$study" "$solver" studies/study/bevameter.json /tmp/terracal_study/bevameter_$solver/$study \
      "$out/study_$solver/$study"
  done
done
