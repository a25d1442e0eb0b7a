"""Scenes drawn by NumPy alone: views, shaded strips, creases by kind, the ground, and SVG.

A scene is what a painter's renderer leaves: screen polygons sorted far to near, each with
its role and colours. It needs nothing but NumPy, so previews can be drawn where
matplotlib is not installed; :meth:`Scene.svg` writes a scene as a plain SVG document and
:mod:`curvefold.figures._plots` draws the same scenes into matplotlib figures.

A view is orthographic, z up. The strips of every tube are quadrilaterals shaded
two-sidedly by their normal under a fixed light; the crease curves and the end rulings of
the strips are line segments, each drawn right after the nearest strip that borders it,
so that whatever lies in front of that strip hides it too. Screen coordinates are in model
units (the unit of the design's radius), x to the right, y up. The colours of the crease
kinds are the caller's (:data:`curvefold.figures._plot_data.KIND_COLORS` for the figures).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING, Literal

import numpy as np

from ..geometry._structure import drawable
from ..geometry._topology import tube_strips
from ..io._planar import bounding_box
from ..io._tables import rgb8
from ..kernel._arrays import frozen, readonly
from ..kernel._errors import InputError
from ..kernel._validate import check_integer

if TYPE_CHECKING:  # pragma: no cover
    from ..geometry._structure import State, Structure
    from ..vault._assembly import Vault

__all__ = [
    "View",
    "Scene",
    "STRIP_RGB",
    "GROUND_COLOR",
    "GROUND_EDGE",
    "RIM_COLOR",
    "rgba",
    "strip_quads",
    "shade",
    "render_strips",
    "render_structure",
    "ground_polygon",
    "vault_scene",
    "state_scene",
    "motion_scenes",
]


#: Base colour of the strips before shading, RGB in [0, 1].
STRIP_RGB = readonly(np.array([0.86, 0.86, 0.85]))
#: Fill and outline of the ground plane z = 0.
GROUND_COLOR, GROUND_EDGE = "#ece6da", "#b9ae98"
#: Colour of the end rulings of the strips.
RIM_COLOR = "#3a3a3a"


def rgba(color: str) -> np.ndarray:
    """RGBA in [0, 1], shape (4,), of a colour written ``"#rrggbb"``.

    Examples
    --------
    >>> rgba("#ff8000").tolist()
    [1.0, 0.5019607843137255, 0.0, 1.0]
    """
    return np.array([*(c / 255 for c in rgb8(color)), 1.0])


def _hex(color: np.ndarray) -> str:
    """``"#rrggbb"`` of an RGB(A) colour in [0, 1]."""
    r, g, b = (int(round(255 * float(c))) for c in np.clip(color[:3], 0.0, 1.0))
    return f"#{r:02x}{g:02x}{b:02x}"


# -- a fixed orthographic view -----------------------------------------------------------------


@dataclass(frozen=True)
class View:
    """An orthographic view direction, z up.

    Attributes
    ----------
    azim : float
        Azimuth of the viewer in degrees, from +x toward +y (matplotlib's convention).
    elev : float
        Elevation of the viewer above the xy plane in degrees.
    """

    azim: float = -50.0
    elev: float = 22.0

    @cached_property
    def basis(self) -> np.ndarray:
        """Rows: screen right, screen up, toward the viewer; shape (3, 3), orthonormal,
        read-only."""
        az, el = np.radians(self.azim), np.radians(self.elev)
        toward = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
        right = np.array([-np.sin(az), np.cos(az), 0.0])
        return readonly(np.stack([right, np.cross(toward, right), toward]))

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Screen coordinates (..., 2) and depth (...,) of points (..., 3); larger depth is
        nearer."""
        q = np.asarray(points, float) @ self.basis.T
        return q[..., :2], q[..., 2]


# -- drawables ---------------------------------------------------------------------------------


def strip_quads(vertices: np.ndarray, strips: np.ndarray) -> np.ndarray:
    """Ruled strips between pairs of curves as quadrilaterals, shape (S·(n−1), 4, 3).

    Parameters
    ----------
    vertices : (M, n, 3) ndarray
        Curves sampled at common parameters (lattice curves, or a crease and its edges).
    strips : (S, 2) ndarray of int
        Rows of ``vertices`` bounding every strip (see
        :func:`~curvefold.geometry._topology.tube_strips`).
    """
    pairs = np.asarray(strips)
    a, b = vertices[pairs[:, 0]], vertices[pairs[:, 1]]  # (S, n, 3)
    quads = np.stack([a[:, :-1], a[:, 1:], b[:, 1:], b[:, :-1]], axis=-2)
    return quads.reshape(-1, 4, 3)


def shade(quads: np.ndarray, view: View, base: np.ndarray | None = None) -> np.ndarray:
    """RGBA colours (Q, 4) of quads (Q, 4, 3) shaded two-sidedly by their normals under a fixed
    light, from their base colours ``base`` (Q, 3) in [0, 1] (default :data:`STRIP_RGB`)."""
    normal = np.cross(quads[:, 2] - quads[:, 0], quads[:, 3] - quads[:, 1])
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = normal / np.where(length > 0, length, 1.0)
    light = np.array([-0.45, 0.6, 0.66]) @ view.basis  # from the upper left, in front
    light /= np.linalg.norm(light)
    lambert = np.abs(normal @ light)
    rgb = (STRIP_RGB[None] if base is None else np.asarray(base, float)) * (
        0.38 + 0.66 * lambert[:, None]
    )
    return np.concatenate([np.clip(rgb, 0, 1), np.ones((len(quads), 1))], axis=1)


@dataclass(frozen=True, eq=False)
class Scene:
    """Screen polygons of one view in painter's order (far to near), with their colours.

    Attributes
    ----------
    paths : sequence of (p, 2) ndarray
        Read-only screen polygons in model units: strips (p = 4, filled and outlined in their own
        colour) and segments of the creases and of the strips' end rulings (p = 2, stroked).
    roles : (P,) ndarray of str
        What each path is: ``"strip"``, the kind of the crease it belongs to (``"fold"``,
        ``"seam"``, ``"junction"``, ``"edge"``) or ``"rim"`` for an end ruling.
    fill, stroke : (P, 4) ndarray
        RGBA colours in [0, 1]; segments have a transparent fill.
    widths : (P,) ndarray
        Stroke widths in points.
    span : float
        Largest side of the 3D bounding box of the drawn curves, model units (for scale bars).
    ground : (4, 2) ndarray or None
        The ground plane z = 0 on screen, drawn below everything, or None.
    """

    paths: Sequence[np.ndarray]
    roles: np.ndarray
    fill: np.ndarray
    stroke: np.ndarray
    widths: np.ndarray
    span: float
    ground: np.ndarray | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "paths", _frozen_paths(self.paths))
        for name in ("roles", "fill", "stroke", "widths"):
            object.__setattr__(self, name, frozen(getattr(self, name)))
        if self.ground is not None:
            object.__setattr__(self, "ground", frozen(np.asarray(self.ground, float)))

    @property
    def flat(self) -> tuple[np.ndarray, np.ndarray]:
        """Every path's points one after the other, shape (N, 2), and the number of points of
        each path (P,)."""
        if isinstance(self.paths, _HeldPaths):
            return self.paths.points, self.paths.sizes
        sizes = np.fromiter(map(len, self.paths), int, len(self.paths))
        return (np.concatenate(self.paths) if self.paths else np.zeros((0, 2))), sizes

    @property
    def strips(self) -> np.ndarray:
        """Screen corners of the strips, shape (Q, 4, 2), in painter's order."""
        points, sizes = self.flat
        return np.compress(np.repeat(self.roles == "strip", sizes), points, axis=0).reshape(
            -1, 4, 2
        )

    @property
    def box(self) -> np.ndarray:
        """Screen box ``[[xmin, ymin], [xmax, ymax]]`` of the strips and the ground, shape (2,
        2)."""
        return bounding_box(
            np.concatenate(
                [self.strips.reshape(-1, 2)] + ([self.ground] if self.ground is not None else [])
            )
        )

    def svg(self, *, pixels: int = 800, margin: float = 0.02) -> str:
        """The scene as a standalone SVG document.

        Its viewBox is the scene's :attr:`box` grown by ``margin`` of its larger side, in
        screen model units with y turned down (SVG's convention); it is ``pixels`` wide.
        Strips and the ground are ``<polygon>`` elements, segments ``<line>`` elements, in
        painter's order, each with its role as its class. The text depends only on the scene.

        Parameters
        ----------
        pixels : int, keyword-only
            Width of the picture in CSS pixels, in [16, 16384]; stroke widths (points) are
            scaled to it.
        margin : float, keyword-only
            Free border, as a fraction of the box's larger side, in [0, 1].
        """
        pixels = check_integer(pixels, "pixels", "[16, 16384]")
        if not np.isfinite(margin) or not 0 <= margin <= 1:
            raise InputError(f"margin must be in [0, 1], got {margin!r}")
        lo, hi = self.box
        pad = margin * float(np.max(hi - lo))
        lo, size = lo - pad, np.maximum(hi - lo + 2 * pad, 1e-12)
        unit = size[0] / pixels * 96 / 72  # one point in model units
        lines = [
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{pixels}" '
            f'height="{_num(pixels * size[1] / size[0])}" viewBox="{_num(lo[0])} '
            f'{_num(-(lo[1] + size[1]))} {_num(size[0])} {_num(size[1])}">',
            '<g stroke-linejoin="round" stroke-linecap="round">',
        ]
        if self.ground is not None:
            lines.append(
                f'<polygon class="ground" points="{_points(self.ground)}" '
                f'fill="{GROUND_COLOR}" stroke="{GROUND_EDGE}" '
                f'stroke-width="{_num(0.6 * unit)}"/>'
            )
        for path, role, fill, stroke, width in zip(
            self.paths, self.roles, self.fill, self.stroke, self.widths
        ):
            paint = f'stroke="{_hex(stroke)}" stroke-width="{_num(width * unit)}"'
            if len(path) == 2:
                (x1, y1), (x2, y2) = path
                lines.append(
                    f'<line class="{role}" x1="{_num(x1)}" y1="{_num(-y1)}" '
                    f'x2="{_num(x2)}" y2="{_num(-y2)}" {paint}/>'
                )
            else:
                lines.append(
                    f'<polygon class="{role}" points="{_points(path)}" '
                    f'fill="{_hex(fill)}" {paint}/>'
                )
        lines += ["</g>", "</svg>", ""]
        return "\n".join(lines)


