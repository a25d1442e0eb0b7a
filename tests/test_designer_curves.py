"""The designer's curves of large-displacement mechanics: the collapse path under load and the
deployment's actuation curve, answered by the API (the numbers of ``curvefold load --nonlinear``
and ``curvefold deploy``) and drawn by the page as inline SVG (labelled, named, axe-clean, reached
by keys); an answer with a value that is not finite is refused, never drawn.
"""

from __future__ import annotations

import json
import math
import urllib.parse

import pytest

import test_designer_browser
from _cli import run
from _designer import get_json
from test_designer_browser import open_page

pytest.importorskip("fastapi")
from curvefold.app.designer import curves, jobs, server  # noqa: E402
from curvefold.kernel._errors import InternalError  # noqa: E402
from curvefold.mechanics._collapse import _strut  # noqa: E402

#: A small vault, deployed in about 2 CPU-s.
DEPLOYED = "tubes=3&samples=21&material=aluminium"
#: The same, its model one element across (curvefold load's --across): to collapse in about 1.
SMALL = DEPLOYED + "&across=1"
#: The designer's server and Chromium, as the other tests of the page have them.
browser = test_designer_browser.browser


@pytest.fixture(scope="module")
def url():
    with server.serving() as base:
        yield base


def test_the_collapse_curve_comes_with_the_design_under_load(url):
    status, answer = get_json(f"{url}api/vault/mechanics?{SMALL}&nonlinear=true")
    assert status == 200, answer
    c, n = answer["collapse_curve"], answer["numbers"]["collapse"]
    lam, w = c["load_factor"], c["control_displacement_mm"]
    # a state per step from the unloaded one; the collapse factor and the displacement there
    # are the path's own (the numbers of curvefold load --nonlinear --json)
    assert len(lam) == len(w) == len(c["stable"]) == n["steps"] + 1 and lam[0] == w[0] == 0
    assert c["factor"] == n["factor"] and c["linear_factor"] == n["linear_factor"]
    assert c["control"] == n["control"] and w[c["at_collapse"]] == 1e3 * n["control_displacement"]
    assert max(lam[: c["stable"].index(False)]) <= c["factor"] <= max(lam)
    printed = json.loads(
        run("load", *_flags(SMALL), "--nonlinear", "--json").stdout  # the command: same numbers
    )
    assert printed["collapse"] == n
    # without --nonlinear there is no curve
    assert "collapse_curve" not in get_json(f"{url}api/vault/mechanics?{SMALL}")[1]


def test_the_curve_is_the_collapse_csv():
    """The curve holds the columns of ``collapse.csv`` (Koiter's strut: λ_cr = 100 N)."""
    strut = _strut(1e-3)
    c = curves.collapse_curve(strut)
    rows = [r.split(",") for r in strut.csv().splitlines()[1:]]
    assert [float(r[1]) for r in rows] == pytest.approx(c["load_factor"], rel=1e-9, abs=1e-12)
    assert [float(r[2]) for r in rows] == pytest.approx(
        c["control_displacement_mm"], rel=1e-9, abs=1e-12
    )
    assert c["linear_factor"] == 100.0 and round(c["factor"], 3) == 98.499


def _flags(query: str) -> list[str]:
    return [x for k, v in urllib.parse.parse_qsl(query) for x in (f"--{k.replace('_', '-')}", v)]


