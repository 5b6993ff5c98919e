#!/usr/bin/env bash
# Looking inside the avoidance experiment (docs/results.md "The paper's
# budget on courses where no line is safe"): every finished champion of
# scripts/avoidance.sh's OUT replayed with `vivae replay --meetings` on the
# held-out placements 1..HELD — a distance-sheet champion seeing, with its
# rays blinded and with its sheet re-sampled to 9 and 15 rays; a surface-only
# one seeing (its meetings record what the default 5 rays would have shown).
# Each replay's meetings-pN.csv goes to MEET/RUN/VIEW-pN/; then
# scripts/avoidance-meetings.py tables them all into MEET/meetings.md. The
# runs are only read: nothing is written into OUT.
#
#   scripts/avoidance-meetings.sh [SEED ...]     (default: seeds 1 2 3 4 5)
#   OUT=runs/avoidance MEET=OUT-meetings HELD=10 SCENARIOS='oncoming obstacles-random' SETUPS='speed cost nsga2' VIVAE=path/to/vivae
#
# A replay whose CSV is there is not run again, so the tables can be
# refreshed as more runs finish.
source "$(dirname "$0")/common.sh"
vivae=${VIVAE:-$vivae}
out=${OUT:-runs/avoidance}
meet=${MEET:-$out-meetings}
held=${HELD:-10}
scenarios=${SCENARIOS:-oncoming obstacles-random}
setups=${SETUPS:-speed cost nsga2}
mkdir -p "$meet"

# The front member of an nsga2 run that is evaluated (as scripts/avoidance.sh picks it).
pick_member() {
  awk -F, 'NR > 1 { f[NR] = $2; c[NR] = $4; m[NR] = $1; if ($2 > best) best = $2 }
    END { for (i in f) if (f[i] >= 0.9 * best && (pick == "" || c[i] < c[pick] || (c[i] == c[pick] && f[i] > f[pick]))) pick = i;
          print m[pick] }' best=-1e300 "$1/front.csv"
}

# A run is finished when its generations.csv holds every generation its config asks for.
finished() {
  local want have
  want=$(sed -n 's/^generations = //p' "$1/config.toml" 2>/dev/null | head -n 1)
  have=0; [ -f "$1/generations.csv" ] && have=$(($(wc -l < "$1/generations.csv") - 1))
  [ -n "$want" ] && [ "$have" -ge "$want" ]
}

for scenario in $scenarios; do
  for seed in "${seeds[@]}"; do
    for setup in $setups; do
      for sheets in surface rays; do
        run=$scenario-$setup-$sheets-seed-$seed
        dir=$out/$run
        finished "$dir" || continue
        member=; [ "$setup" = nsga2 ] && member=$(pick_member "$dir")
        views=(run:seeing); [ "$sheets" = rays ] && views=(run:seeing run:blind 9:seeing 15:seeing)
        for v in "${views[@]}"; do
          r=${v%%:*} view=${v#*:}
          for p in $(seq 1 "$held"); do
            to=$meet/$run/rays$r-$view-p$p
            csv=$to/meetings-p$p.csv; [ "$view" = blind ] && csv=$to/meetings-p$p-blind-rays.csv
            [ -f "$csv" ] && continue
            args=("$dir" --placement-seed "$p" --meetings --out "$to")
            [ -n "$member" ] && args+=(--front "$member")
            [ "$r" = run ] || args+=(--distance-rays "$r")
            [ "$view" = blind ] && args+=(--blind-rays)
            nice -n 10 "$vivae" replay "${args[@]}" > /dev/null 2>&1
          done
        done
      done
    done
  done
done
python3 "$(dirname "$0")/avoidance-meetings.py" "$meet" > "$meet/meetings.md.tmp"
mv "$meet/meetings.md.tmp" "$meet/meetings.md"
cat "$meet/meetings.md"
