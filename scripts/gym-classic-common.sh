# Sourced by the classic-control comparison scripts (gym-classic-neat-python.sh,
# gym-classic-multineat.sh): strict mode, the repository root as working
# directory, the runs' settings from the environment (SEEDS, TASKS,
# EVALUATIONS, CPU_SECONDS) and `venv NAME PIP-ARGUMENT…`, which makes the
# venv VENV (default target/NAME) and pip-installs into it those packages,
# Gymnasium and NumPy.
set -euo pipefail
cd "$(dirname "$0")/.."
SEEDS="${SEEDS:-1 2 3}"
TASKS="${TASKS:-cartpole acrobot mountain-car mountain-car-continuous pendulum}"
EVALUATIONS="${EVALUATIONS:-15000}"
CPU_SECONDS="${CPU_SECONDS:-120}"
venv() {
    local name="$1"
    shift
    local target="${CARGO_TARGET_DIR:-target}"
    mkdir -p "$target"
    VENV="${VENV:-$(cd "$target" && pwd)/$name}"
    if [ ! -x "$VENV/bin/python" ]; then
        python3 -m venv "$VENV"
    fi
    "$VENV/bin/pip" install --quiet --disable-pip-version-check "$@" 'gymnasium>=1,<2' numpy
}
