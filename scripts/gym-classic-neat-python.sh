#!/usr/bin/env bash
# Developer script (not part of CI): neat-python 2.x on Gymnasium's five
# classic-control environments under vivae's protocol (docs/howto/
# classic-control.md, "The protocol"; scripts/gym-classic-neat-python.py):
# the same start draws, evaluation seeds, stopping rule, validation on 100
# fresh starts and thresholds as `vivae reproduce gym-classic`; one line per run.
#
#   scripts/gym-classic-neat-python.sh                      # seeds 1-3, every task
#   SEEDS="1 2 3 4 5" TASKS="cartpole acrobot" scripts/gym-classic-neat-python.sh
#   EVALUATIONS=15000 CPU_SECONDS=120 scripts/gym-classic-neat-python.sh
#
# Budget: a run stops at EVALUATIONS evaluations (vivae's default run: 100
# generations of 150) or CPU_SECONDS of its process's CPU time, whichever
# comes first. The config is neat-python's own single-pole-balancing
# config-feedforward (population 250, sigmoid, feed-forward; its examples ship
# no config for these environments), its inputs and outputs set per
# environment and its fitness threshold off (the script stops a run itself).
# neat-python, Gymnasium and NumPy are installed with pip into a venv under
# target/ (or VENV).
source "$(dirname "$0")/gym-classic-common.sh"
venv neat-python-gym-venv 'neat-python>=2,<3'
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
shape() {
    case "$1" in
        cartpole) echo "4 2" ;;
        acrobot) echo "6 3" ;;
        mountain-car) echo "2 3" ;;
        mountain-car-continuous) echo "2 1" ;;
        pendulum) echo "3 1" ;;
        *) echo "unknown task $1" >&2; exit 2 ;;
    esac
}
for task in $TASKS; do
    read -r inputs outputs <<<"$(shape "$task")"
    cat > "$WORK/config-$task" <<CFG
[NEAT]
fitness_criterion     = max
fitness_threshold     = 1e9
pop_size              = 250
reset_on_extinction   = 0
no_fitness_termination = False

[DefaultGenome]
num_inputs              = $inputs
num_hidden              = 1
num_outputs             = $outputs
initial_connection      = partial_direct 0.5
feed_forward            = True
compatibility_disjoint_coefficient    = 1.0
compatibility_weight_coefficient      = 0.6
conn_add_prob           = 0.2
conn_delete_prob        = 0.2
node_add_prob           = 0.2
node_delete_prob        = 0.2
activation_default      = sigmoid
activation_options      = sigmoid
activation_mutate_rate  = 0.0
aggregation_default     = sum
aggregation_options     = sum
aggregation_mutate_rate = 0.0
bias_init_mean          = 0.0
bias_init_stdev         = 1.0
bias_replace_rate       = 0.1
bias_mutate_rate        = 0.7
bias_mutate_power       = 0.5
bias_max_value          = 30.0
bias_min_value          = -30.0
response_init_mean      = 1.0
response_init_stdev     = 0.0
response_replace_rate   = 0.0
response_mutate_rate    = 0.0
response_mutate_power   = 0.0
response_max_value      = 30.0
response_min_value      = -30.0
weight_max_value        = 30
weight_min_value        = -30
weight_init_mean        = 0.0
weight_init_stdev       = 1.0
weight_mutate_rate      = 0.8
weight_replace_rate     = 0.1
weight_mutate_power     = 0.5
enabled_default         = True
enabled_mutate_rate     = 0.01

[DefaultSpeciesSet]
compatibility_threshold = 3.0

[DefaultStagnation]
species_fitness_func = max
max_stagnation  = 20

[DefaultReproduction]
elitism            = 2
survival_threshold = 0.2
CFG
    for seed in $SEEDS; do
        "$VENV/bin/python" scripts/gym-classic-neat-python.py \
            "$WORK/config-$task" "$task" "$seed" "$EVALUATIONS" "$CPU_SECONDS"
    done
done
