"""Time of `gymnasium.make("vivae/Drive-v0")` + `reset`, in a warm process.

    python python/benchmarks/make_reset.py [--repeats 20]
"""

from __future__ import annotations

import argparse
import statistics
import time

import gymnasium

import vivae  # noqa: F401


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=20)
    a = p.parse_args()
    for scenario in ["roads", "town"]:
        times = []
        for _ in range(a.repeats):
            start = time.perf_counter()
            env = gymnasium.make("vivae/Drive-v0", scenario=scenario, sensors="3x5")
            env.reset(seed=0)
            times.append(1000 * (time.perf_counter() - start))
        print(f"{scenario:>6}: make + reset median {statistics.median(times):.1f} ms, "
              f"max {max(times):.1f} ms over {a.repeats}")


if __name__ == "__main__":
    main()
