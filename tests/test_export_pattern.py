"""Crease-pattern fabrication output: layout, glue tabs, labels, SVG/DXF/PDF writers.

Every written file is opened by a reader we did not write: ``xml.etree`` and
``rsvg-convert`` for SVG, ``ezdxf`` (with its auditor) for DXF, ``pdfinfo``/``pdftoppm``
for PDF. Geometry is checked with ``shapely``.
"""

from __future__ import annotations

import doctest
import io as _io
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from itertools import combinations
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from shapely.geometry import LineString, Point, Polygon
from shapely.ops import unary_union

from _sheets import annular_sheet, tube_sheets, vault_sheets
from curvefold.geometry import Mesh, PatternSheet
from curvefold.io import _cutters as cutters
from curvefold.io import _cutting as cutting
from curvefold.io import _labels as labels
from curvefold.io import _layout as layout_module
from curvefold.io import _legend as legend
from curvefold.io import _pattern as pattern
from curvefold.io import _pdf as pdf
from curvefold.io import _planar as planar
from curvefold.io import _svg as svg
from curvefold.io._cutters import CUTTERS, LEGEND_LAYER, layer_name
from curvefold.io._layout import LayoutRules
from curvefold.io._pattern import (
    DEFAULT_LAYERS,
    LAYERS,
    LEGEND,
    layout_sheets,
    seam_name,
    write_dxf,
    write_pdf,
    write_svg,
)
from curvefold.io._planar import polyline_segments
from curvefold.io._tabs import (
    TAB_WIDTH_STEPS,
    place_tabs,
    tab_fits,
    tab_outline,
    tab_outlines,
    tab_pieces,
    tabs_fit,
)
from curvefold.kernel import InputError

NS = {
    "svg": "http://www.w3.org/2000/svg",
    "inkscape": "http://www.inkscape.org/namespaces/inkscape",
}
INK = "{http://www.inkscape.org/namespaces/inkscape}"


def needs(tool: str):
    return pytest.mark.skipif(shutil.which(tool) is None, reason=f"{tool} not installed")


@pytest.fixture(scope="module")
def tube():
    return tube_sheets()


@pytest.fixture(scope="module")
def tube_layout(tube):
    return layout_sheets(tube)


@pytest.fixture(scope="module")
def vault():
    return vault_sheets(4)


@pytest.fixture(scope="module")
def vault_layout(vault):
    # A5 forces several pages.
    return layout_sheets(vault, page="A5")


# --------------------------------------------------------------------------------------
# helpers (shapely geometry of what the layout placed)


def placed_triangles(sheet: PatternSheet, placed) -> np.ndarray:
    """The sheet's triangles mapped to the page, shape (F, 3, 2)."""
    xy = sheet.mesh.vertices_coords[:, :2] @ placed.transform[:, :2].T + placed.transform[:, 2]
    return xy[sheet.mesh.faces_vertices]


def sheet_polygon(sheet, placed):
    return unary_union([Polygon(t) for t in placed_triangles(sheet, placed)])


def tab_polygons(placed):
    return [Polygon(p.points) for p in placed.on_layer("glue")]


def footprint(sheet, placed):
    return unary_union([sheet_polygon(sheet, placed), *tab_polygons(placed)])


def drawn_lines(placed, layers=("cut", "seam", "mountain", "valley")):
    out = []
    for p in placed.polylines:
        if p.layer in layers:
            pts = np.concatenate([p.points, p.points[:1]]) if p.closed else p.points
            out.append(LineString(pts))
    return unary_union(out)


# --------------------------------------------------------------------------------------
# layout


def test_sheets_do_not_overlap_and_stay_inside_the_margins(vault, vault_layout):
    lay = vault_layout
    W, H = lay.page_size
    assert (W, H) == (148.0, 210.0)
    assert len(lay.pages) > 1
    assert sorted(s.index for s in lay.sheets()) == list(range(len(vault)))
    for page in lay.pages:
        shapes = [footprint(vault[s.index], s) for s in page.sheets]
        for a, b in combinations(shapes, 2):
            assert a.intersection(b).area == 0.0
            assert a.distance(b) >= 4.0 - 1e-6  # the default gap
        for s in page.sheets:
            pts = np.concatenate([p.points for p in s.polylines] + [t.corners() for t in s.labels])
            assert np.all(pts.min(axis=0) >= lay.margin - 1e-9)
            assert np.all(pts.max(axis=0) <= np.array([W, H]) - lay.margin + 1e-9)


def test_packing_turns_sheets_to_small_rectangles():
    # A thin strip at 30° would waste most of its axis-aligned box if not turned.
    sheet = annular_sheet(
        "strip", radii=(2000.0, 2010.0, 2020.0), span_deg=(30.0, 33.0), n=6, seams=(None, None)
    )
    lay = layout_sheets([sheet], glue_tabs=False)
    placed = lay.sheets()[0]
    lo, hi = placed.bounds()
    poly = sheet_polygon(sheet, placed)
    assert (hi - lo).prod() < 1.2 * poly.minimum_rotated_rectangle.area


def test_the_minimum_area_box_agrees_with_shapely_and_costs_linear_memory():
    """Every hull edge tried against every hull vertex took H² memory: 9 GB laying out a single
    fold of 20001 samples, whose outline is all hull. Rotating calipers find the same box."""
    import tracemalloc

    from shapely import MultiPoint

    rng = np.random.default_rng(7)
    for k in range(60):
        pts = rng.normal(size=(int(rng.integers(3, 300)), 2)) * rng.uniform(0.1, 5.0, size=2)
        if k % 2:  # an ellipse's outline: every point on the hull
            t = np.sort(rng.uniform(0, 2 * np.pi, len(pts)))
            pts = np.stack([3 * np.cos(t + k), np.sin(t)], axis=1)
        turned = pts @ planar.rotation(planar.min_area_rotation(pts)).T
        assert np.ptp(turned, axis=0).prod() == pytest.approx(
            MultiPoint(pts).minimum_rotated_rectangle.area, rel=2e-6
        )
    t = np.linspace(0, 2 * np.pi, 40001)[:-1]
    tracemalloc.start()
    planar.min_area_rotation(np.stack([3 * np.cos(t), np.sin(t)], axis=1))
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    # a few dozen arrays of one number per vertex (H² would be 12.8 GB)
    assert peak < 40 * 40000 * 8


def _point_sets(rng: np.random.Generator):
    """Point sets of every kind the layout meets: scattered, all on a curve, on a coarse grid
    (collinear runs and repeated points), along lines sampled with their joints twice."""
    for k in range(80):
        n = int(rng.integers(3, 2000))
        if k % 4 == 0:
            yield rng.normal(size=(n, 2)) * rng.uniform(0.1, 100.0, size=2)
        elif k % 4 == 1:
            t = rng.uniform(0, 2 * np.pi, n)
            yield np.stack([3 * np.cos(t), np.sin(t)], axis=1) * rng.uniform(0.5, 1.0, size=(n, 1))
        elif k % 4 == 2:
            yield rng.integers(0, 12, size=(n, 2)).astype(float)
        else:
            segments = np.cumsum(rng.normal(size=(20, 2)), axis=0)
            yield labels.Obstacles(np.stack([segments[:-1], segments[1:]], axis=1), 0.05).points


