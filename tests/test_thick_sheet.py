"""Crease patterns for thick sheets (curvefold.io._thick_sheet): the drawn insets against the
closed form, a thick strip folded from the drawn pattern against the design's lengths, the
lapped seams, and glue tabs and perforation sized to the sheet; each check shown failing on
damaged input."""

from __future__ import annotations

import numpy as np
import pytest

from curvefold import Crease, InputError, Lattice, SpaceCurve, Structure
from curvefold.app.cli import main
from curvefold.geometry import Mesh, PatternSheet
from curvefold.geometry._bend import Bend
from curvefold.geometry._sheets import sheets
from curvefold.geometry._topology import fold_assignment
from curvefold.io._output import PatternOutput
from curvefold.io._pattern import layout_pattern
from curvefold.io._sheet_bend import sheet_bend
from curvefold.io._thick_sheet import thick_sheet, thick_sheets


def strip(n: int, legs: tuple[float, float], length: float, angle) -> PatternSheet:
    """A sheet of three rows of n samples: seam 0 at y = −legs[0], a straight crease on y = 0
    whose edges fold by ``angle(x)`` degrees at their midpoints, seam 1 at y = legs[1]."""
    x = np.linspace(0.0, length, n)
    xy = np.concatenate([np.c_[x, np.full(n, y)] for y in (-legs[0], 0.0, legs[1])])
    tris = []
    for r in (0, 1):
        for i in range(n - 1):
            v00, v10, v01, v11 = r * n + i, r * n + i + 1, (r + 1) * n + i, (r + 1) * n + i + 1
            tris += [(v00, v10, v11), (v00, v11, v01)]
    faces = np.array(tris)
    edges = sorted(
        {tuple(sorted(p)) for t in tris for p in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    )
    ev = np.array(edges)
    row, col = ev // n, ev % n
    kind = np.where(
        row[:, 0] == row[:, 1],
        np.where(row[:, 0] == 1, "fold", "seam"),
        np.where(
            col[:, 0] != col[:, 1],
            "diagonal",
            np.where(np.isin(col[:, 0], (0, n - 1)), "boundary", "ruling"),
        ),
    )
    mid = xy[ev].mean(axis=1)[:, 0]
    fold_angle = np.where(kind == "fold", -angle(mid), 0.0)
    seam = np.where(kind == "seam", row[:, 0] // 2, -1)
    mesh = Mesh(
        vertices_coords=np.c_[xy, np.zeros(len(xy))],
        edges_vertices=ev,
        edges_assignment=fold_assignment(kind, fold_angle, seams_open=True),
        edges_foldAngle=fold_angle,
        faces_vertices=faces,
        edges_kind=kind,
        faces_group=np.zeros(len(faces), int),
    )
    return PatternSheet("strip", mesh, seam)


def closed_inset(bend: Bend, fold_deg) -> np.ndarray:
    """δ = (R + K t)(tan(θ/2) − θ/2), written out."""
    theta = np.radians(fold_deg)
    return (bend.radius + bend.k * bend.thickness) * (np.tan(theta / 2) - theta / 2)


def folded_legs(drawn: tuple[float, float], bend: Bend, fold_deg: float) -> np.ndarray:
    """Fold a real sheet cut to the drawn legs (each from its seam to the crease line, the bend's
    centre line): a flat leg, the neutral arc of radius R + K t over the bend allowance, a flat
    leg; the legs' lines crossed by a linear solve give the design's sharp fold, and the legs'
    lengths to it are returned."""
    theta = np.radians(fold_deg)
    rho = bend.radius + bend.k * bend.thickness
    half = 0.5 * rho * theta  # half the allowance each side of the centre line
    d0, d1 = np.array([1.0, 0.0]), np.array([np.cos(theta), np.sin(theta)])
    start = np.zeros(2)
    t0 = start + (drawn[0] - half) * d0  # first tangent point
    centre = t0 + rho * np.array([0.0, 1.0])
    t1 = centre + rho * np.array([np.sin(theta), -np.cos(theta)])  # second tangent point
    end = t1 + (drawn[1] - half) * d1
    s, _ = np.linalg.solve(np.c_[d0, -d1], t1 - start)
    corner = start + s * d0
    return np.array([np.linalg.norm(corner - start), np.linalg.norm(end - corner)])


def test_drawn_inset_is_the_closed_form_at_every_sample_of_a_crease():
    """A crease whose fold angle runs from 60° to 100° along it (each edge's at its midpoint, so
    each inner sample's is the linear law's there): every seam sample across it moves in by
    the closed-form inset at that sample, to 1e-15 of the legs; the wrong sign fails."""
    bend = Bend(0.002, 0.002, 0.4)
    n, length, legs = 21, 0.5, (0.08, 0.12)

    def law(x):
        return 60.0 + 40.0 * x / length

    sheet = strip(n, legs, length, law)
    drawn = thick_sheet(sheet, bend).mesh.vertices_coords
    x = drawn[n : 2 * n, 0]
    inner = slice(1, n - 1)
    expected = closed_inset(bend, law(x))[inner]
    got0 = legs[0] + drawn[:n, 1]  # seam 0 at y = −legs[0] moved up
    got1 = legs[1] - drawn[2 * n :, 1]
    assert np.ptp(expected) > 3e-4  # it varies along the crease
    np.testing.assert_allclose(got0[inner], expected, rtol=0, atol=1e-15)
    np.testing.assert_allclose(got1[inner], expected, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(drawn[n : 2 * n], sheet.mesh.vertices_coords[n : 2 * n])
    assert np.abs(-got0[inner] - expected).max() > 1e-4  # damaged: moved out, not in


@pytest.mark.parametrize(("fold", "k"), [(90.0, 0.325), (40.0, 0.5), (150.0, 0.42)])
def test_a_thick_strip_folded_from_the_drawn_pattern_recovers_the_design(fold, k):
    """The real sheet, cut to the drawn pattern and bent round R + K t about the drawn crease,
    has legs to its neutral surface's sharp fold of the design's lengths, to 1e-15; the
    pattern of zero thickness (no inset) is δ long on each, the wrong sign 2δ."""
    bend = Bend(0.003, 0.004, k)
    legs = (0.08, 0.12)
    sheet = strip(5, legs, 0.3, lambda x: np.full_like(x, fold))
    xy = thick_sheet(sheet, bend).mesh.vertices_coords
    drawn = (-xy[2, 1], xy[12, 1])
    np.testing.assert_allclose(folded_legs(drawn, bend, fold), legs, rtol=0, atol=1e-15)
    delta = float(closed_inset(bend, fold))
    thin = folded_legs(legs, bend, fold) - legs  # the pattern of zero thickness
    np.testing.assert_allclose(thin, delta, rtol=1e-12)
    wrong = folded_legs((legs[0] + delta, legs[1] + delta), bend, fold) - legs
    np.testing.assert_allclose(wrong, 2 * delta, rtol=1e-12)


def test_a_thickness_of_zero_or_one_past_the_strip_is_refused():
    sheet = strip(5, (0.08, 0.12), 0.3, lambda x: np.full_like(x, 90.0))
    with pytest.raises(InputError, match="thickness"):
        Bend(0.0, 0.001, 0.5)
    with pytest.raises(InputError, match=r"thickness must leave the strips a width: 0\.3 "):
        thick_sheet(sheet, Bend(0.3, 0.3, 0.5))  # δ = 0.45 (1 − π/4) = 0.097 > 0.08
    thick_sheet(sheet, Bend(0.2, 0.2, 0.5))  # δ = 0.064: drawn


def tube(samples: int = 41, length: float = 1.0) -> Structure:
    curve = SpaceCurve.from_curvature(2.0 / length, 0.5 / length, length, samples=samples)
    return Structure.tube(
        Lattice.from_crease(Crease.from_curve(curve, fold_angle=80), 0.1 * length, 0.1 * length)
    )


def _distance(points: np.ndarray, line: np.ndarray) -> np.ndarray:
    """Distance of points (P, 2) to a polyline (n, 2) run on past its ends along its end
    segments."""
    a, b = line[:-1], line[1:]
    d = b - a
    u = np.einsum("pfk,fk->pf", points[:, None] - a, d) / np.sum(d * d, axis=1)
    lo, hi = np.zeros(len(a)), np.ones(len(a))
    lo[0], hi[-1] = -np.inf, np.inf
    foot = a + np.clip(u, lo, hi)[..., None] * d
    return np.linalg.norm(points[:, None] - foot, axis=2).min(axis=1)


@pytest.mark.parametrize("samples", [41, 81])
def test_a_curved_creases_inset_converges_to_the_closed_form_at_2_alpha(samples):
    """A tube's curved crease (κ = 2, τ = 0.5, 2α = 80°): every sample of sheet B's seams lies
    closer to the crease by δ(2α) = 0.395 mm (t = 2 mm, R = t, K = 0.4). The sheets' fold
    angle is their sampled mesh's dihedral, 2α to O(h²): measured 8.5e-4 of δ at 41 samples and
    2.1e-4 at 81, so the bound halves twice per doubling."""
    bend = Bend(0.002, 0.002, 0.4)
    parts = sheets(tube(samples))
    drawn = thick_sheets(parts, bend)
    delta = float(closed_inset(bend, 80.0))
    b0, b1 = parts[1], drawn[1]  # sheet B: no seam of it lapped
    crease = np.unique(b0.mesh.edges_vertices[b0.mesh.edges_kind == "fold"])
    off = np.setdiff1d(np.arange(len(b0.mesh.vertices_coords)), crease)
    line = b0.mesh.vertices_coords[crease, :2]
    moved = _distance(b0.mesh.vertices_coords[off, :2], line) - _distance(
        b1.mesh.vertices_coords[off, :2], line
    )
    bound = 8.6e-4 * (41 / samples) ** 2
    assert np.abs(moved / delta - 1).max() < bound
    assert np.abs(0 * moved / delta - 1).max() > bound  # the pattern of zero thickness fails


def test_the_lapping_ply_moves_its_seams_out_by_the_thickness():
    """Sheet A of each tube carries the tabs and laps its partner: its seams lie t further out
    than sheet B's rule draws them (each seam vertex t from the unlapped seam's lines, to
    1e-12 of t on the straight strip; on the tube's curved seams within 1e-6 of t)."""
    bend = Bend(0.002, 0.002, 0.5)
    sheet = strip(5, (0.08, 0.12), 0.3, lambda x: np.full_like(x, 90.0))
    plain = thick_sheet(sheet, bend).mesh.vertices_coords
    lapped = thick_sheet(sheet, bend, frozenset({0, 1})).mesh.vertices_coords
    np.testing.assert_allclose(plain[:5, 1] - lapped[:5, 1], bend.thickness, rtol=1e-12)
    np.testing.assert_allclose(lapped[10:, 1] - plain[10:, 1], bend.thickness, rtol=1e-12)
    np.testing.assert_array_equal(lapped[5:10], plain[5:10])
    parts = sheets(tube())
    a_plain = thick_sheet(parts[0], bend)
    a_lapped, b_lapped = thick_sheets(parts, bend)
    np.testing.assert_array_equal(
        b_lapped.mesh.vertices_coords, thick_sheet(parts[1], bend).mesh.vertices_coords
    )
    xy0, xy1 = a_plain.mesh.vertices_coords[:, :2], a_lapped.mesh.vertices_coords[:, :2]
    for sid in (0, 1):
        seam = np.unique(a_plain.mesh.edges_vertices[a_plain.edges_seam == sid])  # in order
        mid = 0.5 * (xy1[seam][1:] + xy1[seam][:-1])  # each lapped edge's midpoint
        offset = _distance(mid, xy0[seam])
        assert np.abs(offset / bend.thickness - 1).max() < 1e-9
    assert np.abs(_distance(mid, xy1[seam])).max() < 1e-15  # damaged: not lapped, no offset


def _tube_layout(bend, perforation=None):
    output = PatternOutput(page="A3", scale=1000.0, perforation=perforation, bend=bend)
    return layout_pattern(tube(21, 0.3), output)


def test_glue_tabs_and_perforation_are_sized_to_the_sheet():
    """4 mm plywood drawn 1:1 (1000 mm per model unit): tabs 8 t = 32 mm wide (none narrowed
    on this tube), perforated creases cut 3 t = 12 mm and tied 1 t = 4 mm (a mountain's cuts
    alternate a dash and a third of one: 12 and 4 mm); without a thickness, 6 mm tabs and the
    asked 1 mm cuts, 0.5 mm ties."""
    sb = sheet_bend("plywood", 0.004)
    for bend, width, dash, gap in ((sb, 32.0, 12.0, 4.0), (None, 6.0, 1.0, 0.5)):
        layout = _tube_layout(bend, (1.0, 0.5))
        assert layout.perforation == (dash, gap)
        widths = []
        for placed in layout.sheets():
            lines = {p.seam: p.points for p in placed.polylines if p.layer == "seam"}
            widths += [
                _distance(p.points, lines[p.seam]).max()
                for p in placed.polylines
                if p.layer == "glue"
            ]
            cuts = [
                np.linalg.norm(np.diff(p.points, axis=0), axis=1).sum()
                for p in placed.polylines
                if p.layer == "mountain"
            ]
            assert cuts and np.allclose(sorted(set(np.round(cuts[:-1], 9))), [dash / 3, dash])
        # (the outer corners are mitred: w / cos of half the seam's turn there, 1e-3 at most)
        assert max(widths) == pytest.approx(width, rel=1e-3)
    assert sb.tab_width(100.0) == 6.0  # the floor: 8 t at 1:10 is 3.2 mm
    assert sb.perforation(None, 1000.0) is None
    with pytest.raises(InputError, match=r"perforation must be a \(dash, gap\) pair .* got 'x'"):
        _tube_layout(sb, "x")
    with pytest.raises(InputError, match="bend must be a SheetBend .* got Bend"):
        _tube_layout(sb.bend)


def test_the_legend_states_the_sheet_and_zero_thickness_draws_as_before():
    layout = _tube_layout(sheet_bend("aluminium", 0.001))
    assert layout.sheet_note == (
        "sheet 1 mm aluminium: creases inset by the bend (R 1 mm, K 0.325 DIN 6935) · sheet A "
        "laps its seams, out 1 mm · tabs 8 mm"
    )
    plain = _tube_layout(None)
    assert plain.sheet_note == ""
    same = layout_pattern(tube(21, 0.3), PatternOutput(page="A3", scale=1000.0))
    for p, q in zip(plain.sheets(), same.sheets()):
        for a, b in zip(p.polylines, q.polylines):
            np.testing.assert_array_equal(a.points, b.points)


def test_a_smooth_design_with_a_material_writes_the_thick_sheets_pattern(tmp_path):
    """``curvefold tube --material aluminium --thickness 0.001``: its pattern's pages (SVG, DXF)
    say so; without a material they do not; a tube of rigid panels keeps its own files."""
    out = tmp_path / "out"
    args = ["tube", "--material", "aluminium", "--thickness", "0.001", "--formats", "svg,dxf"]
    assert main([*args, "--out", str(out)]) == 0
    pages = sorted(out.glob("tube-pattern*.svg")) + [out / "tube-pattern.dxf"]
    assert pages and all(
        "creases inset by the bend (R 1 mm, K 0.325" in p.read_text() for p in pages
    )
    plain = tmp_path / "plain"
    assert main(["tube", "--formats", "svg", "--out", str(plain)]) == 0
    assert not any("inset by the bend" in p.read_text() for p in plain.glob("*.svg"))
    panels = tmp_path / "panels"
    assert main([*args, "--panels", "4", "--out", str(panels)]) == 0
    assert not any("inset by the bend" in p.read_text() for p in panels.glob("*.svg"))


@pytest.mark.parametrize("fold", [80.0, 120.0])
def test_a_tubes_seams_meet_at_2_alpha_where_the_lap_rule_is_exact_at_90(fold):
    """The lap of t is exact where the plies meet at 90°: a tube's seams meet at φ = 2α (their
    dihedral on the design state's mesh, to the sampling's 0.02°), so at 2α = 80° the rule
    leaves t (1 / sin 80° − 1) = 1.5 % of t."""
    from curvefold.geometry._mesh import fold_angles

    curve = SpaceCurve.from_curvature(2.0, 0.5, 1.0, samples=41)
    s = Structure.tube(Lattice.from_crease(Crease.from_curve(curve, fold_angle=fold), 0.1, 0.1))
    top = s.topology("triangles")
    bent = fold_angles(top.coords(s.state(fold).vertices), top.faces_vertices, top.edges_vertices)
    phi = 180.0 - np.abs(bent[top.edges_kind == "seam"])
    np.testing.assert_allclose(phi, fold, atol=0.02)
    assert np.abs(phi - (180.0 - fold)).min() > 1.0  # not the crease's own angle (damaged)
    if fold == 80.0:
        assert 1 / np.sin(np.radians(phi.mean())) - 1 == pytest.approx(0.0154, abs=1e-4)
