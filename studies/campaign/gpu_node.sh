#!/usr/bin/env bash
# A CRM campaign on a node with 2 GPUs (issue: campaigns across GPUs): the coarse spec run
#   A) in one process on GPU 0,
#   B) under mpirun with 3 ranks (the scheduler and one rank per GPU),
#   C) again under mpirun, rank 1 killed mid-job, then started again;
# the job tables, the results compared between A and B, and the wall times go to OUT.
# Usage: studies/campaign/gpu_node.sh BIN_DIR OUT   (BIN_DIR holds terracal and its libraries)
set -uo pipefail
bin=${1:?folder with terracal}; out=${2:?output folder}
here=$(cd "$(dirname "$0")" && pwd)
spec=$here/gpu_node_coarse.json
mkdir -p "$out"
nvidia-smi -L > "$out/gpus.txt" 2>&1
{ command -v mpirun; mpirun --version 2>&1 | head -1; } >> "$out/gpus.txt"
export LD_LIBRARY_PATH=$bin
t0=$(date +%s.%N)
CUDA_VISIBLE_DEVICES=0 timeout "${ONE_LIMIT:-200}" "$bin/terracal" campaign "$spec" --out /tmp/gpu_one > "$out/one.log" 2>&1
echo "one: exit $? in $(awk "BEGIN { print $(date +%s.%N) - $t0 }") s" >> "$out/summary.txt"
# Under mpirun the node's own OpenMPI library serves the program (the launcher and the library must match),
# with the node's C++ library, which that MPI library needs.
mpilib=$(dirname "$(readlink -f "$(command -v mpirun)")")/../lib
mkdir -p /tmp/bm && cp "$bin"/* /tmp/bm/ && rm -f /tmp/bm/libmpi* /tmp/bm/libopen-* /tmp/bm/libstdc++* /tmp/bm/libgcc_s*
run_mpi() { LD_LIBRARY_PATH=/tmp/bm:$mpilib mpirun --allow-run-as-root --oversubscribe -n 3 -x LD_LIBRARY_PATH \
  /tmp/bm/terracal campaign "$spec" --out "$1"; }
t0=$(date +%s.%N)
timeout "${TWO_LIMIT:-150}" bash -c "$(declare -f run_mpi); spec=$spec; mpilib=$mpilib; run_mpi /tmp/gpu_two" > "$out/two.log" 2>&1
echo "two: exit $? in $(awk "BEGIN { print $(date +%s.%N) - $t0 }") s" >> "$out/summary.txt"
for d in one two; do [ -d /tmp/gpu_$d ] && "$bin/terracal" campaign --status /tmp/gpu_$d > "$out/status_$d.txt" 2>&1 \
  && cp /tmp/gpu_$d/report.md "$out/report_$d.md"; done
# A against B, file by file: identical bytes, or the largest relative difference of the numbers.
if [ -d /tmp/gpu_two/jobs ]; then
  (cd /tmp/gpu_one && find jobs -name '*.csv' | sort) | while read -r f; do
    if cmp -s "/tmp/gpu_one/$f" "/tmp/gpu_two/$f"; then echo "same $f"; else
      paste -d, "/tmp/gpu_one/$f" "/tmp/gpu_two/$f" | awk -F, 'NR>1 { n=NF/2; for (i=1;i<=n;i++) { a=$i; b=$(i+n);
        d=(a-b); if (d<0) d=-d; s=(a<0?-a:a); if (s>0 && d/s>m) m=d/s } } END { printf "differs %s max rel %.3g\n", FILENAME, m }' \
        FILENAME="$f"; fi
  done > "$out/compare.txt"
fi
# C: kill rank 1 while a job is in flight, then start again (in one process on GPU 0).
(timeout "${KILL_LIMIT:-120}" bash -c "$(declare -f run_mpi); spec=$spec; mpilib=$mpilib; run_mpi /tmp/gpu_kill" > "$out/kill_first.log" 2>&1 &)
for i in $(seq 1 2400); do
  sleep 0.05
  done_jobs=$(find /tmp/gpu_kill/jobs -name log.txt 2>/dev/null | wc -l)
  inflight=$(find /tmp/gpu_kill/jobs -name '*.tmp' 2>/dev/null | wc -l)
  if [ "$done_jobs" -ge 2 ] && [ "$inflight" -ge 1 ]; then
    for p in $(pgrep -f "terracal campaign"); do
      if tr '\0' '\n' < /proc/$p/environ 2>/dev/null | grep -qx OMPI_COMM_WORLD_RANK=1; then kill -9 "$p"; echo "killed rank 1 (pid $p) with $done_jobs jobs done" >> "$out/summary.txt"; fi
    done
    break
  fi
done
sleep 3
"$bin/terracal" campaign --status /tmp/gpu_kill > "$out/status_kill_before.txt" 2>&1
CUDA_VISIBLE_DEVICES=0 timeout "${RESUME_LIMIT:-150}" "$bin/terracal" campaign "$spec" --out /tmp/gpu_kill > "$out/kill_resume.log" 2>&1
echo "resume: exit $?" >> "$out/summary.txt"
"$bin/terracal" campaign --status /tmp/gpu_kill > "$out/status_kill_after.txt" 2>&1
cat "$out/summary.txt"
