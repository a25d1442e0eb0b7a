"""Pages in headless Chromium (through Playwright): three.js reading our files, the report at phone
and desktop widths.

A folder is served on 127.0.0.1 with ``tests/node/node_modules`` beside it as ``/node_modules``,
so pages import three.js as its users do. Skips when Chromium or Playwright is missing,
unless the environment sets ``CURVEFOLD_REQUIRE_NODE`` (as the test command does after
installing them): then the test fails.
"""

from __future__ import annotations

import functools
import os
import shutil
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import pytest

NODE_MODULES = Path(__file__).parent / "node" / "node_modules"


def _missing() -> str | None:
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "the Playwright package is not installed (pip install playwright)"
    if shutil.which("chromium") is None:
        return "Chromium is not installed (apt-get install chromium)"
    if not (NODE_MODULES / "three").is_dir():
        return "three.js is not installed (npm ci --prefix tests/node)"
    return None


@contextmanager
def served(folder: Path) -> Iterator[str]:
    """Serve ``folder`` (with ``/node_modules``) on 127.0.0.1; yields the base URL."""
    link = folder / "node_modules"
    if not link.exists():
        link.symlink_to(NODE_MODULES, target_is_directory=True)

    class Quiet(SimpleHTTPRequestHandler):
        def log_message(self, *args) -> None:
            pass

    server = ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(folder)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()
        link.unlink()


@contextmanager
def chromium_page(width: int = 1280, height: int = 900) -> Iterator:
    """A page of headless Chromium at the given viewport size."""
    reason = _missing()
    if reason is not None:
        if os.environ.get("CURVEFOLD_REQUIRE_NODE"):
            pytest.fail(reason)
        pytest.skip(reason)
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=shutil.which("chromium"),
            args=["--use-gl=swiftshader", "--enable-unsafe-swiftshader"],
        )
        try:
            page = browser.new_page(viewport={"width": width, "height": height})
            yield page
        finally:
            browser.close()
