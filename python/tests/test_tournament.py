"""vivae.tournament plays one predator-prey run's champions against
another's, as `vivae tournament` does."""

import csv

import pytest

import vivae


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("pp")
    settings = dict(task="predator-prey", generations=3, population=12, steps=80)
    a = vivae.evolve(out=base / "a", seed=1, **settings)["out"]
    b = vivae.evolve(out=base / "b", seed=2, **settings)["out"]
    return base, a, b


def test_rows_for_both_directions_and_the_csv(runs):
    base, a, b = runs
    rows = vivae.tournament(a, b, threads=1, csv=base / "t.csv")
    assert len(rows) == 8
    assert {(r["hunters_run"], r["prey_run"]) for r in rows} == {(str(a), str(b)), (str(b), str(a))}
    hall = [r for r in rows if r["hunters"] == "hall" and r["prey"] == "hall"]
    assert [r["games"] for r in hall] == [9, 9]
    for r in rows:
        assert r["catches"] == round(r["catch_rate"] * r["games"])
        assert (r["mean_catch_step"] is None) == (r["catches"] == 0)
    with open(base / "t.csv", newline="") as f:
        written = list(csv.DictReader(f))
    assert [float(w["mean_hunter_fitness"]) for w in written] == [r["mean_hunter_fitness"] for r in rows]
    # The thread count does not change the games.
    assert vivae.tournament(a, b) == rows


def test_a_run_that_is_no_predator_prey_run_is_a_value_error(runs, tmp_path):
    _, a, _ = runs
    with pytest.raises((ValueError, OSError)):
        vivae.tournament(a, tmp_path / "missing")
