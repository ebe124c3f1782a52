#!/usr/bin/env bash
# The three CRM studies on a GPU machine, their default specs: `studies/study/crm_gpu.sh BIN OUT`
# (BIN: the terracal program). Each study is a campaign in OUT/<study>: run again, it goes on where it
# stopped. results/study_crm holds what this wrote.
set -uo pipefail
bin=${1:?terracal program}; out=${2:?output folder}
mkdir -p "$out"
for study in accuracy-cost effects stability; do
  start=$(date +%s)
  "$bin" study "$study" --solver crm --out "$out/$study" > "$out/$study.log" 2>&1
  echo "$study: exit $? in $(( $(date +%s) - start )) s" | tee -a "$out/times.txt"
done
