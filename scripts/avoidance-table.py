"""The tables of scripts/avoidance.sh from its replays.tsv (Markdown on stdout).

    python3 scripts/avoidance-table.py OUT/replays.tsv COST RAYS [OUT/status.tsv]

Per run, the mean over its held-out placements of: progress (px/step along
the route; for a contact-cost run its replayed fitness plus COST × contacts),
average speed (px/step), contacts begun per 1,000 robot-steps and each kind,
walls included. The contacts the target counts: on the courses where no
line is safe (`corridor`, `kerbed-loop`, `oncoming-edges`) the blocks placed
for the episode and the scripted robots met (`contacts_placed` +
`contacts_traffic`: kerbs are obstacles a robot may scrape along, counted
apart); elsewhere every contact with another robot, a scripted robot or an
obstacle (`collisions`). The target: a distance-sheet champion keeps ≥ 90%
of the surface-only progress champion's progress (same scenario and seed)
with ≤ 25% of its contacts, in ≥ 4 of 5 seeds. A distance-sheet champion
is also replayed with its rays blinded (every ray reads "nothing in
range"): where the rays drive the swerve, contacts go up.
"""

import csv
import sys
from collections import defaultdict
from statistics import mean

tsv, cost, rays = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
status = sys.argv[4] if len(sys.argv) > 4 else None
KINDS = ["robot", "traffic", "obstacle", "wall", "placed"]
SETUP_NAME = {"speed": "progress", "cost": f"progress − {cost:g}/contact", "nsga2": "NSGA-II"}
# Courses whose blocks are placed across the whole road, between kerbs.
COURSES = {"corridor", "kerbed-loop", "oncoming-edges"}

runs = defaultdict(list)
for row in csv.DictReader(open(tsv), delimiter="\t"):
    fitness, collisions = float(row["fitness"]), float(row["collisions"])
    progress = fitness + (cost * collisions if row["setup"] == "cost" else 0.0)
    m = {"progress": progress, "speed": float(row["speed"]), "collisions": collisions}
    # A table of an older experiment has no placed blocks column.
    m.update({k: float(row.get(k) or 0.0) for k in KINDS})
    m["contacts"] = m["placed"] + m["traffic"] if row["scenario"] in COURSES else collisions
    view = row.get("view") or "seeing"
    key = (row["scenario"], row["setup"], row["sheets"], int(row["seed"]), int(row["rays"]), view)
    runs[key].append(m)
run = {k: {f: mean(m[f] for m in v) for f in v[0]} | {"n": len(v)} for k, v in runs.items()}
scenarios = list(dict.fromkeys(k[0] for k in run))
# The setups the experiment ran (SETUPS of avoidance.sh), in a fixed order.
SETUPS = [s for s in ["speed", "cost", "nsga2"] if any(k[1] == s for k in run)]
seeds = sorted({k[3] for k in run})
placements = sorted({m["n"] for m in run.values()})


def sheet_name(sheets, r, view="seeing"):
    name = "surface" if sheets == "surface" else f"surface + {r} rays"
    return name + (", blinded" if view == "blind" else "")


def ratio(a, b):
    return a / b if b else (0.0 if a == 0 else float("inf"))


def meets(r, base):
    """Progress share, contact share and whether the target holds."""
    s, c = ratio(r["progress"], base["progress"]), ratio(r["contacts"], base["contacts"])
    return s, c, s >= 0.9 and c <= 0.25


def pct(x):
    return "∞" if x == float("inf") else f"{100 * x:.0f}%"


def get(sc, setup, sheets, seed, r, view="seeing"):
    return run.get((sc, setup, sheets, seed, r, view))


def contacts_name(sc):
    return ("blocks and scripted robots met (`contacts_placed` + `contacts_traffic`)" if sc in COURSES
            else "contacts (`collisions`)")


if status:
    states = defaultdict(list)
    for row in csv.DictReader(open(status), delimiter="\t"):
        states[row["state"]].append(f"{row['run']} ({row['generations']})")
    total = sum(len(v) for v in states.values())
    print(f"Runs finished and judged: {len(states['finished'])} of {total}.")
    for state, what in [("running", "Still evolving or stopped (generations done)"),
                        ("missing", "Not started")]:
        # A long list of runs not started says no more than its length.
        if len(states[state]) > 12:
            print(f"{what}: {len(states[state])} runs (listed in status.tsv).")
        elif states[state]:
            print(f"{what}: {', '.join(states[state])}.")
    print()
print(f"Held-out placements per champion: {', '.join(map(str, placements))}; "
      f"seeds {', '.join(map(str, seeds))}.\n")
