#!/usr/bin/env bash
# The champions of the paper's experiment (seeds 1-5 by default) re-sampled to
# 9x9 neurons and to 3x6 sensors under each weight-normalisation rule
# (docs/explanation/normalisation.md, "How a re-sampled sheet keeps its drive"): what each rule
# keeps of the champion's fitness at its own resolution under the same rule.
#
#   scripts/normalization-rules.sh [SEED ...]
#
# Uses runs/paper-seed-N when it exists (scripts/paper-experiment.sh makes
# them), else evolves it (about 20-40 s a seed). Prints a Markdown table.
source "$(dirname "$0")/common.sh"
rules=("count:true" "count:false" "area:true" "area:false")
printf '| seed | rule | 3x3 (own) | 9x9 neurons | kept | 3x6 sensors | kept |\n'
printf '| --- | --- | --- | --- | --- | --- | --- |\n'
for seed in "${seeds[@]}"; do
  dir=runs/paper-seed-$seed
  [ -f "$dir/champion.json" ] || $vivae evolve -q --seed "$seed" --out "$dir" --force > /dev/null
  for rule in "${rules[@]}"; do
    by=${rule%%:*}
    loops=${rule##*:}
    flags=(--normalize-by "$by" --normalize-self-loops "$loops" -o "$dir/replay-rules")
    own=$($vivae replay "$dir" "${flags[@]}" 2>/dev/null | field fitness)
    n99=$($vivae replay "$dir" --neurons 9x9 "${flags[@]}" 2>/dev/null | field fitness)
    s36=$($vivae replay "$dir" --sensors 3x6 "${flags[@]}" 2>/dev/null | field fitness)
    name=$by
    [ "$loops" = true ] || name="$by, self-loops kept"
    pct() { awk -v a="$1" -v b="$own" 'BEGIN{printf "%.1f%%", 100*a/b}'; }
    printf '| %s | %s | %.3f | %.3f | %s | %.3f | %s |\n' "$seed" "$name" "$own" "$n99" "$(pct "$n99")" "$s36" "$(pct "$s36")"
  done
done
