# Adds seeded normal noise to trajectory.csv's compared channels (not to the first row, whose vx gives
# the initial speed): usage add_noise.py SEED DIR...
import csv
import sys

import numpy as np

SD = {"vx": 0.05, "yaw_rate": 0.01, "roll": 0.002, "ay": 0.1}
rng = np.random.default_rng(int(sys.argv[1]))
for d in sys.argv[2:]:
    rows = list(csv.reader(open(f"{d}/trajectory.csv")))
    head, data = rows[0], np.array(rows[1:], dtype=float)
    for name, sd in SD.items():
        i = head.index(name)
        data[1:, i] += rng.normal(0, sd, len(data) - 1)
    with open(f"{d}/trajectory.csv", "w") as f:
        f.write(",".join(head) + "\n")
        for row in data:
            f.write(",".join(f"{v:.9g}" for v in row) + "\n")
