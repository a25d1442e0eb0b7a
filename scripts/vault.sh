#!/usr/bin/env bash
# Set up from scratch (see setup.sh) and run the main job on built-in defaults: the paper's
# example vault, written to ./curvefold-vault (replaced if it exists). Extra arguments go to
# 'curvefold vault', e.g. scripts/vault.sh --a 0.5 --p-xy 1.2
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/curvefold vault --force "$@"
