"""Files of thick panels (:class:`~curvefold.geometry.ThickPanels`): the solids as a watertight
binary STL and as closed polysurfaces in a Rhino 3dm, and the cut list as JSON, CSV and a
printable PDF (a row per panel: its sketch, edge lengths, bevels and hinges).

The STL holds every solid closed on its own (each edge of its triangles shared by two of them,
once each way), counter-clockwise seen from outside, so slicers and CAD tools read volumes.
The 3dm holds every solid as a closed Brep (rhino3dm's from its closed mesh: Rhino reads it
as a solid), named by its panel's label, with its bevels as user text.
"""

from __future__ import annotations

import csv
import io
import json
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..geometry._thick import ThickPanels
from ..kernel._errors import InputError
from ..kernel._text import one_line
from ._atomic import atomic_path, atomic_write
from ._mesh3d import stl_records
from ._tables import CREATOR, UNITS

if TYPE_CHECKING:  # pragma: no cover
    from ._pdf import PdfDocument

__all__ = [
    "write_thick_stl",
    "write_cut_list",
    "write_cut_list_csv",
    "write_cut_list_pdf",
    "write_thick_3dm",
    "cut_list_pages",
]


def write_thick_stl(
    path: str | os.PathLike,
    thick: ThickPanels,
    fold_angle: float | None = None,
    *,
    unit: str = "unit",
    to_unit: str | None = None,
) -> Path:
    """Write the solids at a fold angle (default the design angle) as a binary STL.

    Parameters
    ----------
    unit, to_unit : str
        Length units of the model and of the file (:func:`curvefold.io.write_stl`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> with tempfile.TemporaryDirectory() as d:
    ...     size = (
    ...         write_thick_stl(pathlib.Path(d) / "solids.stl", thick, to_unit="mm").stat().st_size
    ...     )
    >>> size == 84 + 50 * 192  # header, count and 12 triangles of 16 solids
    True
    """
    to_unit = unit if to_unit is None else to_unit
    for name, value in (("unit", unit), ("to_unit", to_unit)):
        if value not in UNITS:
            raise InputError(
                f"{name} must be one of {', '.join(UNITS)}, got {value!r}", parameter="units"
            )
    x, triangles = thick.triangles(fold_angle)
    x = x * (UNITS[unit].metres / UNITS[to_unit].metres)
    words = "model units (1 model unit = 1 m)" if to_unit == "unit" else to_unit
    text = f"{CREATOR}, thick panels t = {thick.thickness:g} {unit}, unit {words}"
    header = one_line(text).encode("ascii", "replace")[:80].ljust(80, b" ")
    return atomic_write(path, header + stl_records(x, triangles))


def write_cut_list(path: str | os.PathLike, thick: ThickPanels) -> Path:
    """Write the cut list (:meth:`~curvefold.geometry.ThickPanels.cut_list`) as JSON.

    Examples
    --------
    >>> import tempfile, pathlib, json
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> with tempfile.TemporaryDirectory() as d:
    ...     rows = json.loads(write_cut_list(pathlib.Path(d) / "cut.json", thick).read_text())
    >>> len(rows["panels"]), rows["panels"][0]["panel"]
    (16, 'tube 1 · sheet A · strip 4 · panel 1')
    """
    body = {
        "creator": CREATOR,
        "technique": f"{thick.technique}: hinges on the zero-thickness creases",
        "thickness": thick.thickness,
        "bevels_for_fold_angles": list(thick.reach),
        "panels": list(thick.cut_list()),
    }
    return atomic_write(path, json.dumps(body, indent=1, ensure_ascii=False).encode("utf-8"))


