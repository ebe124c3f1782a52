#!/usr/bin/env python3
"""The wheel-calibration study's table: each SCM set's RMSE against CRM, in % of CRM's range over the
sweep, over the calibration slips, the held-out slips of the calibration load, and the second load."""
import csv
import math
import sys

out = sys.argv[1]
CAL = {0.1, 0.3, 0.5, 0.7}
CHANNELS = [("dbp_N", "DBP"), ("torque_Nm", "torque"), ("sinkage_m", "sinkage")]


def rows(path):
    with open(path) as f:
        return {float(r["slip"]): r for r in csv.DictReader(f)}


def rmse_percent(model, crm, slips, col):
    vals = [float(crm[s][col]) for s in crm]
    spread = max(vals) - min(vals)
    err = math.sqrt(sum((float(model[s][col]) - float(crm[s][col])) ** 2 for s in slips) / len(slips))
    return err, 100 * err / spread


crm = {108: rows(f"{out}/data/crm_108kg.csv"), 162: rows(f"{out}/crm_162kg/wheel.csv")}
print("| set | load | slips | DBP [N] (% of range) | torque [N m] | sinkage [m] |")
print("|---|---|---|---|---|---|")
for name, label in [("bevameter", "bevameter only"), ("joint", "bevameter + wheel"),
                    ("joint_scaled", "bevameter + wheel, annulus scaled"),
                    ("plate_wheel", "plates + wheel, no annulus (MAP)")]:
    for mass in (108, 162):
        model = rows(f"{out}/scm_{name}_{mass}kg/wheel.csv")
        groups = [("calibration (0.1, 0.3, 0.5, 0.7)", sorted(CAL)),
                  ("held out (0, 0.2, 0.4, 0.6, 0.8)", sorted(set(crm[mass]) - CAL))] if mass == 108 else \
                 [("all (second load, held out)", sorted(crm[mass]))]
        for gname, slips in groups:
            cells = []
            for col, _ in CHANNELS:
                e, p = rmse_percent(model, crm[mass], slips, col)
                cells.append(f"{e:.3g} ({p:.0f} %)")
            print(f"| {label} | {mass} kg | {gname} | " + " | ".join(cells) + " |")
print()
print("Per slip (CRM / SCM bevameter only / SCM bevameter + wheel / SCM annulus scaled / SCM plates + wheel):")
print()
print("| load | slip | DBP [N] | torque [N m] | sinkage [m] |")
print("|---|---|---|---|---|")
for mass in (108, 162):
    b = rows(f"{out}/scm_bevameter_{mass}kg/wheel.csv")
    j = rows(f"{out}/scm_joint_{mass}kg/wheel.csv")
    js = rows(f"{out}/scm_joint_scaled_{mass}kg/wheel.csv")
    pw = rows(f"{out}/scm_plate_wheel_{mass}kg/wheel.csv")
    for s in sorted(crm[mass]):
        cells = [f"{float(crm[mass][s][c]):.4g} / {float(b[s][c]):.4g} / {float(j[s][c]):.4g} / "
                 f"{float(js[s][c]):.4g} / {float(pw[s][c]):.4g}"
                 for c, _ in CHANNELS]
        print(f"| {mass} kg | {s:g}{' (c)' if mass == 108 and s in CAL else ''} | " + " | ".join(cells) + " |")
