"""Take the designer's screenshots that the documentation shows: the page at 1280 px
(``designer.png``) and on a 390 px phone (``designer-phone.png``), and the "Under load" panel of
a lighter vault of the paper's (201 samples, 4 tubes) in aluminium (``designer-load.png``).

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
#: A lighter vault under load (the paper's takes minutes on two cores), in aluminium.
LOADED = "?kind=vault&samples=201&tubes=4&material=aluminium"
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
    with server.serving() as url, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=ARGS)
        for name, width, height in (("designer.png", 1280, 800), ("designer-phone.png", 390, 844)):
            page = browser.new_page(viewport={"width": width, "height": height})
            page.goto(url + VAULT)
            page.wait_for_function(SETTLED, timeout=300_000)
            page.screenshot(path=str(folder / name))
            saved.append(folder / name)
            page.close()
        # the load panel: its verdict first, then the figures in mm, kPa or MPa and %
        # (at twice the pixels: the panel alone is narrow)
        page = browser.new_page(viewport={"width": 1280, "height": 800}, device_scale_factor=2)
        page.goto(url + LOADED)
        page.wait_for_function("window.curvefold && window.curvefold.mechanics", timeout=300_000)
        error = page.evaluate("window.curvefold.mechanics.error")
        if error:
            raise SystemExit(f"screenshots: the design under load was not computed: {error}")
        panel = page.locator("section:has(#mechanics)")
        panel.scroll_into_view_if_needed()
        panel.screenshot(path=str(folder / "designer-load.png"))
        saved.append(folder / "designer-load.png")
        browser.close()
    return saved


def main(argv: list[str]) -> None:
    folder = Path(argv[0]) if argv else Path(__file__).resolve().parents[1] / "docs"
    for path in take(folder):
        print(f"wrote {path}")


if __name__ == "__main__":  # the designer's workers start in processes of their own
    main(sys.argv[1:])
