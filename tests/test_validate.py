"""One validator per kind of value; every spec of the schema; the tables the writers share."""

from __future__ import annotations

import math

import numpy as np
import pytest

from curvefold.app._design import SCHEMA, parse_design
from curvefold.io import _cutters as cutters
from curvefold.io import _gltf as gltf
from curvefold.io import _pattern as pattern
from curvefold.io import _rhino as rhino
from curvefold.io import page_size
from curvefold.io._formats import (
    FORMATS,
    check_formats,
    default_formats,
    formats_of,
    missing_dependencies,
)
from curvefold.io._tables import COLOURS, PAGES, UNITS, mm_per_unit, page_mm, rgba, rgba8
from curvefold.kernel import InputError
from curvefold.kernel._validate import KINDS, REQUIRED, Interval, Spec, describe
from curvefold.vault import VaultDesign
from curvefold.vault._assembly import VAULT_SPECS


def spec(kind: str, range_: str | None = None, **kw) -> Spec:
    return Spec("x", kind, None, range_, **kw)


@pytest.mark.parametrize(
    ("s", "good", "bad", "match"),
    [
        (
            spec("real", "(0, 180)", unit="degrees"),
            [(45, 45.0), (np.float32(1.5), 1.5)],
            [180, 0, -1e-300, math.nan, math.inf, True, "90", 10**400],
            [
                r"x must be in \(0, 180\) degrees, got 180\.0$",
                r"got 0\.0$",
                r"got -1e-300$",
                r"x must be a " r"finite number, got nan$",
                r"finite number, got inf$",
                r"x must be a number \(degrees\), got boolean True$",
                r"got string '90'$",
                r"x is too large, got an integer of 1329 bits$",
            ],
        ),
        (
            spec("integer", "[3, 200000]", why="memory bound"),
            [(3, 3), (np.int64(7), 7)],
            [2, 200001, 5.0, "5", False],
            [
                r"x must be an integer in \[3, 200000\] \(memory bound\), got 2$",
                r"got 200001$",
                r"got 5\.0$",
                r"got string '5'$",
                r"got boolean False$",
            ],
        ),
        (
            spec("count", "[1, 1000]"),
            [("max", "max"), (3, 3)],
            [0, "many", 1.0],
            [
                r'x must be an integer in \[1, 1000\] or "max", got 0$',
                r"got string 'many'$",
                r"got 1\.0$",
            ],
        ),
        (
            spec("choice", choices=("+", "-")),
            [("-", "-")],
            ["up", 1],
            [r'x must be one of "\+", ' r'"-", got string \'up\'$', r"got 1$"],
        ),
        (
            spec("text"),
            [("", "")],
            [3, "x" * 1001],
            [r"x must be a string of at most 1000 " r"characters, got 3$", r"got string 'xxx"],
        ),
        (
            spec("flag"),
            [(np.bool_(True), True)],
            [1, "yes"],
            [r"x must be true or false, got 1$", r"got string 'yes'$"],
        ),
        (
            spec("page", "(0, 10000]", unit="mm", choices=("A4", "Letter")),
            [("letter", "Letter"), ([100, 200.5], (100.0, 200.5))],
            ["A5", [0, 297], [210, 1e5], [1, 2, 3]],
            [
                r'x must be one of "A4", "Letter" or \[width, height\] in mm, got string \'A5\'$',
                r"x width must be " r"in \(0, 10000\] mm, got 0\.0$",
                r"x height must be in \(0, 10000\] mm, got 100000\.0$",
                r"got array \[1, 2, 3\]$",
            ],
        ),
        (
            spec("formats", choices=("svg", "fold")),
            [(["svg", "svg", "fold"], ("svg", "fold")), ((), ())],
            ["svg", ["png"]],
            [
                r"x must be an array of format names \(svg, fold\), got string 'svg'$",
                r"x: unknown " r"format string 'png' \(allowed: svg, fold\)$",
            ],
        ),
        (
            spec("cells", "[-2, 2]"),
            [([[0, 0], (1, -2)], ((0, 0), (1, -2)))],
            [[], [[0, 3]], [[0, 0], [0, 0]], [[0]]],
            [
                r"x must be an array of 1 to 10000 \[i, j\] pairs, got array \[\]$",
                r"x\[0\] must be a " r"pair \[i, j\] of integers in \[-2, 2\], got array \[0, 3\]$",
                r"x\[1\] repeats cell \[0, 0\] \(first at index 0\)$",
                r"x\[0\] must be a pair",
            ],
        ),
        (
            spec("function", "(0, inf)", unit="per model unit"),
            [(2, 2.0)],
            [0, "1 + s", [1.0]],
            [
                r"x must be > 0 per model unit, got 0\.0$",
                r"x must be a number, an expression in s "
                r"or a table \{csv = \.\.\., column = \.\.\.\}, got string",
                r"got array \[1\.0\]$",
            ],
        ),
    ],
    ids=lambda v: v.kind if isinstance(v, Spec) else "",
)
def test_each_kind_accepts_its_values_and_refuses_damaged_ones(s, good, bad, match):
    for value, expected in good:
        got = s.check(value)
        assert got == expected and type(got) is type(expected)
    assert len(bad) == len(match)
    for value, pattern_ in zip(bad, match):
        with pytest.raises(InputError, match=pattern_):
            s.check(value)


