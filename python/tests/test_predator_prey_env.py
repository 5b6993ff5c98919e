"""The predator-prey task from Python beyond whole runs: the PettingZoo
parallel environment (hunter_0 and prey_0), whose summed rewards are the
task's fitnesses, and two ask/tell populations co-evolved with
vivae.PredatorPreyTask, which reproduce `vivae evolve --task predator-prey`."""

from __future__ import annotations

import json
import pickle
from pathlib import Path

import numpy as np
import pytest

import vivae

pytest.importorskip("pettingzoo")

STEPS = 120


def drive(env, hunter, prey):
    """One episode of `env` with policies from observation to action:
    summed rewards, the last step's infos, terminations and truncations."""
    obs, _ = env.reset(seed=0)
    total = {a: 0.0 for a in env.possible_agents}
    while env.agents:
        obs, rewards, terms, truncs, infos = env.step(
            {"hunter_0": hunter(obs["hunter_0"]), "prey_0": prey(obs["prey_0"])}
        )
        for a, r in rewards.items():
            total[a] += r
    return total, infos, terms, truncs


def net_policy(genome):
    net = genome.network()
    return lambda obs: np.array(net.activate(list(obs)))


def chase(obs):
    """Full speed at a prey ahead, else slow down and turn towards it (slices: left, ahead, right, behind)."""
    if obs[1] > 0:
        return np.array([0.5, 1.0])
    return np.array([1.0, 0.3]) if obs[2] > 0 else np.array([0.0, 0.3])


def stand(obs):
    return np.array([0.5, 0.5])


def test_predator_prey_env_passes_pettingzoo_parallel_api_test():
    from pettingzoo.test import parallel_api_test

    env = vivae.PredatorPreyParallelEnv(steps=STEPS)
    assert env.possible_agents == ["hunter_0", "prey_0"]
    assert env.observation_space("prey_0").shape == (11,)
    assert env.action_space("hunter_0").shape == (2,)
    parallel_api_test(env, num_cycles=300)


def test_summed_rewards_are_the_task_fitness_and_networks_meet_as_in_rust():
    task = vivae.PredatorPreyTask(steps=STEPS)
    env = vivae.PredatorPreyParallelEnv(steps=STEPS)
    hunters = task.population("hunter", seed=5, size=8)
    prey = task.population("prey", seed=5, size=8)
    pairs = list(zip(hunters.ask(), reversed(prey.ask())))
    for h, p in pairs:
        want = task.meet(h, p)
        total, infos, terms, truncs = drive(env, net_policy(h), net_policy(p))
        # Float64 observations and actions: the same trajectory, the same figures.
        assert infos["hunter_0"]["fitness"] == want["hunter_fitness"]
        assert infos["prey_0"]["fitness"] == want["prey_fitness"]
        assert infos["hunter_0"]["step"] == want["steps"]
        assert terms["hunter_0"] == want["caught"] and truncs["prey_0"] == (not want["caught"])
        assert total["hunter_0"] == pytest.approx(want["hunter_fitness"], abs=1e-12)
        assert total["prey_0"] == pytest.approx(want["prey_fitness"], abs=1e-12)
        assert want["hunter_fitness"] + want["prey_fitness"] == pytest.approx(2.0)
    # A scripted chase catches a standing prey (within the task's 500
    # steps): both terminated, the hunter paid by time.
    long = vivae.PredatorPreyParallelEnv()
    total, infos, terms, truncs = drive(long, chase, stand)
    t, T = infos["hunter_0"]["step"], long.max_steps
    assert terms == {"hunter_0": True, "prey_0": True} and not any(truncs.values())
    assert infos["hunter_0"]["caught"] and t < T == 500
    assert total["hunter_0"] == pytest.approx(2 - t / T, abs=1e-12)
    assert total["prey_0"] == pytest.approx(t / T, abs=1e-12)
    # Standing still: truncated, rewards from the distance kept.
    total, infos, terms, truncs = drive(env, stand, stand)
    assert all(truncs.values()) and not any(terms.values())
    d = infos["hunter_0"]["mean_distance"]
    assert total["hunter_0"] == pytest.approx(1 - d, abs=1e-12)
    assert total["prey_0"] == pytest.approx(1 + d, abs=1e-12)


def test_resets_are_deterministic_whatever_the_seed():
    env = vivae.PredatorPreyParallelEnv(scenario="predator-prey-obstacles", steps=40)

    def trajectory(seed):
        obs, _ = env.reset(seed=seed)
        env.action_space("hunter_0").seed(seed)
        seen = [obs["hunter_0"], obs["prey_0"]]
        actions = [(np.array([0.2, 0.9]), np.array([0.7, 0.8]))] * 40
        for h, p in actions:
            obs, *_ = env.step({"hunter_0": h, "prey_0": p})
            seen += [obs["hunter_0"], obs["prey_0"]]
        return np.array(seen)

    a, b = trajectory(1), trajectory(99)
    assert np.array_equal(a, b)
    assert not np.array_equal(a[0], a[-1]), "the robots moved"
    # The obstacles arena's hunter sees the prey ahead-right and the bias is 1.
    assert a[0][10] == 1.0 and a[0][1] + a[0][2] > 0


