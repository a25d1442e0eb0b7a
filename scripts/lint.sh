#!/usr/bin/env bash
# Lint: ruff check and ruff format (checking, not rewriting), mypy over the library, ESLint over
# the designer's JavaScript. Sets up the lint extra and the designer's npm packages first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/venv.sh lint
.venv/bin/ruff check .
.venv/bin/ruff format --check .
.venv/bin/mypy
npm ci --prefix frontend --no-audit --no-fund --loglevel=error
npm run lint --prefix frontend
