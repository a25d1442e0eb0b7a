"""The crease pattern as one DXF drawing in millimetres, with ezdxf (imported when called).

Every layer of the layout is a DXF layer named by its operation
(:func:`~curvefold.io._cutters.layer_name`) with the colour the layout's cutter gives it
(true colour, and the nearest AutoCAD colour index for readers that ignore true colour),
its linetype (patterns in mm) and lineweight. Lines are ``LWPOLYLINE`` entities with the
linetype-generation flag set, so a dash pattern runs on across their vertices (CAD programs
otherwise restart it at every vertex, and segments shorter than a dash then draw solid).
Readers that restart it all the same (LibreCAD 2.2 does, flag or not) still show the dashes:
a dashed crease is written as circular arcs (bulges) through its points, each as long as the
crease's curvature allows within :data:`ARC_TOLERANCE` (:func:`~curvefold.io._planar.fit_arcs`),
rather than as its chords of a couple of millimetres. Glue areas are solid ``HATCH``
entities; labels ``TEXT`` (height = cap height, centred).
Pages lie in a grid (:func:`page_grid`), each framed on layer ``pages``, with its footer on
the legend layer; neither layer plots. ``$EXTMIN``/``$EXTMAX`` hold every page, set in the
header of every file, and the initial view shows them all.
"""

from __future__ import annotations

import math
import os
from collections.abc import Collection
from pathlib import Path

import numpy as np

from ..kernel._errors import InputError
from ..kernel._text import one_line
from ._atomic import atomic_path
from ._cutters import LEGEND_LAYER, aci
from ._layout import Layout
from ._legend import check_layers, check_layout, layer_look, page_footer
from ._planar import fit_arcs
from ._tables import rgb8

__all__ = ["page_grid", "write_dxf"]

# Cap height of a font as a fraction of its em height (DXF TEXT heights are cap heights).
_CAP_HEIGHT = 0.72
#: Layer of the page frames.
PAGES_LAYER = "pages"
#: Largest distance (mm) of a dashed crease's points from the arcs it is written as.
ARC_TOLERANCE = 0.005


