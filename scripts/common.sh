# Sourced by the experiment scripts (source "$(dirname "$0")/common.sh"):
# strict mode, the repository root as working directory, the release
# program built, the seeds from the script's arguments (default 1 to 5), and
# the helpers that read and format a summary line's fields.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p vivae
vivae=target/release/vivae
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
# The value of `name=value` in a summary line on stdin.
field() { sed -n "s/.*$1=\([^ ]*\).*/\1/p"; }
# "a (a/b as a percentage)".
pct() { awk -v a="$1" -v b="$2" 'BEGIN{printf "%.3f (%.1f%%)", a, 100*a/b}'; }
# A share as a percentage.
road() { awk -v x="$1" 'BEGIN{printf "%.1f%%", 100*x}'; }
