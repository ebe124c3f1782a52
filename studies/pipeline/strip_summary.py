#!/usr/bin/env python3
# The strip-footing reproducer of the plate's run-length problem (results/plate_bin_check, ninth
# study): for each variant, the force at 1, 2, 3, 4 and 4.75 cm sinkage pushed at 0.1 and at
# 0.05 m/s, the change between the two (mean |dF| over mean F, as curve_change.awk), and the share
# of the force at 4.75 cm still held at the end of the 0.4 s hold.
# Input: either a combined CSV (variant,speed,time_s,z_m,fz_N: results/plate_bin_check/contact/strip.csv)
# or run folders NAME_fast and NAME_slow holding `terracal crm` output (bodies.csv):
#   strip_summary.py strip.csv           strip_summary.py --runs DIR NAME [NAME...]
import csv, os, sys
from collections import defaultdict

SURFACE, HALF_THICKNESS = 0.30, 0.03  # the strip scenes' soil surface and plate half thickness [m]
SINKAGES = [0.01, 0.02, 0.03, 0.04, 0.0475]


def force_at(trace, sinkage):
    # mean force of the samples within 1.5 mm of the sinkage (the plate moves 0.33 mm per sample)
    z_centre = SURFACE - sinkage + HALF_THICKNESS
    v = [f for t, z, f in trace if abs(z - z_centre) < 0.0015]
    return sum(v) / len(v) if v else float('nan')


def summary(name, fast, slow):
    ff = [force_at(fast, s) for s in SINKAGES]
    fs = [force_at(slow, s) for s in SINKAGES]
    change = 100 * sum(abs(a - b) for a, b in zip(ff, fs)) / sum(ff)
    kept = 100 * sum(f for _, _, f in fast[-10:]) / 10 / ff[-1]
    print('| %s | %s | %s | %.1f %% | %.0f %% |' % (name, ' / '.join('%.0f' % x for x in ff),
                                                   ' / '.join('%.0f' % x for x in fs), change, kept))


def main():
    print('| variant | F at 1/2/3/4/4.75 cm, 0.1 m/s [N] | at 0.05 m/s [N] | change | held after 0.4 s |')
    print('|---|---|---|---|---|')
    if sys.argv[1] == '--runs':
        folder = sys.argv[2]
        for name in sys.argv[3:]:
            traces = []
            for speed in ('fast', 'slow'):
                rows = csv.DictReader(open(os.path.join(folder, '%s_%s' % (name, speed), 'bodies.csv')))
                traces.append([(float(r['time_s']), float(r['z_m']), float(r['fz_N'])) for r in rows])
            summary(name, *traces)
        return
    runs = defaultdict(list)
    for r in csv.DictReader(open(sys.argv[1])):
        runs[(r['variant'], r['speed'])].append((float(r['time_s']), float(r['z_m']), float(r['fz_N'])))
    for name in dict.fromkeys(v for v, _ in runs):
        summary(name, runs[(name, 'fast')], runs[(name, 'slow')])


if __name__ == '__main__':
    main()
