"""Every public object pickles (genomes and ask/tell states by their JSON,
environments and tasks by their settings), objects whose thread pools ran
keep working in a forked child (`multiprocessing`'s default on Linux), and
genomes evaluated in other processes (fork, spawn, concurrent.futures, Ray)
give the same generations bit for bit as local evaluation."""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import pickle
from pathlib import Path

import numpy as np
import pytest

import vivae

XOR = [((0.0, 0.0), 0.0), ((0.0, 1.0), 1.0), ((1.0, 0.0), 1.0), ((1.0, 1.0), 0.0)]


def xor_fitness(genome: vivae.Genome) -> float:
    net = genome.network()
    error = sum(abs(net.activate([a, b, 1.0])[0] - want) for (a, b), want in XOR)
    return (4.0 - error) ** 2


def test_genomes_and_every_ask_tell_state_pickle_and_continue_bit_for_bit():
    for make in (lambda: vivae.Population(3, 1, seed=3),
                 lambda: vivae.NoveltySearch(3, 1, seed=3, size=20),
                 lambda: vivae.Nsga2(3, 1, seed=3, size=20, objectives=[("fitness", "max")]),
                 lambda: vivae.MapElites(3, 1, seed=3, lower=[0], upper=[1], bins=[4])):
        a = make()
        genomes = a.ask()
        assert [g.to_json() for g in pickle.loads(pickle.dumps(genomes))] == [g.to_json() for g in genomes]
        scores = [xor_fitness(g) for g in genomes]
        told = dict(behaviours=[[min(max(s / 16, 0), 1)] for s in scores])
        a.tell(scores, **told)
        b = pickle.loads(pickle.dumps(a))
        assert type(b) is type(a) and b.to_json() == a.to_json()
        assert [g.to_json() for g in a.ask()] == [g.to_json() for g in b.ask()]


def test_environments_and_tasks_pickle_by_their_settings():
    env = vivae.DriveEnv(scenario="oval", steps=30, sensors="3x6")
    env.reset(seed=0)
    env.step([1.0, 1.0])
    again = pickle.loads(pickle.dumps(env))
    assert again.observation_space == env.observation_space and again.max_steps == 30
    vec = pickle.loads(pickle.dumps(vivae.DriveVectorEnv(3, scenario="oval", steps=30, threads=2)))
    assert vec.num_envs == 3 and vec.threads == 2
    task = vivae.DriveTask(scenario="oval", steps=40, population=6)
    copy = pickle.loads(pickle.dumps(task))
    genomes = task.population().ask()
    assert copy.config_toml() == task.config_toml()
    assert copy.evaluate(genomes) == task.evaluate(genomes)


def test_environments_made_by_gymnasium_pickle():
    import gymnasium

    env = pickle.loads(pickle.dumps(gymnasium.make("vivae/Drive-v0", scenario="oval", steps=20)))
    obs, _ = env.reset(seed=0)
    assert obs.shape == (15,)
    vec = pickle.loads(pickle.dumps(gymnasium.make_vec("vivae/Drive-v0", num_envs=3, scenario="oval")))
    assert vec.reset(seed=0)[0].shape == (3, 15)


def test_the_parallel_env_pickles():
    pytest.importorskip("pettingzoo")
    env = pickle.loads(pickle.dumps(vivae.DriveParallelEnv(scenario="oval", steps=10)))
    obs, _ = env.reset(seed=0)
    assert set(obs) == set(env.possible_agents)


# Set before forking: the children inherit them, thread pools that already ran included.
INHERITED: dict = {}


def step_inherited(_):
    env = INHERITED["vec"]
    env.reset(seed=0)
    obs, rewards, *_ = env.step(np.ones((env.num_envs, 2), dtype=np.float32))
    task, genomes = INHERITED["task"], INHERITED["genomes"]
    return float(rewards.sum()), task.evaluate(genomes)


def test_objects_whose_thread_pools_ran_work_in_a_forked_child():
    vec = vivae.DriveVectorEnv(4, scenario="oval", steps=30, threads=2)
    vec.reset(seed=0)
    vec.step(np.zeros((4, 2), dtype=np.float32))
    task = vivae.DriveTask(scenario="oval", steps=40, population=6, threads=2)
    genomes = task.population().ask()
    local = task.evaluate(genomes)
    INHERITED.update(vec=vec, task=task, genomes=genomes)
    with multiprocessing.get_context("fork").Pool(2) as pool:
        results = pool.map(step_inherited, range(4))
    assert all(fitnesses == local for _, fitnesses in results)
    assert len({r for r, _ in results}) == 1


def evaluate_on(args):
    task, genome = args
    return task.evaluate([genome])[0]


def xor_of(genome):
    return xor_fitness(genome)


def generations(evaluate, n=4):
    pop = vivae.Population(3, 1, seed=5, size=30)
    history = []
    for _ in range(n):
        genomes = pop.ask()
        scores = evaluate(genomes)
        pop.tell(scores)
        history.append(scores)
    return history, pop.to_json()


@pytest.mark.parametrize("method", ["fork", "spawn"])
def test_multiprocessing_pools_evaluate_bit_for_bit(method):
    local = generations(lambda gs: [xor_fitness(g) for g in gs])
    with multiprocessing.get_context(method).Pool(2) as pool:
        assert generations(lambda gs: pool.map(xor_of, gs)) == local
    task = vivae.DriveTask(scenario="oval", steps=40, population=6, threads=2)
    genomes = task.population().ask()
    with multiprocessing.get_context(method).Pool(2) as pool:
        assert pool.map(evaluate_on, [(task, g) for g in genomes]) == task.evaluate(genomes)


def drive_generations(evaluate, n=3):
    """`n` generations of the driving task by ask/tell, each genome's fitness from `evaluate(task, genomes)`."""
    task = vivae.DriveTask(scenario="oval", steps=60, population=8, threads=1)
    pop = task.population()
    history = []
    for _ in range(n):
        genomes = pop.ask()
        scores = evaluate(task, genomes)
        pop.tell(scores)
        history.append(scores)
    return history, pop.to_json()


def test_a_process_pool_executor_evaluates_bit_for_bit():
    local = generations(lambda gs: [xor_fitness(g) for g in gs])
    drive_local = drive_generations(lambda task, gs: task.evaluate(gs))
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=ctx) as ex:
        assert generations(lambda gs: list(ex.map(xor_of, gs))) == local
        remote = drive_generations(lambda task, gs: list(ex.map(evaluate_on, [(task, g) for g in gs])))
    assert remote == drive_local


def test_a_local_ray_cluster_evaluates_bit_for_bit():
    ray = pytest.importorskip("ray", reason="ray is not installed (pip install ray)")
    local = generations(lambda gs: [xor_fitness(g) for g in gs])
    # The workers import this module to run its functions.
    here = str(Path(__file__).resolve().parent)
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False,
             runtime_env={"env_vars": {"PYTHONPATH": here}})
    try:
        remote = ray.remote(xor_of)
        assert generations(lambda gs: ray.get([remote.remote(g) for g in gs])) == local
        # The driving task (the engine) in Ray workers: the task travels by its settings.
        drive = ray.remote(evaluate_on)
        drive_local = drive_generations(lambda task, gs: task.evaluate(gs))
        assert drive_generations(lambda task, gs: ray.get([drive.remote((task, g)) for g in gs])) == drive_local
    finally:
        ray.shutdown()
