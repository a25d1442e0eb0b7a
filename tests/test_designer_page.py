"""The designer's page for everyone: axe-core finds no accessibility violation at 390 and 1280 px,
every control is reached and operated by keys, heavy work says what runs and for how long, a
time-out reads as a notice, the crease pattern opens large, the 3D view is lit with a shadow.

axe-core comes from npm (``tests/node``, beside the other JavaScript the tests use); before these
changes it found 47 form controls without a label at 1280 px (48 at 390 px), 4 unnamed drop-down
lists, 5 pictures without a text, 2 scrolling boxes no key reaches and text of too low a contrast
(4.47:1 for 4.5:1).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import test_designer_browser
from _designer import need
from test_designer_browser import LIGHT, canvas, open_page, settled

#: The designer's server and Chromium, as the other tests of the page have them.
browser = test_designer_browser.browser

AXE = Path(__file__).parent / "node" / "node_modules" / "axe-core" / "axe.min.js"


def violations(page) -> list:
    """axe-core's violations of the page as it stands: ``[rule, impact, [targets]]``."""
    need(AXE.is_file(), "axe-core is not installed (npm ci --prefix tests/node)")
    page.add_script_tag(path=str(AXE))
    return page.evaluate("""() => axe.run(document).then((r) => r.violations.map(
        (v) => [v.id, v.impact, v.nodes.map((n) => n.target.join(' '))]))""")


@pytest.mark.parametrize("width, height", [(390, 844), (1280, 800)])
def test_axe_core_finds_no_violation_on_a_phone_or_a_desktop(browser, width, height):
    page = open_page(browser, LIGHT + "&thickness=0.001", width=width, height=height)
    settled(page)
    page.wait_for_function("window.curvefold.mechanics && window.curvefold.mechanics.numbers")
    assert violations(page) == []
    # every control named for a screen reader: the field's words, the slider's too
    names = page.evaluate("""() => {
        const box = document.querySelector('.field[data-key="a"]');
        const value = box.querySelector('input.value');
        const slider = box.querySelector('input[type=range]');
        return [value.labels[0].textContent, slider.getAttribute('aria-label')]; }""")
    assert names == ["torsion amplitude a", "torsion amplitude, slider"]
    # the check can fail: a control without its label is found
    page.evaluate("""() => {
        const input = document.querySelector('.field[data-key="a"] input.value');
        input.labels[0].htmlFor = ''; }""")
    found = {rule: targets for rule, _, targets in violations(page)}
    assert found["label"] == ["#field-a"] and set(found) <= {"label", "label-title-only"}
    assert page.errors == []


#: A control's name in the tests below: a field's slider by its field, else its id, name or label.
NAME = """(c) => (c.type === 'range' && c.id !== 'fold')
    ? 'slider ' + c.closest('.field').dataset.key
    : c.id || c.name || c.getAttribute('aria-label') || c.textContent"""


def tab_to(page, test: str, most: int = 200) -> None:
    """Press Tab until the focused control ``c`` passes ``test`` (JavaScript)."""
    for _ in range(most):
        page.keyboard.press("Tab")
        if page.evaluate(f"(c => {test})(document.activeElement)"):
            return
    raise AssertionError(f"Tab never reached a control where {test}")


def test_every_control_is_reached_and_operated_by_keys(browser):
    page = open_page(browser)
    settled(page)
    # every visible, enabled control of the page
    controls = page.evaluate(
        """() => [
        ...document.querySelectorAll('input, select, button, a[href]')]
        .filter((c) => !c.disabled && c.getClientRects().length
            && getComputedStyle(c).visibility !== 'hidden'
            && !c.closest('dialog, details:not([open])') && !(c.type === 'radio' && !c.checked))
        .map("""
        + NAME
        + ")"
    )
    assert len(controls) > 60
    reached = []
    page.locator("body").focus()
    for _ in range(len(controls) + 20):
        page.keyboard.press("Tab")
        reached.append(page.evaluate(f"({NAME})(document.activeElement)"))
    assert set(controls) - set(reached) == set(), set(controls) - set(reached)
    # the certificate's list scrolls by keys; each page of the crease pattern is a button (both
    # were out of the keys' reach)
    assert "certificate" in reached and "open crease pattern, page 1 of 4 large" in reached
    # a slider operated by keys: Tab on to a's slider, one step right
    assert "slider a" in reached
    tab_to(page, "c.type === 'range' && c.closest('.field')?.dataset.key === 'a'")
    page.keyboard.press("ArrowRight")
    page.wait_for_function("Math.abs(window.curvefold.preview.numbers.a - 0.301) < 1e-9")
    assert page.input_value('.field[data-key="a"] input.value') == "0.301"
    # a button operated by keys: Tab on to the play button, Space plays, Space again stops
    tab_to(page, "c.id === 'play'")
    page.keyboard.press("Space")
    page.wait_for_function("window.curvefold.frames > 5")
    page.keyboard.press("Space")
    frames = page.evaluate("window.curvefold.frames")
    page.wait_for_timeout(300)
    assert page.evaluate("window.curvefold.frames") == frames and page.errors == []