def _same_cycle(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether point sequences a and b are the same cycle, started anywhere."""
    start = np.flatnonzero((a == b[0]).all(axis=1))
    return len(a) == len(b) and start.size == 1 and np.array_equal(np.roll(a, -start[0], axis=0), b)


def test_tabs_drawn_together_are_each_ones_own():
    """Tab outlines found side by side (each piece padded to the longest) are those of each piece
    alone, bit for bit, pieces too short or of one point repeated among them."""
    rng = np.random.default_rng(16)
    pieces = [np.cumsum(rng.normal(size=(int(rng.integers(2, 14)), 2)), axis=0) for _ in range(200)]
    pieces += [
        np.zeros((3, 2)),
        np.array([[0.0, 0.0], [1e-9, 0.0]]),
        np.array([[0.0, 0.0], [0.0, 0.0], [3.0, 0.0]]),
    ]
    for width in (0.5, 6.0, 40.0):
        together = tab_outlines(pieces, width, np.radians(60.0))
        alone = [tab_outline(p, width, np.radians(60.0)) for p in pieces]
        assert [t is None for t in together] == [t is None for t in alone] and any(
            t is None for t in alone
        )
        assert all(
            a is None or all(np.array_equal(x, y) for x, y in zip(a, t))
            for a, t in zip(alone, together)
        )
    # the check sees a point less
    assert not np.array_equal(
        tab_outlines(pieces[:2], 6.0, 1.0)[0][0],
        tab_outlines([pieces[0][:-1], pieces[1]], 6.0, 1.0)[0][0],
    )


def test_the_convex_hull_is_scipys():
    """The hull the minimum-area box turns on is qhull's, vertex for vertex (where a point
    repeats, one of its copies); on a line it has fewer than three vertices, where qhull
    refuses."""
    from scipy.spatial import ConvexHull, QhullError

    rng = np.random.default_rng(11)
    for pts in _point_sets(rng):
        ours, theirs = pts[planar.convex_hull(pts)], pts[ConvexHull(pts).vertices]
        assert _same_cycle(ours, theirs)
        # the check sees a vertex lost, the turn reversed
        assert not _same_cycle(ours[1:], theirs) and not _same_cycle(ours[::-1], theirs)
    for pts in (np.array([[0.0, 0.0], [1.0, 1.0], [3.0, 3.0]]), np.ones((4, 2))):
        with pytest.raises(QhullError):
            ConvexHull(pts)
        assert len(planar.convex_hull(pts)) < 3 and planar.min_area_rotation(pts) == 0.0


def test_hulls_found_together_are_each_ones_own():
    """Several sets' hulls and minimum-area turns found in one pass are those of each set alone
    (each within its own rounding tolerance), empty, single-point, collinear, non-finite and huge
    sets among them."""
    rng = np.random.default_rng(15)
    sets = [
        *_point_sets(rng),
        np.zeros((0, 2)),
        np.ones((3, 2)),
        np.array([[0.0, 0.0], [1.0, 1.0], [3.0, 3.0]]),
        np.array([[0.0, 0.0], [1.0, np.nan], [2.0, 0.0]]),
        rng.normal(size=(50, 2)) * 1e12,
    ]
    alone = [planar.convex_hull(p) if np.isfinite(p).all() else np.zeros(0, int) for p in sets]
    together = planar.convex_hulls([p if np.isfinite(p).all() else p[:0] for p in sets])
    assert all(np.array_equal(a, b) for a, b in zip(alone, together))
    assert planar.min_area_rotations(sets) == [planar.min_area_rotation(p) for p in sets]
    # the check sees a point less
    assert not np.array_equal(planar.convex_hulls([sets[0], sets[1][1:]])[1], alone[1])


def test_nearest_points_are_the_kd_trees():
    """Distances to the last bit, the same point (ties, between repeated points, aside) and the same
    'none nearer than the limit' as scipy's cKDTree."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(12)
    for pts in _point_sets(rng):
        queries = rng.uniform(
            pts.min(axis=0) - 5, pts.max(axis=0) + 5, size=(int(rng.integers(1, 1500)), 2)
        )
        for limit in (np.inf, 0.3, 2.0):
            d, i = planar.nearest_points(pts, queries, limit)
            d0, i0 = cKDTree(pts).query(queries, distance_upper_bound=limit)
            assert np.array_equal(d, d0) and np.array_equal(i == len(pts), i0 == len(pts))
            found = i0 < len(pts)
            assert np.array_equal(pts[i[found]], pts[i0[found]])
            origin = pts.min(axis=0) - 1.0
            for side in (0.05, 0.7, 9.0):  # the first cells made beforehand, of any side
                given = planar.nearest_points(
                    pts, queries, limit, index=(origin, side, *planar.cell_index(pts, origin, side))
                )
                assert np.array_equal(given[0], d) and np.array_equal(given[1], i)
    d, _ = planar.nearest_points(pts, queries + 1e-12)
    assert not np.array_equal(d, cKDTree(pts).query(queries)[0])  # the check sees a femtometre


def test_label_boxes_keep_the_clearance_the_kd_tree_measures():
    """A label box's margin, to the last bit, as measured by querying a kd-tree of the sampled
    lines at every point of the box (and exactly to the labels already placed)."""
    from scipy.spatial import cKDTree

    def by_tree(obstacles, center, angle, text, size):
        boxes = labels.label_candidates(center, angle, text, size).reshape(-1, 2)
        d, i = cKDTree(obstacles.points).query(boxes, distance_upper_bound=size)
        dist = np.where(i < len(obstacles.points), d - obstacles.spacing / 2, np.inf)
        if len(obstacles.extra):
            exact = planar.point_segment_distance(
                boxes[:, None], obstacles.extra[None, :, 0], obstacles.extra[None, :, 1]
            ).min(axis=1)
            dist = np.minimum(dist, np.where(exact <= size, exact, np.inf))
        worst = np.minimum(dist.reshape(len(center), -1).min(axis=1), size)
        return worst >= 0.25 * size, worst

    rng = np.random.default_rng(13)
    for k in range(40):
        walk = np.cumsum(rng.normal(size=(30, 2)) * 4, axis=0)
        obstacles = labels.Obstacles(np.stack([walk[:-1], walk[1:]], axis=1), 0.15)
        if k % 2:
            obstacles = obstacles.plus(
                polyline_segments(
                    [(labels.Label("S1", tuple(walk[5] + 1), 30.0, 2.0).corners(), True)]
                )
            )
        center = rng.uniform(walk.min(axis=0), walk.max(axis=0), size=(20, 2))
        angle = rng.uniform(-np.pi, np.pi, 20)
        text, size = ("tube 3 left", "S12")[k % 2], float(rng.uniform(1.5, 5.0))
        ok, worst = obstacles.fits(center, angle, text, size)
        ok0, worst0 = by_tree(obstacles, center, angle, text, size)
        assert np.array_equal(ok, ok0) and np.array_equal(worst, worst0)
    # the check sees a nanometre
    assert not np.array_equal(obstacles.fits(center + 1e-9, angle, text, size)[1], worst0)


