"""A vault from what an architect asks of it: its span, its rise and its apex proportion.

A vault of the harmonic-torsion family is scale-free: at radius 1/κ₀ = 1, its shape follows
from a, p_xy, the width scale, the tubes, the layers and the fold angle, and the radius
then scales every length. So, with the width, tubes, layers and fold angle held:

* ``p_xz`` fixes p_xy for each a: p_xy = p_xz / (proportion change)², the change being
  exp(a κ₀s₀ cot α / π) (:func:`curvefold.vault.proportion_change`);
* ``rise / span`` fixes a (one equation in one unknown, solved by a scan of a over the
  family and Brent's method on the bracket found);
* ``span`` (or, alone, ``rise``) then fixes the radius.

Span and rise are those of :meth:`Vault.summary <curvefold.vault.Vault.summary>`:
the distance between the feet of curve 1 and the height of the highest crease sample,
at the design's own samples (so the vault built from the result measures the targets).
Targets no vault of the family reaches (regression bounds a for a given number of tubes)
give the nearest design found (the nearest of a scan over a, refined between its
neighbours) and a sentence saying what the family reaches.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..kernel._errors import ConvergenceError, InputError, InternalError, RegressionError
from ..kernel._validate import Spec
from ._arch import A_MAX, proportion_change, solve_symmetric_arch
from ._assembly import VAULT_SPECS, Vault, VaultDesign

__all__ = ["TARGET_SPECS", "TargetFit", "fit_targets", "SCAN_POINTS"]

#: The targets a vault can be designed from; each replaces a parameter of
#: :data:`~curvefold.vault._assembly.VAULT_SPECS`.
TARGET_SPECS: tuple[Spec, ...] = (
    Spec(
        "span",
        "real",
        None,
        "(0, inf)",
        "model units",
        help="distance between the feet of curve 1; sets the radius",
        label="span, foot to foot",
    ),
    Spec(
        "rise",
        "real",
        None,
        "(0, inf)",
        "model units",
        help="height of the highest crease; with span it sets a, alone the radius",
        label="rise",
    ),
    Spec(
        "p_xz",
        "real",
        None,
        "(0, 100]",
        help="section proportion w_R/w_L at the apex; sets p_xy",
        label="section proportion at the apex",
    ),
)
#: Which parameter each target replaces (a user may give one or the other, not both).
REPLACES = {"span": "radius", "rise": "a", "p_xz": "p_xy"}
#: Points of a over [0, A_MAX) scanned for a bracket of rise/span.
SCAN_POINTS = 25
#: Largest a scanned: the arch family ends at A_MAX.
_A_TOP = A_MAX * (1 - 1e-6)
_SPEC = {spec.name: spec for spec in VAULT_SPECS}


@dataclass(frozen=True)
class TargetFit:
    """A vault design fitted to targets.

    Attributes
    ----------
    design : VaultDesign
        The design that meets the targets, or the nearest one the family can build.
    span, rise, p_xz : float
        What that design measures (model units; p_xz dimensionless).
    reached : bool
        Whether every target given is met to ``rtol``.
    message : str
        Empty when reached; otherwise one line: which target is out of reach, what the
        family reaches and the nearest design.
    note : str
        What the fit chose for the user, if anything: the number of tubes when the design
        asks for the most (``tubes = None``) and both span and rise are given.

    Examples
    --------
    >>> fit = TargetFit(VaultDesign(), span=2.0, rise=1.0, p_xz=1.4, reached=True)
    >>> fit.reached, fit.message, fit.require().a
    (True, '', 0.3)
    """

    design: VaultDesign
    span: float
    rise: float
    p_xz: float
    reached: bool
    message: str = ""
    note: str = ""

    def require(self) -> VaultDesign:
        """The design, or :class:`InputError` with :attr:`message` when a target is out of reach.

        Examples
        --------
        >>> TargetFit(VaultDesign(), 2.0, 1.0, 1.4, True).require() == VaultDesign()
        True
        >>> TargetFit(
        ...     VaultDesign(), 2.0, 1.0, 1.4, False, "rise must be at most 1.14 for this family"
        ... ).require()
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: rise must be at most 1.14 for this family
        """
        if not self.reached:
            raise InputError(self.message, parameter="rise")  # only rise/span can be out of reach
        return self.design


def _measure(design: VaultDesign) -> tuple[float, float, float]:
    """(span, rise, p_xz) of a design; raises what :meth:`Vault.from_design` raises."""
    summary = Vault.from_design(design).summary()
    return summary["span"], summary["rise"], summary["p_xz"]


def fit_targets(
    design: VaultDesign,
    *,
    span: float | None = None,
    rise: float | None = None,
    p_xz: float | None = None,
    rtol: float = 1e-9,
) -> TargetFit:
    """Solve for the radius, a and p_xy that give a vault the targets asked of it.

    Parameters
    ----------
    design : VaultDesign
        Holds what stays fixed (width, tubes, layers, direction, fold angle, samples) and
        the parameters no target replaces (a without ``rise`` and ``span`` together, p_xy
        without ``p_xz``, the radius without ``span`` or ``rise``).
    span, rise : float, optional, keyword-only
        Model units. Both: their ratio sets a, the span the radius. One: it sets the radius.
        Where several a give the ratio (at a fixed p_xz it need not be monotone in a), the
        one nearest ``design.a`` is taken, so a design moves continuously with its targets.
    p_xz : float, optional, keyword-only
        Section proportion at the apex; sets p_xy for every a.
    rtol : float, keyword-only
        Relative tolerance of the fit: Brent's method stops at 1e-13 in a, and rise/span
        moves by O(1) per unit of a, so 1e-9 holds with a wide margin.

    Returns
    -------
    TargetFit

    Raises
    ------
    InputError
        A target outside its range, or a design the family cannot build at all (the
        message of the builder).

    Notes
    -----
    With ``tubes = None`` (the most before regression) and both span and rise, the count
    jumps as a changes, so a count is chosen: the most the design has as given, or fewer
    until one reaches the targets; :attr:`TargetFit.note` says which.

    Examples
    --------
    >>> fit = fit_targets(VaultDesign(tubes=9), span=4.0, rise=2.5, p_xz=1.2)
    >>> fit.reached, round(fit.span, 9), round(fit.rise, 9), round(fit.p_xz, 9)
    (True, 4.0, 2.5, 1.2)
    """
    given = {
        name: value
        for name, value in (("span", span), ("rise", rise), ("p_xz", p_xz))
        if value is not None
    }
    for spec in TARGET_SPECS:
        if spec.name in given:
            given[spec.name] = spec.check(given[spec.name])
    if not given:
        span_, rise_, p_xz_ = _measure(design)
        return TargetFit(design, span_, rise_, p_xz_, True)
    if "span" in given and "rise" in given and design.tubes is None:
        return _fit_tube_count(design, given, rtol)

    def shape(a: float) -> VaultDesign:
        """The design at radius 1 with this a, p_xy following p_xz when it is given."""
        p_xy = design.p_xy
        if "p_xz" in given:
            change = proportion_change(
                a, solve_symmetric_arch(a).kappa0_s0, fold_angle=design.fold_angle
            )
            p_xy = given["p_xz"] / change**2
            _SPEC["p_xy"].check(p_xy, f"p_xy for p_xz = {given['p_xz']:g} at a = {a:g}")
        return replace(design, a=float(a), p_xy=float(p_xy), radius=1.0)

    a, note = design.a, ""
    if "span" in given and "rise" in given:
        a, note = _solve_ratio(
            shape, given["span"], given["rise"], design, with_p_xz="p_xz" in given
        )
    unit = shape(a)
    span1, rise1, _ = _measure(unit)
    radius = (
        given["span"] / span1
        if "span" in given
        else given["rise"] / rise1
        if "rise" in given
        else design.radius
    )
    fitted = replace(unit, radius=_SPEC["radius"].check(radius, "radius for the span and rise"))
    span_, rise_, p_xz_ = _measure(fitted)
    if note:
        message = (
            f"{note}; the nearest vault has a = {fitted.a:.6g}, p_xy = {fitted.p_xy:.6g}, "
            f"radius = {fitted.radius:.6g}: span {span_:.6g}, rise {rise_:.6g} (asked: span "
            f"{given['span']:g}, rise {given['rise']:g})"
        )
        return TargetFit(fitted, span_, rise_, p_xz_, False, message)
    got = {"span": span_, "rise": rise_, "p_xz": p_xz_}
    if not all(math.isclose(got[k], v, rel_tol=rtol) for k, v in given.items()):
        raise InternalError(f"the target fit measures {got}, asked {given}")
    return TargetFit(fitted, span_, rise_, p_xz_, True)


def _fit_tube_count(design: VaultDesign, given: dict, rtol: float) -> TargetFit:
    """The fit with the most tubes that reaches the targets, counting down from the most the
    design has as given."""
    most = Vault.from_design(design).design.tubes
    assert most is not None  # a vault's design has its count
    for tubes in range(most, 0, -1):
        fit = fit_targets(replace(design, tubes=tubes), rtol=rtol, **given)
        if fit.reached:
            return replace(
                fit,
                note=f'tubes = "max": {tubes} tubes, the most that reach these targets (at most '
                f"{most}, the most before regression at a = {design.a:g}, "
                f"p_xy = {design.p_xy:g})",
            )
    return replace(
        fit,
        message=f'with tubes = "max" no count from {most} down to 1 reaches '
        f"these targets; {fit.message}",
    )


def _solve_ratio(
    shape, span: float, rise: float, design: VaultDesign, *, with_p_xz: bool
) -> tuple[float, str]:
    """a with rise/span = ratio (the root nearest ``design.a``), or the nearest a and why none is:
    the ratios the family reaches (overlapping ranges merged) and the rise, or the span, that
    would reach the nearest of them.

    The family stands free of regression on runs of a (intervals: regression bounds a for
    a number of tubes). Each run's ends are found by bisection and its extrema refined, and a
    root is searched between consecutive points of a run: a ratio inside the range a run
    states is always met (rise/span is continuous on it), so a refusal agrees with its words.
    """
    from scipy.optimize import brentq

    assert design.tubes is not None  # fit_targets fits a count of None otherwise (_fit_tube_count)
    ratio = rise / span

    def value(a: float) -> float:
        """rise/span at a, NaN where the family cannot build the vault (regression, no arch)."""
        try:
            s, r, _ = _measure(shape(a))
        except (RegressionError, ConvergenceError, InputError):
            return math.nan
        return r / s

    grid = np.linspace(0.0, _A_TOP, SCAN_POINTS)
    values = np.array([value(a) for a in grid])
    runs = _runs(grid, values, value)
    if not runs:
        raise InputError(
            f"no vault of the family with width = {design.width:g} and "
            f"{_tubes(design.tubes)} stands for any a in [0, {A_MAX:.4f}): every one passes "
            "regression; use fewer tubes or a smaller width"
        )
    roots = []
    for a_run, v_run in runs:
        for i in np.flatnonzero((v_run[:-1] - ratio) * (v_run[1:] - ratio) <= 0):
            roots.append(
                brentq(
                    lambda a: value(a) - ratio,
                    a_run[i],
                    a_run[i + 1],
                    xtol=1e-13,
                    rtol=4 * np.finfo(float).eps,
                )
            )
    if roots:
        return float(min(roots, key=lambda a: abs(a - design.a))), ""
    # Out of reach: the nearest point of every run (ends and extrema included).
    points = np.concatenate([a_run for a_run, _ in runs])
    best = float(points[np.argmin(np.abs(np.concatenate([v_run for _, v_run in runs]) - ratio))])
    ranges = _merged(
        [(float(_rounded(v.min(), up=True)), float(_rounded(v.max(), up=False))) for _, v in runs]
    )
    reach = " and ".join(f"from {lo:.6g} to {hi:.6g}" for lo, hi in ranges)
    stands = " and ".join(f"[{a_run[0]:.3g}, {a_run[-1]:.3g}]" for a_run, _ in runs)
    return best, (
        f"rise/span = {ratio:.6g} is out of reach for width = {design.width:g} and "
        f"{_tubes(design.tubes)}: vaults of the family reach rise/span "
        f"{reach}{' at this p_xz' if with_p_xz else ''} (they stand free of regression for a "
        f"in {stands}){_change(span, rise, ranges)}"
    )


def _merged(ranges: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Ranges with the overlapping ones joined, in increasing order.

    Examples
    --------
    >>> _merged([(0.6, 0.7), (0.5, 0.65), (0.8, 0.9)])
    [(0.5, 0.7), (0.8, 0.9)]
    """
    merged: list[tuple[float, float]] = []
    for lo, hi in sorted(ranges):
        if merged and lo <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(hi, merged[-1][1]))
        else:
            merged.append((lo, hi))
    return merged


