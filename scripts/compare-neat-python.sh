#!/usr/bin/env bash
# Developer script (not part of CI): runs XOR with neat-python and with vivae-neat,
# same population (150), same fitness ((4 − Σ|error|)²) and the same stopping rule
# (all four outputs on the right side of 0.5), and prints per library the solved runs,
# mean evaluations, mean wall time per run and the wall-time ratio.
#
#   scripts/compare-neat-python.sh            # 100 runs each
#   RUNS=20 scripts/compare-neat-python.sh
#
# neat-python is installed with pip into a throw-away venv under target/.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${RUNS:-100}"
TARGET="${CARGO_TARGET_DIR:-target}"
VENV="$TARGET/neat-python-venv"

if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
"$VENV/bin/pip" install --quiet --disable-pip-version-check neat-python
NEAT_VERSION="$("$VENV/bin/python" -c 'import importlib.metadata as m; print(m.version("neat-python"))')"

cargo build --quiet --release -p vivae-neat --example xor
OURS="$("$TARGET/release/examples/xor" --runs "$RUNS" --seed 1)"

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
# neat-python's own XOR example configuration (examples/xor/config-feedforward),
# with the stopping rule moved into the evaluation function below.
cat > "$WORK/config" <<'CFG'
[NEAT]
fitness_criterion     = max
fitness_threshold     = 1000
pop_size              = 150
reset_on_extinction   = False
no_fitness_termination = False

[DefaultGenome]
activation_default      = sigmoid
activation_mutate_rate  = 0.0
activation_options      = sigmoid
aggregation_default     = sum
aggregation_mutate_rate = 0.0
aggregation_options     = sum
bias_init_mean          = 0.0
bias_init_stdev         = 1.0
bias_max_value          = 30.0
bias_min_value          = -30.0
bias_mutate_power       = 0.5
bias_mutate_rate        = 0.7
bias_replace_rate       = 0.1
compatibility_disjoint_coefficient = 1.0
compatibility_weight_coefficient   = 0.5
conn_add_prob           = 0.5
conn_delete_prob        = 0.5
enabled_default         = True
enabled_mutate_rate     = 0.01
feed_forward            = True
initial_connection      = full
node_add_prob           = 0.2
node_delete_prob        = 0.2
num_hidden              = 0
num_inputs              = 2
num_outputs             = 1
response_init_mean      = 1.0
response_init_stdev     = 0.0
response_max_value      = 30.0
response_min_value      = -30.0
response_mutate_power   = 0.0
response_mutate_rate    = 0.0
response_replace_rate   = 0.0
weight_init_mean        = 0.0
weight_init_stdev       = 1.0
weight_max_value        = 30
weight_min_value        = -30
weight_mutate_power     = 0.5
weight_mutate_rate      = 0.8
weight_replace_rate     = 0.1

[DefaultSpeciesSet]
compatibility_threshold = 3.0

[DefaultStagnation]
species_fitness_func = max
max_stagnation       = 20
species_elitism      = 2

[DefaultReproduction]
elitism            = 2
survival_threshold = 0.2
CFG

cat > "$WORK/xor.py" <<'PY'
import random, sys, time
import neat

CASES = [((0.0, 0.0), 0.0), ((0.0, 1.0), 1.0), ((1.0, 0.0), 1.0), ((1.0, 1.0), 0.0)]

class Solved(Exception):
    pass

def main(config_path, runs, max_generations=500):
    config = neat.Config(neat.DefaultGenome, neat.DefaultReproduction,
                         neat.DefaultSpeciesSet, neat.DefaultStagnation, config_path)
    evals, total_s = [], 0.0
    for r in range(runs):
        random.seed(1 + r)
        count = [0]
        def eval_genomes(genomes, config):
            for _, g in genomes:
                net = neat.nn.FeedForwardNetwork.create(g, config)
                err, ok = 0.0, True
                for x, t in CASES:
                    o = net.activate(x)[0]
                    err += abs(o - t)
                    ok &= (o > 0.5) == (t > 0.5)
                g.fitness = (4.0 - err) ** 2
                count[0] += 1
                if ok:
                    raise Solved()
        p = neat.Population(config)
        t0 = time.perf_counter()
        try:
            p.run(eval_genomes, max_generations)
        except Solved:
            evals.append(count[0])
        total_s += time.perf_counter() - t0
    n = len(evals)
    mean = sum(evals) / max(n, 1)
    print(f"neat-python: solved={n}/{runs} mean_evals={mean:.0f} mean_ms={1000 * total_s / runs:.1f}")

main(sys.argv[1], int(sys.argv[2]))
PY
THEIRS="$("$VENV/bin/python" "$WORK/xor.py" "$WORK/config" "$RUNS")"

field() { sed -n "s/.*$2=\([0-9.\/]*\).*/\1/p" <<<"$1"; }
echo "XOR, population 150, $RUNS runs each, stopping when all four outputs are on the right side of 0.5"
printf '%-22s %-10s %-11s %-14s\n' library solved mean_evals mean_ms/run
printf '%-22s %-10s %-11s %-14s\n' "vivae-neat" "$(field "$OURS" solved)" "$(field "$OURS" mean_evals)" "$(field "$OURS" mean_ms)"
printf '%-22s %-10s %-11s %-14s\n' "neat-python $NEAT_VERSION" "$(field "$THEIRS" solved)" "$(field "$THEIRS" mean_evals)" "$(field "$THEIRS" mean_ms)"
awk -v a="$(field "$THEIRS" mean_ms)" -v b="$(field "$OURS" mean_ms)" \
    'BEGIN { printf "wall-time ratio neat-python / vivae-neat: %.1f\n", a / b }'
