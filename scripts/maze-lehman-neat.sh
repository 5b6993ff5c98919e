#!/usr/bin/env bash
# The maze with Lehman's NEAT parameters (issue 34, docs/results.md "The maze"):
# his released code's maze.ne and rtNEAT settings (weight mutation ±0.8
# uniform, weights within ±3, started within ±1; 16 target species; add-node
# 0.005, add-link 0.1; survival 0.4; no stagnation cull) where our config has
# the knob, written out in full: since they became the maze task's defaults
# (tasks::maze::lehman_neat) this is the reproduce pack's run (Lehman's robot
# and walls, population 250, 250,000 evaluations) with a journal of its own. One line per run goes to OUT/runs.tsv (maze, strategy, seed,
# solved, evaluations to solve).
#
#   scripts/maze-lehman-neat.sh [SEED ...]     (default: seeds 1 2 3 4 5)
#   OUT=runs/maze-lehman-neat MAZES=hard-maze STRATEGIES=neat VIVAE=path/to/vivae
#
# Finished runs (a line in runs.tsv) are not run again.
source "$(dirname "$0")/common.sh"
vivae=${VIVAE:-$vivae}
out=${OUT:-runs/maze-lehman-neat}
mazes=${MAZES:-hard-maze}
strategies=${STRATEGIES:-neat}
mkdir -p "$out"
cat > "$out/lehman-neat.toml" <<'TOML'
[experiment]
task = "maze"
generations = 1000

[neat]
population_size = 250
weight_perturb_power = 0.46
weight_amplitude = 3.0
initial_weight_range = 1.0
weight_link_probability = 0.95
weight_replace_probability = 0.1
weight_mutation_probability = 0.6
compatibility_threshold = 4.0
c_excess = 1.0
c_disjoint = 1.0
c_weight = 3.0
target_species = 16
threshold_step = 1.0
survival_threshold = 0.4
stagnation_limit = 1000000
add_node_probability = 0.005
add_link_probability = 0.1
add_link_attempts = 40
mating_probability = 0.7
toggle_enable_probability = 0.1
TOML
[ -f "$out/runs.tsv" ] || printf 'maze\tstrategy\tseed\tsolved\tevaluations\n' > "$out/runs.tsv"
for maze in $mazes; do
  for strategy in $strategies; do
    for seed in "${seeds[@]}"; do
      if awk -F'\t' -v m="$maze" -v k="$strategy" -v s="$seed" '$1==m && $2==k && $3==s {f=1} END{exit !f}' "$out/runs.tsv"; then
        continue
      fi
      line=$("$vivae" evolve -q --config "$out/lehman-neat.toml" --scenario "$maze" --strategy "$strategy" \
        --seed "$seed" --threads 1 --out "$out/$maze-$strategy-seed-$seed" | tail -1)
      printf '%s\t%s\t%s\t%s\t%s\n' "$maze" "$strategy" "$seed" "$(echo "$line" | field solved)" \
        "$(echo "$line" | field evals_to_solve)" >> "$out/runs.tsv"
      echo "$maze $strategy seed $seed: $(echo "$line" | field solved) $(echo "$line" | field evals_to_solve)"
    done
  done
done
awk -F'\t' 'NR>1{k=$1" "$2; n[k]++; if($4=="yes"){s[k]++; e[k]+=$5}} END{for(k in n) printf "%s: solved %d/%d, mean evaluations of the solved %s\n", k, s[k], n[k], (s[k]?sprintf("%.0f", e[k]/s[k]):"—")}' "$out/runs.tsv"
