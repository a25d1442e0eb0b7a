"""The ids of thick panels and the order they are assembled in: the cut list's and the assembly
guide's.

A panel's id says where a builder finds it: ``"tube 2 · sheet A · strip 4 · panel 3"`` is the
third panel from the start of the crease on strip 4 of tube 2, which the crease pattern's sheet
A of tube 2 holds (:mod:`curvefold.geometry._sheets`: sheet A is strips 4 and 1 round crease 1,
sheet B strips 2 and 3 round crease 3). Strips are numbered 1 to 4 from curve 1 round the tube,
as the creases are (crease c runs between strips c − 1 and c, crease 1 between 4 and 1).

The panels are assembled tube by tube, as the assembly guide numbers the tubes; in each tube
sheet A then sheet B, each sheet strip by strip across it (A: strip 4 then strip 1, hinged
along crease 1; B: strip 2 then strip 3, hinged along crease 3), each strip panel by panel
along the crease, every panel hinged to the one before it on their shared edge; then the two
sheets hinged to each other along creases 2 and 4, and the tube to the tubes before it along
the creases they share.
"""

from __future__ import annotations

import numpy as np

__all__ = ["SHEET_STRIPS", "panel_ids", "assembly_order"]

#: The sheets of a tube and their strips (0-based within the tube, ``faces_group % 4``), in the
#: order they are assembled: strip 4 before strip 1 so that each sheet is laid across from one
#: seam to the other.
SHEET_STRIPS = (("A", (3, 0)), ("B", (1, 2)))
_SHEET = {strip: sheet for sheet, strips in SHEET_STRIPS for strip in strips}


def _places(group: np.ndarray) -> np.ndarray:
    """Every face's place along its strip, 0-based, (F,): its rank among the faces of its group,
    in the faces' order (from the start of the crease)."""
    order = np.argsort(group, kind="stable")
    first = np.searchsorted(group[order], group[order])  # where each face's group starts
    place = np.empty(len(group), dtype=np.int64)
    place[order] = np.arange(len(group)) - first
    return place


def panel_ids(group: np.ndarray) -> tuple[str, ...]:
    """Every panel's id from its faces' groups (``topology.faces_group``: 4 per tube).

    Examples
    --------
    >>> panel_ids(np.array([0, 0, 1, 2, 3, 3, 4]))
    ... # doctest: +NORMALIZE_WHITESPACE
    ('tube 1 · sheet A · strip 1 · panel 1', 'tube 1 · sheet A · strip 1 · panel 2',
     'tube 1 · sheet B · strip 2 · panel 1', 'tube 1 · sheet B · strip 3 · panel 1',
     'tube 1 · sheet A · strip 4 · panel 1', 'tube 1 · sheet A · strip 4 · panel 2',
     'tube 2 · sheet A · strip 1 · panel 1')
    """
    group = np.asarray(group, dtype=np.int64)
    return tuple(
        f"tube {g // 4 + 1} · sheet {_SHEET[g % 4]} · strip {g % 4 + 1} · panel {p + 1}"
        for g, p in zip(group.tolist(), _places(group).tolist())
    )


def assembly_order(group: np.ndarray) -> np.ndarray:
    """The faces in the order they are assembled (module notes), (F,) int.

    Examples
    --------
    >>> assembly_order(np.array([0, 0, 1, 2, 3, 3, 4])).tolist()  # strips 4, 1, 2, 3; tube 2
    [4, 5, 0, 1, 2, 3, 6]
    """
    group = np.asarray(group, dtype=np.int64)
    rank = np.array([s for _, strips in SHEET_STRIPS for s in strips]).argsort()
    key = 4 * (group // 4) + rank[group % 4]  # tube, then the strip's turn in its tube
    return np.lexsort((_places(group), key))
