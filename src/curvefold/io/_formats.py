"""The registry of file formats, and the output parameters of a design.

:data:`FORMATS` lists every file curvefold writes beside its report: the name a user
types (``--formats svg,fold``, ``[output] formats = ["svg"]``), the extension, its media
type, what the file holds, the kinds of design it is written for, the function that writes
it and the optional package it needs. The command line (choices and help), the design
schema, the output folder and the designer's downloads read it; nothing else lists format
names, extensions or media types.

Formats of one family are written from one prepared value: the crease patterns are laid
out once (a :class:`~curvefold.io.Layout`) for SVG, DXF and PDF; the 3D files share
one folded state (a :class:`~curvefold.io._models.FoldedModel`); the GIF is written from
frames drawn by :mod:`curvefold.figures._motion`. Each format's writer takes the target
path and that value; the family's writer (:func:`~curvefold.io.write_pattern`,
:func:`~curvefold.io.write_3d`) prepares it once and calls the writer the registry
names for each format asked. Writers are named by their qualified name and imported only
when a file is written, so reading the registry costs no optional import.

A format drawn by a layer above io (the assembly guide, drawn by :mod:`curvefold.figures`)
is declared here without its writer; that layer registers it with :func:`register_writer`
when it is imported, so io never names a module above it.

:data:`OUTPUT_SPECS` are the ``[output]`` parameters of a design (see
:class:`curvefold.kernel.Spec`).
"""

from __future__ import annotations

import importlib
import importlib.util
import os
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from types import MappingProxyType
from typing import Any, cast

from ..kernel._errors import InputError, InternalError
from ..kernel._validate import Interval, Spec
from ._cutters import CUTTERS
from ._output import PatternOutput
from ._tables import PAGES, mm_per_unit

__all__ = [
    "FileFormat",
    "FORMATS",
    "FAMILIES",
    "STRUCTURE_KINDS",
    "OUTPUT_SPECS",
    "formats_of",
    "default_formats",
    "check_formats",
    "check_kind",
    "check_scale",
    "missing_dependencies",
    "formats_left_out",
    "register_writer",
    "MIN_DRAWN_MM",
]

#: Kinds of design that build a structure (the crease kind builds a single crease).
STRUCTURE_KINDS = ("vault", "tube", "block")


@dataclass(frozen=True)
class FileFormat:
    """One file format.

    Attributes
    ----------
    name : str
        What users type, e.g. ``"svg"``.
    extension : str
        File name suffix with its dot.
    holds : str
        What the file holds, for help texts.
    family : str
        Formats of one family are written together (a key of :data:`FAMILIES`).
    kinds : tuple of str
        Kinds of design the format is written for.
    writer : str or callable or None
        The function that writes it, or its qualified name ``"module:function"``, called with
        the target path and the family's prepared value (see the module notes); None until
        the layer that draws the format registers it (:func:`register_writer`).
    media_type : str
        The file's media type (MIME type), as the designer serves it.
    dependency : str or None
        Module writing the file needs that curvefold does not require, or None.
    extra : str or None
        The ``pip install 'curvefold[extra]'`` that brings ``dependency``.
    stem : str or None
        A file name of its own (``"assembly"``: ``assembly.pdf``), instead of the stem its family is
        given.
    optional : bool
        Written only for the designs it applies to and only where ``dependency`` is installed:
        without it the file is left out with a note (:func:`formats_left_out`), never refused.
    """

    name: str
    extension: str
    holds: str
    family: str
    kinds: tuple[str, ...]
    writer: str | Callable[..., Any] | None
    media_type: str
    dependency: str | None = None
    extra: str | None = None
    stem: str | None = None
    optional: bool = False

    def path(self, stem: str | os.PathLike) -> Path:
        """The file of this format for a path stem: ``<stem><extension>``, or its own name beside
        it.

        Examples
        --------
        >>> (
        ...     FORMATS["svg"].path("out/vault-pattern").as_posix(),
        ...     FORMATS["assembly"].path("out/vault").as_posix(),
        ... )
        ('out/vault-pattern.svg', 'out/assembly.pdf')
        """
        stem = Path(stem)
        return stem.with_name((self.stem or stem.name) + self.extension)

    @property
    def title(self) -> str:
        """The format as a download is named: its name in capitals, or its own file name and type.

        Examples
        --------
        >>> FORMATS["svg"].title, FORMATS["assembly"].title
        ('SVG', 'assembly (PDF)')
        """
        return (
            self.name.upper()
            if self.stem is None
            else f"{self.stem} ({self.extension[1:].upper()})"
        )

    def load_writer(self) -> Callable[..., Any]:
        """Import and return the writing function.

        Raises
        ------
        InternalError
            The format's writer was never registered (:func:`register_writer`).
        """
        if self.writer is None:
            raise InternalError(
                f"format {self.name!r} has no writer: the package that draws it "
                "registers one (register_writer) when it is imported"
            )
        if callable(self.writer):
            return self.writer
        module, function = self.writer.split(":")
        return cast(Callable[..., Any], getattr(importlib.import_module(module), function))


