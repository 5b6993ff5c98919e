"""The Gymnasium and PettingZoo environments."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import vivae


def make(**kw):
    return gymnasium.make("vivae/Drive-v0", **kw)


def test_drive_env_passes_gymnasium_check_env():
    env = make(scenario="oval", sensors="3x5", steps=50, render_mode="rgb_array")
    check_env(env.unwrapped, skip_render_check=False)


def test_observation_is_surface_sensors_then_distance_rays():
    env = make(sensors="3x5")
    obs, _ = env.reset(seed=0)
    assert obs.dtype == np.float32 and obs.shape == (15,)
    assert ((obs >= 0) & (obs <= 1)).all()
    env = make(sensors="4x7", distance_rays=5)
    obs, _ = env.reset(seed=0)
    assert obs.shape == (4 * 7 + 5,)


def test_rewards_sum_to_the_odometer_and_episodes_truncate_at_the_step_limit():
    env = make(steps=40)
    env.reset(seed=0)
    total, steps = 0.0, 0
    while True:
        _, reward, terminated, truncated, info = env.step(np.array([1.0, 1.0], dtype=np.float32))
        total += reward
        steps += 1
        assert not terminated
        if truncated:
            break
    assert steps == 40
    assert total > 0 and total == pytest.approx(info["odometer"], rel=1e-9)


def test_seeded_episodes_repeat_bit_for_bit():
    def episode(seed):
        env = make(scenario="roads", steps=200)
        obs, _ = env.reset(seed=seed)
        env.action_space.seed(seed)
        trace = [obs]
        for _ in range(200):
            obs, reward, _, _, _ = env.step(env.action_space.sample())
            trace.append(obs)
            trace.append(np.array([reward], dtype=np.float32))
        return np.concatenate(trace)

    a, b = episode(7), episode(7)
    assert a.tobytes() == b.tobytes()
    assert episode(8).tobytes() != a.tobytes()


def test_render_returns_the_arena_as_an_rgb_image():
    env = make(render_mode="rgb_array", render_scale=0.25)
    env.reset(seed=0)
    image = env.render()
    assert image.dtype == np.uint8 and image.ndim == 3 and image.shape[2] == 3
    assert image.shape[0] > 50 and image.shape[1] > 50
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 3


@pytest.mark.parametrize("action, error", [([1.0], ValueError), ([1.0, 0.0, 0.5], ValueError),
                                           ([[1.0, 1.0]], ValueError), ("fast", TypeError)])
def test_a_wrong_action_is_an_error_not_a_crash(action, error):
    # A wrong shape is a ValueError, a value that is not numbers a TypeError.
    env = make()
    env.reset(seed=0)
    with pytest.raises(error):
        env.step(action)
    # The environment still works afterwards.
    obs, *_ = env.step([0.5, 0.5])
    assert obs.shape == (15,)


def test_nan_and_out_of_range_wheel_commands_are_clamped():
    env = make(steps=5)
    env.reset(seed=0)
    obs, reward, *_ = env.step([np.nan, 7.0])
    assert np.isfinite(obs).all() and np.isfinite(reward)


def test_a_malformed_scenario_is_a_value_error_with_the_one_line_message(tmp_path):
    bad = tmp_path / "broken.svg"
    bad.write_text("<svg><rect width='10'")
    with pytest.raises(ValueError) as e:
        make(scenario=str(bad))
    message = str(e.value)
    assert "broken.svg" in message and "\n" not in message


def test_a_missing_scenario_file_is_an_os_error_naming_it(tmp_path):
    with pytest.raises((OSError, ValueError)) as e:
        make(scenario=str(tmp_path / "nowhere.svg"))
    assert "nowhere.svg" in str(e.value)


def test_bad_settings_are_value_errors():
    with pytest.raises(ValueError, match="sensors"):
        make(sensors="3by5")
    with pytest.raises(ValueError, match="unknown setting"):
        make(wheels=3)
    with pytest.raises(ValueError):
        make(steps=0)


def test_vector_env_matches_single_envs():
    n = 4
    venv = gymnasium.make_vec("vivae/Drive-v0", num_envs=n, steps=30)
    assert isinstance(venv.unwrapped, vivae.DriveVectorEnv)
    obs, _ = venv.reset(seed=3)
    assert obs.shape == (n, 15) and obs.dtype == np.float32
    rng = np.random.default_rng(3)
    actions = rng.uniform(-1, 1, size=(30, n, 2)).astype(np.float32)
    singles = [make(steps=30) for _ in range(n)]
    for e in singles:
        e.reset(seed=3)
    for t in range(30):
        vobs, vrew, vterm, vtrunc, _ = venv.step(actions[t])
        for i, e in enumerate(singles):
            sobs, srew, _, strunc, _ = e.step(actions[t, i])
            assert vobs[i].tobytes() == sobs.tobytes()
            assert vrew[i] == srew
            assert vtrunc[i] == strunc
    assert vtrunc.all() and not vterm.any()
    # Next-step autoreset: the step after the end starts a new episode.
    obs, rew, _, trunc, _ = venv.step(actions[0])
    first, _ = singles[0].reset(seed=3)
    assert obs[0].tobytes() == first.tobytes() and (rew == 0).all() and not trunc.any()


def test_vector_env_results_do_not_depend_on_threads():
    def run(threads):
        venv = vivae.DriveVectorEnv(num_envs=8, threads=threads, steps=50)
        venv.reset(seed=0)
        rng = np.random.default_rng(0)
        out = []
        for _ in range(60):
            o, r, _, _, _ = venv.step(rng.uniform(-1, 1, size=(8, 2)).astype(np.float32))
            out += [o.tobytes(), r.tobytes()]
        return out

    assert run(1) == run(2)


def test_vector_env_refuses_a_wrong_action_shape():
    venv = vivae.DriveVectorEnv(num_envs=3)
    venv.reset()
    with pytest.raises(ValueError, match="shape"):
        venv.step(np.zeros((2, 2), dtype=np.float32))


def test_parallel_env_passes_pettingzoo_parallel_api_test():
    from pettingzoo.test import parallel_api_test

    env = vivae.DriveParallelEnv(steps=100)
    assert len(env.possible_agents) == 5
    parallel_api_test(env, num_cycles=200)


def test_parallel_env_robots_drive_as_in_one_world():
    env = vivae.DriveParallelEnv(steps=20)
    obs, _ = env.reset(seed=1)
    assert set(obs) == set(env.possible_agents)
    for _ in range(20):
        obs, rewards, terms, truncs, _ = env.step({a: np.array([1.0, 0.8], np.float32) for a in env.agents})
    assert all(truncs.values()) and env.agents == []
    assert all(r >= 0 for r in rewards.values())


def test_absurd_world_counts_are_refused_before_anything_is_allocated():
    with pytest.raises(ValueError, match="num_worlds"):
        vivae.DriveVectorEnv(num_envs=10**9)
    with pytest.raises(ValueError, match="num_worlds"):
        vivae.DriveVectorEnv(num_envs=0)


def test_the_core_refuses_read_only_overlapping_strided_and_misaligned_buffers():
    from vivae._vivae import DriveCore

    core = DriveCore(2, robots=1)
    obs = np.zeros((2, 1, 15), np.float32)
    rew, trunc = np.zeros((2, 1)), np.zeros(2, bool)
    act = np.zeros((2, 1, 2), np.float32)
    core.step(act, obs, rew, trunc)
    frozen = obs.copy()
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match="writeable"):
        core.step(act, frozen, rew, trunc)
    shared = np.zeros(2 * 15 + 10, np.float32)
    with pytest.raises(ValueError, match="share memory"):
        core.step(shared[:4].reshape(2, 1, 2), shared[:30].reshape(2, 1, 15), rew, trunc)
    strided = np.zeros((2, 1, 4), np.float32)[:, :, ::2]
    with pytest.raises(ValueError, match="contiguous"):
        core.step(strided, obs, rew, trunc)
    misaligned = np.frombuffer(bytearray(4 * 30 + 1), dtype=np.uint8)[1:].view(np.float32).reshape(2, 1, 15)
    assert not misaligned.flags.aligned
    with pytest.raises(ValueError, match="aligned"):
        core.step(act, misaligned, rew, trunc)
    with pytest.raises(TypeError):
        core.step(act.astype(np.float64), obs, rew, trunc)