def test_a_blocked_label_box_is_one_that_does_not_fit():
    """The quick test that spares measuring a box blocks only boxes that do not keep clear, and most
    of those a line crosses; a line moved into a box that fitted blocks it."""
    rng = np.random.default_rng(14)
    caught = failed = 0
    for k in range(40):
        walk = np.cumsum(rng.normal(size=(30, 2)) * 4, axis=0)
        obstacles = labels.Obstacles(np.stack([walk[:-1], walk[1:]], axis=1), 0.15)
        center = rng.uniform(walk.min(axis=0), walk.max(axis=0), size=(30, 2))
        angle = rng.uniform(-np.pi, np.pi, 30)
        text, size = ("tube 3 left", "S12")[k % 2], float(rng.uniform(1.5, 5.0))
        ok, _ = obstacles.fits(center, angle, text, size)
        blocked = obstacles.blocked(center, angle, text, size)
        assert not (blocked & ok).any()
        caught, failed = caught + int(blocked.sum()), failed + int((~ok).sum())
    assert caught > 0.5 * failed
    free = center[ok][:1]
    corner = labels.label_candidates(free, angle[ok][:1], text, size)[0, 0]
    through = labels.Obstacles(np.array([[corner - 1.0, corner + 1.0]]), 0.15)
    assert through.blocked(free, angle[ok][:1], text, size).all()
    pts = np.array([[0.0, 0.0], [3.0, 4.0]])
    index = (pts.min(axis=0), *planar.cell_index(pts, pts.min(axis=0), 1.0))
    assert planar.near_any(
        pts, np.array([[0.0, 0.999], [0.0, 1.0], [3.7, 4.7]]), 1.0, index
    ).tolist() == [True, False, True]


def test_xml_escapes_are_the_standard_librarys():
    from xml.sax.saxutils import escape, quoteattr

    for text in [
        "",
        "tube 1",
        "a < b & c > d",
        'say "hi"',
        "it's",
        'it\'s "x"',
        "tab\tnew\nline\r",
        "&amp;",
    ]:
        assert svg._escape(text) == escape(text) and svg._quoteattr(text) == quoteattr(text)
    assert svg._quoteattr("it's") != quoteattr("its")


def test_each_sheet_has_one_closed_outline_around_sheet_and_tabs(tube, tube_layout):
    for placed in tube_layout.sheets():
        sheet = tube[placed.index]
        cuts = placed.on_layer("cut")
        assert len(cuts) == 1 and cuts[0].closed
        outline = Polygon(cuts[0].points)
        assert outline.is_valid
        expected = footprint(sheet, placed)
        assert outline.symmetric_difference(expected).area < 1e-6 * expected.area


def test_tabs_lie_outside_their_sheet_along_the_seam(tube, tube_layout):
    placed = next(s for s in tube_layout.sheets() if s.index == 0)
    sheet = tube[0]
    body = sheet_polygon(sheet, placed)
    tabs = tab_polygons(placed)
    assert len(tabs) >= 2
    for tab in tabs:
        assert tab.is_valid and tab.area > 1.0
        assert tab.intersection(body).area < 1e-9 * tab.area
        assert tab.distance(body) < 1e-9  # attached along the seam
    for a, b in combinations(tabs, 2):
        assert a.intersection(b).area < 1e-9
    # the fold line of each tab is the whole seam, drawn once, on the seam layer
    for p in placed.on_layer("seam"):
        mask = sheet.edges_seam == p.seam
        seam_length = sheet.mesh.edge_lengths()[mask].sum() * tube_layout.scale
        assert LineString(p.points).length == pytest.approx(seam_length, rel=1e-9)
    assert sorted(p.seam for p in placed.on_layer("seam")) == [0, 1]


def test_tabs_go_on_one_side_of_each_seam_only(vault, vault_layout):
    owners: dict[int, set[int]] = {}
    for placed in vault_layout.sheets():
        for p in placed.on_layer("glue") + placed.on_layer("seam"):
            owners.setdefault(p.seam, set()).add(placed.index)
    seam_ids = sorted({int(i) for s in vault for i in s.edges_seam if i >= 0})
    assert sorted(owners) == seam_ids
    for sid, who in owners.items():
        having = [i for i, s in enumerate(vault) if sid in s.edges_seam]
        assert who == {min(having)}


def test_seam_labels_match_in_pairs_inside_their_sheets(vault, vault_layout):
    seen: dict[str, list[int]] = {}
    for placed in vault_layout.sheets():
        sheet = vault[placed.index]
        body = sheet_polygon(sheet, placed)
        for t in placed.labels:
            if t.kind != "seam":
                continue
            assert t.text == seam_name(t.seam)
            seen.setdefault(t.text, []).append(placed.index)
            box = Polygon(t.corners())
            assert body.contains(box)
            # beside its own seam: closer to it than to any other line of the sheet's outline
            mask = sheet.edges_seam == t.seam
            ev = sheet.mesh.edges_vertices[mask]
            xy = (
                sheet.mesh.vertices_coords[:, :2] @ placed.transform[:, :2].T
                + placed.transform[:, 2]
            )
            seam_line = unary_union([LineString(xy[e]) for e in ev])
            assert seam_line.distance(box) < 1.5 * t.size
    assert sorted(seen) == sorted(seam_name(i) for i in range(8))
    for text, sheets in seen.items():
        assert len(sheets) == 2 and sheets[0] != sheets[1], text


def test_labels_keep_clear_of_lines(tube, tube_layout):
    for placed in tube_layout.sheets():
        lines = drawn_lines(placed)
        body = sheet_polygon(tube[placed.index], placed)
        kinds = sorted(t.kind for t in placed.labels)
        assert kinds == ["seam", "seam", "sheet"]
        for t in placed.labels:
            box = Polygon(t.corners())
            assert not box.intersects(lines), t
            assert body.contains(box)
            assert -90 < t.angle <= 90
        sheet_label = next(t for t in placed.labels if t.kind == "sheet")
        assert sheet_label.text == tube[placed.index].label and sheet_label.size == 4.0
    assert tube_layout.notes == ()


def test_creases_are_chained_and_diagonals_never_drawn(tube, tube_layout):
    a = next(s for s in tube_layout.sheets() if s.index == 0)
    b = next(s for s in tube_layout.sheets() if s.index == 1)
    assert [len(p.points) for p in a.on_layer("mountain")] == [25]
    assert [len(p.points) for p in b.on_layer("valley")] == [25]
    assert a.on_layer("valley") == () and b.on_layer("mountain") == ()
    assert len(a.on_layer("rulings")) == 23  # interior radial lines, each through the crease
    sheet = tube[0]
    xy = sheet.mesh.vertices_coords[:, :2] @ a.transform[:, :2].T + a.transform[:, 2]
    diag = sheet.mesh.edges_vertices[sheet.mesh.edges_kind == "diagonal"]
    drawn = drawn_lines(a, layers=LAYERS)
    for e in diag:
        assert drawn.distance(Point(xy[e].mean(axis=0))) > 0.1


def test_a_sheet_seen_from_its_back_is_mirrored():
    front = annular_sheet("front", fold="M")
    back = annular_sheet("back", fold="M", clockwise=True)
    lay = layout_sheets([front, back], glue_tabs=False)
    for placed in lay.sheets():
        sheet = (front, back)[placed.index]
        det = np.linalg.det(placed.transform[:, :2])
        assert det == pytest.approx(1.0 if placed.index == 0 else -1.0)
        tri = placed_triangles(sheet, placed)
        u, v = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
        area = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
        assert np.all(area > 0)  # seen from the side the normals point to
        assert len(placed.on_layer("mountain")) == 1


