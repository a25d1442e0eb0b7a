#!/usr/bin/env bash
# Copy the designer's JavaScript libraries from npm into the Python package: three.js and
# its orbit controls, at the versions frontend/package-lock.json pins, with their licence.
# The copies (src/curvefold/app/designer/static/vendor/) are not kept in git; a build of the
# package makes them the same way when npm is there (setup.py's build_bundle, run here).
set -euo pipefail
cd "$(dirname "$0")/.."
"${PYTHON:-python3}" -c 'import setup; setup.build_bundle()'
