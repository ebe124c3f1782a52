#!/usr/bin/env bash
# The coarse CRM campaign on a node with 2 GPUs under `mpirun --enable-recovery` (the scheduler and one
# rank per GPU), rank 1 killed mid-job: the other rank carries on, the killed job goes back to the queue,
# the run finishes. The log, the job table and a summary go to OUT.
# Usage: studies/campaign/gpu_node_recovery.sh BIN_DIR OUT   (BIN_DIR holds terracal and its libraries)
set -uo pipefail
bin=${1:?folder with terracal}; out=${2:?output folder}
here=$(cd "$(dirname "$0")" && pwd)
spec=$here/gpu_node_coarse.json
mkdir -p "$out"
nvidia-smi -L > "$out/gpus.txt" 2>&1
{ command -v mpirun; mpirun --version 2>&1 | head -1; } >> "$out/gpus.txt"
# The node's own OpenMPI library serves the program (launcher and library must match), with the node's
# C++ library, which that MPI library needs.
mpilib=$(dirname "$(readlink -f "$(command -v mpirun)")")/../lib
mkdir -p /tmp/bm && cp "$bin"/* /tmp/bm/ && rm -f /tmp/bm/libmpi* /tmp/bm/libopen-* /tmp/bm/libstdc++* /tmp/bm/libgcc_s*
t0=$(date +%s.%N)
(LD_LIBRARY_PATH=/tmp/bm:$mpilib timeout "${LIMIT:-240}" mpirun --allow-run-as-root --oversubscribe --enable-recovery \
  -n 3 -x LD_LIBRARY_PATH /tmp/bm/terracal campaign "$spec" --out /tmp/gpu_recover > "$out/recover.log" 2>&1;
 echo "mpirun: exit $? in $(awk "BEGIN { print $(date +%s.%N) - $t0 }") s" >> "$out/summary.txt") &
for i in $(seq 1 2400); do
  sleep 0.05
  done_jobs=$(find /tmp/gpu_recover/jobs -name log.txt 2>/dev/null | wc -l)
  inflight=$(find /tmp/gpu_recover/jobs -name '*.tmp' 2>/dev/null | wc -l)
  if [ "$done_jobs" -ge 2 ] && [ "$inflight" -ge 1 ]; then
    for p in $(pgrep -f "terracal campaign"); do
      if tr '\0' '\n' < /proc/$p/environ 2>/dev/null | grep -qx OMPI_COMM_WORLD_RANK=1; then
        kill -9 "$p"; echo "killed rank 1 (pid $p) with $done_jobs jobs done" >> "$out/summary.txt"; fi
    done
    break
  fi
done
wait
LD_LIBRARY_PATH=$bin "$bin/terracal" campaign --status /tmp/gpu_recover > "$out/status.txt" 2>&1
cp /tmp/gpu_recover/report.md "$out/report.md" 2>/dev/null
cat "$out/summary.txt"
