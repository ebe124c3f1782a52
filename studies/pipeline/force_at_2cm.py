#!/usr/bin/env python3
# The plate force at 2 cm sinkage from a `terracal crm` run's bodies.csv, as the convergence test
# measures it (tests/highfi/crm/crm_plate_study.hpp): a least-squares line of force against sinkage over
# 1.5-2.5 cm, read at 2 cm. Usage: force_at_2cm.py RUN/bodies.csv [...]
import csv, sys
for path in sys.argv[1:]:
    rows = list(csv.DictReader(open(path)))
    z0 = float(rows[0]['z_m']) + 0.1 * float(rows[0]['time_s'])  # the plate's start: it moves at 0.1 m/s
    pts = [(z0 - float(r['z_m']) - 0.02, float(r['fz_N'])) for r in rows]
    pts = [(x, y) for x, y in pts if -0.005 <= x <= 0.005]
    n = len(pts); sx = sum(x for x, _ in pts); sy = sum(y for _, y in pts)
    sxx = sum(x * x for x, _ in pts); sxy = sum(x * y for x, y in pts)
    slope = (n * sxy - sx * sy) / (n * sxx - sx * sx)
    print('%s: force at 2 cm %.2f N (%d samples, slope %.0f N/m)' % (path, (sy - slope * sx) / n, n, slope))
