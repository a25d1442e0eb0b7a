"""Thick panels' ids and their order of assembly (curvefold.geometry._thick_ids): the cut list's
rows, the assembly guide's steps and the cut list printed in the guide name the same panels,
each once, in the same order; the guide read back by pdfplumber.
"""

from __future__ import annotations

import csv
import re

import numpy as np
import pytest

from curvefold.figures._assembly import assembly_plan, write_assembly
from curvefold.geometry import ThickPanels
from curvefold.geometry._thick_ids import SHEET_STRIPS, assembly_order, panel_ids
from curvefold.io import layout_pattern
from curvefold.io._solids import write_cut_list_csv
from curvefold.vault import Vault, VaultDesign

pdfplumber = pytest.importorskip("pdfplumber")
MM = 72 / 25.4
ID = re.compile(r"^tube (\d+) · sheet ([AB]) · strip ([1-4]) · panel (\d+)$")


@pytest.fixture(scope="module")
def vault():
    """Two tubes of 4 panels per crease, 2 mm thick, and its crease pattern's layout."""
    structure = Vault.from_design(VaultDesign(panels=4, tubes=2)).structure
    return ThickPanels.offset(structure, 0.002), layout_pattern(structure)


def same_order(guide: tuple[str, ...], rows: list[str], ids: tuple[str, ...]) -> bool:
    """Whether the guide's order names every panel once and the cut list's rows follow it."""
    return (
        len(set(guide)) == len(guide) == len(ids)
        and set(guide) == set(ids)
        and (list(guide) == rows)
    )


def test_every_id_names_its_tube_sheet_strip_and_place_once(vault):
    thick, _ = vault
    ids = thick.labels()
    group = thick.structure.topology().faces_group
    assert len(set(ids)) == len(ids) == 32
    for f, label in enumerate(ids):
        tube, sheet, strip, place = ID.match(label).groups()  # type: ignore[union-attr]
        g = int(group[f])
        assert (int(tube), int(strip)) == (g // 4 + 1, g % 4 + 1)
        # the crease pattern's sheets (curvefold.geometry._sheets): A = strips 4, 1; B = 2, 3
        assert sheet == ("A" if g % 4 in (3, 0) else "B")
        assert int(place) == f - int(np.flatnonzero(group == g)[0]) + 1  # from the crease's start
    assert dict(SHEET_STRIPS) == {"A": (3, 0), "B": (1, 2)}


def test_the_order_is_tube_by_tube_sheet_a_then_b_strip_by_strip_along_the_crease(vault):
    thick, _ = vault
    ids = [thick.labels()[f] for f in thick.order]
    keys = [tuple(ID.match(i).groups()) for i in ids]  # type: ignore[union-attr]
    strips = {"4": 0, "1": 1, "2": 2, "3": 3}
    ranks = [(int(t), strips[s], int(p)) for t, _, s, p in keys]
    assert ranks == sorted(ranks) and len(set(ranks)) == 32
    assert ids[:5] == [f"tube 1 · sheet A · strip 4 · panel {p}" for p in (1, 2, 3, 4)] + [
        "tube 1 · sheet A · strip 1 · panel 1"
    ]
    # on a small hand-made grouping: strips 4, 1, 2, 3 of tube 1, then tube 2
    assert assembly_order(np.array([0, 0, 1, 2, 3, 3, 4])).tolist() == [4, 5, 0, 1, 2, 3, 6]
    assert panel_ids(np.array([3, 3]))[1] == "tube 1 · sheet A · strip 4 · panel 2"


def test_the_guides_order_is_the_cut_lists_rows_and_a_damaged_order_fails(vault, tmp_path):
    thick, layout = vault
    plan = assembly_plan(thick.structure, layout, thick=thick)
    rows = [r["panel"] for r in thick.cut_list()]
    text = write_cut_list_csv(tmp_path / "c.csv", thick).read_text().splitlines()
    csv_rows = list(csv.DictReader(text))
    k = thick.local.shape[1] // 2
    assert [r["panel"] for r in csv_rows[::k]] == rows
    assert same_order(plan.panels, rows, thick.labels())
    assert [len(s.panels) for s in plan.steps] == [16, 16]
    # damaged: two panels swapped, one named twice, one left out
    swapped = (plan.panels[1], plan.panels[0], *plan.panels[2:])
    assert not same_order(swapped, rows, thick.labels())
    assert not same_order((*plan.panels[:-1], plan.panels[0]), rows, thick.labels())
    assert not same_order(plan.panels[:-1], rows[:-1], thick.labels())
    # each step says the cut-list rows of its strips, in the order
    assert "cut-list rows 1–4: tube 1 · sheet A · strip 4 · panel 1 to 4" in plan.steps[0].lines[0]
    assert "cut-list rows 29–32" in plan.steps[1].lines[1]
    assert "tube 2's crease 1" in plan.steps[1].lines[-1]


def test_the_guide_prints_the_steps_and_the_cut_list_in_one_order(vault, tmp_path):
    thick, layout = vault
    path = write_assembly(tmp_path / "assembly.pdf", thick.structure, layout, thick=thick)
    with pdfplumber.open(path) as pdf:
        texts = [page.extract_text() for page in pdf.pages]
        # the ids' column of the cut list's pages: left of the sketches (62 mm)
        column = [p.crop((0, 20 * MM, 60 * MM, p.height)).extract_text() for p in pdf.pages]
    a4 = [t for t in texts if t.startswith("Cut list:")]
    assert len(a4) == 2 and len(texts) > 2  # 32 rows: 22 a page
    text = "\n".join(column[-2:])
    printed = re.findall(r"^(\d+)\. (tube \d · sheet [AB])\n(strip \d · panel \d)", text, re.M)
    assert [int(n) for n, _, _ in printed] == list(range(1, 33))
    rows = [r["panel"] for r in thick.cut_list()]
    assert [f"{a} · {b}" for _, a, b in printed] == rows
    guide = "\n".join(texts[: -len(a4)])
    assert "Panels to cut and hinge" in guide and "Order: tube by tube" in guide
    assert "Cut list:" not in guide
    # panels are hinged, not glued: no seams, tabs or scoring of sheets
    assert not re.search(r"tabs|[Gg]lue|[Ss]core", guide)
    # without thick panels the guide has no cut list
    plain = write_assembly(tmp_path / "plain.pdf", thick.structure, layout)
    with pdfplumber.open(plain) as pdf:
        assert not any((p.extract_text() or "").startswith("Cut list:") for p in pdf.pages)


def test_the_commands_guide_has_the_panels_only_where_the_command_writes_them(tmp_path):
    """`curvefold vault|tube|block` (thick files written) gets the panels' guide; `curvefold load`
    of the same design (its thickness the mechanics' alone) keeps the sheets' guide."""
    from curvefold.app import _products as products
    from curvefold.app import design_from_dict
    from curvefold.app._build import build

    data = {"kind": "vault", "vault": {"panels": 4, "tubes": 2}, "material": {"thickness": 0.002}}
    built = build(design_from_dict(data))
    for thick, cut_list in ((True, True), (False, False)):
        jobs = dict(products.jobs(built, ("assembly",), thick=thick))
        folder = tmp_path / str(thick)
        folder.mkdir()
        (path,) = jobs["assembly guide"](folder)
        with pdfplumber.open(path) as pdf:
            texts = [page.extract_text() or "" for page in pdf.pages]
        assert any(t.startswith("Cut list: 32 panels 2 mm thick") for t in texts) is cut_list
        assert ("Panels to cut and hinge" in texts[0]) is cut_list
