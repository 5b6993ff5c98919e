"""XOR by ask/tell with vivae against neat-python 2.x, in the same process,
with the same fitness function and stopping rule.

    pip install "neat-python>=2,<3"
    python python/benchmarks/xor_vs_neat_python.py [--seeds 10]

Both evolve 150 genomes with each library's own XOR settings (vivae:
`Population(3, 1)`, Stanley's; neat-python: its examples/xor config, in
xor_neat_python.cfg) and the fitness neat-python's example uses,
4 - sum of squared errors over the four cases, computed in Python for both.
A run stops at the first generation whose best reaches 3.9, or after 300
generations. Reported: wall time per run (mean over seeds), generations,
and how many runs reached 3.9.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import vivae

CASES = [((0.0, 0.0), 0.0), ((0.0, 1.0), 1.0), ((1.0, 0.0), 1.0), ((1.0, 1.0), 0.0)]
THRESHOLD, MAX_GENERATIONS = 3.9, 300


def vivae_run(seed: int) -> tuple[float, int, bool]:
    start = time.perf_counter()
    pop = vivae.Population(3, 1, seed=seed)
    for generation in range(1, MAX_GENERATIONS + 1):
        scores = []
        for g in pop.ask():
            net = g.network()
            scores.append(4.0 - sum((net.activate([a, b, 1.0])[0] - want) ** 2 for (a, b), want in CASES))
        pop.tell(scores)
        if max(scores) >= THRESHOLD:
            return time.perf_counter() - start, generation, True
    return time.perf_counter() - start, MAX_GENERATIONS, False


def neat_python_run(seed: int) -> tuple[float, int, bool]:
    import neat

    path = os.path.join(os.path.dirname(__file__), "xor_neat_python.cfg")
    start = time.perf_counter()
    config = neat.Config(neat.DefaultGenome, neat.DefaultReproduction, neat.DefaultSpeciesSet,
                         neat.DefaultStagnation, path)

    def eval_genomes(genomes, config):
        for _, genome in genomes:
            net = neat.nn.FeedForwardNetwork.create(genome, config)
            genome.fitness = 4.0 - sum((net.activate(xi)[0] - want) ** 2 for xi, want in CASES)

    pop = neat.Population(config, seed=seed)
    best = pop.run(eval_genomes, MAX_GENERATIONS)
    return time.perf_counter() - start, pop.generation, best.fitness >= THRESHOLD


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=10)
    a = p.parse_args()
    results = {}
    for name, run in [("vivae", vivae_run), ("neat-python", neat_python_run)]:
        rows = [run(seed) for seed in range(1, a.seeds + 1)]
        wall = statistics.mean(r[0] for r in rows)
        gens = statistics.mean(r[1] for r in rows)
        solved = sum(r[2] for r in rows)
        results[name] = wall
        print(f"{name:>12}: {1000 * wall:9.1f} ms per run, {gens:6.1f} generations, "
              f"{solved}/{a.seeds} reached {THRESHOLD}")
    print(f"neat-python / vivae wall time per run: {results['neat-python'] / results['vivae']:.0f}x")


if __name__ == "__main__":
    main()
