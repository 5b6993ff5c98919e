"""XOR by ask/tell with vivae against neat-python 2.x, in the same process,
with the same fitness function and stopping rule.

    pip install "neat-python>=2,<3"
    python python/benchmarks/xor_vs_neat_python.py [--runs 20]

The rule of scripts/compare-neat-python.sh: population 150, fitness
(4 - sum |error|)^2 computed in Python for both, and a run stops at the first
genome whose four outputs are all on the right side of 0.5 (at most 500
generations). Each library uses its own XOR settings (vivae:
`Population(3, 1)`, Stanley's; neat-python: its examples/xor config,
xor_neat_python.cfg). Reported per library: runs solved, mean evaluations
and mean wall time per run, and the ratio of the wall times.
"""

from __future__ import annotations

import argparse
import os
import random
import time

import vivae

CASES = [((0.0, 0.0), 0.0), ((0.0, 1.0), 1.0), ((1.0, 0.0), 1.0), ((1.0, 1.0), 0.0)]
MAX_GENERATIONS = 500


class Solved(Exception):
    pass


def score(activate) -> tuple[float, bool]:
    """The fitness of a network's `activate` and whether it solves XOR."""
    err, ok = 0.0, True
    for (a, b), want in CASES:
        o = activate(a, b)
        err += abs(o - want)
        ok &= (o > 0.5) == (want > 0.5)
    return (4.0 - err) ** 2, ok


def vivae_run(seed: int) -> tuple[float, int | None]:
    start = time.perf_counter()
    pop = vivae.Population(3, 1, seed=seed)
    evals = 0
    for _ in range(MAX_GENERATIONS):
        scores = []
        for g in pop.ask():
            net = g.network()
            f, ok = score(lambda a, b: net.activate([a, b, 1.0])[0])
            evals += 1
            if ok:
                return time.perf_counter() - start, evals
            scores.append(f)
        pop.tell(scores)
    return time.perf_counter() - start, None


def neat_python_run(seed: int) -> tuple[float, int | None]:
    import neat

    path = os.path.join(os.path.dirname(__file__), "xor_neat_python.cfg")
    config = neat.Config(neat.DefaultGenome, neat.DefaultReproduction, neat.DefaultSpeciesSet,
                         neat.DefaultStagnation, path)
    random.seed(seed)
    count = [0]

    def eval_genomes(genomes, config):
        for _, g in genomes:
            net = neat.nn.FeedForwardNetwork.create(g, config)
            g.fitness, ok = score(lambda a, b: net.activate((a, b))[0])
            count[0] += 1
            if ok:
                raise Solved()

    start = time.perf_counter()
    pop = neat.Population(config)
    try:
        pop.run(eval_genomes, MAX_GENERATIONS)
    except Solved:
        return time.perf_counter() - start, count[0]
    return time.perf_counter() - start, None


def main() -> None:
    import importlib.metadata

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", type=int, default=20)
    a = p.parse_args()
    version = importlib.metadata.version("neat-python")
    print(f"XOR, population 150, {a.runs} runs each, stopping when all four outputs are on the right side of 0.5")
    print(f"{'library':<22} {'solved':<8} {'mean_evals':<11} mean_ms/run")
    wall = {}
    for name, run in [("vivae (ask/tell)", vivae_run), (f"neat-python {version}", neat_python_run)]:
        rows = [run(seed) for seed in range(1, a.runs + 1)]
        solved = [e for _, e in rows if e is not None]
        wall[name] = sum(t for t, _ in rows) / a.runs
        evals = sum(solved) / max(len(solved), 1)
        print(f"{name:<22} {len(solved)}/{a.runs:<6} {evals:<11.0f} {1000 * wall[name]:.1f}")
    ours, theirs = wall.values()
    print(f"wall-time ratio neat-python / vivae: {theirs / ours:.1f}")


if __name__ == "__main__":
    main()