def test_the_deployment_is_what_curvefold_deploy_prints(url):
    query = DEPLOYED
    plan = jobs.plan("deploy", "vault", urllib.parse.parse_qsl(query))
    assert plan.lane == "heavy" and plan.estimate.total > 0
    status, d = get_json(f"{url}api/vault/deploy?{query}")
    assert status == 200, d
    assert d["angles_deg"] == [10.0 * k for k in range(1, 10)] and d["error"] is None
    assert d["step"] == curves.STEP and d["material"] == "aluminium" and d["thickness"] == 1e-3
    n = len(d["angles_deg"])
    assert all(len(d[k]) == n for k in ("actuation_Nm_per_rad", "max_stress_MPa", "distance_mm"))
    printed = json.loads(run("deploy", *_flags(query), "--step", "10", "--json").stdout)
    assert d["summary"] == printed["deployment"]  # the same computation, to the last bit
    s = d["summary"]
    assert s["peak_actuation_Nm"] in d["actuation_Nm_per_rad"]
    assert s["max_stress_MPa"] == max(d["max_stress_MPa"])
    assert s["max_distance_mm"] == max(d["distance_mm"])


@pytest.mark.parametrize(
    "query, words, key",
    [
        # the paper's vault: 261 samples kept × 96 strips (tubes = "max" counts its cap)
        ("", f"at most {curves.LARGEST_DEPLOYMENT} nodes", "samples"),
        ("samples=201&tubes=4", "got 3216 (201 × 16)", "samples"),
        ("thickness=0", "thickness must be in (0, 1) m", "thickness"),
    ],
)
def test_a_deployment_too_large_is_refused_before_any_work(url, query, words, key):
    status, answer = get_json(f"{url}api/vault/deploy?{query}")
    assert status == 422 and words in answer["error"] and answer["key"] == key, answer
    assert "\n" not in answer["error"]
    status, answer = get_json(f"{url}api/crease/deploy")
    assert status == 422 and "no end sections to hold" in answer["error"]


def test_a_non_finite_answer_is_never_sent():
    """Strict JSON refuses a value that is not finite, naming it (the server's one-line 500,
    never a NaN the page cannot parse); a finite one passes."""
    answer = {"angles_deg": [10.0, 20.0], "actuation_Nm_per_rad": [1.0, -2.0]}
    assert json.loads(jobs._json(answer)) == answer
    answer["actuation_Nm_per_rad"][1] = math.nan
    with pytest.raises(InternalError, match=r"actuation_Nm_per_rad\[1\] = nan"):
        jobs._json(answer)


def plots(page) -> dict:
    """The page's plots: id → name, description, axis labels, lines and their points."""
    return page.evaluate("""() => Object.fromEntries([...document.querySelectorAll('svg.plot')]
        .map((s) => [s.id, {
            role: s.getAttribute('role'),
            name: s.querySelector('title').textContent,
            desc: s.querySelector('desc').textContent,
            texts: [...s.querySelectorAll('.axes text')].map((t) => t.textContent),
            lines: [...s.querySelectorAll('polyline')].map((p) => ({
                dashed: p.classList.contains('dashed'),
                points: p.getAttribute('points').split(' ').length}))}]))""")


def test_the_page_draws_both_curves_and_the_deploy_button_is_reached_by_keys(browser):
    from test_designer_page import tab_to, violations

    page = open_page(browser, f"?kind=vault&{SMALL}&nonlinear=true")
    page.wait_for_function(
        "window.curvefold.mechanics && window.curvefold.mechanics.numbers", timeout=120_000
    )
    page.locator("#collapse-curve").wait_for()
    curve = page.evaluate("window.curvefold.mechanics.collapse_curve")
    shown = plots(page)["collapse-curve"]
    assert shown["role"] == "img" and shown["name"] == "Load–displacement curve to collapse"
    assert "load factor λ" in shown["texts"] and any("(mm)" in t for t in shown["texts"])
    # the path, a point per state, and the linear factor dashed
    assert shown["lines"] == [
        {"dashed": False, "points": len(curve["load_factor"])},
        {"dashed": True, "points": 2},
    ]
    # the collapse marked on the path: a dot (and its legend's)
    assert page.locator("#collapse-curve circle.marker").count() == 2
    linear = float(f"{curve['linear_factor']:.3g}")  # three digits, as the page writes it
    assert f"linear buckling factor {linear:g} (dashed)" in shown["desc"]
    # the deploy button, by keys: Tab to it, Enter deploys
    tab_to(page, "c.id === 'deploy'")
    page.keyboard.press("Enter")
    page.locator("#actuation-curve").wait_for(timeout=120_000)
    d = page.evaluate("window.curvefold.deployment")
    shown = plots(page)["actuation-curve"]
    assert shown["texts"][-2:] == ["fold angle 2α (°)", "actuation Q (N·m/rad)"]
    assert shown["lines"] == [{"dashed": False, "points": len(d["angles_deg"])}]
    rows = page.inner_text("#deploy-rows")
    assert "largest stress" in rows and "off the rigid path" in rows and "MPa" in rows
    assert f"{d['summary']['max_stress_MPa']:.3g} at" in rows
    assert page.inner_text("#deploy-status").startswith("aluminium 1 mm, both feet carried")
    assert violations(page) == []
    # a new design clears the deployment shown
    page.fill('.field[data-key="thickness"] input.value', "0.0012")
    page.wait_for_function("window.curvefold.deployment === null")
    assert page.locator("#actuation-curve").count() == 0 and page.errors == []


