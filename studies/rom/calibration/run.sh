#!/usr/bin/env bash
# The ROM calibration study (results/rom_calibration/README.md):
#   A. references made by the 18-DOF ROM itself (known parameters) plus noise: 3 parameters on two 4 s
#      manoeuvres, independence chains against the ensemble; the 10 default parameters on four
#      manoeuvres;
#   B. references made by the full multibody HMMWV: four training manoeuvres, two held out.
# Usage: studies/rom/calibration/run.sh OUT [DEVICE]   (DEVICE: cpu or cuda; default cpu)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
exe=${TERRACAL:-$here/../../../build/terracal}
out=${1:?output folder}
dev=${2:-cpu}
mkdir -p "$out"
py=$(command -v /usr/bin/python3 || command -v python3)

# A1: two short manoeuvres, 3 parameters.
for r in short_steer short_accel; do
  "$exe" rom --model 18dof --vehicle hmmwv --inputs "$here/$r.txt" --initial-speed 8 --end-time 4 --output-rate 50 \
    --no-plots --out "$out/A/$r" > /dev/null
done
"$py" "$here/add_noise.py" 1 "$out/A/short_steer" "$out/A/short_accel"
refs="$out/A/short_steer,$out/A/short_accel"
"$exe" calibrate-rom --vehicle hmmwv --reference "$refs" --params "$here/three_parameters.json" --device "$dev" \
  --out "$out/A/independence" | tee "$out/A/independence.txt"
[ "$dev" = cpu ] && "$exe" calibrate-rom --vehicle hmmwv --reference "$refs" --params "$here/three_parameters.json" \
  --sampler ensemble --warmup 300 --device cpu --out "$out/A/ensemble" | tee "$out/A/ensemble.txt"

# Full-vehicle runs (also the inputs of A2).
for r in accel stepL stepR; do
  "$exe" vehicle --vehicle hmmwv --inputs "$here/$r.txt" --initial-speed 8 --output-rate 20 --no-plots --out "$out/B/$r"
done
"$exe" vehicle --vehicle hmmwv --maneuver "$here/../dlc_iso3888_1.json" --output-rate 20 --no-plots --out "$out/B/dlc"
for r in sine brake; do
  "$exe" vehicle --vehicle hmmwv --inputs "$here/$r.txt" --initial-speed 12 --output-rate 20 --no-plots --out "$out/B/$r"
done

# A2: the ROM on the full vehicle's inputs, 10 default parameters.
for r in accel stepL stepR dlc; do
  v=8; [ $r = dlc ] && v=15
  "$exe" rom --model 18dof --vehicle hmmwv --inputs "$out/B/$r/inputs.txt" --initial-speed $v --output-rate 20 \
    --no-plots --out "$out/A2/$r" > /dev/null
done
"$py" "$here/add_noise.py" 7 "$out/A2/accel" "$out/A2/stepL" "$out/A2/stepR" "$out/A2/dlc"
"$exe" calibrate-rom --vehicle hmmwv --reference "$out/A2/accel,$out/A2/stepL,$out/A2/stepR,$out/A2/dlc" \
  --device "$dev" --out "$out/A2/cal" | tee "$out/A2/cal.txt" || true

# B: against the full vehicle (a draw cap: its chains do not converge, see the README).
"$exe" calibrate-rom --vehicle hmmwv --reference "$out/B/accel,$out/B/stepL,$out/B/stepR,$out/B/dlc" \
  --max-draws 100 --device "$dev" --out "$out/B/cal" | tee "$out/B/cal.txt" || true
"$exe" validate-rom --posterior "$out/B/cal" --reference "$out/B/sine,$out/B/brake" --draws 2000 --device "$dev" \
  --out "$out/B/validation"
