"""Thick panels from the command line (curvefold.app._thickness) and in the certificate: the files
read back (a watertight STL, closed solids in the 3dm, the cut list), the range and DOF against
the library's, refusals in one line, and each thickness check failing on its damage.
"""

from __future__ import annotations

import csv
import json
import re
import struct

import numpy as np
import pytest
import rhino3dm

import curvefold.analysis._thick_checks as thick_checks
from _cli import run
from curvefold import Crease, InputError, Lattice, SpaceCurve, Structure
from curvefold.analysis import certify
from curvefold.app._thickness import TAPER
from curvefold.geometry import PanelLattice, ThickPanels, ThickRange
from curvefold.geometry._thick import thickness_limit
from curvefold.mechanics import MATERIALS
from curvefold.vault import Vault, VaultDesign
from test_thick import _moved_hinge

T = 0.002  # metres: 2 mm plywood on a vault of radius 1 m
FLAGS = ("--panels", "8", "--tubes", "2", "--thickness", str(T), "--material", "plywood")


def refused(r, match: str) -> None:
    lines = r.stderr.splitlines()
    assert (
        r.returncode == 2 and r.stdout == "" and len(lines) == 1 and "Traceback" not in r.stderr
    ), r.stderr
    assert re.search(match, lines[0]), lines[0]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """The output folder and printed JSON of a two-tube vault of 2 mm plywood panels."""
    out = tmp_path_factory.mktemp("thick") / "vault"
    r = run("vault", *FLAGS, "--formats", "3dm", "--out", str(out), "--json")
    assert r.returncode == 0 and r.stderr == "", r.stderr
    return out, json.loads(r.stdout)


@pytest.fixture(scope="module")
def library():
    """The same vault's thick panels, built by the library."""
    return ThickPanels.offset(Vault.from_design(VaultDesign(panels=8, tubes=2)).structure, T)


def _stl(path):
    """Triangles (n, 3, 3) of a binary STL."""
    data = path.read_bytes()
    (n,) = struct.unpack("<I", data[80:84])
    records = np.frombuffer(
        data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    )
    assert len(records) == n
    return records["v"].astype(float)


def test_the_vault_writes_its_solids_as_a_watertight_stl_and_closed_3dm_solids(folder, library):
    out, _ = folder
    tri = _stl(out / "vault_solids.stl")
    assert tri.shape == (64 * 12, 3, 3)  # 64 quads, 12 triangles each
    # watertight: in every solid (welded as written, float32) every directed edge once, and its
    # reverse once (neighbours share their hinge corners, so the solids are welded apart)
    for solid in tri.reshape(64, 12, 3, 3):
        points = np.unique(solid.reshape(-1, 3), axis=0)
        assert len(points) == 8
        ids = [[int(np.flatnonzero((points == p).all(1))[0]) for p in t] for t in solid]
        directed = [(a, b) for t in ids for a, b in zip(t, t[1:] + t[:1])]
        assert len(set(directed)) == 36 and set(directed) == {(b, a) for a, b in directed}
    # 1:1 in millimetres: the library's solids at the design angle, to float32 rounding
    x, triangles = library.triangles()
    ulp = float(np.spacing(np.float32(2048)))  # 2.4e-4 mm: coordinates reach 1.9e3 mm
    assert np.abs(tri - 1e3 * x[triangles]).max() <= ulp
    # the 3dm: a closed Brep per panel, named as the cut list, in metres
    model = rhino3dm.File3dm.Read(str(out / "vault_solids.3dm"))
    assert str(model.Settings.ModelUnitSystem) == "UnitSystem.Meters"
    solids = list(model.Objects)
    assert len(solids) == 64 and all(o.Geometry.IsSolid for o in solids)
    assert [o.Attributes.Name for o in solids] == list(library.labels())
    # its corners are the solid's, in double precision
    for f, o in enumerate(solids):
        corners = np.array(
            [[v.Location.X, v.Location.Y, v.Location.Z] for v in o.Geometry.Vertices]
        )
        assert np.abs(np.sort(corners, 0) - np.sort(x[8 * f : 8 * f + 8], 0)).max() < 1e-15


