"""The tables of scripts/avoidance-meetings.sh from its meetings CSVs (Markdown on stdout).

    python3 scripts/avoidance-meetings.py MEET

MEET/RUN/raysR-VIEW-pN/meetings-pN[-blind-rays].csv, one per replay
(`vivae replay --meetings`); RUN is SCENARIO-SETUP-SHEETS-seed-N, R the
rays replayed (`run`: the run's own), VIEW seeing or blind. A meeting: a
robot within 100 px (along the route) of a block placed for the episode. The
block is on the robot's line when its centre is less than 14 px (robot
radius + half a block) across the road from where the robot was on entering
those 100 px. Counted per group of replays:

* touched: meetings in which the robot touched the block; by line (on / off)
  and by the block's place (edge: its centre ≥ 14 px from the road's middle,
  so a side within 8 px of the kerb; middle: nearer);
* chance: the share touched if where a robot crossed the block's row had
  nothing to do with where the block was (every meeting's crossing against
  every block of the group): what a robot that does not avoid touches;
* seen: on-line meetings in which a distance ray showed the block (it was
  the nearest thing on that ray) before any touch; from how far along the
  route it first did (median, px), and the reading at its nearest before
  the touch (median, for the touched ones);
* shift: how far the robot moved away from the block's side between entry
  and crossing (mean px; negative: towards it), on-line meetings touched and
  not touched.
"""

import csv
import glob
import os
import re
import sys
from collections import defaultdict
from statistics import mean, median

meet = sys.argv[1]
LINE = 14.0
groups = defaultdict(list)
placements = defaultdict(set)
for path in sorted(glob.glob(os.path.join(meet, "*", "*", "meetings-p*.csv"))):
    run, view_dir = path.split(os.sep)[-3:-1]
    m = re.fullmatch(r"(.+)-(speed|cost|nsga2)-(surface|rays)-seed-(\d+)", run)
    v = re.fullmatch(r"rays(\w+)-(seeing|blind)-p(\d+)", view_dir)
    if not m or not v:
        continue
    scenario, setup, sheets, seed = m.group(1), m.group(2), m.group(3), int(m.group(4))
    rays = 0 if sheets == "surface" else v.group(1)
    key = (scenario, setup, sheets, seed, rays, v.group(2))
    placements[key].add(int(v.group(3)))
    for row in csv.DictReader(open(path)):
        groups[key].append(row)

SETUP_NAME = {"speed": "progress", "cost": "contact cost", "nsga2": "NSGA-II"}


def name(key):
    _, setup, sheets, seed, rays, view = key
    if sheets == "surface":
        return f"{SETUP_NAME[setup]}, surface (seed {seed})"
    r = "run's rays" if rays == "run" else f"re-sampled to {rays} rays"
    blind = ", blinded" if view == "blind" else ""
    return f"{SETUP_NAME[setup]}, surface + rays, {r}{blind} (seed {seed})"


def share(rows, test):
    return f"{100 * sum(1 for r in rows if test(r)) / len(rows):.0f}% of {len(rows)}" if rows else "–"


def touched(r):
    return int(r["touches"]) > 0


def chance(rows):
    # Meetings that reached the block's row (passed or touched).
    crossed = [float(r["pass_across"]) for r in rows if r["exit"] == "passed" or touched(r)]
    blocks = [float(r["block_across"]) for r in rows]
    if not crossed or not blocks:
        return "–"
    hits = sum(1 for c in crossed for b in blocks if abs(c - b) < LINE)
    return f"{100 * hits / (len(crossed) * len(blocks)):.0f}%"


def med(values, fmt):
    return fmt.format(median(values)) if values else "–"


def avg(values):
    return f"{mean(values):+.1f}" if values else "–"


for scenario in dict.fromkeys(k[0] for k in groups):
    keys = sorted((k for k in groups if k[0] == scenario), key=lambda k: (k[1], k[2] != "surface", k[3], str(k[4]) != "run", str(k[4]), k[5]))
    print(f"### `{scenario}`: meetings with the placed blocks\n")
    print("| replay | placements | meetings | touched | chance | touched, on line | touched, off line | touched, edge block | touched, middle block |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for k in keys:
        rows = groups[k]
        crossing = [r for r in rows if r["exit"] == "passed" or touched(r)]
        on = [r for r in crossing if r["on_line"] == "true"]
        off = [r for r in crossing if r["on_line"] != "true"]
        edge = [r for r in crossing if abs(float(r["block_across"])) >= LINE]
        middle = [r for r in crossing if abs(float(r["block_across"])) < LINE]
        print(f"| {name(k)} | {len(placements[k])} | {len(crossing)} | {share(crossing, touched)} | {chance(rows)} "
              f"| {share(on, touched)} | {share(off, touched)} | {share(edge, touched)} | {share(middle, touched)} |")
    print()
    print(f"### `{scenario}`: what the rays showed on the robot's line, and the swerve\n")
    print("| replay | on line: seen before a touch | first seen at (px, median) | touched: nearest reading before the touch (median) | shift, touched (px) | shift, not touched (px) | robot's line: mean distance from the middle (px) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for k in keys:
        rows = groups[k]
        crossing = [r for r in rows if r["exit"] == "passed" or touched(r)]
        on = [r for r in crossing if r["on_line"] == "true"]
        seen = [float(r["seen_at"]) for r in on if r["seen_at"]]
        peaks = [float(r["peak"]) for r in on if touched(r) and float(r["peak"]) > 0]
        print(f"| {name(k)} | {share(on, lambda r: int(r['seen_steps']) > 0)} | {med(seen, '{:.0f}')} | {med(peaks, '{:.2f}')} "
              f"| {avg([float(r['shift']) for r in on if touched(r)])} | {avg([float(r['shift']) for r in on if not touched(r)])} "
              f"| {mean(abs(float(r['entry_across'])) for r in crossing):.1f} |")
    print()