class _HeldPaths(Sequence):
    """Paths held as one read-only array of their points (built by :func:`render_strips`): a
    scene draws from :attr:`points` and :attr:`sizes` at once, and makes the read-only views
    of its thousands of paths only when they are asked for (once)."""

    def __init__(self, points: np.ndarray, sizes: np.ndarray) -> None:
        self.points, self.sizes = points, sizes

    @classmethod
    def ordered(cls, groups: Sequence[np.ndarray], order: np.ndarray) -> _HeldPaths:
        """The paths of ``groups`` (each (G, p, 2), read-only), one after the other, taken in
        ``order``."""
        sizes = np.concatenate([np.full(len(group), group.shape[1]) for group in groups])
        first = (np.cumsum(sizes) - sizes)[order]  # of every path, in the groups' points
        held_sizes = sizes[order]
        gather = np.repeat(first - (np.cumsum(held_sizes) - held_sizes), held_sizes) + np.arange(
            int(held_sizes.sum())
        )
        return cls(
            readonly(
                np.take(np.concatenate([group.reshape(-1, 2) for group in groups]), gather, axis=0)
            ),
            readonly(held_sizes),
        )

    @cached_property
    def _views(self) -> tuple[np.ndarray, ...]:
        ends = np.cumsum(self.sizes).tolist()
        return tuple(map(self.points.__getitem__, map(slice, [0] + ends[:-1], ends)))

    def __len__(self) -> int:
        return len(self.sizes)

    def __getitem__(self, index):
        return self._views[index]

    def __iter__(self):
        return iter(self._views)


