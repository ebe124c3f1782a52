#!/usr/bin/env python3
"""A model of the GPU soil loop's warps: how many times a warp runs the pair arithmetic.

The CUDA soil stage gives each particle a thread; a warp is 32 particles in a row of cells (the cells
are sorted x fastest). Each thread walks its 25 rows of neighbour cells (cells of 1.05 h, reach 2),
tests a row's candidates, then sums that row's hits (sph_neighbours.hpp, for_each_hit). A warp runs the
pair arithmetic as often as the lane with the most hits in a loop over hits, so a warp costs the sum over
such loops of the largest lane's hits, not the lanes' mean. This script counts both on a jittered lattice
(h = 1.4 d0) for rows summed one at a time (today's loop) and for rows grouped before their hits are
summed: consecutive rows, and phases of rows in pairs opposite each other about the particle's cell (a
particle high in its cell has more neighbours in the rows above and fewer in those below). The phases
were built and timed (commit 77dba40, reverted): the model's 36 % fewer passes for phases of 8 rows gave
the rigs' configuration 2-3 % on an H100, and the bare kernel lost 13 % (bench/RESULTS.md, "Hit phases").
So the passes it counts are not what bounds the stage; it is kept as the record of that reasoning.

Usage: python3 bench/warp_hit_balance.py   (standard library only; about a second)
"""
import math
import random


def main():
    random.seed(3)
    h = 1.0
    cell = 1.05 * h  # 2h (1 + sort_skin) / reach
    support2 = (2 * h) ** 2
    d0 = h / 1.4
    ncell = (40, 8, 8)
    pts = []
    for i in range(int(ncell[0] * cell / d0)):
        for j in range(int(ncell[1] * cell / d0)):
            for k in range(int(ncell[2] * cell / d0)):
                pts.append(tuple((a + 0.5 + random.uniform(-0.2, 0.2)) * d0 for a in (i, j, k)))

    def cell_of(p):
        return tuple(int(c / cell) for c in p)

    cells = {}
    for p in pts:
        cells.setdefault(cell_of(p), []).append(p)
    order = sorted(pts, key=lambda p: (cell_of(p)[2], cell_of(p)[1], cell_of(p)[0]))

    # Rows in opposite pairs, as the GPU soil loop orders them: (r, 24 - r) for r = 0..11, then 12.
    opposite = [x for r in range(12) for x in (r, 24 - r)] + [12]

    def phases(rows_per_phase):
        return [tuple(opposite[a:a + rows_per_phase]) for a in range(0, 25, rows_per_phase)]

    groupings = {
        "one row at a time": [(r,) for r in range(25)],
        "consecutive pairs": [tuple(range(r, min(r + 2, 25))) for r in range(0, 25, 2)],
        "opposite pairs (r, 24 - r)": phases(2),
        "phases of 4 rows in opposite pairs": phases(4),
        "phases of 8 rows in opposite pairs": phases(8),
        "phases of 12 rows in opposite pairs": phases(12),
        "all 25 rows together (the floor)": phases(25),
    }
    cost = {name: 0 for name in groupings}
    mean_hits = 0.0
    warps = 0
    for w0 in range(0, len(order) - 31, 32):
        warp = order[w0:w0 + 32]
        cs = [cell_of(p) for p in warp]
        interior = all(2 <= c[a] <= ncell[a] - 3 for c in cs for a in range(3))
        if not interior:
            continue
        warps += 1
        hits = []  # per lane, per row (z major, y minor)
        for p, c in zip(warp, cs):
            row_hits = []
            for dz in range(-2, 3):
                for dy in range(-2, 3):
                    n = 0
                    for dx in range(-2, 3):
                        for q in cells.get((c[0] + dx, c[1] + dy, c[2] + dz), []):
                            if q is not p and sum((p[a] - q[a]) ** 2 for a in range(3)) < support2:
                                n += 1
                    row_hits.append(n)
            hits.append(row_hits)
        mean_hits += sum(map(sum, hits)) / 32
        for name, groups in groupings.items():
            cost[name] += sum(max(sum(lane[r] for r in g) for lane in hits) for g in groups)
    print(f"{warps} warps inside the bed; a lane's neighbours: {mean_hits / warps:.1f} on average")
    print("passes of the pair arithmetic per warp:")
    base = cost["one row at a time"]
    for name, c in cost.items():
        print(f"  {name:36s} {c / warps:7.1f}  ({c / base:.2f})")


if __name__ == "__main__":
    main()