def test_a_damaged_answer_is_not_drawn(browser):
    page = open_page(browser, "?kind=vault&tubes=3&samples=21")
    d = {
        "angles_deg": [10.0, 20.0, 30.0],
        "actuation_Nm_per_rad": [-1.0, None, -3.0],  # a NaN, as JSON can carry it: null
        "max_stress_MPa": [1.0, 2.0, 3.0],
        "distance_mm": [1.0, 2.0, 3.0],
        "summary": {
            "peak_actuation_Nm": -3.0,
            "peak_actuation_at_deg": 30.0,
            "max_stress_MPa": 3.0,
            "max_stress_at_deg": 30.0,
            "max_distance_mm": 3.0,
            "max_distance_span": 1e-3,
            "max_distance_at_deg": 30.0,
        },
        "material": "aluminium",
        "thickness": 1e-3,
        "step": 10.0,
        "error": None,
    }
    page.route(
        "**/api/vault/deploy?*",
        lambda route: route.fulfill(
            status=200, content_type="application/json", body=json.dumps(d)
        ),
    )
    page.click("#deploy")
    page.wait_for_function("window.curvefold.deployment !== null")
    assert "not a finite number: not drawn" in page.inner_text("#deploy-status")
    assert page.locator("#actuation-curve").count() == 0
    # the check can pass: the same answer finite is drawn
    d["actuation_Nm_per_rad"][1] = -2.0
    page.unroute("**/api/vault/deploy?*")
    page.route(
        "**/api/vault/deploy?*",
        lambda route: route.fulfill(
            status=200, content_type="application/json", body=json.dumps(d)
        ),
    )
    page.click("#deploy")
    page.locator("#actuation-curve").wait_for()
    # a time-out (504) is said once, as the server says it
    sentence = "This design needs more than the designer's time limit of 120 s: lower samples."
    page.unroute("**/api/vault/deploy?*")
    page.route(
        "**/api/vault/deploy?*",
        lambda route: route.fulfill(
            status=504, content_type="application/json", body=json.dumps({"error": sentence})
        ),
    )
    page.click("#deploy")
    page.wait_for_function(
        "document.getElementById('deploy-status').textContent.includes('time limit')"
    )
    assert page.inner_text("#deploy-status") == sentence
    assert all("status of 504" in e for e in page.errors), page.errors


def test_the_plots_arithmetic_in_node():
    """plot.js runs in Node (tests/node/designer_plot.mjs): an answer is drawn only when every
    value is a finite number (a null, NaN, infinity, text or a short array refused), and its
    ticks are round."""
    import shutil
    import subprocess
    from pathlib import Path

    from _designer import need

    need(shutil.which("node") is not None, "Node.js is not installed (apt-get install nodejs)")
    script = Path(__file__).parent / "node" / "designer_plot.mjs"
    done = subprocess.run(["node", str(script)], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr
