"""vivae.export's `out` follows the CLI's `-o` rules: a file vivae did not
write is never replaced (unless force=True), nothing is written inside a run
directory, into a missing folder, through a link or over a special file, and
`out=""` is refused by name; each refusal is a ValueError naming the file."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import vivae


@pytest.fixture(scope="module")
def run(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("export-outputs") / "run"
    vivae.evolve(out=out, generations=2, steps=60, population=12, seed=7, progress=False)
    return out


def test_out_refuses_what_vivae_did_not_write(run, tmp_path):
    champion = run / "champion.json"
    before = champion.read_bytes()
    with pytest.raises(ValueError, match="inside the run directory"):
        vivae.export(run, "json", champion, force=True)
    assert champion.read_bytes() == before
    with pytest.raises(ValueError, match='out="": the file name is empty'):
        vivae.export(run, "json", "")
    with pytest.raises(ValueError, match="missing.*does not exist"):
        vivae.export(run, "json", tmp_path / "missing" / "c.json")
    assert not (tmp_path / "missing").exists()
    with pytest.raises(ValueError, match="ends in .h"):
        vivae.export(run, "c", tmp_path / "x.h")
    os.mkfifo(tmp_path / "pipe.onnx")
    with pytest.raises(ValueError, match="FIFO"):
        vivae.export(run, "onnx", tmp_path / "pipe.onnx", force=True)
    mine = tmp_path / "mine.json"
    mine.write_text("{}")
    (tmp_path / "link.json").symlink_to(mine)
    with pytest.raises(ValueError, match="symbolic link"):
        vivae.export(run, "json", tmp_path / "link.json", force=True)
    with pytest.raises(ValueError, match="mine.json.*force"):
        vivae.export(run, "json", mine)
    assert mine.read_text() == "{}"
    # An earlier export is replaced; with force=True, any regular file.
    assert vivae.export(run, "json", mine, force=True) == [str(mine)]
    assert vivae.export(run, "json", mine) == [str(mine)]
