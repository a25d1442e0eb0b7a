"""Take the designer's screenshots that the documentation shows: the page at 1280 px
(``designer.png``) and on a 390 px phone (``designer-phone.png``), and the "Under load" panel of
a light vault (41 samples, 2 tubes) in aluminium followed to collapse and deployed
(``designer-load.png``).

Starts the designer on a free port of 127.0.0.1 and drives headless Chromium through
Playwright (the browser the tests use: Debian's ``chromium``, software WebGL).

Run: ``python scripts/screenshots.py [FOLDER]`` (``docs`` by default; needs the ``designer``
extra, Playwright and Chromium).
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

from curvefold.app.designer import server

#: The paper's vault, as the page opens it.
VAULT = "?kind=vault"
#: A light vault under load, followed to collapse (the paper's takes minutes on two cores).
LOADED = "?kind=vault&samples=41&tubes=2&material=aluminium&nonlinear=true"
#: Seconds the designer may take over the collapse and the deployment (measured: 41 CPU-s).
TIME_LIMIT = 600.0
#: WebGL without a GPU: SwiftShader, the software renderer Chromium ships.
ARGS = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox"]
#: Everything the page asks for after a change has come (the full certificate and pattern).
SETTLED = "(t => t && t.settled !== undefined)(window.curvefold && window.curvefold.timings.at(-1))"


def take(folder: Path) -> list[Path]:
    """Save the three screenshots into ``folder``; returns their paths."""
    from playwright.sync_api import sync_playwright

    chromium = shutil.which("chromium")
    if chromium is None:
        raise SystemExit("screenshots: Chromium is not installed (apt-get install chromium)")
    folder.mkdir(parents=True, exist_ok=True)
    saved = []
    with server.serving(time_limit=TIME_LIMIT) as url, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=ARGS)
        for name, width, height in (("designer.png", 1280, 800), ("designer-phone.png", 390, 844)):
            page = browser.new_page(viewport={"width": width, "height": height})
            page.goto(url + VAULT)
            page.wait_for_function(SETTLED, timeout=300_000)
            page.screenshot(path=str(folder / name))
            saved.append(folder / name)
            page.close()
        load_panel(browser, url, folder / "designer-load.png")
        saved.append(folder / "designer-load.png")
        browser.close()
    return saved


def load_panel(browser, url: str, path: Path) -> None:
    """The "Under load" panel: its verdict, the figures in mm, kPa or MPa and %, the collapse
    path and, on the deploy button, the actuation curve (at twice the pixels: the panel alone
    is narrow)."""
    # tall enough to hold the whole panel in the view
    page = browser.new_page(viewport={"width": 1280, "height": 2000}, device_scale_factor=2)
    page.goto(url + LOADED)
    page.wait_for_function("window.curvefold && window.curvefold.mechanics", timeout=900_000)
    error = page.evaluate("window.curvefold.mechanics.error")
    if error:
        raise SystemExit(f"screenshots: the design under load was not computed: {error}")
    page.click("#deploy")
    page.wait_for_function("window.curvefold.deployment", timeout=900_000)
    error = page.evaluate("window.curvefold.deployment.error")
    if error:
        raise SystemExit(f"screenshots: the deployment was not computed: {error}")
    panel = page.locator("section:has(#mechanics)")
    panel.scroll_into_view_if_needed()
    panel.screenshot(path=str(path))
    page.close()


def main(argv: list[str]) -> None:
    folder = Path(argv[0]) if argv else Path(__file__).resolve().parents[1] / "docs"
    for path in take(folder):
        print(f"wrote {path}")


if __name__ == "__main__":  # the designer's workers start in processes of their own
    main(sys.argv[1:])
