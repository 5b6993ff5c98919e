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


@pytest.mark.parametrize("num_worlds", [0, 10**9])
def test_too_many_worlds_names_the_range(num_worlds):
    with pytest.raises(ValueError, match=rf"num_worlds = {num_worlds}: expected 1 to \d+"):
        vivae.DriveVectorEnv(num_worlds)


@pytest.mark.parametrize("value", [-1, 10**30])
def test_negative_or_huge_sizes_are_refused(value):
    with pytest.raises((ValueError, OverflowError, TypeError)):
        vivae.Population(3, 1, size=value)
