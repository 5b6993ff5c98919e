"""Hostile arguments at the Python boundary: every message names the argument
and the allowed range; exception types as documented (TypeError for a value
of the wrong type, ValueError for one out of range)."""

from __future__ import annotations

import numpy as np
import pytest

import vivae


@pytest.mark.parametrize("key", ["steps", "robots", "generations", "population", "seed", "threads",
                                 "distance_rays"])
def test_a_negative_count_names_the_setting_and_its_range(key):
    with pytest.raises(ValueError, match=rf"{key}=-5: expected an integer from 0 to \d+"):
        vivae.DriveTask(scenario="oval", **{key: -5})


@pytest.mark.parametrize("value", ["10", 1.5, True, [3]])
def test_a_count_that_is_not_an_integer_is_a_type_error(value):
    with pytest.raises(TypeError, match="steps: expected an integer"):
        vivae.DriveTask(scenario="oval", steps=value)


def test_a_huge_count_names_its_range():
    with pytest.raises(ValueError, match=r"steps=\d+: expected an integer from 0 to 4294967295"):
        vivae.DriveTask(scenario="oval", steps=10**30)


def test_a_neat_parameter_of_the_wrong_type_names_the_field():
    with pytest.raises(ValueError, match=r"params\[\"compatibility_threshold\"\] = \"high\""):
        vivae.Population(3, 1, params={"compatibility_threshold": "high"})
    with pytest.raises(ValueError, match="unknown field"):
        vivae.Population(3, 1, params={"no_such_parameter": 1})


@pytest.mark.parametrize("seed", [0, 3, np.int64(3), np.uint8(7)])
def test_integer_seeds_of_numpy_types_are_accepted(seed):
    for env in (vivae.DriveEnv(scenario="oval", steps=5), vivae.DriveVectorEnv(2, scenario="oval", steps=5)):
        env.reset(seed=seed)


@pytest.mark.parametrize("seed, error", [(-1, ValueError), (1.5, TypeError), ("3", TypeError),
                                         (True, TypeError)])
def test_bad_seeds_name_the_seed(seed, error):
    with pytest.raises(error, match="seed"):
        vivae.DriveEnv(scenario="oval", steps=5).reset(seed=seed)
    with pytest.raises(error, match="seed"):
        vivae.DriveVectorEnv(2, scenario="oval", steps=5).reset(seed=seed)


def test_a_seed_list_needs_one_seed_per_environment():
    env = vivae.DriveVectorEnv(4, scenario="oval", steps=5)
    with pytest.raises(ValueError, match="a list of 1 seeds for 4 environments"):
        env.reset(seed=[1])
    env.reset(seed=[1, 2, 3, 4])


@pytest.mark.parametrize("options", [[1], "reset", 3])
def test_options_must_be_a_dict(options):
    with pytest.raises(TypeError, match="options: expected a dict or None"):
        vivae.DriveEnv(scenario="oval", steps=5).reset(options=options)
    with pytest.raises(TypeError, match="options: expected a dict or None"):
        vivae.DriveVectorEnv(2, scenario="oval", steps=5).reset(options=options)


def test_the_seed_seeds_the_action_space():
    a, b = vivae.DriveEnv(scenario="oval", steps=5), vivae.DriveEnv(scenario="oval", steps=5)
    a.reset(seed=11)
    b.reset(seed=11)
    assert (a.action_space.sample() == b.action_space.sample()).all()


@pytest.mark.parametrize("make", [
    lambda: vivae.DriveEnv(render_mode="human"),
    lambda: vivae.DriveVectorEnv(2, render_mode="human"),
])
def test_render_modes_that_render_nothing_are_refused(make):
    with pytest.raises(ValueError, match="render_mode='human': expected 'rgb_array' or None"):
        make()


def test_render_human_is_refused_by_the_parallel_env():
    pytest.importorskip("pettingzoo")
    with pytest.raises(ValueError, match="render_mode"):
        vivae.DriveParallelEnv(render_mode="human")


@pytest.mark.parametrize("make", [
    lambda s: vivae.DriveEnv(scenario=s),
    lambda s: vivae.DriveVectorEnv(2, scenario=s),
])
def test_a_list_of_scenarios_is_refused_where_one_world_has_one_map(make):
    with pytest.raises(TypeError, match="one scenario"):
        make(["oval", "figure8"])


def test_a_list_of_scenarios_is_refused_by_gymnasium_make():
    import gymnasium

    with pytest.raises(TypeError, match="one scenario"):
        gymnasium.make("vivae/Drive-v0", scenario=["oval", "figure8"])


def test_a_list_of_scenarios_is_accepted_where_several_maps_are_used():
    task = vivae.DriveTask(scenario=["oval", "figure8"], steps=20, population=4)
    assert len(task.evaluate(task.population().ask())) == 4


def test_the_parallel_env_does_not_step_before_reset_nor_after_the_end():
    pytest.importorskip("pettingzoo")
    env = vivae.DriveParallelEnv(scenario="oval", steps=3)
    with pytest.raises(RuntimeError, match="reset"):
        env.step({})
    env.reset(seed=0)
    for _ in range(3):
        env.step({a: [1.0, 1.0] for a in env.agents})
    assert env.agents == []
    with pytest.raises(RuntimeError, match="reset"):
        env.step({})


def test_a_scenario_that_is_not_utf8_is_a_value_error(tmp_path):
    bad = tmp_path / "bad.svg"
    bad.write_bytes(b"<svg \xff\xfe>")
    with pytest.raises(ValueError, match="not UTF-8"):
        vivae.DriveEnv(scenario=str(bad))


def test_scenario_warnings_become_python_warnings(tmp_path):
    svg = tmp_path / "labels.svg"
    svg.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" '
        'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="200" height="200">'
        '<rect id="r" inkscape:label="Road" x="0" y="0" width="200" height="200"/>'
        '<rect id="x" inkscape:label="Roda" x="0" y="0" width="20" height="20"/>'
        '<circle id="c" inkscape:label="Robot" cx="100" cy="100" r="5"/></svg>'
    )
    with pytest.warns(UserWarning, match="Roda"):
        vivae.DriveEnv(scenario=str(svg))


def test_a_second_tell_of_the_same_batch_is_refused():
    pop = vivae.Population(3, 1, size=10)
    pop.ask()
    pop.tell([1.0] * 10)
    with pytest.raises(ValueError, match="already told"):
        pop.tell([5.0] * 10)
    assert pop.best_ever[1] == 1.0
    pop.ask()
    pop.tell([2.0] * 10)
    assert pop.best_ever[1] == 2.0
