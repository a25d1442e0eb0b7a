#!/usr/bin/env bash
# Build the sdist and the wheel (the wheel from the sdist, as pip would), check them with
# twine, then install the wheel into a fresh virtual environment with no extra and with
# each extra and run scripts/smoke.py in each. Run after scripts/setup.sh (it needs the
# dev extra and the designer's JavaScript, which the build refuses to leave out).
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
