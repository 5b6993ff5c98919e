"""A plain task (CartPole-v1, on the task seam's plain adapter) from Python:
evolve to Gymnasium's threshold, resume bit-identically, the CLI's run,
report.html, its network exported; driving's settings refused by name."""

from __future__ import annotations

import json
import subprocess

import pytest

import vivae

# Gymnasium's CartPole-v1 reward_threshold.
THRESHOLD = 475.0
RESULTS = ["generations.csv", "population.csv", "champion.json", "best-genomes.jsonl", "config.toml"]


def test_cartpole_reaches_the_threshold_reports_and_exports(tmp_path):
    out = tmp_path / "run"
    r = vivae.evolve(out=out, task="cartpole", seed=1, generations=30, progress=False)
    assert r["solved"] and r["best"] >= THRESHOLD, r
    assert r["generations"] < 30, "a solved run stops"
    assert not (out / "scenario.svg").exists(), "a plain task loads no map"
    page = vivae.report(out)
    assert '"task":"cartpole"' in page.read_text()
    written = vivae.export(out, "json", tmp_path / "net.json")
    doc = json.loads((tmp_path / "net.json").read_text())
    assert written == [str(tmp_path / "net.json")]
    assert doc["substrate"] == "neat" and doc["net"]["inputs"] == 5


def test_cartpole_resumes_bit_identically(tmp_path):
    common = dict(task="cartpole", seed=5, population=30, strategy="nsga2", progress=False)
    vivae.evolve(out=tmp_path / "whole", generations=4, **common)
    vivae.evolve(out=tmp_path / "part", generations=2, **common)
    vivae.resume(tmp_path / "part", generations=4, progress=False)
    for name in RESULTS:
        assert (tmp_path / "whole" / name).read_bytes() == (tmp_path / "part" / name).read_bytes(), name


def test_the_cli_writes_the_same_cartpole_run(tmp_path, cli):
    vivae.evolve(out=tmp_path / "py", task="cartpole", seed=2, population=30, generations=3, progress=False)
    subprocess.run(
        [cli, "evolve", "-q", "--task", "cartpole", "--seed", "2", "--population", "30",
         "--generations", "3", "--out", str(tmp_path / "cli")],
        check=True, capture_output=True,
    )
    for name in RESULTS:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


@pytest.mark.parametrize(
    ("setting", "key"),
    [({"sensors": "5x7"}, "surface_sensors"), ({"robots": 2}, "experiment.robots"),
     ({"scenario": "oval"}, "experiment.scenario")],
)
def test_driving_settings_are_refused_by_name(tmp_path, setting, key):
    with pytest.raises(ValueError, match=f"{key}.*cartpole"):
        vivae.evolve(out=tmp_path / "run", task="cartpole", generations=2, progress=False, **setting)
    assert not (tmp_path / "run").exists()


# Gymnasium's reward_threshold of each other classic-control task (Pendulum
# has none; vivae's bar is -200).
THRESHOLDS = {"acrobot": -100.0, "mountain-car": -110.0, "mountain-car-continuous": 90.0, "pendulum": -200.0}


@pytest.mark.parametrize("task", list(THRESHOLDS))
def test_each_classic_control_task_evolves_to_its_threshold_from_python(tmp_path, task):
    out = tmp_path / "run"
    # MountainCar's seed 1 holds its check (by three standard errors) in
    # generation 36.
    r = vivae.evolve(out=out, task=task, seed=1, generations=40, progress=False)
    assert r["best"] >= THRESHOLDS[task], r
    if task == "pendulum":
        # Its genomes reach -200 on their 5 training episodes, but none holds
        # it on the 100 check episodes: the run does not stop.
        assert not r["solved"] and r["generations"] == 40, r
    else:
        assert r["solved"] and r["generations"] < 40, r
    assert f'"task":"{task}"' in vivae.report(out).read_text()


def test_a_classic_control_run_returns_and_writes_its_validation(tmp_path, cli):
    # Its champion on 100 fresh episodes: validation.json (vivae.gym.validate's
    # shape) and the result's "validation", the CLI's file byte for byte.
    common = ["--seed", "3", "--population", "20", "--generations", "3"]
    r = vivae.evolve(out=tmp_path / "py", task="cartpole", seed=3, population=20, generations=3, progress=False)
    v = json.loads((tmp_path / "py" / "validation.json").read_text())
    assert r["validation"] == v
    assert v["env"] == "cartpole" and v["episodes"] == 100 and v["seeds"] == [0, 99]
    assert v["reward_threshold"] == THRESHOLD and v["solved"] == (v["mean"] >= THRESHOLD)
    assert v["min"] <= v["mean"] <= v["max"] and v["std"] >= 0
    assert (v["generation"], v["fitness"]) == (r["champion_generation"], r["best"])
    subprocess.run([cli, "evolve", "-q", "--task", "cartpole", *common, "--out", str(tmp_path / "cli")],
                   check=True, capture_output=True)
    assert (tmp_path / "cli" / "validation.json").read_bytes() == (tmp_path / "py" / "validation.json").read_bytes()
    # A task without validation: none written, none returned.
    m = vivae.evolve(out=tmp_path / "maze", task="maze", population=10, generations=1, progress=False)
    assert "validation" not in m and not (tmp_path / "maze" / "validation.json").exists()
