"""The package itself: typed stubs that match the module, portable math, docstrings."""

from __future__ import annotations

import subprocess
import sys

import pytest

import vivae
from vivae import _vivae


def test_the_stubs_match_the_native_module_and_the_package(tmp_path):
    pytest.importorskip("mypy")
    done = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "--ignore-disjoint-bases", "vivae"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_svg_stack_calls_the_portable_math_functions():
    # As the CLI does: a scenario's geometry has the same bits on every CPU.
    assert _vivae.math_is_portable()


def test_every_public_name_is_documented():
    for name in vivae.__all__:
        thing = getattr(vivae, name)
        if callable(thing):
            assert thing.__doc__ and thing.__doc__.strip(), name
    for cls in (vivae.Population, vivae.Genome, vivae.DriveTask):
        for attr, member in vars(cls).items():
            if not attr.startswith("_") and callable(member):
                assert member.__doc__, f"{cls.__name__}.{attr}"
