#!/usr/bin/env bash
# Set up what the tests need (scripts/setup.sh with the "all,test,lint" extras: every optional
# feature, the test tools and the type checker, the Node.js readers, the designer's ESLint, the
# system packages) and run the test suite; extra arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh all,test,lint
# The Node.js readers were just installed: a test that needs them must not skip.
CURVEFOLD_REQUIRE_NODE=1 .venv/bin/python -m pytest "$@"
