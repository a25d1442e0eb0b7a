"""A small PDF writer for vector pages in millimetres, with named layers (optional content).

What the crease patterns and the assembly guide need and no more: pages of any size,
polylines stroked with a colour, width and dash pattern, filled polygons, and lines of
text in DejaVu Sans (embedded, a subset of the glyphs used: :mod:`curvefold.io._pdf_font`),
each drawn on a named layer. Layers are PDF optional content groups, which Acrobat,
Illustrator, Inkscape and laser software list as layers; a layer may be marked not to print
(the page frames).

Coordinates are millimetres from the page's lower-left corner, y up; line widths and dash
lengths are millimetres too (each page's content starts by scaling points to mm). Text is
encoded in WinAnsi (Windows-1252): a character outside it is written as ``?``. Content
streams are compressed; the file is written atomically.

Examples
--------
>>> doc = PdfDocument(title="a square", layers=["cut"])
>>> page = doc.page(210.0, 297.0)
>>> page.stroke(
...     [np.array([[10.0, 10.0], [20.0, 10.0], [20.0, 20.0]])],
...     "#ff0000",
...     0.25,
...     closed=True,
...     layer="cut",
... )
>>> doc.to_bytes()[:8]
b'%PDF-1.5'
"""

from __future__ import annotations

import math
import os
import zlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..kernel._errors import InputError
from ..kernel._text import one_line
from ._atomic import atomic_write
from ._pdf_font import DESCRIPTOR, FONT_NAME, WIDTHS, encode, font_program, subset_tag
from ._tables import CREATOR, rgb8

__all__ = ["PdfDocument", "PdfPage", "PdfText", "text_advance", "advance_units"]

_PT_PER_MM = 72.0 / 25.4


def text_advance(text: str, size: float) -> float:
    """Width of ``text`` set in DejaVu Sans of em height ``size`` (the unit of ``size``).

    Examples
    --------
    >>> round(text_advance("S0", 10.0), 3)
    12.71
    >>> text_advance("", 10.0)
    0.0
    """
    return advance_units(text) * size / 1000.0


def advance_units(text: str) -> int:
    """Width of ``text`` set in DejaVu Sans, thousandths of the em (the font's advance widths,
    :data:`curvefold.io._pdf_font.WIDTHS`; a character the pages cannot set is a ``?``): an
    integer, so the width of a line is the sum of its words' and spaces' (:func:`text_advance`
    scales it).

    Examples
    --------
    >>> advance_units("S0"), advance_units("S") + advance_units("0"), advance_units("κ")
    (1271, 1271, 531)
    """
    unknown = WIDTHS["?"]
    return sum(WIDTHS.get(c, unknown) for c in text)


def _num(v: float) -> str:
    """A number for a content stream: at most 4 decimals, never ``-0``."""
    return _number(float(v))


@lru_cache(maxsize=4096)
def _number(v: float) -> str:
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


@lru_cache(maxsize=1024)
def _colour(code: str) -> str:
    return " ".join(_num(c / 255.0) for c in rgb8(code))


def _string(text: str) -> bytes:
    raw = encode(one_line(text))
    return b"(" + raw.replace(b"\\", b"\\\\").replace(b"(", b"\\(").replace(b")", b"\\)") + b")"


@lru_cache(maxsize=256)
def _path(points: int, closed: bool) -> str:
    """Path construction operators of a polyline of ``points`` points, with a ``%.3f`` (mm to the
    micrometre) for each of its coordinates (:func:`_drawn` fills them in)."""
    if points == 0:
        return ""
    return "%.3f %.3f m\n" + "%.3f %.3f l\n" * (points - 1) + ("h\n" if closed else "")


def _drawn(operators: list[str], polylines: Sequence[np.ndarray]) -> str:
    """``operators`` (one string for each polyline, holding its :func:`_path` and no other ``%``)
    with the coordinates of the polylines (each (n, 2), mm) filled in, all at once."""
    drawn = [p for p in polylines if len(p)]
    coordinates = np.concatenate(drawn, axis=0, dtype=float).ravel().tolist() if drawn else []
    return "".join(operators) % tuple(coordinates)


