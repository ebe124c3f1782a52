"""Errors of the ROMs against the full vehicle in studies/rom/soft_soil/run.sh's runs: vx and yaw-rate
RMSE over each run, the final speed, and wall times; writes OUT/errors.csv, OUT/table.md and the
plot OUT/soft_soil.png (gnuplot)."""
import csv
import json
import os
import bisect
import math
import subprocess
import sys

out = sys.argv[1]
runs = os.path.join(out, "runs")


def load(folder):
    with open(os.path.join(runs, folder, "trajectory.csv")) as f:
        rows = list(csv.DictReader(f))
    cols = {k: [float(r[k]) for r in rows] for k in ("time", "vx", "yaw_rate")}
    with open(os.path.join(runs, folder, "run.json")) as f:
        cols["wall"] = json.load(f)["wall_seconds"]
    return cols


def interp(t, ts, ys):
    """Linear interpolation of (ts, ys) at t, clamped to the ends."""
    i = bisect.bisect_right(ts, t)
    if i == 0:
        return ys[0]
    if i == len(ts):
        return ys[-1]
    w = (t - ts[i - 1]) / (ts[i] - ts[i - 1])
    return ys[i - 1] + w * (ys[i] - ys[i - 1])


def rmse(ref, rom, key):
    d = [interp(t, rom["time"], rom[key]) - y for t, y in zip(ref["time"], ref[key])]
    return math.sqrt(sum(x * x for x in d) / len(d))


rows = []
for m, name in (("accel", "straight acceleration, throttle 0.5"), ("turn", "constant steer 0.3, 5 m/s target")):
    for ground in ("scm", "rigid"):
        ref = load(f"full_{m}_{ground}")
        cases = [(f"rom_{model}_{m}_{ground}", model, "table" if ground == "scm" else "rigid") for model in ("11dof", "18dof")]
        if ground == "scm":
            cases += [(f"rom_{model}_{m}_scm_as_rigid", model, "rigid (soil left out)") for model in ("11dof", "18dof")]
        for folder, model, terrain in cases:
            rom = load(folder)
            rows.append({
                "maneuver": name, "full_vehicle_on": "SCM dry sand" if ground == "scm" else "rigid ground",
                "rom": model, "rom_terrain": terrain,
                "vx_rmse": rmse(ref, rom, "vx"), "yaw_rate_rmse": rmse(ref, rom, "yaw_rate"),
                "vx_end_full": float(ref["vx"][-1]), "vx_end_rom": interp(ref["time"][-1], rom["time"], rom["vx"]),
                "yaw_rate_end_full": float(ref["yaw_rate"][-1]),
                "yaw_rate_end_rom": interp(ref["time"][-1], rom["time"], rom["yaw_rate"]),
                "wall_full_s": ref["wall"], "wall_rom_s": rom["wall"], "simulated_s": float(ref["time"][-1]),
            })

with open(os.path.join(out, "errors.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)

lines = ["| manoeuvre | full vehicle on | ROM | ROM's ground | vx RMSE [m/s] | yaw-rate RMSE [rad/s] | final vx full / ROM [m/s] | final yaw rate full / ROM [rad/s] | wall full / ROM [s] |",
         "|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    lines.append(f"| {r['maneuver']} | {r['full_vehicle_on']} | {r['rom']} | {r['rom_terrain']} | {r['vx_rmse']:.3f} | "
                 f"{r['yaw_rate_rmse']:.4f} | {r['vx_end_full']:.2f} / {r['vx_end_rom']:.2f} | "
                 f"{r['yaw_rate_end_full']:.3f} / {r['yaw_rate_end_rom']:.3f} | {r['wall_full_s']:.1f} / {r['wall_rom_s']:.4f} |")
with open(os.path.join(out, "table.md"), "w") as f:
    f.write("\n".join(lines) + "\n")
print("\n".join(lines))

gp = f"""
set terminal pngcairo noenhanced size 1400,900 font 'Sans,11'
set output '{out}/soft_soil.png'
set datafile separator ','
set grid
set key bottom right
set multiplot layout 2,2
r = '{runs}/'
do for [m in "accel turn"] {{
  set title m.': vx on SCM dry sand'
  set xlabel 'time [s]'; set ylabel 'vx [m/s]'
  plot r.'full_'.m.'_scm/trajectory.csv' using 1:8 with lines lw 3 title 'full vehicle on SCM', \\
       r.'rom_18dof_'.m.'_scm/trajectory.csv' using 1:8 with lines lw 2 title '18-DOF ROM, dry-sand table', \\
       r.'rom_11dof_'.m.'_scm/trajectory.csv' using 1:8 with lines lw 2 dt 2 title '11-DOF ROM, dry-sand table', \\
       r.'rom_18dof_'.m.'_scm_as_rigid/trajectory.csv' using 1:8 with lines lw 2 dt 3 title '18-DOF ROM, rigid ground'
  set title m.': yaw rate on SCM dry sand'
  set ylabel 'yaw rate [rad/s]'
  plot r.'full_'.m.'_scm/trajectory.csv' using 1:10 with lines lw 3 title 'full vehicle on SCM', \\
       r.'rom_18dof_'.m.'_scm/trajectory.csv' using 1:10 with lines lw 2 title '18-DOF ROM, dry-sand table', \\
       r.'rom_11dof_'.m.'_scm/trajectory.csv' using 1:10 with lines lw 2 dt 2 title '11-DOF ROM, dry-sand table', \\
       r.'rom_18dof_'.m.'_scm_as_rigid/trajectory.csv' using 1:10 with lines lw 2 dt 3 title '18-DOF ROM, rigid ground'
}}
unset multiplot
"""
subprocess.run(["gnuplot"], input=gp, text=True, check=True)