def test_a_sheet_seen_from_its_back_keeps_its_glue_tabs_outside():
    # Mirrored, the back's clockwise triangles turn counter-clockwise: its outline runs with
    # the sheet on its left like the front's, so tabs and seam names land as on the front.
    front, back = (
        layout_sheets([annular_sheet(name, clockwise=cw)], page="A3")
        for name, cw in (("front", False), ("back", True))
    )
    assert back.notes == front.notes == ()
    for lay, cw in ((front, False), (back, True)):
        placed = lay.sheets()[0]
        body = sheet_polygon(annular_sheet("x", clockwise=cw), placed)
        tabs = tab_polygons(placed)
        assert len(tabs) == 8
        assert all(tab.intersection(body).area < 1e-9 * tab.area for tab in tabs)
        assert all(body.contains(Point(t.position)) for t in placed.labels if t.kind == "seam")
    assert sum(t.area for t in tab_polygons(back.sheets()[0])) == pytest.approx(
        sum(t.area for t in tab_polygons(front.sheets()[0])), rel=1e-9
    )


def test_without_tabs_seams_are_cut_edges():
    a, b = tube_sheets()
    lay = layout_sheets([a, b], glue_tabs=False)
    for placed in lay.sheets():
        assert placed.on_layer("glue") == () and placed.on_layer("seam") == ()
        sheet = (a, b)[placed.index]
        outline = Polygon(placed.on_layer("cut")[0].points)
        body = sheet_polygon(sheet, placed)
        assert outline.symmetric_difference(body).area < 1e-6 * body.area
    assert sorted(t.text for t in lay.sheets()[0].labels if t.kind == "seam") == ["S0", "S1"]


def test_scale_target_size_and_units(tube):
    assert layout_sheets(tube, scale=0.5).scale == 0.5
    assert layout_sheets(tube, units="in", scale=1 / 25.4).scale == pytest.approx(1.0)
    lay = layout_sheets(tube, target_size=100.0)
    # the longer side of the largest sheet's minimum-area rectangle is 100 mm
    sides = []
    for p in lay.sheets():
        rect = np.asarray(sheet_polygon(tube[p.index], p).minimum_rotated_rectangle.exterior.coords)
        sides.append(np.linalg.norm(np.diff(rect, axis=0), axis=1).max())
    assert max(sides) == pytest.approx(100.0, rel=1e-6)
    letter = layout_sheets(tube, page="letter")
    assert letter.page_size == (215.9, 279.4)
    assert layout_sheets(tube, page=(297, 210)).page_size == (297.0, 210.0)


def test_a_sheet_too_big_for_the_page_is_refused_with_both_sizes(tube):
    with pytest.raises(
        InputError, match=r"tube 1 · sheet A.*needs [\d.]+ × [\d.]+ mm.*210 × 297 " r"mm"
    ):
        layout_sheets(tube, scale=10.0)
    with pytest.raises(InputError, match=r"A5 page \(148 × 210 mm\)"):
        layout_sheets(tube, page="A5", scale=3.0)


def _with(sheet: PatternSheet, **changes) -> dict:
    m = sheet.mesh
    fields = dict(
        vertices_coords=m.vertices_coords,
        edges_vertices=m.edges_vertices,
        edges_assignment=m.edges_assignment,
        edges_foldAngle=m.edges_foldAngle,
        faces_vertices=m.faces_vertices,
        edges_kind=m.edges_kind,
        faces_group=m.faces_group,
    )
    fields.update(changes)
    return fields


@pytest.mark.parametrize(
    "inner, note, folds",
    [
        (4.0, "1 glue tab piece(s) narrowed, 0 left out (of 1)", [0, 1]),
        (1.0, "0 glue tab piece(s) narrowed, 1 left out (of 1)", [1]),
    ],
)
def test_tight_concave_seams_get_narrower_tabs_or_none_and_a_note(inner, note, folds):
    a = annular_sheet(
        "tight", radii=(inner, inner + 8.0, inner + 16.0), span_deg=(0.0, 300.0), n=30
    )
    lay = layout_sheets([a])
    assert lay.notes == (f"sheet 'tight', seam S0: {note} to keep clear of the sheet",)
    placed = lay.sheets()[0]
    assert sorted(p.seam for p in placed.on_layer("seam")) == folds
    body = sheet_polygon(a, placed)
    for tab in tab_polygons(placed):
        assert tab.intersection(body).area < 1e-9
    outline = Polygon(placed.on_layer("cut")[0].points)
    assert outline.symmetric_difference(footprint(a, placed)).area < 1e-6 * body.area


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(page="B7"), "page must be one of"),
        (dict(page=(0, 100)), "positive"),
        (dict(units="furlong"), "units must be one of"),
        (dict(scale=1.0, target_size=100.0), "not both"),
        (dict(scale=-1.0), "scale must be positive"),
        (dict(rules=LayoutRules(tab_angle=95.0)), "tab_angle must be in"),
        (dict(rules=LayoutRules(margin=200.0)), "leave no room"),
        (dict(rules=LayoutRules(tab_width=float("nan"))), "tab_width must be positive"),
    ],
)
def test_invalid_layout_arguments(tube, kwargs, match):
    with pytest.raises(InputError, match=match):
        layout_sheets(tube, **kwargs)


def test_invalid_sheets():
    a, b = tube_sheets()
    c, _ = tube_sheets(2)
    with pytest.raises(InputError, match=r"seam id 0 appears on sheets \[0, 1, 2\]"):
        layout_sheets([a, b, c])
    with pytest.raises(InputError, match="at least one"):
        layout_sheets([])
    with pytest.raises(InputError, match=r"sheets\[1\] must be a PatternSheet"):
        layout_sheets([a, "b"])
    xyz = np.array(a.mesh.vertices_coords)
    xyz[3, 2] = 1.0
    with pytest.raises(InputError, match="must lie in z = 0"):
        PatternSheet("lifted", Mesh(**_with(a, vertices_coords=xyz)), a.edges_seam)
    seam = np.array(a.edges_seam)
    seam[np.flatnonzero(a.mesh.edges_kind == "ruling")[0]] = 4
    with pytest.raises(InputError, match="exactly on edges of kind 'seam'.*'ruling' has seam id 4"):
        PatternSheet("odd seam", a.mesh, seam)
    assign = np.where(a.mesh.edges_kind == "fold", "F", a.mesh.edges_assignment)
    with pytest.raises(InputError, match="fold edges must be assigned 'M' or 'V'"):
        PatternSheet("flat fold", Mesh(**_with(a, edges_assignment=assign)), a.edges_seam)
    with pytest.raises(InputError, match=r"edges_seam must have shape"):
        PatternSheet("short", a.mesh, a.edges_seam[:-1])
    kinds = np.where(a.mesh.edges_kind == "boundary", "ruling", a.mesh.edges_kind)
    with pytest.raises(InputError, match="lies on the outline, but its kind is 'ruling'"):
        layout_sheets([PatternSheet("open", Mesh(**_with(a, edges_kind=kinds)), a.edges_seam)])


@settings(max_examples=8, deadline=None)
@given(
    inner=st.floats(8.0, 60.0),
    width=st.floats(6.0, 30.0),
    span=st.floats(20.0, 300.0),
    n=st.integers(3, 40),
    angle=st.floats(0.0, 360.0),
)
# tabs split where the seam turns 60° toward them
@example(inner=8.0, width=6.0, span=300.0, n=5, angle=0.0)
def test_tabs_never_overlap_their_sheet_on_random_sectors(inner, width, span, n, angle):
    # Tight concave seams (small inner radius) make tabs narrow or drop out, never overlap.
    a = annular_sheet(
        "a", radii=(inner, inner + width / 2, inner + width), span_deg=(angle, angle + span), n=n
    )
    lay = layout_sheets([a], page="A3")
    placed = lay.sheets()[0]
    body = sheet_polygon(a, placed)
    tabs = tab_polygons(placed)
    for tab in tabs:
        assert tab.is_valid
        assert tab.intersection(body).area < 1e-6 * max(tab.area, 1e-9)
    for t1, t2 in combinations(tabs, 2):
        assert t1.intersection(t2).area < 1e-6
    outline = Polygon(placed.on_layer("cut")[0].points)
    assert outline.is_valid
    assert outline.symmetric_difference(footprint(a, placed)).area < 1e-6 * body.area


