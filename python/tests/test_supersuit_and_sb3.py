"""The PettingZoo → SB3 recipe: SuperSuit's `pettingzoo_env_to_vec_env_v1`
and `concat_vec_envs_v1` (its worker processes receive the environment
pickled) carry `DriveParallelEnv`, and SB3's PPO learns on it when SB3 is
installed (it pulls torch, too heavy for CI: skipped there with the reason)."""

from __future__ import annotations

import numpy as np
import pytest

import vivae


def vec_env(base_class: str, num_cpus: int):
    pytest.importorskip("pettingzoo")
    ss = pytest.importorskip("supersuit", reason="supersuit is not installed (pip install supersuit)")
    env = vivae.DriveParallelEnv(scenario="oval", steps=50)
    env = ss.pettingzoo_env_to_vec_env_v1(env)
    return ss.concat_vec_envs_v1(env, 2, num_cpus=num_cpus, base_class=base_class)


def test_supersuit_concatenates_the_parallel_env_across_processes():
    envs = vec_env("gymnasium", num_cpus=2)
    try:
        obs, _ = envs.reset(seed=0)
        assert obs.shape[0] == envs.num_envs
        for _ in range(60):  # past the episode's end: autoreset
            obs, rewards, term, trunc, _ = envs.step(np.ones((envs.num_envs, 2), dtype=np.float32))
        assert np.isfinite(rewards).all()
    finally:
        envs.close()


def test_sb3_ppo_runs_on_the_concatenated_parallel_env():
    sb3 = pytest.importorskip("stable_baselines3", reason="stable-baselines3 (and torch) is not installed")
    envs = vec_env("stable_baselines3", num_cpus=2)
    try:
        # No seed= to PPO: it calls venv.seed(), which SuperSuit's ProcConcatVec lacks.
        model = sb3.PPO("MlpPolicy", envs, n_steps=64, batch_size=64, n_epochs=1, verbose=0)
        model.learn(total_timesteps=256)
    finally:
        envs.close()