def _frozen_paths(paths: Sequence[np.ndarray]) -> Sequence[np.ndarray]:
    """Every path :func:`~curvefold.kernel._arrays.frozen`, as floats (:class:`_HeldPaths` as
    they are)."""
    return (
        paths
        if isinstance(paths, _HeldPaths)
        else tuple(frozen(np.asarray(p, float)) for p in paths)
    )


def _num(v: float) -> str:
    """A number for SVG: 7 significant digits, never "-0"."""
    return f"{float(v) + 0.0:.7g}"


def _points(path: np.ndarray) -> str:
    return " ".join(f"{_num(x)},{_num(-y)}" for x, y in path)


def render_strips(
    vertices: np.ndarray,
    strips: np.ndarray,
    kinds: Sequence[str],
    view: View,
    *,
    colors: Mapping[str, str],
    crease_width: float = 1.1,
    strip_edge: float = 0.3,
    strip_rgb: np.ndarray | None = None,
) -> Scene:
    """Shaded strips, their curves and end rulings in one view, sorted by depth.

    Parameters
    ----------
    vertices : (M, k, 3) ndarray
        Curves, already subsampled along t.
    strips : (S, 2) ndarray of int
        Rows of ``vertices`` bounding every strip (see
        :func:`~curvefold.geometry._topology.tube_strips`).
    kinds : sequence of str, length M
        Kind of every curve ("fold", "seam", "junction", "edge").
    view : View
    colors : mapping of str to str, keyword-only
        Line colour ``"#rrggbb"`` of every kind; a kind without one is drawn in the colour of
        "edge".
    crease_width : float, keyword-only
        Line width of the curves in points (end rulings get half of it); 0 draws strips only.
    strip_edge : float, keyword-only
        Width of the strips' outline in their own colour (hides hairline gaps), points.
    strip_rgb : (S, 3) or (S, k − 1, 3) array_like, optional, keyword-only
        Base colour of every strip, or of every quad of every strip, before shading, RGB in
        [0, 1] (to pick some out, or to colour a field); default :data:`STRIP_RGB` for all.

    Returns
    -------
    Scene
        Without ground.
    """
    pairs = np.asarray(strips)
    quads = strip_quads(vertices, pairs)
    q2, qd = view.project(quads)
    base = (
        None
        if strip_rgb is None
        else np.broadcast_to(
            np.asarray(strip_rgb, float).reshape(len(pairs), -1, 3),
            (len(pairs), vertices.shape[1] - 1, 3),
        ).reshape(-1, 3)
    )
    face = shade(quads, view, base)
    strip_depth = qd.mean(axis=1)
    paths = [q2]
    depth = [strip_depth]
    roles = [np.full(len(q2), "strip")]
    fills, strokes, widths = [face], [face], [np.full(len(q2), strip_edge)]
    if crease_width > 0:
        # Curves and end rulings are drawn right after the nearest strip that borders them.
        per_strip = strip_depth.reshape(len(pairs), -1)  # (S, k − 1)
        eps = 1e-9 * (1.0 + float(np.abs(qd).max()))
        # the curves of the strips, in order
        used = np.flatnonzero(np.bincount(pairs.ravel(), minlength=len(vertices)))
        seg = np.stack([vertices[used, :-1], vertices[used, 1:]], axis=-2).reshape(-1, 2, 3)
        s2, _ = view.project(seg)
        used_kinds = np.asarray(kinds)[used]
        # a few kinds, many curves
        kind_rgba = {k: _kind_color(colors, k) for k in dict.fromkeys(used_kinds.tolist())}
        per_curve = np.array([kind_rgba[k] for k in used_kinds.tolist()]).reshape(-1, 4)
        # of the strips bordering each curve, per segment
        nearest = np.full((len(vertices), per_strip.shape[1]), -np.inf)
        np.maximum.at(nearest, pairs[:, 0], per_strip)
        np.maximum.at(nearest, pairs[:, 1], per_strip)
        seg_depth = nearest[used].reshape(-1) + eps
        # end rulings of every strip
        rim = np.swapaxes(vertices[pairs][:, :, [0, -1]], 1, 2).reshape(-1, 2, 3)
        e2, _ = view.project(rim)
        paths += [s2, e2]
        depth += [seg_depth, per_strip[:, [0, -1]].reshape(-1) + eps]
        roles += [np.repeat(used_kinds, vertices.shape[1] - 1), np.full(len(e2), "rim")]
        fills += [np.zeros((len(s2) + len(e2), 4))]
        strokes += [
            np.repeat(per_curve, vertices.shape[1] - 1, axis=0),
            np.tile(rgba(RIM_COLOR), (len(e2), 1)),
        ]
        widths += [np.full(len(s2), crease_width), np.full(len(e2), 0.5 * crease_width)]
    order = np.argsort(np.concatenate(depth), kind="stable")
    lo, hi = bounding_box(vertices)
    return Scene(
        _HeldPaths.ordered([readonly(np.asarray(group, float)) for group in paths], order),
        np.concatenate(roles)[order],
        # (rows gathered by np.take: NumPy's indexing is slower)
        np.take(np.concatenate(fills), order, axis=0),
        np.take(np.concatenate(strokes), order, axis=0),
        np.concatenate(widths)[order],
        float((hi - lo).max()),
    )


