#!/usr/bin/env python3
"""Is the plates' unload slope's bin dependence the elastic far field? (issue 28, point 6)

For each bin's plate.csv (terracal bevameter output, CRM): the least-squares slope of each plate's
first unload branch, against a rigid disc on an elastic layer of depth H over a rigid base,
K = 2 E a / (1 - nu^2) * (1 + 1.28 a / H) (Kausel's static stiffness of a disc on a stratum, as
tabulated by Gazetas), H being the soil below the plate at the unload. Also the elastic waves' round
trip through the bed against the unload's duration.

Usage: plate_unload_check.py E NU RHO SPEED LABEL:PLATE_CSV:FILL_DEPTH_M ...
  e.g. plate_unload_check.py 1e6 0.3 1700 0.1 rigs:set_bins/bin_1/plate.csv:2.12,2.88 \
       1.5x:set_bins/bin_1.5/plate.csv:3.16,4.28
  (FILL_DEPTH_M: one depth per plate radius, in the order the radii appear in the file.)
"""
import csv
import math
import sys


def unload_branches(path):
    """{radius: [(sinkage, force), ...]} of each plate's first contiguous unload rows."""
    rows = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows.setdefault(float(r["plate_radius_m"]), []).append(r)
    branches = {}
    for radius, rs in rows.items():
        branch, started = [], False
        for r in rs:
            if r.get("phase") == "unload":
                branch.append((float(r["sinkage_m"]), float(r["force_N"])))
                started = True
            elif started:
                break
        if len(branch) >= 3:
            branches[radius] = branch
    return branches


def slope(points):
    n = len(points)
    sx = sum(z for z, _ in points)
    sy = sum(f for _, f in points)
    sxx = sum(z * z for z, _ in points)
    sxy = sum(z * f for z, f in points)
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)


def main(argv):
    if len(argv) < 6:
        print(__doc__, file=sys.stderr)
        return 2
    E, nu, rho, speed = (float(x) for x in argv[1:5])
    c_p = math.sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho)
    bins = []
    for spec in argv[5:]:
        label, path, depths = spec.split(":")
        branches = unload_branches(path)
        fills = [float(d) for d in depths.split(",")]
        if len(fills) != len(branches):
            print(f"{spec}: {len(branches)} plates with an unload branch, {len(fills)} depths given", file=sys.stderr)
            return 2
        bins.append((label, branches, dict(zip(branches.keys(), fills))))
    print(f"E = {E:g} Pa, nu = {nu:g}, rho = {rho:g} kg/m3: P wave {c_p:.1f} m/s; plate speed {speed:g} m/s\n")
    print("| bin | plate radius [m] | unload [m] / [s] | slope [N/m] | half-space 2Ea/(1-nu^2) | "
          "layer H [m] | 1 + 1.28 a/H | slope / layer | P-wave round trip [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    ref = {}
    for label, branches, fills in bins:
        for a, branch in branches.items():
            s = slope(branch)
            z_unload = branch[0][0]
            H = fills[a] - z_unload
            half = 2 * E * a / (1 - nu * nu)
            layer = 1 + 1.28 * a / H
            dz = branch[0][0] - branch[-1][0]
            print(f"| {label} | {a:g} | {dz:.4f} / {dz / speed:.3f} | {s:.4g} | {half:.3g} | {H:.2f} | "
                  f"{layer:.3f} | {s / (half * layer):.2f} | {2 * H / c_p:.3f} |")
            ref.setdefault(a, []).append((label, s, layer))
    print()
    for a, entries in ref.items():
        l0, s0, f0 = entries[0]
        for label, s, layer in entries[1:]:
            print(f"- plate {a:g} m, {l0} -> {label}: unload slope {100 * (s / s0 - 1):+.1f} %, "
                  f"an elastic layer predicts {100 * (layer / f0 - 1):+.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
