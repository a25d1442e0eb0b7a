"""Layers by operation and the colour conventions of cutting machines (``--cutter``).

Laser software and cutting plotters sort what they import by colour or by layer and give
each its operation: cut through, score (cut part-way, or engrave a line), engrave, or leave
alone. The crease-pattern writers (SVG, DXF, PDF) therefore put every kind of line on a
layer named by its operation and the fold it makes (:func:`layer_name`), and draw it in the
colour the chosen convention (a :class:`Cutter` of :data:`CUTTERS`) gives that layer:

========================  ==================================  =============================
layout layer              file layer                          operation
========================  ==================================  =============================
``cut``                   ``cut``                             cut through: each sheet's
                                                              outline
``mountain``, ``valley``  ``score - mountain``, ``- valley``  score and fold
(perforated)              ``perforate - mountain``,           cut dashes
                          ``- valley``                        (:mod:`~curvefold.io._cutting`)
``seam``                  ``score - seam``                    score: the fold line of each
                                                              glue tab
``rulings``               ``engrave - rulings``               engrave (optional guide lines)
``labels``                ``engrave - labels``                engrave: sheet names and seam
                                                              names
``glue``                  ``reference - glue (not cut)``      nothing: where the glue goes
(footer)                  ``reference - legend (not cut)``    nothing: scale bar, scale,
                                                              legend
========================  ==================================  =============================

The sheets' lines are drawn in their layers' colours only. The page footer, on a layer of
its own, draws its scale bar and text in the convention's reference colour (a dark grey for
the laser, which no basic colour matches, readable on screen and paper), and each legend
sample in its layer's colour and dash pattern with the colour's code written beside it:
software that sorts by colour runs a sample with its layer (a short line in the footer band,
clear of every sheet); leave the legend layer out to skip it.

Names use `` - `` rather than a colon, which DXF forbids in layer names. Colours are
``#rrggbb``; the DXF's AutoCAD colour index of each is the nearest of the standard palette
(:func:`aci`), exact for the primaries.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..kernel._errors import InputError
from ._tables import COLOURS, rgb8

__all__ = [
    "Cutter",
    "CUTTERS",
    "DEFAULT_CUTTER",
    "LayerStyle",
    "STYLES",
    "LEGEND_LAYER",
    "layer_name",
    "cutter",
    "aci",
]

_KEYS = ("glue", "rulings", "seam", "valley", "mountain", "cut", "labels", "legend")

#: What is done with each layout layer, and the fold it makes (:func:`layer_name`).
_OPERATIONS = MappingProxyType(
    {
        "cut": ("cut", ""),
        "mountain": ("score", "mountain"),
        "valley": ("score", "valley"),
        "seam": ("score", "seam"),
        "rulings": ("engrave", "rulings"),
        "labels": ("engrave", "labels"),
        "glue": ("reference", "glue (not cut)"),
        "legend": ("reference", "legend (not cut)"),
    }
)

#: The file layer of the page footer (scale bar, scale note and legend).
LEGEND_LAYER = "reference - legend (not cut)"


def layer_name(key: str, *, perforated: bool = False) -> str:
    """The file layer of a layout layer (or ``"legend"``), named by its operation.

    Examples
    --------
    >>> layer_name("mountain"), layer_name("mountain", perforated=True), layer_name("cut")
    ('score - mountain', 'perforate - mountain', 'cut')
    """
    if key not in _OPERATIONS:
        raise InputError(f"layer must be one of {list(_OPERATIONS)}, got {key!r}")
    operation, what = _OPERATIONS[key]
    if perforated and key in ("mountain", "valley"):
        operation = "perforate"
    return f"{operation} - {what}" if what else operation


@dataclass(frozen=True)
class LayerStyle:
    """How a layer's lines look, whatever their colour.

    Attributes
    ----------
    linetype : str
        DXF linetype name.
    dashes : tuple of float
        Dash pattern in mm (on, off, on, off…); empty for a solid line.
    width : float
        Line width as a multiple of the writer's ``line_width``.
    fill : bool
        Closed polylines are filled areas, not lines.
    """

    linetype: str = "CONTINUOUS"
    dashes: tuple[float, ...] = ()
    width: float = 1.0
    fill: bool = False


#: The look of every layer (and of the legend's text), colour aside. Perforated creases are
#: solid: their dashes are geometry. The DXF linetypes carry these patterns under the names of
#: LibreCAD's small built-in ones, which LibreCAD draws in their place (it reads no pattern
#: from a file), so that they come out dashed there at about the same size.
STYLES: Mapping[str, LayerStyle] = MappingProxyType(
    {
        "glue": LayerStyle(fill=True),
        "rulings": LayerStyle(width=0.5),
        "seam": LayerStyle("DOTTINY", (0.8, 0.8)),
        "valley": LayerStyle("DASHEDTINY", (3.0, 1.5)),
        "mountain": LayerStyle("DASHDOTTINY", (4.0, 1.2, 0.7, 1.2)),
        "cut": LayerStyle(),
        "labels": LayerStyle(),
        "legend": LayerStyle(),
    }
)


@dataclass(frozen=True)
class Cutter:
    """A colour convention: the colour of every layer, and where the convention is documented.

    Attributes
    ----------
    name : str
        What users type (``--cutter laser``).
    title : str
        Who it is for, one line.
    colours : mapping of str to str
        ``#rrggbb`` of every layout layer and of ``"legend"``.
    source : str
        The documentation the convention follows (empty for curvefold's own).
    """

    name: str
    title: str
    colours: Mapping[str, str]
    source: str = ""

    def __post_init__(self) -> None:
        missing = [k for k in _KEYS if k not in self.colours]
        if missing:
            raise ValueError(f"cutter {self.name!r} gives no colour for {missing}")
        cut = self.colours["cut"].lower()
        if any(self.colours[k].lower() == cut for k in _KEYS if k != "cut"):
            raise ValueError(
                f"cutter {self.name!r}: only the cut layer may be drawn in the cut colour {cut}"
            )
        for code in self.colours.values():
            rgb8(code)
        object.__setattr__(self, "colours", MappingProxyType(dict(self.colours)))


#: The order of a palette's colours (:func:`_palette`).
_PALETTE = ("cut", "mountain", "valley", "seam", "rulings", "labels", "glue", "legend")


def _palette(colours: tuple[str, str, str, str, str, str, str, str]) -> dict[str, str]:
    """The colour of each layer, given in the order of :data:`_PALETTE`."""
    return dict(zip(_PALETTE, colours, strict=True))


#: The conventions ``--cutter`` offers, by name.
CUTTERS: Mapping[str, Cutter] = MappingProxyType(
    {
        c.name: c
        for c in (
            Cutter(
                "print",
                "printing on paper, folding and cutting by hand: folds red and blue, as in "
                "the 3D files",
                _palette(
                    (
                        COLOURS["boundary"],
                        COLOURS["fold"],
                        COLOURS["valley"],
                        COLOURS["tab"],
                        COLOURS["ruling"],
                        COLOURS["label"],
                        COLOURS["glue"],
                        "#595959",
                    )
                ),
            ),
            Cutter(
                "laser",
                "laser software that gives each colour its own layer and operation "
                "(LightBurn; Epilog's colour mapping): one of the six basic colours, or black, per "
                "layer",
                _palette(
                    (
                        "#ff0000",
                        "#0000ff",
                        "#00ff00",
                        "#00ffff",
                        "#ff00ff",
                        "#000000",
                        "#ffff00",
                        "#595959",
                    )
                ),
                "LightBurn documentation, 'Colors and Layers': each colour is a layer, each "
                "layer one operation, run in layer order; Epilog Laser, Zing manual, "
                "section 'Color Mapping': use the six basic colours red, green, blue, "
                "cyan, yellow, magenta, whose values must match exactly",
            ),
            Cutter(
                "service",
                "laser-cutting services that read red as cut, blue as score and black as engrave",
                _palette(
                    (
                        "#ff0000",
                        "#0000ff",
                        "#0000ff",
                        "#0000ff",
                        "#000000",
                        "#000000",
                        "#ffff00",
                        "#ffff00",
                    )
                ),
                "Lasergarage Berlin, 'Farbenkodierung in den Schnittdateien für Lasercutter': red "
                "(255, 0, 0) cut, blue (0, 0, 255) score, black (0, 0, 0) engrave, yellow (255, "
                "255, 0) a frame to check the scale, not processed",
            ),
        )
    }
)

#: The convention of the files unless told otherwise.
DEFAULT_CUTTER = "print"


def cutter(name: str | Cutter) -> Cutter:
    """The convention named ``name`` (a :class:`Cutter` is returned as it is).

    Examples
    --------
    >>> cutter("laser").colours["cut"]
    '#ff0000'
    """
    if isinstance(name, Cutter):
        return name
    if name not in CUTTERS:
        raise InputError(
            f"cutter must be one of {', '.join(CUTTERS)}, got {name!r}", parameter="cutter"
        )
    return CUTTERS[name]


# AutoCAD colour index 1–9: red, yellow, green, cyan, blue, magenta, white (drawn black on white),
# grey, light grey.
_ACI = {
    1: (255, 0, 0),
    2: (255, 255, 0),
    3: (0, 255, 0),
    4: (0, 255, 255),
    5: (0, 0, 255),
    6: (255, 0, 255),
    7: (0, 0, 0),
    8: (128, 128, 128),
    9: (192, 192, 192),
}


def aci(colour: str) -> int:
    """The AutoCAD colour index nearest to ``#rrggbb`` among 1–9 (7 for black), for DXF readers that
    ignore true colour.

    Examples
    --------
    >>> aci("#ff0000"), aci("#000000"), aci("#1f4fe0")
    (1, 7, 5)
    """
    r, g, b = rgb8(colour)
    return min(
        _ACI, key=lambda i: (_ACI[i][0] - r) ** 2 + (_ACI[i][1] - g) ** 2 + (_ACI[i][2] - b) ** 2
    )
