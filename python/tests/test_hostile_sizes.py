"""Sizes are bounded before anything is allocated: a request too large for
memory is a MemoryError or a ValueError naming the argument, never an abort
of the interpreter."""

from __future__ import annotations

import numpy as np
import pytest

import vivae


@pytest.mark.parametrize("inputs, outputs, size", [(10**9, 1, 2), (2, 10**8, None), (10**6, 10**6, 1),
                                                   (2**63, 1, 1)])
def test_a_population_too_large_for_memory_is_a_memory_error(inputs, outputs, size):
    with pytest.raises((MemoryError, ValueError, OverflowError), match="inputs|outputs|size|int"):
        vivae.Population(inputs, outputs, size=size)


@pytest.mark.parametrize("make", [
    lambda: vivae.NoveltySearch(10**9, 1),
    lambda: vivae.Nsga2(10**9, 1, objectives=[("fitness", "max")]),
    lambda: vivae.MapElites(10**9, 1, lower=[0], upper=[1], bins=[4]),
])
def test_every_ask_tell_class_bounds_its_genomes(make):
    with pytest.raises(MemoryError, match="genes"):
        make()


def test_too_many_genomes_names_the_size():
    with pytest.raises(ValueError, match="population_size"):
        vivae.Population(3, 1, size=10**7)


def test_too_many_worlds_names_the_range():
    with pytest.raises(ValueError, match=r"num_worlds = 1000000000: expected 1 to \d+"):
        vivae.DriveVectorEnv(10**9)
    with pytest.raises(ValueError, match=r"num_worlds = 0: expected 1 to \d+"):
        vivae.DriveVectorEnv(0)


@pytest.mark.parametrize("value", [-1, 10**30])
def test_negative_or_huge_sizes_are_refused(value):
    with pytest.raises((ValueError, OverflowError, TypeError)):
        vivae.Population(3, 1, size=value)


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(num_envs=-1), ValueError, "num_envs=-1: expected an integer from 1"),
    (dict(num_envs=2.5), TypeError, "num_envs: expected an integer"),
    (dict(num_envs=2, threads=-1), ValueError, "threads=-1: expected an integer from 0"),
])
def test_vector_env_counts_name_themselves(kwargs, error, message):
    with pytest.raises(error, match=message):
        vivae.DriveVectorEnv(**kwargs)


# Every size, count, seed and index argument: a negative or out-of-range
# value is a ValueError naming the argument and its range (not pyo3's
# nameless OverflowError), anything but an integer a TypeError naming it.
def _task():
    return vivae.DriveTask(scenario="oval", steps=5, population=4)


def _core():
    from vivae._vivae import DriveCore

    return DriveCore(1, scenario="oval", steps=5)


def _new_core(*args, **kwargs):
    from vivae._vivae import DriveCore

    return DriveCore(*args, **kwargs)


OBJECTIVES = [("fitness", "max")]
SIZES = [
    ("inputs", lambda v: vivae.Population(v, 1)),
    ("outputs", lambda v: vivae.Population(3, v)),
    ("size", lambda v: vivae.Population(3, 1, size=v)),
    ("seed", lambda v: vivae.Population(3, 1, seed=v)),
    ("size", lambda v: vivae.NoveltySearch(3, 1, size=v)),
    ("seed", lambda v: vivae.NoveltySearch(3, 1, seed=v)),
    ("size", lambda v: vivae.Nsga2(3, 1, objectives=OBJECTIVES, size=v)),
    ("seed", lambda v: vivae.Nsga2(3, 1, objectives=OBJECTIVES, seed=v)),
    ("inputs", lambda v: vivae.MapElites(v, 1, lower=[0], upper=[1], bins=[4])),
    ("bins[0]", lambda v: vivae.MapElites(3, 1, lower=[0], upper=[1], bins=[v])),
    ("cvt_cells", lambda v: vivae.MapElites(3, 1, lower=[0], upper=[1], cvt_cells=v)),
    ("cvt_samples", lambda v: vivae.MapElites(3, 1, lower=[0], upper=[1], cvt_cells=4, cvt_samples=v)),
    ("cvt_iterations", lambda v: vivae.MapElites(3, 1, lower=[0], upper=[1], cvt_cells=4, cvt_iterations=v)),
    ("seed", lambda v: vivae.MapElites(3, 1, lower=[0], upper=[1], bins=[4], seed=v)),
    ("size", lambda v: _task().population(size=v)),
    ("seed", lambda v: _task().population(seed=v)),
    ("robots", lambda v: _task().controller(_task().population().ask()[0], robots=v)),
    ("generation", lambda v: _task().save_champion(_task().population().ask()[0], "x.json", 1.0, v)),
    ("size", lambda v: vivae.PredatorPreyTask(steps=5).population("hunter", size=v)),
    ("seed", lambda v: vivae.PredatorPreyTask(steps=5).population("hunter", seed=v)),
    ("num_worlds", lambda v: _new_core(v)),
    ("threads", lambda v: _new_core(1, threads=v)),
    ("index", lambda v: _core().elapsed(v)),
    ("index", lambda v: _core().odometers(v)),
    ("index", lambda v: _core().render(v)),
    ("steps", lambda v: _core().run_random(v)),
    ("seed", lambda v: _core().run_random(1, seed=v)),
    ("generations", lambda v: vivae.resume("no-such-run", generations=v)),
    ("threads", lambda v: vivae.resume("no-such-run", threads=v)),
    ("threads", lambda v: vivae.tournament("no-such-run", "no-such-run", threads=v)),
    ("runs", lambda v: vivae.reproduce("no-such-pack", runs=v)),
    ("seed", lambda v: vivae.reproduce("no-such-pack", seed=v)),
    ("evaluations", lambda v: vivae.reproduce("no-such-pack", evaluations=v)),
    ("threads", lambda v: vivae.reproduce("no-such-pack", threads=v)),
    ("generation", lambda v: vivae.export("no-such-run", "json", "x.json", generation=v)),
    ("elite", lambda v: vivae.export("no-such-run", "json", "x.json", elite=v)),
    ("front", lambda v: vivae.export("no-such-run", "json", "x.json", front=v)),
    ("robot", lambda v: vivae.record_episode("no-such-run", robot=v)),
    ("steps", lambda v: vivae.record_episode("no-such-run", steps=v)),
    ("generation", lambda v: vivae.record_episode("no-such-run", generation=v)),
    ("elite", lambda v: vivae.drive_image("no-such-run", [], elite=v)),
    ("front", lambda v: vivae.drive_image("no-such-run", [], front=v)),
    ("generation", lambda v: vivae.drive_image("no-such-run", [], generation=v)),
]