def page_grid(count: int, size: tuple[float, float], spacing: float) -> np.ndarray:
    """Lower-left corners (count, 2) of pages laid in a grid of ⌈√count⌉ columns, row by row from
    the top.

    Examples
    --------
    >>> page_grid(3, (210.0, 297.0), 20.0).tolist()
    [[0.0, 0.0], [230.0, 0.0], [0.0, -317.0]]
    """
    columns = math.ceil(math.sqrt(count))
    i = np.arange(count)
    return np.stack(
        [(i % columns) * (size[0] + spacing), -(i // columns) * (size[1] + spacing)], axis=1
    ).astype(float)


def write_dxf(
    path: str | os.PathLike,
    layout: Layout,
    *,
    layers: Collection[str] | None = None,
    page_spacing: float = 20.0,
) -> Path:
    """Write the layout as one DXF drawing in millimetres (needs ``ezdxf``); see the module notes.

    Parameters
    ----------
    path : path-like
    layout : Layout
    layers : collection of str, optional
        Layout layers to write; default :data:`~curvefold.io._legend.DEFAULT_LAYERS` (all but
        ``rulings``).
    page_spacing : float
        Gap between pages, mm.

    Returns
    -------
    Path
    """
    check_layout(layout)
    names = check_layers(layers)
    if not (
        isinstance(page_spacing, (int, float)) and math.isfinite(page_spacing) and page_spacing >= 0
    ):
        raise InputError(f"page_spacing must be a non-negative number of mm, got {page_spacing!r}")
    try:
        import ezdxf
        from ezdxf import colors
        from ezdxf.enums import TextEntityAlignment
        from ezdxf.lldxf.const import LWPOLYLINE_PLINEGEN
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("write_dxf needs ezdxf: pip install 'ezdxf>=1.1,<2'") from exc

    doc = ezdxf.new("R2010", units=4)
    doc.header["$INSUNITS"] = 4
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LTSCALE"] = 1.0
    doc.header["$PLINEGEN"] = 1  # new polylines too generate their linetype across vertices
    looks = {name: layer_look(layout, name) for name in (*names, "legend")}
    for key, (layer, colour, st) in looks.items():
        if st.dashes and st.linetype not in doc.linetypes:
            pattern = [float(sum(st.dashes))] + [
                d if k % 2 == 0 else -d for k, d in enumerate(st.dashes)
            ]
            doc.linetypes.add(
                st.linetype,
                pattern,
                description=f"curvefold {key} " + " ".join(f"{d:g}" for d in st.dashes),
            )
        entry = doc.layers.add(
            layer,
            color=aci(colour),
            true_color=colors.rgb2int(rgb8(colour)),
            linetype=st.linetype if st.dashes else "CONTINUOUS",
            lineweight=13 if st.width < 1 else 25,
        )
        if key == "legend":
            entry.dxf.plot = 0
    doc.layers.add(PAGES_LAYER, color=8).dxf.plot = 0
    msp = doc.modelspace()

    def inked(layer: str, colour: str | None) -> dict:
        """An entity's attributes: its layer, and a colour of its own when given."""
        own = (
            {}
            if colour is None
            else {"color": aci(colour), "true_color": colors.rgb2int(rgb8(colour))}
        )
        return {"layer": layer} | own

    def text(
        words: str, position, size: float, angle: float, layer: str, colour: str | None = None
    ) -> None:
        entity = msp.add_text(
            words, height=_CAP_HEIGHT * size, rotation=angle, dxfattribs=inked(layer, colour)
        )
        entity.set_placement(
            tuple(float(v) for v in position), align=TextEntityAlignment.MIDDLE_CENTER
        )

    def line(
        points: np.ndarray,
        layer: str,
        closed: bool = False,
        arcs: bool = False,
        linetype: str | None = None,
        colour: str | None = None,
    ) -> None:
        rows = np.zeros((len(points), 5))  # x, y, start width, end width, bulge: ezdxf's vertices
        rows[:, :2] = points
        if arcs and not closed and len(points) > 2:
            keep, bulge = fit_arcs(points, ARC_TOLERANCE)
            rows = rows[keep]
            rows[:, 4] = bulge
        attributes = (
            inked(layer, colour)
            | {"flags": LWPOLYLINE_PLINEGEN}
            | ({"linetype": linetype} if linetype else {})
        )
        # the vertices at once
        msp.add_lwpolyline((), close=closed, dxfattribs=attributes).lwpoints.set(rows)

    W, H = layout.page_size
    corners = page_grid(len(layout.pages), (W, H), page_spacing)
    legend = LEGEND_LAYER
    for i, (page, shift) in enumerate(zip(layout.pages, corners)):
        line(
            np.array([shift, shift + (W, 0), shift + (W, H), shift + (0, H)]),
            PAGES_LAYER,
            closed=True,
        )
        for key in names:
            layer, _, st = looks[key]
            if key == "labels":
                for t in page.labels():
                    text(one_line(t.text), np.asarray(t.position) + shift, t.size, t.angle, layer)
                continue
            for p in page.on_layer(key):
                if st.fill and p.closed:
                    msp.add_hatch(color=256, dxfattribs={"layer": layer}).paths.add_polyline_path(
                        (p.points + shift).tolist(), is_closed=True
                    )
                else:
                    line(p.points + shift, layer, p.closed, arcs=bool(st.dashes))
        footer = page_footer(layout, i, names)
        msp.add_hatch(color=256, dxfattribs={"layer": legend}).paths.add_polyline_path(
            (footer.bar + shift).tolist(), is_closed=True
        )
        for (key, points), ink in zip(footer.samples, footer.inks):
            if looks[key][2].fill:
                hatch = msp.add_hatch(color=aci(ink), dxfattribs=inked(legend, ink))
                hatch.paths.add_polyline_path((points + shift).tolist(), is_closed=True)
            else:
                line(
                    points + shift,
                    legend,
                    linetype=looks[key][2].linetype if looks[key][2].dashes else "CONTINUOUS",
                    colour=ink,
                )
        for t, ink in zip(footer.texts, footer.text_inks):
            own = None if ink == footer.colour else ink
            text(t.text, np.asarray(t.position) + shift, t.size, 0.0, legend, own)
    lo, hi = corners.min(axis=0), corners.max(axis=0) + (W, H)
    # ezdxf copies the modelspace's extents into the header only when they do not start at
    # (0, 0, 0), as a single row of pages does: set the header itself.
    doc.header["$EXTMIN"] = (float(lo[0]), float(lo[1]), 0.0)
    doc.header["$EXTMAX"] = (float(hi[0]), float(hi[1]), 0.0)
    msp.dxf.extmin, msp.dxf.extmax = doc.header["$EXTMIN"], doc.header["$EXTMAX"]
    doc.set_modelspace_vport(
        height=float(hi[1] - lo[1]) * 1.05, center=tuple(float(v) for v in 0.5 * (lo + hi))
    )
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
    return Path(path)
