"""The font of the PDF pages: DejaVu Sans, embedded as a subset of the glyphs a document uses.

A print shop's PDF tools set text in the fonts the file carries: a standard font such as
Helvetica, which a file only names, comes out in whatever the shop's software substitutes,
with other widths. The pages are set in DejaVu Sans (the font matplotlib ships, under the
Bitstream Vera licence, which allows embedding; its OS/2 ``fsType`` is 0, installable), the
font the SVG files name first. Its advance widths (:data:`WIDTHS`, thousandths of the em,
rounded from its 2048 units per em) are written here, so the layout of a page never depends on
what is installed; the PDF writes the same numbers as the font's ``/Widths``.

The font program is a subset (fontTools, which matplotlib depends on) of the glyphs a document
uses, embedded as ``/FontFile2``: 4.9 kB (3.3 kB compressed) for the paper vault's crease
pattern, 6.2 kB (4.2 kB) for its assembly guide. Without fontTools or the font file (an install
without matplotlib), :func:`font_program` answers None and the document names DejaVu Sans
without embedding it, with the same widths.

Examples
--------
>>> WIDTHS["S"], WIDTHS["0"], WIDTHS["·"]
(635, 636, 318)
"""

from __future__ import annotations

import hashlib
import importlib.util
import io
from functools import lru_cache
from pathlib import Path

__all__ = ["FONT_NAME", "WIDTHS", "DESCRIPTOR", "encode", "font_program", "font_path", "subset_tag"]

#: PostScript name of the font.
FONT_NAME = "DejaVuSans"

# Advance widths of DejaVu Sans 2.35 (thousandths of the em) for the Windows-1252 codes 32–255;
# 0 for DEL and the five codes Windows-1252 leaves undefined (never set).
_TABLE = """
318 401 460 838 636 950 780 275 390 390 500 838 318 361 318 337 636 636 636 636 636 636 636 636
636 636 337 337 838 838 838 531 1000 684 686 698 770 632 575 775 752 295 295 656 557 863 748 787
603 787 695 635 611 732 684 989 685 611 685 390 337 390 838 500 500 613 635 550 635 615 352 635
634 278 278 579 278 974 634 612 635 635 411 521 392 634 592 818 592 592 525 636 337 636 838 0
636 0 318 352 518 1000 500 500 500 1342 635 400 1070 0 685 0 0 318 318 518 518 590 500 1000 500
1000 521 400 1023 0 525 611 318 401 636 636 636 636 337 500 500 1000 471 612 838 361 1000 500 500
838 401 401 500 636 636 318 500 401 471 612 969 969 969 531 684 684 684 684 684 684 974 698 632
632 632 632 295 295 295 295 775 748 787 787 787 787 787 838 787 732 732 732 732 611 605 630 613
613 613 613 613 613 982 550 615 615 615 615 278 278 278 278 612 634 612 612 612 612 612 838 612
634 634 634 634 592 635 592
"""
_CODES = [bytes([code]) for code in range(32, 256)]
#: Advance width (thousandths of the em) of each character the pages can set.
WIDTHS: dict[str, int] = {
    code.decode("cp1252"): int(width)
    for code, width in zip(_CODES, _TABLE.split())
    if code not in (b"\x7f", b"\x81", b"\x8d", b"\x8f", b"\x90", b"\x9d")
}
#: The font descriptor's metrics (thousandths of the em): bounding box, ascent and descent
#: (hhea), cap height (the top of H), stem width, and flags (32: non-symbolic).
DESCRIPTOR = {
    "FontBBox": (-1021, -463, 1793, 1232),
    "Ascent": 928,
    "Descent": -236,
    "CapHeight": 729,
    "ItalicAngle": 0,
    "StemV": 80,
    "Flags": 32,
}


def encode(text: str) -> bytes:
    """``text`` in Windows-1252 (the document's encoding): a character outside it is ``?``.

    Examples
    --------
    >>> encode("S1 · 90°, κ")
    b'S1 \\xb7 90\\xb0, ?'
    """
    return text.encode("cp1252", errors="replace")


def font_path() -> Path | None:
    """The file of DejaVu Sans in matplotlib's data (found without importing matplotlib), or
    None."""
    spec = importlib.util.find_spec("matplotlib")
    if spec is None or spec.origin is None:
        return None
    path = Path(spec.origin).parent / "mpl-data" / "fonts" / "ttf" / "DejaVuSans.ttf"
    return path if path.is_file() else None


def subset_tag(characters: str) -> str:
    """The six capital letters that name a subset (``ABCDEF+DejaVuSans``), from its characters.

    Examples
    --------
    >>> subset_tag("S01"), len(subset_tag("abc"))
    ('FPBSFW', 6)
    """
    digest = hashlib.sha256("".join(sorted(set(characters))).encode("utf-8")).digest()
    return "".join(chr(65 + b % 26) for b in digest[:6])


def font_program(characters: str) -> bytes | None:
    """The TrueType program of DejaVu Sans cut down to the glyphs of ``characters`` (and
    ``.notdef``), without hinting or layout tables; None when fontTools or the font is not
    installed. The same characters give the same bytes."""
    return _program("".join(sorted(set(characters))))


@lru_cache(maxsize=32)
def _program(characters: str) -> bytes | None:
    path = font_path()
    if path is None or importlib.util.find_spec("fontTools") is None:
        return None
    from fontTools import subset
    from fontTools.ttLib import TTFont

    options = subset.Options()
    options.hinting = False  # screens and printers render the outlines unhinted as well
    options.layout_features = []
    options.name_IDs = [0, 1, 2, 3, 4, 5, 6]  # copyright, names and version
    options.notdef_outline = True
    options.drop_tables += ["FFTM", "GSUB", "GPOS", "GDEF", "kern"]
    font = TTFont(_font_bytes(path), recalcTimestamp=False)
    subsetter = subset.Subsetter(options)
    subsetter.populate(text=characters)
    subsetter.subset(font)
    out = io.BytesIO()
    font.save(out)
    return out.getvalue()


def _font_bytes(path: Path) -> io.BytesIO:
    return io.BytesIO(_read(str(path)))


@lru_cache(maxsize=1)
def _read(path: str) -> bytes:
    return Path(path).read_bytes()
