#!/usr/bin/env bash
# The squeeze scene (results/crm_squeeze): the bevameter study soil (2022) with 1000 Pa cohesion and
# the rigs' effects, a 1 x 1 m bin filled 0.2 m deep, a disc pushed down at 0.1 m/s from one spacing
# above the surface towards the floor.
#   scene.sh SPACING RADIUS DURATION [CFL] > scene.json
# Environment: THICK (disc thickness, default max(0.02, 2 spacings)), LOSTF (checks.max_lost_fraction),
# WALL (resolution.wall_contact, default 0).
set -euo pipefail
d=${1:?spacing}; r=${2:?radius}; T=${3:?duration}; cfl=${4:-0.3}
t=${THICK:-$(python3 -c "print(max(0.02, 2 * $d))")}
z=$(python3 -c "print(round(0.2 + $d + $t / 2, 6))")
cat <<J
{
  "soil": {"density": 1700, "young_modulus": 1e6, "poisson_ratio": 0.3, "mu_s": 0.7, "mu_2": 0.7, "I0": 0.03,
           "grain_diameter": 0.005, "cohesion": 1000, "gravity": [0, 0, -9.81]},
  "bin": {"size": [1, 1, 0.4], "fill_height": 0.2},
  "resolution": {"spacing": $d, "h_over_d0": 1.4, "cfl": $cfl, "wall_contact": ${WALL:-0}},
  "effects": ["artificial_viscosity", "cohesion", "hourglass_damping", "hourglass_stiffness"],
  "hourglass_damping": {"alpha": 0.4},
  "hourglass_stiffness": {"beta": 0.03},
  "settle_time": 0.3,
  "duration": $T,
  "bodies": [
    {"name": "plate", "shape": {"type": "disc", "radius": $r, "thickness": $t},
     "position": [0.5, 0.5, $z],
     "motion": {"type": "prescribed", "linear_velocity": [0, 0, -0.1]}}
  ],
  "checks": {"max_lost_fraction": ${LOSTF:-0.001}},
  "output": {"progress_seconds": 5}
}
J