def test_tab_check_rejects_tabs_that_fold_back_graze_or_cross_themselves():
    # An inner seam of radius 8 in 60° steps, tabs on its right (toward the centre). Split at
    # a vertex, where it turns 60° toward them, the neighbouring 60° tapers lie on one line:
    # the second tab's cut runs back along the first's (the outline doubles back on itself).
    th = np.radians(-60.0 * np.arange(5))
    ring = np.stack([np.cos(th), np.sin(th)], axis=1)
    seam = 8.0 * ring

    def sheet(seam):  # the sheet's outline: radii 8 to 14
        return polyline_segments([(np.concatenate([seam, 14.0 * ring[::-1]]), True)])

    outline = sheet(seam)
    taper, tol = np.radians(60.0), 1e-9
    first, second = (tab_outline(piece, 6.0, taper) for piece in (seam[:3], seam[2:]))
    assert tab_fits(first, outline, [], tol) and tab_fits(second, outline, [], tol)
    assert_allclose(first[1][-2:][::-1], second[1][:2], atol=1e-12)  # the same segment, both ways
    assert not tab_fits(second, outline, [first[0]], tol)
    # each as if those before it were placed
    assert tabs_fit([first, second], outline, [], tol).tolist() == [True, False]
    assert tabs_fit([second, first], outline, [], tol).tolist() == [True, False]
    # split in the middle of a segment instead, the two tabs leave 60° between their tapers
    pieces = tab_pieces(seam, 1e3, 15.0)  # two pieces (at least 15 long, of 32)
    assert len(pieces) == 2
    middles = 0.5 * (seam[:-1] + seam[1:])
    assert np.linalg.norm(middles - pieces[0][-1], axis=1).min() < 1e-12
    a, b = (tab_outline(p, 6.0, taper) for p in pieces)
    split = sheet(np.concatenate([pieces[0][:-1], pieces[1]]))
    assert tab_fits(a, split, [], tol) and tab_fits(b, split, [a[0]], tol)
    # damaged tabs: an outer corner moved onto the seam (at a vertex or between), two outer
    # corners swapped (self-crossing), the whole tab moved into the sheet
    polygon, cut = first
    for point in (seam[3], 0.5 * (seam[3] + seam[4])):
        grazing = cut.copy()
        grazing[2] = point
        assert not tab_fits((polygon, grazing), outline, [], tol)
    crossed = cut.copy()
    crossed[[1, -2]] = crossed[[-2, 1]]
    assert not tab_fits((polygon, crossed), outline, [], tol)
    across = cut.copy()
    across[2] = 20.0 * ring[1]  # a corner beyond the sheet: the cut runs across it
    assert not tab_fits((polygon, across), outline, [], tol)
    inward = (cut - seam[1]) * 0.1 + 11.0 * ring[1]
    assert not tab_fits((polygon, inward), outline, [], tol)
    # ... or a tab that would cover a piece of the sheet or another tab whole (an island)
    middle = polygon.mean(axis=0)
    island = polyline_segments([(middle + 0.2 * (polygon - middle), True)])
    assert not tab_fits(first, np.concatenate([outline, island]), [], tol)
    assert not tab_fits(first, outline, [middle + 0.2 * (polygon - middle)], tol)
    # ... or a corner of the sheet that touches the cut from outside
    m = 0.5 * (cut[1] + cut[2])
    u, w = -m / np.linalg.norm(m), np.array([m[1], -m[0]]) / np.linalg.norm(m)
    touching = polyline_segments(
        [(np.stack([m, m + 0.3 * u + 0.1 * w, m + 0.3 * u - 0.1 * w]), True)]
    )
    assert tab_fits(first, np.concatenate([outline, touching + 1e-6 * u]), [], tol)
    assert not tab_fits(first, np.concatenate([outline, touching]), [], tol)


def test_tabs_placed_a_batch_at_a_time_are_those_placed_one_by_one():
    # A wavy seam on a strip, in pieces whose tabs meet their neighbours' and the strip's far side:
    # widest, narrowed and left out, more pieces than a batch
    x = np.linspace(0.0, 60.0, 121)
    # the strip above it (on its left), tabs below
    seam = np.stack([x, 2.5 * np.sin(x / 3.0)], axis=1)
    taper, tol = np.radians(60.0), 1e-9
    for width, length in ((3.0, 8.0), (6.0, 7.0), (9.0, 6.0), (14.0, 1.8), (30.0, 1.8)):
        pieces = tab_pieces(seam, length, 1.0)
        # the seam split where they meet
        split = np.concatenate([p[:-1] for p in pieces] + [seam[-1:], [[60.0, 9.0], [0.0, 9.0]]])
        outline = polyline_segments([(split, True)])
        accepted, expected = [], []
        for piece in pieces:  # one by one
            got = None
            for step, fraction in enumerate(TAB_WIDTH_STEPS):
                tab = tab_outline(piece, fraction * width, taper)
                if tab is not None and tab_fits(tab, outline, accepted, tol):
                    got = (tab, step)
                    accepted.append(tab[0])
                    break
            expected.append(got)
        placed = place_tabs(pieces, outline, width, taper, tol)
        assert [None if g is None else g[1] for g in placed] == [
            None if g is None else g[1] for g in expected
        ]
        for g, e in zip(placed, expected):
            if g is not None:
                assert np.array_equal(g[0][0], e[0][0]) and np.array_equal(g[0][1], e[0][1])


def test_docstring_examples():
    for module in (layout_module, labels, planar, cutters, cutting, pdf):
        assert doctest.testmod(module).failed == 0


# --------------------------------------------------------------------------------------
# SVG


