"""Shared by the wheel study's tables: wheel.csv rows by slip, and an SCM sweep's RMSE against CRM in %
of CRM's range over its sweep, per channel (pull / torque / sinkage)."""
import csv
import math

CHANNELS = ["dbp_N", "torque_Nm", "sinkage_m"]


def rows(path):
    with open(path) as f:
        return {round(float(r["slip"]), 3): r for r in csv.DictReader(f)}


def rmse(model, crm, slips):
    cells = []
    for col in CHANNELS:
        vals = [float(r[col]) for r in crm.values()]
        err = math.sqrt(sum((float(model[s][col]) - float(crm[s][col])) ** 2 for s in slips) / len(slips))
        cells.append(f"{100 * err / (max(vals) - min(vals)):.1f}")
    return " / ".join(cells)
