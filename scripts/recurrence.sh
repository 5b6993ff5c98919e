#!/usr/bin/env bash
# Why re-sampled champions break: the lateral recurrent field (docs/results.md,
# "Why 9x9 re-sampling fails"). Two tables in Markdown:
#
# 1. The paper-experiment champions (runs/paper-seed-N; scripts/paper-experiment.sh
#    makes them, else they are evolved here) replayed at 3x3 with their lateral links
#    cut (--recurrence self) and with all recurrent links cut (--recurrence none), and
#    re-sampled to 5x5, 7x7, 9x9 and 15x15 neurons with the paper's full recurrence.
# 2. Runs evolved without lateral links (--recurrence self --normalize-self-loops false,
#    runs/lateral-free-seed-N): fitness, on road, and what re-sampling to 9x9 neurons
#    and to 3x6 sensors keeps.
#
#   scripts/recurrence.sh [SEED ...]      (default: seeds 1 2 3 4 5; about 30 s a seed)
source "$(dirname "$0")/common.sh"

printf '| seed | 3x3 | no lateral links | no recurrent links | 5x5 | 7x7 | 9x9 | 15x15 |\n'
printf '| --- | --- | --- | --- | --- | --- | --- | --- |\n'
for seed in "${seeds[@]}"; do
  dir=runs/paper-seed-$seed
  [ -f "$dir/champion.json" ] || $vivae evolve -q --seed "$seed" --out "$dir" --force > /dev/null
  r() { $vivae replay "$dir" -o "$dir/replay-recurrence" "$@" 2>/dev/null | field fitness; }
  own=$(r)
  row="| $seed | $(printf '%.3f' "$own")"
  for flags in "--recurrence self" "--recurrence none" "--neurons 5x5" "--neurons 7x7" "--neurons 9x9" "--neurons 15x15"; do
    # shellcheck disable=SC2086
    row="$row | $(pct "$(r $flags)" "$own")"
  done
  echo "$row |"
done

echo
printf '| seed | champion (gen) | on road | 9x9 neurons | 3x6 sensors | 3x6 after 20 gen retrain |\n'
printf '| --- | --- | --- | --- | --- | --- |\n'
for seed in "${seeds[@]}"; do
  dir=runs/lateral-free-seed-$seed
  line=$($vivae evolve -q --seed "$seed" --recurrence self --normalize-self-loops false --out "$dir" --force)
  best=$(echo "$line" | field best)
  gen=$(echo "$line" | field champion_generation)
  on_road=$(echo "$line" | field on_road)
  n99=$($vivae replay "$dir" --neurons 9x9 2>/dev/null | field fitness)
  s36=$($vivae replay "$dir" --sensors 3x6 2>/dev/null | field fitness)
  re=$($vivae retrain "$dir" --sensors 3x6 --generations 20 -q --out "$dir-retrain-3x6" --force | field best)
  printf '| %s | %.3f (%s) | %.1f%% | %s | %s | %s |\n' "$seed" "$best" "$gen" \
    "$(awk -v x="$on_road" 'BEGIN{print 100*x}')" "$(pct "$n99" "$best")" "$(pct "$s36" "$best")" "$(pct "$re" "$best")"
done
