"""The designer used as a person would: Playwright driving Debian's chromium against a real server on 127.0.0.1."""

from __future__ import annotations

import io
import json
import os

import numpy as np
import pytest

from _cli import run
from _designer import CHROMIUM, CHROMIUM_ARGS, need

pytest.importorskip("fastapi")
from curvefold.analysis.foldcheck import check_fold  # noqa: E402
from curvefold.app.designer import server  # noqa: E402

#: A light vault, so that downloads at full resolution stay quick.
LIGHT = "?kind=vault&samples=201&tubes=4"


@pytest.fixture(scope="module")
def browser():
    need(server.missing_bundle() is None, "the designer's JavaScript is not built (bash scripts/build-designer.sh)")
    need(os.path.exists(CHROMIUM), "chromium is not installed (apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        need(False, "playwright is not installed (pip install playwright)")
    with server.serving() as url, sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        chromium.url = url
        yield chromium
        chromium.close()


def open_page(browser, query: str = LIGHT, context=None):
    """A page of the designer with its first preview shown; console errors are collected in ``page.errors``."""
    page = context.new_page() if context else browser.new_page(viewport={"width": 1200, "height": 800})
    page.errors = []
    page.on("console", lambda m: page.errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: page.errors.append(str(e)))
    page.goto(browser.url + query)
    page.wait_for_function("window.curvefold && window.curvefold.preview")
    return page


def canvas(page) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(page.locator("#canvas").screenshot())).convert("RGB"), float)


def slider_end(page) -> str:
    """The first contact as the page holds it, written as the slider's max."""
    return page.evaluate("String(window.curvefold.contact)")


def numbers(page) -> dict:
    return page.evaluate("window.curvefold.preview.numbers")


def test_a_slider_changes_the_numbers_and_the_view(browser):
    page = open_page(browser)
    before, shown = canvas(page), page.inner_text("#numbers")
    # not blank: the vault, the ground and the background make many colours
    assert len(np.unique(before.reshape(-1, 3), axis=0)) > 100 and before.std() > 10
    slider = page.locator('.field[data-key="a"] input[type=range]')
    slider.focus()
    for _ in range(30):  # 30 steps of 1.2/400 to the right (the typical span of a): a = 0.3 → 0.39
        page.keyboard.press("ArrowRight")
    page.wait_for_function("Math.abs(window.curvefold.preview.numbers.a - 0.39) < 1e-9")
    page.wait_for_timeout(300)
    after = canvas(page)
    assert page.inner_text("#numbers") != shown
    assert numbers(page)["kappa0_s0"] > 3.17 and np.abs(after - before).mean() > 1.0
    assert page.errors == []


def test_the_fold_slider_plays_without_a_request(browser):
    page = open_page(browser)
    page.locator("#pattern img").first.wait_for()  # the figures that follow a design change have come
    assert page.input_value("#fold") == "90" and page.get_attribute("#fold", "max") == str(slider_end(page))
    requests = []
    page.on("request", lambda r: requests.append(r.url))
    designed = canvas(page)
    page.click("#play")
    page.wait_for_function("(window.curvefold.frames ?? 0) > 5")
    page.click("#play")
    moved = canvas(page)
    assert requests == [] and np.abs(moved - designed).mean() > 1.0
    page.fill("#fold", "0")
    page.dispatch_event("#fold", "input")
    assert page.inner_text("#fold-value") == "0.0°" and float(page.inner_text("#lift-off")) > 0.1
    page.click("#to-design")
    assert page.inner_text("#fold-value") == "90.0° (design)" and float(page.inner_text("#lift-off")) < 1e-6
    assert page.errors == []


def test_an_invalid_value_shows_its_message_and_keeps_the_design(browser):
    page = open_page(browser)
    shown = numbers(page)
    page.fill('.field[data-key="width"] input.value', "9")
    error = page.locator('.field[data-key="width"] .error')
    error.wait_for(state="visible")
    assert error.inner_text().startswith("width = 9 is past regression for the base tube: ")
    assert numbers(page) == shown
    page.fill('.field[data-key="width"] input.value', "0.08")
    page.wait_for_function("document.querySelector('.field[data-key=\"width\"] .error').textContent === ''")


def test_downloads_pass_the_check_and_the_saved_design_rebuilds(browser, tmp_path):
    page = open_page(browser)
    with page.expect_download(timeout=120_000) as fold:
        page.click("#downloads a:text-is('FOLD')")
    path = tmp_path / fold.value.suggested_filename
    fold.value.save_as(path)
    assert path.name == "vault.fold" and check_fold(path).ok
    with page.expect_download() as toml:
        page.click("#downloads a:text-is('design (TOML)')")
    saved = tmp_path / "saved.toml"
    toml.value.save_as(saved)
    rebuilt = json.loads(run("vault", str(saved), "--json").stdout)
    shown = numbers(page)
    assert {k: rebuilt[k] for k in shown if k in rebuilt} == {k: v for k, v in shown.items() if k in rebuilt}


def test_two_sessions_never_see_each_other(browser):
    first, second = (browser.new_context(viewport={"width": 1200, "height": 800}) for _ in range(2))
    a = open_page(browser, context=first)
    b = open_page(browser, context=second)
    a.fill('.field[data-key="p_xy"] input.value', "1.1")
    a.wait_for_function("window.curvefold.preview.numbers.p_xy === 1.1")
    b.reload()
    b.wait_for_function("window.curvefold && window.curvefold.preview")
    assert numbers(b)["p_xy"] == 0.75 and "p_xy" not in b.url
    first.close()
    second.close()


def test_a_vault_from_span_and_rise(browser):
    page = open_page(browser)
    page.check("input[name=mode][value=targets]")
    rise = page.locator('.field[data-key="rise"] input.value')
    rise.wait_for()
    rise.fill("1.5")  # at this p_xz and 4 tubes, rise/span stays below 0.59
    error = page.locator('.field[data-key="rise"] .error')
    error.wait_for(state="visible")
    assert "is out of reach for width = 0.08 and 4 tubes: vaults of the family reach rise/span from" in error.inner_text()
    rise.fill("1.15")
    page.wait_for_function("Math.abs(window.curvefold.preview.numbers.rise - 1.15) < 1e-9")
    solved = numbers(page)
    assert solved["a"] != 0.3 and float(page.input_value('.field[data-key="a"] input.value')) == pytest.approx(solved["a"], rel=1e-5)
