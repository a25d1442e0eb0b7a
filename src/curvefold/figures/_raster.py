"""Raster primitives under the canvas: the font, text runs, inks, ticks, strokes and PNG files.

DejaVu Sans is the font matplotlib ships, found on disk by :func:`font_file` (matplotlib
itself is never imported); text may hold subscripts written ``w_L`` or ``p_{xy}``, set
smaller and lower. Colours become Pillow's inks (:func:`inks`, :func:`viridis`), axes get
round ticks (:func:`nice_ticks`), polylines are stroked with round joints where they bend
and cut into dashes, and a finished picture is written as an unfiltered PNG
(:func:`png_bytes`).
"""

from __future__ import annotations

import functools
import importlib.util
import os
import re
import struct
import zlib
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..io._atomic import atomic_write
from ..io._tables import rgb8

if TYPE_CHECKING:  # pragma: no cover
    from PIL import Image

__all__ = [
    "font_file",
    "nice_ticks",
    "viridis",
    "inks",
    "png_bytes",
    "write_png",
]

#: Viridis at t = 0, 0.1, ..., 1 (matplotlib's colour map, interpolated linearly between them).
_VIRIDIS = (
    "#440154",
    "#482475",
    "#414487",
    "#355f8d",
    "#2a788e",
    "#21918c",
    "#22a884",
    "#44bf70",
    "#7ad151",
    "#bddf26",
    "#fde725",
)
#: A subscript: ``_x`` or ``_{...}``.
_SUBSCRIPT = re.compile(r"_(\{[^}]*\}|\w)")


def font_file() -> Path:
    """The DejaVu Sans that matplotlib ships (the font of the figures), found without importing
    matplotlib.

    Raises
    ------
    ImportError
        Without matplotlib.

    Examples
    --------
    >>> font_file().name
    'DejaVuSans.ttf'
    """
    spec = importlib.util.find_spec("matplotlib")
    if spec is None or not spec.submodule_search_locations:
        raise ImportError(
            "curvefold's pictures need matplotlib's font: pip install 'curvefold[plot]'"
        )
    return (
        Path(next(iter(spec.submodule_search_locations)))
        / "mpl-data"
        / "fonts"
        / "ttf"
        / "DejaVuSans.ttf"
    )


@functools.lru_cache(maxsize=32)
def _font(pixels: int):
    from PIL import ImageFont

    return ImageFont.truetype(str(font_file()), max(pixels, 1))


@functools.lru_cache(maxsize=1024)
def _length(pixels: int, piece: str) -> float:
    """Advance width (pixels) of ``piece`` in DejaVu Sans at ``pixels`` (tick labels and legends
    repeat)."""
    return _font(pixels).getlength(piece)


def nice_ticks(lo: float, hi: float, count: int = 6) -> np.ndarray:
    """Round tick values (1, 2 or 5 × 10^k apart) inside [lo, hi], about ``count`` of them.

    Examples
    --------
    >>> nice_ticks(-11.7, 11.7).tolist()
    [-10.0, -5.0, 0.0, 5.0, 10.0]
    >>> nice_ticks(0.059, 0.081).tolist()
    [0.06, 0.065, 0.07, 0.075, 0.08]
    >>> nice_ticks(1.0, 1.0).tolist()  # an empty range: its one value
    [1.0]
    """
    if not hi > lo:
        return np.array([float(lo)])
    raw = (hi - lo) / max(count - 1, 1)
    k = np.floor(np.log10(raw))
    step = min(
        (m * 10**k for m in (1.0, 2.0, 5.0, 10.0) if m * 10**k >= raw * 0.999),
        default=10 ** (k + 1),
    )
    ticks = np.arange(np.ceil(lo / step - 1e-9), np.floor(hi / step + 1e-9) + 1) * step
    return np.round(ticks, int(max(0, -k + 2))) + 0.0


def tick_label(value: float, step: float) -> str:
    """A tick's text: as many decimals as its step needs, a real minus sign."""
    decimals = int(max(0, -np.floor(np.log10(step) + 1e-9))) if step > 0 else 0
    if step > 0 and abs(round(step * 10**decimals) - step * 10**decimals) > 1e-6:
        decimals += 1  # 0.25, 2.5
    return f"{value:.{decimals}f}".replace("-", "−")


def viridis(t: np.ndarray) -> np.ndarray:
    """RGB in [0, 1], shape (..., 3), of viridis at ``t`` (..., ) in [0, 1] (clipped)."""
    table = np.array([rgb8(c) for c in _VIRIDIS], float) / 255
    x = np.clip(np.asarray(t, float), 0, 1) * (len(table) - 1)
    return np.stack([np.interp(x, np.arange(len(table)), table[:, c]) for c in range(3)], axis=-1)


