"""The share of a Gymnasium MuJoCo step spent in MuJoCo's own `mj_step`
calls (what a native Rust task would still pay), in CPU time.

    python python/benchmarks/mujoco_share.py Hopper-v5 [--steps 3000]
"""

from __future__ import annotations

import argparse
import time

import gymnasium
import mujoco  # type: ignore[import-untyped]
import numpy as np


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("env")
    parser.add_argument("--steps", type=int, default=3000)
    a = parser.parse_args()
    env = gymnasium.make(a.env)
    env.reset(seed=0)
    u = env.unwrapped
    action = np.zeros(env.action_space.shape)
    started = time.process_time()
    for _ in range(a.steps):
        _, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            env.reset()
    step = (time.process_time() - started) / a.steps
    started = time.process_time()
    for _ in range(a.steps):
        for _ in range(u.frame_skip):
            mujoco.mj_step(u.model, u.data)
    physics = (time.process_time() - started) / a.steps
    print(
        f"{a.env}: a Gymnasium step {step * 1e6:.1f} us; its {u.frame_skip} mj_step calls "
        f"{physics * 1e6:.1f} us ({physics / step:.0%})"
    )


if __name__ == "__main__":
    main()
