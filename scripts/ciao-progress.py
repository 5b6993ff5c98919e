#!/usr/bin/env python3
"""Arms-race progress from predator-prey runs' ciao.csv (no dependencies).

For each run directory given: the mean hunter fitness and the catch rate
over the CIAO cells where the hunter is of a later generation than the prey
(later hunters against earlier prey) and where it is of an earlier one. A
progressing arms race has later > earlier; cycling gives about the same.

    python3 scripts/ciao-progress.py RUN [RUN ...]
"""

import csv
import statistics
import sys


def measure(run):
    later, earlier = [], []
    with open(f"{run}/ciao.csv") as f:
        for r in csv.DictReader(f):
            h, p = int(r["hunter_generation"]), int(r["prey_generation"])
            cell = (float(r["hunter_fitness"]), r["caught"] == "1")
            if h > p:
                later.append(cell)
            elif h < p:
                earlier.append(cell)
    mean = lambda cells, k: statistics.mean(float(c[k]) for c in cells)
    return mean(later, 0), mean(earlier, 0), mean(later, 1), mean(earlier, 1)


rows = [(run, measure(run)) for run in sys.argv[1:]]
print("run  later_hunter_fitness  earlier_hunter_fitness  later_catch_rate  earlier_catch_rate")
for run, m in rows:
    print(run, " ".join(f"{x:.3f}" for x in m))
if rows:
    print("mean", " ".join(f"{statistics.mean(m[i] for _, m in rows):.3f}" for i in range(4)))
