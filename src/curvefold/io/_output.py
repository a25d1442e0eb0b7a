"""The printed output of a crease pattern as one value: page, units, scale, cutter and the rest.

A :class:`PatternOutput` is what a design's ``[output]`` table says about the crease-pattern
files; the layout functions (:func:`~curvefold.io.layout_pattern`,
:func:`~curvefold.io._single_fold.layout_single_fold`) and
:func:`~curvefold.io.write_pattern` take it whole, as a matplotlib backend takes a
GraphicsContext, so its defaults are stated once, here.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..kernel._errors import InputError
from ._cutters import DEFAULT_CUTTER

__all__ = ["PatternOutput", "check_output"]


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


def check_output(output: PatternOutput) -> PatternOutput:
    """``output`` if it is a :class:`PatternOutput`, else the error saying what it is."""
    if not isinstance(output, PatternOutput):
        raise InputError(f"output must be a PatternOutput (page, units, scale…), got {type(output).__name__}: {output!r}",
                         parameter="output")
    return output
