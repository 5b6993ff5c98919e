#!/usr/bin/env bash
# Avoidance, learnt (issue 38, docs/results.md "Avoidance, learnt"): on the
# shipped scenarios `oncoming` and `obstacles-random`, per seed, the
# surface sheet only and surface + RAYS distance rays, each evolved with
#   speed  — the progress fitness (speed along the road's route),
#   cost   — progress minus COST per contact per 1,000 robot-steps,
#   nsga2  — NSGA-II over progress and -contacts; the member evaluated is the
#            one with fewest training contacts among the front's members
#            with ≥ 90% of its fittest member's training fitness;
# then every champion replayed on placements (obstacles and traffic) 1..HELD,
# never used in training (training draws each evaluation's placement from a
# hashed seed), and every distance-sheet champion also with its distance
# sheet re-sampled to 9 and 15 rays. Runs, replays and the tables go to OUT:
# OUT/replays.tsv (one line per replay) and OUT/summary.md (the tables).
#
#   scripts/avoidance.sh [SEED ...]     (default: seeds 1 2 3 4 5)
#   GENERATIONS=50 HELD=10 RAYS=5 COST=0.25 OUT=runs/avoidance SCENARIOS='oncoming obstacles-random' VIVAE=path/to/vivae
#   PLACEMENTS=1 (placements per evaluation in training: experiment.placements)
#   SETUPS='speed cost nsga2' (which of the three fitness setups to run)
#
# Finished runs (a champion.json) are not evolved again, so a stopped
# experiment continues where it stopped.
source "$(dirname "$0")/common.sh"
vivae=${VIVAE:-$vivae}
gens=${GENERATIONS:-50}
held=${HELD:-10}
rays=${RAYS:-5}
cost=${COST:-0.25}
out=${OUT:-runs/avoidance}
scenarios=${SCENARIOS:-oncoming obstacles-random}
placements=${PLACEMENTS:-1}
setups=${SETUPS:-speed cost nsga2}
mkdir -p "$out"
# One config per setup and sheet.
for setup in $setups; do
  for sheets in surface rays; do
    {
      printf '[fitness]\nkind = "progress"\n'
      [ "$setup" = cost ] && printf 'contact_cost = %s\n' "$cost"
      [ "$sheets" = rays ] && printf '[distance_sensors]\nrays = %s\n' "$rays"
      [ "$setup" = nsga2 ] && printf '[strategy]\nkind = "nsga2"\n'
      if [ "$placements" -gt 1 ]; then printf '[experiment]\nplacements = %s\n' "$placements"; fi
    } > "$out/$setup-$sheets.toml"
  done
done

# The front member of an nsga2 run that is evaluated (see above).
pick_member() {
  awk -F, 'NR > 1 { f[NR] = $2; c[NR] = $4; m[NR] = $1; if ($2 > best) best = $2 }
    END { for (i in f) if (f[i] >= 0.9 * best && (pick == "" || c[i] < c[pick] || (c[i] == c[pick] && f[i] > f[pick]))) pick = i;
          print m[pick] }' best=-1e300 "$1/front.csv"
}

# One replay as a TSV line: scenario setup sheets seed rays placement member fields...
replay_line() {
  local dir=$1 placement=$2 member=$3 r=$4 tag=$5
  local args=("$dir" --placement-seed "$placement" --out "$dir/held-out/$tag-p$placement")
  [ -n "$member" ] && args+=(--front "$member")
  [ "$r" = run ] || args+=(--distance-rays "$r")
  nice -n 10 "$vivae" replay "${args[@]}" 2>/dev/null
}

tsv=$out/replays.tsv
[ -f "$tsv" ] || printf 'scenario\tsetup\tsheets\tseed\trays\tplacement\tmember\tfitness\tspeed\ton_road\tcollisions\trobot\ttraffic\tobstacle\twall\n' > "$tsv"
for scenario in $scenarios; do
  for seed in "${seeds[@]}"; do
    for setup in $setups; do
      for sheets in surface rays; do
        dir=$out/$scenario-$setup-$sheets-seed-$seed
        if [ ! -f "$dir/champion.json" ]; then
          nice -n 10 "$vivae" evolve -q --config "$out/$setup-$sheets.toml" --scenario "$scenario" \
            --generations "$gens" --seed "$seed" --out "$dir" --force > "$dir.evolve.txt"
        fi
        member=; [ "$setup" = nsga2 ] && member=$(pick_member "$dir")
        rayset=(run); [ "$sheets" = rays ] && rayset=(run 9 15)
        for r in "${rayset[@]}"; do
          nr=$r; [ "$r" = run ] && { nr=$rays; [ "$sheets" = surface ] && nr=0; }
          # Already replayed (a continued experiment)?
          grep -q "^$scenario	$setup	$sheets	$seed	$nr	" "$tsv" && continue
          for p in $(seq 1 "$held"); do
            line=$(replay_line "$dir" "$p" "$member" "$r" "rays$nr")
            f() { echo "$line" | field "$1"; }
            printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' \
              "$scenario" "$setup" "$sheets" "$seed" "$nr" "$p" "${member:--}" \
              "$(f fitness)" "$(f speed)" "$(f on_road)" "$(f collisions)" \
              "$(f contacts_robot)" "$(f contacts_traffic)" "$(f contacts_obstacle)" "$(f contacts_wall)" >> "$tsv"
          done
        done
      done
    done
  done
done
python3 "$(dirname "$0")/avoidance-table.py" "$tsv" "$cost" "$rays" > "$out/summary.md.tmp"
mv "$out/summary.md.tmp" "$out/summary.md"
cat "$out/summary.md"