#: Where a line of text's (x, y) is along its baseline, as a fraction of its width.
_ANCHORS = {"start": 0.0, "center": 0.5, "end": 1.0}


@dataclass(frozen=True)
class PdfText:
    """One line of text to draw on a page (:meth:`PdfPage.text`).

    Attributes
    ----------
    text : str
    x, y : float
        The point (mm) the baseline goes through.
    size : float
        Em height in mm.
    colour : str
        ``"#rrggbb"``.
    angle : float
        Direction of the baseline in degrees, counter-clockwise from +x.
    anchor : str
        Where (x, y) is along the baseline: ``"start"``, ``"center"`` or ``"end"``.
    layer : str or None
        The layer it is drawn on; None for none.

    Examples
    --------
    >>> PdfText("S1", 105.0, 20.0, 4.0, "#000000", anchor="start").anchor
    'start'
    >>> PdfText("S1", 105.0, 20.0, 4.0, "#000000", anchor="left")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: anchor must be 'start', 'center' or 'end', got 'left'
    """

    text: str
    x: float
    y: float
    size: float
    colour: str
    angle: float = 0.0
    anchor: str = "center"
    layer: str | None = None

    def __post_init__(self) -> None:
        if self.anchor not in _ANCHORS:
            raise InputError(f"anchor must be 'start', 'center' or 'end', got {self.anchor!r}")


class PdfPage:
    """One page being drawn (see :meth:`PdfDocument.page`)."""

    def __init__(self, document: PdfDocument, width: float, height: float) -> None:
        self.size = (float(width), float(height))
        self._doc = document
        self._parts: list[str | bytes] = [
            f"{_num(_PT_PER_MM)} 0 0 {_num(_PT_PER_MM)} 0 0 cm\n1 J 1 j\n"
        ]
        self._layer: str | None = None

    def _on(self, layer: str | None) -> None:
        """Start drawing on ``layer`` (ending the one before)."""
        if layer == self._layer:
            return
        if self._layer is not None:
            self._parts.append("EMC\n")
        if layer is not None:
            self._parts.append(f"/OC /{self._doc.layer_tag(layer)} BDC\n")
        self._layer = layer

    def stroke(
        self,
        polylines: Sequence[np.ndarray],
        colour: str,
        width: float,
        *,
        dashes: Sequence[float] = (),
        closed: bool | Sequence[bool] = False,
        layer: str | None = None,
        cap: str = "butt",
    ) -> None:
        """Stroke polylines (each (n, 2), mm) with a colour, a width in mm and a dash pattern in
        mm."""
        closed = [closed] * len(polylines) if isinstance(closed, bool) else list(closed)
        self._on(layer)
        pattern = " ".join(_num(d) for d in dashes)
        self._parts.append(
            f"q {_colour(colour)} RG {_num(width)} w [{pattern}] 0 d "
            f"{dict(butt=0, round=1)[cap]} J\n"
        )
        self._parts.append(_drawn([_path(len(p), c) for p, c in zip(polylines, closed)], polylines))
        self._parts.append("S Q\n")

    def fill(
        self, polygons: Sequence[np.ndarray], colour: str, *, layer: str | None = None
    ) -> None:
        """Fill closed polygons (each (n, 2), mm) with a colour (non-zero winding)."""
        self._on(layer)
        self._parts.append(f"q {_colour(colour)} rg\n")
        self._parts.append(_drawn([_path(len(p), True) for p in polygons], polygons))
        self._parts.append("f Q\n")

    def paint(
        self,
        paths: Sequence[np.ndarray],
        fills: Sequence[str | None],
        strokes: Sequence[str],
        widths: Sequence[float],
        *,
        layer: str | None = None,
    ) -> None:
        """Paths (each (n, 2), mm) one after the other, each with its own fill (None: an open
        line, stroked only), stroke colour and width in mm, in the order given (a painter's
        order)."""
        self._on(layer)
        self._parts.append("q 0 J\n")
        self._parts.append(
            _drawn(
                [
                    f"{_colour(stroke)} RG {_num(width)} w {_colour(fill)} rg "
                    f"{_path(len(path), True)}B\n"
                    if fill is not None
                    else f"{_colour(stroke)} RG {_num(width)} w {_path(len(path), False)}S\n"
                    for path, fill, stroke, width in zip(paths, fills, strokes, widths)
                ],
                paths,
            )
        )
        self._parts.append("Q\n")

    def text(self, line: PdfText) -> None:
        """One line of DejaVu Sans of em height ``line.size`` mm, its baseline through
        (``line.x``, ``line.y``) turned by ``line.angle`` degrees, on ``line.layer``."""
        self._on(line.layer)
        text = one_line(line.text)
        self._doc.characters.update(encode(text))
        shift = _ANCHORS[line.anchor] * text_advance(text, line.size)
        a = math.radians(line.angle)
        c, s = math.cos(a), math.sin(a)
        x0, y0 = line.x - shift * c, line.y - shift * s
        self._parts.append(
            f"BT {_colour(line.colour)} rg /F1 {_num(line.size)} Tf {_num(c)} {_num(s)} "
            f"{_num(-s)} {_num(c)} {_num(x0)} {_num(y0)} Tm "
        )
        self._parts.append(_string(line.text) + b" Tj ET\n")

    def content(self) -> bytes:
        """The page's content stream (uncompressed)."""
        self._on(None)
        return b"".join(p.encode("ascii") if isinstance(p, str) else p for p in self._parts)


