#!/usr/bin/env bash
# Check what users install. Builds the sdist and the wheel (the wheel from the sdist, as pip
# would), checks them with twine and that both carry every file of the designer's page (its
# modules and the vendored three.js); runs `pip install .` from a copy of the tracked files
# alone (a fresh clone) with npm hidden from PATH and checks that the installed designer
# serves its JavaScript; installs the wheel into a fresh virtual environment with no extra and
# with each extra and runs scripts/smoke.py in each. Builds with $DEV_PYTHON (default
# .venv/bin/python) where it has build and twine (the dev extra), else with a virtual
# environment of its own; every environment is made with $PYTHON (default python3) under a
# temporary folder.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
PYTHON=${PYTHON:-python3}
DEV_PYTHON=${DEV_PYTHON:-.venv/bin/python}
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
pip_install() { "$1" -m pip install --quiet --disable-pip-version-check "${@:2}"; }

if ! "$DEV_PYTHON" -c 'import build, twine' 2>/dev/null; then
    "$PYTHON" -m venv "$work/tools"
    pip_install "$work/tools/bin/python" build twine
    DEV_PYTHON=$work/tools/bin/python
fi

"$DEV_PYTHON" -m build --outdir "$work/dist" . >"$work/build.log" 2>&1 \
    || { cat "$work/build.log" >&2; exit 1; }
"$DEV_PYTHON" -m twine check --strict "$work"/dist/*
wheel=$(echo "$work"/dist/*.whl)
sdist=$(echo "$work"/dist/*.tar.gz)

# The page's files as git holds them, in the wheel and in the sdist.
git ls-files -z src/curvefold/app/designer/static | "$DEV_PYTHON" -c '
import sys, tarfile, zipfile
tracked = sys.stdin.read().strip("\0").split("\0")
wheel = set(zipfile.ZipFile(sys.argv[1]).namelist())
with tarfile.open(sys.argv[2]) as sdist:
    packed = {name.split("/", 1)[1] for name in sdist.getnames() if "/" in name}
left = [f"wheel: {n}" for n in tracked if n.removeprefix("src/") not in wheel]
left += [f"sdist: {n}" for n in tracked if n not in packed]
if left or not tracked:
    sys.exit("missing from the distribution: " + ", ".join(left or ["the page"]))
print(f"the wheel and the sdist carry the {len(tracked)} files of the designer'"'"'s page")
' "$wheel" "$sdist"

# Each check in a venv of its own, two at a time (installing is half waiting for the disk);
# a failing one fails the script when it ends.
smoke() {
    local extra=$1 start=$SECONDS spec=$wheel
    "$PYTHON" -m venv "$work/$extra"
    [ "$extra" = core ] || spec="$wheel[$extra]"
    pip_install "$work/$extra/bin/python" "$spec"
    # From an empty folder, so that only the installed package can be imported.
    (cd "$work" && "$work/$extra/bin/python" "$repo/scripts/smoke.py" "$extra")
    echo "smoke test of the wheel with extra '$extra' passed in $((SECONDS - start)) s"
    rm -rf "${work:?}/$extra"
}

# pip install . from a fresh clone, npm out of reach: PATH holds every command but npm's.
clone_install() {
    local start=$SECONDS dir
    mkdir "$work/clone" "$work/no-npm"
    git ls-files -z | tar --null -T - -c | tar -x -C "$work/clone"
    IFS=: read -ra dirs <<<"$PATH"
    for dir in "${dirs[@]}"; do
        for tool in "$dir"/*; do
            case ${tool##*/} in npm | npx | node | nodejs | corepack) continue ;; esac
            [ -x "$tool" ] && [ ! -e "$work/no-npm/${tool##*/}" ] && ln -s "$tool" "$work/no-npm/"
        done
    done
    "$PYTHON" -m venv "$work/clone-venv"
    PATH="$work/no-npm" command -v npm >/dev/null && { echo "npm is still on PATH" >&2; return 1; }
    PATH="$work/clone-venv/bin:$work/no-npm" pip_install "$work/clone-venv/bin/python" \
        "$work/clone[designer]" >"$work/clone.log" 2>&1 || { cat "$work/clone.log" >&2; return 1; }
    (cd "$work" && "$work/clone-venv/bin/python" "$repo/scripts/smoke.py" designer)
    echo "pip install . from a fresh clone without npm serves the designer: $((SECONDS - start)) s"
    rm -rf "${work:?}/clone" "${work:?}/clone-venv" "${work:?}/no-npm"
}

checks=(dev clone core export rhino step designer dask) # the longest first
started=0 ended=0
for job in "${checks[@]}"; do
    if [ "$job" = clone ]; then clone_install & else smoke "$job" & fi
    started=$((started + 1))
    if [ $((started - ended)) -eq 2 ]; then
        wait -n # whichever ends first (its failure ends the script)
        ended=$((ended + 1))
    fi
done
while [ "$ended" -lt "$started" ]; do
    wait -n
    ended=$((ended + 1))
done
