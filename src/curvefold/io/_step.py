"""Thick panels (:class:`~curvefold.geometry.ThickPanels`) as a STEP file (ISO 10303-21, AP214):
one closed B-rep solid per panel, for CAD tools that read solids rather than meshes.

Every solid is built by OpenCascade (the ``OCP`` bindings, ``pip install 'curvefold[step]'``,
imported only here and only when a file is written) from its planar faces: each face a closed
polygon made a plane face, the faces sewn into a shell, the shell made a solid and oriented
so that its volume is positive (its normals point out), the solid checked valid and closed
(:func:`check_solid`). Each is a product of the file named by its panel's id (the cut list's
and the assembly guide's ``tube 1 · sheet B · strip 2 · panel 3``), in the output units, which
the file states (its ``SI_UNIT`` or ``CONVERSION_BASED_UNIT``).

On the tube of 16 panels of the examples, t = 1 cm, the solids read back (STEPControl_Reader)
have the volumes of the closed triangle meshes of :meth:`ThickPanels.triangles` to 1.5e-14
relative and their bounding box to 1e-9 of its size (tests/test_step.py).
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from ..geometry._thick import ThickPanels
from ..kernel._errors import InputError
from ._atomic import atomic_path
from ._tables import CREATOR, UNITS

__all__ = ["write_thick_step", "check_solid", "STEP_UNITS", "STEP_NEEDS", "STEP_EXTRA"]

#: The module the STEP writer needs and the extra that brings it.
STEP_NEEDS, STEP_EXTRA = "OCP", "step"
#: The length units a STEP file states (OpenCascade's ``write.step.unit``), by curvefold's name;
#: the model unit is written as metres (1 model unit = 1 m).
STEP_UNITS = {"mm": "MM", "cm": "CM", "m": "M", "in": "INCH", "ft": "FT", "um": "UM", "unit": "M"}
#: Sewing tolerance, in the file's units: the faces of a solid share their corners exactly (one
#: array of vertices), so sewing merges only coincident points.
_SEWING = 1e-9
#: A character outside ASCII (the labels' are in the Basic Multilingual Plane: ``\\X2\\``).
_OTHER = re.compile(r"[^\x00-\x7f]")


def _ocp() -> Any:
    """The OCP module, or the one-line error naming the extra that brings it."""
    try:
        import OCP
    except ImportError as exc:
        raise ImportError(
            f"writing STEP needs {STEP_NEEDS}: pip install 'curvefold[{STEP_EXTRA}]'"
        ) from exc
    return OCP


def _faces(k: int, counter_clockwise: bool) -> list[list[int]]:
    """The corners of a prism's k + 2 faces (bottom, top, then the sides), counter-clockwise
    seen from outside for an outline counter-clockwise in its panel's frame (reversed if not)."""
    faces = [list(range(k - 1, -1, -1)), list(range(k, 2 * k))]
    faces += [[e, (e + 1) % k, k + (e + 1) % k, k + e] for e in range(k)]
    return faces if counter_clockwise else [face[::-1] for face in faces]


def _solid(vertices: np.ndarray, faces: list[list[int]]) -> Any:
    """A closed B-rep solid of planar faces (each a list of rows of ``vertices``), its normals
    out."""
    from OCP.BRepBuilderAPI import (
        BRepBuilderAPI_MakeFace,
        BRepBuilderAPI_MakePolygon,
        BRepBuilderAPI_MakeSolid,
        BRepBuilderAPI_Sewing,
    )
    from OCP.BRepLib import BRepLib
    from OCP.gp import gp_Pnt
    from OCP.TopoDS import TopoDS

    sewing = BRepBuilderAPI_Sewing(_SEWING)
    for face in faces:
        polygon = BRepBuilderAPI_MakePolygon()
        for u, v, w in vertices[face].tolist():
            polygon.Add(gp_Pnt(u, v, w))
        polygon.Close()
        sewing.Add(BRepBuilderAPI_MakeFace(polygon.Wire(), True).Face())
    sewing.Perform()
    shell = getattr(TopoDS, "Shell_s", None) or TopoDS.Shell  # OCP 7.8 or 8
    solid = BRepBuilderAPI_MakeSolid(shell(sewing.SewedShape())).Solid()
    BRepLib.OrientClosedSolid_s(solid)
    return solid


def _ascii(text: str) -> str:
    """Text of a STEP file in ASCII: every other character as ISO 10303-21's ``\\X2\\hhhh\\X0\\``
    (OpenCascade writes names in UTF-8).

    Examples
    --------
    >>> print(_ascii("tube 1 · strip 1"))
    tube 1 \\X2\\00B7\\X0\\ strip 1
    """
    return _OTHER.sub(lambda c: f"\\X2\\{ord(c[0]):04X}\\X0\\", text)


@contextmanager
def _quiet() -> Iterator[None]:
    """OpenCascade's messages below failures kept off the standard output while it works."""
    from OCP.Message import Message, Message_Gravity

    printers = Message.DefaultMessenger_s().Printers()
    levels = [(p, p.GetTraceLevel()) for p in printers]
    for printer, _ in levels:
        printer.SetTraceLevel(Message_Gravity.Message_Fail)
    try:
        yield
    finally:
        for printer, level in levels:
            printer.SetTraceLevel(level)


