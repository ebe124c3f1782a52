#!/usr/bin/env bash
# The CRM wheel of results/pipeline_bevameter_2022 at a second load (162 kg, 1.5x the pipeline's
# 108 kg), at the pipeline's CRM settings (0.02 m spacing, 3 s per slip): the held-out load of the
# wheel-calibration study (run.sh). Needs a GPU.
# Usage: studies/wheel_calibration/crm_second_load.sh TERRACAL OUT
set -euo pipefail
exe=${1:?terracal binary}; out=${2:?output folder}
here=$(cd "$(dirname "$0")" && pwd)
"$exe" wheel --terrain crm --soil "$here/../pipeline/bevameter_soil_2022.json" --device cuda --spacing 0.02 \
  --wheel "$here/wheel_162kg.json" --slips 0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8 --duration 3 --no-plots --out "$out"
