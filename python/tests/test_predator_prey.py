"""The predator-prey task from Python: vivae.evolve(task="predator-prey")
co-evolves both populations and vivae.resume continues it bit for bit."""

from __future__ import annotations

from pathlib import Path

import vivae

FILES = [
    "config.toml",
    "hunters.csv",
    "prey.csv",
    "ciao.csv",
    "hall-of-fame.jsonl",
    "checkpoint.json",
    "champions.json",
]
SETTINGS = dict(task="predator-prey", population=12, steps=100, seed=3, progress=False)


def test_predator_prey_runs_and_resumes_bit_identical(tmp_path: Path) -> None:
    whole = vivae.evolve(out=tmp_path / "whole", generations=4, **SETTINGS)
    assert whole["task"] == "predator-prey"
    assert whole["generations"] == 4 and whole["finished"] is True
    for side in ("hunter", "prey"):
        assert 0 <= whole[f"{side}_champion_generation"] < 4
        assert 0.0 <= whole[f"{side}_master_fitness"] <= 2.0
    ciao = (tmp_path / "whole" / "ciao.csv").read_text().splitlines()
    assert ciao[0] == "hunter_generation,prey_generation,hunter_fitness,caught"
    assert sorted(tuple(map(int, r.split(",")[:2])) for r in ciao[1:]) == [
        (h, p) for h in range(4) for p in range(4)
    ]

    part = vivae.evolve(out=tmp_path / "part", generations=2, **SETTINGS)
    assert part["generations"] == 2
    resumed = vivae.resume(tmp_path / "part", generations=4, progress=False)
    assert resumed["generations"] == 4
    for name in FILES:
        assert (tmp_path / "whole" / name).read_bytes() == (tmp_path / "part" / name).read_bytes(), name


def test_a_python_run_draws_its_ciao_figure_and_report(tmp_path: Path) -> None:
    vivae.evolve(out=tmp_path / "run", generations=3, **SETTINGS)
    for name in ("figures/ciao.png", "figures/ciao.svg", "figures/coevolution.png", "figures/coevolution.svg",
                 "report.html"):
        assert (tmp_path / "run" / name).stat().st_size > 0, name
    svg = (tmp_path / "run" / "figures" / "ciao.svg").read_bytes()
    (tmp_path / "run" / "figures" / "ciao.svg").unlink()
    page = vivae.report(tmp_path / "run")
    assert Path(page) == tmp_path / "run" / "report.html"
    assert (tmp_path / "run" / "figures" / "ciao.svg").read_bytes() == svg