def test_svg_has_mm_units_inkscape_layers_and_chained_polylines(tmp_path, tube_layout):
    (path,) = write_svg(tmp_path / "tube.svg", tube_layout)
    assert path == tmp_path / "tube.svg"
    root = ET.parse(path).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == (
        "210mm",
        "297mm",
        "0 0 210 297",
    )
    assert "sodipodi:namedview" in path.read_text() and "xmlns:sodipodi" in path.read_text()
    groups = root.findall("svg:g", NS)
    assert [g.get(f"{INK}label") for g in groups] == [layer_name(k) for k in DEFAULT_LAYERS] + [
        LEGEND_LAYER
    ]
    assert [g.get(f"{INK}label") for g in groups][:4] == [
        "reference - glue (not cut)",
        "score - seam",
        "score - valley",
        "score - mountain",
    ]
    assert all(g.get(f"{INK}groupmode") == "layer" for g in groups)
    by_name = {k: g for k, g in zip([*DEFAULT_LAYERS, "legend"], groups)}
    legend = by_name.pop("legend")
    groups = groups[:-1]
    page = tube_layout.pages[0]
    for name in ("cut", "mountain", "valley", "seam", "glue"):
        assert len(list(by_name[name])) == len(page.on_layer(name)) > 0
    assert len(list(by_name["cut"])) == 2  # one outline per sheet, not one element per edge
    assert "stroke-dasharray" in by_name["mountain"].get("style")
    assert "stroke-dasharray" in by_name["valley"].get("style")
    assert "stroke-dasharray" not in by_name["cut"].get("style")
    texts = [t.text for t in by_name["labels"].findall("svg:text", NS)]
    assert sorted(texts) == sorted(["tube 1 · sheet A", "tube 1 · sheet B", "S0", "S0", "S1", "S1"])
    # coordinates are page mm, y flipped: every point inside the margins
    pts = np.array(
        [
            [float(v) for v in pair.split(",")]
            for g in groups
            for el in g
            if el.get("points")
            for pair in el.get("points").split()
        ]
    )
    assert pts.min() >= 10 - 1e-6 and pts[:, 0].max() <= 200 and pts[:, 1].max() <= 287
    # the sheets keep clear of the footer band (SVG y runs down)
    assert pts[:, 1].max() <= 287 - tube_layout.footer
    # the footer: a 10 mm scale bar with the print scale, and a legend of what this page draws
    bar = np.array(
        [[float(v) for v in pair.split(",")] for pair in legend[0].get("points").split()]
    )
    assert (
        np.ptp(bar[:, 0]) == pytest.approx(10.0)
        and 297 - 10 - tube_layout.footer <= bar[:, 1].min() <= bar[:, 1].max() <= 287
    )
    words = [t.text for t in legend.iter(f"{{{NS['svg']}}}text")]
    assert any(
        "10 mm: print at 100 %" in w and "1 model unit = " in w and "page 1 of 1" in w
        for w in words
    )
    colours = CUTTERS["print"].colours
    # for print the legend names the layers, its samples show their colours
    assert {LEGEND[k] for k in ("cut", "mountain", "valley", "seam", "glue", "labels")} | {
        "S1"
    } <= set(words)
    painted = {
        m for el in legend.iter() for m in re.findall(r"#[0-9a-f]{6}", f"{el.get('style', '')}")
    }
    assert painted == {
        colours[k] for k in ("legend", "cut", "mountain", "valley", "seam", "glue", "labels")
    }
    assert colours["legend"] not in {colours[k] for k in DEFAULT_LAYERS}


def _png(path: Path) -> np.ndarray:
    from matplotlib.image import imread

    img = imread(path)
    return img[..., :3] if img.dtype != np.uint8 else img[..., :3] / 255.0


def _colour_counts(img: np.ndarray) -> dict[str, int]:
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return {
        "ink": int(np.count_nonzero(img.min(axis=-1) < 0.9)),
        "black": int(np.count_nonzero(img.max(axis=-1) < 0.3)),
        "red": int(np.count_nonzero((r > 0.7) & (g < 0.35) & (b < 0.35))),
        "blue": int(np.count_nonzero((b > 0.7) & (r < 0.45) & (g < 0.55))),
        "green": int(np.count_nonzero((g > r + 0.08) & (g > b + 0.08))),
        "purple": int(np.count_nonzero((r > 0.35) & (b > 0.5) & (g < 0.35))),
    }


@needs("rsvg-convert")
def test_svg_renders_at_true_size_with_every_layer_visible(tmp_path, tube_layout):
    (path,) = write_svg(tmp_path / "tube.svg", tube_layout)
    png = tmp_path / "tube.png"
    subprocess.run(
        ["rsvg-convert", "-d", "150", "-p", "150", "-b", "white", str(path), "-o", str(png)],
        check=True,
    )
    img = _png(png)
    assert np.abs(np.array(img.shape[:2]) - np.array([297, 210]) / 25.4 * 150).max() <= 1
    counts = _colour_counts(img)
    assert counts["ink"] > 0.01 * img.shape[0] * img.shape[1]
    for colour in ("black", "red", "blue", "green", "purple"):
        assert counts[colour] > 200, (colour, counts)


def test_svg_pages_get_numbered_files(tmp_path, vault_layout):
    n = len(vault_layout.pages)
    paths = write_svg(tmp_path / "vault.svg", vault_layout)
    assert [p.name for p in paths] == [f"vault-p{i + 1}.svg" for i in range(n)]
    assert not (tmp_path / "vault.svg").exists()
    for p, page in zip(paths, vault_layout.pages):
        root = ET.parse(p).getroot()
        assert root.get("width") == "148mm"
        assert len(root.findall("svg:g[@id='layer-labels']/svg:text", NS)) == len(page.labels())
    (one,) = write_svg(tmp_path / "second.svg", vault_layout, 1, layers=LAYERS)
    root = ET.parse(one).getroot()
    assert [g.get(f"{INK}label") for g in root.findall("svg:g", NS)] == [
        layer_name(k) for k in LAYERS
    ] + [LEGEND_LAYER]
    with pytest.raises(
        InputError, match=rf"page_index must be an integer in \[0, {n - 1}\], got " rf"{n}$"
    ):
        write_svg(tmp_path / "x.svg", vault_layout, n)
    # was taken as page 1
    with pytest.raises(InputError, match=r"page_index must be an integer .*, got boolean True$"):
        write_svg(tmp_path / "x.svg", vault_layout, True)
    with pytest.raises(InputError, match="layers must be among"):
        write_svg(tmp_path / "x.svg", vault_layout, layers=["cut", "engrave"])


# --------------------------------------------------------------------------------------
# DXF


def test_dxf_pages_lie_framed_in_a_grid_within_the_extents(tmp_path, vault_layout):
    ezdxf = pytest.importorskip("ezdxf")
    from ezdxf import bbox

    doc = ezdxf.readfile(write_dxf(tmp_path / "v.dxf", vault_layout))
    msp = doc.modelspace()
    n, (W, H) = len(vault_layout.pages), vault_layout.page_size
    frames = [np.array(f.get_points("xy")) for f in msp.query('LWPOLYLINE[layer=="pages"]')]
    corners = pattern.page_grid(n, (W, H), 20.0)
    assert sorted(map(tuple, (f.min(axis=0) for f in frames))) == sorted(map(tuple, corners))
    assert all(np.ptp(f, axis=0).tolist() == [W, H] for f in frames)
    assert len(set(corners[:, 0])) == int(np.ceil(np.sqrt(n))) < n  # a grid, not one row
    extents = bbox.extents(msp)  # of every entity, as a CAD program zooms to
    assert doc.header["$EXTMIN"][:2] == pytest.approx(tuple(extents.extmin)[:2])
    assert doc.header["$EXTMAX"][:2] == pytest.approx(tuple(extents.extmax)[:2])
    assert doc.layers.get("pages").dxf.plot == 0 and doc.layers.get(LEGEND_LAYER).dxf.plot == 0
    words = [t.dxf.text for t in msp.query(f'TEXT[layer=="{LEGEND_LAYER}"]')]
    assert sum("10 mm: print at 100 %" in w for w in words) == n


