#!/usr/bin/env python3
"""elastic_sweep.sh's table: for each given Ke (and the plates' own, run.sh's joint_scaled), the SCM
wheel's RMSE against CRM in % of CRM's range, and the motion resistance T / r - DBP at slip 0."""
import json
import sys

from wheel_rmse import rmse, rows

out = sys.argv[1]
RADIUS = 0.47




def resistance(r):
    return float(r[0.0]["torque_Nm"]) / RADIUS - float(r[0.0]["dbp_N"])


crm = {108: rows(f"{out}/data/crm_108kg.csv"), 162: rows(f"{out}/crm_162kg/wheel.csv")}
if "--k-grid" in sys.argv:  # elastic_k_grid.sh's table
    print("RMSE in % of CRM's range, pull / torque / sinkage, with the set's Janosi k replaced")
    print()
    print("| set (its own k) | k [m] | 108 kg, slips 0.2-0.8 | 162 kg, every slip | worst of pull and torque |")
    print("|---|---|---|---|---|")
    for base, label in [("joint_scaled", "plates' Ke 2.15e6"), ("ke_8e6", "Ke 8e6"), ("ke_4e7", "Ke 4e7")]:
        for k in ["0.015", "0.025", "0.035", "0.045", "0.06"]:
            g = f"{out}/elastic_sweep/k_grid/scm_{base}_k{k}"
            m108, m162 = rows(f"{g}_108kg/wheel.csv"), rows(f"{g}_162kg/wheel.csv")
            a, b = rmse(m108, crm[108], [0.2, 0.4, 0.6, 0.8]), rmse(m162, crm[162], sorted(crm[162]))
            worst = max(float(x) for x in a.split(" / ")[:2] + b.split(" / ")[:2])
            print(f"| {label} | {k} | {a} | {b} | {worst:.1f} |")
    sys.exit(0)
runs = [("plates' fit", f"{out}/joint_scaled/scm_params.json", f"{out}/scm_joint_scaled")]
for ke in ["3e6", "4e6", "8e6", "1.6e7", "4e7"]:
    runs.append((ke, f"{out}/elastic_sweep/ke_{ke}/scm_params.json", f"{out}/elastic_sweep/scm_ke_{ke}"))
print("RMSE in % of CRM's range, pull / torque / sinkage; resistance T/r - DBP at slip 0 (CRM: "
      f"{resistance(crm[108]):.0f} N at 108 kg, {resistance(crm[162]):.0f} N at 162 kg)")
print()
print("| set's Ke [Pa/m] | c [Pa], phi [deg], k [m], S | 108 kg, slips 0.2-0.8 | 108 kg, slips 0, 0.2-0.8 | "
      "162 kg, every slip | resistance at slip 0, 108 / 162 kg [N] |")
print("|---|---|---|---|---|---|")
for label, params, prefix in runs:
    p = json.load(open(params))
    s = p["Soil parameters"]
    ke = s["Elastic stiffness"]
    m108, m162 = rows(f"{prefix}_108kg/wheel.csv"), rows(f"{prefix}_162kg/wheel.csv")
    soil = (f"{s['Mohr cohesive limit']:.0f}, {s['Mohr friction limit']:.1f}, {s['Janosi shear coefficient']:.3f}, "
            f"{p['Slip sinkage']['S']:.2f}")
    print(f"| {label} ({ke:.3g}) | {soil} | {rmse(m108, crm[108], [0.2, 0.4, 0.6, 0.8])} | "
          f"{rmse(m108, crm[108], [0.0, 0.2, 0.4, 0.6, 0.8])} | {rmse(m162, crm[162], sorted(crm[162]))} | "
          f"{resistance(m108):.0f} / {resistance(m162):.0f} |")
