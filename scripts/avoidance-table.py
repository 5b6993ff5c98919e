"""The tables of scripts/avoidance.sh from its replays.tsv (Markdown on stdout).

    python3 scripts/avoidance-table.py OUT/replays.tsv COST RAYS

Per run, the mean over its held-out placements of: progress (px/step along
the route; for a contact-cost run its replayed fitness plus COST × contacts),
average speed (px/step), contacts begun per 1,000 robot-steps (robot–robot,
robot–scripted robot, robot–obstacle: the `collisions` measure) and each
kind, walls included. The target (issue 38): a distance-sheet champion keeps
≥ 90% of the surface-only speed champion's speed (same scenario and seed)
with ≤ 25% of its contacts, in ≥ 4 of 5 seeds.
"""

import csv
import sys
from collections import defaultdict
from statistics import mean

tsv, cost, rays = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
KINDS = ["robot", "traffic", "obstacle", "wall"]
SETUP_NAME = {"speed": "progress", "cost": f"progress − {cost:g}/contact", "nsga2": "NSGA-II"}

runs = defaultdict(list)
for row in csv.DictReader(open(tsv), delimiter="\t"):
    fitness, collisions = float(row["fitness"]), float(row["collisions"])
    progress = fitness + (cost * collisions if row["setup"] == "cost" else 0.0)
    m = {"progress": progress, "speed": float(row["speed"]), "contacts": collisions}
    m.update({k: float(row[k]) for k in KINDS})
    key = (row["scenario"], row["setup"], row["sheets"], int(row["seed"]), int(row["rays"]))
    runs[key].append(m)
run = {k: {f: mean(m[f] for m in v) for f in v[0]} | {"n": len(v)} for k, v in runs.items()}
scenarios = list(dict.fromkeys(k[0] for k in run))
# The setups the experiment ran (SETUPS of avoidance.sh), in a fixed order.
SETUPS = [s for s in ["speed", "cost", "nsga2"] if any(k[1] == s for k in run)]
seeds = sorted({k[3] for k in run})
placements = sorted({m["n"] for m in run.values()})


def sheet_name(sheets, r):
    return "surface" if sheets == "surface" else f"surface + {r} rays"


def ratio(a, b):
    return a / b if b else (0.0 if a == 0 else float("inf"))


def meets(r, base):
    """Speed share, contact share and whether the target holds, per speed measure."""
    out = {}
    for speed in ["progress", "speed"]:
        s, c = ratio(r[speed], base[speed]), ratio(r["contacts"], base["contacts"])
        out[speed] = (s, c, s >= 0.9 and c <= 0.25)
    return out


def pct(x):
    return "∞" if x == float("inf") else f"{100 * x:.0f}%"


print(f"Held-out placements per champion: {', '.join(map(str, placements))}; seeds {', '.join(map(str, seeds))}.\n")
for sc in scenarios:
    print(f"### `{sc}`: means over seeds (per 1,000 robot-steps: contacts and each kind)\n")
    print("| fitness | sheets | progress | speed | contacts | robot | scripted | obstacle | wall |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for setup in SETUPS:
        for sheets, r in [("surface", 0), ("rays", rays)]:
            rs = [run[k] for k in run if k[:3] == (sc, setup, sheets) and k[4] == r]
            if not rs:
                continue
            avg = {f: mean(x[f] for x in rs) for f in rs[0]}
            print(f"| {SETUP_NAME[setup]} | {sheet_name(sheets, r)} | {avg['progress']:.3f} | {avg['speed']:.3f} | "
                  f"{avg['contacts']:.2f} | " + " | ".join(f"{avg[k]:.2f}" for k in KINDS) + " |")
    print()
    print(f"### `{sc}`: per seed, against the surface-only speed champion\n")
    print("Each cell: progress, speed (px/step), contacts per 1,000 robot-steps; then progress share and "
          "contact share of the surface-only speed champion's; ✓ where the target holds on progress.\n")
    print("| seed | surface, progress | " + " | ".join(
        f"{sheet_name('rays', rays)}, {SETUP_NAME[s]}" for s in SETUPS) + " | surface, " + " | surface, ".join(
        SETUP_NAME[s] for s in SETUPS[1:]) + " |")
    print("| --- " * (2 + 2 * len(SETUPS) - 1) + "|")
    met = defaultdict(int)
    for seed in seeds:
        base = run.get((sc, "speed", "surface", seed, 0))
        if base is None:
            continue
        cells = [f"{base['progress']:.3f}, {base['speed']:.3f}, {base['contacts']:.2f}"]
        for sheets, r, setups in [("rays", rays, SETUPS), ("surface", 0, SETUPS[1:])]:
            for setup in setups:
                x = run.get((sc, setup, sheets, seed, r))
                if x is None:
                    cells.append("–")
                    continue
                m = meets(x, base)
                s, c, ok = m["progress"]
                met[(setup, sheets, "progress")] += ok
                met[(setup, sheets, "speed")] += m["speed"][2]
                cells.append(f"{x['progress']:.3f}, {x['speed']:.3f}, {x['contacts']:.2f} ({pct(s)}, {pct(c)}){' ✓' if ok else ''}")
        print(f"| {seed} | " + " | ".join(cells) + " |")
    print()
    n = sum(1 for seed in seeds if (sc, "speed", "surface", seed, 0) in run)
    for setup in SETUPS:
        for sheets, r in [("rays", rays), ("surface", 0)]:
            if setup == "speed" and sheets == "surface":
                continue
            print(f"- {sheet_name(sheets, r)}, {SETUP_NAME[setup]}: target met in "
                  f"{met[(setup, sheets, 'progress')]} of {n} seeds on progress, "
                  f"{met[(setup, sheets, 'speed')]} of {n} on average speed")
    print()
    resampled = sorted({k[4] for k in run if k[0] == sc and k[2] == "rays"})
    if len(resampled) > 1:
        print(f"### `{sc}`: the distance sheet re-sampled (means over seeds; target seeds on progress)\n")
        print("| fitness | " + " | ".join(f"{r} rays: progress, contacts, target" for r in resampled) + " |")
        print("| --- " * (1 + len(resampled)) + "|")
        for setup in SETUPS:
            cells = []
            for r in resampled:
                rs = [(seed, run[(sc, setup, "rays", seed, r)]) for seed in seeds if (sc, setup, "rays", seed, r) in run]
                if not rs:
                    cells.append("–")
                    continue
                ok = sum(meets(x, run[(sc, "speed", "surface", seed, 0)])["progress"][2]
                         for seed, x in rs if (sc, "speed", "surface", seed, 0) in run)
                cells.append(f"{mean(x['progress'] for _, x in rs):.3f}, {mean(x['contacts'] for _, x in rs):.2f}, "
                             f"{ok} of {len(rs)}")
            print(f"| {SETUP_NAME[setup]} | " + " | ".join(cells) + " |")
        print()