def test_the_crease_pattern_opens_large_and_escape_closes_it(browser):
    page = open_page(browser)
    settled(page)
    thumbnail = page.locator("#pattern button.page").first
    shown = thumbnail.bounding_box()
    assert thumbnail.get_attribute("aria-label").startswith("open crease pattern, page 1 of ")
    thumbnail.focus()
    page.keyboard.press("Enter")
    dialog = page.locator("#pattern-dialog")
    assert dialog.evaluate("d => d.open") and page.text_content("#pattern-dialog-title").startswith(
        "Crease pattern: page 1 of "
    )
    large = page.locator("#pattern-large img")
    large.wait_for()
    page.wait_for_function("document.querySelector('#pattern-large img').complete")
    box = large.bounding_box()
    # the whole page, at least three times the thumbnail's width
    assert box["width"] >= 3 * shown["width"] and large.get_attribute("alt").startswith(
        "crease pattern, page 1"
    )
    assert violations(page) == []  # the dialog too: named by its heading, its image by its text
    page.keyboard.press("Escape")
    assert not dialog.evaluate("d => d.open")
    # the focus back on the thumbnail that opened it; the close button closes it too
    assert page.evaluate("document.activeElement.classList.contains('page')")
    thumbnail.click()
    page.click("#pattern-close")
    assert not dialog.evaluate("d => d.open") and page.errors == []


def test_heavy_work_says_what_runs_and_for_how_long(browser):
    page = open_page(browser, "?kind=vault&samples=301&tubes=5")
    settled(page)
    # the prompt names the thickness the field shows rather than ask for one
    prompt = page.inner_text("#mechanics-status")
    assert "choose a material" in prompt and "1 mm is the thickness it will take" in prompt
    page.fill('.field[data-key="thickness"] input.value', "0.0012")
    busy = page.locator("section:has(#mechanics) .busy")
    busy.wait_for()
    line = busy.text_content()
    assert re.fullmatch(r"Computing the design under load \(bar-and-hinge model\)…\d+ s", line)
    # an indeterminate bar (no value), named for a screen reader, its seconds counting
    bar = page.locator("section:has(#mechanics) .busy progress")
    assert bar.evaluate("p => p.position") == -1 and bar.get_attribute("aria-label").startswith(
        "Computing the design under load"
    )
    page.wait_for_function(
        "window.curvefold.mechanics && window.curvefold.mechanics.numbers", timeout=120_000
    )
    assert page.locator(".busy").count() == 0 or page.evaluate(
        "[...document.querySelectorAll('.busy')].every((b) => !b.closest('section').contains("
        "document.getElementById('mechanics')))"
    )
    assert page.errors == []


def test_a_time_out_of_the_preview_is_a_notice_in_the_servers_words(browser):
    page = open_page(browser)
    sentence = (
        "The designer was busy with other work for its whole time limit of 3 s: try again in a "
        "moment, or lower samples or the number of tubes, cells or panels."
    )
    page.route(
        "**/api/vault/preview?*",
        lambda route: route.fulfill(
            status=503,
            content_type="application/json",
            body=json.dumps({"detail": sentence, "key": "samples"}),
        ),
    )
    page.fill('.field[data-key="p_xy"] input.value', "1.1")
    message = page.locator("#message")
    message.wait_for(state="visible")
    # as the server says it, once, as a notice: not a user's error at a field
    assert message.inner_text() == sentence and message.get_attribute("class") == "notice"
    assert message.get_attribute("role") == "status"
    assert (
        page.locator(".field.invalid").count() == 0 and page.inner_text("body").count(sentence) == 1
    )
    page.unroute("**/api/vault/preview?*")
    # a refusal of the design stays an error at its field
    page.fill('.field[data-key="width"] input.value', "9")
    page.locator('.field[data-key="width"] .error').wait_for(state="visible")
    assert not page.is_visible("#message")


def test_the_view_is_lit_and_shaded_with_crease_edges_and_a_ground_shadow(browser):
    page = open_page(browser)
    scene = page.evaluate("""() => {
        const v = window.curvefold.view, lights = [];
        v.scene.traverse((o) => { if (o.isLight) lights.push(o.type); });
        return {lights, material: v.main.material.type, flat: v.main.material.flatShading,
            lines: v.main.lines.children.filter((l) => l.isLineSegments).length,
            shadows: v.renderer.shadowMap.enabled, casts: v.main.surface.castShadow,
            sun: v.sun.castShadow, ground: v.ground.receiveShadow}; }""")
    assert sorted(scene.pop("lights")) == ["DirectionalLight", "HemisphereLight"]
    assert scene == {
        "material": "MeshStandardMaterial",
        "flat": True,
        "lines": 3,
        "shadows": True,
        "casts": True,
        "sun": True,
        "ground": True,
    }
    # the shadow shows: the picture without it is lighter, on the ground alone
    shaded = canvas(page)
    page.evaluate("""() => { const v = window.curvefold.view;
        v.ground.receiveShadow = false; v.ground.material.needsUpdate = true; v.render(); }""")
    unshaded = canvas(page)
    darker = (unshaded - shaded).mean(axis=2)
    # measured: 1.7 % of the view darker by more than 20 (of 255; up to 58), nothing lighter
    assert (darker > 20).mean() > 0.01 and (darker < -1).mean() < 0.001
    # faces turned differently are shaded differently: many greys on the surface
    assert len(np.unique(shaded.reshape(-1, 3), axis=0)) > 200
    assert page.errors == []