def test_every_kind_is_covered_and_unknown_kinds_are_refused():
    assert set(KINDS) == {
        "real",
        "integer",
        "count",
        "choice",
        "text",
        "flag",
        "page",
        "formats",
        "cells",
        "function",
    }
    with pytest.raises(ValueError, match="kind must be one of"):
        Spec("x", "float")


def test_where_and_shown_name_what_the_user_typed():
    s = Spec("fold_angle", "real", 90.0, "(0, 180)", "degrees")
    with pytest.raises(
        InputError,
        match=r"^--fold-angle 1e3: fold_angle must be in \(0, 180\) " r"degrees, got 1e3$",
    ):
        s.check(1000.0, "--fold-angle 1e3: fold_angle", shown="1e3")


def test_samples_of_a_function():
    s = Spec("kappa", "function", 1.0, "(0, inf)", "per model unit")
    grid = np.linspace(0.0, 2.0, 5)
    s.check_samples(1 + grid, "k", lambda i: f"at s = {grid[i]:g}")
    for damaged, match in (
        (1 - grid, r"^k must be finite and > 0 per model unit; at s = 1 it is " r"0$"),
        (np.where(grid > 1, np.nan, 1.0), r"at s = 1\.5 it is nan$"),
    ):
        with pytest.raises(InputError, match=match):
            s.check_samples(damaged, "k", lambda i: f"at s = {grid[i]:g}")
    free = Spec("tau", "function", 0.0, "(-inf, inf)")
    with pytest.raises(InputError, match=r"^t must be finite; at s = 0\.5 it is inf$"):
        free.check_samples(np.array([0.0, np.inf]), "t", lambda i: f"at s = {grid[i]:g}")


def test_interval_mask_agrees_with_membership():
    for text in ("[0, 3)", "(0, inf)", "(-inf, inf)", "(0, 180]"):
        r = Interval.parse(text)
        x = np.array([-1.0, 0.0, 1e-300, 2.999, 3.0, 180.0, 1e300, np.inf, -np.inf, np.nan])
        assert r.mask(x).tolist() == [bool(np.isfinite(v)) and v in r for v in x]


def test_describe_and_required():
    assert (
        describe(np.float64(2.5)) == "2.5"
        and describe({"a": 1}) == "table {'a': 1}"
        and describe(None) == "NoneType None"
    )
    assert (
        Spec("kind", "choice", choices=("a",)).required
        and Spec("x", "real", None).required is False
    )
    assert repr(REQUIRED) == "REQUIRED"


# --------------------------------------------------------------------------------------------
# The schema


def _specs():
    return [(section, s) for section, specs in SCHEMA.items() for s in specs.values()]


@pytest.mark.parametrize(
    ("section", "s"), _specs(), ids=lambda v: v.name if isinstance(v, Spec) else v or "top"
)
def test_every_default_passes_its_own_check_and_every_bound_is_enforced(section, s):
    if not s.required and s.default is not None:  # formats default to those of the design's kind
        assert s.check(s.default) == s.default
    if s.kind in ("real", "integer", "function") and s.range is not None:
        r = s.range
        for bound, closed, step in ((r.lo, r.lo_closed, -1), (r.hi, r.hi_closed, 1)):
            if math.isfinite(bound):
                outside = (
                    bound + step
                    if s.kind == "integer"
                    else (bound if not closed else bound + step * max(1e-9, abs(bound) * 1e-9))
                )
                with pytest.raises(InputError, match=rf"^{s.name} must be"):
                    s.check(outside)


