#!/usr/bin/env bash
# Developer script (not part of CI): MultiNEAT (the `multineat` package) on
# Gymnasium's five classic-control environments under the protocol
# scripts/gym-classic-neat-python.sh runs neat-python on (docs/howto/
# classic-control.md, "The protocol"; scripts/gym-classic-multineat.py): the
# same start draws, evaluation seeds, stopping rule (training fitness, no
# check), validation on 100 fresh starts and thresholds; one line per run.
#
#   scripts/gym-classic-multineat.sh                        # seeds 1-3, every task
#   SEEDS="1 2 3 4 5" TASKS="cartpole acrobot" scripts/gym-classic-multineat.sh
#   EVALUATIONS=15000 CPU_SECONDS=120 scripts/gym-classic-multineat.sh
#
# Budget: a run stops at EVALUATIONS evaluations (vivae's default run: 100
# generations of 150) or CPU_SECONDS of its process's CPU time, whichever
# comes first. MultiNEAT's parameters are its defaults (population 300); the
# start genome is built as its XOR example builds it (the driver's docstring
# says how). multineat 0.12 (a manylinux wheel, no compiler), Gymnasium and
# NumPy are installed with pip into a venv under target/ (or VENV).
source "$(dirname "$0")/gym-classic-common.sh"
venv multineat-gym-venv --only-binary :all: 'multineat==0.12'
for task in $TASKS; do
    case "$task" in
        cartpole | acrobot | mountain-car | mountain-car-continuous | pendulum) ;;
        *) echo "unknown task $task" >&2; exit 2 ;;
    esac
    for seed in $SEEDS; do
        "$VENV/bin/python" scripts/gym-classic-multineat.py \
            "$task" "$seed" "$EVALUATIONS" "$CPU_SECONDS"
    done
done
