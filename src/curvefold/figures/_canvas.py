"""A raster canvas drawn with Pillow from NumPy: scenes and small plots, without matplotlib.

The report's pictures and the frames of the folding GIF are drawn here (Pillow comes with
matplotlib, ``pip install curvefold[plot]``; the font, inks, ticks and strokes are
:mod:`curvefold.figures._raster`'s). A :class:`Canvas` is drawn at ``supersample`` times
its size and reduced with a box filter, so edges come out smooth; lengths given in points
are taken at its ``dpi``. A :class:`Frame` is a plot's axes on the canvas: data limits
mapped to a pixel rectangle, what it draws clipped to it, a frame with round ticks,
labels, a title, and a legend.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ._raster import (
    _dashed,
    _font,
    _length,
    _line,
    _rgba,
    _runs,
    inks,
    nice_ticks,
    tick_label,
    viridis,
)

if TYPE_CHECKING:  # pragma: no cover
    from PIL import Image

    from ._scene import Scene

__all__ = ["Canvas", "Frame", "draw_ground", "draw_scene"]


def draw_ground(draw, ground: np.ndarray | None, to_pixels, width: float) -> None:
    """Paint the ground of a scene (its screen corners (4, 2), or None: nothing) with a Pillow
    ImageDraw of an RGB image, its outline ``width`` pixels wide; ``to_pixels`` maps screen
    points (N, 2) to pixels (N, 2)."""
    from ._scene import GROUND_COLOR, GROUND_EDGE

    if ground is not None:
        draw.polygon(
            [tuple(p) for p in to_pixels(ground).tolist()],
            fill=GROUND_COLOR,
            outline=GROUND_EDGE,
            width=max(1, round(width)),
        )


def draw_scene(
    draw,
    scene: Scene,
    to_pixels,
    pixels_per_point: float,
    ground_width: float,
    *,
    ground: bool = True,
) -> None:
    """Paint a scene (ground first, then its paths far to near) with a Pillow ImageDraw of an RGB
    image.

    ``to_pixels`` maps screen points (N, 2) to pixels (N, 2). Strips are filled (their
    outline is their own colour: the fill covers it), segments stroked at their widths.
    With ``ground`` False the ground is left out (:func:`draw_ground` drew it already).
    """
    if ground:
        draw_ground(draw, scene.ground, to_pixels, ground_width)
    points, sizes = scene.flat
    ends = (2 * np.cumsum(sizes)).tolist()
    flat = to_pixels(points).ravel().tolist()
    quad = (sizes > 2).tolist()
    fill_inks, stroke_inks = inks(scene.fill), inks(scene.stroke)
    widths = (
        np.maximum(1, np.round(np.asarray(scene.widths) * pixels_per_point)).astype(int).tolist()
    )
    core, start = draw.draw, 0
    for end, is_quad, fill, stroke, width in zip(ends, quad, fill_inks, stroke_inks, widths):
        if is_quad:
            core.draw_polygon(flat[start:end], fill, 1)
        else:
            core.draw_lines(flat[start:end], stroke, width)
        start = end


class Canvas:
    """A white RGB picture of ``size`` pixels, drawn at ``supersample`` times that size.

    Parameters
    ----------
    size : (int, int)
        Width and height of the picture in pixels.
    dpi : float, keyword-only
        Pixels of the picture per inch: lengths and font sizes in points are taken at it.
    supersample : int, keyword-only
    """

    def __init__(self, size: tuple[int, int], *, dpi: float = 150.0, supersample: int = 2) -> None:
        from PIL import Image, ImageDraw

        self.size, self.supersample = (int(size[0]), int(size[1])), int(supersample)
        self.pt = dpi / 72 * self.supersample  # canvas pixels per point
        self.image = Image.new(
            "RGB", (self.size[0] * self.supersample, self.size[1] * self.supersample), "white"
        )
        self.draw = ImageDraw.Draw(self.image, "RGBA")

    def font(self, points: float):
        """DejaVu Sans at ``points``."""
        return _font(self._pixels(points))

    def _pixels(self, points: float) -> int:
        return int(round(points * self.pt))

    def text_size(self, text: str, points: float) -> tuple[float, float]:
        """Width and height (canvas pixels) of a line of text."""
        return sum(
            _length(self._pixels(points * (0.72 if sub else 1)), piece)
            for piece, sub in _runs(text)
        ), points * self.pt

    def text(
        self,
        xy: Sequence[float],
        text: str,
        points: float = 9.0,
        *,
        color="#000000",
        anchor: str = "lm",
        draw=None,
    ) -> None:
        """A line of text at ``xy`` (canvas pixels); ``anchor`` is Pillow's two letters (l/m/r,
        t/m/b; "b" the baseline side)."""
        draw = self.draw if draw is None else draw
        width, height = self.text_size(text, points)
        x = xy[0] - {"l": 0.0, "m": 0.5, "r": 1.0}[anchor[0]] * width
        base = xy[1] + {"t": 0.78, "m": 0.36, "b": 0.0}[anchor[1]] * height  # the baseline
        ink = _rgba(color)
        for piece, sub in _runs(text):
            pixels = self._pixels(points * (0.72 if sub else 1))
            draw.text(
                (x, base + (0.22 * height if sub else 0.0)),
                piece,
                fill=ink,
                font=_font(pixels),
                anchor="ls",
            )
            x += _length(pixels, piece)

    def vertical_text(self, xy: Sequence[float], text: str, points: float = 9.0) -> None:
        """A line of text turned a quarter left (reading upward), centred on ``xy``."""
        from PIL import Image, ImageDraw

        width, height = self.text_size(text, points)
        strip = Image.new("L", (int(width) + 4, int(1.4 * height) + 4), 0)
        mask_canvas = ImageDraw.Draw(strip)
        self.text(
            (2, strip.height / 2),
            text,
            points,
            color=(1, 1, 1),
            anchor="lm",
            draw=_MaskDraw(mask_canvas),
        )
        turned = strip.rotate(90, expand=True)
        self.image.paste(
            (0, 0, 0), (int(xy[0] - turned.width / 2), int(xy[1] - turned.height / 2)), turned
        )

    def frame(
        self, rect: Sequence[float], xlim: Sequence[float], ylim: Sequence[float], **options
    ) -> Frame:
        """Axes on the rectangle ``rect`` = (left, top, right, bottom) in picture pixels (not
        supersampled); ``options`` (``log``, ``grid``, ``ticks``) go to :class:`Frame`."""
        return Frame(self, np.asarray(rect, float) * self.supersample, xlim, ylim, **options)

    def picture(self) -> Image.Image:
        """The picture, reduced to :attr:`size` (each pixel the mean of its ``supersample`` ×
        ``supersample`` block)."""
        return self.image.reduce(self.supersample) if self.supersample > 1 else self.image.copy()


class _MaskDraw:
    """An ImageDraw of a one-band mask that takes RGBA inks (their first band)."""

    def __init__(self, draw) -> None:
        self._draw = draw

    def text(self, xy, text, fill, font, anchor):
        self._draw.text(xy, text, fill=fill[0], font=font, anchor=anchor)


class Frame:
    """A plot's axes on a :class:`Canvas`: data (x, y) in ``xlim`` × ``ylim`` drawn in ``rect``
    (left, top, right, bottom; canvas pixels), clipped to it; with ``log`` both axes are
    logarithmic."""

    def __init__(
        self,
        canvas: Canvas,
        rect: np.ndarray,
        xlim: Sequence[float],
        ylim: Sequence[float],
        *,
        log: bool = False,
        grid: bool = True,
        ticks: int = 7,
    ) -> None:
        from PIL import ImageDraw

        self.canvas, self.rect, self.log = canvas, rect, log
        self.xlim, self.ylim = (float(xlim[0]), float(xlim[1])), (float(ylim[0]), float(ylim[1]))
        left, top, right, bottom = (int(round(v)) for v in rect)
        # drawn on, then put back: translucent fills blend
        self.layer = canvas.image.crop((left, top, right, bottom))
        self.draw = ImageDraw.Draw(self.layer, "RGBA")
        self.x_ticks, self.y_ticks = self._ticks(self.xlim, ticks), self._ticks(self.ylim, ticks)
        self._tick_pixels = (
            self.pixels(
                np.stack([self.x_ticks, np.full(len(self.x_ticks), self.ylim[0])], axis=-1)
            )[:, 0],
            self.pixels(
                np.stack([np.full(len(self.y_ticks), self.xlim[0]), self.y_ticks], axis=-1)
            )[:, 1],
        )
        if grid:
            w, gray = max(1, round(0.4 * canvas.pt)), (0, 0, 0, 30)
            for x in self._tick_pixels[0].tolist():
                self.draw.line((x, 0, x, self.layer.height), fill=gray, width=w)
            for y in self._tick_pixels[1].tolist():
                self.draw.line((0, y, self.layer.width, y), fill=gray, width=w)

    def _axis(self, values: np.ndarray, lim: tuple[float, float]) -> np.ndarray:
        f = np.log10 if self.log else (lambda v: v)
        lo, hi = f(lim[0]), f(lim[1])
        return (f(np.asarray(values, float)) - lo) / (hi - lo)

    def pixels(self, xy: np.ndarray) -> np.ndarray:
        """Layer pixels (..., 2) of data points (..., 2)."""
        xy = np.asarray(xy, float)
        width, height = self.layer.size
        return np.stack(
            [
                self._axis(xy[..., 0], self.xlim) * width,
                (1 - self._axis(xy[..., 1], self.ylim)) * height,
            ],
            axis=-1,
        )

    def lines(
        self,
        paths: Sequence[np.ndarray],
        color,
        width: float = 1.0,
        *,
        dash: tuple[float, float] | None = None,
    ) -> None:
        """Polylines (each (n, 2), data units); ``width`` and the ``dash`` (on, off) lengths in
        points."""
        pt, ink = self.canvas.pt, _rgba(color)
        w = max(1, int(round(width * pt)))
        for path in paths:
            px = self.pixels(path)
            pieces = [px] if dash is None else _dashed(px, dash[0] * pt, dash[1] * pt)
            for piece in pieces:
                if len(piece) > 1:
                    _line(self.draw, piece, ink, w)

    def polygons(
        self,
        polygons: Sequence[np.ndarray],
        fill=None,
        edge=None,
        width: float = 1.0,
        *,
        dash: tuple[float, float] | None = None,
    ) -> None:
        """Filled (RGBA ``fill``, may be translucent) and outlined polygons, each (p, 2) in data
        units."""
        for polygon in polygons:
            if fill is not None:
                self.draw.polygon(self.pixels(polygon).ravel().tolist(), fill=_rgba(fill))
        if edge is not None:
            self.lines([np.concatenate([p, p[:1]]) for p in polygons], edge, width, dash=dash)

    def markers(
        self, xy: np.ndarray, color, size: float = 4.0, *, shape: str = "o", width: float = 1.0
    ) -> None:
        """Markers of ``size`` points across at data points (N, 2): discs ("o"), rings ("ring")
        or crosses ("x")."""
        r, ink, w = (
            0.5 * size * self.canvas.pt,
            _rgba(color),
            max(1, int(round(width * self.canvas.pt))),
        )
        for x, y in self.pixels(np.asarray(xy, float).reshape(-1, 2)).tolist():
            if shape == "o":
                self.draw.ellipse((x - r, y - r, x + r, y + r), fill=ink)
            elif shape == "ring":
                self.draw.ellipse((x - r, y - r, x + r, y + r), outline=ink, width=w)
            else:
                self.draw.line((x - r, y - r, x + r, y + r), fill=ink, width=w)
                self.draw.line((x - r, y + r, x + r, y - r), fill=ink, width=w)

    def text(
        self,
        xy: Sequence[float],
        text: str,
        points: float = 8.0,
        *,
        offset: Sequence[float] = (0, 0),
        anchor: str = "lm",
        color="#000000",
    ) -> None:
        """Text at a data point, moved by ``offset`` points (x right, y up)."""
        (x, y), pt = self.pixels(np.asarray(xy, float)), self.canvas.pt
        self.canvas.text(
            (x + offset[0] * pt, y - offset[1] * pt),
            text,
            points,
            color=color,
            anchor=anchor,
            draw=self.draw,
        )

    def to_canvas(self, xy: np.ndarray) -> np.ndarray:
        """Canvas pixels of data points."""
        return self.pixels(xy) + self.rect[:2]

    def finish(
        self,
        *,
        title: str = "",
        xlabel: str = "",
        ylabel: str = "",
        xticks: bool = True,
        points: float = 9.0,
    ) -> None:
        """Put the drawing on the canvas, frame it and write its ticks, labels and title."""
        canvas, (left, top, right, bottom) = self.canvas, self.rect
        pt = canvas.pt
        canvas.image.paste(self.layer, (int(round(left)), int(round(top))))
        xs, ys = self._tick_pixels
        x_ticks, y_ticks = self.x_ticks, self.y_ticks
        draw, ink, tick = canvas.draw, (0, 0, 0, 255), 3.5 * pt
        draw.rectangle((left, top, right, bottom), outline=ink, width=max(1, round(0.8 * pt)))
        for x, value in zip((xs + left).tolist(), x_ticks.tolist()):
            if xticks:
                draw.line((x, bottom, x, bottom + tick), fill=ink, width=max(1, round(0.8 * pt)))
                canvas.text(
                    (x, bottom + tick + 2 * pt), self._label(value, x_ticks), points, anchor="mt"
                )
        for y, value in zip((ys + top).tolist(), y_ticks.tolist()):
            draw.line((left - tick, y, left, y), fill=ink, width=max(1, round(0.8 * pt)))
            canvas.text((left - tick - 2 * pt, y), self._label(value, y_ticks), points, anchor="rm")
        if xlabel:
            canvas.text(
                ((left + right) / 2, bottom + tick + 4 * pt + points * pt),
                xlabel,
                points + 1,
                anchor="mt",
            )
        if ylabel:
            widest = max(
                (canvas.text_size(self._label(v, y_ticks), points)[0] for v in y_ticks), default=0.0
            )
            canvas.vertical_text(
                (left - tick - 5 * pt - widest - 0.6 * (points + 1) * pt, (top + bottom) / 2),
                ylabel,
                points + 1,
            )
        if title:
            canvas.text(((left + right) / 2, top - 5 * pt), title, points + 2, anchor="mb")

    def _ticks(self, lim: tuple[float, float], count: int) -> np.ndarray:
        if not self.log:
            return nice_ticks(min(lim), max(lim), count)
        lo, hi = np.ceil(np.log10(min(lim)) - 1e-9), np.floor(np.log10(max(lim)) + 1e-9)
        every = max(1, int(np.ceil((hi - lo + 1) / count)))
        return 10.0 ** np.arange(lo, hi + 1, every)

    def _label(self, value: float, ticks: np.ndarray) -> str:
        if self.log:
            exponent = int(round(np.log10(value)))
            return (
                "1"
                if exponent == 0
                else "10"
                if exponent == 1
                else f"1e{exponent}".replace("-", "−")
            )
        return tick_label(
            value, float(np.min(np.diff(ticks))) if len(ticks) > 1 else abs(value) or 1.0
        )

    def legend(
        self,
        entries: Sequence[tuple[str, dict]],
        corner: str = "upper left",
        *,
        points: float = 7.5,
        avoid: Sequence[np.ndarray] = (),
    ) -> None:
        """A framed legend inside the axes: ``entries`` are (label, style), the style a dict with
        one of ``line`` (colour; ``width``, ``dash``), ``patch`` (fill; ``edge``) or ``marker``
        (colour; ``shape``, ``size``).

        ``corner`` "best" takes the corner or side whose legend covers the fewest of the data points
        ``avoid`` (each (n, 2)).
        """
        if corner == "best":
            points_px = self.to_canvas(
                np.concatenate([np.asarray(p, float).reshape(-1, 2) for p in avoid])
            )

            def covered(where: str) -> int:
                x0, y0, x1, y1 = legend_box(self.canvas, entries, self.rect, where, points=points)
                return int(
                    (
                        (points_px[:, 0] >= x0)
                        & (points_px[:, 0] <= x1)
                        & (points_px[:, 1] >= y0)
                        & (points_px[:, 1] <= y1)
                    ).sum()
                )

            corner = min(_INSIDE, key=covered)
        legend(self.canvas, entries, self.rect, corner, points=points)


#: Where a legend may go inside a frame, in order of preference.
_INSIDE = ("upper right", "upper left", "lower left", "lower right", "center right", "center left")


def legend_box(
    canvas: Canvas,
    entries: Sequence[tuple[str, dict]],
    rect: Sequence[float] | np.ndarray,
    corner: str,
    *,
    points: float = 7.5,
) -> tuple[float, float, float, float]:
    """(left, top, right, bottom) of a framed legend in the ``corner`` of ``rect`` (canvas
    pixels)."""
    pt = canvas.pt
    row, key, gap = 1.45 * points * pt, 2.4 * points * pt, 0.6 * points * pt
    width = (
        key
        + 3 * gap
        + max((canvas.text_size(label, points)[0] for label, _ in entries), default=0.0)
    )
    height = row * len(entries) + gap
    left, top, right, bottom = rect
    x = (
        left + gap
        if "left" in corner
        else right - gap - width
        if corner != "right"
        else right + gap
    )
    y = (
        top + gap
        if "upper" in corner
        else bottom - gap - height
        if "lower" in corner
        else (top + bottom - height) / 2
    )
    return x, y, x + width, y + height


def legend(
    canvas: Canvas,
    entries: Sequence[tuple[str, dict]],
    rect: Sequence[float] | np.ndarray,
    corner: str,
    *,
    points: float = 7.5,
    framed: bool = True,
) -> None:
    """Draw a legend in the ``corner`` ("upper left", "lower right", "right", "below", ...) of
    ``rect`` (canvas pixels): see :meth:`Frame.legend`."""
    pt = canvas.pt
    row, key, gap = 1.45 * points * pt, 2.4 * points * pt, 0.6 * points * pt
    widths = [canvas.text_size(label, points)[0] for label, _ in entries]
    left, top, right, bottom = rect
    if corner == "below":  # one row under the rectangle
        total = sum(key + gap + w + 2 * gap for w in widths)
        x, y = (left + right - total) / 2, bottom + gap
        for (label, style), w in zip(entries, widths):
            _key(canvas, style, (x, y + row / 2), key, points)
            canvas.text((x + key + gap, y + row / 2), label, points, anchor="lm")
            x += key + gap + w + 2 * gap
        return
    x, y, x1, y1 = legend_box(canvas, entries, rect, corner, points=points)
    if framed:
        canvas.draw.rounded_rectangle(
            (x, y, x1, y1),
            radius=0.4 * points * pt,
            fill=(255, 255, 255, 235),
            outline=(204, 204, 204, 255),
            width=max(1, round(0.6 * pt)),
        )
    for k, (label, style) in enumerate(entries):
        middle = y + gap / 2 + row * (k + 0.5)
        _key(canvas, style, (x + gap, middle), key, points)
        canvas.text((x + 2 * gap + key, middle), label, points, anchor="lm")


def _key(canvas: Canvas, style: dict, at: tuple[float, float], key: float, points: float) -> None:
    """The little picture of a legend entry, ``key`` pixels wide, its left middle at ``at``."""
    x, y = at
    pt, draw = canvas.pt, canvas.draw
    if "line" in style:
        line = np.array([[x, y], [x + key, y]])
        dash = style.get("dash")
        pieces = [line] if dash is None else _dashed(line, dash[0] * pt, dash[1] * pt)
        for piece in pieces:
            draw.line(
                piece.ravel().tolist(),
                fill=_rgba(style["line"]),
                width=max(1, round(style.get("width", 1.2) * pt)),
            )
    elif "patch" in style:
        h = 0.7 * points * pt
        draw.rectangle(
            (x, y - h / 2, x + key, y + h / 2),
            fill=_rgba(style["patch"]),
            outline=_rgba(style.get("edge", "#555555")),
            width=max(1, round(0.8 * pt)),
        )
    else:
        r = 0.5 * style.get("size", 4.0) * pt
        c = (x + key / 2, y)
        box = (c[0] - r, c[1] - r, c[0] + r, c[1] + r)
        shape, ink = style.get("shape", "o"), _rgba(style["marker"])
        if shape == "o":
            draw.ellipse(box, fill=ink)
        elif shape == "ring":
            draw.ellipse(box, outline=ink, width=max(1, round(pt)))
        else:
            draw.line(box, fill=ink, width=max(1, round(1.2 * pt)))
            draw.line((box[0], box[3], box[2], box[1]), fill=ink, width=max(1, round(1.2 * pt)))


def colour_key(canvas: Canvas, rect: Sequence[float], label: str, *, points: float = 8.0) -> None:
    """A vertical viridis key for t in [0, 1] in ``rect`` (canvas pixels), ticks every 0.2,
    ``label`` beside it."""
    from PIL import Image

    left, top, right, bottom = (int(round(v)) for v in rect)
    t = np.linspace(1, 0, bottom - top)
    column = np.round(255 * viridis(t)).astype(np.uint8)[:, None, :]
    canvas.image.paste(
        Image.fromarray(
            np.ascontiguousarray(np.broadcast_to(column, (bottom - top, right - left, 3)))
        ),
        (left, top),
    )
    pt = canvas.pt
    canvas.draw.rectangle(
        (left, top, right, bottom), outline=(0, 0, 0, 255), width=max(1, round(0.8 * pt))
    )
    for value in np.linspace(0, 1, 6):
        y = bottom - value * (bottom - top)
        canvas.draw.line(
            (right, y, right + 3.5 * pt, y), fill=(0, 0, 0, 255), width=max(1, round(0.8 * pt))
        )
        canvas.text((right + 5.5 * pt, y), f"{value:.1f}", points, anchor="lm")
    canvas.vertical_text(
        (
            right + 5.5 * pt + canvas.text_size("0.0", points)[0] + 1.2 * points * pt,
            (top + bottom) / 2,
        ),
        label,
        points,
    )
