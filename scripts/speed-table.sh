#!/usr/bin/env bash
# Measures every row of the speed table in docs/benchmarks.md ("Speed at every
# resolution") on this machine and prints each row's measurement under a
# heading. Run it on a quiet machine: every figure is a wall-clock one.
#
#   scripts/speed-table.sh [OUT_DIR]     (default target/speed-table)
#
# Benchmarks print divan's fastest and median sample; the whole runs and the
# peak memory come from /usr/bin/time (GNU time, Debian package `time`). Exact
# and fast precision are measured side by side (issue 36): each whole run
# twice, the two precisions alternated, so that a host's drift hits both.
# Runs go to OUT_DIR with --force, which replaces only a run directory vivae
# wrote (it refuses any other), so the script never deletes a user's file.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/speed-table}
mkdir -p "$out"

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

# `run NAME PRECISION ARGS...`: one whole run on every core (the 2 of the
# machines measured), its wall and CPU time.
run() {
    local name=$1 precision=$2
    shift 2
    printf '%-8s %-5s ' "$name" "$precision"
    /usr/bin/time -f "%e s wall, %U s user, %M KB peak" target/release/vivae evolve -q \
        --precision "$precision" --out "$out/$name-$precision" --force "$@" 2>&1 | tail -1
}

echo "== whole default run (400 generations, 3x5 -> 3x3), 2 threads, exact and fast alternated"
for _ in 1 2; do
    run default exact
    run default fast
done

# On an AVX-512 CPU, the same run with AVX2, what a CPU without AVX-512
# runs: a slow path there (the f32 sigmoid one lane at a time, until
# 0aa3a28) does not show at the widest level.
if grep -qw avx512f /proc/cpuinfo; then
    echo "== whole default run with VIVAE_SIMD=avx2, exact and fast alternated"
    VIVAE_SIMD=avx2 run default exact
    VIVAE_SIMD=avx2 run default fast
fi

echo "== camera run (8 generations, 32x96 -> 9x9), 2 threads, exact and fast alternated"
for _ in 1 2; do
    run camera exact --sensors 32x96 --neurons 9x9 --generations 8
    run camera fast --sensors 32x96 --neurons 9x9 --generations 8
done

echo "== one evaluation (robot-steps/s), exact then fast"
bench vivae experiment evaluation_3x5_to_3x3
bench vivae experiment evaluation_32x96_to_9x9

echo "== controller step alone, 5 robots (exact and fast)"
bench vivae-neat decode controller_batch_step

echo "== surface sensors alone (robot-steps/s): 20x60 in f64; 3x5 and 32x96 in f64 and f32"
bench vivae-sim sim read_5_robots_20x60_surface_sensors
bench vivae-sim sim read_5_robots_3x5_surface_sensors
bench vivae-sim sim read_5_robots_32x96_surface_sensors

echo "== decoding 8,002,000 connections (exact, fast)"
bench vivae-neat decode decode_8m

echo "== NEAT"
bench vivae-neat neat xor_run
bench vivae-neat neat reproduction

echo "== peak memory, 32x96 -> 9x9, population 20, 2 generations, 2 threads"
/usr/bin/time -f "%M KB peak, %e s wall" target/release/vivae evolve -q --sensors 32x96 \
    --neurons 9x9 --population 20 --generations 2 --out "$out/memory-run" --force 2>&1 | tail -1

echo "== figures at camera resolution"
bench vivae figures network_32x96_to_9x9
bench vivae figures convergence_400_generations
bench vivae figures trajectories_drawing