def _change(span: float, rise: float, ranges: list[tuple[float, float]]) -> str:
    """What reaches the nearest ratio of ``ranges``: the rise for this span, or the span for this
    rise, each rounded into reach.

    Examples
    --------
    >>> _change(4.0, 3.0, [(0.5, 0.625)])[:60]
    '; to reach it, lower the rise to 2.5 (by 0.5) for span 4, or'
    >>> _change(4.0, 3.0, [(0.5, 0.625)])[60:]
    ' raise the span to 4.8 (by 0.8) for rise 3'
    """
    ratio = rise / span
    nearest = min((end for pair in ranges for end in pair), key=lambda end: abs(end - ratio))
    up = nearest > ratio  # rise/span must grow
    new_rise = float(_rounded(nearest * span, up=up))
    new_span = float(_rounded(rise / nearest, up=not up))
    return (
        f"; to reach it, {'raise' if up else 'lower'} the rise to {new_rise:.6g} (by "
        f"{abs(new_rise - rise):.6g}) for span {span:g}, or {'lower' if up else 'raise'} the span "
        f"to {new_span:.6g} (by {abs(new_span - span):.6g}) for rise {rise:g}"
    )


def _rounded(x: float, *, up: bool) -> str:
    """x to 6 significant digits, rounded into the range it bounds (up for a lower end), so every
    value the message states is reached."""
    if float(f"{x:.6g}") == x:  # 2.5 stays 2.5, not 2.49999
        return f"{x:.6g}"
    step = 10.0 ** (math.floor(math.log10(abs(x))) - 5) if x else 1e-6
    text = f"{(math.ceil(x / step) if up else math.floor(x / step)) * step:.6g}"
    return (
        text
        if (float(text) >= x) == up or float(text) == x
        else f"{float(text) + (step if up else -step):.6g}"
    )


