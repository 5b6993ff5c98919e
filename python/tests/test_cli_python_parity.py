"""The command line and Python resolve settings through the library's one
preparation: the same flags and keywords give byte-identical config.toml and
the same first generation, for every task and every strategy; what one
refuses, the other refuses with the same reason."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

import vivae

SMALL = dict(generations=1, seed=3, threads=1)


def flags_of(settings: dict) -> list[str]:
    """The CLI flags that mean `settings` (keyword names are the flags' names)."""
    out: list[str] = []
    for key, value in settings.items():
        flag = "--" + key.replace("_", "-")
        if key == "scenario" and isinstance(value, list):
            for v in value:
                out += [flag, v]
        elif isinstance(value, list):
            out += [flag, ",".join(value)]
        elif isinstance(value, bool):
            out += [flag, "true" if value else "false"]
        else:
            out += [flag, str(value)]
    return out


def strategies() -> list[str]:
    return list(vivae.STRATEGIES)


def tasks() -> list[str]:
    # A task whose episodes a host plays (Gymnasium's, from Python) the
    # program refuses to evolve (vivae.gym.evolve runs it; tests/test_gym.py
    # checks that run and the program's refusal).
    return [t for t in vivae.TASKS if t not in vivae.HOSTED_TASKS]


def size_for(task: str) -> dict:
    # A short episode and a small population keep each run below a second.
    if task == "driving":
        return dict(population=12, steps=40)
    return dict(population=12)


def cases() -> list[tuple[str, dict]]:
    table: list[tuple[str, dict]] = []
    for task in tasks():
        for strategy in strategies():
            table.append((f"{task}-{strategy}", dict(task=task, strategy=strategy, **size_for(task))))
    table += [
        # The maze's scenario alone names its task.
        ("hard-maze-alone", dict(scenario="hard-maze", population=12)),
        ("fast-precision", dict(precision="fast", population=12, steps=40)),
        ("several-maps", dict(scenario=["roads", "oval"], robots=1, population=12, steps=40)),
        ("resolutions", dict(sensors="3x6", neurons="5x5", train_neurons=["3x3", "5x5"], population=12, steps=30)),
        ("wiring", dict(recurrence="self", normalize_self_loops=False, population=12, steps=30)),
        ("es-hyperneat", dict(substrate="es-hyperneat", population=12, steps=30)),
        ("placements", dict(scenario="obstacles-random", placements=2, placements_aggregate="min", population=12,
                            steps=30, distance_rays=5)),
        ("behaviour", dict(strategy="map-elites", behaviour="end-position", population=12, steps=30)),
        ("maze-robot", dict(task="maze", robot="vivae", population=12)),
        ("refused-robot", dict(robot="vivae", population=12, steps=30)),
        ("refused-robots", dict(scenario="hard-maze", robots=5)),
    ]
    return table


def reason(message: str, origin: str) -> str:
    """A refusal without who says it and where the settings came from, a
    setting spelled as Python does (`--train-neurons 3x3` → `train_neurons=3x3`)."""
    message = message.removeprefix("error: ").removeprefix(origin)
    return re.sub(r"^--([a-z-]+) ", lambda m: m.group(1).replace("-", "_") + "=", message)


def first_generation(run: Path) -> str | None:
    """The first data row of the run's per-generation record (the driver's
    own file for a task that runs on its own driver)."""
    for name in ("generations.csv", "hunters.csv"):
        path = run / name
        if path.exists():
            return path.read_text().splitlines()[1]
    return None


@pytest.mark.parametrize("name, settings", cases(), ids=[c[0] for c in cases()])
def test_flags_and_keywords_resolve_to_the_same_run(tmp_path, cli, name, settings):
    settings = {**SMALL, **settings}
    theirs, ours = tmp_path / "cli", tmp_path / "py"
    done = subprocess.run([cli, "evolve", "-q", "--out", str(theirs), *flags_of(settings)],
                          capture_output=True, text=True)
    try:
        vivae.evolve(out=ours, progress=False, **settings)
        refused = None
    except (ValueError, TypeError) as e:
        refused = str(e)
    if done.returncode != 0:
        # Refused by both, for the same reason (each names the setting its own way).
        assert done.returncode == 2, done.stderr
        assert refused is not None, f"the CLI refused ({done.stderr.strip()}), Python ran"
        assert reason(done.stderr.strip().splitlines()[-1], "command line: ") == reason(refused, "arguments: ")
        return
    assert refused is None, f"Python refused ({refused}), the CLI ran"
    assert (ours / "config.toml").read_bytes() == (theirs / "config.toml").read_bytes()
    assert first_generation(ours) is not None
    assert first_generation(ours) == first_generation(theirs)


def test_the_table_covers_every_task_and_strategy():
    names = {c[0] for c in cases()}
    for task in tasks():
        for strategy in strategies():
            assert f"{task}-{strategy}" in names
    assert len(tasks()) >= 3 and len(strategies()) >= 4
