#!/usr/bin/env python3
"""Times gymnasium-hardmaze (PyPI) stepping its hard maze for 400 steps with a
fixed policy, the Python side of the maze speed comparison (the Rust side is
`cargo bench -p vivae-lab --bench maze`).

    python3 -m venv /tmp/venv-maze && /tmp/venv-maze/bin/pip install gymnasium-hardmaze
    /tmp/venv-maze/bin/python crates/lab/examples/maze_gym.py --episodes 50

Prints the fastest, median and mean time of one episode (reset + 400 steps), in ms.
"""

import argparse
import statistics
import sys
import time

import gymnasium as gym
import numpy as np

import gymnasium_hardmaze  # noqa: F401  (registers HardMaze-v0)

STEPS = 400


def episode(env, action):
    """One episode of STEPS steps with a fixed action; returns its wall time in s."""
    start = time.perf_counter()
    env.reset(seed=0)
    for _ in range(STEPS):
        _, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            break
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=50, help="episodes timed (default 50)")
    args = parser.parse_args()
    if args.episodes < 1:
        parser.error("--episodes must be at least 1")
    # The unwrapped env: the time-limit and checker wrappers are Python overhead a
    # user could drop too; what is timed is the simulator's own step.
    env = gym.make("HardMaze-v0").unwrapped
    # Full speed ahead, no turn (the action is [left turn, forward, right turn]).
    action = np.array([0.0, 1.0, 0.0], dtype=np.float32)
    episode(env, action)  # warm-up
    times = [episode(env, action) for _ in range(args.episodes)]
    print(
        f"gymnasium-hardmaze: {STEPS} steps fastest_ms={1e3 * min(times):.3f} "
        f"median_ms={1e3 * statistics.median(times):.3f} "
        f"mean_ms={1e3 * statistics.mean(times):.3f} episodes={args.episodes}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
