"""Sizes are bounded before anything is allocated: a request too large for
memory is a MemoryError or a ValueError naming the argument, never an abort
of the interpreter."""

from __future__ import annotations

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
