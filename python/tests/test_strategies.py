"""Novelty search, MAP-Elites and NSGA-II driven ask/tell from Python."""

from __future__ import annotations

import pytest

import vivae

CASES = [((0.0, 0.0), 0.0), ((0.0, 1.0), 1.0), ((1.0, 0.0), 1.0), ((1.0, 1.0), 0.0)]


def xor(genome: vivae.Genome) -> tuple[float, list[float]]:
    """XOR fitness, and the four outputs as the behaviour."""
    net = genome.network()
    outputs = [net.activate([a, b, 1.0])[0] for (a, b), _ in CASES]
    error = sum(abs(o - want) for o, (_, want) in zip(outputs, CASES))
    return (4.0 - error) ** 2, outputs


def run(strategy, generations: int, measure):
    for _ in range(generations):
        told = [measure(g) for g in strategy.ask()]
        strategy.tell(
            [t[0] for t in told],
            behaviours=[t[1] for t in told],
            metrics=[t[2] for t in told] if len(told[0]) > 2 else None,
        )
    return strategy


def test_novelty_search_archives_novel_behaviours_and_restores_bit_for_bit():
    ns = vivae.NoveltySearch(3, 1, seed=2, size=50, novelty={"k": 10, "threshold": 0.3})
    run(ns, 15, xor)
    assert ns.generation == 14
    assert len(ns.archive) > 0 and all(len(b) == 4 for b in ns.archive)
    assert len(ns.novelty) == 50 and max(ns.novelty) > 0.0
    restored = vivae.NoveltySearch.from_json(ns.to_json())
    for s in (ns, restored):
        run(s, 3, xor)
    assert restored.to_json() == ns.to_json()
    genome, fitness, generation = ns.best_ever
    assert xor(genome)[0] == fitness and generation <= ns.generation


def test_map_elites_fills_cells_with_their_best_genomes():
    me = vivae.MapElites(3, 1, lower=[0.0, 0.0], upper=[1.0, 1.0], bins=[5, 5], seed=3)
    assert me.cells == 25
    me.tell([0.0] * len(me.ask()), behaviours=[[0.5, 0.5]] * 100)
    assert me.archive_stats()["filled"] == 1

    def two_outputs(genome):
        fitness, out = xor(genome)
        return fitness, [out[1], out[2]]

    run(me, 30, two_outputs)
    stats = me.archive_stats()
    assert stats["filled"] > 5 and stats["coverage"] == stats["filled"] / 25
    elites = me.elites()
    assert len(elites) == stats["filled"]
    for e in elites:
        # Each elite sits in the cell its behaviour falls in and is its genome's best.
        assert me.cell_of(e["behaviour"]) == e["cell"]
        assert abs(two_outputs(e["genome"])[0] - e["fitness"]) < 1e-9
    assert stats["qd_score"] == pytest.approx(sum(e["fitness"] for e in elites))
    cvt = vivae.MapElites(3, 1, lower=[0.0], upper=[1.0], cvt_cells=7, cvt_samples=700)
    assert cvt.cells == 7


def test_nsga2_keeps_a_front_no_member_of_which_dominates_another():
    def fitness_and_size(genome):
        fitness, out = xor(genome)
        return fitness, out, [float(genome.num_links)]

    ns = vivae.Nsga2(3, 1, objectives=[("fitness", "max"), (0, "min")], size=40, seed=5)
    run(ns, 20, fitness_and_size)
    front = ns.pareto_front()
    assert front
    points = [(objs[0], objs[1]) for _, objs, _ in front]
    for (f1, s1) in points:
        for (f2, s2) in points:
            assert not (f1 >= f2 and s1 <= s2 and (f1 > f2 or s1 < s2))
    for genome, objs, fitness in front:
        assert objs[0] == fitness and objs[1] == genome.num_links
    restored = vivae.Nsga2.from_json(ns.to_json())
    for s in (ns, restored):
        run(s, 2, fitness_and_size)
    assert restored.to_json() == ns.to_json()


def test_bad_strategy_settings_are_value_errors():
    with pytest.raises(ValueError, match="novelty"):
        vivae.NoveltySearch(3, 1, novelty={"kk": 3})
    with pytest.raises(ValueError, match="bins= or cvt_cells="):
        vivae.MapElites(3, 1, lower=[0.0], upper=[1.0], bins=[3], cvt_cells=3)
    with pytest.raises(ValueError):
        vivae.MapElites(3, 1, lower=[1.0], upper=[0.0], bins=[3])
    with pytest.raises(ValueError, match="expected \"max\" or \"min\""):
        vivae.Nsga2(3, 1, objectives=[("fitness", "up")])
    with pytest.raises(ValueError, match="metric"):
        vivae.Nsga2(3, 1, objectives=[("speed", "max")])
    ns = vivae.Nsga2(3, 1, objectives=[("fitness", "max")], size=10)
    ns.ask()
    with pytest.raises(ValueError, match="9"):
        ns.tell([0.0] * 9)
    with pytest.raises(ValueError, match="metrics"):
        ns.tell([0.0] * 10, metrics=[[1.0]] * 3)
    with pytest.raises(ValueError):
        vivae.MapElites.from_json("{}")
