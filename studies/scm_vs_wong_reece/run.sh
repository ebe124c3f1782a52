#!/usr/bin/env bash
# The SCM single wheel (0.01 m grid, 1e-3 s step, damping) against the Wong-Reece
# model on dry sand (shared/reference), slips 0.1-0.5. Writes OUT/comparison.md and the curves.
# Then OUT/decomposition.md: what separates the two, one assumption at a time (decompose.cpp, built
# as scm_wr_decomposition beside terracal).
# Usage: studies/scm_vs_wong_reece/run.sh [OUT=results/scm_vs_wong_reece] [TERRACAL=build/terracal]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-results/scm_vs_wong_reece}
bin=${2:-build/terracal}
"$bin" wheel --terrain scm --with-wong-reece --scm "$here/../bevameter_cost/dry_sand_scm.json" \
  --wheel "$here/wheel.json" --slips 0.1,0.2,0.3,0.4,0.5 --out "$out"
cat "$out/comparison.md"
"$(dirname "$bin")/scm_wr_decomposition" "$here/../bevameter_cost/dry_sand_scm.json" "$out/decomposition.md"
