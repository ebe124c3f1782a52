#!/usr/bin/env python3
"""The wheel study's RMSE against CRM rows that have reached a steady state. CRM's wheel at slips
0.6-0.8 is still digging after the sweeps' 3 s (crm_steadiness.py); crm_9s/ holds 9 s runs of those
slips (means over 4.5-9 s). This writes data/crm_108kg_steady.csv and data/crm_162kg_steady.csv (the 3 s
rows with the 9 s rows in their place) and prints each SCM set's RMSE in % of CRM's range, pull /
torque / sinkage, against them. Usage: steady_reference.py OUT (results/wheel_calibration_2022)."""
import csv
import glob
import sys

from wheel_rmse import CHANNELS, rmse, rows

out = sys.argv[1]



def steady(base, mass):
    table = rows(base)
    for path in sorted(glob.glob(f"{out}/crm_9s/{mass}kg_*/wheel.csv")):
        table.update(rows(path))
    fields = list(next(iter(table.values())).keys())
    with open(f"{out}/data/crm_{mass}kg_steady.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        for s in sorted(table):
            w.writerow(table[s])
    return table



crm3 = {108: rows(f"{out}/data/crm_108kg.csv"), 162: rows(f"{out}/crm_162kg/wheel.csv")}
crm = {108: steady(f"{out}/data/crm_108kg.csv", 108), 162: steady(f"{out}/crm_162kg/wheel.csv", 162)}
print("CRM rows replaced by 9 s runs (pull, torque, sinkage; 3 s -> 9 s):")
print()
for mass in (108, 162):
    for s in sorted(crm[mass]):
        if crm[mass][s] is not crm3[mass][s] and crm[mass][s] != crm3[mass][s]:
            a, b = crm3[mass][s], crm[mass][s]
            print(f"- {mass} kg, slip {s:g}: " + ", ".join(f"{float(a[c]):.4g} -> {float(b[c]):.4g}" for c in CHANNELS))
print()
print("| set | 108 kg, slips 0.2-0.8: 3 s rows | steady rows | 162 kg, every slip: 3 s rows | steady rows |")
print("|---|---|---|---|---|")
sets = [("bevameter + wheel, shared", "scm_joint"), ("bevameter + wheel, annulus scaled", "scm_joint_scaled"),
        ("plates + wheel, no annulus", "scm_plate_wheel"),
        ("annulus scaled, calibrated on the steady rows", "scm_joint_scaled_steady")]
sets += [(f"scaled, Ke {ke}", f"elastic_sweep/scm_ke_{ke}") for ke in ["3e6", "4e6", "8e6", "1.6e7", "4e7"]]
held = [0.2, 0.4, 0.6, 0.8]
for label, prefix in sets:
    m108, m162 = rows(f"{out}/{prefix}_108kg/wheel.csv"), rows(f"{out}/{prefix}_162kg/wheel.csv")
    print(f"| {label} | {rmse(m108, crm3[108], held)} | {rmse(m108, crm[108], held)} | "
          f"{rmse(m162, crm3[162], sorted(crm3[162]))} | {rmse(m162, crm[162], sorted(crm[162]))} |")