def _tubes(n: int) -> str:
    return f"{n} tube" + "s" * (n != 1)


#: Bisection steps for the end of a run of valid a (2⁻²⁴ of a grid step, about 3e-9 in a).
_EDGE_STEPS = 24


def _runs(grid: np.ndarray, values: np.ndarray, value) -> list[tuple[np.ndarray, np.ndarray]]:
    """The runs of valid a: (a, rise/span) at the grid points of each, its ends bisected against the
    invalid neighbours and its interior extrema refined, sorted by a."""
    from scipy.optimize import minimize_scalar

    valid = np.isfinite(values)
    runs = []
    k = 0
    while k < len(grid):
        if not valid[k]:
            k += 1
            continue
        j = k
        while j + 1 < len(grid) and valid[j + 1]:
            j += 1
        points = {float(grid[i]): float(values[i]) for i in range(k, j + 1)}
        for inside, outside in ((k, k - 1), (j, j + 1)):
            if 0 <= outside < len(grid):  # bisect to the end of the valid set
                lo, hi, last = float(grid[inside]), float(grid[outside]), float(values[inside])
                for _ in range(_EDGE_STEPS):
                    mid = 0.5 * (lo + hi)
                    found = value(mid)
                    lo, hi, last = (mid, hi, found) if np.isfinite(found) else (lo, mid, last)
                points[lo] = last
        a_run = np.array(sorted(points))
        v_run = np.array([points[a] for a in a_run])
        # a local extremum of the run: refine it between its neighbours
        for i in range(1, len(a_run) - 1):
            if (v_run[i] - v_run[i - 1]) * (v_run[i + 1] - v_run[i]) < 0:
                sign = 1.0 if v_run[i] < v_run[i - 1] else -1.0

                def signed(a: float, sign: float = sign) -> float:
                    found = value(a)
                    return sign * found if np.isfinite(found) else math.inf

                found = minimize_scalar(
                    signed,
                    bounds=(a_run[i - 1], a_run[i + 1]),
                    method="bounded",
                    options={"xatol": 1e-10},
                )
                if np.isfinite(found.fun):
                    points[float(found.x)] = sign * float(found.fun)
        a_run = np.array(sorted(points))
        runs.append((a_run, np.array([points[a] for a in a_run])))
        k = j + 1
    return runs
