"""Vector env throughput: robot-steps/s of `vivae.DriveVectorEnv` driven from
Python with random actions, against the same worlds stepped by a Rust loop.

    python python/benchmarks/vector_env.py [--envs 64] [--steps 3000] [--repeats 7] [--threads 0]

Both sides step the same 64 one-robot worlds (3x5 sensors, the road
scenario) with the same threads; the Rust side draws its random wheel
commands in Rust (`DriveCore.run_random`), the Python side with numpy and
hands them over through `step`, getting observations, rewards and
truncations back as numpy arrays.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

import vivae
from vivae._vivae import DriveCore


def python_loop(envs: int, steps: int, threads: int) -> float:
    env = vivae.DriveVectorEnv(num_envs=envs, sensors="3x5", threads=threads)
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(64, envs, 2)).astype(np.float32)
    start = time.perf_counter()
    for t in range(steps):
        env.step(actions[t & 63])
    return envs * steps / (time.perf_counter() - start)


def python_loop_fresh_actions(envs: int, steps: int, threads: int) -> float:
    env = vivae.DriveVectorEnv(num_envs=envs, sensors="3x5", threads=threads)
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    start = time.perf_counter()
    for _ in range(steps):
        env.step(rng.uniform(-1, 1, size=(envs, 2)).astype(np.float32))
    return envs * steps / (time.perf_counter() - start)


def rust_loop(envs: int, steps: int, threads: int) -> float:
    core = DriveCore(envs, threads=threads, sensors="3x5", robots=1)
    start = time.perf_counter()
    done = core.run_random(steps, 0)
    return done / (time.perf_counter() - start)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--envs", type=int, default=64)
    p.add_argument("--steps", type=int, default=3000)
    p.add_argument("--repeats", type=int, default=7)
    p.add_argument("--threads", type=int, default=0, help="0 = one per core")
    a = p.parse_args()
    rows = {"rust": rust_loop, "python": python_loop, "python+rng": python_loop_fresh_actions}
    runs: dict[str, list[float]] = {name: [] for name in rows}
    # Interleaved, so that every repeat measures the three under the same load.
    for _ in range(a.repeats):
        for name, f in rows.items():
            runs[name].append(f(a.envs, a.steps, a.threads))
    for name, r in runs.items():
        print(f"{name:>11}: best {max(r):>12,.0f} robot-steps/s, median {statistics.median(r):>12,.0f}")
    for name in ["python", "python+rng"]:
        ratios = [p / r for p, r in zip(runs[name], runs["rust"])]
        print(f"{name} / rust: median {100 * statistics.median(ratios):.0f}% over {a.repeats} interleaved repeats, "
              f"best/best {100 * max(runs[name]) / max(runs['rust']):.0f}%")


if __name__ == "__main__":
    main()
