"""Files of thick panels (:class:`~curvefold.geometry.ThickPanels`): the solids as a watertight
binary STL, and the cut list as JSON.

The STL holds every solid closed on its own (each edge of its triangles shared by two of them,
once each way), counter-clockwise seen from outside, so slicers and CAD tools read volumes.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from ..geometry._thick import ThickPanels
from ..kernel._errors import InputError
from ..kernel._text import one_line
from ._atomic import atomic_write
from ._mesh3d import stl_records
from ._tables import CREATOR, UNITS

__all__ = ["write_thick_stl", "write_cut_list"]


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
    (16, 'tube 1 · strip 1 · panel 1')
    """
    body = {
        "creator": CREATOR,
        "technique": "offset panels: hinges on the zero-thickness creases, solids outside",
        "thickness": thick.thickness,
        "bevels_for_fold_angles": list(thick.reach),
        "panels": list(thick.cut_list()),
    }
    return atomic_write(path, json.dumps(body, indent=1, ensure_ascii=False).encode("utf-8"))
