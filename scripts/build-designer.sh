#!/usr/bin/env bash
# Copy the designer's JavaScript libraries from npm into the Python package: three.js and
# its orbit controls, at the versions frontend/package-lock.json pins, with their licence.
# The copies (src/curvefold/app/designer/static/vendor/) are not kept in git.
set -euo pipefail
cd "$(dirname "$0")/.."
npm ci --prefix frontend --no-audit --no-fund --loglevel=error
three=frontend/node_modules/three
vendor=src/curvefold/app/designer/static/vendor
rm -rf "$vendor"
mkdir -p "$vendor/addons/controls"
cp "$three/build/three.module.js" "$three/build/three.core.js" "$three/LICENSE" "$vendor/"
cp "$three/examples/jsm/controls/OrbitControls.js" "$vendor/addons/controls/"