def inks(rgb: np.ndarray) -> list[int]:
    """Pillow's ink integers of opaque RGB colours (..., 3) in [0, 1], for drawing on an RGB
    image."""
    c = (
        np.round(255 * np.clip(np.asarray(rgb, float)[..., :3], 0, 1))
        .astype(np.int64)
        .reshape(-1, 3)
    )
    packed = c[:, 0] | c[:, 1] << 8 | c[:, 2] << 16 | 255 << 24
    return packed.astype(np.uint32).view(np.int32).tolist()


def _rgba(color) -> tuple[int, ...]:
    """An RGBA tuple of 0-255 ints of ``"#rrggbb"`` or RGB(A) floats in [0, 1]."""
    if isinstance(color, str):
        return (*rgb8(color), 255)
    c = [int(round(255 * float(v))) for v in color]
    return tuple(c) if len(c) == 4 else (*c, 255)


def _runs(text: str) -> list[tuple[str, bool]]:
    """``text`` as (piece, is subscript) runs."""
    out, at = [], 0
    for match in _SUBSCRIPT.finditer(text):
        out += [(text[at : match.start()], False), (match.group(1).strip("{}"), True)]
        at = match.end()
    return [(piece, sub) for piece, sub in out + [(text[at:], False)] if piece]


def _line(draw, points: np.ndarray, ink: tuple[int, ...], width: int) -> None:
    """A polyline (n, 2) of ``width`` pixels; wider than 4 with round joints (Pillow's) where it
    bends.

    A joint fills the notch a bend leaves at the outer side of a wide line. Where the line
    turns so little that the notch is under a quarter pixel deep (a smooth curve's samples),
    it is left out; an opaque line draws its bends' joints with their two segments (drawn
    again, the same), a translucent one its joints at every vertex, as Pillow does.
    """
    if width <= 4 or ink[3] < 255 or len(points) < 3:
        draw.line(
            points.ravel().tolist(), fill=ink, width=width, joint="curve" if width > 4 else None
        )
        return
    step = np.diff(points, axis=0)
    heading = np.arctan2(step[:, 1], step[:, 0])
    turn = np.abs((np.diff(heading) + np.pi) % (2 * np.pi) - np.pi)
    draw.line(points.ravel().tolist(), fill=ink, width=width)
    for k in (np.flatnonzero(turn * width / 2 > 0.25) + 1).tolist():
        draw.line(points[k - 1 : k + 2].ravel().tolist(), fill=ink, width=width, joint="curve")


def _dashed(points: np.ndarray, on: float, off: float) -> list[np.ndarray]:
    """The dashes (each (k, 2)) of a polyline (n, 2): ``on`` drawn, ``off`` left out, along its
    length (pixels)."""
    step = np.linalg.norm(np.diff(points, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(step)])
    period = on + off
    if s[-1] <= 0 or period <= 0:
        return [points]
    starts = np.arange(0.0, s[-1], period)
    stops = np.minimum(starts + on, float(s[-1]))
    # (D, 2, 2)
    ends = np.stack(
        [np.interp(np.stack([starts, stops], axis=-1), s, points[:, c]) for c in range(2)], axis=-1
    )
    # vertices strictly within
    inside = zip(
        np.searchsorted(s, starts, "right").tolist(), np.searchsorted(s, stops, "left").tolist()
    )
    return [np.concatenate([end[:1], points[i:j], end[1:]]) for end, (i, j) in zip(ends, inside)]


def png_bytes(picture: Image.Image, *, level: int = 3) -> bytes:
    """An RGB picture as the bytes of a PNG file: 8-bit RGB, every row unfiltered, deflated at zlib
    ``level``.

    Pillow's PNG encoder picks one of five filters for every row of an RGB picture; on
    drawings of flat colours that costs about five times the time and compresses worse
    (the paper's vault's five pictures: 0.19 CPU-s and 440 kB at level 6, unfiltered at
    level 3 0.04 CPU-s and 453 kB). The pixels are the same (PNG is lossless).
    """
    width, height = picture.size
    # each row: filter type 0 (none), then its pixels
    rows = np.zeros((height, 1 + 3 * width), np.uint8)
    rows[:, 1:] = np.frombuffer(
        (picture if picture.mode == "RGB" else picture.convert("RGB")).tobytes(), np.uint8
    ).reshape(height, -1)

    def chunk(kind: bytes, data: bytes) -> bytes:
        return (
            struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
        )

    # 8 bits, truecolour, deflate, no filter choice, no interlace
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    data = zlib.compress(rows, level)  # type: ignore[arg-type]  # an array is a buffer
    return (
        b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", data) + chunk(b"IEND", b"")
    )


def write_png(picture: Image.Image, path: str | os.PathLike) -> Path:
    """Write a picture as a PNG file (:func:`png_bytes`), atomically."""
    return atomic_write(path, png_bytes(picture))
