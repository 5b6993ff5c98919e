#!/usr/bin/env bash
# Multi-resolution evolution (issue 11 §2, docs/results.md "Multi-resolution
# evolution"): per seed, evolve the paper's experiment with every genome
# evaluated at 3x3, 5x5 and 9x9 neurons (runs/multires-seed-N), then replay the
# champion at its own 3x3, re-sampled to 9x9 neurons, to 3x6 sensors and to a
# 32x96 camera-sized sensor sheet, and compare its own 3x3 fitness with the
# single-resolution champion of the same seed (runs/paper-seed-N, evolved here if
# missing). Prints a Markdown table.
#
#   scripts/multi-resolution.sh [SEED ...]            (default: seeds 1 2 3 4 5)
#   TRAIN="3x3,9x9" scripts/multi-resolution.sh 1     (other training sheets)
source "$(dirname "$0")/common.sh"
train=${TRAIN:-3x3,5x5,9x9}
tag=${train//,/-}
printf '| seed | training fitness | own 3x3 (vs single-res) | on road | 9x9 neurons | 3x6 sensors | 32x96 sensors (on road) | 32x96 sensors, 9x9 neurons (on road) | wall s |\n'
printf '| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n'
for seed in "${seeds[@]}"; do
  single=runs/paper-seed-$seed
  [ -f "$single/champion.json" ] || $vivae evolve -q --seed "$seed" --out "$single" --force > /dev/null
  base=$($vivae replay "$single" -o "$single/replay" 2>/dev/null | field fitness)
  dir=runs/multires-$tag-seed-$seed
  line=$($vivae evolve -q --seed "$seed" --train-neurons "$train" --out "$dir" --force)
  best=$(echo "$line" | field best)
  wall=$(echo "$line" | field wall_s)
  r() { $vivae replay "$dir" "$@" 2>/dev/null; }
  own=$(r); own_f=$(echo "$own" | field fitness)
  n99=$(r --neurons 9x9 | field fitness)
  s36=$(r --sensors 3x6 | field fitness)
  cam=$(r --sensors 32x96)
  cam9=$(r --sensors 32x96 --neurons 9x9)
  printf '| %s | %.3f | %s | %s | %s | %s | %s (%s) | %s (%s) | %.0f |\n' "$seed" "$best" \
    "$(pct "$own_f" "$base")" "$(road "$(echo "$own" | field on_road)")" \
    "$(pct "$n99" "$own_f")" "$(pct "$s36" "$own_f")" \
    "$(pct "$(echo "$cam" | field fitness)" "$own_f")" "$(road "$(echo "$cam" | field on_road)")" \
    "$(pct "$(echo "$cam9" | field fitness)" "$own_f")" "$(road "$(echo "$cam9" | field on_road)")" "$wall"
done