_S = STRUCTURE_KINDS
# a single curved fold writes its crease pattern, FOLD file and 3D models too
_ALL = (*STRUCTURE_KINDS, "crease")

#: The registry, filled once here; a writer of a layer above io is added by :func:`register_writer`.
_FORMATS: dict[str, FileFormat] = {
    f.name: f
    for f in (
        FileFormat(
            "svg",
            ".svg",
            "crease pattern pages in mm with one layer per operation, a scale bar and legend",
            "pattern",
            _ALL,
            "curvefold.io._svg:write_svg",
            "image/svg+xml",
        ),
        FileFormat(
            "dxf",
            ".dxf",
            "crease pattern pages in mm with layers, colours and linetypes, framed in a grid",
            "pattern",
            _ALL,
            "curvefold.io._dxf:write_dxf",
            "image/vnd.dxf",
            "ezdxf",
            "export",
        ),
        FileFormat(
            "pdf",
            ".pdf",
            "printable crease pattern pages at 1:1 with a layer per operation, "
            "a scale bar and legend",
            "pattern",
            _ALL,
            "curvefold.io._pattern_pdf:write_pdf",
            "application/pdf",
        ),
        FileFormat(
            "assembly",
            ".pdf",
            "the assembly guide: the sheets to cut, which seam glues to "
            "which, the order of folding and gluing tube by tube with a picture of each step, on "
            "the pattern's pages",
            "guide",
            _S,
            # the writer is figures' (register_writer)
            None,
            "application/pdf",
            stem="assembly",
        ),
        FileFormat(
            "fold",
            ".fold",
            "FOLD 1.1: the crease pattern and the frames of the folding "
            "motion, and one FOLD file per sheet",
            "fold",
            _ALL,
            "curvefold.io._fold:write_structure_fold",
            "application/json",
        ),
        FileFormat(
            "glb",
            ".glb",
            "glTF 3D model, a node per sheet, at the design state, the folding "
            "motion as named morph targets and an animation",
            "model",
            _ALL,
            "curvefold.io._model_files:model_glb",
            "model/gltf-binary",
        ),
        FileFormat(
            "obj",
            ".obj",
            "3D mesh of the folded state (Y up, ruling quads) with the creases as polylines",
            "model",
            _ALL,
            "curvefold.io._model_files:model_obj",
            "model/obj",
        ),
        FileFormat(
            "3dm",
            ".3dm",
            "Rhino model in metres: a mesh per sheet, each strip a ruled NURBS "
            "surface, the creases NURBS curves",
            "model",
            _ALL,
            "curvefold.io._model_files:model_3dm",
            "application/octet-stream",
            "rhino3dm",
            "rhino",
        ),
        FileFormat(
            "stl",
            ".stl",
            "3D mesh of the folded state (triangles) at the crease pattern's scale, in the "
            "output units (millimetres by default), for slicers: a surface without thickness, "
            "open along its edges, not a solid",
            "model",
            _ALL,
            "curvefold.io._model_files:model_stl",
            "model/stl",
        ),
        FileFormat(
            "ply",
            ".ply",
            "3D mesh of the folded state (binary PLY)",
            "model",
            _ALL,
            "curvefold.io._model_files:model_ply",
            "application/octet-stream",
        ),
        FileFormat(
            "step",
            ".step",
            "STEP (AP214) of thick panels (--thickness on rigid panels): a closed B-rep solid per "
            "panel named as in the cut list, in the output units (millimetres by default)",
            "solids",
            _S,
            "curvefold.io._step:write_thick_step",
            "model/step",
            "OCP",
            "step",
            optional=True,
        ),
        FileFormat(
            "gif",
            ".gif",
            "animation of the folding motion, flat to the design angle",
            "motion",
            _S,
            # frames drawn with matplotlib's font and Pillow
            "curvefold.io._gif:write_gif",
            "image/gif",
            "matplotlib",
            "plot",
        ),
    )
}
#: Every format, in the order files are written and listed.
FORMATS: Mapping[str, FileFormat] = MappingProxyType(_FORMATS)


