#!/usr/bin/env bash
# Set up a development environment from scratch: a virtual environment with curvefold and
# all its extras, the Node.js readers the tests use, the designer's JavaScript, the renderers
# for SVG and PDF checks and the browser that drives the designer's tests.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/venv.sh dev

if command -v npm >/dev/null 2>&1; then
    npm ci --prefix tests/node --no-audit --no-fund --loglevel=error
    bash scripts/build-designer.sh
fi

# rsvg-convert (SVG → PNG) and pdftoppm (PDF → PNG) check what a person would see; Debian's
# chromium is the browser Playwright drives in the designer's, three.js and report tests
# (Playwright's own browser download is not used); OpenSees, the mechanics tests' independent
# finite-element engine, links the system's libblas.so.3.
if ! command -v rsvg-convert >/dev/null 2>&1 || ! command -v pdftoppm >/dev/null 2>&1 || ! command -v chromium >/dev/null 2>&1 \
    || ! { ldconfig -p 2>/dev/null | grep -q 'libblas\.so\.3'; }; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        apt-get update -qq >/dev/null && apt-get install -y -qq librsvg2-bin poppler-utils chromium libblas3 >/dev/null
    else
        echo "note: install librsvg2-bin, poppler-utils, chromium and libblas3 for the rendering, browser and finite-element checks" >&2
    fi
fi
