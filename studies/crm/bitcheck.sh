#!/usr/bin/env bash
# Runs studies/crm/digest_plate.json (a plate pushed and turned into a bed) under every combination
# of the CRM effects, in float64 and float32 on the CPU (or on the GPU), and writes one line file
# per run: the plate's wrench every 50 steps and a digest of the particle state. Two builds whose
# folders `diff -r` finds equal computed the same bits in every combination.
# Usage: studies/crm/bitcheck.sh OUT [DIGEST=build/crm_state_digest] [cpu|cuda] [STEPS=300]
set -euo pipefail
out=$1; digest=${2:-build/crm_state_digest}; device=${3:-cpu}; steps=${4:-300}
scene=$(dirname "$0")/digest_plate.json
effects=(cohesion artificial_viscosity shifting active_domain hourglass_damping hourglass_stiffness)
mkdir -p "$out"
precisions=(double float)
[ "$device" = cuda ] && precisions=(float)
for ((mask = 0; mask < 64; ++mask)); do
  list=()
  for ((e = 0; e < 6; ++e)); do (( mask >> e & 1 )) && list+=("${effects[e]}"); done
  named=$(IFS=,; echo "${list[*]:-none}")
  for p in "${precisions[@]}"; do
    "$digest" "$scene" "$steps" 50 "$device" "$named" "$p" > "$out/${named//,/+}_$p.csv"
  done
done
echo "bitcheck: $(ls "$out" | wc -l) runs in $out"