def _kind_color(colors: Mapping[str, str], kind: str) -> np.ndarray:
    color = colors.get(kind, colors.get("edge"))
    if color is None:
        raise InputError(
            f"colors must give a colour for the crease kind {str(kind)!r} or for "
            f"'edge', got one for {sorted(colors)}"
        )
    return rgba(color)


def render_structure(
    vertices: np.ndarray, cell_curves: np.ndarray, kinds: Sequence[str], view: View, **kwargs
) -> Scene:
    """:func:`render_strips` of the four strips of every tube (cell_curves (K, 4))."""
    return render_strips(vertices, tube_strips(cell_curves), kinds, view, **kwargs)


def ground_polygon(lo: np.ndarray, hi: np.ndarray, view: View, *, pad: float) -> np.ndarray:
    """Screen corners (4, 2) of the ground plane z = 0 over the xy box [lo, hi] grown by ``pad``."""
    x0, y0 = lo[:2] - pad
    x1, y1 = hi[:2] + pad
    rect = np.array([[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]])
    return view.project(rect)[0]


# -- whole scenes --------------------------------------------------------------------------------


def vault_scene(
    vault: Vault,
    *,
    colors: Mapping[str, str],
    angle: float | None = None,
    view: View = View(),
    anchor: Literal["start", "middle"] = "start",
    segments: int = 96,
    max_tubes: int = 200,
) -> Scene:
    """A vault over the ground plane in one view.

    Parameters
    ----------
    vault : Vault
    colors : mapping of str to str, keyword-only
        Line colour ``"#rrggbb"`` of every crease kind (see :func:`render_strips`).
    angle : float, optional, keyword-only
        Fold angle 2α in degrees; default the design angle (standing on the ground).
    view : View, keyword-only
    anchor : {"start", "middle"}, keyword-only
        Which frame stays fixed when ``angle`` differs from the design angle.
    segments : int, keyword-only
        Segments drawn along each crease (the crease is subsampled; ends and apex kept).
    max_tubes : int, keyword-only
        Draw at most this many tubes, evenly spread along the stack.

    Returns
    -------
    Scene
        With the ground under the vault's box, grown by 8 % of its largest side.
    """
    vertices = (
        vault.vertices
        if angle is None
        else vault.motion(np.array([angle], float), anchor=anchor)[0]
    )
    V, cells, kinds = drawable(vault.structure, vertices, segments=segments, max_cells=max_tubes)
    lo, hi = bounding_box(V)
    ground = ground_polygon(lo, hi, view, pad=0.08 * float(np.max(hi - lo)))
    return replace(render_structure(V, cells, kinds, view, colors=colors), ground=ground)