def test_dxf_reads_back_with_layers_linetypes_units_and_entities(tmp_path, vault_layout):
    ezdxf = pytest.importorskip("ezdxf")
    path = write_dxf(tmp_path / "vault.dxf", vault_layout)
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    assert doc.header["$INSUNITS"] == 4
    by_name = {layer.dxf.name: layer for layer in doc.layers}
    assert {layer_name(k) for k in DEFAULT_LAYERS} <= set(
        by_name
    ) and "engrave - rulings" not in by_name
    layers = {k: by_name[layer_name(k)] for k in DEFAULT_LAYERS}
    assert layers["cut"].dxf.linetype.upper() == "CONTINUOUS"
    # LibreCAD's small built-in patterns by name, ours inside
    assert layers["mountain"].dxf.linetype == "DASHDOTTINY"
    assert layers["valley"].dxf.linetype == "DASHEDTINY"
    assert layers["seam"].dxf.linetype == "DOTTINY"
    assert (layers["cut"].color, layers["mountain"].color, layers["valley"].color) == (7, 1, 5)
    # mm
    assert doc.linetypes.get("DASHEDTINY").simplified_line_pattern() == pytest.approx((3.0, 1.5))
    assert doc.linetypes.get("DASHDOTTINY").simplified_line_pattern() == pytest.approx(
        (4.0, 1.2, 0.7, 1.2)
    )
    msp = doc.modelspace()
    sheets = vault_layout.sheets()

    def count(layer):
        return sum(len(s.on_layer(layer)) for s in sheets)

    assert len(msp.query('LWPOLYLINE[layer=="cut"]')) == len(sheets)
    assert all(e.closed for e in msp.query('LWPOLYLINE[layer=="cut"]'))
    for layer in ("mountain", "valley", "seam"):
        assert len(msp.query(f'LWPOLYLINE[layer=="{layer_name(layer)}"]')) == count(layer) > 0
    assert len(msp.query(f'HATCH[layer=="{layer_name("glue")}"]')) == count("glue") > 0
    texts = msp.query(f'TEXT[layer=="{layer_name("labels")}"]')
    assert sorted(t.dxf.text for t in texts) == sorted(t.text for s in sheets for t in s.labels)
    assert len(msp.query("LINE")) == 0  # polylines only
    # pages side by side: every entity of page 2 is right of page 1
    W = vault_layout.page_size[0]
    xs = [min(x for x, *_ in e.get_points()) for e in msp.query("LWPOLYLINE")]
    assert max(xs) > W + 20


# --------------------------------------------------------------------------------------
# PDF


@needs("pdftoppm")
def test_pdf_pages_size_and_content(tmp_path, vault_layout):
    path = write_pdf(tmp_path / "vault.pdf", vault_layout, layers=LAYERS)
    n = len(vault_layout.pages)
    subprocess.run(["pdftoppm", "-r", "50", "-png", str(path), str(tmp_path / "page")], check=True)
    pngs = sorted(tmp_path.glob("page-*.png"))
    assert len(pngs) == n
    for png in pngs:
        img = _png(png)
        assert abs(img.shape[1] - 148 / 25.4 * 50) <= 1 and abs(img.shape[0] - 210 / 25.4 * 50) <= 1
        assert _colour_counts(img)["ink"] > 0.01 * img.shape[0] * img.shape[1]
    info = subprocess.run(["pdfinfo", str(path)], check=True, capture_output=True, text=True).stdout
    assert re.search(rf"^Pages:\s+{n}$", info, re.M)
    assert "419.528 x 595.276 pts" in info  # A5 in points


@needs("pdftoppm")
def test_pdf_prints_a4_at_one_to_one_with_a_10_mm_scale_bar(tmp_path, tube_layout):
    path = write_pdf(tmp_path / "tube.pdf", tube_layout)
    subprocess.run(["pdftoppm", "-r", "50", "-png", str(path), str(tmp_path / "low")], check=True)
    (low,) = tmp_path.glob("low-*.png")
    img = _png(low)
    assert abs(img.shape[1] - 413) <= 1 and abs(img.shape[0] - 585) <= 1
    counts = _colour_counts(img)
    assert counts["ink"] > 1000 and counts["red"] > 10 and counts["blue"] > 10
    dpi = 300
    subprocess.run(
        ["pdftoppm", "-r", str(dpi), "-png", str(path), str(tmp_path / "high")], check=True
    )
    (high,) = tmp_path.glob("high-*.png")
    img = _png(high)
    mm = dpi / 25.4
    ink = img.max(axis=-1) < 0.9
    # printers leave the outer 3–6 mm blank: nothing is drawn within 9.5 mm of an edge
    edge = int(9.5 * mm)
    assert (
        not ink[:edge].any()
        and not ink[-edge:].any()
        and not ink[:, :edge].any()
        and not ink[:, -edge:].any()
    )
    band = img[-int((10 + tube_layout.footer) * mm) : -int(10 * mm), : int(25 * mm)]
    grey = np.abs(band - 0x59 / 255).max(axis=-1) < 0.06  # the footer's reference grey, #595959
    row = grey[np.argmax(grey.sum(axis=1))]
    runs = np.diff(np.flatnonzero(np.diff(np.concatenate([[0], row.astype(int), [0]]))))[::2]
    assert runs.max() / mm == pytest.approx(10.0, abs=0.15)


def test_pdf_scale_bar_is_10_mm_and_every_operation_has_its_layer(tmp_path, tube_layout):
    """pdfplumber (pdfminer) reads the drawing back: the scale bar is a 10.00 mm rectangle in the
    reference colour, the labels are text, and the document lists one optional-content layer per
    operation."""
    pdfplumber = pytest.importorskip("pdfplumber")
    path = write_pdf(tmp_path / "tube.pdf", tube_layout)
    mm = 72 / 25.4
    with pdfplumber.open(path) as doc:
        (page,) = doc.pages
        assert (page.width, page.height) == pytest.approx((210 * mm, 297 * mm))
        bars = [
            c
            for c in page.curves + page.rects
            if c.get("fill")
            and abs(c["width"] - 10 * mm) < 0.5
            and abs(c["height"] - 1.2 * mm) < 0.1
        ]
        assert len(bars) == 1 and bars[0]["width"] / mm == pytest.approx(10.0, abs=1e-3)
        assert tuple(bars[0]["non_stroking_color"]) == pytest.approx((0x59 / 255,) * 3, abs=1e-3)
        words = page.extract_text()
        assert "tube 1 · sheet A" in words and "S0" in words and "10 mm: print at 100 %" in words
        catalog = doc.doc.catalog
        groups = [g.resolve()["Name"].decode() for g in catalog["OCProperties"]["OCGs"]]
    assert groups == [layer_name(k) for k in DEFAULT_LAYERS] + [LEGEND_LAYER]


def test_pdf_text_is_centred_with_the_fonts_own_widths(tmp_path, tube_layout):
    """The footer's scale note, set left to right at 0°: pdfminer's glyph boxes (from the font's
    own metrics) span exactly the box the footer laid out for it."""
    pdfplumber = pytest.importorskip("pdfplumber")
    path = write_pdf(tmp_path / "tube.pdf", tube_layout)
    mm = 72 / 25.4
    note = legend.page_footer(tube_layout, 0).texts[0]
    with pdfplumber.open(path) as doc:
        chars = doc.pages[0].chars
    text = "".join(c["text"] for c in chars)
    start = text.index("10 mm: print")
    run = chars[start : start + len(note.text)]
    assert "".join(c["text"] for c in run) == note.text
    left, right = run[0]["x0"] / mm, run[-1]["x1"] / mm
    assert 0.5 * (left + right) == pytest.approx(note.position[0], abs=5e-3)
    # positions written to 0.1 µm, sizes to 4 decimals
    assert right - left == pytest.approx(pdf.text_advance(note.text, note.size), abs=5e-3)
    # within the box the layout kept clear
    assert right - left <= labels.text_width(note.text, note.size)


