#!/usr/bin/env bash
# Does the fast precision change the science? (issue 36, docs/results.md
# "Exact and fast precision"). The paper's experiment (`vivae evolve`, the
# default run) for each seed in both precisions; per run the champion's
# fitness, its share of robot-steps on the road, and its fitness and on-road
# share with its neuron sheet re-sampled to 9x9 (no re-training). Then each
# column's mean and standard deviation per precision and an exact two-sided
# Mann-Whitney (rank-sum) p-value for exact against fast.
#
#   scripts/precision-science.sh [SEED ...]      (default: seeds 1 2 3 4 5)
#   OUT=runs/precision VIVAE=path/to/vivae
#
# Finished runs (a champion.json) are not evolved again.
source "$(dirname "$0")/common.sh"
vivae=${VIVAE:-$vivae}
out=${OUT:-runs/precision}
mkdir -p "$out"
rows="$out/runs.tsv"
: > "$rows"
for seed in "${seeds[@]}"; do
  for p in exact fast; do
    dir="$out/$p-seed-$seed"
    if [ ! -f "$dir/champion.json" ]; then
      "$vivae" evolve -q --seed "$seed" --precision "$p" --out "$dir" --force > "$dir.evolve.txt"
    fi
    line=$(cat "$dir.evolve.txt")
    r99=$("$vivae" replay "$dir" --neurons 9x9 2>/dev/null)
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$p" "$seed" \
      "$(echo "$line" | field best)" "$(echo "$line" | field on_road)" \
      "$(echo "$r99" | field fitness)" "$(echo "$r99" | field on_road)" \
      "$(echo "$line" | field wall_s)" >> "$rows"
  done
done
python3 - "$rows" <<'PY'
import itertools, statistics, sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1])]
cols = ["champion fitness", "on road", "9x9 fitness", "9x9 on road", "wall s"]
print("| precision | seed | " + " | ".join(cols) + " |")
print("| --- " * (len(cols) + 2) + "|")
for r in rows:
    print("| " + " | ".join(r[:2] + [f"{float(x):.3f}" for x in r[2:]]) + " |")
def ranksum_p(a, b):
    # Exact two-sided p of the rank-sum statistic over all splits of the pooled values.
    pooled = a + b
    order = sorted(range(len(pooled)), key=lambda i: pooled[i])
    ranks = [0.0] * len(pooled)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and pooled[order[j + 1]] == pooled[order[i]]:
            j += 1
        for k in range(i, j + 1):
            ranks[order[k]] = (i + j) / 2 + 1
        i = j + 1
    mean = len(a) * (len(pooled) + 1) / 2
    seen = abs(sum(ranks[: len(a)]) - mean)
    splits = list(itertools.combinations(range(len(pooled)), len(a)))
    extreme = sum(1 for s in splits if abs(sum(ranks[k] for k in s) - mean) >= seen - 1e-9)
    return extreme / len(splits)
print()
print("| column | exact mean (sd) | fast mean (sd) | rank-sum p |")
print("| --- | --- | --- | --- |")
for c, name in enumerate(cols[:4]):
    e = [float(r[2 + c]) for r in rows if r[0] == "exact"]
    f = [float(r[2 + c]) for r in rows if r[0] == "fast"]
    sd = lambda x: statistics.stdev(x) if len(x) > 1 else 0.0
    print(f"| {name} | {statistics.mean(e):.3f} ({sd(e):.3f}) | {statistics.mean(f):.3f} ({sd(f):.3f}) | {ranksum_p(e, f):.2f} |")
PY