def check_solid(shape: Any) -> str | None:
    """Why a shape is not one valid closed solid of positive volume (None if it is): OpenCascade's
    checks (``BRepCheck_Analyzer``), its shells closed (every edge in two faces) and its
    volume.

    Examples
    --------
    >>> from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    >>> check_solid(BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Solid()) is None
    True
    """
    _ocp()
    from OCP.BRep import BRep_Tool
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.TopAbs import TopAbs_SHELL, TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    if shape.ShapeType() != TopAbs_SOLID:
        return f"a {shape.ShapeType().name.removeprefix('TopAbs_').lower()}, not a solid"
    if not BRepCheck_Analyzer(shape).IsValid():
        return "not valid (BRepCheck_Analyzer)"
    shells = TopExp_Explorer(shape, TopAbs_SHELL)
    if not shells.More():
        return "no shell"
    while shells.More():
        if not BRep_Tool.IsClosed_s(shells.Current()):
            return "a shell not closed (an edge in one face)"
        shells.Next()
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    if not props.Mass() > 0:
        return f"volume {props.Mass():.6g}, not positive"
    return None


def write_thick_step(
    path: str | os.PathLike,
    thick: ThickPanels,
    fold_angle: float | None = None,
    *,
    unit: str = "unit",
    to_unit: str | None = None,
) -> Path:
    """Write the solids at a fold angle (default the design angle) as a STEP file (AP214): a
    closed B-rep solid per panel named by its label, in ``to_unit`` (stated in the file).

    Parameters
    ----------
    unit, to_unit : str
        Length units of the model and of the file (a key of :data:`STEP_UNITS`; ``to_unit``
        defaults to ``unit``, the model unit written as metres).

    Raises
    ------
    InputError
        A unit a STEP file cannot state.
    ImportError
        OCP is not installed (the message names the extra).
    RuntimeError
        A solid OpenCascade does not find valid and closed (:func:`check_solid`), naming it.

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
    ...     text = write_thick_step(pathlib.Path(d) / "s.step", thick, to_unit="mm").read_text()
    >>> text.count("MANIFOLD_SOLID_BREP"), "SI_UNIT(.MILLI.,.METRE.)" in text
    (16, True)
    """
    to_unit = unit if to_unit is None else to_unit
    for name, value in (("unit", unit), ("to_unit", to_unit)):
        if value not in STEP_UNITS:
            raise InputError(
                f"{name} must be one of {', '.join(STEP_UNITS)} (the units a STEP file states), "
                f"got {value!r}",
                parameter="units",
            )
    _ocp()
    from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Controller
    from OCP.TCollection import TCollection_ExtendedString, TCollection_HAsciiString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    words = "model units (1 model unit = 1 m)" if to_unit == "unit" else to_unit
    description = f"thick panels t = {thick.thickness:g} {unit}, unit {words}"
    x, _ = thick.triangles(fold_angle)
    x = x * (UNITS[unit].metres / UNITS[to_unit].metres)
    F, m = thick.local.shape[:2]
    k = m // 2
    xy = thick.local[:, :k, :2]
    ahead = np.roll(xy, -1, axis=1)
    area = (xy[..., 0] * ahead[..., 1] - xy[..., 1] * ahead[..., 0]).sum(1)  # twice, signed
    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    shapes = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    # the document's length unit is the file's: the writer converts nothing
    XCAFDoc_DocumentTool.SetLengthUnit_s(doc, UNITS[to_unit].metres)
    for f, label in enumerate(thick.labels()):
        solid = _solid(x[f * m : (f + 1) * m], _faces(k, bool(area[f] > 0)))
        why = check_solid(solid)
        if why is not None:
            raise RuntimeError(f"the solid of {label} is {why}")
        TDataStd_Name.Set_s(shapes.AddShape(solid, False), TCollection_ExtendedString(label, True))
    STEPControl_Controller.Init_s()  # registers the parameters set next
    for key, value in (("write.step.schema", "AP214IS"), ("write.step.unit", STEP_UNITS[to_unit])):
        if not Interface_Static.SetCVal_s(key, value):
            raise RuntimeError(f"OpenCascade has no parameter {key} = {value}")
    writer = STEPCAFControl_Writer()
    writer.SetNameMode(True)
    with _quiet():
        if not writer.Transfer(doc, STEPControl_AsIs):
            raise RuntimeError(f"OpenCascade could not transfer the solids of {path}")
        header = APIHeaderSection_MakeHeader(writer.ChangeWriter().Model())
        header.SetOriginatingSystem(TCollection_HAsciiString(CREATOR))
        header.SetName(TCollection_HAsciiString(Path(path).name))
        header.SetDescriptionValue(1, TCollection_HAsciiString(_ascii(description)))
        with atomic_path(path) as tmp:
            if writer.Write(str(tmp)) != IFSelect_RetDone:
                raise OSError(f"OpenCascade could not write {path}")
            text = tmp.read_text(encoding="utf-8")
            tmp.write_text(_ascii(text), encoding="ascii")
    return Path(path)
