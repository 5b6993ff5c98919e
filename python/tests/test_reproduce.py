"""vivae.reproduce runs a replication pack as `vivae reproduce` does and returns its table as data."""

from __future__ import annotations

import subprocess

import pytest

import vivae


def test_reproduce_returns_the_clis_table_as_data(tmp_path, cli):
    table = vivae.reproduce("maze-hard", runs=2, seed=3, evaluations=1000, threads=1)
    assert table["columns"][:2] == ["method", "ours: solved"]
    assert [r[0] for r in table["rows"]] == ["novelty search", "fitness-based NEAT", "MAP-Elites (10-unit grid)"]
    assert all(r[1].endswith("/2") for r in table["rows"])
    assert table["rows"][0][4] == "39/40"
    out = tmp_path / "t.md"
    printed = subprocess.run(
        [cli, "reproduce", "maze-hard", "--runs", "2", "--seed", "3", "--evaluations", "1000", "--threads", "1",
         "-q", "-o", str(out)],
        check=True, capture_output=True, text=True,
    ).stdout
    assert printed == table["markdown"] == out.read_text()
    assert ("maze-hard", vivae.reproduce_packs()[1][1]) in vivae.reproduce_packs()


def test_an_unknown_pack_is_a_value_error_naming_the_packs():
    with pytest.raises(ValueError, match="maze-medium"):
        vivae.reproduce("maze-huge")


def test_every_pack_runs_at_tiny_settings_and_returns_its_table():
    names = [name for name, _ in vivae.reproduce_packs()]
    assert {"xor", "pole-markov", "pole-nonmarkov", "boxes", "retina", "road", "gym-classic"} <= set(names)
    for name in names:
        table = vivae.reproduce(name, runs=1, evaluations=200, threads=1)
        assert table["rows"], name
        assert all(len(r) == len(table["columns"]) for r in table["rows"]), name
        assert table["columns"][-1] == "source", name
        assert table["markdown"].startswith("### "), name


def test_a_journal_skips_finished_runs_and_methods_pick_rows(tmp_path):
    journal = tmp_path / "runs.tsv"
    first = vivae.reproduce("maze-hard", runs=2, seed=2, evaluations=1000, threads=1,
                            methods=["neat"], journal=journal)
    assert first["rows"][0][1] == "not run (--method)"
    assert first["rows"][1][1].endswith("/2")
    assert len([line for line in journal.read_text().splitlines() if not line.startswith("#")]) == 2
    again = vivae.reproduce("maze-hard", runs=2, seed=2, evaluations=1000, threads=1, journal=journal)
    assert again["rows"][1] == first["rows"][1]
    fresh = vivae.reproduce("maze-hard", runs=2, seed=2, evaluations=1000, threads=1)
    assert fresh["rows"] == again["rows"]
    with pytest.raises(ValueError, match="no method"):
        vivae.reproduce("maze-hard", methods=["cma-es"])


def test_gym_classic_validates_each_champion_as_the_cli_does(tmp_path, cli):
    table = vivae.reproduce("gym-classic", runs=2, seed=5, evaluations=300, threads=1, methods=["cartpole", "acrobot"])
    assert [r[0] for r in table["rows"]] == ["cartpole", "acrobot"]
    assert [r[1] for r in table["rows"]] == ["475", "-100"]
    assert all(r[2].endswith("/2") and r[3].endswith("/2") for r in table["rows"])
    assert "100 fresh episodes" in " ".join(table["notes"])
    out = tmp_path / "g.md"
    printed = subprocess.run(
        [cli, "reproduce", "gym-classic", "--runs", "2", "--seed", "5", "--evaluations", "300", "--threads", "1",
         "--method", "cartpole,acrobot", "-q", "--no-journal", "-o", str(out)],
        check=True, capture_output=True, text=True,
    ).stdout
    # The same runs, so the same table but for the wall times (column 5).
    strip = lambda md: [line.split(" | ")[:5] + line.split(" | ")[6:] for line in md.splitlines()]
    assert strip(printed) == strip(table["markdown"])