class PdfDocument:
    """A PDF being built page by page; :meth:`save` writes it.

    Parameters
    ----------
    title : str
        The document's title (its information dictionary).
    layers : sequence of str
        The layers (optional content groups) pages draw on, in the order readers list them.
    hidden_in_print : sequence of str
        Layers shown on screen but not printed.
    """

    def __init__(
        self, *, title: str, layers: Sequence[str] = (), hidden_in_print: Sequence[str] = ()
    ) -> None:
        self.title = one_line(title)
        self.layers = list(dict.fromkeys(layers))
        self.hidden_in_print = [name for name in hidden_in_print if name in self.layers]
        self.pages: list[PdfPage] = []
        #: The Windows-1252 codes of the text set so far (the embedded font's glyphs).
        self.characters: set[int] = set()

    def layer_tag(self, name: str) -> str:
        """The resource name of a layer (``oc1``…)."""
        if name not in self.layers:
            raise InputError(f"layer must be one of the document's {self.layers}, got {name!r}")
        return f"oc{self.layers.index(name) + 1}"

    def page(self, width: float, height: float) -> PdfPage:
        """A new page of width × height mm, added at the end."""
        if not (math.isfinite(width) and math.isfinite(height) and width > 0 and height > 0):
            raise InputError(
                f"a page must have a positive finite size in mm, got {width!r} × {height!r}"
            )
        page = PdfPage(self, width, height)
        self.pages.append(page)
        return page

    def to_bytes(self) -> bytes:
        """The whole file."""
        objects: list[bytes] = []

        def add(body: bytes | str) -> int:
            objects.append(body.encode("latin-1") if isinstance(body, str) else body)
            return len(objects)

        catalog, pages_id = add(b""), add(b"")  # filled in at the end
        font = self._font(add)
        groups = [
            add(f"<< /Type /OCG /Name {_string(name).decode('latin-1')} >>") for name in self.layers
        ]
        properties = " ".join(f"/oc{i + 1} {g} 0 R" for i, g in enumerate(groups))
        kids = []
        for page in self.pages:
            data = zlib.compress(page.content(), 6)
            stream = add(
                b"<< /Length %d /Filter /FlateDecode >>\nstream\n" % len(data)
                + data
                + b"\nendstream"
            )
            w, h = (_num(side * _PT_PER_MM) for side in page.size)
            kids.append(
                add(
                    f"<< /Type /Page /Parent {pages_id} 0 R /MediaBox [0 0 {w} {h}] "
                    f"/Contents {stream} 0 R /Resources << /Font << /F1 {font} 0 R >> /Properties "
                    f"<< {properties} >> >> >>"
                )
            )
        objects[pages_id - 1] = (
            f"<< /Type /Pages /Kids [{' '.join(f'{k} 0 R' for k in kids)}] /Count {len(kids)} >>"
        ).encode()
        refs = " ".join(f"{g} 0 R" for g in groups)
        for name in self.hidden_in_print:  # shown on screen, left out when printed
            g = groups[self.layers.index(name)]
            objects[g - 1] = objects[g - 1][:-2] + b"/Usage << /Print << /PrintState /OFF >> >> >>"
        usage = (
            f" /AS [<< /Event /Print /Category [/Print] /OCGs [{refs}] >>]"
            if self.hidden_in_print
            else ""
        )
        oc = (
            f" /OCProperties << /OCGs [{refs}] /D << /Order [{refs}] /ON [{refs}]{usage} >> >>"
            if groups
            else ""
        )
        objects[catalog - 1] = f"<< /Type /Catalog /Pages {pages_id} 0 R{oc} >>".encode()
        info = add(
            b"<< /Title "
            + _string(self.title)
            + b" /Creator "
            + _string(CREATOR)
            + b" /Producer "
            + _string(CREATOR)
            + b" >>"
        )
        out = bytearray(b"%PDF-1.5\n%\xe2\xe3\xcf\xd3\n")
        offsets = []
        for number, body in enumerate(objects, start=1):
            offsets.append(len(out))
            out += b"%d 0 obj\n" % number + body + b"\nendobj\n"
        xref = len(out)
        out += b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1)
        out += b"".join(b"%010d 00000 n \n" % o for o in offsets)
        out += b"trailer\n<< /Size %d /Root %d 0 R /Info %d 0 R >>\nstartxref\n%d\n%%%%EOF\n" % (
            len(objects) + 1,
            catalog,
            info,
            xref,
        )
        return bytes(out)

    def _font(self, add: Callable[[bytes | str], int]) -> int:
        """Add the font's objects (its program, descriptor and dictionary); its number."""
        codes = sorted(self.characters) or [32]
        text = bytes(codes).decode("cp1252")
        program = font_program(text)
        name = FONT_NAME if program is None else f"{subset_tag(text)}+{FONT_NAME}"
        metrics = " ".join(
            f"/{key} [{' '.join(map(str, value))}]"
            if isinstance(value, tuple)
            else f"/{key} {value}"
            for key, value in DESCRIPTOR.items()
        )
        embedded = ""
        if program is not None:
            data = zlib.compress(program, 9)
            stream = add(
                b"<< /Length %d /Length1 %d /Filter /FlateDecode >>\nstream\n"
                % (len(data), len(program))
                + data
                + b"\nendstream"
            )
            embedded = f" /FontFile2 {stream} 0 R"
        descriptor = add(f"<< /Type /FontDescriptor /FontName /{name} {metrics}{embedded} >>")
        first, last = codes[0], codes[-1]
        widths = " ".join(
            str(advance_units(bytes([c]).decode("cp1252", errors="replace")))
            for c in range(first, last + 1)
        )
        return add(
            f"<< /Type /Font /Subtype /TrueType /BaseFont /{name} /FirstChar {first} "
            f"/LastChar {last} /Widths [{widths}] /Encoding /WinAnsiEncoding "
            f"/FontDescriptor {descriptor} 0 R >>"
        )

    def save(self, path: str | os.PathLike) -> Path:
        """Write the file atomically; returns its path."""
        return atomic_write(path, self.to_bytes())
