#!/usr/bin/env bash
# Set up a development environment from scratch: a virtual environment with curvefold and
# all its extras, the Node.js readers the tests use, and the renderers for SVG and PDF checks.
set -euo pipefail
cd "$(dirname "$0")/.."

PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e '.[dev]'

if command -v npm >/dev/null 2>&1; then
    npm ci --prefix tests/node --no-audit --no-fund --loglevel=error
fi

# rsvg-convert (SVG → PNG) and pdftoppm (PDF → PNG) check what a person would see.
if ! command -v rsvg-convert >/dev/null 2>&1 || ! command -v pdftoppm >/dev/null 2>&1; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        apt-get update -qq >/dev/null && apt-get install -y -qq librsvg2-bin poppler-utils >/dev/null
    else
        echo "note: install librsvg2-bin and poppler-utils for the rendering checks" >&2
    fi
fi

# Chromium runs three.js and the report in the browser tests (driven by the Playwright package).
if ! command -v chromium >/dev/null 2>&1; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        apt-get update -qq >/dev/null && apt-get install -y -qq chromium >/dev/null
    else
        echo "note: install chromium for the browser checks" >&2
    fi
fi
