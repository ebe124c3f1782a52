#!/usr/bin/env python3
"""Two SCM sets calibrated on plate curves from two CRM bins -> a markdown comparison.

Prints (1) each CRM plate's force at a few sinkages in both bins, (2) each Bekker/Mohr/Janosi
parameter of both sets (MAP and posterior mean +- sd) with its relative change, (3) the Bekker
pressure (Kc/b + Kphi) z^n of both sets at the widths and sinkages a user drives on, which is what
the set is for: Kc and Kphi trade off against each other, so their pressure moves less than they do.
Usage: plate_bin_set_compare.py SET_A.json SET_B.json PLATE_A.csv PLATE_B.csv
"""
import csv
import json
import sys

SINKAGES = (0.02, 0.05, 0.1, 0.19)
WIDTHS = (0.125, 0.2, 0.3)  # the pipeline wheel's half width, the two plates' radii [m]


def loading_leg(path):
    """Per plate radius: the first loading, then the reload once it passes the first loading's depth."""
    rows = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["phase"] in ("load", "reload"):
                rows.setdefault(float(row["plate_radius_m"]), []).append(
                    (row["phase"], float(row["sinkage_m"]), float(row["force_N"])))
    legs = {}
    for r, rs in rows.items():
        first = [(z, f) for phase, z, f in rs if phase == "load"]
        deepest = max(z for z, _ in first)
        legs[r] = first + [(z, f) for phase, z, f in rs if phase == "reload" and z > deepest]
    return legs


def force_at(leg, z):
    for (z0, f0), (z1, f1) in zip(leg, leg[1:]):
        if z0 <= z <= z1:
            return f0 + (f1 - f0) * (z - z0) / (z1 - z0) if z1 > z0 else f1
    return float("nan")


def pct(a, b):
    return 100.0 * (b - a) / abs(a) if a else float("nan")


def main(set_a, set_b, plate_a, plate_b):
    sets = [json.load(open(p)) for p in (set_a, set_b)]
    legs = [loading_leg(p) for p in (plate_a, plate_b)]
    print("CRM plate force, rigs' bin -> 1.5x bin [N]:\n")
    print("| plate radius [m] | " + " | ".join(f"z = {z} m" for z in SINKAGES) + " |")
    print("|---" * (len(SINKAGES) + 1) + "|")
    for r in sorted(legs[0]):
        cells = []
        for z in SINKAGES:
            a, b = force_at(legs[0][r], z), force_at(legs[1].get(r, []), z)
            cells.append(f"{a:.0f} -> {b:.0f} ({pct(a, b):+.1f} %)")
        print(f"| {r} | " + " | ".join(cells) + " |")

    print("\nThe sets (MAP; posterior mean +- sd):\n")
    print("| parameter | rigs' bin | 1.5x bin | change of the MAP | change in posterior sd |")
    print("|---|---|---|---|---|")
    soil = [s["Soil parameters"] for s in sets]
    post = [s.get("Posterior", {}) for s in sets]
    for k in soil[0]:
        if k not in post[0]:
            continue
        a, b = soil[0][k], soil[1][k]
        pa, pb = post[0][k], post[1].get(k, {})
        sd = max(pa.get("sd", 0), pb.get("sd", 0))
        z = f"{(b - a) / sd:+.2f}" if sd > 0 else "-"
        print(f"| {k} | {a:.5g}; {pa.get('mean', a):.5g} +- {pa.get('sd', 0):.2g} | "
              f"{b:.5g}; {pb.get('mean', b):.5g} +- {pb.get('sd', 0):.2g} | {pct(a, b):+.1f} % | {z} |")

    print("\nBekker pressure (Kc/b + Kphi) z^n of the MAP sets, change from the rigs' bin's set:\n")
    print("| width b [m] | " + " | ".join(f"z = {z} m" for z in SINKAGES) + " |")
    print("|---" * (len(SINKAGES) + 1) + "|")
    worst = 0.0
    for w in WIDTHS:
        cells = []
        for z in SINKAGES:
            p = [(s["Bekker Kc"] / w + s["Bekker Kphi"]) * z ** s["Bekker n exponent"] for s in soil]
            worst = max(worst, abs(pct(p[0], p[1])))
            cells.append(f"{p[0] / 1e3:.1f} -> {p[1] / 1e3:.1f} kPa ({pct(p[0], p[1]):+.1f} %)")
        print(f"| {w} | " + " | ".join(cells) + " |")
    print(f"\nLargest change of the pressure: {worst:.1f} % (bound 5 %).")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
