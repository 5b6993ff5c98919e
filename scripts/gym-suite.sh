#!/usr/bin/env bash
# Developer script (not part of CI): the Gymnasium suite of
# docs/howto/gymnasium-python.md ("The Gymnasium suite"): every run
# `vivae.gym.evolve(ENV, out=OUT/ENV-seed-N, generations=G, population=P,
# seed=N, episodes=E)`, its champion validated on 100 fresh episodes, then
# the table (scripts/gym_suite_table.py) written to OUT/table.md.
#
#   scripts/gym-suite.sh                               # the whole suite, in order
#   ENVS="ip idp" scripts/gym-suite.sh                 # some environments only
#   OUT=runs/suite LANDER_SEEDS="1 2 3" scripts/gym-suite.sh
#   nohup nice -n 19 scripts/gym-suite.sh > suite.log 2>&1 &
#
# Resumable: run it again after it was stopped or killed and it goes on
# where it was. A finished run is skipped, an interrupted one is continued
# from its last checkpoint by `vivae.gym.resume` (the same files as an
# uninterrupted run), one killed during its validation is validated again.
# One run at a time, in one process (`processes=1`), so each run's CPU
# seconds (OUT/cpu/) are its own cost.
#
# Order and budgets (ENVS; per environment KEY_SEEDS, KEY_GENERATIONS,
# KEY_POPULATION, KEY_EPISODES, KEY being the upper-case short name, and
# KEY_CONFIG, a config TOML file new runs start from instead of the
# environment's own (below): `task = "gymnasium"` under [experiment] and the
# keys it changes, e.g. `target_species = 10` under [neat]; use another OUT
# for runs of another config):
#   ip       InvertedPendulum-v5        seeds 1-5   20 generations of 150, 3 episodes
#   idp      InvertedDoublePendulum-v5  seeds 1-5  100 generations of 150, 3 episodes,
#                                       config scripts/gym-suite-idp.toml (small weights)
#   lander   LunarLander-v3             seeds 1-10 200 generations of 150, 3 episodes,
#                                       config scripts/gym-suite-lander.toml (10 species)
#   swimmer  Swimmer-v5                 seeds 1-5   50 generations of 150, 3 episodes
#   cheetah  HalfCheetah-v5             seeds 1-5   50 generations of 150, 3 episodes
#   hopper   Hopper-v5                  seeds 1-5   50 generations of 150, 3 episodes
#   walker   BipedalWalker-v3           seeds 1-5   50 generations of 150, 3 episodes
# The docs give each budget's measured CPU cost and why it was chosen.
#
# PYTHON is a Python with vivae and gymnasium[box2d,mujoco] installed
# (default: python3). MuJoCo renders the champion's film through EGL
# (MUJOCO_GL=egl unless set); without it the validation still stands.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
OUT="${OUT:-runs/gym-suite}"
PYTHON="${PYTHON:-python3}"
ENVS="${ENVS:-ip idp lander swimmer cheetah hopper walker}"
export MUJOCO_GL="${MUJOCO_GL:-egl}"
mkdir -p "$OUT"

env_id() {
    case "$1" in
        ip) echo InvertedPendulum-v5 ;;
        idp) echo InvertedDoublePendulum-v5 ;;
        lander) echo LunarLander-v3 ;;
        swimmer) echo Swimmer-v5 ;;
        cheetah) echo HalfCheetah-v5 ;;
        hopper) echo Hopper-v5 ;;
        walker) echo BipedalWalker-v3 ;;
        *) echo "gym-suite.sh: unknown environment '$1' in ENVS (ip idp lander swimmer cheetah hopper walker)" >&2; exit 2 ;;
    esac
}
# Default budgets: seeds, generations, population, episodes.
defaults() {
    case "$1" in
        ip) echo "1 2 3 4 5|20|150|3" ;;
        idp) echo "1 2 3 4 5|100|150|3" ;;
        lander) echo "1 2 3 4 5 6 7 8 9 10|200|150|3" ;;
        *) echo "1 2 3 4 5|50|150|3" ;;
    esac
}
# Default config files: InvertedDoublePendulum's small weights
# (scripts/gym-suite-idp.toml), LunarLander's speciation
# (scripts/gym-suite-lander.toml).
default_config() {
    case "$1" in
        idp) echo "$HERE/gym-suite-idp.toml" ;;
        lander) echo "$HERE/gym-suite-lander.toml" ;;
        *) echo "" ;;
    esac
}
setting() { # KEY NAME DEFAULT: $KEY_NAME if set, else DEFAULT
    local var
    var="$(echo "$1" | tr '[:lower:]' '[:upper:]')_$2"
    echo "${!var:-$3}"
}

for key in $ENVS; do
    env="$(env_id "$key")"
    IFS='|' read -r seeds generations population episodes <<<"$(defaults "$key")"
    seeds="$(setting "$key" SEEDS "$seeds")"
    generations="$(setting "$key" GENERATIONS "$generations")"
    population="$(setting "$key" POPULATION "$population")"
    episodes="$(setting "$key" EPISODES "$episodes")"
    config="$(setting "$key" CONFIG "$(default_config "$key")")"
    for seed in $seeds; do
        echo "== $env seed $seed: $generations generations of $population, $episodes episodes"
        "$PYTHON" "$HERE/gym_suite_run.py" "$env" "$seed" "$OUT" "$generations" "$population" "$episodes" "$config"
        "$PYTHON" "$HERE/gym_suite_table.py" "$OUT" > "$OUT/.table.md.tmp" && mv "$OUT/.table.md.tmp" "$OUT/table.md"
    done
done
cat "$OUT/table.md"