def test_the_cut_list_gives_every_edge_its_length_bevel_and_hinge(folder, library):
    out, _ = folder
    rows = list(csv.DictReader((out / "vault_cut_list.csv").read_text("utf-8").splitlines()))
    assert len(rows) == 64 * 4
    listed = json.loads((out / "vault_cut_list.json").read_text())["panels"]
    for row in rows:
        panel = listed[[p["panel"] for p in listed].index(row["panel"])]
        e = int(row["edge"]) - 1
        assert float(row["bevel_deg"]) == pytest.approx(panel["bevels"][e], abs=1e-3)
        assert float(row["length_mm"]) == pytest.approx(1e3 * panel["edges"][e], abs=1e-5)
        assert bool(int(row["hinged"])) == panel["hinged"][e]
        ends = np.array([[row["x0_mm"], row["y0_mm"]], [row["x1_mm"], row["y1_mm"]]], float)
        assert np.linalg.norm(ends[1] - ends[0]) == pytest.approx(float(row["length_mm"]), 1e-6)
    # the PDF: a printable row per panel, the CSV's numbers as printed
    pdfplumber = pytest.importorskip("pdfplumber")
    with pdfplumber.open(out / "vault_cut_list.pdf") as doc:
        assert len(doc.pages) == 3  # 22 rows a page
        text = "\n".join(page.extract_text() for page in doc.pages)
    outline = library.local[:, :4, :2] * 1e3
    lengths = np.linalg.norm(np.roll(outline, -1, axis=1) - outline, axis=-1)
    bevels = np.degrees(library.bevels)
    row = {f: n + 1 for n, f in enumerate(library.order.tolist())}  # the order of assembly
    for f, label in enumerate(library.labels()):
        parts = label.split(" · ")  # printed on two lines, numbered
        first, second = (re.escape(" · ".join(p)) for p in (parts[:2], parts[2:]))
        assert re.search(rf"^{row[f]}\. {first}(?= |$).*\n{second}(?= |$)", text, re.M), label
        for e in range(4):
            printed = f"{e + 1}: {lengths[f, e]:.1f}, {bevels[f, e]:.1f}°"
            assert printed + (" hinged" if library.hinged[f, e] else "") in text, printed
    assert max(float(r["bevel_deg"]) for r in rows) == pytest.approx(
        np.degrees(library.bevels.max()), abs=1e-3
    )


def test_the_report_states_the_range_stack_and_dof_as_the_library_measures_them(folder, library):
    out, printed = folder
    report = json.loads((out / "report.json").read_text())
    t = report["thickness"]
    assert printed["thickness"] == t
    r = library.motion_range()
    assert (t["range"]["low"], t["range"]["high"]) == (r.low, r.high)
    assert 10 < r.low < 20  # two tubes' walls meet: it stops short of flat
    assert t["range"]["short_of_flat"] == r.low
    assert t["range"]["low_contact"] == [library.labels()[i] for i in r.low_pair]
    # the zero-thickness range beside it: flat to the certificate's first contact
    assert t["zero_thickness_range"] == {
        "low": 0.0,
        "high": report["certificate_frames"]["first_contact"],
        "ends_at_contact": True,
    }
    assert t["stack_height"] == pytest.approx(2 * T, abs=1e-12)  # two plies
    assert t["dof"] and set(t["dof"]) == {1} and t["dof_scope"] == "every tube"
    # the mass: the solids' volume (prismatoid, independent of the triangles) times plywood's
    k = library.local.shape[1] // 2

    def area(z):  # the section's area at height z, from the outline set back by z tan b
        from curvefold.geometry._thick_solids import prism

        xy = prism(library.local[:, :k, :2], z, library.bevels)[:, k:, :2]
        return 0.5 * np.abs(
            (xy[..., 0] * np.roll(xy[..., 1], -1, 1) - xy[..., 1] * np.roll(xy[..., 0], -1, 1)).sum(
                1
            )
        )

    volume = (T / 6 * (area(0.0) + 4 * area(T / 2) + area(T))).sum()
    assert t["volume"] == pytest.approx(volume, rel=1e-9)
    assert t["mass"] == pytest.approx(volume * MATERIALS["plywood"].density, rel=1e-9)
    page = (out / "report.html").read_text("utf-8")
    assert "<h2>Thick panels</h2>" in page and f"{r.low:.4g}° to 90°" in page
    names = {c["name"]: c["status"] for c in report["certificate"]}
    assert [names[n] for n in ("thick_hinges", "thick_contact", "thick_dof")] == ["pass"] * 3
    assert set(report["files"]) >= {
        "vault_solids.stl",
        "vault_solids.3dm",
        "vault_cut_list.csv",
        "vault_cut_list.json",
        "vault_cut_list.pdf",
    }