for sc in scenarios:
    print(f"### `{sc}`: means over seeds (per 1,000 robot-steps: contacts and each kind)\n")
    print(f"Contacts: {contacts_name(sc)}; the kinds: other learners, scripted robots, obstacles "
          "(kerbs and placed blocks), walls, placed blocks.\n")
    print("| fitness | sheets | seeds | progress | speed | contacts | robot | scripted | obstacle | wall | placed |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for setup in SETUPS:
        for sheets, r, view in [("surface", 0, "seeing"), ("rays", rays, "seeing"), ("rays", rays, "blind")]:
            rs = [run[k] for k in run if k[:3] == (sc, setup, sheets) and k[4:] == (r, view)]
            if not rs:
                continue
            avg = {f: mean(x[f] for x in rs) for f in rs[0]}
            print(f"| {SETUP_NAME[setup]} | {sheet_name(sheets, r, view)} | {len(rs)} | {avg['progress']:.3f} | "
                  f"{avg['speed']:.3f} | {avg['contacts']:.2f} | " + " | ".join(f"{avg[k]:.2f}" for k in KINDS) + " |")
    print()
    print(f"### `{sc}`: per seed, against the surface-only progress champion\n")
    print("Each cell: progress, speed (px/step), contacts per 1,000 robot-steps; then progress share and "
          "contact share of the surface-only progress champion's; ✓ where the target holds.\n")
    print("| seed | surface, progress | " + " | ".join(
        f"{sheet_name('rays', rays)}, {SETUP_NAME[s]}" for s in SETUPS) + "".join(
        f" | surface, {SETUP_NAME[s]}" for s in SETUPS[1:]) + " |")
    print("| --- " * (2 + 2 * len(SETUPS) - 1) + "|")
    met = defaultdict(int)
    judged = defaultdict(int)
    for seed in seeds:
        base = get(sc, "speed", "surface", seed, 0)
        if base is None:
            continue
        cells = [f"{base['progress']:.3f}, {base['speed']:.3f}, {base['contacts']:.2f}"]
        for sheets, r, setups in [("rays", rays, SETUPS), ("surface", 0, SETUPS[1:])]:
            for setup in setups:
                x = get(sc, setup, sheets, seed, r)
                if x is None:
                    cells.append("–")
                    continue
                s, c, ok = meets(x, base)
                met[(setup, sheets)] += ok
                judged[(setup, sheets)] += 1
                cells.append(f"{x['progress']:.3f}, {x['speed']:.3f}, {x['contacts']:.2f} ({pct(s)}, {pct(c)}){' ✓' if ok else ''}")
        print(f"| {seed} | " + " | ".join(cells) + " |")
    print()
    for setup in SETUPS:
        for sheets, r in [("rays", rays), ("surface", 0)]:
            if setup == "speed" and sheets == "surface":
                continue
            n = judged[(setup, sheets)]
            print(f"- {sheet_name(sheets, r)}, {SETUP_NAME[setup]}: target met in "
                  f"{met[(setup, sheets)]} of {n} seed{'' if n == 1 else 's'} judged")
    print()
    blinded = [(seed, setup) for setup in SETUPS for seed in seeds
               if get(sc, setup, "rays", seed, rays, "blind") and get(sc, setup, "rays", seed, rays)]
    if blinded:
        print(f"### `{sc}`: the rays blinded\n")
        print("Each distance-sheet champion seeing and with every ray reading \"nothing in range\" "
              "(`vivae replay --blind-rays`), on the same placements: progress (px/step), contacts "
              "per 1,000 robot-steps and per 1,000 px driven (a robot that drives less meets less); "
              "the last column the blinded contacts per px driven over the seeing ones.\n")
        print("| fitness | seed | seeing: progress, contacts, per 1,000 px | blinded: progress, contacts, per 1,000 px "
              "| contacts per px, blinded / seeing |")
        print("| --- | --- | --- | --- | --- |")
        up = up_px = 0
        for seed, setup in blinded:
            see, blind = get(sc, setup, "rays", seed, rays), get(sc, setup, "rays", seed, rays, "blind")
            per_px = [ratio(x["contacts"], x["speed"]) for x in (see, blind)]
            up += blind["contacts"] > see["contacts"]
            up_px += per_px[1] > per_px[0]
            print(f"| {SETUP_NAME[setup]} | {seed} | {see['progress']:.3f}, {see['contacts']:.2f}, {per_px[0]:.2f} | "
                  f"{blind['progress']:.3f}, {blind['contacts']:.2f}, {per_px[1]:.2f} | {pct(ratio(per_px[1], per_px[0]))} |")
        print(f"\nBlinding the rays raised contacts per 1,000 robot-steps for {up} of {len(blinded)} distance-sheet "
              f"champions, per px driven for {up_px}.\n")
    resampled = sorted({k[4] for k in run if k[0] == sc and k[2] == "rays" and k[5] == "seeing"})
    if len(resampled) > 1:
        print(f"### `{sc}`: the distance sheet re-sampled (means over seeds; seeds meeting the target)\n")
        print("| fitness | " + " | ".join(f"{r} rays: progress, contacts, target" for r in resampled) + " |")
        print("| --- " * (1 + len(resampled)) + "|")
        for setup in SETUPS:
            cells = []
            for r in resampled:
                rs = [(seed, get(sc, setup, "rays", seed, r)) for seed in seeds if get(sc, setup, "rays", seed, r)]
                if not rs:
                    cells.append("–")
                    continue
                ok = sum(meets(x, get(sc, "speed", "surface", seed, 0))[2]
                         for seed, x in rs if get(sc, "speed", "surface", seed, 0))
                cells.append(f"{mean(x['progress'] for _, x in rs):.3f}, {mean(x['contacts'] for _, x in rs):.2f}, "
                             f"{ok} of {len(rs)}")
            print(f"| {SETUP_NAME[setup]} | " + " | ".join(cells) + " |")
        print()
        print(f"Per seed: progress, contacts per 1,000 robot-steps (share of the same seed's surface-only progress champion's, ✓ where the target holds):\n")
        print("| fitness | seed | " + " | ".join(f"{r} rays" for r in resampled) + " |")
        print("| --- " * (2 + len(resampled)) + "|")
        for setup in SETUPS:
            for seed in seeds:
                if not get(sc, setup, "rays", seed, resampled[0]):
                    continue
                base = get(sc, "speed", "surface", seed, 0)
                cells = []
                for r in resampled:
                    x = get(sc, setup, "rays", seed, r)
                    if not x:
                        cells.append("–")
                        continue
                    cell = f"{x['progress']:.3f}, {x['contacts']:.2f}"
                    if base:
                        p, c, ok = meets(x, base)
                        cell += f" ({pct(p)}, {pct(c)}{' ✓' if ok else ''})"
                    cells.append(cell)
                print(f"| {SETUP_NAME[setup]} | {seed} | " + " | ".join(cells) + " |")
        print()
