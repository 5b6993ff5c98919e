#!/usr/bin/env bash
# Developer script (not part of CI): neat-python 2.x on LunarLander-v3 beside
# vivae's runs of scripts/gym-suite.sh, on the same protocol and budget
# (scripts/gym-lander-neat-python.py): EPISODES episodes per evaluation drawn
# from the evaluation's seed, GENERATIONS generations of neat-python's
# shipped population of 150, the champion validated on seeds 0-99.
#
#   scripts/gym-lander-neat-python.sh                    # seeds 1-3, 200 generations, 3 episodes
#   SEEDS="1 2" GENERATIONS=50 OUT=runs/lander-np scripts/gym-lander-neat-python.sh
#
# Resumable like gym-suite.sh: run it again after a stop and each run goes on
# from neat-python's checkpoint of its last generation; finished runs are
# skipped. The config is neat-python's shipped examples/lunar-lander/
# config-feedforward (population 150, clamped activations, feed-forward,
# argmax of 4 outputs), with its fitness threshold off (the run plays its
# generations) and the keys neat-python 2.0 does not read left out.
# neat-python, Gymnasium with Box2D and NumPy come from VENV (created under
# target/ and installed with pip when absent).
set -euo pipefail
cd "$(dirname "$0")/.."
SEEDS="${SEEDS:-1 2 3}"
GENERATIONS="${GENERATIONS:-200}"
EPISODES="${EPISODES:-3}"
OUT="${OUT:-runs/gym-suite-neat-python}"
TARGET="${CARGO_TARGET_DIR:-target}"
mkdir -p "$TARGET" "$OUT"
VENV="${VENV:-$(cd "$TARGET" && pwd)/neat-python-gym-venv}"
if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
"$VENV/bin/python" -c 'import neat, gymnasium, Box2D, pygame, numpy' 2>/dev/null ||
    "$VENV/bin/pip" install --quiet --disable-pip-version-check 'neat-python>=2,<3' 'gymnasium[box2d]>=1,<2' numpy
cat > "$OUT/config-feedforward" <<'CFG'
[NEAT]
fitness_criterion     = max
fitness_threshold     = 1e9
pop_size              = 150
reset_on_extinction   = 0
no_fitness_termination = True

[DefaultGenome]
num_inputs              = 8
num_hidden              = 0
num_outputs             = 4
initial_connection      = partial_direct 0.5
feed_forward            = True
compatibility_disjoint_coefficient = 1.0
compatibility_weight_coefficient   = 1.0
conn_add_prob           = 0.15
conn_delete_prob        = 0.1
node_add_prob           = 0.15
node_delete_prob        = 0.1
activation_default      = clamped
activation_options      = clamped
activation_mutate_rate  = 0.0
aggregation_default     = sum
aggregation_options     = sum
aggregation_mutate_rate = 0.0
bias_init_mean          = 0.0
bias_init_stdev         = 1.0
bias_replace_rate       = 0.02
bias_mutate_rate        = 0.8
bias_mutate_power       = 0.4
bias_max_value          = 30.0
bias_min_value          = -30.0
response_init_mean      = 1.0
response_init_stdev     = 0.0
response_replace_rate   = 0.0
response_mutate_rate    = 0.1
response_mutate_power   = 0.01
response_max_value      = 30.0
response_min_value      = -30.0
weight_max_value        = 30
weight_min_value        = -30
weight_init_mean        = 0.0
weight_init_stdev       = 1.0
weight_mutate_rate      = 0.8
weight_replace_rate     = 0.02
weight_mutate_power     = 0.4
enabled_default         = True
enabled_mutate_rate     = 0.01

[DefaultSpeciesSet]
compatibility_threshold = 3.0

[DefaultStagnation]
species_fitness_func = mean
max_stagnation       = 15
species_elitism      = 4

[DefaultReproduction]
elitism            = 2
survival_threshold = 0.2
CFG
for seed in $SEEDS; do
    "$VENV/bin/python" scripts/gym-lander-neat-python.py \
        "$OUT/config-feedforward" "$OUT/LunarLander-v3-seed-$seed" "$seed" "$GENERATIONS" "$EPISODES"
done
