"""The atlas under load: the mechanics columns, their agreement with ``curvefold load``, the
figure's marks, the flags and the memory estimate.

A 3 × 3 grid at 41 samples, polypropylene 1 mm under its own weight and 0.3 kPa of snow: the
row a = 0.3 (9 tubes) stands, the row a = 0.9 (1–2 tubes) fails its deflection check and the
row a = 1.5 has no arch (empty cells). Each check is shown failing on damaged input.
"""

import csv
import json
import math

import pytest

from _cli import run
from curvefold import InputError
from curvefold.app._budget import atlas_mechanics, require_atlas_budget
from curvefold.mechanics import MATERIALS, AtlasLoad, G, Loads, SelfWeight, Snow
from curvefold.mechanics._atlas_load import LOAD_FIELDS
from curvefold.vault import run_atlas
from curvefold.vault._atlas import FIELDS

pytest.importorskip("matplotlib")

P_XY, A_VALUES = [0.75, 1.0, 1.25], [0.3, 0.9, 1.5]
FLAGS = ["--samples", "41", "--load", "--snow", "0.3", "--workers", "1"]
LOAD = AtlasLoad(MATERIALS["polypropylene"], 1e-3, Loads((SelfWeight(), Snow(300.0))))
#: The columns that hold numbers.
NUMBERS = ("buckling_factor", "utilisation", "deflection", "deflection_span", "mass")


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """The command's summary and its folder."""
    out = tmp_path_factory.mktemp("atlas") / "out"
    grid = ["--p-xy", ",".join(map(str, P_XY)), "--a", ",".join(map(str, A_VALUES))]
    result = run("atlas", *grid, *FLAGS, "--out", str(out), "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout), out


@pytest.fixture(scope="module")
def records(written):
    """The records of atlas.json, read strictly (a NaN or infinity is an error)."""

    def refuse(name):
        raise ValueError(f"non-finite number {name} in atlas.json")

    text = (written[1] / "atlas.json").read_text()
    return json.loads(text, parse_constant=refuse)["records"]


@pytest.fixture(scope="module")
def atlas():
    return run_atlas(P_XY, A_VALUES, samples=41, load=LOAD, workers=1)


def unusable(record: dict) -> list[str]:
    """The mechanics cells of a record that break the columns' promise: a valid design has every
    number finite and a verdict; an invalid one has every cell empty."""
    if not record["valid"]:
        return [k for k in LOAD_FIELDS if record[k] is not None]
    bad = [
        k
        for k in NUMBERS
        if not (isinstance(record[k], float) and math.isfinite(record[k]) and record[k] > 0)
    ]
    bad += [] if isinstance(record["stands"], bool) else ["stands"]
    bad += [] if record["governing"] in ("stability", "strength", "deflection") else ["governing"]
    return bad


def test_columns_are_present_finite_and_empty_for_invalid_designs(written, records):
    payload, out = written
    header = json.loads((out / "atlas.json").read_text())
    assert header["fields"] == list(FIELDS + LOAD_FIELDS)
    assert header["load"]["loads"] == "self-weight + snow 0.3 kPa"
    assert (header["load"]["samples"], header["load"]["across"]) == (41, 1)
    with open(out / "atlas.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == list(FIELDS + LOAD_FIELDS)
    assert [r["valid"] for r in records] == [True] * 6 + [False] * 3
    assert all(unusable(r) == [] for r in records)
    assert all(r[k] == "" for r in rows[6:] for k in LOAD_FIELDS)  # no arch: empty cells
    # the rows: a = 0.3 stands (stability governs), a = 0.9 fails its deflection
    assert [r["stands"] for r in records[:6]] == [True] * 3 + [False] * 3
    assert {r["governing"] for r in records[3:6]} == {"deflection"}
    assert all(r["utilisation"] > 1 for r in records[3:6])
    assert payload["stands"] == 3
    light = payload["lightest"]
    assert (light["row"], light["col"]) == (0, 0)
    assert light["mass"] == min(r["mass"] for r in records if r["stands"])


def test_the_check_of_the_columns_fails_on_damaged_records(records):
    good, invalid = records[0], records[-1]
    assert unusable(good | {"mass": math.nan}) == ["mass"]
    assert unusable(good | {"deflection": math.inf}) == ["deflection"]
    assert unusable(good | {"buckling_factor": None}) == ["buckling_factor"]
    assert unusable(good | {"stands": None, "governing": "wind"}) == ["stands", "governing"]
    assert unusable(invalid | {"mass": 1.0}) == ["mass"]


def test_the_summary_names_the_lightest_design_that_stands(tmp_path):
    grid = ["--p-xy", "0.75,1.0", "--a", "0.3,0.9"]
    result = run("atlas", *grid, *FLAGS, "--out", str(tmp_path / "out"))
    assert result.returncode == 0, result.stderr
    line = result.stdout.splitlines()[1]
    assert line.startswith("  under load: 2/4 valid designs stand; the lightest: a = 0.3, p_xy = ")
    assert "p_xy = 0.75 (row 0, column 0), 7.203 kg, 9 tubes, governed by stability" in line


def load_figures(record: dict) -> dict:
    """``curvefold load --json`` on the record's design (its a, p_xy, width and tubes) at the
    model's samples, with the atlas's loads: its exit status and payload."""
    result = run(
        "load",
        "--a",
        repr(record["a"]),
        "--p-xy",
        repr(record["p_xy"]),
        "--width",
        repr(record["width"]),
        "--tubes",
        str(record["tubes"]),
        "--samples",
        "41",
        "--snow",
        "0.3",
        "--across",
        "1",
        "--json",
    )
    assert result.returncode in (0, 1), result.stderr
    return json.loads(result.stdout) | {"status": result.returncode}


def disagreements(record: dict, loaded: dict) -> list[str]:
    """The columns of an atlas record that are not what ``curvefold load`` says of its design."""
    deflection = next(c for c in loaded["checks"] if c["name"] == "deflection")
    span = deflection["limit"] * 250.0  # its limit: the span / 250
    expected = {
        "buckling_factor": loaded["buckling_factor"],
        "utilisation": loaded["governing"]["utilisation"],
        "deflection": deflection["value"],
        "deflection_span": deflection["value"] / span,
        "mass": loaded["total_weight"] / G,
    }
    off = [k for k, v in expected.items() if not math.isclose(record[k], v, rel_tol=1e-9)]
    off += [] if record["governing"] == loaded["governing"]["name"] else ["governing"]
    stands = loaded["verdict"] == "stands" and loaded["status"] == 0
    return off + ([] if record["stands"] == stands else ["stands"])


@pytest.mark.parametrize("index", [1, 5], ids=["stands", "fails"])
def test_a_designs_columns_are_what_curvefold_load_prints(records, index):
    record = records[index]
    loaded = load_figures(record)
    assert loaded["samples"] == 41 and loaded["thickness"] == 1e-3  # the same model
    assert disagreements(record, loaded) == []
    # damaged: each column off by a part in a million, or the verdict turned
    for key in NUMBERS:
        assert disagreements(record | {key: record[key] * (1 + 1e-6)}, loaded) == [key]
    assert disagreements(record | {"stands": not record["stands"]}, loaded) == ["stands"]


def sheet_mass(record: dict) -> float:
    """ρ t × the developed area of the record's vault at the model's samples: the area of its
    mesh's triangles (each tube's two sheets), in m² (radius 1 m)."""
    import numpy as np

    from curvefold.vault import Vault, VaultDesign

    design = VaultDesign(a=record["a"], p_xy=record["p_xy"], tubes=record["tubes"], samples=41)
    mesh = Vault.from_design(design).structure.state().mesh()
    x = mesh.vertices_coords[mesh.faces_vertices]
    area = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1).sum()
    return MATERIALS["polypropylene"].density * 1e-3 * float(area)


def test_the_mass_is_the_sheets_density_times_its_developed_area(records):
    for record in records[:6]:
        assert record["mass"] == pytest.approx(sheet_mass(record), rel=1e-12)
    narrower = records[4] | {"p_xy": 0.75}  # damaged: another proportion, the same tubes
    assert sheet_mass(narrower) != pytest.approx(records[4]["mass"], rel=0.1)


def marks(figure) -> dict[str, set[tuple[int, int]]]:
    """(row, col) of the cells outlined as standing and as the lightest, read off the figure."""
    ax = figure.axes[0]
    rows = round(ax.get_ylim()[1])
    found: dict[str, set[tuple[int, int]]] = {"stands": set(), "lightest": set()}
    for patch in ax.patches:
        if patch.get_gid() in found:
            x, y = patch.get_xy()
            found[patch.get_gid()].add((rows - 1 - math.floor(y), math.floor(x)))
    return found


def mark_errors(atlas, figure) -> list[str]:
    """How the figure's marks differ from the records' verdicts."""
    stands = {(r["row"], r["col"]) for r in atlas.records if r["stands"] is True}
    light = min((r for r in atlas.records if r["stands"] is True), key=lambda r: r["mass"])
    found = marks(figure)
    errors = [] if found["stands"] | found["lightest"] == stands else ["stands"]
    return errors + ([] if found["lightest"] == {(light["row"], light["col"])} else ["lightest"])


def test_the_figure_marks_the_designs_that_stand(atlas, records):
    import matplotlib.pyplot as plt

    from curvefold.figures._atlas import atlas_figure

    assert [r["stands"] for r in atlas.records] == [r["stands"] for r in records]
    figure = atlas_figure(atlas)
    try:
        assert mark_errors(atlas, figure) == []
        assert marks(figure)["lightest"] == {(0, 0)}
        assert [t.get_text() for t in figure.axes[0].get_legend().get_texts()] == [
            "stands",
            "lightest that stands",
        ]
        # damaged: a design that stands recorded as failing, one that fails as standing (and,
        # lighter, as the lightest), or the lightest made heavier
        failing = atlas.records[1] | {"stands": False}
        damaged = type(atlas)(atlas.grid, (atlas.records[0], failing, *atlas.records[2:]), ())
        assert mark_errors(damaged, figure) == ["stands"]
        standing = atlas.records[3] | {"stands": True}
        damaged = type(atlas)(atlas.grid, (*atlas.records[:3], standing, *atlas.records[4:]), ())
        assert mark_errors(damaged, figure) == ["stands", "lightest"]
        heavy = atlas.records[0] | {"mass": 100.0}
        damaged = type(atlas)(atlas.grid, (heavy, *atlas.records[1:]), ())
        assert mark_errors(damaged, figure) == ["lightest"]
    finally:
        plt.close(figure)


@pytest.mark.parametrize(
    ("flags", "words"),
    [
        (["--load", "--thickness", "0"], "--thickness 0: thickness must be in (0, 1) m"),
        (["--load", "--load-samples", "7"], "--load-samples 7: load_samples must be an integer"),
        (["--load", "--across", "65"], "--across 65: across must be"),
        (["--load", "--snow", "-1"], "--snow -1: snow must be in [0, 1000] kPa"),
        (["--load", "--material", "steel"], "--material steel: material must be one of"),
        (["--thickness", "0.002"], "--thickness sets the mechanics columns, which only --load"),
        (
            ["--load", "--load-samples", "801", "--across", "64"],
            "this atlas needs about",
        ),
    ],
)
def test_a_bad_flag_is_one_line_and_exit_2(flags, words, tmp_path):
    out = tmp_path / "out"
    result = run(
        "atlas", "--p-xy", "0.75", "--a", "0.3", "--samples", "41", *flags, "--out", str(out)
    )
    assert result.returncode == 2
    assert result.stdout == "" and result.stderr.count("\n") == 1, result.stderr
    assert words in result.stderr
    assert flags[-1] in result.stderr or "budget" in result.stderr  # the value, or the budget
    assert not out.exists()  # refused before any work


def test_the_memory_estimate_counts_the_mechanics(monkeypatch):
    monkeypatch.delenv("CURVEFOLD_MEMORY_BUDGET", raising=False)
    plain = require_atlas_budget(25, samples=201, workers=2)
    loaded = require_atlas_budget(25, samples=201, workers=2, load=LOAD)
    # each process holds one vault's mechanics: 24 tubes at 41 samples
    assert loaded - plain == pytest.approx(2 * atlas_mechanics(41, 1))
    assert atlas_mechanics(81, 1) > atlas_mechanics(41, 1)
    assert atlas_mechanics(41, 4) > 4**2 * (atlas_mechanics(41, 1) - atlas_mechanics(21, 1))
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "1G")
    require_atlas_budget(25, samples=201, workers=2, load=LOAD)
    heavy = AtlasLoad(MATERIALS["polypropylene"], 1e-3, across=4, samples=81)
    with pytest.raises(InputError, match="mechanics on 81 samples × 4"):
        require_atlas_budget(25, samples=201, workers=2, load=heavy)


def test_a_design_the_model_refuses_gets_empty_cells_and_its_reason():
    from curvefold.vault import Vault

    vault = Vault.from_design(samples=201, tubes=1)
    columns = AtlasLoad(MATERIALS["polypropylene"], 1e-3, Loads(())).measure(vault)  # no load
    assert all(columns[k] is None for k in LOAD_FIELDS if k != "load_error")
    assert columns["load_error"].startswith("InputError: ")
    # a vault that cannot be built again at the model's samples: here more tubes than it holds
    from dataclasses import replace

    crowded = replace(vault, design=replace(vault.design, tubes=1000))
    columns = LOAD.measure(crowded)
    assert columns["load_error"].startswith("RegressionError: tubes must be ≤ 9")
    assert all(columns[k] is None for k in LOAD_FIELDS if k != "load_error")


def test_the_columns_are_the_same_on_a_local_cluster(atlas):
    pytest.importorskip("distributed")
    two = run_atlas(P_XY, A_VALUES, samples=41, load=LOAD, workers=2)
    assert two.records == atlas.records