@pytest.mark.parametrize("name, make", SIZES, ids=[f"{n}-{i}" for i, (n, _) in enumerate(SIZES)])
@pytest.mark.parametrize("value", [-1, -5, 10**40])
def test_every_size_count_seed_and_index_names_itself_and_its_range(name, make, value):
    import re

    with pytest.raises(ValueError, match=rf"^{re.escape(name)}={value}: expected an integer from \d+ to \d+"):
        make(value)


@pytest.mark.parametrize("name, make", SIZES, ids=[f"{n}-{i}" for i, (n, _) in enumerate(SIZES)])
@pytest.mark.parametrize("value", [2.5, "3", True])
def test_every_size_count_seed_and_index_of_another_type_is_a_type_error(name, make, value):
    with pytest.raises(TypeError, match=rf"{name.split('[')[0]}.*expected an integer, got"):
        make(value)


def test_numpy_integers_are_integers():
    pop = vivae.Population(np.int64(3), np.uint8(1), size=np.int32(10), seed=np.uint64(4))
    assert pop.size == 10


def test_a_controller_drives_one_to_as_many_robots_as_worlds():
    task = _task()
    genome = task.population().ask()[0]
    with pytest.raises(ValueError, match=r"robots=0: expected an integer from 1 to 65536"):
        task.controller(genome, robots=0)
    with pytest.raises(ValueError, match=r"robots=1000000: expected an integer from 1 to 65536"):
        task.controller(genome, robots=10**6)
    assert task.controller(genome, robots=3).act(np.zeros((3, 15))).shape == (3, 2)


@pytest.mark.parametrize("make", [
    lambda v: vivae.DriveEnv(scenario="oval", robots=v),
    lambda v: vivae.DriveVectorEnv(2, scenario="oval", robots=v),
    lambda v: __import__("gymnasium").make("vivae/Drive-v0", scenario="oval", robots=v),
    lambda v: __import__("gymnasium").make_vec("vivae/Drive-v0", num_envs=2, vectorization_mode="vector_entry_point", scenario="oval", robots=v),
])
def test_environments_of_one_robot_per_world_refuse_another_count(make):
    for v in (-1, 0, 3):
        with pytest.raises(ValueError, match=rf"robots={v}: expected 1"):
            make(v)
    with pytest.raises(TypeError, match="robots: expected an integer"):
        make("3")
    make(1)


@pytest.mark.parametrize("make", [
    lambda: vivae.DriveEnv(scenario="oval", steps=-5),
    lambda: vivae.DriveVectorEnv(2, scenario="oval", steps=-5),
    lambda: vivae.DriveParallelEnv(scenario="oval", steps=-5),
    lambda: vivae.DriveParallelEnv(scenario="oval", robots=-5),
    lambda: vivae.PredatorPreyParallelEnv(steps=-5),
])
def test_negative_steps_and_robots_of_every_environment_are_named(make):
    pytest.importorskip("pettingzoo")
    with pytest.raises(ValueError, match=r"(steps|robots)=-5: expected an integer from 0 to \d+"):
        make()
