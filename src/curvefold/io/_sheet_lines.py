"""One developed sheet drawn in its own frame: its outline, creases, glue tabs and labels.

The sheet is scaled to millimetres and seen from the side its face normals point to
(mirrored when its triangles turn clockwise); its outline loops run with the interior on
the left, split into chains of one seam each; its folds and rulings are chained into
polylines (triangulating diagonals are never drawn). :func:`build_sheet` adds the glue
tabs on the tabbed seams and places the sheet's and seams' labels clear of its lines.
:func:`curvefold.io._layout.layout_sheets` places the sheets so drawn on pages.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import numpy as np

from ..geometry._mesh import edges_faces
from ..geometry._sheets import PatternSheet
from ..kernel._errors import InputError
from ._labels import MIN_LABEL_SIZE, Label, Obstacles, seam_label, seam_name, sheet_label
from ._planar import bounding_box, cross2, polyline_segments
from ._tabs import place_tabs, tab_pieces

__all__ = ["LocalSheet", "SeamChain", "SheetRules", "build_sheet", "local_sheet"]


def _chain_edges(edges: np.ndarray) -> list[tuple[list[int], bool]]:
    """Chain undirected edges (k, 2) into polylines of vertex indices: (indices, closed)."""
    pairs = edges.tolist()
    adj: defaultdict[int, list[tuple[int, int]]] = defaultdict(list)
    for k, (a, b) in enumerate(pairs):
        adj[a].append((k, b))
        adj[b].append((k, a))
    used = [False] * len(pairs)  # (a list: read and set one at a time)

    def walk(start: int) -> tuple[list[int], bool]:
        path, cur = [start], start
        while True:
            k, other = next(((k, other) for k, other in adj[cur] if not used[k]), (-1, -1))
            if k < 0:
                return path, False
            used[k] = True
            cur = other
            if cur == start:
                return path, True
            path.append(cur)
            if len(adj[cur]) != 2:
                return path, False

    chains = []
    for v in sorted(adj):
        if len(adj[v]) != 2:
            for k, _ in adj[v]:  # each walk from v leaves by its first unused edge
                if not used[k]:
                    chains.append(walk(v))
    for k in range(len(pairs)):
        if not used[k]:
            chains.append(walk(pairs[k][0]))
    return chains


@dataclass(frozen=True, eq=False)
class SeamChain:
    """A maximal run of seam edges with one id on one outline loop (local mm)."""

    sheet: int
    seam: int
    loop: int
    start: int  # position of its first edge in the loop
    count: int  # number of edges
    points: np.ndarray  # (count + 1, 2), sheet interior on the left


@dataclass(frozen=True, eq=False)
class LocalSheet:
    """A sheet in its own frame, scaled to mm and seen from the front."""

    xy: np.ndarray  # (V, 2)
    mirror: bool
    # per loop: vertex ids (n,), edge ids (n,), interior on the left
    loops: list[tuple[np.ndarray, np.ndarray]]
    chains: list[SeamChain]
    creases: list[tuple[str, np.ndarray, bool, int]]  # mountain, valley, rulings: Polyline's fields


def local_sheet(index: int, sheet: PatternSheet, scale: float) -> LocalSheet:
    # polygons split; the added diagonals come after the sheet's own edges
    mesh = sheet.mesh.triangulated()
    name = sheet.label
    xy = mesh.vertices_coords[:, :2] * scale
    faces = mesh.faces_vertices
    tri = xy[faces]
    area2 = cross2(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    mirror = bool(area2.sum() < 0)
    if mirror:
        xy = xy * np.array([-1.0, 1.0])
        area2 = -area2
    tol = 1e-9 * float(np.abs(area2).max(initial=0.0))
    if np.any(area2 < -tol):
        raise InputError(
            f"sheet {name!r}: triangles must all turn the same way in the plane; "
            f"{int(np.count_nonzero(area2 < -tol))} of {len(faces)} are flipped"
        )
    ef = edges_faces(faces, mesh.edges_vertices)  # counter-clockwise in xy, mirrored or not
    nfaces = np.count_nonzero(ef >= 0, axis=1)
    outline = np.isin(mesh.edges_kind, ("boundary", "seam"))
    bad = np.flatnonzero(outline & (nfaces != 1))
    if bad.size:
        raise InputError(
            f"sheet {name!r}: edge {bad[0]} of kind "
            f"{str(mesh.edges_kind[bad[0]])!r} must border exactly one triangle, borders "
            f"{nfaces[bad[0]]}"
        )
    bad = np.flatnonzero(~outline & (nfaces != 2))
    if bad.size:
        raise InputError(
            f"sheet {name!r}: edge {bad[0]} borders {nfaces[bad[0]]} triangle(s), "
            f"so it lies on the outline, but its kind is {str(mesh.edges_kind[bad[0]])!r} "
            "(must be 'boundary' or 'seam')"
        )

    # Outline loops, directed as their triangle traverses them (interior on the left).
    ids = np.flatnonzero(outline)
    ev = mesh.edges_vertices[ids]
    directed = np.where((ef[ids, 0] >= 0)[:, None], ev, ev[:, ::-1])
    tails, heads = directed[:, 0].tolist(), directed[:, 1].tolist()
    out_of: defaultdict[int, list[int]] = defaultdict(list)
    for j, a in enumerate(tails):
        out_of[a].append(j)
    used = [False] * len(ids)
    loops = []
    for j0 in range(len(ids)):
        if used[j0]:
            continue
        order, j = [], j0  # the loop's outline edges, as positions in ids
        while not used[j]:
            used[j] = True
            order.append(j)
            after = out_of.get(heads[j], ())
            # (one but where loops touch)
            j = after[0] if len(after) == 1 else next((k for k in after if not used[k]), j0)
        loops.append((directed[order, 0], ids[order]))

    chains = []
    for li, (verts, edges) in enumerate(loops):
        sid = sheet.edges_seam[edges]
        n = len(edges)
        change = np.flatnonzero(sid != np.roll(sid, 1))
        starts = change.tolist() if change.size else [0]
        for k, s0 in enumerate(starts):
            count = ((starts[(k + 1) % len(starts)] - s0) % n) or n
            if sid[s0] < 0:
                continue
            idx = verts[(s0 + np.arange(count + 1)) % n]
            chains.append(SeamChain(index, int(sid[s0]), li, s0, count, xy[idx]))

    kind, assign = mesh.edges_kind, mesh.edges_assignment
    paths = [
        (layer, path, closed)
        for layer, mask in (
            ("mountain", (kind == "fold") & (assign == "M")),
            ("valley", (kind == "fold") & (assign == "V")),
            ("rulings", kind == "ruling"),
        )
        for path, closed in _chain_edges(mesh.edges_vertices[mask])
    ]
    # every crease's points, gathered at once
    points = xy[[v for _, path, _ in paths for v in path]]
    ends = np.cumsum([len(path) for _, path, _ in paths]).tolist()
    creases = [
        (layer, points[end - len(path) : end], closed, -1)
        for (layer, path, closed), end in zip(paths, ends)
    ]
    return LocalSheet(xy, mirror, loops, chains, creases)


@dataclass(frozen=True)
class SheetRules:
    """What :func:`build_sheet` needs of the rules, in mm (and the taper in radians)."""

    tab_width: float
    tab_length: float
    taper: float
    label_size: float


def _outline_segments(loc: LocalSheet, pieces_of: dict[int, list[np.ndarray]]) -> np.ndarray:
    """Segments (S, 2, 2) of a sheet's outline loops, tabbed seams split where their tab pieces
    meet."""
    segs = []
    for li, (verts, _) in enumerate(loc.loops):
        n = len(verts)
        keep = np.ones(n, bool)
        for ch in loc.chains:
            if ch.loop == li and id(ch) in pieces_of:
                keep[(ch.start + np.arange(ch.count)) % n] = False
        p = loc.xy[verts]
        segs.append(np.stack([p, np.roll(p, -1, axis=0)], axis=1)[keep])
    segs += [
        polyline_segments([(piece, False)]) for pieces in pieces_of.values() for piece in pieces
    ]
    return np.concatenate(segs)


def build_sheet(
    sheet: PatternSheet, loc: LocalSheet, tabbed: set[int], rules: SheetRules, notes: list[str]
) -> tuple[list[tuple[str, np.ndarray, bool, int]], np.ndarray, list[Label], bool]:
    """The lines of one sheet in its local mm frame, as :class:`Polyline`'s fields (layer, points,
    closed, seam), all their points (its footprint), its labels and whether it is mirrored."""
    tab_width, tab_length, taper = rules.tab_width, rules.tab_length, rules.taper
    label_size = rules.label_size
    name = sheet.label
    pieces_of = {
        id(ch): tab_pieces(ch.points, tab_length, 2.5 * tab_width)
        for ch in loc.chains
        if id(ch) in tabbed
    }
    outline = _outline_segments(loc, pieces_of)
    # coordinate rounding, mm
    tol = 1e-9 * max(float(np.ptp(bounding_box(loc.xy), axis=0).max()), 1.0)
    # per loop: position of first edge -> (count of edges, replacement points without the last)
    replace: dict[tuple[int, int], tuple[int, np.ndarray]] = {}
    lines: list[tuple[str, np.ndarray, bool, int]] = []
    tabbed_chains = [ch for ch in loc.chains if id(ch) in pieces_of]
    placed = iter(
        place_tabs(
            [piece for ch in tabbed_chains for piece in pieces_of[id(ch)]],
            outline,
            tab_width,
            taper,
            tol,
        )
    )
    for ch in tabbed_chains:
        pieces = pieces_of[id(ch)]
        cut_parts, dropped, narrowed = [], 0, 0
        runs: list[list[np.ndarray]] = [[]]  # consecutive tabbed pieces: one fold line each
        for piece in pieces:
            got = next(placed)
            if got is None:
                dropped += 1
                cut_parts.append(piece[:-1])
                runs.append([])
                continue
            (polygon, cut), step = got
            narrowed += step > 0
            lines.append(("glue", polygon, True, ch.seam))
            cut_parts.append(cut[:-1])
            runs[-1].append(piece)
        for run in runs:
            if run:
                line = np.concatenate([p[:-1] for p in run] + [run[-1][-1:]])
                lines.append(("seam", line, False, ch.seam))
        replace[(ch.loop, ch.start)] = (ch.count, np.concatenate(cut_parts))
        if narrowed or dropped:
            notes.append(
                f"sheet {name!r}, seam {seam_name(ch.seam)}: {narrowed} glue tab "
                f"piece(s) narrowed, {dropped} left out (of {len(pieces)}) to keep clear of "
                "the sheet"
            )

    for li, (verts, _) in enumerate(loc.loops):
        n = len(verts)
        replaced = sorted((pos, *replace[(l2, pos)]) for (l2, pos) in replace if l2 == li)
        if not replaced:
            lines.append(("cut", loc.xy[verts], True, -1))
            continue
        parts = []  # from the first replaced run, so no run wraps around the walk's end
        for k, (pos, count, pts) in enumerate(replaced):
            # the next run's start
            until = replaced[k + 1][0] if k + 1 < len(replaced) else replaced[0][0] + n
            parts += [pts, loc.xy[verts[np.arange(pos + count, until) % n]]]
        lines.append(("cut", np.concatenate(parts), True, -1))
    lines.extend(loc.creases)

    # Labels: seam names first (each then becomes an obstacle), then the sheet label.
    obstacle_lines = [
        (points, closed)
        for layer, points, closed, _ in lines
        if layer in ("cut", "seam", "mountain", "valley")
    ]
    segments = polyline_segments(obstacle_lines)
    obstacles = Obstacles(segments, 0.1 * MIN_LABEL_SIZE)
    labels: list[Label] = []
    for ch in loc.chains:
        lab, ok = seam_label(ch.points, ch.seam, obstacles, 0.8 * label_size)
        if not ok:
            notes.append(
                f"sheet {name!r}: seam name {lab.text} could not be kept clear of the lines"
            )
        labels.append(lab)
        obstacles = obstacles.plus(polyline_segments([(lab.corners(), True)]))
    tri = loc.xy[sheet.mesh.triangulated().faces_vertices]
    areas = 0.5 * np.abs(cross2(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]))
    lab, ok = sheet_label(name, tri.mean(axis=1), areas, obstacles, label_size)
    if not ok:
        notes.append(f"sheet {name!r}: its label could not be kept clear of the lines")
    if name:
        labels.append(lab)
    return lines, np.concatenate([points for _, points, _, _ in lines]), labels, loc.mirror
