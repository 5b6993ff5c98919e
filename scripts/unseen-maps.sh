#!/usr/bin/env bash
# Controllers that drive on maps they never saw (issue 11 §5): per seed,
# evolves on several training maps at once into runs/maps-seed-N, then replays
# the champion on every map (trained and unseen) with all of each map's robots.
# Prints a Markdown table: seed, training fitness (the mean over the training
# maps), and per map the replay's fitness and share of robot-steps on road
# (maps the run trained on are marked *).
#
#   scripts/unseen-maps.sh [SEED ...]            # default seeds 1-5
#
# Environment overrides (defaults: the paper's settings):
#   MAPS="roads oval figure8"                   training maps
#   TEST_MAPS="town obstacles traffic"          unseen maps to replay on
#   GENERATIONS=400                             generations per run
#   RUNS=runs                                   where runs/maps-seed-N go
#   EXTRA="--population 50"                     more flags for vivae evolve
# A run directory that already holds a finished run of that many generations
# is reused, not evolved again.
source "$(dirname "$0")/common.sh"
read -r -a maps <<< "${MAPS:-roads oval figure8}"
read -r -a test_maps <<< "${TEST_MAPS:-town obstacles traffic}"
generations=${GENERATIONS:-400}
runs=${RUNS:-runs}
read -r -a extra <<< "${EXTRA:-}"

scenario_flags=()
for m in "${maps[@]}"; do scenario_flags+=(--scenario "$m"); done
all_maps=("${maps[@]}" "${test_maps[@]}")

header='| seed | training fitness |'
rule='| --- | --- |'
for m in "${all_maps[@]}"; do
  mark=""
  for t in "${maps[@]}"; do [ "$t" = "$m" ] && mark="*"; done
  header+=" $m$mark fitness | $m$mark on road |"
  rule+=' --- | --- |'
done
echo "$header"
echo "$rule"
for seed in "${seeds[@]}"; do
  dir=$runs/maps-seed-$seed
  done_gens=0
  [ -f "$dir/generations.csv" ] && done_gens=$(($(wc -l < "$dir/generations.csv") - 1))
  if [ ! -f "$dir/champion.json" ] || [ "$done_gens" -ne "$generations" ]; then
    $vivae evolve -q --seed "$seed" --generations "$generations" "${scenario_flags[@]}" \
      ${extra[@]+"${extra[@]}"} --out "$dir" --force > /dev/null
  fi
  training=$(sed -n 's/.*"fitness": \([^,]*\),*/\1/p' "$dir/champion.json" | head -1)
  row=$(printf '| %s | %.3f |' "$seed" "$training")
  for m in "${all_maps[@]}"; do
    line=$($vivae replay "$dir" --scenario "$m" -o "$dir/replay-maps" 2>/dev/null)
    fitness=$(echo "$line" | field fitness)
    on_road=$(echo "$line" | field on_road)
    row+=$(printf ' %.3f | %.1f%% |' "$fitness" "$(awk -v r="$on_road" 'BEGIN{print 100*r}')")
  done
  echo "$row"
done
echo
echo "(* = a training map; replays drive all of each map's robots for the run's steps)"
