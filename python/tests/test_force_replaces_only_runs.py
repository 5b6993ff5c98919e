"""`vivae.evolve(force=True)` replaces a vivae run and nothing else: a folder of
the user's files, a run with a file of the user's, the working directory,
its parents and the home directory are refused with a one-line ValueError
and every file in them is left as it was."""

from __future__ import annotations

import os

import pytest

import vivae

SETTINGS = dict(scenario="oval", steps=60, population=8, generations=1, threads=1, progress=False)


def test_a_run_is_replaced(tmp_path):
    run = tmp_path / "run"
    vivae.evolve(out=run, seed=1, **SETTINGS)
    first = (run / "generations.csv").read_bytes()
    # Said in Python's words, not the command line's flags.
    with pytest.raises(ValueError, match=r"choose another out=, or pass force=True") as e:
        vivae.evolve(out=run, seed=2, **SETTINGS)
    assert "--" not in str(e.value)
    vivae.evolve(out=run, seed=2, force=True, **SETTINGS)
    assert (run / "generations.csv").read_bytes() != first
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_run_holding_a_file_of_the_users_is_refused(tmp_path):
    run = tmp_path / "run"
    vivae.evolve(out=run, seed=1, **SETTINGS)
    (run / "notes.txt").write_text("mine")
    (run / "checkpoints" / "keep.me").write_text("mine too")
    with pytest.raises(ValueError, match="which vivae did not write") as e:
        vivae.evolve(out=run, seed=2, force=True, **SETTINGS)
    assert len(str(e.value).splitlines()) == 1
    assert (run / "notes.txt").read_text() == "mine"
    assert (run / "checkpoints" / "keep.me").read_text() == "mine too"


def test_a_folder_of_the_users_files_is_refused(tmp_path):
    mine = tmp_path / "mine"
    (mine / "sub").mkdir(parents=True)
    (mine / "sub" / "data.csv").write_text("1,2\n")
    with pytest.raises(ValueError, match="is not a vivae run") as e:
        vivae.evolve(out=mine, force=True, **SETTINGS)
    said = str(e.value)
    assert "force=True replaces only a vivae run directory (choose another out=)" in said
    assert "--force" not in said and "--out" not in said
    assert (mine / "sub" / "data.csv").read_text() == "1,2\n"


@pytest.mark.parametrize("out, why", [(".", "is the working directory"),
                                      ("..", "is a parent of the working directory"),
                                      ("/", "is a parent of the working directory")])
def test_the_working_directory_and_its_parents_are_refused(tmp_path, monkeypatch, out, why):
    work = tmp_path / "work"
    work.mkdir()
    (work / "precious.txt").write_text("mine")
    monkeypatch.chdir(work)
    with pytest.raises(ValueError, match=why):
        vivae.evolve(out=out, force=True, **SETTINGS)
    assert (work / "precious.txt").read_text() == "mine"


def test_the_home_directory_is_refused(tmp_path, monkeypatch):
    home = tmp_path / "home"
    home.mkdir()
    (home / "thesis.tex").write_text("mine")
    monkeypatch.setenv("HOME", str(home))
    with pytest.raises(ValueError, match="is the home directory"):
        vivae.evolve(out=home, force=True, **SETTINGS)
    assert (home / "thesis.tex").read_text() == "mine"
    assert os.listdir(tmp_path) == ["home"]
