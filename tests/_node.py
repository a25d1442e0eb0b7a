"""The Node.js readers under tests/node (Khronos glTF validator, FOLD library, Rabbit Ear)."""

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

NODE_DIR = Path(__file__).parent / "node"


def run_node(script: str, *args: str) -> dict:
    """Run one of the node scripts and return the JSON it prints.

    Skips when Node.js or the installed packages are missing, unless the environment sets
    ``CURVEFOLD_REQUIRE_NODE`` (as the test command does after installing them): then the
    test fails, so a missing install cannot pass unnoticed.
    """
    node = shutil.which("node")
    if node is None or not (NODE_DIR / "node_modules").is_dir():
        reason = "Node.js validators not installed (need `node` and `npm ci --prefix tests/node`)"
        if os.environ.get("CURVEFOLD_REQUIRE_NODE"):
            pytest.fail(reason)
        pytest.skip(reason)
    run = subprocess.run(
        [node, str(NODE_DIR / script), *args],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)
