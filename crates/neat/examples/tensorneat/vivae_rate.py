"""Evaluations/s of a vivae example run, from its per-run stderr lines
(`NAME seed=S evals=E|unsolved hidden=H generalisation=G ms=T`).

    python vivae_rate.py POP MAX_GENERATIONS < stderr-file

vivae counts evaluations up to the first solving genome; the whole generation
was evaluated, so the genomes evaluated are ceil(E / POP) * POP (an unsolved
run: MAX_GENERATIONS * POP). Prints one JSON line. Standard library only.
"""
import json
import math
import re
import sys

pop, max_gen = int(sys.argv[1]), int(sys.argv[2])
runs = solved = evaluated = to_solve = 0
ms = 0.0
per_run_ms = []
for line in sys.stdin:
    m = re.search(r"seed=(\d+) evals=(\S+) .* ms=(\d+)", line)
    if not m:
        continue
    runs += 1
    t = float(m.group(3))
    ms += t
    per_run_ms.append(t)
    if m.group(2) == "unsolved":
        evaluated += max_gen * pop
    else:
        e = int(m.group(2))
        solved += 1
        to_solve += e
        evaluated += math.ceil(e / pop) * pop
per_run_ms.sort()
print(json.dumps({
    "runs": runs,
    "solved": solved,
    "mean_evals_to_solver": round(to_solve / max(solved, 1), 1),
    "genomes_evaluated": evaluated,
    "total_ms": ms,
    "mean_ms_per_run": round(ms / runs, 2),
    "median_ms_per_run": per_run_ms[len(per_run_ms) // 2],
    "evals_per_s": round(evaluated / (ms / 1e3), 1),
}))
