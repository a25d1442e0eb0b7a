"""The folding motion as picture frames, drawn with Pillow from the scene renderer (optional).

:func:`motion_frames` draws a structure or vault folding, flat to its design angle, at one
scale: the scenes of :func:`curvefold.figures._scene.motion_scenes` rasterised by
:func:`raster`, each under a title line naming its fold angle. :func:`write_motion_gif`
writes them as the GIF of the output folder with :func:`curvefold.io._gif.write_gif`.
Pillow comes with matplotlib (``pip install curvefold[plot]``), whose DejaVu Sans sets the
titles: Pillow is imported when a frame is drawn, matplotlib never (its font file is found
without running matplotlib: :func:`curvefold.figures._raster.font_file`).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Literal, overload

import numpy as np

from ..geometry._lattice import check_anchor
from ..io._gif import write_gif
from ..kernel._errors import InputError
from ._canvas import Canvas, draw_ground, draw_scene
from ._plot_data import KIND_COLORS, structure_of
from ._scene import Scene, View, motion_scenes

if TYPE_CHECKING:  # pragma: no cover
    from PIL import Image

    from ..geometry._structure import Structure
    from ..vault._assembly import Vault

__all__ = ["raster", "motion_frames", "write_motion_gif"]


@overload
def raster(
    scene: Scene,
    box: np.ndarray,
    size: tuple[int, int],
    title: str,
    *,
    supersample: int = 2,
    canvas: None = None,
    rect: None = None,
    title_points: float | None = None,
) -> Image.Image: ...
@overload
def raster(
    scene: Scene,
    box: np.ndarray,
    size: tuple[int, int] | None,
    title: str,
    *,
    supersample: int = 2,
    canvas: Canvas,
    rect: Sequence[float],
    title_points: float | None = None,
) -> float: ...
def raster(
    scene: Scene,
    box: np.ndarray,
    size: tuple[int, int] | None,
    title: str,
    *,
    supersample: int = 2,
    canvas: Canvas | None = None,
    rect: Sequence[float] | None = None,
    title_points: float | None = None,
) -> Image.Image | float:
    """A scene drawn with Pillow: the screen points ``box`` (P, 2) fit below a title line.

    Drawn at ``supersample`` times the size and reduced, so edges are smoothed; line widths
    in points are taken at 100 dots per inch, as in the figures.

    Parameters
    ----------
    scene : Scene
    box : (P, 2) ndarray
        Screen points that must fit in the picture (the boxes of every frame of a motion,
        so all share one scale).
    size : (int, int)
        Width and height in pixels.
    title : str
        The line above the drawing.
    supersample : int, keyword-only
    canvas : Canvas, optional, keyword-only
        Draw into this canvas, in ``rect`` (left, top, right, bottom; picture pixels), rather
        than into a picture of its own (``size`` is not used).
    title_points : float, optional, keyword-only
        Size of the title; default a twentieth of the height.

    Returns
    -------
    PIL.Image.Image or float
        An RGB image of ``size``; drawn into ``canvas``, the scale instead: canvas pixels per model
        unit.
    """
    from PIL import ImageDraw

    own = canvas is None
    if canvas is None:
        assert size is not None  # a picture of its own has a size
        canvas = Canvas(size, dpi=100.0, supersample=supersample)
        rect = (0, 0, *size)
    assert rect is not None  # drawn into a canvas: in rect
    place = _Placement(canvas, box, rect, title, title_points)
    draw_scene(ImageDraw.Draw(canvas.image), scene, place.pixels, canvas.pt, canvas.supersample)
    place.title(title)
    return canvas.picture() if own else place.scale


class _Placement:
    """Where a drawing goes in ``rect`` (left, top, right, bottom; picture pixels) of a canvas:
    the screen points ``box`` (P, 2) fit below the line of a title (if there is one)."""

    def __init__(
        self,
        canvas: Canvas,
        box: np.ndarray,
        rect: Sequence[float],
        title: str,
        title_points: float | None,
    ) -> None:
        left, top, right, bottom = (v * canvas.supersample for v in rect)
        w, h = right - left, bottom - top
        self.canvas, self.at = canvas, (left + w / 2, top + 0.02 * h)
        self.title_px = 0.05 * h if title_points is None else title_points * canvas.pt
        head, pad = (
            (0.12 * h if title_points is None else 2.2 * self.title_px) if title else 0.0,
            0.02 * w,
        )
        lo, hi = box.min(axis=0), box.max(axis=0)
        self.middle = 0.5 * (lo + hi)
        #: Canvas pixels per model unit.
        self.scale = min(
            (w - 2 * pad) / max(hi[0] - lo[0], 1e-12), (h - head - pad) / max(hi[1] - lo[1], 1e-12)
        )
        self.centre = np.array([left + w / 2, top + (h + head - pad) / 2])

    def pixels(self, points: np.ndarray) -> np.ndarray:
        """Canvas pixels (N, 2) of screen points (N, 2)."""
        return (points - self.middle) * self.scale * np.array([1.0, -1.0]) + self.centre

    def title(self, title: str) -> None:
        """Write the title line (nothing if it is empty)."""
        if title:
            self.canvas.text(self.at, title, self.title_px / self.canvas.pt, anchor="mt")


def _frames(
    scenes: Sequence[Scene], box: np.ndarray, size: tuple[int, int], titles: Sequence[str]
) -> list[Image.Image]:
    """:func:`raster` of each scene of a motion (they share one ground, or none) under its title,
    all drawn on one canvas: the ground once, then each frame over a copy of it."""
    from PIL import ImageDraw

    canvas = Canvas(size, dpi=100.0)
    draw = ImageDraw.Draw(canvas.image)
    place = _Placement(canvas, box, (0, 0, *size), titles[0], None)
    draw_ground(draw, scenes[0].ground, place.pixels, canvas.supersample)
    backdrop = canvas.image.copy()
    frames = []
    for scene, title in zip(scenes, titles):
        canvas.image.paste(backdrop)
        draw_scene(draw, scene, place.pixels, canvas.pt, canvas.supersample, ground=False)
        place.title(title)
        frames.append(canvas.picture())
    return frames


def motion_frames(
    obj: Vault | Structure,
    *,
    angles: Sequence[float] | None = None,
    anchor: Literal["start", "middle"] = "start",
    view: View = View(),
    size: tuple[int, int] = (640, 480),
    segments: int = 48,
    max_cells: int = 60,
) -> list[Image.Image]:
    """Frames of the rigid folding motion, one per fold angle, all at one scale (a vault over its
    ground).

    Parameters
    ----------
    obj : Vault or Structure
    angles : sequence of float, optional, keyword-only
        2α of the frames in degrees; default 16 steps from 0° to the design angle.
    anchor : {"start", "middle"}, keyword-only
        Which frame of curve 1 stays fixed: at its start (t = 0) or at its middle sample.
    view : View, keyword-only
    size : (int, int), keyword-only
        Width and height in pixels, each in [64, 4096].
    segments, max_cells : int, keyword-only
        Detail drawn: segments along each crease, and at most this many cells.

    Returns
    -------
    list of PIL.Image.Image
        RGB frames of ``size``, in the order of ``angles``, each titled with its 2α.
    """
    from ..vault._assembly import Vault

    structure, lattice, own = structure_of(obj)
    check_anchor(anchor)
    w_px, h_px = (int(v) for v in size)
    if not (64 <= w_px <= 4096 and 64 <= h_px <= 4096):
        raise InputError(
            f"size must be (width, height) in pixels, each in [64, 4096], got {size!r}"
        )
    steps = (
        np.linspace(0.0, own, 16) if angles is None else np.atleast_1d(np.asarray(angles, float))
    )
    if steps.ndim != 1 or steps.size == 0:
        raise InputError(
            f"angles must be a non-empty list of fold angles in degrees, got {angles!r}"
        )
    motion = lattice.fold_points(structure.curves_uv, steps, anchor=anchor)
    scenes = motion_scenes(
        structure,
        motion,
        colors=KIND_COLORS,
        view=view,
        segments=segments,
        max_cells=max_cells,
        crease_width=0.7,
        ground=isinstance(obj, Vault),
    )
    joint = np.concatenate([scene.box for scene in scenes])  # one scale for all frames
    return _frames(scenes, joint, (w_px, h_px), [f"2α = {f:5.1f}°" for f in steps])


def write_motion_gif(
    obj: Vault | Structure, path: str | os.PathLike, *, frame_seconds: float = 0.12, **frames
) -> Path:
    """An animated GIF of the rigid folding motion, flat to the design angle and back, written
    atomically.

    Parameters
    ----------
    obj : Vault or Structure
    path : str or path-like
        Target file (its folder must exist).
    frame_seconds : float, keyword-only
        Duration of one frame.
    **frames
        ``angles``, ``anchor``, ``view``, ``size``, ``segments`` and ``max_cells`` of
        :func:`motion_frames`. The animation plays the frames forward, then backward, and loops.

    Returns
    -------
    Path
    """
    return write_gif(path, motion_frames(obj, **frames), frame_seconds=frame_seconds, bounce=True)
