#!/usr/bin/env bash
# Set up from scratch (see setup.sh) and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# The Node.js readers were just installed: a test that needs them must not skip.
CURVEFOLD_REQUIRE_NODE=1 .venv/bin/python -m pytest "$@"
