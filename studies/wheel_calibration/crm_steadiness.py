#!/usr/bin/env python3
"""Is a CRM wheel sweep steady over its averaging window? For each slip of a wheel_series.csv, the means
of pull, torque and sinkage over the two halves of the window (the second half of the run, as
`terracal wheel` averages), and their drift from the first half to the second in % of the first.
Usage: crm_steadiness.py wheel_series.csv [wheel_series.csv ...]"""
import csv
import sys

COLS = [("dbp_N", "pull"), ("torque_Nm", "torque"), ("sinkage_m", "sinkage")]

for path in sys.argv[1:]:
    rows = list(csv.DictReader(open(path)))
    print(f"{path}\n")
    print("| slip | window [s] | pull [N]: 1st half / 2nd half (drift) | torque [N m] | sinkage [m] |")
    print("|---|---|---|---|---|")
    for slip in sorted({float(r["slip"]) for r in rows}):
        r = [x for x in rows if float(x["slip"]) == slip]
        end = max(float(x["time_s"]) for x in r)
        a, m = end / 2, 3 * end / 4

        def mean(lo, hi, col):
            v = [float(x[col]) for x in r if lo <= float(x["time_s"]) <= hi]
            return sum(v) / len(v)

        cells = []
        for col, _ in COLS:
            first, second = mean(a, m, col), mean(m, end, col)
            drift = 100 * (second - first) / abs(first) if first else float("nan")
            cells.append(f"{first:.4g} / {second:.4g} ({drift:+.1f} %)")
        print(f"| {slip:g} | {a:.2f}–{end:.2f} | " + " | ".join(cells) + " |")
    print()
