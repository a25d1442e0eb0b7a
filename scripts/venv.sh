#!/usr/bin/env bash
# Make .venv (with $PYTHON, python3 by default) unless it exists, and install curvefold
# into it in editable mode with the extra named by the first argument.
set -euo pipefail
cd "$(dirname "$0")/.."

PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e ".[$1]"
