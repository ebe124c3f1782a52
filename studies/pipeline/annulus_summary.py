#!/usr/bin/env python3
"""Summarises annulus_bin_check.sh: per case the torque and sinkage in five parts of the base's angle
range, and the change of the torque curve against a base case as rigs::curve_change measures it
(the second curve read at the first one's angles where both reach, in five parts; the largest
difference of the parts' means over the largest mean).
Usage: annulus_summary.py OUT [BASE=w1_d1_r1_a0.6] [PAIR=BASE:CASE ...]
       annulus_summary.py --ensemble CASE_A CASE_B DIR [DIR ...]
The second form takes one run of each case from every DIR (realisations of the same test, e.g. with
different --settle-jitter) and compares the mean curves of A and B; it also prints the change
between every two runs of one case (the scatter of single runs)."""
import csv
import os
import sys


def load(path):
    rows = list(csv.DictReader(open(path)))
    return ([float(r["angle_rad"]) for r in rows], [float(r["torque_Nm"]) for r in rows],
            [float(r["sinkage_m"]) for r in rows])


def interpolate(x, y, at):
    for k in range(1, len(x)):
        if x[k] >= at:
            w = (at - x[k - 1]) / (x[k] - x[k - 1]) if x[k] > x[k - 1] else 1.0
            return y[k - 1] + w * (y[k] - y[k - 1])
    return y[-1]


def curve_change(base, check):
    bx, by = base
    cx, cy = check
    a, b = [], []
    for x, y in zip(bx, by):
        if cx[0] <= x <= cx[-1]:
            a.append(y)
            b.append(interpolate(cx, cy, x))
    n = len(a)
    if n < 5:
        return 0.0
    diff = scale = 0.0
    for p in range(5):
        lo, hi = p * n // 5, (p + 1) * n // 5
        ma, mb = sum(a[lo:hi]) / (hi - lo), sum(b[lo:hi]) / (hi - lo)
        diff, scale = max(diff, abs(ma - mb)), max(scale, abs(ma), abs(mb))
    return diff / scale if scale > 0 else 0.0


def parts(x, y, upto):
    """Means of y over five equal angle ranges of [0, upto]."""
    out = []
    for p in range(5):
        lo, hi = p * upto / 5, (p + 1) * upto / 5
        v = [yy for xx, yy in zip(x, y) if lo < xx <= hi + 1e-9]
        out.append(sum(v) / len(v) if v else float("nan"))
    return out


def mean_curve(runs):
    x = runs[0][0]
    return x, [sum(interpolate(r[0], r[1], xx) for r in runs) / len(runs) for xx in x]


def ensemble(a, b, dirs):
    runs = {c: [load(os.path.join(d, c, "shear.csv")) for d in dirs] for c in (a, b)}
    upto = runs[a][0][0][-1]
    for c in (a, b):
        x, t = mean_curve(runs[c])
        pairs = [100 * curve_change(runs[c][i][:2], runs[c][j][:2])
                 for i in range(len(dirs)) for j in range(i + 1, len(dirs))]
        sink = [r[2][-1] for r in runs[c]]
        print(f"{c}: mean torque in fifths of 0-{upto:g} rad " + " / ".join(f"{v:.0f}" for v in parts(x, t, upto)) +
              f" N m; sinkage at the end {min(sink):.4f}-{max(sink):.4f} m; single runs against each other " +
              ", ".join(f"{p:.1f}" for p in pairs) + " %")
    print(f"mean of {b} against mean of {a} ({len(dirs)} runs each): "
          f"{100 * curve_change(mean_curve(runs[a]), mean_curve(runs[b])):.1f} %")


def main():
    if sys.argv[1] == "--ensemble":
        ensemble(sys.argv[2], sys.argv[3], sys.argv[4:])
        return
    out = sys.argv[1]
    base = sys.argv[2] if len(sys.argv) > 2 else "w1_d1_r1_a0.6"
    cases = sorted(d for d in os.listdir(out) if os.path.isfile(os.path.join(out, d, "shear.csv")))
    curves = {c: load(os.path.join(out, c, "shear.csv")) for c in cases}
    upto = curves[base][0][-1] if base in curves else 0.6
    print(f"| case | torque in fifths of 0-{upto:g} rad [N m] | sinkage at {upto:g} rad [m] | "
          f"torque change vs {base} |")
    print("|---|---|---|---|")
    for c in cases:
        x, t, s = curves[c]
        tp = " / ".join(f"{v:.0f}" for v in parts(x, t, upto))
        ch = f"{100 * curve_change(curves[base][:2], (x, t)):.1f} %" if base in curves and c != base else "-"
        print(f"| {c} | {tp} | {interpolate(x, s, upto):.4f} | {ch} |")
    for pair in sys.argv[3:]:
        a, b = pair.split(":")
        print(f"{b} against {a}: {100 * curve_change(curves[a][:2], curves[b][:2]):.1f} %")


if __name__ == "__main__":
    main()
