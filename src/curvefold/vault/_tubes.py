"""How many tubes a vault stacks: decided once, on the smooth build of its design.

A vault's tubes are the cells [j, j+1]² of its lattice, stacked along the diagonal. The most
free of regression (:func:`max_tubes`) is measured on the smooth lattice of the design, and
``tubes = "max"`` takes that count (:func:`design_tubes`) whatever the panels: a panel
lattice's discrete domain reaches past the smooth one by O(1/N²), so counting on it gave the
default vault 14 tubes with 4 panels and 10 with 8 … 16, the smooth 9, the tenth with crease
sides 0.002 of the median. A panel build of the count is then refused where its panels
regress or are slivers (:func:`panel_structure`).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..geometry._kinds import StructureLattice
from ..geometry._structure import Structure
from ..geometry._topology import CORNERS
from ..kernel._errors import RegressionError

__all__ = ["DEFAULT_TUBES_CAP", "MAX_TUBES_SEARCH", "design_tubes", "max_tubes", "panel_structure"]

#: Stacks are searched up to this many tubes; a longer valid stack reports this number.
MAX_TUBES_SEARCH = 10_000
#: Tubes built when none are asked for and the stack could be longer.
DEFAULT_TUBES_CAP = 24


def max_tubes(
    lattice: StructureLattice, *, direction: int = 1, limit: int = MAX_TUBES_SEARCH
) -> int:
    """Largest n such that the tubes [j, j+1]², j = 0 … n−1 (stacked in ±(u, v)) are free of
    regression.

    All four corner creases of every tube must be valid lattice curves (Eq. 18). The valid
    set is convex, and every corner of the stack is a convex combination of corners of its
    first and last tubes, so a stack is valid exactly when those two tubes are: validity
    is monotone in n. A corner's speed factor falls linearly with j, ``f(j) = f(0) − j s``,
    which places the first tube past regression; it is then checked exactly (that tube
    invalid, the one before valid), and a bisection decides where rounding leaves it in
    doubt. Returns 0 when even the base tube regresses, and ``limit`` when the stack is
    valid that far.

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> vault = Vault.from_design(samples=41, tubes=3)  # coarse, for a quick example
    >>> max_tubes(vault.lattice), max_tubes(vault.lattice, limit=5)  # the search stops at the limit
    (9, 5)
    """
    domain = lattice.domain

    def tube_ok(j: int) -> bool:
        return bool(domain.contains(direction * (j + CORNERS) - (direction < 0)).all())

    if not tube_ok(0):
        return 0
    slope = direction * (domain.a + domain.b)  # s: the fall of every corner's factor per tube
    falling = slope > 0
    if not falling.any():
        return limit
    # f(0) / s
    first = domain.factor(direction * CORNERS - (direction < 0))[:, falling] / slope[falling]
    guess = min(int(np.ceil(first.min())), limit)
    if 0 < guess < limit and tube_ok(guess - 1) and not tube_ok(guess):
        return guess
    if tube_ok(limit - 1):
        return limit
    lo, hi = 0, limit - 1  # tube lo is valid, tube hi is not
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (mid, hi) if tube_ok(mid) else (lo, mid)
    return hi


def design_tubes(
    smooth: StructureLattice, tubes: int | None, *, direction: int = 1, what: str = "this design"
) -> tuple[int, int]:
    """The tubes a vault design builds and the most before regression, (tubes, most).

    ``smooth`` is the lattice of the design's smooth build, whatever its panels: the one
    place the count is decided. ``tubes`` None ("max") takes the most tubes free of
    regression (:func:`max_tubes`), at most :data:`DEFAULT_TUBES_CAP`; ``what`` names the
    design in the message.

    Raises
    ------
    RegressionError
        If ``tubes`` is more than the most before regression.

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> lattice = Vault.from_design(samples=41, tubes=3).lattice  # coarse, for a quick example
    >>> design_tubes(lattice, None), design_tubes(lattice, 4)
    ((9, 9), (4, 9))
    >>> design_tubes(lattice, 10)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.RegressionError: tubes must be ≤ 9 (the maximum before regression
    for this design), got 10
    """
    most = max_tubes(smooth, direction=direction)
    count = tubes if tubes is not None else min(most, DEFAULT_TUBES_CAP)
    if count > most:
        raise RegressionError(
            f"tubes must be ≤ {most} (the maximum before regression for {what}), got {count}",
            parameter="tubes",
        )
    return count, most


def panel_structure(
    lattice: StructureLattice,
    tubes: int,
    *,
    direction: int = 1,
    layers: int = 1,
    panels: int = 0,
    chosen: bool = False,
) -> Structure:
    """The stack of ``tubes`` tubes on ``lattice`` (:meth:`Structure.diagonal`).

    On a panel lattice of ``panels`` panels the stack is refused where its panels regress or
    are slivers (:meth:`~curvefold.geometry.PanelLattice.check`); ``chosen``: the count is
    the one ``tubes = "max"`` chose (the message says so).

    Raises
    ------
    RegressionError
        Naming ``tubes``, the most tubes these panels build and the panel at fault.

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> lattice = Vault.from_design(samples=41, panels=16, tubes=3).lattice
    >>> panel_structure(lattice, 9, panels=16).cells.shape  # the smooth design's count
    (9, 2)
    >>> panel_structure(lattice, 10, panels=16)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.RegressionError: tubes must be ≤ 9 with panels = 16, got 10: cells: a
    panel side along lattice polyline (u, v) = (10, 10) on panel 9 of 16 is 0.0023 of the median
    of its kind, below min_side = 0.01 (a sliver panel)
    """

    def stack(count: int) -> Structure:
        return Structure.diagonal(lattice, count, direction=direction, layers=layers)

    if not panels:
        return stack(tubes)
    try:
        return stack(tubes)
    except RegressionError as err:
        fewer = next((n for n in range(tubes - 1, 0, -1) if _builds(stack, n)), 0)
        why = ' (tubes = "max": the smooth design\'s count)' if chosen else ""
        raise RegressionError(
            f"tubes must be ≤ {fewer} with panels = {panels}, got {tubes}{why}: {err}",
            parameter="tubes",
        ) from None


def _builds(stack: Callable[[int], Structure], count: int) -> bool:
    """Whether ``stack(count)`` builds, free of regression."""
    try:
        stack(count)
    except RegressionError:
        return False
    return True