def test_pdf_text_anchors_its_point_along_the_baseline():
    """A line set from its start, centre or end: its matrix starts the text at x minus 0, ½
    or 1 of its width; an anchor not known is refused where the line is made."""
    width = pdf.text_advance("S12", 5.0)
    for anchor, shift in (("start", 0.0), ("center", 0.5), ("end", 1.0)):
        page = pdf.PdfDocument(title="anchors", layers=["labels"]).page(210.0, 297.0)
        page.text(pdf.PdfText("S12", 100.0, 50.0, 5.0, "#000000", anchor=anchor, layer="labels"))
        matrix = page.content().split(b" Tf ")[1].split(b" Tm")[0].split()
        assert float(matrix[4]) == pytest.approx(100.0 - shift * width, abs=1e-4), anchor
        assert float(matrix[5]) == 50.0
    with pytest.raises(InputError, match="anchor must be 'start', 'center' or 'end', got 'left'"):
        pdf.PdfText("S12", 100.0, 50.0, 5.0, "#000000", anchor="left")


def _pdffonts(path: Path) -> list[list[str]]:
    """pdffonts' rows: name, type, encoding, emb, sub, uni, object number."""
    out = subprocess.run(["pdffonts", str(path)], check=True, capture_output=True, text=True)
    return [line.split() for line in out.stdout.splitlines()[2:]]


@needs("pdffonts")
@needs("pdftotext")
def test_pdf_embeds_a_subset_of_dejavu_sans_and_its_text_reads(tmp_path, tube_layout, monkeypatch):
    """poppler lists the one font as an embedded TrueType subset (``emb yes``, ``sub yes``) of
    DejaVu Sans in WinAnsi; its text reads back (pdftotext); the program holds the glyphs used
    and no more (under 12 kB). Without the program, pdffonts reports it: ``emb no``."""
    path = write_pdf(tmp_path / "tube.pdf", tube_layout)
    ((name, kind, encoding, emb, sub, *_),) = _pdffonts(path)
    assert re.fullmatch(r"[A-Z]{6}\+DejaVuSans", name)
    assert (kind, encoding, emb, sub) == ("TrueType", "WinAnsi", "yes", "yes")
    words = subprocess.run(
        ["pdftotext", str(path), "-"], check=True, capture_output=True, text=True
    ).stdout
    assert "tube 1 · sheet A" in words and "10 mm: print at 100 %" in words
    from curvefold.io import _pdf_font

    used = "".join(sorted({c for c in words if c.isprintable()}))
    program = _pdf_font.font_program(used)
    assert program is not None and len(program) < 12_000
    monkeypatch.setattr(pdf, "font_program", lambda characters: None)
    damaged = write_pdf(tmp_path / "named.pdf", tube_layout)
    ((name, kind, encoding, emb, sub, *_),) = _pdffonts(damaged)
    assert (name, emb, sub) == ("DejaVuSans", "no", "no")


def _widths_off(path: Path, expected: dict[str, int]) -> set[str]:
    """The characters whose advance, as pdfminer reads it (from the file's /Widths), over the
    advance ``expected`` at em height 1 mm is none of the em heights the page sets text at."""
    import pdfplumber

    with pdfplumber.open(path) as doc:
        chars = doc.pages[0].chars
        content = b"".join(s.get_data() for s in doc.pages[0].page_obj.contents)
    (font,) = {c["fontname"] for c in chars}
    assert font.endswith("+DejaVuSans")
    sizes = [float(v) for v in re.findall(rb"/F1 (\S+) Tf", content)]
    return {
        c["text"]
        for c in chars
        if min(abs(c["adv"] * 1000.0 / expected[c["text"]] - v) for v in sizes) > 1e-9
    }


def test_pdf_widths_are_the_embedded_fonts_own(tmp_path, tube_layout, monkeypatch):
    """The widths the layout sets text with (:data:`~curvefold.io._pdf_font.WIDTHS`) are the
    advance widths of DejaVu Sans as fontTools reads them from the font file (its 2048 units per
    em, rounded to thousandths of the em); the embedded program and the ``/Widths`` that
    pdfminer reads agree with them glyph for glyph. A table with one width off by one is seen."""
    ttlib = pytest.importorskip("fontTools.ttLib")
    pytest.importorskip("pdfplumber")
    from curvefold.io import _pdf_font

    font = ttlib.TTFont(str(_pdf_font.font_path()))
    cmap, advances = font.getBestCmap(), font["hmtx"]
    scale = 1000.0 / font["head"].unitsPerEm
    expected = {c: round(advances[cmap[ord(c)]][0] * scale) for c in _pdf_font.WIDTHS}
    assert _pdf_font.WIDTHS == expected and len(expected) == 218
    embedded = ttlib.TTFont(_io.BytesIO(_pdf_font.font_program("".join(expected))))
    sub_cmap, sub_advances = embedded.getBestCmap(), embedded["hmtx"]
    assert {c: round(sub_advances[sub_cmap[ord(c)]][0] * scale) for c in expected} == expected
    assert _widths_off(write_pdf(tmp_path / "tube.pdf", tube_layout), expected) == set()
    monkeypatch.setitem(_pdf_font.WIDTHS, "S", expected["S"] + 1)
    assert _widths_off(write_pdf(tmp_path / "off.pdf", tube_layout), expected) == {"S"}


# --------------------------------------------------------------------------------------
# atomic writes


def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


@pytest.mark.parametrize("fail_at", [1, 2])
def test_svg_write_failing_midway_leaves_nothing(tmp_path, vault_layout, monkeypatch, fail_at):
    # fail_at=2: the first page is already complete when the second fails; neither stays.
    real = Path.write_bytes
    calls = []

    def fail_partway(self, data):
        calls.append(self)
        if len(calls) < fail_at:
            return real(self, data)
        real(self, data[: len(data) // 2])
        raise OSError("disk full")

    monkeypatch.setattr(Path, "write_bytes", fail_partway)
    with pytest.raises(OSError, match="disk full"):
        write_svg(tmp_path / "vault.svg", vault_layout)
    assert len(calls) == fail_at
    assert _leftovers(tmp_path) == []


def test_dxf_write_failing_midway_leaves_nothing_and_keeps_the_old_file(
    tmp_path, tube_layout, monkeypatch
):
    ezdxf = pytest.importorskip("ezdxf")
    old = tmp_path / "tube.dxf"
    old.write_text("old")

    def half_then_fail(self, filename, **kwargs):
        Path(filename).write_text("0\nSECTION\n")
        raise OSError("disk full")

    monkeypatch.setattr(ezdxf.document.Drawing, "saveas", half_then_fail)
    with pytest.raises(OSError, match="disk full"):
        write_dxf(old, tube_layout)
    assert _leftovers(tmp_path) == ["tube.dxf"] and old.read_text() == "old"


def test_pdf_write_failing_midway_leaves_nothing(tmp_path, vault_layout, monkeypatch):
    real = Path.write_bytes

    def half_then_fail(self, data):
        real(self, data[: len(data) // 2])
        raise OSError("disk full")

    monkeypatch.setattr(Path, "write_bytes", half_then_fail)
    with pytest.raises(OSError, match="disk full"):
        write_pdf(tmp_path / "vault.pdf", vault_layout)
    assert _leftovers(tmp_path) == []


def test_writers_refuse_what_is_not_a_layout(tmp_path):
    for writer in (write_svg, write_dxf, write_pdf):
        with pytest.raises(InputError, match="layout must be a Layout"):
            writer(tmp_path / "x.out", "not a layout")
    assert _leftovers(tmp_path) == []
    assert cutters.STYLES.keys() == {*LAYERS, "legend"} and all(
        c.colours.keys() == {*LAYERS, "legend"} for c in CUTTERS.values()
    )