def register_writer(name: str, writer: str | Callable[..., Any]) -> None:
    """Give a declared format its writer: how a layer above io adds the writer it owns.

    Parameters
    ----------
    name : str
        A format of :data:`FORMATS` declared without a writer (or with this one: registering
        again changes nothing).
    writer : str or callable
        The function, called as the format's family calls its writers, or its qualified
        name ``"module:function"``, imported when a file is first written.

    Raises
    ------
    InputError
        An unknown format, one whose writer is another, or a writer that is neither.

    Examples
    --------
    >>> register_writer("svg", "curvefold.io._svg:write_svg")  # its own: nothing changes
    >>> register_writer("svg", "a:b")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: writer of 'svg' is 'curvefold.io._svg:write_svg' already,
    cannot register 'a:b'
    """
    f = _FORMATS.get(name)
    if f is None:
        raise InputError(
            f"name must be a format of the registry ({', '.join(_FORMATS)}), got {name!r}"
        )
    if not (callable(writer) or (isinstance(writer, str) and writer.count(":") == 1)):
        raise InputError(f"writer must be a function or 'module:function', got {writer!r}")
    if f.writer is not None and f.writer != writer:
        raise InputError(f"writer of {name!r} is {f.writer!r} already, cannot register {writer!r}")
    _FORMATS[name] = replace(f, writer=writer)


#: What each family of formats writes, as the subject of a sentence in messages.
FAMILIES: Mapping[str, str] = MappingProxyType(
    {
        "pattern": "the crease patterns are",
        "guide": "the assembly guide is",
        "fold": "the FOLD file is",
        "model": "the 3D models are",
        "motion": "the GIF of the folding motion is",
        "solids": "the STEP file of thick panels is",
    }
)


def formats_of(family: str) -> tuple[str, ...]:
    """Names of the formats of one family, in registry order.

    Examples
    --------
    >>> formats_of("pattern")
    ('svg', 'dxf', 'pdf')
    """
    return tuple(name for name, f in FORMATS.items() if f.family == family)


def default_formats(kind: str) -> tuple[str, ...]:
    """Every format written for a kind of design: its default ``formats``.

    Examples
    --------
    >>> default_formats("crease")
    ('svg', 'dxf', 'pdf', 'fold', 'glb', 'obj', '3dm', 'stl', 'ply')
    """
    return tuple(name for name, f in FORMATS.items() if kind in f.kinds)


def check_formats(
    formats: str | Iterable[str], family: str, *, name: str = "formats"
) -> tuple[str, ...]:
    """A non-empty selection of the formats of ``family``, duplicates dropped.

    Raises
    ------
    InputError
        An empty selection or a name outside the family.
    """
    allowed = formats_of(family)
    formats = (formats,) if isinstance(formats, str) else tuple(formats)
    bad = [f for f in formats if f not in allowed]
    if bad or not formats:
        raise InputError(f"{name} must be a non-empty selection of {allowed}, got {formats!r}")
    return tuple(dict.fromkeys(formats))


def check_kind(formats: Iterable[str], kind: str, where: str) -> None:
    """Refuse an unknown format, or one that is not written for ``kind`` with the reason.

    Examples
    --------
    >>> check_kind(["gif"], "crease", "formats")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: formats: "gif" is not written for a crease design: the GIF
    of the folding motion is written for vault, tube and block designs
    """
    for name in formats:
        f = FORMATS.get(name)
        if f is None:
            raise InputError(f"{where}: unknown format {name!r} (allowed: {', '.join(FORMATS)})")
        if kind not in f.kinds:
            kinds = (
                ", ".join(f.kinds[:-1]) + f" and {f.kinds[-1]}" if len(f.kinds) > 1 else f.kinds[0]
            )
            raise InputError(
                f'{where}: "{name}" is not written for a {kind} design: '
                f"{FAMILIES[f.family]} written for {kinds} designs"
            )


def missing_dependencies(formats: Iterable[str]) -> list[str]:
    """For each requested format whose optional package is not installed, one line saying how to
    get it."""
    out = []
    for name in formats:
        f = FORMATS[name]
        if f.optional:
            continue  # left out, with a note (formats_left_out)
        if f.dependency is not None and importlib.util.find_spec(f.dependency) is None:
            out.append(f"{name} needs {f.dependency}: pip install 'curvefold[{f.extra}]'")
    return out


