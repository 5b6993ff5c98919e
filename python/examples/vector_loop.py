"""64 worlds stepped together in Rust threads, numpy in and out.

    python python/examples/vector_loop.py
"""

import time

import gymnasium
import numpy as np

import vivae  # noqa: F401

envs = gymnasium.make_vec("vivae/Drive-v0", num_envs=64, sensors="3x5")
obs, _ = envs.reset(seed=0)
rng = np.random.default_rng(0)
returns = np.zeros(64)
start = time.perf_counter()
for _ in range(2000):
    actions = rng.uniform(-1, 1, size=(64, 2)).astype(np.float32)
    obs, rewards, terminated, truncated, _ = envs.step(actions)
    returns += rewards
seconds = time.perf_counter() - start
print(f"{64 * 2000 / seconds:,.0f} robot-steps/s; mean distance driven {returns.mean():.1f} px")
