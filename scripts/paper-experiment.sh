#!/usr/bin/env bash
# Reproduces docs/results.md: the paper's experiment for several seeds, the
# champion re-sampled to 9x9 neurons and to 3x6 sensors without re-training,
# and 20 generations of `retrain` at 3x6 sensors.
#
#   scripts/paper-experiment.sh [SEED ...]      (default: seeds 1 2 3 4 5)
#
# Runs go to runs/paper-seed-N (existing ones are replaced). Prints one table row per seed.
source "$(dirname "$0")/common.sh"
printf '| seed | gen 1 | gen 10 | champion (gen) | on road | wall s | robot-steps/s | 9x9 | 3x6 | 3x6 after 20 gen retrain |\n'
printf '| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n'
for seed in "${seeds[@]}"; do
  dir=runs/paper-seed-$seed
  line=$($vivae evolve -q --seed "$seed" --out "$dir" --force)
  best=$(echo "$line" | field best)
  champ_gen=$(echo "$line" | field champion_generation)
  on_road=$(echo "$line" | field on_road)
  wall=$(echo "$line" | field wall_s)
  rate=$(echo "$line" | field robot_steps_per_s)
  g1=$(awk -F, '$1==1{print $2}' "$dir/generations.csv")
  g10=$(awk -F, '$1==10{print $2}' "$dir/generations.csv")
  n99=$($vivae replay "$dir" --neurons 9x9 2>/dev/null | field fitness)
  s36=$($vivae replay "$dir" --sensors 3x6 2>/dev/null | field fitness)
  re=$($vivae retrain "$dir" --sensors 3x6 --generations 20 -q --out "$dir-retrain-3x6" --force | field best)
  pct() { awk -v a="$1" -v b="$best" 'BEGIN{printf "%.1f%%", 100*a/b}'; }
  printf '| %s | %.3f | %.3f | %.3f (%s) | %.1f%% | %s | %.2f M | %.3f (%s) | %.3f (%s) | %.3f (%s) |\n' \
    "$seed" "$g1" "$g10" "$best" "$champ_gen" "$(awk -v p="$on_road" 'BEGIN{print 100*p}')" "$wall" \
    "$(awk -v r="$rate" 'BEGIN{print r/1e6}')" "$n99" "$(pct "$n99")" "$s36" "$(pct "$s36")" "$re" "$(pct "$re")"
done
