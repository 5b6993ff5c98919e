#!/usr/bin/env bash
# A second input substrate for obstacles and other robots (issue 11 §4,
# docs/results.md "Two-way traffic"): per seed, the paper's experiment on the
# shipped `traffic` scenario (6 robots, two-way, blocks and movable crates on
# the road), evolved without and with a sheet of RAYS distance sensors
# (runs/traffic-{surface,distance}-seed-N); each champion replayed for its
# fitness, time on road and collisions per 1,000 robot-steps. Prints a Markdown table.
#
#   scripts/traffic.sh [SEED ...]          (default: seeds 1 2 3 4 5)
#   RAYS=9 scripts/traffic.sh 1            (default 5 rays over 180 degrees)
source "$(dirname "$0")/common.sh"
rays=${RAYS:-5}
config=$(mktemp --suffix .toml)
trap 'rm -f "$config"' EXIT
printf '[distance_sensors]\nrays = %s\n' "$rays" > "$config"
printf '| seed | sheets | champion (gen) | fitness | on road | collisions / 1000 robot-steps | side |\n'
printf '| --- | --- | --- | --- | --- | --- | --- |\n'
for seed in "${seeds[@]}"; do
  for sheets in surface distance; do
    dir=runs/traffic-$sheets-seed-$seed
    flags=(--scenario traffic --robots 6 --seed "$seed" --out "$dir" --force)
    [ "$sheets" = surface ] || flags+=(--config "$config")
    line=$($vivae evolve -q "${flags[@]}")
    rep=$($vivae replay "$dir" 2>/dev/null)
    label=$sheets; [ "$sheets" = surface ] || label="surface + $rays distance rays"
    printf '| %s | %s | %.3f (%s) | %.3f | %.1f%% | %s | %s |\n' "$seed" "$label" \
      "$(echo "$line" | field best)" "$(echo "$line" | field champion_generation)" \
      "$(echo "$rep" | field fitness)" "$(awk -v x="$(echo "$rep" | field on_road)" 'BEGIN{print 100*x}')" \
      "$(echo "$rep" | field collisions)" "$(echo "$rep" | field side)"
  done
done