def state_scene(
    state: State,
    *,
    colors: Mapping[str, str],
    view: View = View(),
    segments: int = 96,
    max_cells: int = 400,
) -> Scene:
    """A tube or cellular block at one fold angle in one view, without ground.

    Parameters
    ----------
    state : State
        The structure at a fold angle (:meth:`~curvefold.geometry.Structure.state`).
    colors : mapping of str to str, keyword-only
        Line colour ``"#rrggbb"`` of every crease kind (see :func:`render_strips`).
    view : View, keyword-only
    segments : int, keyword-only
        Segments drawn along each crease.
    max_cells : int, keyword-only
        Draw at most this many cells, evenly spread.
    """
    V, cells, kinds = drawable(
        state.structure, state.vertices, segments=segments, max_cells=max_cells
    )
    return render_structure(V, cells, kinds, view, colors=colors)


def motion_scenes(
    structure: Structure,
    motion: np.ndarray,
    *,
    colors: Mapping[str, str],
    view: View = View(),
    segments: int = 64,
    max_cells: int = 100,
    crease_width: float = 1.1,
    ground: bool = True,
) -> tuple[Scene, ...]:
    """A folding motion as scenes at one scale, one per fold angle.

    Parameters
    ----------
    structure : Structure
    motion : (A, M, n, 3) ndarray
        Its curves (rows of ``structure.curves_uv``) at A fold angles.
    colors : mapping of str to str, keyword-only
        Line colour ``"#rrggbb"`` of every crease kind (see :func:`render_strips`).
    view : View, keyword-only
    segments : int, keyword-only
        Segments drawn along each crease.
    max_cells : int, keyword-only
        Draw at most this many cells, evenly spread.
    crease_width : float, keyword-only
        Line width of the creases in points.
    ground : bool, keyword-only
        Put one ground plane z = 0 under all of them: under the xy box of every frame,
        grown by 6 % of its larger side.

    Returns
    -------
    tuple of Scene
        One per fold angle, each with the largest :attr:`Scene.span` of them all.
    """
    V, cells, kinds = drawable(structure, motion, segments=segments, max_cells=max_cells)
    lo, hi = bounding_box(V)
    floor = (
        ground_polygon(lo, hi, view, pad=0.06 * float(np.max((hi - lo)[:2]))) if ground else None
    )
    span = float(np.max(hi - lo))
    return tuple(
        replace(
            render_structure(Vf, cells, kinds, view, colors=colors, crease_width=crease_width),
            ground=floor,
            span=span,
        )
        for Vf in V
    )