def write_cut_list_csv(
    path: str | os.PathLike, thick: ThickPanels, *, unit: str = "unit", to_unit: str = "mm"
) -> Path:
    """Write the cut list as CSV, a row per panel edge, the panels in the order of assembly
    (:attr:`~curvefold.geometry.ThickPanels.order`): the panel's id, the edge (1 to k,
    from corner e to e + 1 of its outline), its ends in the panel's plane and its length (in
    ``to_unit``), its bevel (degrees; 0 a square cut) and whether it is on a hinge.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> with tempfile.TemporaryDirectory() as d:
    ...     rows = write_cut_list_csv(pathlib.Path(d) / "cut.csv", thick).read_text().splitlines()
    >>> len(rows), rows[0].split(",")[:4]
    (65, ['panel', 'edge', 'x0_mm', 'y0_mm'])
    """
    for name, value in (("unit", unit), ("to_unit", to_unit)):
        if value not in UNITS:
            raise InputError(
                f"{name} must be one of {', '.join(UNITS)}, got {value!r}", parameter="units"
            )
    scale = UNITS[unit].metres / UNITS[to_unit].metres
    k = thick.local.shape[1] // 2
    outline = thick.local[:, :k, :2] * scale
    ends = np.roll(outline, -1, axis=1)
    lengths = np.linalg.norm(ends - outline, axis=-1)
    bevels = np.degrees(thick.bevels)
    text = io.StringIO()
    out = csv.writer(text, lineterminator="\n")
    u = to_unit
    out.writerow(
        ["panel", "edge", f"x0_{u}", f"y0_{u}", f"x1_{u}", f"y1_{u}", f"length_{u}"]
        + ["bevel_deg", "hinged", f"thickness_{u}"]
    )
    labels = thick.labels()
    for f in thick.order.tolist():  # the order of assembly
        for e in range(k):
            out.writerow(
                [labels[f], e + 1]
                + [f"{v:.6f}" for v in (*outline[f, e], *ends[f, e], lengths[f, e])]
                + [f"{bevels[f, e]:.3f}", int(thick.hinged[f, e]), f"{thick.thickness * scale:g}"]
            )
    return atomic_write(path, text.getvalue().encode("utf-8"))


def write_thick_3dm(
    path: str | os.PathLike, thick: ThickPanels, fold_angle: float | None = None
) -> Path:
    """Write the solids at a fold angle (default the design angle) to a Rhino 3dm in metres (one
    model unit = 1 m): a closed Brep per panel on the layer "Thick panels", named by its label,
    its bevels and thickness as user text.

    Examples
    --------
    >>> import tempfile, pathlib, rhino3dm
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> with tempfile.TemporaryDirectory() as d:
    ...     model = rhino3dm.File3dm.Read(str(write_thick_3dm(pathlib.Path(d) / "s.3dm", thick)))
    ...     solids = [o.Geometry.IsSolid for o in model.Objects]
    >>> len(solids), all(solids)
    (16, True)
    """
    try:
        import rhino3dm as module
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("writing 3dm needs rhino3dm: pip install 'curvefold[rhino]'") from exc
    rhino3dm: Any = module  # its stubs lack tables and settable properties
    x, triangles = thick.triangles(fold_angle)
    F = len(thick.side)
    per = len(triangles) // F
    m = len(x) // F
    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = rhino3dm.UnitSystem.Meters
    model.ApplicationName = CREATOR
    layer = model.Layers.AddLayer("Thick panels", (196, 150, 98, 255))
    for f, label in enumerate(thick.labels()):
        mesh = rhino3dm.Mesh()
        mesh.Vertices.UseDoublePrecisionVertices = True
        for u, v, w in x[f * m : (f + 1) * m].tolist():
            mesh.Vertices.AddPoint3d(u, v, w)
        for a, b, c in (triangles[f * per : (f + 1) * per] - f * m).tolist():
            mesh.Faces.AddFace(a, b, c)
        mesh.Normals.ComputeNormals()
        mesh.Compact()
        brep = rhino3dm.Brep.CreateFromMesh(mesh, True)
        attr = rhino3dm.ObjectAttributes()
        attr.LayerIndex = layer
        attr.Name = label
        attr.SetUserString("curvefold:kind", "thick panel")
        attr.SetUserString("curvefold:thickness_m", f"{thick.thickness:.9g}")
        attr.SetUserString(
            "curvefold:bevels_deg", " ".join(f"{b:.3f}" for b in np.degrees(thick.bevels[f]))
        )
        model.Objects.AddBrep(brep, attr)
    with atomic_path(path) as tmp:
        if not model.Write(str(tmp), 7):
            raise OSError(f"rhino3dm could not write {path}")
    return Path(path)


#: Rows of the cut list's PDF per A4 page, and their height (mm).
_ROWS, _ROW = 22, 12.0


