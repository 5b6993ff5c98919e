#!/usr/bin/env bash
# The avoidance experiment (docs/results.md, "Avoidance, learnt"): on SCENARIO
# (default oncoming), per seed, the surface sheet only and surface + 5
# distance rays, each with speed fitness, speed + a contact cost, and NSGA-II
# (speed against contacts); every champion replayed on placements 1-5 (never
# used in training: training draws placements from hashed evaluation seeds).
# Prints one line per replay: scenario setup sheets seed placement fitness collisions contacts_*.
# Usage: [SETUPS='speed cost nsga2'] scripts/avoidance.sh SCENARIO GENERATIONS SEED... (runs go to runs/avoid-*)
set -euo pipefail
vivae=${VIVAE:-vivae}
scenario=$1; gens=$2; shift 2
mkdir -p runs
printf '[distance_sensors]\nrays = 5\n' > runs/rays.toml
printf '[fitness]\ncontact_cost = 0.25\n' > runs/cost.toml
printf '[distance_sensors]\nrays = 5\n[fitness]\ncontact_cost = 0.25\n' > runs/rays-cost.toml
for seed in "$@"; do
  for setup in ${SETUPS:-speed cost nsga2}; do
    for sheets in surface rays; do
      out=runs/avoid-$scenario-$setup-$sheets-$seed
      args=(--scenario "$scenario" --generations "$gens" --seed "$seed" --out "$out")
      case $setup-$sheets in
        speed-rays) args+=(--config runs/rays.toml) ;;
        cost-surface) args+=(--config runs/cost.toml) ;;
        cost-rays) args+=(--config runs/rays-cost.toml) ;;
        nsga2-surface) args+=(--strategy nsga2) ;;
        nsga2-rays) args+=(--strategy nsga2 --config runs/rays.toml) ;;
      esac
      [ -f "$out/champion.json" ] || nice -n 10 "$vivae" evolve -q "${args[@]}" >/dev/null
      for p in 1 2 3 4 5; do
        line=$(nice -n 10 "$vivae" replay "$out" --placement-seed "$p" --out "$out/held-out-$p" 2>/dev/null)
        field() { echo "$line" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
        echo "$scenario $setup $sheets $seed $p $(field fitness) $(field collisions) $(field contacts_robot) $(field contacts_traffic) $(field contacts_obstacle) $(field contacts_wall)"
      done
    done
  done
done
