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


# Every params/options error names the key and what it expected.
@pytest.mark.parametrize("make, what", [
    (lambda p: vivae.Population(3, 1, params=p), "params"),
    (lambda p: vivae.NoveltySearch(3, 1, params=p), "params"),
    (lambda p: vivae.DriveTask(scenario="oval", steps=5, population=4).population(params=p), "params"),
    (lambda p: vivae.PredatorPreyTask(steps=5).population("prey", params=p), "params"),
    (lambda p: vivae.NoveltySearch(3, 1, novelty={"k": p["weight_amplitude"]}), "novelty"),
    (lambda p: vivae.MapElites(3, 1, lower=[0], upper=[1], bins=[4],
                               map={"crossover_probability": p["weight_amplitude"]}), "map"),
])
def test_a_parameter_json_cannot_hold_names_its_key(make, what):
    import re

    for value in (float("nan"), float("inf"), -float("inf")):
        with pytest.raises(ValueError, match=rf'{what}\["\w+"\] = {re.escape(repr(value))}: expected a finite number'):
            make({"weight_amplitude": value})
    for value in ({1, 2}, object(), b"3"):
        with pytest.raises(TypeError, match=rf'{what}\["\w+"\] = .*expected a number, bool, string, list or dict, got'):
            make({"weight_amplitude": value})


def test_a_parameter_of_the_wrong_type_names_the_key_and_the_type_expected():
    with pytest.raises(ValueError, match=r'params\["population_size"\] = "many": invalid type: string "many", expected usize'):
        vivae.Population(3, 1, params={"population_size": "many"})
    with pytest.raises(ValueError, match=r'params\["population_size"\] = -3: invalid value: integer `-3`, expected usize'):
        vivae.Population(3, 1, params={"population_size": -3})
    with pytest.raises(TypeError, match="params: keys are parameter names"):
        vivae.Population(3, 1, params={1: 2})


@pytest.mark.parametrize("mask, error, message", [
    (5, TypeError, r"options\['reset_mask'\]: expected 2 bools \(one per environment\), got int"),
    ("ab", TypeError, r"options\['reset_mask'\]: expected 2 bools"),
    ([True], ValueError, r"options\['reset_mask'\]: 1 entries for 2 environments"),
    (["a", "b"], TypeError, r"options\['reset_mask'\]\[0\]: expected a bool, got str"),
    ([1, 0], TypeError, r"options\['reset_mask'\]\[0\]: expected a bool, got int"),
])
def test_a_reset_mask_names_the_option_and_what_it_expected(mask, error, message):
    env = vivae.DriveVectorEnv(2, scenario="oval", steps=5)
    with pytest.raises(error, match=message):
        env.reset(options={"reset_mask": mask})
    env.reset(options={"reset_mask": np.array([True, False])})
    env.reset(options={"reset_mask": [False, True]})


@pytest.mark.parametrize("call, message", [
    (lambda s, n: s.tell(["a"] * n), r"fitnesses\[0\]: expected a real number, got str"),
    (lambda s, n: s.tell("abc"), r"fitnesses: expected a list of real numbers, got str"),
    (lambda s, n: s.tell(5), r"fitnesses: expected a list of real numbers, got int"),
    (lambda s, n: s.tell([None] * n), r"fitnesses\[0\]: expected a real number, got NoneType"),
    (lambda s, n: s.tell([1.0] * n, behaviours=[["x"]] * n), r"behaviours\[0\]\[0\]: expected a real number, got str"),
    (lambda s, n: s.tell([1.0] * n, behaviours=[0.5] * n), r"behaviours\[0\]: expected a list of real numbers, got float"),
    (lambda s, n: s.tell([1.0] * n, metrics=[[True]] * n), r"metrics\[0\]\[0\]: expected a real number, got bool"),
])
@pytest.mark.parametrize("make", [
    lambda: vivae.Population(3, 1, size=6),
    lambda: vivae.NoveltySearch(3, 1, size=6),
    lambda: vivae.Nsga2(3, 1, objectives=[("fitness", "max")], size=6),
    lambda: vivae.MapElites(3, 1, lower=[0], upper=[1], bins=[4]),
])
def test_tell_names_the_argument_and_what_it_expected(make, call, message):
    strategy = make()
    n = len(strategy.ask())
    with pytest.raises(TypeError, match=message):
        call(strategy, n)
    # Numbers of any width are numbers.
    strategy.tell(list(np.arange(n, dtype=np.float32)), behaviours=[[np.float64(0.5)]] * n)


def test_cell_of_names_the_behaviour():
    archive = vivae.MapElites(3, 1, lower=[0], upper=[1], bins=[4])
    with pytest.raises(TypeError, match=r"behaviour\[0\]: expected a real number, got str"):
        archive.cell_of(["a"])
    assert archive.cell_of([0.9]) == 3


@pytest.mark.parametrize("task", ["driving", "cartpole", "predator-prey"])
def test_an_empty_run_directory_name_is_refused_by_name(task, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=r'out="": the run directory\'s name is empty'):
        vivae.evolve(out="", task=task, generations=1, progress=False)
    assert list(tmp_path.iterdir()) == [], "nothing was written"


def test_an_empty_run_directory_name_is_refused_by_vivae_gym_too(tmp_path, monkeypatch):
    pytest.importorskip("gymnasium")
    import vivae.gym

    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=r'out="": the run directory\'s name is empty'):
        vivae.gym.evolve("CartPole-v1", out="", generations=1, progress=False, validate=0)
    assert list(tmp_path.iterdir()) == [], "nothing was written"
