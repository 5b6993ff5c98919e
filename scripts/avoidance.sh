#!/usr/bin/env bash
# Avoidance, learnt (docs/results.md "Avoidance, learnt"): on shipped
# scenarios (default `oncoming` and `obstacles-random`; the courses where no
# line is safe: SCENARIOS='corridor kerbed-loop'), per seed, the surface
# sheet only and surface + RAYS distance rays, each evolved with
#   speed  — the progress fitness (speed along the road's route),
#   cost   — progress minus COST per contact per 1,000 robot-steps,
#   nsga2  — NSGA-II over progress and -contacts; the member evaluated is the
#            one with fewest training contacts among the front's members
#            with ≥ 90% of its fittest member's training fitness;
# then every finished run's champion replayed on placements (obstacles and
# traffic) 1..HELD, never used in training (training draws each
# evaluation's placement from a 64-bit hash of run seed, generation and
# individual, and its further placements from a hash of that), and every
# distance-sheet champion also with its rays blinded (`replay
# --blind-rays`: every ray reads "nothing in range") and with its distance
# sheet re-sampled to 9 and 15 rays. Runs, replays and the tables go to OUT:
# OUT/replays.tsv (one line per replay), OUT/status.tsv (which runs are
# finished) and OUT/summary.md (the tables).
#
#   scripts/avoidance.sh [SEED ...]     (default: seeds 1 2 3 4 5)
#   GENERATIONS=50 HELD=10 RAYS=5 COST=0.25 OUT=runs/avoidance SCENARIOS='oncoming obstacles-random' VIVAE=path/to/vivae
#   PLACEMENTS=1 (placements per evaluation in training: experiment.placements)
#   SETUPS='speed cost nsga2' (which of the three fitness setups to run)
#   EVOLVE=0 (evolve nothing: table the runs of OUT that are finished)
#
# A run directory that is there is never evolved again: a finished run
# (generations.csv as long as its config asks) is replayed, once; an
# unfinished one (still evolving in another process, or stopped: `vivae
# resume` it) is left alone and listed as running. So a stopped experiment
# continues where it stopped, and the tables can be made while runs go on.
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
# One config per setup and sheet; one already there (a continued
# experiment) must be what these settings write.
for setup in $setups; do
  for sheets in surface rays; do
    {
      printf '[fitness]\nkind = "progress"\n'
      [ "$setup" = cost ] && printf 'contact_cost = %s\n' "$cost"
      [ "$sheets" = rays ] && printf '[distance_sensors]\nrays = %s\n' "$rays"
      [ "$setup" = nsga2 ] && printf '[strategy]\nkind = "nsga2"\n'
      if [ "$placements" -gt 1 ]; then printf '[experiment]\nplacements = %s\n' "$placements"; fi
    } > "$out/.$setup-$sheets.toml.new"
    if [ ! -f "$out/$setup-$sheets.toml" ]; then
      mv "$out/.$setup-$sheets.toml.new" "$out/$setup-$sheets.toml"
    elif cmp -s "$out/.$setup-$sheets.toml.new" "$out/$setup-$sheets.toml"; then
      rm "$out/.$setup-$sheets.toml.new"
    else
      rm "$out/.$setup-$sheets.toml.new"
      echo "$out/$setup-$sheets.toml: not the config these settings (COST, RAYS, PLACEMENTS) write; use another OUT" >&2
      exit 2
    fi
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
  local dir=$1 placement=$2 member=$3 r=$4 tag=$5 view=$6
  local args=("$dir" --placement-seed "$placement" --out "$dir/held-out/$tag-p$placement")
  [ -n "$member" ] && args+=(--front "$member")
  [ "$r" = run ] || args+=(--distance-rays "$r")
  [ "$view" = blind ] && args+=(--blind-rays)
  nice -n 10 "$vivae" replay "${args[@]}" 2>/dev/null
}

# Generations a run has done (0 before its first).
gens_done() {
  if [ -f "$1/generations.csv" ]; then echo $(($(wc -l < "$1/generations.csv") - 1)); else echo 0; fi
}

# A run is finished when its generations.csv holds every generation its
# config asks for (a champion.json alone is written as it goes).
finished() {
  local want have
  want=$(sed -n 's/^generations = //p' "$1/config.toml" 2>/dev/null | head -n 1)
  have=$(gens_done "$1")
  [ -n "$want" ] && [ "$have" -ge "$want" ]
}

tsv=$out/replays.tsv
status=$out/status.tsv
columns='scenario\tsetup\tsheets\tseed\trays\tview\tplacement\tmember\tfitness\tspeed\ton_road\tcollisions\trobot\ttraffic\tobstacle\twall\tplaced'
[ -f "$tsv" ] || printf "$columns\n" > "$tsv"
if [ "$(head -n 1 "$tsv")" != "$(printf "$columns")" ]; then
  echo "$tsv: written by an older avoidance.sh (other columns); move it away to replay again" >&2
  exit 2
fi
printf 'run\tstate\tgenerations\n' > "$status.tmp"
for scenario in $scenarios; do
  for seed in "${seeds[@]}"; do
    for setup in $setups; do
      for sheets in surface rays; do
        run=$scenario-$setup-$sheets-seed-$seed
        dir=$out/$run
        if [ ! -e "$dir" ] && [ "${EVOLVE:-1}" != 0 ]; then
          nice -n 10 "$vivae" evolve -q --config "$out/$setup-$sheets.toml" --scenario "$scenario" \
            --generations "$gens" --seed "$seed" --out "$dir" > "$dir.evolve.txt"
        fi
        done_gens=$(gens_done "$dir")
        if ! finished "$dir"; then
          # Still evolving (another process's), stopped, or not started: not judged yet.
          state=running; [ -e "$dir" ] || state=missing
          printf '%s\t%s\t%s\n' "$run" "$state" "$done_gens" >> "$status.tmp"
          continue
        fi
        printf '%s\tfinished\t%s\n' "$run" "$done_gens" >> "$status.tmp"
        member=; [ "$setup" = nsga2 ] && member=$(pick_member "$dir")
        # What is replayed: the run's sheets seeing; a distance-sheet
        # champion also with its rays blinded and re-sampled to 9 and 15.
        views=(run:seeing); [ "$sheets" = rays ] && views=(run:seeing run:blind 9:seeing 15:seeing)
        for v in "${views[@]}"; do
          r=${v%%:*} view=${v#*:}
          nr=$r; [ "$r" = run ] && { nr=$rays; [ "$sheets" = surface ] && nr=0; }
          # Already replayed (a continued experiment)?
          grep -q "^$scenario	$setup	$sheets	$seed	$nr	$view	" "$tsv" && continue
          for p in $(seq 1 "$held"); do
            line=$(replay_line "$dir" "$p" "$member" "$r" "rays$nr-$view" "$view")
            f() { echo "$line" | field "$1"; }
            printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' \
              "$scenario" "$setup" "$sheets" "$seed" "$nr" "$view" "$p" "${member:--}" \
              "$(f fitness)" "$(f speed)" "$(f on_road)" "$(f collisions)" \
              "$(f contacts_robot)" "$(f contacts_traffic)" "$(f contacts_obstacle)" "$(f contacts_wall)" \
              "$(f contacts_placed)" >> "$tsv"
          done
        done
      done
    done
  done
done
mv "$status.tmp" "$status"
python3 "$(dirname "$0")/avoidance-table.py" "$tsv" "$cost" "$rays" "$status" > "$out/summary.md.tmp"
mv "$out/summary.md.tmp" "$out/summary.md"
cat "$out/summary.md"
