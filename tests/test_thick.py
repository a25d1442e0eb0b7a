"""Thick panels by the offset-panel technique (curvefold.geometry._thick, analysis._thick_checks):
the first contact against closed forms and a second method, hinges on their creases, one degree
of freedom; each check shown failing on damaged input.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import linprog

from curvefold import Crease, InputError, Lattice, SpaceCurve, Structure
from curvefold.analysis import hinge_offsets, thick_mechanism
from curvefold.geometry import PanelLattice, PanelPattern, ThickPanels
from curvefold.geometry._contact import _overlapping_boxes
from curvefold.geometry._panel_pattern import fold_line_angle
from curvefold.geometry._thick_solids import halfspaces, panel_axes, penetration, prism
from curvefold.vault import Vault, VaultDesign

EPS = np.finfo(float).eps
T = 0.002  # the thickness of the structures below: 2.5 % of their narrowest strip


@pytest.fixture(scope="module")
def lattice():
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=161
    )
    smooth = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)
    return PanelLattice.from_lattice(smooth, 8)


@pytest.fixture(scope="module")
def tube(lattice):
    return ThickPanels.offset(Structure.tube(lattice), T)


@pytest.fixture(scope="module")
def block(lattice):
    """Three tubes on the lattice diagonal, glued along their shared creases."""
    return ThickPanels.offset(Structure.diagonal(lattice, 3), T)


@pytest.fixture(scope="module")
def vault():
    return ThickPanels.offset(Vault.from_design(VaultDesign(panels=8, tubes=2)).structure, T)


def first_contact(depth, lo: float, hi: float, tol: float = 1e-12) -> float:
    """Bisection for the first parameter in (lo, hi] where depth(x) > 0 (lo clear, hi not)."""
    assert depth(lo) <= 0 < depth(hi)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if depth(mid) > 0 else (mid, hi)
    return hi


def ball_radius(h1: np.ndarray, h2: np.ndarray) -> float:
    """Radius of the largest ball inside two solids given as half-spaces [n, c] (unit n): > 0
    when their interiors overlap (linear programme, independent of the separating axes)."""
    h = np.concatenate([h1, h2])
    res = linprog(
        [0, 0, 0, -1],
        A_ub=np.concatenate([h[:, :3], np.ones((len(h), 1))], 1),
        b_ub=h[:, 3],
        bounds=[(None, None)] * 3 + [(None, 1.0)],
        method="highs",
    )
    assert res.status == 0
    return -float(res.fun)


# -- the first contact against closed forms ------------------------------------------------------
def _hinged(gamma: float, bevels: tuple[float, float], t: float = 0.1):
    """Two unit squares hinged on the y axis, solids on +z, the second folded up by γ toward
    them: vertices (2, 8, 3), face normals (2, 6, 3), half-spaces (2, 6, 4)."""
    one = np.array([[0.0, 0], [0, 1], [-1, 1], [-1, 0]])  # edge 0 on the hinge
    two = np.array([[0.0, 1], [0, 0], [1, 0], [1, 1]])
    c, s = np.cos(-gamma), np.sin(-gamma)
    R = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    out = []
    for xy, b, rot in ((one, bevels[0], np.eye(3)), (two, bevels[1], R)):
        b_e = np.array([b, 0, 0, 0])
        h = halfspaces(xy, t, b_e)
        out.append((prism(xy, t, b_e) @ rot.T, h[:, :3] @ rot.T, np.c_[h[:, :3] @ rot.T, h[:, 3]]))
    return tuple(np.stack(x) for x in zip(*out))


@pytest.mark.parametrize("bevels", [(20.0, 35.0), (0.0, 50.0), (44.0, 44.0)])
def test_two_panels_on_one_hinge_touch_where_their_bevels_meet(bevels):
    b = np.radians(bevels)

    def depth(gamma, bevels=b):
        v, n, _ = _hinged(gamma, bevels)
        return float(penetration(v[:1], v[1:], n[:1], n[1:])[0]) - 1e-14

    # closed form: the side faces meet when the wedge between the panels closes to π − b₁ − b₂
    assert abs(first_contact(depth, 0.0, 0.5 * np.pi) - b.sum()) < 1e-11
    # the second method, a linear programme on the half-spaces, agrees on either side of it:
    # before, the largest ball in both is the hinge line's (radius 0); after, one fits
    before, after = (ball_radius(*_hinged(g, b)[2]) for g in (b.sum() - 1e-3, b.sum() + 1e-3))
    assert abs(before) < 1e-12 and after > 1e-6, (before, after)
    # damaged: a bevel cut 2° short moves the contact by 2°
    short = first_contact(lambda g: depth(g, b - [0, np.radians(2)]), 0.0, 0.5 * np.pi)
    assert abs(short - b.sum() + np.radians(2)) < 1e-11


def _miura_vertex(phi: float):
    """A flat-foldable degree-4 vertex of Miura-ori type (β = 90°, the crease turning by φ): the
    project's panel pattern of two panels, and its four panels' corners at α (A,)."""
    T0, T1 = (np.array([np.cos(a), np.sin(a)]) for a in (-phi / 2, phi / 2))
    pattern = PanelPattern.from_polyline(
        [0, 1, 2],
        [-T0, [0, 0], T1],
        [np.pi / 2] * 3,
        start_tangent=T0,
        end_tangent=T1,
        left_length=1.0,
        right_length=1.0,
    )

    def corners(alpha):
        x, L, R, _ = pattern.fold(np.atleast_1d(alpha))
        x0, x1, x2 = (x[:, k] for k in range(3))
        L0, L1, L2 = (L[:, k] for k in range(3))
        R0, R1, R2 = (R[:, k] for k in range(3))
        quads = [
            [x0, x1, x1 + L1, x0 + L0],  # L0: edge 1 on fold line L1
            [x1, x2, x2 + L2, x1 + L1],  # L1: edge 3 on L1
            [x0, x0 + R0, x1 + R1, x1],  # R0: edge 2 on fold line R1
            [x1, x1 + R1, x2 + R2, x2],  # R1: edge 0 on R1
        ]
        return np.stack([np.stack(q, axis=1) for q in quads], axis=1)  # (A, 4, 4, 3)

    return corners


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_a_miura_vertex_first_touches_where_its_fold_line_reaches_the_bevels(side):
    phi, t = np.radians(40.0), 0.05
    fold_bevel, crease_bevel = np.radians(12.0), np.radians(80.0)
    bevels = np.zeros((4, 4))
    bevels[0, 1] = bevels[1, 3] = bevels[2, 2] = bevels[3, 0] = fold_bevel
    bevels[0, 0] = bevels[1, 0] = bevels[2, 3] = bevels[3, 3] = crease_bevel
    corners = _miura_vertex(phi)
    sides = np.full(4, side)
    origin, axes = panel_axes(corners(0.0)[0], sides)
    xy = np.einsum("fkd,fjd->fkj", corners(0.0)[0] - origin[:, None], axes)[..., :2]

    def depth(alpha, bevels=bevels):
        local, faces = prism(xy, t, bevels), halfspaces(xy, t, bevels)[..., :3]
        o, a = panel_axes(corners(alpha)[0], sides)
        v = o[:, None] + np.einsum("fvj,fjd->fvd", local, a)
        n = np.einsum("fnj,fjd->fnd", faces, a)
        i, j = np.triu_indices(4, 1)
        return float(penetration(v[i], v[j], n[i], n[j]).max()) - 1e-12

    # closed form: the vertex folds its fold lines by tan(ρ/2) = sin(φ/2)/sin β · tan α; the
    # concave one closes on its bevels at |ρ| = 2 b; the crease's bevels (80°) come later
    expected = np.arctan(np.tan(fold_bevel) / np.sin(phi / 2))
    assert abs(fold_line_angle(phi, np.pi / 2, expected) - 2 * fold_bevel) < 1e-14
    assert abs(first_contact(depth, 1e-3, 1.5) - expected) < 1e-10
    # damaged: one panel's fold-line bevel at 10° instead of 12°, on both fold lines: earlier
    cut = bevels.copy()
    cut[[0, 3], [1, 0]] = np.radians(10.0)
    earlier = first_contact(lambda a: depth(a, cut), 1e-3, 1.5)
    assert abs(earlier - np.arctan(np.tan(np.radians(11.0)) / np.sin(phi / 2))) < 1e-10


# -- structures ----------------------------------------------------------------------------------
def _bevel_sum(thick: ThickPanels, p: int, q: int) -> float:
    """b₁ + b₂ in degrees of two panels on the hinge they share."""
    topology = thick.structure.topology()
    key = topology.vertex_curve * len(thick.structure.lattice.s) + topology.vertex_sample
    edges = [
        {frozenset(key[[f[e], f[(e + 1) % 4]]]): e for e in range(4)}
        for f in topology.faces_vertices[[p, q]]
    ]
    (shared,) = set(edges[0]) & set(edges[1])
    return float(np.degrees(thick.bevels[p, edges[0][shared]] + thick.bevels[q, edges[1][shared]]))


def test_a_tube_folds_flat_to_a_stack_of_two_plies(tube):
    r = tube.motion_range()
    # outward solids clear every crease and seam; the fold lines' bevels are cut at the design
    # angle, so they close exactly there (bisection tolerance 1e-7°)
    assert r.low == 0.0 and r.low_pair is None
    assert abs(r.high - 90.0) < 1e-6 and r.high_pair is not None
    # the flat state: the two plies, each t thick, on either side of the pattern's plane
    assert abs(tube.stack_height() - 2 * T) < 1e-12
    # "outside" measured: every solid's normal points away from its tube's section centre
    structure, topology = tube.structure, tube.structure.topology()
    state, faces = structure.state(), topology.faces_vertices
    _, axes = tube.placements([90.0])
    samples, curves = (
        topology.vertex_sample[faces],
        structure.cell_curves[topology.faces_group // 4],
    )
    centre = np.stack([state.vertices[c][:, k].mean(axis=(0, 1)) for c, k in zip(curves, samples)])
    away = np.einsum(
        "fd,fd->f", axes[0][:, 2], topology.coords(state.vertices)[faces].mean(1) - centre
    )
    assert (away > 0).all()
    # inside, the seams close on the solids as the tube flattens: it stops short of flat where
    # the touching pair's bevels meet, 180° − b₁ − b₂ (measured 12.12°)
    inside = ThickPanels.offset(structure, T, side="inside")
    assert (np.einsum("fd,fd->f", inside.placements([90.0])[1][0][:, 2], axes[0][:, 2]) < 0).all()
    r = inside.motion_range(step=2.0)
    assert abs(r.low - (180.0 - _bevel_sum(inside, *r.low_pair))) < 1e-6 and 12 < r.low < 13
    # square cuts (bevels removed) collide at once
    square = replace(tube, local=prism(tube.local[:, :4, :2], T, 0 * tube.bevels))
    assert square.interpenetrate(45.0) and not tube.interpenetrate(45.0)


def test_a_block_stops_short_of_flat_where_the_bevels_of_two_tubes_meet(block):
    r = block.motion_range()
    # two tubes' walls fold onto each other across their shared crease (their gap is 2α); each
    # bevel is capped at atan(r / 2t) by its panel's inradius r, and the walls meet at
    # 2α = 180° − b₁ − b₂ (closed form, measured 12.12°)
    assert abs(r.low - (180.0 - _bevel_sum(block, *r.low_pair))) < 1e-6 and 10 < r.low < 15
    assert abs(r.high - 90.0) < 1e-6
    # thicker panels stop farther from flat
    assert ThickPanels.offset(block.structure, 2 * T).motion_range(step=2.0).low > r.low + 5


def test_the_separating_axes_agree_with_the_halfspace_programme(block):
    """Every pair of solids near the block's lower contact: the depth's sign is the sign of the
    largest ball inside both (linear programme), wherever either is clear of zero."""
    low = block.motion_range(step=2.0).low
    checked = 0
    for angle in (low - 0.5, low + 0.5, 45.0):
        vertices, normals = (v[0] for v in block.solids([angle]))
        origin, axes = (v[0] for v in block.placements([angle]))
        local = halfspaces(block.local[:, :4, :2], T, block.bevels)
        n = np.einsum("fnj,fjd->fnd", local[..., :3], axes)
        h = np.concatenate([n, (local[..., 3] + np.einsum("fnd,fd->fn", n, origin))[..., None]], -1)
        a, b = _overlapping_boxes(vertices.min(1), vertices.max(1), 1e-12)
        a, b = a[a < b], b[a < b]
        depth = penetration(vertices[a], vertices[b], normals[a], normals[b])
        for i in np.flatnonzero(np.abs(depth) > 1e-6 * T)[::20]:
            radius = ball_radius(h[a[i]], h[b[i]])
            assert np.sign(radius) == np.sign(depth[i]), (angle, a[i], b[i], depth[i], radius)
            checked += 1
        assert (depth.max() > 1e-6 * T) == (angle < low)
    assert checked > 20


# -- hinges and degrees of freedom --------------------------------------------------------------
def _moved_hinge(thick: ThickPanels, face: int, edge: int, offset: float) -> ThickPanels:
    """The hinge of one fold line moved off its crease by ``offset`` along the panel's normal, on
    both panels it joins (both hold the moved axis)."""
    topology = thick.structure.topology()
    key = topology.vertex_curve * len(thick.structure.lattice.s) + topology.vertex_sample
    faces = topology.faces_vertices
    ends = {frozenset(key[[f[e], f[(e + 1) % 4]]]) for f, e in [(faces[face], edge)]}
    design = thick.structure.lattice.crease.fold_angle
    origin, axes = (v[0] for v in thick.placements([design]))
    hinges = thick.hinges.copy()
    for g, row in enumerate(faces):
        for e in range(4):
            if frozenset(key[[row[e], row[(e + 1) % 4]]]) in ends:
                hinges[g, e] += offset * (axes[g] @ axes[face, 2])
    return replace(thick, hinges=hinges)


def test_every_hinge_axis_lies_on_its_crease_in_every_frame(tube, block, vault):
    frames = np.linspace(0.0, 170.0, 18)
    for thick in (tube, block, vault):
        assert hinge_offsets(thick, frames).max() < 8 * EPS
    # damaged: a fold line's hinge on the panels' top face is t off its crease, in every frame
    moved = hinge_offsets(_moved_hinge(tube, 9, 1, T), frames)
    assert np.allclose(moved, T, rtol=1e-9)


def test_the_thick_linkage_moves_with_one_degree_of_freedom(tube, block, vault):
    for thick, frames in ((tube, (10, 45, 90, 150)), (block, (20, 45, 90)), (vault, (45, 90))):
        for m in thick_mechanism(thick, frames):
            assert m.consistent and m.residual < 64 * EPS, m.to_dict()
            assert m.dof == 1 and m.gap > 1e10 and m.clearance < 1e-4, m.to_dict()
    # damaged: one hinge a thickness off its crease locks the two vertices on it (a spatial
    # four-bar), and the zero-thickness motion no longer moves the thick linkage
    moved = _moved_hinge(tube, 9, 1, T)
    at_design, away = thick_mechanism(moved, (90, 60))
    assert at_design.consistent and at_design.dof == 0 and at_design.gap > 1e6, at_design.to_dict()
    assert not away.consistent


# -- bad input -----------------------------------------------------------------------------------
def test_bad_thickness_is_one_line_with_the_value_and_the_limit(lattice):
    tube = Structure.tube(lattice)
    with pytest.raises(
        InputError,
        match=r"^thickness must be in \(0, 0\.0\d+\) model units \(the "
        r"smallest panel's inradius, panel \d of tube 1: use a thinner sheet or "
        r"fewer panels\), got 0\.2$",
    ):
        ThickPanels.offset(tube, 0.2)
    with pytest.raises(InputError, match=r"^thickness must be > 0 model units, got -1\.0$"):
        ThickPanels.offset(tube, -1.0)
    # two tubes' walls meet at the design angle's 90° gap: a bevel of 45° sets the top face back
    # by t, more than half the inradius once t > r / 2
    block = Structure.diagonal(lattice, 2)
    with pytest.raises(InputError) as err:
        ThickPanels.offset(block, 0.02)
    text = str(err.value)
    assert "\n" not in text and text.startswith("thickness must be below 0.0")
    assert "to reach the design angle 2α = 90°" in text and text.endswith(
        "got 0.02: use a thinner sheet or fewer panels"
    )
    with pytest.raises(InputError, match="^side must be 'outside' or 'inside', got 'up'$"):
        ThickPanels.offset(tube, T, side="up")
    smooth = Structure.tube(lattice.source)
    with pytest.raises(InputError, match="^thickness: thick panels need a structure of rigid"):
        ThickPanels.offset(smooth, T)


def test_a_wall_two_tubes_share_is_refused_at_the_design_angle(lattice):
    """Tubes (0, 0) and (0, 1) share a wall: offset outward, one ply's solid enters the other
    tube, by a fixed fraction of t (measured 0.27 t): one line says so, whatever the thickness."""
    block = Structure.from_cells(lattice, [(0, 0), (0, 1), (1, 1)])
    for t in (T, T / 4):
        thick = ThickPanels.offset(block, t)
        depth, _ = thick.deepest(90.0)
        assert abs(depth / t - 0.2735) < 1e-3
        with pytest.raises(InputError) as err:
            thick.motion_range()
        text = str(err.value)
        assert "\n" not in text and "(0.27 t), got t = " in text
        assert text.endswith("build the cells along one diagonal")
    # the linkage is still one of one degree of freedom
    assert [m.dof for m in thick_mechanism(ThickPanels.offset(block, T), (45, 90))] == [1, 1]


# -- files to build from ---------------------------------------------------------------------------
def _edges_twice_each_way(corners: np.ndarray) -> bool:
    """Whether every edge of triangles (T, 3, 3), by its end points, is in exactly two triangles,
    once each way (a closed, consistently oriented surface)."""
    points, index = np.unique(corners.reshape(-1, 3), axis=0, return_inverse=True)
    tri = index.reshape(-1, 3)
    directed = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    forward = {tuple(e) for e in directed.tolist()}
    return len(forward) == len(directed) and all((b, a) in forward for a, b in forward)


def _volume(corners: np.ndarray) -> float:
    """Enclosed volume of closed triangles (T, 3, 3) (divergence theorem)."""
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


def test_the_solids_are_a_watertight_stl_of_the_prisms_volume(tube, tmp_path):
    from curvefold.io import write_cut_list, write_thick_stl

    x, tri = tube.triangles(60.0)
    # closed form: the bevelled prism's cross-section is quadratic in z, so Simpson's rule
    # (the prismatoid formula) is exact: V = t/6 (A(0) + 4 A(t/2) + A(t)), one solid at a time
    outline = tube.local[:, :4, :2]

    def area(xy):
        return 0.5 * np.abs(
            (xy[..., 0] * np.roll(xy[..., 1], -1, -1)).sum(-1)
            - (xy[..., 1] * np.roll(xy[..., 0], -1, -1)).sum(-1)
        )

    mid = prism(outline, T / 2, tube.bevels)[:, 4:, :2]
    prismatoid = T / 6 * (area(outline) + 4 * area(mid) + area(tube.local[:, 4:, :2]))
    per_solid = x[tri].reshape(len(outline), 12, 3, 3)
    volumes = np.array([_volume(s) for s in per_solid])
    assert np.abs(volumes / prismatoid - 1).max() < 1e-9
    assert all(_edges_twice_each_way(s) for s in per_solid)
    # the file: 32-bit floats keep every solid closed; its volume to float precision
    path = write_thick_stl(tmp_path / "solids.stl", tube, 60.0, to_unit="mm")
    data = np.frombuffer(
        path.read_bytes()[84:], dtype=[("n", "<f4", 3), ("c", "<f4", (3, 3)), ("a", "<u2")]
    )
    corners = data["c"].astype(float).reshape(len(outline), 12, 3, 3)
    assert all(_edges_twice_each_way(s) for s in corners)
    assert abs(sum(_volume(s) for s in corners) / (prismatoid.sum() * 1e9) - 1) < 1e-5
    # damaged: a solid missing a triangle is open
    assert not _edges_twice_each_way(corners[0][1:])
    # the cut list: every panel once, its bevels and the edges on hinges (the tube's two ends free)
    rows = __import__("json").loads(write_cut_list(tmp_path / "cut.json", tube).read_text())
    panels = rows["panels"]
    assert len({r["panel"] for r in panels}) == len(panels) == 32
    # its rows in the order of assembly (tests/test_thick_ids.py)
    assert [r["panel"] for r in panels] == [tube.labels()[f] for f in tube.order]
    assert np.allclose([r["bevels"] for r in panels], np.degrees(tube.bevels[tube.order]).round(3))
    assert sum(not h for r in panels for h in r["hinged"]) == 8


def test_bevels_cut_for_a_wider_reach_let_a_tube_fold_exactly_that_far(lattice):
    structure = Structure.tube(lattice)
    for hi in (120.0, 150.0):
        r = ThickPanels.offset(structure, T, reach=(0.0, hi)).motion_range(step=2.0)
        assert r.low == 0.0 and abs(r.high - hi) < 1e-6
    # the reach must hold the design angle and lie in [0°, 180°)
    with pytest.raises(InputError, match=r"^reach must hold the design angle 90° .*got \(0, 60\)"):
        ThickPanels.offset(structure, T, reach=(0.0, 60.0))
    with pytest.raises(InputError, match=r"^reach\[1\] must be in \[0, 180\) degrees, got 180"):
        ThickPanels.offset(structure, T, reach=(0.0, 180.0))


def test_the_thickness_checks_pass_and_each_fails_on_its_damage(tube, vault):
    from curvefold.analysis._thick_checks import thickness_checks
    from curvefold.geometry import ThickRange

    def verdicts(report):
        return {c["name"]: c["passed"] for c in report["checks"]}

    # one tube of the two within the budget: 204 unknowns, both 381
    report = thickness_checks(vault, budget=300)
    assert report["mechanism"][0]["unknowns"] == 204
    assert (
        all(verdicts(report).values()) and report["mechanism_scope"] == "the first 1 of the 2 tubes"
    )
    assert (
        report["range"]["high"] == pytest.approx(90.0, abs=1e-6)
        and 10 < report["range"]["low"] < 40
    )
    good = thickness_checks(tube)
    assert all(verdicts(good).values()) and good["range"]["low"] == 0.0
    # a hinge off its crease: the hinges are t off, and the linkage is locked or inconsistent
    moved = verdicts(thickness_checks(_moved_hinge(tube, 9, 1, T)))
    assert moved == {
        "hinges on creases": False,
        "no interpenetration": True,
        "one degree of freedom": False,
    }
    # a range stated 5° past the first contact
    wide = ThickRange(90.0, 0.0, 95.0, None, None)
    assert verdicts(thickness_checks(tube, wide)) == {
        "hinges on creases": True,
        "no interpenetration": False,
        "one degree of freedom": True,
    }


def test_tapered_panels_reach_further_and_stop_where_their_deeper_bevels_meet(block):
    """Top faces set back by up to 3/4 of the inradius: the bevels are capped at atan(0.75 r / t),
    the block's walls meet where they do (2α = 180° − b₁ − b₂, closed form), nearer flat."""
    from curvefold.geometry._thick_solids import inradius

    tapered = ThickPanels.offset(block.structure, T, setback=0.75)
    r = tapered.motion_range()
    assert abs(r.low - (180.0 - _bevel_sum(tapered, *r.low_pair))) < 1e-6
    assert r.low < block.motion_range().low - 3 and abs(r.high - 90.0) < 1e-6
    cap = np.arctan(0.75 * inradius(tapered.local[:, :4, :2]) / T)[:, None]
    assert np.all(tapered.bevels <= cap + 1e-15) and np.isclose(tapered.bevels, cap).any()
    assert tapered.technique.startswith("tapered panels") and block.technique.startswith("offset")
    # the hinges stay on their creases and the linkage keeps one degree of freedom
    assert hinge_offsets(tapered, [0, 45, 90]).max() < 2e-15
    assert [m.dof for m in thick_mechanism(tapered, [20, 90])] == [1, 1]
    with pytest.raises(InputError, match=r"^setback must be in \(0, 1\) .*got 1\.0$"):
        ThickPanels.offset(block.structure, T, setback=1.0)


def test_a_top_face_that_loses_an_edge_is_refused(tube):
    """Damaged: a panel's two long edges set back by 1.2 of its inradius each cross."""
    from curvefold.geometry._thick import _check_tops
    from curvefold.geometry._thick_solids import inradius

    topology = tube.structure.topology()
    _check_tops(tube.local, topology, 0.5)  # as built: every top face whole
    solids = tube.local.copy()
    xy = tube.local[3, :4, :2]
    solids[3] = prism(xy, T, np.full(4, np.arctan(1.2 * float(inradius(xy)) / T)))
    with pytest.raises(InputError, match=r"^setback must be smaller: .* loses an edge"):
        _check_tops(solids, topology, 0.5)
