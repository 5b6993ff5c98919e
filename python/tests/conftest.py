"""Shared helpers of the vivae Python tests."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def vivae_binary() -> str | None:
    """The `vivae` program to compare with: $VIVAE_BIN, else the workspace's release build, else PATH."""
    given = os.environ.get("VIVAE_BIN")
    if given:
        return given
    for target in filter(None, [os.environ.get("CARGO_TARGET_DIR"), str(REPO / "target")]):
        candidate = Path(target) / "release" / "vivae"
        if candidate.is_file():
            return str(candidate)
    return shutil.which("vivae")


@pytest.fixture
def cli() -> str:
    """The `vivae` binary; CI (VIVAE_REQUIRE_CLI=1) fails rather than skips without one."""
    found = vivae_binary()
    if found is None:
        if os.environ.get("VIVAE_REQUIRE_CLI") == "1":
            pytest.fail("no vivae binary (set VIVAE_BIN or build it with cargo build --release -p vivae)")
        pytest.skip("no vivae binary to compare with (set VIVAE_BIN)")
    return found