def formats_left_out(formats: Iterable[str]) -> list[str]:
    """For each requested optional format (:attr:`FileFormat.optional`) whose package is not
    installed, one line saying it is left out and how to get it."""
    out = []
    for name in formats:
        f = FORMATS[name]
        if f.optional and f.dependency and importlib.util.find_spec(f.dependency) is None:
            out.append(
                f"{name} left out (it needs {f.dependency}: pip install 'curvefold[{f.extra}]')"
            )
    return out


_OUT = PatternOutput()  # the defaults of the crease-pattern files
#: The ``[output]`` parameters of a design (the crease pattern's defaults are
#: :class:`PatternOutput`'s).
OUTPUT_SPECS: tuple[Spec, ...] = (
    Spec(
        "units",
        "choice",
        _OUT.units,
        choices=("mm", "cm", "m", "in"),
        help="unit of the crease-pattern page lengths and scale, and of the STL (which has "
        "the pattern's scale, stated in its header)",
        label="units of the printed files",
    ),
    Spec(
        "scale",
        "real",
        None,
        Interval.parse("(0, inf)"),
        "output units per model unit",
        help="crease-pattern scale (default: fit the largest sheet to the page)",
        label="print scale",
    ),
    Spec(
        "page",
        "page",
        _OUT.page,
        Interval.parse("(0, 10000]"),
        "mm",
        choices=tuple(PAGES),
        help="page of the crease patterns",
        label="page size",
    ),
    Spec(
        "glue_tabs",
        "flag",
        _OUT.glue_tabs,
        help="draw glue tabs along the seams of the crease patterns",
        label="glue tabs",
    ),
    Spec(
        "rulings",
        "flag",
        _OUT.rulings,
        help="draw the rulings on the crease patterns (for scoring or engraving)",
        label="rulings drawn",
    ),
    Spec(
        "cutter",
        "choice",
        _OUT.cutter,
        choices=tuple(CUTTERS),
        help="colour convention of the crease patterns' layers: print (paper), laser (a colour "
        "per operation), service (red cut, blue score)",
        label="cutter convention",
    ),
    Spec(
        "perforation",
        "real",
        None,
        Interval.parse("(0, 100]"),
        "mm",
        help="draw the creases as cut dashes this long, for machines that only cut (default: "
        "score lines)",
        label="perforation dash",
    ),
    Spec(
        "perforation_gap",
        "real",
        1.0,
        Interval.parse("(0, 100]"),
        "mm",
        help="gap between the dashes of perforated creases",
        label="perforation gap",
    ),
    Spec(
        "kerf",
        "real",
        _OUT.kerf,
        Interval.parse("[0, 5]"),
        "mm",
        help="width the cutter removes: the cut outlines move out by half of it, so parts keep "
        "their size",
        label="kerf",
    ),
    Spec(
        "formats",
        "formats",
        None,
        choices=tuple(FORMATS),
        help="files to write besides the report (default: every format the design's kind writes)",
        label="file formats",
    ),
)


#: Shortest a crease may be drawn, in mm: the 10 mm scale bar every page carries. Shorter, its
#: pattern is at most 40 widths of its 0.25 mm lines long, which merge into a blot.
MIN_DRAWN_MM = 10.0


def check_scale(scale: float | None, units: str, length: float, where: str) -> float | None:
    """The print scale of a design whose crease is ``length`` model units long, or the error saying
    it draws too small.

    The scale's spec bounds it by > 0; what a page and a line width can show bounds it
    further: the crease must be drawn at least :data:`MIN_DRAWN_MM` long (a scale too large
    for the page is refused when the sheets are laid out, naming the sheet and the page).

    Examples
    --------
    >>> check_scale(50.0, "mm", 6.0, "scale")
    50.0
    >>> check_scale(0.001, "mm", 6.0, "scale")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: scale: 0.001 mm per model unit draws the 6-unit crease
    0.006 mm long, shorter than the 10 mm scale bar: use a scale of at least 1.67 mm per unit (or
    leave it out to fit the page)
    """
    if scale is None:
        return None
    drawn = scale * length * mm_per_unit(units)
    if not drawn >= MIN_DRAWN_MM:
        least = MIN_DRAWN_MM / (length * mm_per_unit(units))
        raise InputError(
            f"{where}: {scale:g} {units} per model unit draws the {length:g}-unit "
            f"crease {drawn:.3g} mm long, shorter than the {MIN_DRAWN_MM:g} mm scale bar: use "
            f"a scale of at least {least:.3g} {units} per unit (or leave it out to fit the "
            "page)",
            parameter="scale",
        )
    return scale
