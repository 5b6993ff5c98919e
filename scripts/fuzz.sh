#!/usr/bin/env bash
# Coverage-guided fuzzing of the input readers (docs/fuzzing.md).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
# Needs the nightly toolchain and cargo-fuzz (cargo install cargo-fuzz).
# One fuzzing process, targets one after another (no -jobs: with it libFuzzer
# writes fuzz-N.log into the current folder).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-1800}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scenario_loader config_parser genome_reader checkpoint_reader)
shared=../shared/vivae-scenarios

# Seed corpora, rebuilt from the project's files (never committed).
seed() {
    local dir="fuzz/corpus/$1"
    shift
    mkdir -p "$dir"
    for f in "$@"; do
        [ -f "$f" ] && cp "$f" "$dir/$(basename "$(dirname "$f")")-$(basename "$f")"
    done
    return 0
}
seed scenario_loader scenarios/*.svg "$shared"/*.svg tests/bad-inputs/*.svg
seed config_parser tests/bad-inputs/*.toml
seed genome_reader tests/bad-inputs/*.json
mkdir -p fuzz/corpus/checkpoint_reader
# A real checkpoint body as the checkpoint seed, when a run is at hand.
for c in runs/*/checkpoints/gen-000001.ckpt; do
    [ -f "$c" ] && tail -n +2 "$c" > fuzz/corpus/checkpoint_reader/seed-ckpt.json && break
done

for t in "${targets[@]}"; do
    echo "== $t (${seconds}s)"
    cargo +nightly fuzz run --fuzz-dir fuzz "$t" "fuzz/corpus/$t" -- \
        -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
        -max_len=262144 -print_final_stats=1
done
