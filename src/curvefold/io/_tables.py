"""The one table of pages, length units and line colours every writer and figure reads.

Pages
    :data:`PAGES`: portrait (width, height) in millimetres of the named paper sizes.
    Names are matched case-insensitively (:func:`page_mm`).
Units
    :data:`UNITS`: every length unit curvefold writes, with its size in metres and its
    Rhino unit system. ``"unit"`` is the model unit, which has no size of its own; where a
    file needs one (glTF is in metres, a page in millimetres) one model unit is taken as
    one metre, the same everywhere.
Colours
    :data:`COLOURS`: ``#rrggbb`` of every kind of line, shared by the 3D files (glTF,
    3dm), the crease patterns (SVG, DXF, PDF) and the figures: folds red, seams blue,
    boundaries black, rulings green, as in the paper's figures.
Creator
    ``CREATOR``: the program and version the files name as their creator (FOLD's
    ``file_creator``, glTF's ``asset.generator``, the 3dm's application, the PDF's creator):
    ``"curvefold <version>"`` (``curvefold.kernel._version.VERSION``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..kernel._errors import InputError
from ..kernel._version import VERSION

__all__ = [
    "PAGES",
    "UNITS",
    "COLOURS",
    "CREATOR",
    "Unit",
    "page_mm",
    "mm_per_unit",
    "rgb8",
    "rgba",
    "rgba8",
]

#: The program and version the files name as their creator.
CREATOR = f"curvefold {VERSION}"


#: Paper sizes, portrait (width, height) in millimetres.
PAGES: Mapping[str, tuple[float, float]] = MappingProxyType(
    {
        "A5": (148.0, 210.0),
        "A4": (210.0, 297.0),
        "A3": (297.0, 420.0),
        "A2": (420.0, 594.0),
        "A1": (594.0, 841.0),
        "A0": (841.0, 1189.0),
        "Letter": (215.9, 279.4),
        "Legal": (215.9, 355.6),
        "Tabloid": (279.4, 431.8),
    }
)


@dataclass(frozen=True)
class Unit:
    """A length unit.

    Attributes
    ----------
    metres : float
        Its size in metres (1 for the model unit, by convention).
    rhino : str
        The ``rhino3dm.UnitSystem`` member of the unit.
    """

    metres: float
    rhino: str


#: Every length unit, by name.
UNITS: Mapping[str, Unit] = MappingProxyType(
    {
        "mm": Unit(1e-3, "Millimeters"),
        "cm": Unit(1e-2, "Centimeters"),
        "m": Unit(1.0, "Meters"),
        "in": Unit(0.0254, "Inches"),
        "pt": Unit(0.0254 / 72.0, "PrinterPoints"),
        "ft": Unit(0.3048, "Feet"),
        "um": Unit(1e-6, "Microns"),
        "nm": Unit(1e-9, "Nanometers"),
        "unit": Unit(1.0, "Meters"),
    }
)

#: Colour of every kind of line: the edge kinds of a mesh (``fold``, ``seam``,
#: ``boundary``, ``ruling``), the curve kinds of the figures (``junction``, ``edge``), the
#: surfaces, and the crease-pattern layers that have no edge kind of their own.
COLOURS: Mapping[str, str] = MappingProxyType(
    {
        "fold": "#ff0000",
        "seam": "#0000ff",
        "boundary": "#000000",
        "ruling": "#00a000",
        "junction": "#7b3294",
        "edge": "#4d4d4d",
        "surface": "#cccccc",
        "valley": "#1f4fe0",
        "tab": "#16a016",
        "glue": "#c6ecc6",
        "label": "#7b2fa6",
    }
)


def page_mm(name: str) -> tuple[float, float]:
    """(width, height) in mm of a page name, in any letter case.

    Examples
    --------
    >>> page_mm("a4"), page_mm("LETTER")
    ((210.0, 297.0), (215.9, 279.4))
    """
    for key, size in PAGES.items():
        if isinstance(name, str) and name.strip().casefold() == key.casefold():
            return size
    raise InputError(f"page must be one of {', '.join(PAGES)} or (width, height), got {name!r}")


def mm_per_unit(name: str) -> float:
    """Millimetres per length unit ``name``.

    Examples
    --------
    >>> mm_per_unit("in"), mm_per_unit("pt") == 25.4 / 72
    (25.4, True)
    """
    if name not in UNITS:
        raise InputError(f"units must be one of {', '.join(UNITS)}, got {name!r}")
    return UNITS[name].metres * 1000.0


def rgb8(code: str) -> tuple[int, int, int]:
    """The channels, 0–255, of a colour written ``"#rrggbb"``.

    Examples
    --------
    >>> rgb8("#ff8000")
    (255, 128, 0)
    """
    text = str(code)
    try:
        if len(text) != 7 or text[0] != "#":
            raise ValueError
        return tuple(int(text[k : k + 2], 16) for k in (1, 3, 5))  # type: ignore[return-value]
    except ValueError:
        raise InputError(f"a colour must be written '#rrggbb', got {code!r}") from None


def rgba(kind: str) -> tuple[float, float, float, float]:
    """The colour of ``kind`` as RGBA in [0, 1] (opaque)."""
    return (*(c / 255.0 for c in rgb8(COLOURS[kind])), 1.0)  # type: ignore[return-value]


def rgba8(kind: str) -> tuple[int, int, int, int]:
    """The colour of ``kind`` as RGBA in 0–255 (opaque)."""
    return (*rgb8(COLOURS[kind]), 255)
