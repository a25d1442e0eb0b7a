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
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT

.venv/bin/python -m build --outdir "$work/dist" . >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; exit 1; }
.venv/bin/python -m twine check --strict "$work"/dist/*
wheel=$(echo "$work"/dist/*.whl)

# Each extra in a venv of its own, two at a time (installing is half waiting for the disk);
# a failing one fails the script when it ends.
smoke() {
    local extra=$1 start=$SECONDS spec=$wheel
    "$PYTHON" -m venv "$work/$extra"
    [ "$extra" = core ] || spec="$wheel[$extra]"
    "$work/$extra/bin/python" -m pip install --quiet --disable-pip-version-check "$spec"
    # From an empty folder, so that only the installed package can be imported.
    (cd "$work" && "$work/$extra/bin/python" "$repo/scripts/smoke.py" "$extra")
    echo "smoke test of the wheel with extra '$extra' passed in $((SECONDS - start)) s"
    rm -rf "${work:?}/$extra"
}

clone_install() {
    local start=$SECONDS
    mkdir "$work/clone"
    git ls-files -z | tar --null -T - -c | tar -x -C "$work/clone"
    "$PYTHON" -m venv "$work/clone-venv"
    "$work/clone-venv/bin/python" -m pip install --quiet --disable-pip-version-check "$work/clone" >"$work/clone.log" 2>&1 || { cat "$work/clone.log" >&2; return 1; }
    (cd "$work" && "$work/clone-venv/bin/python" -c 'import sys; from curvefold.app.designer.server import missing_bundle; sys.exit(missing_bundle())')
    echo "pip install . from a fresh clone made and installed the designer's JavaScript in $((SECONDS - start)) s"
    rm -rf "${work:?}/clone" "${work:?}/clone-venv"
}

checks=(dev core export rhino designer dask)  # the longest first
if command -v npm >/dev/null 2>&1; then
    checks+=(clone)
else
    echo "note: npm is not installed, so pip install . from a fresh clone (which runs npm) is not checked" >&2
fi
started=0 ended=0
for job in "${checks[@]}"; do
    if [ "$job" = clone ]; then clone_install & else smoke "$job" & fi
    started=$((started + 1))
    if [ $((started - ended)) -eq 2 ]; then
        wait -n  # whichever ends first (its failure ends the script)
        ended=$((ended + 1))
    fi
done
while [ "$ended" -lt "$started" ]; do
    wait -n
    ended=$((ended + 1))
done
