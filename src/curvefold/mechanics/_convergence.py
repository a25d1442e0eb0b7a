"""How a figure converges as its mesh is refined: the observed order and Richardson's estimate.

A figure f_h of a mesh of size h that converges at order p, f_h = f + c hᵖ + o(hᵖ), gives
from three meshes refined by the same ratio r (h, h / r, h / r²) its observed order

    p = log((f_h − f_h/r) / (f_h/r − f_h/r²)) / log r,

and from two of them Richardson's estimate of its limit and of the error of the finer:

    f ≈ f_h/r + (f_h/r − f_h) / (rᵖ − 1),     error(f_h/r) ≈ |f_h/r − f_h| / (rᵖ − 1).

The estimate holds once the meshes are in the asymptotic range (the order observed on
three meshes near the one assumed); the tests measure it on each figure.

**The error of a result.** :func:`figure_errors` and :func:`check_errors` estimate the
error of every figure of a result on k elements across each strip from the same result on
k / 2 (Richardson, r = 2), at the order :data:`ORDERS` assumes for its kind, chosen so
that the estimate errs large: on a tube and a vault of three tubes every figure's estimate
from k = 2 and 4 is above its difference to k = 16 (the tests). The orders observed there
(k = 2, 4, 8) are 2.4–3.6 for the deflection, 0.6–1.2 for the free eigenvalues (taken at
0.8: the lowest at which the estimates bound the difference; the guide's tables find 0.4
on the paper's vault and the block, whose eigenvalues move by under 2 % from k = 2 to 8)
and above 3 for the supported ones. The buckling factor and the largest stress are taken
at first order: both are found where the sheet meets its supports, whose corners make the
linear model's stress singular, so that they keep moving slowly as the mesh is refined (the
paper's vault at k = 2, 4, 8: buckling factor 24.27, 23.87, 23.51; largest stress 138.6,
139.3, 147.3 kPa, the last in an element on the supports). The loads, the reactions and the
weight carry no error of the elements across (the weight is ρ g t times the developed area
of the samples kept).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from ..kernel._errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    from ._analysis import LoadResult
    from ._verdict import Verdict

__all__ = [
    "observed_order",
    "richardson",
    "figure_errors",
    "check_errors",
    "ORDERS",
    "TOLERANCE",
]

#: The order of convergence in the elements across assumed for each kind of figure (module
#: notes).
ORDERS = {
    "deflection": 2.0,
    "buckling": 1.0,
    "stress": 1.0,
    "eigenvalue": 0.8,
    "supported eigenvalue": 2.0,
}
#: The estimated relative error of a printed figure above which the mesh is called too coarse.
TOLERANCE = 0.05


def observed_order(coarse: float, medium: float, fine: float, *, ratio: float = 2.0) -> float:
    """The order p observed on three meshes refined by ``ratio`` (module notes); inf when the
    finer two agree exactly.

    Examples
    --------
    >>> round(observed_order(1 + 1 / 4, 1 + 1 / 16, 1 + 1 / 64), 12)  # f = 1 + h², h = ½, ¼, ⅛
    2.0
    """
    if not ratio > 1:
        raise InputError(f"ratio must be > 1 (the meshes refined), got {ratio!r}")
    a, b = abs(coarse - medium), abs(medium - fine)
    if b == 0:
        return math.inf
    if a == 0:
        return -math.inf
    return math.log(a / b) / math.log(ratio)


def richardson(
    coarse: float, fine: float, *, order: float, ratio: float = 2.0
) -> tuple[float, float]:
    """Richardson's estimate from two meshes refined by ``ratio``: the limit and the error of the
    finer figure (module notes).

    Parameters
    ----------
    coarse, fine : float
        The figure on the coarser and the finer mesh.
    order : float, keyword-only
        p, the order of convergence (> 0): the observed one, or the one the method has.
    ratio : float, keyword-only
        r, how much finer the finer mesh is (> 1).

    Examples
    --------
    >>> limit, error = richardson(1 + 1 / 16, 1 + 1 / 64, order=2)  # f = 1 + h², h = ¼, ⅛
    >>> round(limit, 12), round(error, 12)
    (1.0, 0.015625)
    """
    if not order > 0:
        raise InputError(f"order must be > 0, got {order!r}")
    if not ratio > 1:
        raise InputError(f"ratio must be > 1 (the meshes refined), got {ratio!r}")
    step = (fine - coarse) / (ratio**order - 1)
    return fine + step, abs(step)


def _relative(coarse: float, fine: float, order: float, ratio: float) -> float:
    """The relative error of ``fine`` (Richardson, module notes); 0 for two infinite figures
    (nothing buckles), inf when one of them is."""
    if math.isinf(coarse) or math.isinf(fine):
        return 0.0 if coarse == fine else math.inf
    _, error = richardson(coarse, fine, order=order, ratio=ratio)
    return error / abs(fine) if fine else (0.0 if error == 0 else math.inf)


def figure_errors(coarse: LoadResult, fine: LoadResult) -> dict[str, float | list[float]]:
    """The estimated relative error of every figure of ``fine`` that depends on the mesh, from
    the same structure and loads on fewer elements across (module notes).

    Keys as :meth:`LoadResult.to_dict`'s: ``max_displacement``, ``max_stress``,
    ``buckling_factor``, ``fold_mode_gap`` (floats) and ``modes``, ``supported_modes``
    (one per eigenvalue, as many as both results have).

    Examples
    --------
    >>> from curvefold.mechanics import StructureModel, analyse_load, MATERIALS
    >>> from curvefold.vault import Vault
    >>> one = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, samples=21).structure.state(), MATERIALS["aluminium"], 1e-3
    ... )
    >>> errors = figure_errors(analyse_load(one.with_across(2)), analyse_load(one.with_across(4)))
    >>> sorted(errors)
    ['buckling_factor', 'fold_mode_gap', 'max_displacement', 'max_stress', 'modes',
     'supported_modes']
    >>> round(errors["max_displacement"], 4)  # 36.08 µm on two across, 37.55 on four: 1.47 / 3
    0.0131
    """
    ratio = fine.structure.across / coarse.structure.across
    if not ratio > 1:
        raise InputError(
            f"the finer result must have more elements across, got {fine.structure.across} "
            f"against {coarse.structure.across}"
        )
    errors: dict[str, float | list[float]] = {}
    for key, (read, kind) in _FIGURES.items():
        a, b = read(coarse), read(fine)
        if isinstance(b, float):
            errors[key] = _relative(float(a), b, ORDERS[kind], ratio)
        else:
            errors[key] = [_relative(float(x), float(y), ORDERS[kind], ratio) for x, y in zip(a, b)]
    return errors


#: Every figure of a result that depends on the mesh: how it is read and its kind in
#: :data:`ORDERS`.
_FIGURES: dict[str, tuple[Callable[[LoadResult], Any], str]] = {
    "max_displacement": (lambda r: r.static.max_displacement, "deflection"),
    "max_stress": (lambda r: r.static.max_stress, "stress"),
    "buckling_factor": (lambda r: r.buckling.factor, "buckling"),
    "fold_mode_gap": (lambda r: r.modes.fold_mode_gap, "eigenvalue"),
    "modes": (lambda r: r.modes.eigenvalues, "eigenvalue"),
    "supported_modes": (lambda r: r.supported_eigenvalues, "supported eigenvalue"),
}


#: The kind of figure each check's value is (its order in :data:`ORDERS`).
_CHECK_KIND = {"stability": "buckling", "strength": "stress", "deflection": "deflection"}


def check_errors(coarse: Verdict, fine: Verdict, across: tuple[int, int]) -> Verdict:
    """``fine`` with every check's estimated relative error (:attr:`Check.error`) from the same
    check of ``coarse``, and its note on the mesh saying so; ``across``: the elements across
    of the two (module notes).

    Examples
    --------
    >>> from curvefold.mechanics import Check, Verdict
    >>> at = lambda d: Verdict((Check("deflection", d, 0.01, "m", "SLS G"),), (), notes=("",))
    >>> estimated = check_errors(at(0.0012), at(0.0015), (2, 4))
    >>> round(estimated.checks[0].error, 12)  # 0.0001 / 0.0015
    0.066666666667
    >>> estimated.notes[0].startswith("every figure is the model's with 4 elements across")
    True
    """
    from ._verdict import mesh_note

    ratio = across[1] / across[0]
    before = {(c.name, c.combination): c.value for c in coarse.checks}
    checks = tuple(
        replace(c, error=_relative(before[key], c.value, ORDERS[_CHECK_KIND[c.name]], ratio))
        if (key := (c.name, c.combination)) in before
        else c
        for c in fine.checks
    )
    return replace(fine, checks=checks, notes=(mesh_note(across[1], across[0]), *fine.notes[1:]))
