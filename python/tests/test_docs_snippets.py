"""Every ```python block of docs/python.md runs alone, as written, in a fresh
interpreter (its own working directory), so that the documentation cannot
drift from the package."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys

import pytest

from conftest import REPO

DOC = REPO / "docs" / "python.md"
SNIPPETS = re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)


def test_the_page_has_snippets():
    assert len(SNIPPETS) >= 5


@pytest.mark.parametrize("index", range(len(SNIPPETS)))
def test_each_snippet_runs_alone(index, tmp_path):
    code = SNIPPETS[index]
    for module in re.findall(r"^(?:import|from) (\w+)", code, flags=re.M):
        if importlib.util.find_spec(module) is None:
            pytest.skip(f"snippet {index + 1} needs {module}, which is not installed")
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, f"snippet {index + 1}:\n{code}\n{done.stderr[-3000:]}"
