"""Python users get the whole run: `vivae.resume` continues an interrupted
run (or extends a finished one) to the files of an uninterrupted one, and
`vivae.report` draws the figures and report.html with the program's own code,
built into the package (no separate program)."""

from __future__ import annotations

import pytest

import vivae

SETTINGS = dict(scenario="oval", population=12, steps=60, seed=3, threads=2, progress=False)
SAME = ["config.toml", "generations.csv", "population.csv", "best-genomes.jsonl", "champion.json"]


def test_an_interrupted_run_resumes_to_the_uninterrupted_files(tmp_path):
    whole = tmp_path / "whole"
    vivae.evolve(out=whole, generations=4, **SETTINGS)

    def interrupt(record):
        if record["generation"] == 2:
            raise KeyboardInterrupt

    cut = tmp_path / "cut"
    with pytest.raises(KeyboardInterrupt, match=r"vivae\.resume\("):
        vivae.evolve(out=cut, generations=4, on_generation=interrupt, **SETTINGS)
    result = vivae.resume(cut, threads=1, progress=False)
    assert result["finished"] and result["generations"] == 4
    for name in SAME:
        assert (cut / name).read_bytes() == (whole / name).read_bytes(), name


def test_a_finished_run_is_extended(tmp_path):
    whole = tmp_path / "whole"
    vivae.evolve(out=whole, generations=3, **SETTINGS)
    short = tmp_path / "short"
    vivae.evolve(out=short, generations=2, **SETTINGS)
    vivae.resume(short, generations=3, progress=False)
    for name in ["generations.csv", "population.csv", "best-genomes.jsonl", "champion.json"]:
        assert (short / name).read_bytes() == (whole / name).read_bytes(), name
    with pytest.raises(ValueError, match="already has 3 generations"):
        vivae.resume(short, generations=2, progress=False)


def test_resume_of_a_folder_that_is_not_a_run_is_an_error(tmp_path):
    with pytest.raises((ValueError, OSError)):
        vivae.resume(tmp_path, progress=False)


def test_report_draws_the_figures_and_the_html_without_the_program(tmp_path, monkeypatch):
    # No `vivae` program anywhere: the package draws them itself.
    monkeypatch.delenv("VIVAE_BIN", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    run = tmp_path / "run"
    vivae.evolve(out=run, generations=2, **SETTINGS)
    assert not (run / "report.html").exists()
    before = (run / "generations.csv").read_bytes()
    path = vivae.report(run)
    assert path == run / "report.html" and path.is_file()
    assert (run / "figures" / "convergence.png").is_file()
    assert (run / "figures" / "trajectories-champion.png").is_file()
    assert (run / "generations.csv").read_bytes() == before


def test_report_draws_what_the_program_draws(tmp_path, cli):
    import subprocess

    ours, theirs = tmp_path / "ours", tmp_path / "theirs"
    for run in (ours, theirs):
        vivae.evolve(out=run, generations=2, **SETTINGS)
    vivae.report(ours)
    subprocess.run([cli, "resume", "-q", str(theirs)], check=True, capture_output=True)
    names = sorted(p.name for p in (theirs / "figures").iterdir())
    assert names == sorted(p.name for p in (ours / "figures").iterdir())
    for name in names:
        if name.endswith(".svg") or name.endswith(".txt"):
            assert (ours / "figures" / name).read_bytes() == (theirs / "figures" / name).read_bytes(), name


def test_report_of_a_folder_that_is_not_a_run_is_an_error(tmp_path):
    with pytest.raises((ValueError, OSError)):
        vivae.report(tmp_path)


def test_a_fast_run_keeps_its_precision_and_refuses_the_other(tmp_path):
    fast = tmp_path / "fast"
    vivae.evolve(out=fast, generations=2, precision="fast", **SETTINGS)
    assert 'precision = "fast"' in (fast / "config.toml").read_text()
    exact = tmp_path / "exact"
    vivae.evolve(out=exact, generations=2, **SETTINGS)
    assert "precision" not in (exact / "config.toml").read_text()
    assert (fast / "champion.json").read_bytes() != (exact / "champion.json").read_bytes()
    before = (fast / "generations.csv").read_bytes()
    with pytest.raises(ValueError, match="computes in fast precision"):
        vivae.resume(fast, generations=3, precision="exact", progress=False)
    assert (fast / "generations.csv").read_bytes() == before
    with pytest.raises(ValueError, match="expected exact or fast"):
        vivae.evolve(out=tmp_path / "bad", generations=2, precision="half", **SETTINGS)
    vivae.resume(fast, generations=3, precision="fast", progress=False)
    # A champion re-scored in the other precision (as `vivae replay --precision`).
    # 300 steps: long enough that some output is not saturated in either.
    own = vivae.replay(fast, steps=300)["fitness"]
    assert vivae.replay(fast, steps=300, precision="fast")["fitness"] == own
    assert vivae.replay(fast, steps=300, precision="exact")["fitness"] != own
