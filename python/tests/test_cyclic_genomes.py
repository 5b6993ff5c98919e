"""A genome whose links form a cycle is recurrent wherever it is built or
loaded: activated as a feed-forward network it would silently compute
something else."""

from __future__ import annotations

import json

import pytest

import vivae

NODES = [{"id": 0, "kind": "input", "activation": "linear"},
         {"id": 1, "kind": "output", "activation": "sigmoid"},
         {"id": 2, "kind": "hidden", "activation": "bipolar_sigmoid"}]


def genome(links, recurrent=False):
    text = json.dumps({"nodes": NODES, "links": [
        {"innovation": i, "from": a, "to": b, "weight": w, "enabled": True}
        for i, (a, b, w) in enumerate(links)]})
    return vivae.Genome.from_json(text, recurrent=recurrent)


def test_a_cycle_makes_a_genome_recurrent():
    cyclic = genome([(0, 2, 1.0), (2, 1, 1.0), (1, 2, 0.8)])
    assert cyclic.recurrent
    assert genome([(0, 1, 1.0), (1, 1, 0.5)]).recurrent      # a self-loop is a cycle
    assert not genome([(0, 2, 1.0), (2, 1, 1.0)]).recurrent
    assert genome([(0, 2, 1.0), (2, 1, 1.0)], recurrent=True).recurrent


def test_a_cyclic_genome_keeps_state_between_activations():
    net = genome([(0, 2, 1.0), (2, 1, 1.0), (1, 2, 0.8)]).network()
    outs = [net.activate([1.0])[0] for _ in range(4)]
    assert len(set(outs)) > 1


def test_the_recurrent_flag_survives_json_and_pickle():
    import pickle

    cyclic = genome([(0, 1, 1.0), (1, 1, 0.5)])
    again = pickle.loads(pickle.dumps(cyclic))
    assert again.recurrent and again.to_json() == cyclic.to_json()


def has_cycle(genome: vivae.Genome) -> bool:
    """Depth-first search over the enabled links, independent of the Rust check."""
    data = json.loads(genome.to_json())
    nxt: dict = {}
    for link in data["links"]:
        if link["enabled"]:
            nxt.setdefault(link["from"], []).append(link["to"])
    state: dict = {}

    def visit(n) -> bool:
        state[n] = 1
        for m in nxt.get(n, []):
            if state.get(m) == 1 or (m not in state and visit(m)):
                return True
        state[n] = 2
        return False

    return any(n["id"] not in state and visit(n["id"]) for n in data["nodes"])


def test_a_maze_champion_is_recurrent_exactly_when_it_has_a_cycle(tmp_path):
    result = vivae.evolve(out=tmp_path / "maze", task="maze", generations=3, population=20, seed=1,
                          progress=False, threads=1)
    champion = result["champion"]
    loaded, _, _ = vivae.load_genome(tmp_path / "maze")
    assert champion.recurrent == loaded.recurrent == has_cycle(champion)
    pop = vivae.Population(3, 1, seed=2, size=50, recurrent=True)
    for _ in range(30):
        genomes = pop.ask()
        for g in genomes:
            assert g.recurrent
            plain = vivae.Genome.from_json(g.to_json())
            assert plain.recurrent == has_cycle(g)
        pop.tell([float(g.num_links) for g in genomes])


def cppn(links):
    """A CPPN of the driving task's shape (5 inputs, 3 outputs) with `links`."""
    nodes = [{"id": i, "kind": "input", "activation": "linear"} for i in range(5)]
    nodes += [{"id": 5 + o, "kind": "output", "activation": "bipolar_sigmoid"} for o in range(3)]
    text = json.dumps({"nodes": nodes, "links": [
        {"innovation": i, "from": a, "to": b, "weight": w, "enabled": True}
        for i, (a, b, w) in enumerate(links)]})
    return vivae.Genome.from_json(text)


def test_the_driving_task_refuses_a_cyclic_cppn_on_every_path(tmp_path):
    task = vivae.DriveTask(scenario="oval", steps=5, population=4)
    acyclic = [(i, 5 + o, 0.5) for i in range(5) for o in range(3)]
    fine = cppn(acyclic)
    cyclic = cppn(acyclic + [(5, 6, 1.0), (6, 5, 1.0)])
    assert cyclic.recurrent and not fine.recurrent
    paths = [
        lambda g: task.evaluate([g]),
        lambda g: task.controller(g),
        lambda g: task.decode(g),
        lambda g: task.episode(g),
        lambda g: task.save_champion(g, tmp_path / "c.json", 1.0),
    ]
    for path in paths:
        path(fine)
        with pytest.raises(ValueError, match="genome: its links form a cycle"):
            path(cyclic)
    # A recurrent population's genome without a cycle is still a CPPN.
    plain = vivae.Genome.from_json(fine.to_json(), recurrent=True)
    task.evaluate([plain])
