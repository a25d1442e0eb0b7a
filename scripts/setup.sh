#!/usr/bin/env bash
# Set up a development environment: .venv with curvefold (editable) and the extras named by
# the first argument (default dev: every extra with the test, docs and lint tools), the
# Node.js readers the tests use (tests/node), the designer's npm packages (frontend/: ESLint,
# and three.js for scripts/build-designer.sh), and the system packages of the rendering,
# browser and finite-element checks. scripts/test.sh runs it with "all,test,lint".
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/venv.sh "${1:-dev}"

if command -v npm >/dev/null 2>&1; then
    npm ci --prefix tests/node --no-audit --no-fund --loglevel=error
    npm ci --prefix frontend --no-audit --no-fund --loglevel=error
else
    echo "note: npm is not installed: the tests that read files with Node.js" \
        "and the designer's ESLint will not run" >&2
fi

# Debian's chromium is the browser Playwright drives in the designer's, three.js and report
# tests (Playwright's own browser download is not used); pdftoppm (poppler-utils) and
# rsvg-convert (librsvg2-bin) render PDF and SVG to check what a person would see; OpenSees,
# the mechanics tests' independent finite-element engine, links the system's libblas.so.3.
packages="chromium poppler-utils librsvg2-bin libblas3"
why="the browser tests, PDF/SVG rendering and OpenSees need them"
has() { command -v "$1" >/dev/null 2>&1; }
if ! has chromium || ! has pdftoppm || ! has rsvg-convert \
    || ! { ldconfig -p 2>/dev/null | grep -q 'libblas\.so\.3'; }; then
    if has apt-get && [ "$(id -u)" = 0 ]; then
        echo "installing $packages as root with apt-get: $why"
        apt-get update -qq >/dev/null && apt-get install -y -qq $packages >/dev/null
    else
        echo "note: not root with apt-get, so not installing $packages ($why):" \
            "install them (sudo apt-get install $packages); going on without them" >&2
    fi
fi
