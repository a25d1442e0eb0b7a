"""The face table of a FOLD frame, bounded by what the file holds.

Faces of any length are held as one table padded with -1 to the longest face. Padding costs
``faces × longest`` indices, which a small file can make enormous: one face of 2000 vertices
beside 1998 triangles is 76 kB of JSON and 8000 indices, but a table of 4 million (and the
checks hold several arrays of its shape, about 480 MB at once). :func:`padded_faces` refuses
such a table before allocating it: the padded table may hold at most :data:`PADDING` times
the indices the faces hold, or :data:`PADDED_FLOOR` indices, whichever is larger.
"""

from __future__ import annotations

import numpy as np

from ..kernel._errors import InputError

__all__ = ["padded_faces", "PADDING", "PADDED_FLOOR"]

#: Largest ratio of the padded table to the indices the faces hold (triangles beside quads: 4/3).
PADDING = 4
#: Padded tables up to this many indices are read whatever the ratio (8 MiB of int64).
PADDED_FLOOR = 1 << 20


def padded_faces(rows: list[list[int]], key: str, where: str) -> np.ndarray:
    """``rows`` of any lengths (at least 3) as one (F, k) int64 table, -1 padded.

    Raises
    ------
    InputError
        The padded table would hold more than ``max(PADDING × held, PADDED_FLOOR)`` indices;
        the message names the longest face, the sizes and what to do.
    """
    lengths = [len(row) for row in rows]
    longest = max([3, *lengths])
    held, padded = sum(lengths), len(rows) * longest
    limit = max(PADDING * held, PADDED_FLOOR)
    if padded > limit:
        i = lengths.index(longest)
        raise InputError(
            f"{where}: {key}[{i}] has {longest} vertices: its {len(rows)} faces padded to it "
            f"would hold {padded} indices, more than the {limit} curvefold reads ({PADDING} "
            f"times the {held} they hold, at least {PADDED_FLOOR}); split that face"
        )
    out = np.full((len(rows), longest), -1, np.int64)
    for i, row in enumerate(rows):
        out[i, : len(row)] = row
    return out