def test_the_summary_says_how_far_the_thick_vault_folds(tmp_path):
    r = run("vault", *FLAGS, "--formats", "fold", "--out", str(tmp_path / "v"))
    assert r.returncode == 0, r.stderr
    assert re.search(r"thick panels +64 of plywood 2 mm", r.stdout)
    assert re.search(
        r"range with t +2α = 1\d\.\d+° to 90° \(zero thickness: 0° to \d+°\)", r.stdout
    )
    assert "flat stack         4 mm, were it to fold flat; DOF 1 (every tube)" in r.stdout


def test_a_thickness_the_panels_or_the_design_angle_cannot_take_is_one_line(tmp_path):
    # more than the smallest panel's inradius
    refused(
        run("vault", "--panels", "16", "--thickness", "0.05", "--material", "plywood", "--json"),
        r"^curvefold: error: curvefold vault .*: \[material\] thickness must be in \(0, 0\.0108\) "
        r"model units \(the smallest panel's inradius, .*\), got 0\.05, or a vault of radius > "
        r"4\.63 \(--radius",
    )
    # two tubes' walls need 45° bevels at the design angle: more than even tapered panels take
    refused(
        run(*TWO_TUBES, "--thickness", "0.025", "--json"),
        r"thickness must be below 0\.0222 model units to reach the design angle 2α = 90° \(.* "
        r"needs a bevel of 45°, which would set its top face back by more than 0\.75 of its "
        r"inradius .*\), got 0\.025: use a thinner sheet or fewer panels, or a vault of radius > "
        r"1\.13 \(--radius",
    )
    # a design file says the same, naming its section
    (tmp_path / "design.toml").write_text(
        'kind = "vault"\n[vault]\npanels = 16\n[material]\nmaterial = "plywood"\nthickness = 0.02\n'
    )
    refused(
        run("vault", "design.toml", "--json", cwd=tmp_path),
        r"^curvefold: error: design\.toml: \[material\] thickness must be in \(0, 0\.0108\) ",
    )


TWO_TUBES = ("vault", "--panels", "8", "--tubes", "2", "--material", "plywood")


def test_the_radius_the_refusal_asks_for_is_the_one_that_builds():
    structure = Vault.from_design(VaultDesign(panels=8, tubes=2)).structure
    limit = thickness_limit(structure, setback=TAPER)
    t = 0.03
    need = t / limit  # radius 1: lengths, and the limit, scale with it
    flags = (*TWO_TUBES, "--thickness", str(t))
    r = run(*flags, "--radius", f"{need * 0.999:.6g}", "--json")
    refused(r, rf"radius > {need:.3g} ")
    r = run(*flags, "--radius", f"{need * 1.001:.6g}", "--json")
    assert r.returncode == 0, r.stderr
    thickness = json.loads(r.stdout)["thickness"]
    assert thickness["range"]["high"] == pytest.approx(90, abs=1e-6)
    assert thickness["technique"].startswith("tapered panels") and thickness["setback"] == TAPER


def test_the_issues_command_builds_tapered_panels_where_offset_ones_cannot_reach():
    """1 cm plywood on the paper's vault (radius 1 m): offset panels' bevels cannot reach the
    design angle, tapered ones (top faces set back up to 3/4 of the inradius) can."""
    structure = Vault.from_design(VaultDesign(panels=16)).structure
    with pytest.raises(InputError, match=r"^thickness must be below 0\.00856 model units"):
        ThickPanels.offset(structure, 0.01)
    r = run("vault", "--panels", "16", "--thickness", "0.01", "--material", "plywood", "--json")
    assert r.returncode == 0, r.stderr
    payload = json.loads(r.stdout)
    t = payload["thickness"]
    assert t["technique"] == (
        "tapered panels (top faces set back up to 0.75 of the inradius), solids outside the tubes"
    )
    tapered = ThickPanels.offset(structure, 0.01, setback=TAPER)
    expected = tapered.motion_range()
    assert (t["range"]["low"], t["range"]["high"]) == (expected.low, expected.high)
    assert 65 < expected.low < 75 and set(t["dof"]) == {1}
    names = {c["name"]: c["status"] for c in payload["certificate"]}
    assert [names[n] for n in ("thick_hinges", "thick_contact", "thick_dof")] == ["pass"] * 3