@pytest.mark.parametrize("name", ["a", "p_xy", "width", "radius", "layers"])
def test_vault_design_and_design_files_refuse_with_the_same_words(name):
    s = next(v for v in VAULT_SPECS if v.name == name)
    value = (
        s.range.hi + 1
        if s.kind == "integer"
        else s.range.hi * 2
        if math.isfinite(s.range.hi)
        else -1.0
    )
    with pytest.raises(InputError) as api:
        VaultDesign(**{name: value})
    with pytest.raises(InputError) as file:
        parse_design(f'kind = "vault"\n[vault]\n{name} = {value!r}', source="design.toml")
    assert str(file.value) == f"design.toml: [vault] {api.value}"


def test_vault_specs_are_the_vault_section():
    assert tuple(SCHEMA["vault"].values()) == VAULT_SPECS
    assert {s.name: s.default for s in VAULT_SPECS} | {"tubes": None, "direction": 1} == {
        k: getattr(VaultDesign(), k)
        for k in (
            "a",
            "p_xy",
            "width",
            "tubes",
            "fold_angle",
            "radius",
            "layers",
            "direction",
            "panels",
        )
    }


# --------------------------------------------------------------------------------------------
# Tables and the format registry


def test_pages_units_and_colours_are_one_table():
    assert (
        [page_size(name.upper()) for name in PAGES]
        == list(PAGES.values())
        == [page_mm(n.lower()) for n in PAGES]
    )
    assert SCHEMA["output"]["page"].choices == tuple(PAGES)
    with pytest.raises(InputError, match=r"page must be one of A5, A4"):
        page_mm("B9")
    assert mm_per_unit("in") == 25.4 and mm_per_unit("pt") == pytest.approx(25.4 / 72, rel=1e-15)
    assert set(SCHEMA["output"]["units"].choices) <= set(UNITS)
    assert gltf.CREASE_COLOURS["fold"] == rgba("fold") == (1.0, 0.0, 0.0, 1.0)
    assert dict(rhino.LAYERS) == {
        "Sheets": rgba8("surface"),
        "Strips": rgba8("surface"),
        **{k.title(): rgba8(k) for k in ("fold", "seam", "boundary")},
    }
    assert (
        cutters.CUTTERS["print"].colours["mountain"] == COLOURS["fold"]
        and cutters.CUTTERS["print"].colours["cut"] == COLOURS["boundary"]
    )
    assert SCHEMA["output"]["cutter"].choices == tuple(cutters.CUTTERS)


def test_registry_families_and_kinds():
    assert formats_of("pattern") == pattern.PATTERN_FORMATS == ("svg", "dxf", "pdf")
    assert set(formats_of("model")) == {"glb", "obj", "stl", "ply", "3dm"}
    assert default_formats("tube") == tuple(FORMATS) and default_formats("crease") == tuple(
        name for name in FORMATS if name not in ("gif", "assembly", "step")
    )
    assert SCHEMA["output"]["formats"].choices == tuple(FORMATS)
    with pytest.raises(
        InputError,
        match=r"formats must be a non-empty selection of \('svg', "
        r"'dxf', 'pdf'\), got \('obj',\)",
    ):
        check_formats(["obj"], "pattern")
    assert missing_dependencies(["svg", "obj", "fold"]) == []


def test_text_reads_as_a_design_files_value_or_stays_text_for_the_spec_to_refuse():
    from curvefold.kernel._validate import from_text

    real, count = Spec("width", "real", 1.0, "(0, inf)"), Spec("tubes", "count", 9, "[1, 99]")
    assert [from_text(real, t) for t in ("3", "0.5", "wide")] == [3, 0.5, "wide"]
    assert from_text(count, "max") == "max"
    with pytest.raises(InputError, match=r"^width must be a number, got 'wide'$"):
        real.check(from_text(real, "wide"), "width", shown="'wide'")
    assert from_text(Spec("formats", "formats", ()), "svg, ,pdf") == ["svg", "pdf"]
    assert from_text(Spec("page", "page", "A4", choices=("A4",)), "300,200") == [300.0, 200.0]
    assert from_text(Spec("cells", "cells", ((0, 0),)), "[[0, 1]]") == [[0, 1]]
    assert from_text(Spec("glue_tabs", "flag", True), "False") is False
