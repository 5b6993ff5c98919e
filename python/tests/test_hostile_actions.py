"""Hostile actions at every environment: anything but real numbers (None,
strings, complex numbers, bools, objects) is a TypeError naming the action;
a wrong shape a ValueError naming both shapes. Nothing is converted silently."""

from __future__ import annotations

import numpy as np
import pytest

import vivae

NOT_REAL = [
    [0.5, None],
    ["0.5", "1"],
    [0.5 + 1j, 0.0],
    np.array([1 + 0j, 0j]),
    [True, False],
    [object(), object()],
    "01",
]


def envs():
    single = vivae.DriveEnv(scenario="oval", steps=20)
    single.reset(seed=0)
    vector = vivae.DriveVectorEnv(2, scenario="oval", steps=20, threads=1)
    vector.reset(seed=0)
    return single, vector


@pytest.mark.parametrize("action", NOT_REAL, ids=repr)
def test_non_numeric_actions_are_a_type_error(action):
    single, vector = envs()
    with pytest.raises(TypeError, match="action"):
        single.step(action)
    with pytest.raises(TypeError, match="action"):
        vector.step([action, action])


def test_non_numeric_actions_of_an_agent_are_a_type_error():
    pytest.importorskip("pettingzoo")
    env = vivae.DriveParallelEnv(scenario="oval", steps=20)
    env.reset(seed=0)
    for action in NOT_REAL:
        with pytest.raises(TypeError, match="action"):
            env.step({"robot_0": action})


@pytest.mark.parametrize("action", [[0.5], [0.1, 0.2, 0.3], [[0.5, 0.5]], 0.5])
def test_actions_of_the_wrong_shape_are_a_value_error(action):
    single, _ = envs()
    with pytest.raises(ValueError, match=r"action has shape .*expected \(2,\)"):
        single.step(action)


def test_integer_and_float_actions_of_any_width_are_accepted():
    single, _ = envs()
    for action in ([1, 0], np.array([0.5, 0.5], dtype=np.float16), np.array([1, -1], dtype=np.int8)):
        single.step(action)


def test_a_controller_takes_the_environments_float32_observations():
    task = vivae.DriveTask(scenario="oval", steps=20, population=4)
    genome = task.population().ask()[0]
    controller = task.controller(genome)
    env = vivae.DriveEnv(scenario="oval", steps=20)
    obs, _ = env.reset(seed=0)
    assert controller.act(obs[None]).shape == (1, 2)
    with pytest.raises(TypeError, match="obs"):
        controller.act(np.array([["a"] * obs.size]))


def test_the_core_names_the_buffer_and_the_dtype_it_expected():
    from vivae._vivae import DriveCore

    core = DriveCore(2, scenario="oval", steps=5, robots=1)
    n = core.obs_size
    good = dict(actions=np.zeros((2, 1, 2), np.float32), obs=np.zeros((2, 1, n), np.float32),
                rewards=np.zeros((2, 1), np.float64), truncated=np.zeros(2, bool))
    core.reset(good["obs"])
    core.step(**good)
    for name, wrong in [("actions", np.zeros((2, 1, 2), np.float64)),
                        ("obs", np.zeros((2, 1, n), np.float64)),
                        ("rewards", np.zeros((2, 1), np.float32)),
                        ("truncated", np.zeros(2, np.int8))]:
        dtype = {"actions": "float32", "obs": "float32", "rewards": "float64", "truncated": "bool"}[name]
        with pytest.raises(TypeError, match=rf"{name}: expected a numpy array of dtype {dtype} .*got an array of dtype {wrong.dtype}"):
            core.step(**{**good, name: wrong})
    with pytest.raises(TypeError, match=r"actions: expected a numpy array of dtype float32 with 3 dimensions, got a list"):
        core.step(**{**good, "actions": [[[0.0, 0.0]]] * 2})
    with pytest.raises(TypeError, match=r"actions: expected .* 3 dimensions, got an array of dtype float32 with 2 dimensions"):
        core.step(**{**good, "actions": np.zeros((2, 2), np.float32)})
    with pytest.raises(TypeError, match=r"obs: expected a numpy array of dtype float32 .*got an array of dtype float64"):
        core.reset(np.zeros((2, 1, n), np.float64))
