#!/usr/bin/env bash
# Creates the venv for bench.py: JAX (CPU) and TensorNEAT at a pinned commit.
#
#   TENSORNEAT_SRC=/path/to/tensorneat bash setup.sh [VENV]     (default VENV=/work/tnvenv)
#
# TENSORNEAT_SRC is a checkout of TensorNEAT (EMI-Group/tensorneat) at commit
# ee204900e8e55ffe0ed756651ea871c70230dd34; the script checks the commit when it
# is a git checkout. Without TENSORNEAT_SRC it asks pip for the same commit from
# its git source (this needs access to that host; the machine these figures were
# taken on had none, so they were taken with a local copy of that commit).
# Every other package comes from PyPI at the version in requirements-freeze.txt
# (what pip resolved on 2026-12-04 for tensorneat's own requirements: jax and
# jaxlib 0.10.2, numpy 2.4.6, brax 0.14.2, gymnax 1.0.1, ...).
set -euo pipefail
VENV=${1:-/work/tnvenv}
COMMIT=ee204900e8e55ffe0ed756651ea871c70230dd34
python3 -m venv "$VENV"
"$VENV/bin/pip" install -q --upgrade pip
"$VENV/bin/pip" install -q -r "$(dirname "$0")/requirements-freeze.txt"
if [ -n "${TENSORNEAT_SRC:-}" ]; then
  if [ -d "$TENSORNEAT_SRC/.git" ]; then
    got=$(git -C "$TENSORNEAT_SRC" rev-parse HEAD)
    [ "$got" = "$COMMIT" ] || { echo "setup.sh: $TENSORNEAT_SRC is at $got, expected $COMMIT" >&2; exit 1; }
  fi
  "$VENV/bin/pip" install -q --no-deps "$TENSORNEAT_SRC"
else
  "$VENV/bin/pip" install -q --no-deps "tensorneat @ git+https://github.com/EMI-Group/tensorneat@$COMMIT"
fi
"$VENV/bin/python" -c 'import jax, tensorneat.pipeline; print("jax", jax.__version__, jax.devices())'
