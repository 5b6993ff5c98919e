#!/usr/bin/env bash
# Developer script (not part of CI): evaluations per second of vivae-neat and
# neat-python on the same networks (structural mutations off on both sides),
# on the six tasks of issue 36, one library after the other, one thread each
# (not under `nice`: a niced run gets a fraction of a core whenever anything
# else runs, which is no longer a like-for-like measurement).
#
#   scripts/neat-python-six.sh                    # 2 runs of 15 s per task and library
#   SECONDS_PER_RUN=30 TASKS="sinewave prey_capture" scripts/neat-python-six.sh
#
# neat-python is installed with pip into a throw-away venv under target/. Prints
# each side's summary lines (the pole tasks add steps_per_s) and the ratio.
set -euo pipefail
cd "$(dirname "$0")/.."
T="${SECONDS_PER_RUN:-15}"
TASKS="${TASKS:-xor pole_markov pole_nonmarkov multiplexer sinewave prey_capture}"
TARGET="${CARGO_TARGET_DIR:-target}"
mkdir -p "$TARGET"
VENV="$(cd "$TARGET" && pwd)/neat-python-venv"
if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
"$VENV/bin/pip" install --quiet --disable-pip-version-check 'neat-python==2.0.0'
FIXED="--set add_node_probability=0 --set add_link_probability=0"
example() {
    case "$1" in
        xor) echo xor_speed ;;
        pole_markov) echo pole_markov_speed ;;
        pole_nonmarkov) echo pole_nonmarkov_speed ;;
        *) echo "$1" ;;
    esac
}
for task in $TASKS; do
    cargo build --quiet --release -p vivae-neat --example "$(example "$task")"
done
rate() { sed -n 's/.*evals_per_s=\([0-9.]*\).*/\1/p' | head -1; }
for task in $TASKS; do
    echo "== $task ($(date -u +%H:%M:%S) UTC, load $(cut -d' ' -f1 /proc/loadavg))"
    # shellcheck disable=SC2086
    ours="$("$TARGET/release/examples/$(example "$task")" --runs 2 --seconds "$T" --seed 1 $FIXED 2>/dev/null)"
    echo "$ours"
    theirs="$(cd crates/neat/examples/neat_python && "$VENV/bin/python" efficacy.py "$task" "$T" 2 fixed 2>/dev/null)"
    echo "$theirs"
    a="$(echo "$ours" | rate)"
    b="$(echo "$theirs" | rate)"
    python3 -c "print(f'$task: vivae-neat / neat-python = {$a / $b:.0f}x in evaluations per second')"
    steps() { sed -n 's/.*steps_per_s=\([0-9.]*\).*/\1/p' | head -1; }
    if [ -n "$(echo "$ours" | steps)" ]; then
        a="$(echo "$ours" | steps)"
        b="$(echo "$theirs" | steps)"
        python3 -c "print(f'$task: vivae-neat / neat-python = {$a / $b:.0f}x in network activations per second')"
    fi
done
