#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on its embedded default:
# `terracal demo`, which writes results/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs" --target terracal
./build/terracal demo --out results/demo "$@"
