#!/usr/bin/env bash
# Makes the demo data set of `terracal demo`: synthetic bevameter curves of dry sand (truth.json)
# with 2 % multiplicative noise. Plates of 0.1 and 0.2 m radius to 0.1 m sinkage; an annulus of
# 0.15-0.20 m at normal pressures of 2, 8, 14 and 20 kPa, turned to 0.8 rad.
# Usage: studies/demo/make_demo_data.sh [path/to/terracal]   (default: build/terracal)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
exe=${1:-$here/../../build/terracal}
"$exe" synthesize --truth "$here/truth.json" --out "$here" --seed 2026 \
  --plates 0.1,0.2 --max-sinkage 0.1 --plate-points 12 \
  --annulus 0.15,0.20 --pressures 2000,8000,14000,20000 --max-angle 0.8 --shear-points 15 --noise 0.02
