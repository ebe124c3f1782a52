#!/usr/bin/env python3
# The strip footing at five spacings with the scratch spring of the tenth study (k = beta E/(rho h^2),
# no reaction on the neighbours): force at 1/2/3/4/4.75 cm at 0.1 m/s, the share kept after 0.4 s
# held, and at 0.01 and 0.005 m the change at 0.05 m/s. Usage: summary.py strip_spring.csv
import csv, sys
from collections import defaultdict
S = [0.01, 0.02, 0.03, 0.04, 0.0475]
runs = defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    runs[(r['beta'], r['d0'], r['speed'])].append((float(r['time_s']), float(r['z_m']), float(r['fz_N'])))
def at(tr, s):
    zc = 0.30 - s + 0.03; v = [f for t, z, f in tr if abs(z - zc) < 0.0015]; return sum(v) / len(v) if v else float('nan')
print('| beta | d0 [m] | F at 1/2/3/4/4.75 cm, 0.1 m/s [N] | held after 0.4 s | change at 0.05 m/s |')
print('|---|---|---|---|---|')
for beta in ['0', '0.03', '0.1']:
    for d0 in ['0.02', '0.014', '0.01', '0.007', '0.005']:
        tr = runs[(beta, d0, 'fast')]; ff = [at(tr, s) for s in S]
        kept = sum(x for _, _, x in tr[-10:]) / 10 / ff[-1] * 100
        ch = '-'
        if (beta, d0, 'slow') in runs:
            fs = [at(runs[(beta, d0, 'slow')], s) for s in S]
            ch = '%.1f %%' % (100 * sum(abs(a - b) for a, b in zip(ff, fs)) / sum(ff))
        print('| %s | %s | %s | %.0f %% | %s |' % (beta, d0, ' / '.join('%.0f' % x for x in ff), kept, ch))
