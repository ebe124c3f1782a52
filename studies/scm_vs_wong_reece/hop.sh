#!/usr/bin/env bash
# The SCM wheel on stiff sand at high slip (results/scm_vs_wong_reece/hop.md): LETE sand of
# shared/reference (the 108 kg wheel sinks 3 mm, a third of it elastic), slips 0 ... 0.9, without
# damping and with Chrono's default damping, each against Wong-Reece. Each comparison.md ends with
# the runs' steadiness; the log warns of a wheel that hops.
# Usage: studies/scm_vs_wong_reece/hop.sh [OUT=results/scm_vs_wong_reece/lete_sand] [TERRACAL=build/terracal]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-results/scm_vs_wong_reece/lete_sand}
bin=${2:-build/terracal}
for effects in none damping; do
  "$bin" wheel --terrain scm --with-wong-reece --scm "$here/lete_sand_scm.json" --scm-effects "$effects" \
    --wheel "$here/wheel.json" --slips 0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9 --out "$out/$effects"
  echo "== effects: $effects"
  cat "$out/$effects/comparison.md"
done
