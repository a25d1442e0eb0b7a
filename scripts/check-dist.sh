#!/usr/bin/env bash
# Build the sdist and the wheel (the wheel from the sdist, as pip would), check them with
# twine, then install the wheel into a fresh virtual environment with no extra and with
# each extra and run scripts/smoke.py in each. Run after scripts/setup.sh (it needs the
# dev extra and the designer's JavaScript, which the build refuses to leave out). Where
# npm is, also install with `pip install .` from a copy of the tracked files alone (a fresh
# clone: no JavaScript copied yet), which must make the designer's JavaScript itself.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
PYTHON=${PYTHON:-python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

.venv/bin/python -m build --outdir "$work/dist" . >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; exit 1; }
.venv/bin/python -m twine check --strict "$work"/dist/*
wheel=$(echo "$work"/dist/*.whl)

for extra in core export rhino designer dask dev; do
    start=$SECONDS
    "$PYTHON" -m venv "$work/$extra"
    spec=$wheel
    [ "$extra" = core ] || spec="$wheel[$extra]"
    "$work/$extra/bin/python" -m pip install --quiet --disable-pip-version-check "$spec"
    # From an empty folder, so that only the installed package can be imported.
    (cd "$work" && "$work/$extra/bin/python" "$repo/scripts/smoke.py" "$extra")
    echo "smoke test of the wheel with extra '$extra' passed in $((SECONDS - start)) s"
    rm -rf "${work:?}/$extra"
done

if command -v npm >/dev/null 2>&1; then
    start=$SECONDS
    mkdir "$work/clone"
    git ls-files -z | tar --null -T - -c | tar -x -C "$work/clone"
    "$PYTHON" -m venv "$work/clone-venv"
    "$work/clone-venv/bin/python" -m pip install --quiet --disable-pip-version-check "$work/clone" >"$work/clone.log" 2>&1 || { cat "$work/clone.log" >&2; exit 1; }
    (cd "$work" && "$work/clone-venv/bin/python" -c 'import sys; from curvefold.app.designer.server import missing_bundle; sys.exit(missing_bundle())')
    echo "pip install . from a fresh clone made and installed the designer's JavaScript in $((SECONDS - start)) s"
    rm -rf "${work:?}/clone" "${work:?}/clone-venv"
else
    echo "note: npm is not installed, so pip install . from a fresh clone (which runs npm) is not checked" >&2
fi
