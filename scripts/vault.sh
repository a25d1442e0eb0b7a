#!/usr/bin/env bash
# Make .venv with what the main job needs (curvefold with the "export" extra for the DXF
# patterns, the GIF and the pictures, and "rhino" for the 3DM model; no npm, no system
# packages) and run it on built-in defaults: the paper's example vault, written to
# ./curvefold-vault (replaced if it exists). Extra arguments go to 'curvefold vault', e.g.
# scripts/vault.sh --a 0.5 --p-xy 1.2
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/venv.sh export,rhino
.venv/bin/curvefold vault --force "$@"