# -- the certificate's thickness checks, each failing on its damage -------------------------------
@pytest.fixture(scope="module")
def tube():
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=161
    )
    smooth = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)
    structure = Structure.tube(PanelLattice.from_lattice(smooth, 8))
    return smooth.crease, ThickPanels.offset(structure, T)


def _thick_statuses(crease, thick) -> dict:
    cert = certify(crease, thick.structure, thick=thick)
    return {c.name: c.status for c in cert.checks if c.name.startswith("thick_")}


def test_the_certificate_passes_the_thickness_checks_of_correct_thick_panels(tube):
    crease, thick = tube
    cert = certify(crease, thick.structure, thick=thick)
    assert cert.passed and cert.thickness is not None
    assert _thick_statuses(crease, thick) == dict.fromkeys(
        ("thick_hinges", "thick_contact", "thick_dof"), "pass"
    )
    assert certify(crease, thick.structure).thickness is None  # thin: no thickness checks


def test_a_hinge_off_its_crease_fails_the_hinges_and_the_dof(tube):
    crease, thick = tube
    assert _thick_statuses(crease, _moved_hinge(thick, 9, 1, T)) == {
        "thick_hinges": "fail",
        "thick_contact": "pass",
        "thick_dof": "fail",
    }


def test_a_range_stated_past_the_first_contact_fails_the_contact(tube, monkeypatch):
    crease, thick = tube
    monkeypatch.setattr(
        ThickPanels, "motion_range", lambda self, **kw: ThickRange(90.0, 0.0, 95.0, None, None)
    )
    assert _thick_statuses(crease, thick) == {
        "thick_hinges": "pass",
        "thick_contact": "fail",
        "thick_dof": "pass",
    }


def test_hinges_left_unjoined_fail_the_dof(tube, monkeypatch):
    """Hinge ends welded only where they coincide exactly: every solid a free body."""
    crease, thick = tube
    framework = thick_checks.thick_framework
    monkeypatch.setattr(
        thick_checks, "thick_framework", lambda thick, tol=1e-9: framework(thick, tol=1e-300)
    )
    assert _thick_statuses(crease, thick) == {
        "thick_hinges": "pass",
        "thick_contact": "pass",
        "thick_dof": "fail",
    }


def test_a_tube_of_thick_panels_folds_flat_and_a_block_sharing_walls_is_refused():
    r = run("tube", "--panels", "8", "--thickness", "0.002", "--json")
    assert r.returncode == 0, r.stderr
    t = json.loads(r.stdout)["thickness"]
    assert t["range"]["low"] == 0.0 and t["range"]["short_of_flat"] == 0.0
    assert t["stack_height"] == pytest.approx(0.004, abs=1e-12)  # two plies of 2 mm
    assert t["material"] == "polypropylene"  # the default material, its thickness given
    assert t["technique"] == "offset panels, solids outside the tubes" and set(t["dof"]) == {1}
    # the default block's tubes share walls: offset outward, a ply enters the other tube
    refused(
        run("block", "--panels", "8", "--thickness", "0.002", "--json"),
        r"^curvefold: error: thickness: at the design angle 2α = 90° the solids of panel \d+ of "
        r"tube \d and panel \d+ of tube \d interpenetrate by .* build the cells along one "
        r"diagonal$",
    )
    # smooth sheets keep zero thickness: no thick panels, whatever the material says
    r = run("tube", "--thickness", "0.002", "--samples", "101", "--json")
    assert r.returncode in (0, 1) and "thickness" not in json.loads(r.stdout), r.stderr
