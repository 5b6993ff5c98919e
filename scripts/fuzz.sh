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
[ ${#targets[@]} -gt 0 ] || targets=(scenario_loader config_parser genome_reader checkpoint_reader rundir_reader view_messages python_json image_reader)
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

# Run-directory readers: the files of a real run when one is at hand, and
# small hand-written rows otherwise.
mkdir -p fuzz/corpus/rundir_reader
for r in runs/*/; do
    [ -f "$r/generations.csv" ] || continue
    for f in generations.csv timing.csv champion.json best-genomes.jsonl config.toml figures/drawn-generations.txt; do
        [ -f "$r/$f" ] && head -c 65536 "$r/$f" > "fuzz/corpus/rundir_reader/seed-$(basename "$f")"
    done
    head -n 200 "$r/population.csv" > fuzz/corpus/rundir_reader/seed-population.csv
    break
done
printf 'generation,rank,fitness\n1,1,0.5\n1,2,0.25\n2,1,0.75\n' > fuzz/corpus/rundir_reader/rows-population.csv
printf 'generation,seconds,robot_steps_per_second\n1,0.5,1000\n2,0.25,2000\n' > fuzz/corpus/rundir_reader/rows-timing.csv
printf '3\n' > fuzz/corpus/rundir_reader/rows-drawn.txt
# PNG frames and maps: the test corpus's pictures, when there are any.
mkdir -p fuzz/corpus/image_reader
find crates/vivae/tests/data docs -name '*.png' -size -256k 2>/dev/null | head -n 20 |
    while read -r f; do cp "$f" "fuzz/corpus/image_reader/seed-$(basename "$f")"; done
# Viewer messages: one message a line, every kind the page sends.
mkdir -p fuzz/corpus/view_messages
printf '%s\n' '{"type":"play"}' '{"type":"step","n":30}' '{"type":"select","robot":1}' \
    > fuzz/corpus/view_messages/play-step
printf '%s\n' '{"type":"resolution","sensors":"8x24","neurons":"5x5"}' '{"type":"step"}' \
    '{"type":"controller","which":"none"}' '{"type":"drive","robot":0}' \
    '{"type":"keys","up":true,"down":false,"left":true,"right":false}' '{"type":"step","n":5}' \
    > fuzz/corpus/view_messages/resolution-drive
printf '%s\n' '{"type":"drag","robot":2,"x":100.5,"y":200.25,"heading":1.0}' '{"type":"speed","value":4}' \
    '{"type":"scenario","index":0}' '{"type":"reset"}' '{"type":"controller","which":"champion"}' \
    '{"type":"pause"}' '{"type":"controller","which":3}' \
    > fuzz/corpus/view_messages/drag-reset

for t in "${targets[@]}"; do
    echo "== $t (${seconds}s)"
    # One viewer input is up to 8 page messages of up to about a second of
    # work each in a release build, several times that under AddressSanitizer.
    timeout=10
    [ "$t" = view_messages ] && timeout=60
    cargo +nightly fuzz run --fuzz-dir fuzz "$t" "fuzz/corpus/$t" -- \
        -max_total_time="$seconds" -rss_limit_mb=2048 -timeout="$timeout" \
        -max_len=262144 -print_final_stats=1
done
