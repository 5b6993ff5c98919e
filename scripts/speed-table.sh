#!/usr/bin/env bash
# Measures every row of the speed table in docs/benchmarks.md ("Speed at every
# resolution") on this machine and prints each row's measurement under a
# heading. Run it on a quiet machine: every figure is a wall-clock one.
#
#   scripts/speed-table.sh [OUT_DIR]     (default target/speed-table)
#
# Benchmarks print divan's fastest and median sample; the whole default run and
# the peak memory come from /usr/bin/time (GNU time, Debian package `time`).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/speed-table}
mkdir -p "$out"
rm -rf "$out/default-run" "$out/memory-run"

cargo build --release -q -p vivae
cargo bench -q --workspace --no-run

# `bench CRATE BENCH FILTER`: divan's rows for FILTER (fastest, slowest, median,
# mean; with a counter, a second row gives the same as throughput).
bench() {
    local log="$out/$2-$3.txt"
    cargo bench -q -p "$1" --bench "$2" -- "$3" >"$log" 2>&1
    grep -v -e '^Timer precision' -e '^$' -e '^Running' "$log"
}

echo "== machine"
grep -m1 "model name" /proc/cpuinfo
# The widest level the CPU has (grep -o would print whichever flag comes first).
for level in avx512f avx2; do
    if grep -qw "$level" /proc/cpuinfo; then echo "widest vector level: $level"; break; fi
done
uptime

echo "== whole default run, 2 threads (wall seconds)"
/usr/bin/time -f "%e s wall, %U s user, %M KB peak" \
    target/release/vivae evolve -q --out "$out/default-run" 2>&1 | tail -1

echo "== one evaluation (robot-steps/s)"
bench vivae experiment evaluation_3x5_to_3x3
bench vivae experiment evaluation_32x96_to_9x9

echo "== surface sensors alone, 20x60 (robot-steps/s)"
bench vivae-sim sim read_5_robots_20x60_surface_sensors

echo "== decoding 8,002,000 connections"
bench vivae-neat decode decode_8m

echo "== NEAT"
bench vivae-neat neat xor_run
bench vivae-neat neat reproduction

echo "== peak memory, 32x96 -> 9x9, population 20, 2 generations, 2 threads"
/usr/bin/time -f "%M KB peak, %e s wall" target/release/vivae evolve -q --sensors 32x96 \
    --neurons 9x9 --population 20 --generations 2 --out "$out/memory-run" 2>&1 | tail -1

echo "== figures at camera resolution"
bench vivae figures network_32x96_to_9x9
bench vivae figures convergence_400_generations
bench vivae figures trajectories_drawing
