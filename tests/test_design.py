"""Tests of curvefold.app._design: the examples, the schema, every class of error, fuzzing."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose, assert_array_equal

from curvefold.app._design import (
    KINDS,
    SCHEMA,
    SECTIONS_OF_KIND,
    BlockParams,
    CreaseParams,
    CurveParams,
    Design,
    OutputParams,
    TableColumn,
    TubeParams,
    VaultParams,
    default_design,
    design_from_dict,
    load_design,
    parse_design,
)
from curvefold.app._loading import LoadParams, MaterialParams
from curvefold.io._formats import FORMATS
from curvefold.io._tables import PAGES
from curvefold.kernel import Expression, InputError, Interval, as_function

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SRC = "design.toml"


def parse(text: str, **kw) -> Design:
    return parse_design(text, source=SRC, **kw)


# --------------------------------------------------------------------------------------------
# A tiny TOML writer for the tests (tomllib only reads)


def toml_string(text: str) -> str:
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def toml_key(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else toml_string(key)


def toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return (
            "nan"
            if math.isnan(value)
            else ("inf" if value > 0 else "-inf")
            if math.isinf(value)
            else repr(value)
        )
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{toml_key(k)} = {toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(type(value))


def toml_dumps(data: dict) -> str:
    lines = [f"{toml_key(k)} = {toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for name, table in data.items():
        if isinstance(table, dict):
            lines.append(f"[{toml_key(name)}]")
            lines += [f"{toml_key(k)} = {toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def test_toml_writer_round_trips():
    import tomllib

    data = {"a": 1, "b": [1.5, -2.0, 'x"\\\n\x7f'], "t": {"k": {"csv": "f.csv"}, "": True}}
    assert tomllib.loads(toml_dumps(data)) == data


# --------------------------------------------------------------------------------------------
# The examples


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.name)
def test_example_loads_and_round_trips(path):
    design = load_design(path)
    assert design.kind in KINDS
    assert design.source == str(path)
    again = design_from_dict(design.to_dict(), base_dir=design.base_dir)
    assert again == design
    assert parse_design(toml_dumps(design.to_dict()), base_dir=path.parent) == design


def test_examples_cover_every_kind_and_csv():
    names = {p.name for p in EXAMPLES.glob("*.toml")}
    assert {
        "paper-vault.toml",
        "tube.toml",
        "cellular-block.toml",
        "single-fold.toml",
        "tube-csv.toml",
    } <= names
    assert {load_design(EXAMPLES / n).kind for n in names} == set(KINDS)


def test_paper_vault_values():
    d = load_design(EXAMPLES / "paper-vault.toml")
    assert d.vault == VaultParams(
        a=0.3,
        p_xy=0.75,
        width=0.08,
        tubes="max",
        fold_angle=90.0,
        radius=1.0,
        layers=1,
        direction="+",
    )
    assert d.samples == 801
    assert (d.curve, d.tube, d.block, d.crease) == (None, None, None, None)
    assert d.output == OutputParams(
        units="mm",
        scale=None,
        page="A4",
        glue_tabs=True,
        rulings=False,
        cutter="print",
        perforation=None,
        perforation_gap=1.0,
        kerf=0.0,
        formats=("svg", "pdf", "fold", "glb"),
    )


def test_tube_example_expressions():
    d = load_design(EXAMPLES / "tube.toml")
    assert isinstance(d.curve.kappa, Expression)
    s = np.linspace(0.0, 6.0, 13)
    assert_allclose(d.curve.kappa(s), 1 + 0.3 * np.sin(2 * np.pi * s / 6), rtol=1e-15)
    kappa = d.function("kappa")
    assert_allclose(kappa(s), 1 + 0.3 * np.sin(2 * np.pi * s / 6), rtol=1e-15)
    assert_allclose(kappa.derivative(s), 0.3 * 2 * np.pi / 6 * np.cos(2 * np.pi * s / 6), atol=1e-9)
    assert d.to_dict()["curve"]["kappa"] == "1 + 0.3*sin(2*pi*s/6)"


def test_csv_example_values():
    d = load_design(EXAMPLES / "tube-csv.toml")
    kappa, tau = d.curve.kappa, d.curve.tau
    assert (
        isinstance(kappa, TableColumn)
        and kappa.path == "tube-kappa-tau.csv"
        and kappa.column == "kappa"
    )
    s = np.linspace(0.0, 6.0, 61)
    assert_allclose(kappa.values, 1 + 0.25 * np.sin(2 * np.pi * s / 6) ** 2, atol=1e-9)
    assert_allclose(tau.values, 0.35 + 0.15 * np.cos(np.pi * s / 6), atol=1e-9)
    assert not kappa.values.flags.writeable
    # as_function takes the column directly (through __array__) and through Design.function.
    f = as_function(kappa, name="kappa", length=6.0)
    assert_allclose(f(s), kappa.values, atol=1e-12)
    assert_allclose(d.function("kappa")(s), kappa.values, atol=1e-12)
    assert d.to_dict()["curve"]["tau"] == {"csv": "tube-kappa-tau.csv", "column": "tau"}


def test_block_and_crease_examples():
    block = load_design(EXAMPLES / "cellular-block.toml")
    assert block.block.cells == ((0, 0), (0, 1), (1, 1))
    assert block.output.page == (500.0, 350.0)
    assert block.curve.kappa == 0.8
    crease = load_design(EXAMPLES / "single-fold.toml")
    assert crease.crease.alpha is None
    s = np.linspace(0.0, 3.0, 7)
    assert_allclose(crease.function("beta_left")(s), 80 + 10 * np.sin(np.pi * s / 3), rtol=1e-15)
    assert crease.function("kappa_2d").constant == 0.5


# --------------------------------------------------------------------------------------------
# Schema and defaults


def test_schema_matches_the_dataclasses():
    types = {
        "vault": VaultParams,
        "curve": CurveParams,
        "tube": TubeParams,
        "block": BlockParams,
        "crease": CreaseParams,
        "output": OutputParams,
        "material": MaterialParams,
        "loads": LoadParams,
    }
    for section, cls in types.items():
        listed = ["case"] if section == "loads" else []  # [[loads.case]]: tables checked apart
        assert [f.name for f in dataclasses.fields(cls)] == list(SCHEMA[section]) + listed
    assert set(SCHEMA) == {"", *types}


@pytest.mark.parametrize("kind", KINDS)
def test_flag_names_are_unique_within_a_kind(kind):
    names = [k for s in ("", *SECTIONS_OF_KIND[kind], "output") for k in SCHEMA[s]]
    assert len(names) == len(set(names))


@pytest.mark.parametrize("kind", KINDS)
def test_default_design(kind):
    d = default_design(kind)
    assert d.kind == kind and d.samples == 801 and d.title == ""
    for section in ("vault", "curve", "tube", "block", "crease"):
        assert (getattr(d, section) is not None) == (section in SECTIONS_OF_KIND[kind])
    assert d == parse(f'kind = "{kind}"')


def test_default_values():
    v = default_design("vault").vault
    assert (v.a, v.p_xy, v.width, v.tubes, v.fold_angle, v.radius, v.layers, v.direction) == (
        0.3,
        0.75,
        0.08,
        "max",
        90.0,
        1.0,
        1,
        "+",
    )
    c = default_design("crease").crease
    assert (c.kappa_2d, c.beta_left, c.beta_right, c.fold_angle, c.length, c.alpha) == (
        0.5,
        90.0,
        90.0,
        60.0,
        3.0,
        None,
    )
    assert default_design("block").block.cells == ((0, 0), (0, 1), (1, 1))


def test_default_design_unknown_kind():
    with pytest.raises(
        InputError,
        match=r'<defaults>: kind must be one of "vault", "tube", '
        r'"block", "crease", got string \'dome\'',
    ):
        default_design("dome")


def test_interval():
    r = Interval.parse("[0, 3)")
    assert 0 in r and 2.999 in r and 3 not in r and -1e-300 not in r and math.nan not in r
    assert str(r) == "in [0, 3)"
    assert str(Interval.parse("(0, inf)")) == "> 0"
    assert str(Interval.parse("[1, inf)")) == ">= 1"
    assert math.inf not in Interval.parse("(0, inf)")


def test_integers_become_floats_and_types_are_exact():
    d = parse('kind = "vault"\n[vault]\na = 1\nfold_angle = 45\ntubes = 3')
    assert d.vault.a == 1.0 and type(d.vault.a) is float
    assert type(d.vault.fold_angle) is float
    assert d.vault.tubes == 3 and type(d.vault.tubes) is int


def test_design_is_hashable_and_immutable():
    d = load_design(EXAMPLES / "tube.toml")
    assert hash(d) == hash(load_design(EXAMPLES / "tube.toml"))
    with pytest.raises(dataclasses.FrozenInstanceError):
        d.samples = 3  # type: ignore[misc]


def test_formats_deduplicated_and_pages():
    d = parse('kind = "vault"\n[output]\nformats = ["svg", "dxf", "svg"]\npage = "Letter"')
    assert d.output.formats == ("svg", "dxf")
    assert d.output.page == "Letter" and PAGES["Letter"] == (215.9, 279.4)


def test_expression_checked_on_the_sample_grid():
    with pytest.raises(
        InputError,
        match=r"design\.toml: \[curve\] kappa must be finite and > 0 "
        r"per model unit; at s = 2\.646 it is -0\.0044",
    ):
        parse('kind = "tube"\nsamples = 1001\n[curve]\nkappa = "sin(s + 0.5)"\nlength = 6.0')
    with pytest.raises(
        InputError,
        match=r"\[crease\] beta_left must be finite and in \(0, 180\) "
        r"degrees; at s = 0 it is 180",
    ):
        parse('kind = "crease"\n[crease]\nbeta_left = "180 - s"')
    with pytest.raises(InputError, match=r"\[curve\] tau must be finite; at s = 0 it is inf"):
        parse('kind = "tube"\n[curve]\ntau = "1/s"')


def test_crease_alpha_optional():
    d = parse('kind = "crease"\n[crease]\nalpha = "30 + s"')
    assert isinstance(d.crease.alpha, Expression)
    assert d.to_dict()["crease"]["alpha"] == "30 + s"
    with pytest.raises(
        InputError, match=r"\[crease\] alpha must be in \(0, 90\) degrees, got " r"90\.0"
    ):
        parse('kind = "crease"\n[crease]\nalpha = 90')
    with pytest.raises(InputError, match=r"\[crease\] alpha is not set"):
        default_design("crease").function("alpha")
    with pytest.raises(InputError, match=r"'kappa' is not a function-valued key of kind 'vault'"):
        default_design("vault").function("kappa")


# --------------------------------------------------------------------------------------------
# Overrides


def test_overrides_replace_values_and_validate():
    d = load_design(EXAMPLES / "paper-vault.toml")
    e = d.overrides(
        a=0.5, samples=1601, fold_angle=60.0, formats=["dxf"], width=None, **{"p-xy": 1.5}
    )
    assert (e.vault.a, e.samples, e.vault.fold_angle, e.output.formats, e.vault.p_xy) == (
        0.5,
        1601,
        60.0,
        ("dxf",),
        1.5,
    )
    assert e.vault.width == d.vault.width  # None leaves the file value
    assert d.vault.a == 0.3  # the original is untouched
    assert e.source == f"{d.source} (with overrides)"
    with pytest.raises(
        InputError,
        match=r"paper-vault\.toml \(with overrides\): \[vault\] "
        r"fold_angle must be in \(0, 180\) degrees, got 0\.0",
    ):
        d.overrides(fold_angle=0.0)
    with pytest.raises(
        InputError,
        match=r"unknown option 'kappa' for kind 'vault' \(allowed: " r"samples, title, a, p_xy",
    ):
        d.overrides(kappa="1")
    with pytest.raises(InputError, match=r"unknown option 'radios' .*did you mean 'radius'\?"):
        d.overrides(radios=2.0)


def test_overrides_section_mapping_and_functions():
    d = load_design(EXAMPLES / "tube-csv.toml")
    e = d.overrides(curve={"kappa": "2 + s", "tau": 0.1, "length": 4.0}, width_left=0.1)
    assert isinstance(e.curve.kappa, Expression) and e.curve.kappa.text == "2 + s"
    assert (e.curve.tau, e.curve.length, e.tube.width_left) == (0.1, 4.0, 0.1)
    assert e.curve.fold_angle == d.curve.fold_angle
    # The CSV s column runs to 6, so a new length is refused for the CSV-driven tau.
    with pytest.raises(InputError, match=r"the s column must run from 0 to length 4"):
        d.overrides(length=4.0)


def test_overrides_change_kind():
    d = load_design(EXAMPLES / "paper-vault.toml")
    e = d.overrides(kind="crease", length=2.0)
    assert e.kind == "crease" and e.vault is None and e.crease.length == 2.0
    assert e.output == d.output and e.samples == d.samples
    with pytest.raises(InputError, match=r"kind must be one of"):
        d.overrides(kind="dome")


# --------------------------------------------------------------------------------------------
# Errors


@pytest.mark.parametrize(
    ("text", "match"),
    [
        # unknown keys and sections
        (
            'kind = "vault"\n[vault]\nradios = 1.0',
            r"^design\.toml: \[vault\] unknown key 'radios' \(allowed: a, p_xy, width, tubes, "
            r"fold_angle, radius, layers, direction, panels\); did you mean 'radius'\?$",
        ),
        (
            'kind = "vault"\n[vaults]\na = 1',
            r"^design\.toml: unknown section \[vaults\] .*did " r"you mean 'vault'\?$",
        ),
        (
            'kind = "vault"\nsampels = 3',
            r"design\.toml: unknown key 'sampels' \(allowed keys: "
            r"kind, samples, title; sections: vault, curve",
        ),
        (
            'kind = "vault"\n[output]\nformat = ["svg"]',
            r"\[output\] unknown key 'format' .*did " r"you mean 'formats'\?",
        ),
        (
            "samples = 3",
            r"design\.toml: missing required key 'kind' \(one of \"vault\", "
            r"\"tube\", \"block\", \"crease\"\)",
        ),
        (
            'kind = "dome"',
            r"design\.toml: kind must be one of \"vault\", \"tube\", \"block\", "
            r"\"crease\", got string 'dome'",
        ),
        ("kind = 3", r"kind must be one of .*, got 3$"),
        # sections for another kind
        (
            'kind = "vault"\n[curve]\nlength = 2.0',
            r"design\.toml: section \[curve\] is used by kind 'tube' or 'block', not by kind "
            r"'vault'; remove it or change kind",
        ),
        (
            'kind = "tube"\n[block]\ncells = [[0, 0]]',
            r"section \[block\] is used by kind " r"'block', not by kind 'tube'",
        ),
        (
            'kind = "crease"\n[vault]',
            r"section \[vault\] is used by kind 'vault', not by kind " r"'crease'",
        ),
        (
            'kind = "vault"\nvault = 3',
            r"design\.toml: vault must be a table \(\[vault\] " r"section\), got 3$",
        ),
        (
            'kind = "vault"\n[[vault]]\na = 1',
            r"vault must be a table \(\[vault\] section\), got " r"array",
        ),
        # wrong types
        (
            'kind = "vault"\n[vault]\nfold_angle = "90"',
            r"design\.toml: \[vault\] fold_angle must " r"be a number \(degrees\), got string '90'",
        ),
        ('kind = "vault"\n[vault]\na = true', r"\[vault\] a must be a number, got boolean True"),
        (
            'kind = "vault"\nsamples = 801.0',
            r"design\.toml: samples must be an integer in \[9, " r"200000\] \(.*\), got 801\.0",
        ),
        ('kind = "vault"\nsamples = "801"', r"samples must be an integer .*, got string '801'"),
        (
            'kind = "vault"\n[vault]\ntubes = "many"',
            r"\[vault\] tubes must be an integer in \[1, " r"1000\] or \"max\", got string 'many'",
        ),
        (
            'kind = "vault"\n[vault]\ntubes = 2.0',
            r"tubes must be an integer in \[1, 1000\] or " r"\"max\", got 2\.0",
        ),
        (
            'kind = "vault"\n[vault]\nlayers = [1]',
            r"\[vault\] layers must be an integer in \[1, " r"50\], got array \[1\]",
        ),
        (
            'kind = "vault"\n[vault]\ndirection = "up"',
            r"direction must be one of \"\+\", \"-\", " r"got string 'up'",
        ),
        (
            'kind = "vault"\n[output]\nglue_tabs = 1',
            r"\[output\] glue_tabs must be true or " r"false, got 1",
        ),
        (
            'kind = "vault"\n[output]\nformats = "svg"',
            r"\[output\] formats must be an array of " r"format names",
        ),
        (
            'kind = "vault"\n[output]\nformats = ["svg", "png"]',
            r"\[output\] formats: unknown " r"format string 'png' \(allowed: svg, dxf",
        ),
        (
            'kind = "vault"\n[output]\npage = "A9"',
            r"page must be one of \"A5\", \"A4\", \"A3\", "
            r"\"A2\", \"A1\", \"A0\", \"Letter\", \"Legal\", \"Tabloid\" or \[width, height\] "
            r"in mm, got string 'A9'",
        ),
        (
            'kind = "vault"\n[output]\npage = [100.0]',
            r"page must be one of .*, got array " r"\[100\.0\]",
        ),
        (
            'kind = "vault"\n[output]\nunits = "ft"',
            r"units must be one of \"mm\", \"cm\", \"m\", " r"\"in\", got string 'ft'",
        ),
        (
            'kind = "vault"\ntitle = 3',
            r"design\.toml: title must be a string of at most 1000 " r"characters, got 3",
        ),
        ('kind = "vault"\ntitle = 1979-05-27', r"title must be a string .*, got date "),
        (
            'kind = "block"\n[block]\ncells = [[0]]',
            r"\[block\] cells\[0\] must be a pair \[i, "
            r"j\] of integers in \[-1000, 1000\], got array \[0\]",
        ),
        ('kind = "block"\n[block]\ncells = [[0, 0], [0, 0.5]]', r"cells\[1\] must be a pair"),
        (
            'kind = "block"\n[block]\ncells = [[0, 0], [1, 0], [0, 0]]',
            r"\[block\] cells\[2\] " r"repeats cell \[0, 0\] \(first at index 0\)",
        ),
        (
            'kind = "block"\n[block]\ncells = []',
            r"cells must be an array of 1 to 10000 \[i, j\] " r"pairs, got array \[\]",
        ),
        ('kind = "block"\n[block]\ncells = [[0, 2000]]', r"cells\[0\] must be a pair"),
        (
            'kind = "tube"\n[curve]\nkappa = true',
            r"\[curve\] kappa must be a number, an "
            r"expression in s or a table \{csv = \.\.\., column = \.\.\.\}, got boolean True",
        ),
        (
            'kind = "tube"\n[curve]\nkappa = [1.0, 2.0]',
            r"\[curve\] kappa must be a number, an " r"expression .*, got array",
        ),
        # out of range
        (
            'kind = "vault"\n[vault]\nfold_angle = 180.0',
            r"^design\.toml: \[vault\] fold_angle " r"must be in \(0, 180\) degrees, got 180\.0$",
        ),
        (
            'kind = "vault"\n[vault]\nfold_angle = 0',
            r"fold_angle must be in \(0, 180\) degrees, " r"got 0\.0",
        ),
        (
            'kind = "vault"\n[vault]\na = 3.0',
            r"\[vault\] a must be in \[0, 1\.2707093728\) \(no "
            r"arch stands beyond it: Eq\. \(20\) has no root next to π there\), got 3\.0",
        ),
        (
            'kind = "vault"\n[vault]\na = -0.1',
            r"a must be in \[0, 1\.2707093728\) \(no arch "
            r"stands beyond it: Eq\. \(20\) has no root next to π there\), got -0\.1",
        ),
        ('kind = "vault"\n[vault]\np_xy = 100.5', r"p_xy must be in \(0, 100\], got 100\.5"),
        ('kind = "vault"\n[vault]\nwidth = 0', r"width must be in \(0, 10\], got 0\.0"),
        (
            'kind = "vault"\n[vault]\nradius = -1',
            r"\[vault\] radius must be in \[0\.001, "
            r"1000000\] model units \(numerical range\), got -1\.0",
        ),
        (
            'kind = "vault"\n[vault]\nradius = inf',
            r"\[vault\] radius must be a finite number, " r"got inf",
        ),
        ('kind = "vault"\n[vault]\nradius = nan', r"radius must be a finite number, got nan"),
        (
            'kind = "vault"\n[vault]\ntubes = 0',
            r"tubes must be an integer in \[1, 1000\] or " r"\"max\", got 0",
        ),
        ('kind = "vault"\n[vault]\nlayers = 51', r"layers must be an integer in \[1, 50\], got 51"),
        (
            'kind = "vault"\nsamples = 8',
            r"samples must be an integer in \[9, 200000\] \(the "
            r"certificate's differences need 9; memory is budgeted besides\), got 8",
        ),
        ('kind = "vault"\nsamples = 200001', r"samples must be .*, got 200001"),
        (
            'kind = "vault"\n[output]\nscale = 0.0',
            r"\[output\] scale must be > 0 output units " r"per model unit, got 0\.0",
        ),
        (
            'kind = "vault"\n[output]\npage = [0, 297]',
            r"\[output\] page width must be in \(0, " r"10000\] mm, got 0\.0",
        ),
        (
            'kind = "vault"\n[output]\npage = [210, 1e5]',
            r"page height must be in \(0, 10000\] " r"mm, got 100000\.0",
        ),
        (
            'kind = "tube"\n[curve]\nkappa = 0',
            r"\[curve\] kappa must be > 0 per model unit, got " r"0\.0",
        ),
        (
            'kind = "tube"\n[curve]\nlength = 0',
            r"\[curve\] length must be in \[0\.001, 1000000\] "
            r"model units \(numerical range\), got 0\.0",
        ),
        (
            'kind = "crease"\n[crease]\nbeta_right = 180',
            r"\[crease\] beta_right must be in \(0, " r"180\) degrees, got 180\.0",
        ),
        (
            'kind = "vault"\n[vault]\na = 1' + "0" * 400,
            r"\[vault\] a is too large, got an " r"integer of \d+ bits",
        ),
        # expressions
        (
            'kind = "tube"\n[curve]\nkappa = "1 + x"',
            r"^design\.toml: \[curve\] kappa: unknown " r"name 'x' \(allowed: s, pi, e\)$",
        ),
        (
            'kind = "tube"\n[curve]\ntau = "s.__class__"',
            r"design\.toml: \[curve\] tau: attribute " r"access is not allowed",
        ),
        (
            'kind = "crease"\n[crease]\nkappa_2d = "9**9**9"',
            r"\[crease\] kappa_2d: constant " r"exponent",
        ),
        # malformed TOML
        (
            'kind = "vault"\n[vault\na = 1',
            r"^design\.toml: invalid TOML: .*\(at line 2, column " r"\d+\)$",
        ),
        ("kind = \n", r"design\.toml: invalid TOML: Invalid value \(at line 1, column 8\)"),
        ('kind = "vault"\nkind = "tube"', r"design\.toml: invalid TOML: Cannot overwrite a value"),
        ('kind = "vault"\na = ' + "[" * 5000, r"design\.toml: invalid TOML: nested too deeply"),
        (
            'kind = "vault"\nsamples = ' + "9" * 5000,
            r"design\.toml: invalid TOML: Exceeds the " r"limit",
        ),
    ],
)
def test_errors(text, match):
    with pytest.raises(InputError, match=match):
        parse(text)


def test_error_messages_are_one_line():
    with pytest.raises(InputError) as info:
        parse('kind = "tube"\n[curve]\nkappa = "(1 +\n * 2)"')
    assert "\n" not in str(info.value)


def test_not_text_or_not_a_table():
    with pytest.raises(InputError, match=r"design\.toml: expected TOML text, got bytes"):
        parse_design(b"kind = 1", source=SRC)
    with pytest.raises(InputError, match=r"<dict>: a design must be a table, got array \[\]"):
        design_from_dict([])
    with pytest.raises(InputError, match=r"design\.toml: design text is longer than"):
        parse("#" * (2 << 20))


def test_json_null_means_default():
    d = design_from_dict({"kind": "vault", "samples": None, "vault": {"a": None}})
    assert d == default_design("vault")
    with pytest.raises(InputError, match="kind must be one of"):
        design_from_dict({"kind": None})


def test_numpy_numbers_accepted():
    d = design_from_dict(
        {
            "kind": "vault",
            "samples": np.int64(401),
            "vault": {"a": np.float32(0.5), "tubes": np.int32(3)},
        }
    )
    assert d.samples == 401 and type(d.samples) is int and d.vault.a == 0.5 and d.vault.tubes == 3
    with pytest.raises(InputError, match="glue_tabs must be true or false"):
        design_from_dict({"kind": "vault", "output": {"glue_tabs": "yes"}})


# --------------------------------------------------------------------------------------------
# Files and CSV tables


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


CSV_DESIGN = (
    'kind = "tube"\n[curve]\nlength = 6.0\nkappa = {{ csv = "{path}", column = "{column}" }}\n'
)


def csv_design(
    tmp_path: Path, csv_text: str, *, path: str = "k.csv", column: str = "kappa"
) -> Design:
    write(tmp_path, path if ".." not in path and not path.startswith("/") else "k.csv", csv_text)
    return load_design(write(tmp_path, "design.toml", CSV_DESIGN.format(path=path, column=column)))


def test_csv_without_s_column_and_in_subfolder(tmp_path):
    d = csv_design(tmp_path, "kappa\n1.0\n2.0\n3.0\n", path="data/k.csv")
    assert_array_equal(d.curve.kappa.values, [1.0, 2.0, 3.0])
    assert d.to_dict()["curve"]["kappa"] == {"csv": "data/k.csv", "column": "kappa"}


def test_csv_column_defaults_to_key_and_skips_comments(tmp_path):
    write(tmp_path, "k.csv", "\ufeff# measured\n s , kappa \n\n0, 1\n3, 2\n6, 3\n")
    d = load_design(write(tmp_path, "d.toml", 'kind = "tube"\n[curve]\nkappa = {csv = "k.csv"}\n'))
    assert_array_equal(d.curve.kappa.values, [1.0, 2.0, 3.0])


def test_csv_s_column_tolerates_print_rounding(tmp_path):
    s = np.linspace(0.0, 6.0, 7)
    rows = "\n".join(f"{x + 1e-7:.7f},1.5" for x in s)
    assert_array_equal(csv_design(tmp_path, "s,kappa\n" + rows).curve.kappa.values, np.full(7, 1.5))


@pytest.mark.parametrize(
    ("csv_text", "path", "column", "match"),
    [
        # escapes
        (
            "kappa\n1\n2\n",
            "../k.csv",
            "kappa",
            r"design\.toml: \[curve\] kappa: csv path must be "
            r"relative to the design file's folder and stay inside it, got '\.\./k\.csv'",
        ),
        ("kappa\n1\n2\n", "a/../../k.csv", "kappa", r"stay inside it"),
        ("kappa\n1\n2\n", "/etc/passwd", "kappa", r"stay inside it, got '/etc/passwd'"),
        ("kappa\n1\n2\n", "C:\\\\k.csv", "kappa", r"stay inside it"),
        ("kappa\n1\n2\n", "..\\\\k.csv", "kappa", r"stay inside it"),
        # spacing
        (
            "s,kappa\n0,1\n1,1\n3,1\n6,1\n",
            "k.csv",
            "kappa",
            r"\[curve\] kappa \(k\.csv\): the s column must be uniformly spaced over \[0, 6\]: at "
            r"line 3 s = 1, expected 2 \(4 samples, spacing 2\)",
        ),
        (
            "s,kappa\n0,1\n2.5,1\n5,1\n",
            "k.csv",
            "kappa",
            r"the s column must run from 0 to " r"length 6, got 0 to 5",
        ),
        (
            "s,kappa\n1,1\n3.5,1\n6,1\n",
            "k.csv",
            "kappa",
            r"the s column must run from 0 to " r"length 6, got 1 to 6",
        ),
        ("s,kappa\n0,1\nnan,1\n6,1\n", "k.csv", "kappa", r"uniformly spaced .* s = nan"),
        # contents
        ("kappa\n1\n", "k.csv", "kappa", r"column 'kappa' needs at least 2 samples, got 1"),
        ("", "k.csv", "kappa", r"CSV file is empty"),
        (
            "kappa,tau\n1,2\n3\n",
            "k.csv",
            "kappa",
            r"\(k\.csv\): line 3 has 1 fields, the header " r"has 2",
        ),
        ("kappa\n1\nabc\n", "k.csv", "kappa", r"\(k\.csv\): line 3: 'abc' is not a number"),
        ("kappa\n1\n2\n", "k.csv", "tau", r"\(k\.csv\): no column 'tau' \(columns: 'kappa'\)"),
        (
            "kappa\n1\n-1\n2\n",
            "k.csv",
            "kappa",
            r"\(k\.csv\) column 'kappa' must be finite and > "
            r"0 per model unit; at line 3 \(s = 3\) it is -1",
        ),
        (
            "kappa\n1\ninf\n",
            "k.csv",
            "kappa",
            r"must be finite and > 0 .* at line 3 \(s = 6\) it " r"is inf",
        ),
        ('kappa\n1\n"2\n', "k.csv", "kappa", r"\(k\.csv\): (malformed CSV|line \d+)"),
    ],
)
def test_csv_errors(tmp_path, csv_text, path, column, match):
    with pytest.raises(InputError, match=match):
        csv_design(tmp_path, csv_text, path=path, column=column)


def test_csv_missing_file_and_bad_table(tmp_path):
    d = write(tmp_path, "d.toml", 'kind = "tube"\n[curve]\nkappa = {csv = "none.csv"}\n')
    with pytest.raises(
        InputError, match=r"d\.toml: \[curve\] kappa: csv file 'none\.csv' not " r"found"
    ):
        load_design(d)
    d = write(tmp_path, "d.toml", 'kind = "tube"\n[curve]\nkappa = {csv = "k.csv", col = "x"}\n')
    with pytest.raises(
        InputError,
        match=r"\[curve\] kappa: unknown key 'col' in CSV table " r"\(allowed: csv, column\)",
    ):
        load_design(d)
    d = write(tmp_path, "d.toml", 'kind = "tube"\n[curve]\nkappa = {column = "x"}\n')
    with pytest.raises(
        InputError,
        match=r"kappa: csv must be a file name relative to the design " r"file, got NoneType None",
    ):
        load_design(d)
    d = write(tmp_path, "d.toml", 'kind = "tube"\n[curve]\nkappa = {csv = ".", column = "x"}\n')
    with pytest.raises(InputError, match=r"csv file '\.' not found"):
        load_design(d)


def test_csv_symlink_escape(tmp_path):
    outside = write(tmp_path, "outside/k.csv", "kappa\n1\n2\n")
    inside = tmp_path / "project"
    inside.mkdir()
    try:
        (inside / "k.csv").symlink_to(outside)
    except OSError:
        pytest.skip("symlinks not available")
    d = write(inside, "d.toml", 'kind = "tube"\n[curve]\nkappa = {csv = "k.csv"}\n')
    with pytest.raises(
        InputError, match=r"csv path 'k\.csv' leads outside the design file's " r"folder"
    ):
        load_design(d)


def test_csv_non_utf8(tmp_path):
    (tmp_path / "k.csv").write_bytes(b"kappa\n\xff\n")
    d = write(tmp_path, "d.toml", 'kind = "tube"\n[curve]\nkappa = {csv = "k.csv"}\n')
    with pytest.raises(InputError, match=r"CSV file is not UTF-8 text \(bad byte at offset 6\)"):
        load_design(d)


def test_parse_design_reads_csv_from_base_dir(tmp_path):
    write(tmp_path, "k.csv", "kappa\n1\n2\n")
    d = parse_design('kind = "tube"\n[curve]\nkappa = {csv = "k.csv"}\n', base_dir=tmp_path)
    assert_array_equal(d.curve.kappa.values, [1.0, 2.0])


def test_load_design_file_errors(tmp_path):
    with pytest.raises(
        InputError, match=r"missing\.toml: cannot read design file: No such file " r"or directory"
    ):
        load_design(tmp_path / "missing.toml")
    with pytest.raises(
        InputError, match=r"cannot read design file: it is a folder, not a " r"regular file"
    ):
        load_design(tmp_path)
    bad = tmp_path / "bad.toml"
    bad.write_bytes(b'kind = "vault"\ntitle = "\xff"\n')
    with pytest.raises(
        InputError, match=r"bad\.toml: design file is not UTF-8 text \(bad byte " r"at offset 24\)"
    ):
        load_design(bad)
    big = tmp_path / "big.toml"
    big.write_text("#" * (2 << 20))
    with pytest.raises(
        InputError,
        match=r"big\.toml: design file is 2097152 bytes, more than " r"the limit of 1048576 bytes",
    ):
        load_design(big)


# --------------------------------------------------------------------------------------------
# Fuzzing: only InputError may escape


@pytest.fixture(scope="module")
def fuzz_dir(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fuzz")
    write(folder, "k.csv", "s,kappa,tau\n0,1,0\n3,1.5,0.1\n6,1,0\n")
    return folder


_names = st.one_of(
    st.sampled_from(
        sorted({k for section in SCHEMA.values() for k in section} | set(SCHEMA) - {""})
    ),
    st.text(max_size=8),
)
_scalars = st.one_of(
    st.booleans(),
    st.integers(min_value=-(10**20), max_value=10**20),
    st.floats(),
    st.text(max_size=20),
    st.sampled_from(
        [
            "max",
            "svg",
            "A4",
            "mm",
            "+",
            "vault",
            "tube",
            "block",
            "crease",
            "1 + s",
            "k.csv",
            "kappa",
        ]
    ),
)
_values = st.recursive(
    _scalars,
    lambda inner: st.one_of(
        st.lists(inner, max_size=4), st.dictionaries(_names, inner, max_size=4)
    ),
    max_leaves=10,
)
_documents = st.builds(
    lambda kind, top, sections: {**top, **({} if kind is None else {"kind": kind}), **sections},
    st.one_of(st.none(), st.sampled_from(KINDS), _scalars),
    st.dictionaries(_names, _values, max_size=4),
    st.dictionaries(
        st.sampled_from(sorted(set(SCHEMA) - {""})),
        st.one_of(st.dictionaries(_names, _values, max_size=5), _values),
        max_size=3,
    ),
)


def _only_input_error(call):
    try:
        design = call()
    except InputError as exc:
        assert str(exc)
        return None
    assert isinstance(design, Design)
    return design


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_documents)
def test_fuzz_dicts(fuzz_dir, data):
    design = _only_input_error(lambda: design_from_dict(data, base_dir=fuzz_dir))
    try:
        text = toml_dumps(data)
    except TypeError:
        return
    _only_input_error(lambda: parse_design(text, base_dir=fuzz_dir))
    if design is not None:
        assert design_from_dict(design.to_dict(), base_dir=fuzz_dir) == design


_toml_alphabet = st.sampled_from(
    list('kind="vaulttubeblockcrease"[]{}=,.\n 0123456789-+eE_:#\'\\samplesoutputcsv')
)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(st.text(max_size=200), st.text(alphabet=_toml_alphabet, max_size=200)))
def test_fuzz_text(fuzz_dir, text):
    _only_input_error(lambda: parse_design(text, base_dir=fuzz_dir))


# Valid designs drawn from the schema itself: every one loads and round-trips.


def _valid_value(spec):
    if spec.kind == "real" or (spec.kind == "function" and spec.range.lo > -math.inf):
        r = spec.range
        hi = min(r.hi, 1e6)
        return st.floats(
            min_value=r.lo,
            max_value=hi,
            exclude_min=not r.lo_closed,
            exclude_max=not r.hi_closed or hi < r.hi,
        )
    if spec.kind == "function":
        return st.one_of(st.floats(-1e6, 1e6), st.sampled_from(["0.2*cos(s)", "s - 1", "pi/4"]))
    if spec.kind == "integer":
        return st.integers(int(spec.range.lo), min(int(spec.range.hi), 2000))
    if spec.kind == "count":
        return st.one_of(st.just("max"), st.integers(1, 20))  # within the vertex budget
    if spec.kind == "choice":
        return st.sampled_from(spec.choices)
    # one line, no control characters (those are refused, tests/test_attacks.py)
    if spec.kind == "text":
        return st.text(
            st.characters(
                exclude_categories=("Cc", "Cs", "Zl", "Zp"),
                exclude_characters="\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069",
            ),
            max_size=30,
        )
    if spec.kind == "flag":
        return st.booleans()
    if spec.kind == "page":
        return st.one_of(
            st.sampled_from(spec.choices), st.lists(st.floats(1.0, 1000.0), min_size=2, max_size=2)
        )
    if spec.kind == "formats":
        return st.lists(st.sampled_from(tuple(FORMATS)), max_size=4, unique=True)
    if spec.kind == "cells":
        return st.lists(
            st.tuples(st.integers(-3, 3), st.integers(-3, 3)).map(list),
            min_size=1,
            max_size=6,
            unique_by=tuple,
        )
    raise AssertionError(spec.kind)


def _without_alpha_conflicts(section: dict) -> dict:
    """A [crease] with alpha gives neither beta_right nor fold_angle (they follow from alpha)."""
    return {
        k: v
        for k, v in section.items()
        if "alpha" not in section or k not in ("beta_right", "fold_angle")
    }


def _drawable(data: dict) -> dict:
    """A document whose print scale draws its crease at least the scale bar long
    (io.formats.check_scale)."""
    from curvefold.io._formats import MIN_DRAWN_MM
    from curvefold.io._tables import mm_per_unit

    out = data.get("output", {})
    if out.get("scale") is None:
        return data
    kind = data["kind"]
    section = {"vault": "vault", "crease": "crease"}.get(kind, "curve")
    length = (
        math.pi * data.get("vault", {}).get("radius", 1.0)
        if kind == "vault"
        else data.get(section, {}).get("length", SCHEMA[section]["length"].default)
    )
    least = MIN_DRAWN_MM / (length * mm_per_unit(out.get("units", "mm")))
    return {**data, "output": {**out, "scale": max(out["scale"], 1.01 * least)}}


def _valid_documents(kind):
    sections = {
        s: st.fixed_dictionaries(
            {}, optional={k: _valid_value(spec) for k, spec in SCHEMA[s].items()}
        )
        for s in (*SECTIONS_OF_KIND[kind], "output")
    }
    if kind == "crease":
        sections["crease"] = sections["crease"].map(_without_alpha_conflicts)
    top = {k: _valid_value(spec) for k, spec in SCHEMA[""].items() if k != "kind"}
    return st.fixed_dictionaries({"kind": st.just(kind)}, optional={**top, **sections}).map(
        _drawable
    )


@settings(max_examples=100, deadline=None)
@given(st.sampled_from(KINDS).flatmap(_valid_documents))
def test_valid_documents_load_and_round_trip(data):
    design = parse_design(toml_dumps(data))
    assert design_from_dict(data) == design
    assert design_from_dict(design.to_dict()) == design
    for section, table in data.items():
        if isinstance(table, dict):
            for key, value in table.items():
                got = design.to_dict()[section][key]
                if isinstance(value, float) or (
                    isinstance(value, list) and SCHEMA[section][key].kind == "page"
                ):
                    assert np.allclose(got, value)
                elif SCHEMA[section][key].kind != "formats":
                    assert got == value
