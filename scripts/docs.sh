#!/usr/bin/env bash
# Set up and build the documentation site into docs/_build/html (open its index.html):
# a virtual environment with curvefold and its docs extra, MathJax from npm (so that the
# equations render offline), then Sphinx with warnings as errors, every cross-reference
# resolved, the gallery's examples and the tutorial notebook executed, and every internal
# link of the built pages checked. Extra arguments go to sphinx-build.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/venv.sh docs

npm ci --prefix docs --no-audit --no-fund --loglevel=error
rm -rf docs/_vendor
mkdir -p docs/_vendor
cp -r docs/node_modules/mathjax/es5 docs/_vendor/mathjax

# The gallery and the API pages are generated: build them afresh.
rm -rf docs/_build docs/auto_examples docs/api/generated docs/jupyter_execute
MPLBACKEND=agg .venv/bin/python -m sphinx -b html -W --keep-going -n docs docs/_build/html "$@"
.venv/bin/python scripts/check_links.py docs/_build/html
