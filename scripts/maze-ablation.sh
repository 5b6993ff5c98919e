#!/usr/bin/env bash
# The maze ablation (issue 34, docs/results.md "The maze, with Lehman's robot"):
# which of Lehman's robot, his collision rule and his walls makes the
# strategies solve the mazes. Per maze, strategy (default: novelty search)
# and seed, at the maze task's defaults (Lehman's NEAT parameters,
# population 250, the paper's budget of 250,000 evaluations), with
#   lehman     — Lehman's robot, walls and collision rule (the reproduce pack's run),
#   walls      — the same, through the shipped SVG's walls (maze.walls = "scenario"),
#   slide      — the same, sliding along walls (maze.collision = "slide"),
#   vivae      — our differential robot of [physics] (maze.robot = "vivae").
# One line per run goes to OUT/runs.tsv (maze, variant, strategy, seed, solved,
# evaluations to solve), the table to OUT/summary.md.
#
#   scripts/maze-ablation.sh [SEED ...]     (default: seeds 1 2 3 4 5)
#   OUT=runs/maze-ablation MAZES='medium-maze hard-maze' VARIANTS='lehman walls slide vivae'
#   STRATEGIES='novelty' (any of novelty neat map-elites) VIVAE=path/to/vivae
#   EXTRA='[neat]\nstart_hidden = 0' (config lines appended to every variant's
#   file, `\n` for newlines: here NEAT's minimal start instead of Lehman's)
#
# Finished runs (a line in runs.tsv) are not run again, so a stopped
# experiment continues where it stopped.
source "$(dirname "$0")/common.sh"
vivae=${VIVAE:-$vivae}
out=${OUT:-runs/maze-ablation}
mazes=${MAZES:-medium-maze hard-maze}
variants=${VARIANTS:-lehman walls slide vivae}
strategies=${STRATEGIES:-novelty}
mkdir -p "$out"
[ -f "$out/runs.tsv" ] || printf 'maze\tvariant\tstrategy\tseed\tsolved\tevaluations\n' > "$out/runs.tsv"
for variant in $variants; do
  case $variant in
    lehman) body='' ;;
    walls) body='walls = "scenario"' ;;
    slide) body='collision = "slide"' ;;
    vivae) body='robot = "vivae"' ;;
    *) echo "unknown variant $variant" >&2; exit 2 ;;
  esac
  printf '[experiment]\ntask = "maze"\n[maze]\n%s\n%b\n' "$body" "${EXTRA:-}" > "$out/$variant.toml"
done
for maze in $mazes; do
  for variant in $variants; do
    for strategy in $strategies; do
      for seed in "${seeds[@]}"; do
        if awk -F'\t' -v m="$maze" -v v="$variant" -v k="$strategy" -v s="$seed" \
          '$1==m && $2==v && $3==k && $4==s {f=1} END{exit !f}' "$out/runs.tsv"; then
          continue
        fi
        line=$("$vivae" evolve -q --config "$out/$variant.toml" --scenario "$maze" --strategy "$strategy" \
          --seed "$seed" --generations 1000 --threads 1 --out "$out/$maze-$variant-$strategy-seed-$seed" | tail -1)
        solved=$(echo "$line" | field solved)
        evals=$(echo "$line" | field evals_to_solve)
        printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$maze" "$variant" "$strategy" "$seed" "$solved" "$evals" >> "$out/runs.tsv"
        echo "$maze $variant $strategy seed $seed: solved=$solved evaluations=$evals"
      done
    done
  done
done
# The table: solved runs and the mean (sd) and median evaluations of the solved ones.
python3 - "$out/runs.tsv" > "$out/summary.md" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1]), delimiter="\t"))
names = {"lehman": "Lehman's robot, walls and collision rule",
         "walls": "… through the SVG's walls (maze.walls = \"scenario\")",
         "slide": "… sliding along walls (maze.collision = \"slide\")",
         "vivae": "our robot (maze.robot = \"vivae\")"}
print("| maze | model | strategy | solved | mean evaluations (sd) | median |")
print("| --- | --- | --- | --- | --- | --- |")
for maze, v, k in dict.fromkeys((r["maze"], r["variant"], r["strategy"]) for r in rows):
    rs = [r for r in rows if (r["maze"], r["variant"], r["strategy"]) == (maze, v, k)]
    ev = [int(r["evaluations"]) for r in rs if r["solved"] == "yes"]
    mean = f"{statistics.mean(ev):,.0f} ({statistics.stdev(ev):,.0f})" if len(ev) > 1 else (f"{ev[0]:,}" if ev else "—")
    med = f"{statistics.median(ev):,.0f}" if ev else "—"
    print(f"| {maze} | {names.get(v, v)} | {k} | {len(ev)}/{len(rs)} | {mean} | {med} |")
PY
cat "$out/summary.md"