def write_cut_list_pdf(
    path: str | os.PathLike, thick: ThickPanels, *, unit: str = "unit", to_unit: str = "mm"
) -> Path:
    """Write the cut list as A4 pages, a row per panel in the order of assembly, numbered
    (:func:`cut_list_pages`): the CSV's rows (:func:`write_cut_list_csv`) for the workshop.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from curvefold import Structure
    >>> from curvefold.geometry import PanelLattice, ThickPanels
    >>> from curvefold.geometry._lattice import _example_lattice
    >>> thick = ThickPanels.offset(
    ...     Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), 0.01
    ... )
    >>> with tempfile.TemporaryDirectory() as d:
    ...     data = write_cut_list_pdf(pathlib.Path(d) / "cut.pdf", thick).read_bytes()
    >>> data[:8], data.count(b"/Type /Page ")  # 16 panels: one page
    (b'%PDF-1.5', 1)
    """
    from ._pdf import PdfDocument

    for name, value in (("unit", unit), ("to_unit", to_unit)):
        if value not in UNITS:
            raise InputError(
                f"{name} must be one of {', '.join(UNITS)}, got {value!r}", parameter="units"
            )
    scale = UNITS[unit].metres / UNITS[to_unit].metres
    doc = PdfDocument(title=f"cut list, thick panels t = {thick.thickness * scale:g} {to_unit}")
    cut_list_pages(doc, thick, scale, to_unit)
    return doc.save(path)


def cut_list_pages(doc: PdfDocument, thick: ThickPanels, scale: float, to_unit: str) -> int:
    """Draw the cut list on A4 pages of ``doc``; return how many.

    A row per panel in the order of assembly (:attr:`~curvefold.geometry.ThickPanels.order`),
    numbered from 1: its id on two lines (tube and sheet; strip and place along the crease), a
    sketch of its outline seen from its top face (edge numbers 1 to k from corner e to e + 1,
    hinged edges red; a bevel sets the top face back from its edge), and every edge's length
    (model lengths times ``scale``, in ``to_unit``), bevel (degrees) and whether it is hinged.
    """
    from ._pdf import PdfText
    from ._tables import COLOURS

    k = thick.local.shape[1] // 2
    outline = thick.local[:, :k, :2] * scale
    lengths = np.linalg.norm(np.roll(outline, -1, axis=1) - outline, axis=-1)
    bevels = np.degrees(thick.bevels)
    black, red = "#000000", COLOURS["fold"]
    labels, order = thick.labels(), thick.order.tolist()
    pages = -(-len(order) // _ROWS)
    for first in range(0, len(order), _ROWS):
        page = doc.page(210.0, 297.0)
        heads = (
            f"Cut list: {len(order)} panels {thick.thickness * scale:g} {to_unit} thick, in the "
            f"order of assembly, page {first // _ROWS + 1} of {pages}.",
            f"Edge: length ({to_unit}), bevel (degrees from square); hinged edges red. Outlines "
            "seen from the top face,",
            "which each bevel sets back from its edge on the hinge face.",
        )
        for n, head in enumerate(heads):
            page.text(PdfText(head, 12.0, 287.0 - 4.2 * n, 3.0, black, anchor="start"))
        for row, n in enumerate(range(first, min(first + _ROWS, len(order)))):
            f, y = order[n], 270.0 - row * _ROW
            tube, sheet, strip, place = labels[f].split(" · ")
            for line, name in enumerate((f"{n + 1}. {tube} · {sheet}", f"{strip} · {place}")):
                page.text(PdfText(name, 12.0, y - 3.6 * line, 2.8, black, anchor="start"))
            # the sketch, fitted into 50 × 9 mm with its aspect kept
            xy = outline[f] - outline[f].min(axis=0)
            size = np.maximum(xy.max(axis=0), 1e-12)
            fit = min(50.0 / size[0], 9.0 / size[1])
            sketch = xy * fit + [62.0, y - 6.0]
            ends = np.stack([sketch, np.roll(sketch, -1, axis=0)], axis=1)
            centre = sketch.mean(axis=0)
            for e in range(k):
                colour = red if thick.hinged[f, e] else black
                page.stroke([ends[e]], colour, 0.3 if thick.hinged[f, e] else 0.15)
                mid = ends[e].mean(axis=0)
                out = (mid - centre) / max(float(np.linalg.norm(mid - centre)), 1e-12)
                at = mid + 1.4 * out - [0.0, 0.6]
                page.text(PdfText(str(e + 1), float(at[0]), float(at[1]), 1.8, colour))
            words = [
                f"{e + 1}: {lengths[f, e]:.1f}, {bevels[f, e]:.1f}°"
                + (" hinged" if thick.hinged[f, e] else "")
                for e in range(k)
            ]
            for line in range(0, k, 2):
                text = "   ".join(words[line : line + 2])
                page.text(PdfText(text, 118.0, y - 3.6 * (line // 2), 2.6, black, anchor="start"))
    return pages