def test_bad_actions_and_arguments_are_python_exceptions():
    env = vivae.PredatorPreyParallelEnv(steps=5)
    with pytest.raises(RuntimeError, match="reset"):
        env.step({"hunter_0": [0.5, 0.5], "prey_0": [0.5, 0.5]})
    env.reset()
    ok = np.array([0.5, 0.5])
    for actions, error, match in [
        ({"hunter_0": [0.5, 0.5, 0.5], "prey_0": ok}, ValueError, "shape"),
        ({"hunter_0": "fast", "prey_0": ok}, TypeError, "real numbers"),
        ({"hunter_0": None, "prey_0": ok}, TypeError, "real numbers"),
        ({"hunter_0": [np.nan, 0.5], "prey_0": ok}, ValueError, "NaN"),
        ({"hunter_0": ok}, ValueError, "prey_0"),
        ({"hunter_0": ok, "prey_0": ok, "robot_0": ok}, ValueError, "no agent"),
        ([ok, ok], TypeError, "dict"),
    ]:
        with pytest.raises(error, match=match):
            env.step(actions)
    # Out of the box is clamped: the episode goes on to its end.
    for _ in range(5):
        env.step({"hunter_0": [7.0, -3.0], "prey_0": [np.inf, 0.5]})
    assert env.agents == []
    with pytest.raises(RuntimeError):
        env.step({"hunter_0": ok, "prey_0": ok})
    for kwargs, error, match in [
        (dict(scenario="roads"), ValueError, "hunter"),
        (dict(task="driving"), ValueError, "predator-prey"),
        (dict(render_mode="human"), ValueError, "rgb_array"),
        (dict(steps="5"), TypeError, "steps"),
        (dict(steps=-1), ValueError, "steps"),
        (dict(steps=0), ValueError, "steps"),
        (dict(scenario=["predator-prey"]), TypeError, "one arena"),
        (dict(colour="red"), ValueError, "unknown setting"),
    ]:
        with pytest.raises(error, match=match):
            vivae.PredatorPreyParallelEnv(**kwargs)
    with pytest.raises(ValueError, match="seed"):
        env.reset(seed=-1)
    task = vivae.PredatorPreyTask(steps=5)
    xor = vivae.Population(3, 1, size=5).ask()[0]
    g = task.population("hunter", size=5).ask()[0]
    with pytest.raises(ValueError, match="11 and 2"):
        task.meet(xor, g)
    with pytest.raises(ValueError, match="side"):
        task.population("wolf")
    with pytest.raises(ValueError, match="side"):
        task.evaluate("wolf", [g], [g])
    with pytest.raises(ValueError, match="opponents"):
        task.evaluate("hunter", [g], [])


def test_the_env_and_the_task_pickle_and_render():
    env = pickle.loads(pickle.dumps(vivae.PredatorPreyParallelEnv(steps=10, render_mode="rgb_array")))
    env.reset()
    image = env.render()
    assert image.dtype == np.uint8 and image.shape[2] == 3 and image.shape[0] > 100
    task = pickle.loads(pickle.dumps(vivae.PredatorPreyTask(steps=10, scenario="predator-prey-obstacles")))
    assert task.steps == 10 and task.shape == (11, 2)


def coevolve(generations, **settings):
    """Two ask/tell populations, each genome scored against the other
    side's previous champion (in generation 0 its first genome), as
    `vivae evolve --task predator-prey` does by default: each generation's
    champions and their fitnesses."""
    task = vivae.PredatorPreyTask(**settings)
    hunters, prey = task.population("hunter"), task.population("prey")
    hall = []
    for _ in range(generations):
        hs, ps = hunters.ask(), prey.ask()
        assert hunters.champion is None, "a batch asked, not yet told"
        against_hunters = [hall[-1][2]] if hall else [ps[0]]
        against_prey = [hall[-1][0]] if hall else [hs[0]]
        hunters.tell(task.evaluate("hunter", hs, against_hunters))
        prey.tell(task.evaluate("prey", ps, against_prey))
        (h, hf), (p, pf) = hunters.champion, prey.champion
        hall.append((h, hf, p, pf))
    return hall


def test_two_ask_tell_populations_coevolve_as_the_cli_run_does(tmp_path: Path):
    settings = dict(population=12, steps=100, seed=3)
    hall = coevolve(3, **settings)
    assert [(h.to_json(), hf) for h, hf, _, _ in hall] == [
        (h.to_json(), hf) for h, hf, _, _ in coevolve(3, **settings)
    ], "the same seed, the same co-evolution"
    vivae.evolve(out=tmp_path / "run", task="predator-prey", generations=3, progress=False, **settings)
    lines = [json.loads(x) for x in (tmp_path / "run" / "hall-of-fame.jsonl").read_text().splitlines()]
    ran = {(e["side"], e["generation"]): e for e in lines}
    assert len(ran) == 6
    for g, (h, hf, p, pf) in enumerate(hall):
        for side, genome, fitness in (("hunter", h, hf), ("prey", p, pf)):
            assert json.loads(genome.to_json()) == ran[side, g]["genome"], (side, g)
            assert fitness == ran[side, g]["fitness"], (side, g)
    # Another seed co-evolves differently.
    other = coevolve(3, **{**settings, "seed": 4})
    assert [h.to_json() for h, *_ in other] != [h.to_json() for h, *_ in hall]
