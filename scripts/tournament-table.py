#!/usr/bin/env python3
"""Summarises `vivae tournament A B --csv FILE` tables over seeds.

Usage: python3 scripts/tournament-table.py FILE.csv...

Keeps the rows whose hunters are run A's (the first run of each table) and
groups them by the kind of A (its directory name without the trailing
`-SEED`), B, and the sets played (champion or hall); prints per group the
seeds, the mean catch rate, the mean hunter fitness and the mean step of the
catches (over the seeds that caught), each seed's catch rate in brackets.
"""
import csv
import re
import sys
from collections import defaultdict


def main(paths):
    groups = defaultdict(list)
    for path in paths:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        first = rows[0]["hunters_run"]
        for r in rows:
            if r["hunters_run"] != first:
                continue
            kind = re.sub(r"-\d+$", "", first.rstrip("/").split("/")[-1])
            prey = r["prey_run"].rstrip("/").split("/")[-1]
            groups[(kind, prey, r["hunters"], r["prey"])].append(r)
    print("hunters prey sets seeds catch_rate hunter_fitness catch_step per_seed_catch_rate")
    for (kind, prey, hs, ps), rows in sorted(groups.items()):
        rate = [float(r["catch_rate"]) for r in rows]
        fit = [float(r["mean_hunter_fitness"]) for r in rows]
        steps = [float(r["mean_catch_step"]) for r in rows if r["mean_catch_step"]]
        step = f"{sum(steps) / len(steps):.1f}" if steps else "-"
        each = " ".join(f"{x:.2f}" for x in rate)
        print(
            f"{kind} {prey} {hs}x{ps} {len(rows)} {sum(rate) / len(rate):.3f} "
            f"{sum(fit) / len(fit):.3f} {step} [{each}]"
        )


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
