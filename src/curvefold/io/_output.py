"""What the files of a structure are written as: one value per family of files.

A :class:`PatternOutput` is what a design's ``[output]`` table says about the crease-pattern
files; the layout functions (:func:`~curvefold.io.layout_pattern`,
:func:`~curvefold.io._single_fold.layout_single_fold`) and
:func:`~curvefold.io.write_pattern` take it whole, as a matplotlib backend takes a
GraphicsContext, so its defaults are stated once, here. A :class:`ModelOutput` is the same
for the 3D files of :func:`~curvefold.io.write_3d`: units, metadata, sampling and what the
GLB and the 3dm carry besides the model; a :class:`FoldOutput` for the FOLD file of
:func:`~curvefold.io.to_fold`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from ..kernel._errors import InputError
from ._cutters import DEFAULT_CUTTER

if TYPE_CHECKING:
    from ._layout import Layout
    from ._sheet_bend import SheetBend

__all__ = ["FoldOutput", "ModelOutput", "PatternOutput", "check_output"]


@dataclass(frozen=True)
class PatternOutput:
    """How a crease pattern is printed or cut.

    Attributes
    ----------
    page : str or (2,) tuple of float
        Page name (``"A4"``…, see :data:`~curvefold.io._tables.PAGES`) or (width, height)
        in ``units``.
    units : str
        Unit of ``page`` and ``scale`` (``"mm"``, ``"cm"``, ``"in"``…).
    scale : float or None
        Page length in ``units`` per model unit. None: the largest sheet fills the page
        inside its margins at a plain scale (:func:`~curvefold.io.layout_pattern`).
    glue_tabs : bool
        Draw glue tabs along the seams.
    rulings : bool
        Also draw the rulings (thin green, for scoring), when the files are written.
    cutter : str
        The colour convention of the files, a key of :data:`curvefold.io.CUTTERS`.
    perforation : (float, float) or None
        (dash, gap) in mm: every crease drawn as cut dashes
        (:func:`curvefold.io._cutting.perforation_dashes`); None: score lines.
    kerf : float
        Width in mm a cutter removes: the cut outlines move out by half of it.
    name : str
        Label prefix of the sheets.
    bend : SheetBend or None
        The sheet's thickness and bend: creases inset, seams lapped, tabs and perforation
        sized to it (:mod:`curvefold.io._thick_sheet`); None: a sheet of zero thickness.

    Examples
    --------
    >>> PatternOutput().page, PatternOutput().units, PatternOutput().cutter
    ('A4', 'mm', 'print')
    >>> PatternOutput(page="A3", scale=50.0).scale
    50.0
    """

    page: str | tuple[float, float] = "A4"
    units: str = "mm"
    scale: float | None = None
    glue_tabs: bool = True
    rulings: bool = False
    cutter: str = DEFAULT_CUTTER
    perforation: tuple[float, float] | None = None
    kerf: float = 0.0
    name: str = ""
    bend: SheetBend | None = None


def check_output(output: PatternOutput) -> PatternOutput:
    """``output`` if it is a :class:`PatternOutput`, else the error saying what it is."""
    if not isinstance(output, PatternOutput):
        raise InputError(
            f"output must be a PatternOutput (page, units, scale…), "
            f"got {type(output).__name__}: {output!r}",
            parameter="output",
        )
    return output


@dataclass(frozen=True, eq=False)
class ModelOutput:
    """How a structure's 3D files are written (:func:`~curvefold.io.write_3d`).

    Attributes
    ----------
    unit : str
        Model unit (``"unit"``, ``"m"``, ``"mm"``…); GLB converts it to metres.
    print_unit : str or None
        Length unit of the STL, which slicers read as millimetres (``"mm"``); None: the
        model unit. The model unit counts as one metre (:data:`curvefold.io._tables.UNITS`).
    print_scale : float or None
        Millimetres of the STL per model unit, the crease pattern's scale
        (:attr:`~curvefold.io.Layout.scale`), so that a print matches the pattern; None: the
        true size.
    metadata : mapping or None
        Extra design parameters, merged over the defaults of :func:`~curvefold.io.to_fold`.
    anchor : {"start", "middle"}
        Which frame of curve 1 stays fixed along the motion.
    keep : sequence of (m_k,) array_like of int, or None
        The samples each tube's mesh keeps (:func:`curvefold.geometry.choose_sampling`);
        None: every sample.
    seconds_per_state : float
        GLB animation time between consecutive states.
    morph_targets : mapping of str to (V, 3) array_like, or None
        Further named morph targets of the GLB (a deformed shape, mode shapes): displacements,
        in model units, of the vertices of ``structure.state(fold_angle).mesh(keep=keep)``
        from that state (see :func:`curvefold.io.write_glb`).
    pattern : Layout or None
        The crease pattern the 3dm lays beside the model on its ``crease pattern`` layer
        (:func:`curvefold.io.layout_pattern`).

    Examples
    --------
    >>> ModelOutput().unit, ModelOutput(unit="mm", print_unit="cm").print_unit
    ('unit', 'cm')
    """

    unit: str = "unit"
    print_unit: str | None = None
    print_scale: float | None = None
    metadata: Mapping[str, object] | None = None
    anchor: Literal["start", "middle"] = "start"
    keep: Sequence[np.ndarray] | None = None
    seconds_per_state: float = 1.0
    morph_targets: Mapping[str, np.ndarray] | None = None
    pattern: Layout | None = None


@dataclass(frozen=True, eq=False)
class FoldOutput:
    """How a structure's FOLD file is made (:func:`~curvefold.io.to_fold`), besides the fold angles
    of its frames.

    Attributes
    ----------
    unit : str
        Model unit (``frame_unit``).
    metadata : mapping or None
        Extra design parameters; merged over the ones recorded by default (tubes, cells,
        samples, curve length, widths at t = 0, the design, crease and seam angles, the seam
        numbering and the bonds as text).
    anchor : {"start", "middle"}
        Which frame of curve 1 stays fixed along the motion.
    faces : {"triangles", "quads"}
        The sheets' faces.
    keep : sequence of (m_k,) array_like of int, or None
        The samples each tube keeps; None: every sample.
    design : mapping or None
        The design the structure was built from, as a design file holds it
        (:meth:`curvefold.app.Design.to_dict`); recorded with the frames' fold angles,
        anchor and faces, so that the file can be built again and compared.
    ground : bool
        Whether every folded frame stands on the ground ``z = 0`` as the design frame does (a
        vault): turned about the span's normal until its feet are level, then set down
        (:func:`curvefold.geometry._standing.standing_frames`).

    Examples
    --------
    >>> FoldOutput().faces, FoldOutput(unit="mm").unit
    ('triangles', 'mm')
    """

    unit: str = "unit"
    metadata: Mapping[str, object] | None = None
    anchor: Literal["start", "middle"] = "start"
    faces: Literal["triangles", "quads"] = "triangles"
    keep: Sequence[np.ndarray] | None = None
    design: Mapping[str, object] | None = None
    ground: bool = False
