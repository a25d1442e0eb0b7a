"""The designer in tests: a server on a free port of 127.0.0.1, requests to it, and the browser."""

from __future__ import annotations

import json
import os
import shutil
import urllib.error
import urllib.request

import pytest

#: Debian's chromium (installed by scripts/setup.sh); Playwright's own browser download is not used.
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
#: WebGL in a headless browser without a GPU: SwiftShader, the software renderer chromium ships.
CHROMIUM_ARGS = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox"]


def need(condition: bool, reason: str) -> None:
    """Skip without ``condition``, or fail when the environment sets CURVEFOLD_REQUIRE_NODE (the
    test command, after set-up)."""
    if not condition:
        if os.environ.get("CURVEFOLD_REQUIRE_NODE"):
            pytest.fail(reason)
        pytest.skip(reason)


def get(url: str) -> tuple[int, str, bytes]:
    """Status, content type and body of a GET, errors included."""
    try:
        with urllib.request.urlopen(url, timeout=300) as r:
            return r.status, r.headers.get("content-type", ""), r.read()
    except urllib.error.HTTPError as err:
        return err.code, err.headers.get("content-type", ""), err.read()


def get_json(url: str) -> tuple[int, object]:
    status, _, body = get(url)
    return status, json.loads(body)
