"""Bend allowance of a thick sheet: how much a crease pattern must give up where a sheet of
thickness t bends round a radius instead of folding on a line.

A sheet of thickness t folded by an angle θ (the fold angle, 0 flat) bends round an inner
radius R; its neutral surface, where the length does not change, lies K·t from the inside
(K the *K-factor*, sheet-metal practice). The zero-thickness design is a sharp fold of that
neutral surface; the real sheet replaces the corner by an arc of radius ρ = R + K t:

* bend allowance ``BA = θ (R + K t)``: the neutral arc's length (the sheet between the tangent
  points of the bend);
* bend deduction ``BD = 2 (R + t) tan(θ/2) − BA``: what the flat length is shorter than the two
  outside mold-line lengths (to the virtual sharp of the outer surface), the workshop's
  dimension;
* inset ``δ = ρ (tan(θ/2) − θ/2)``: how far each side of the crease moves in on the flat
  pattern, when the design's faces are the neutral surface with a sharp fold: the legs reach
  ρ tan(θ/2) past the tangent points, the arc only ρ θ/2. For small θ, δ ≈ ρ θ³/24.

The K-factor is empirical. For bent metal sheet, DIN 6935 gives the correction factor
``k = 0.65 + 0.5 log10(R/t)`` for R/t ≤ 5 (k = 1 beyond), K = k/2: 0.325 at R = t, 0.5 (the
mid-surface) from R = 5t on. The closed forms are exact for that model (measured against a
bent strip built apart, to 1e-10 of its 50 units: ``tests/test_bend.py``); the remaining error is
the K-factor's, a fit and not a law: a K off by ΔK moves the allowance by ΔK θ t (0.08 mm for
ΔK = 0.05 at a 90° fold of a 1 mm sheet). Polymers, board and plywood have no such practice
(a scored or creased line crushes the sheet rather than bending it): their K is the
mid-surface's 0.5, stated as an assumption (:data:`K_SOURCES`); give a measured one where
it matters.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
from numpy.typing import ArrayLike

from ..kernel._errors import InputError
from ..kernel._validate import Spec

__all__ = ["Bend", "K_SOURCES", "din6935_k", "bend_for", "crease_insets"]

#: Where each material's K-factor comes from (curvefold.mechanics.MATERIALS' names).
K_SOURCES = MappingProxyType(
    {
        "aluminium": "DIN 6935: k = 0.65 + 0.5 log10(R/t) for R/t ≤ 5, k = 1 beyond; K = k/2",
        "polypropylene": "no sheet-metal practice for a scored polymer: K = 0.5 (the "
        "mid-surface) assumed",
        "paperboard": "no sheet-metal practice for creased board: K = 0.5 (the mid-surface) "
        "assumed",
        "plywood": "no sheet-metal practice for plywood: K = 0.5 (the mid-surface) assumed",
    }
)
_RATIO = Spec("R/t", "real", None, "[0.05, inf)", why="k = 0.65 + 0.5 log10(R/t) > 0")
_K = Spec("k_factor", "real", None, "[0, 1]", why="the neutral surface lies within the sheet")
_LENGTH = Spec("length", "real", None, "(0, inf)", "model units")
_ANGLE = Spec("fold angle", "real", None, "[0, 180)", "degrees")


def din6935_k(radius: float, thickness: float) -> float:
    """The K-factor of DIN 6935 for an inner bend radius R and thickness t.

    Examples
    --------
    >>> din6935_k(1.0, 1.0), din6935_k(10.0, 1.0)
    (0.325, 0.5)
    """
    ratio = _RATIO.check(_LENGTH.check(radius, "radius") / _LENGTH.check(thickness, "thickness"))
    return 0.5 if ratio > 5 else 0.5 * (0.65 + 0.5 * float(np.log10(ratio)))


@dataclass(frozen=True)
class Bend:
    """How a sheet bends at its creases: thickness t, inner radius R and K-factor, with the
    K-factor's source (module notes).

    Examples
    --------
    >>> b = Bend(1.0, 1.0, 0.325)
    >>> round(float(b.allowance(90)), 6), round(float(b.deduction(90)), 6)
    (2.081305, 1.918695)
    """

    thickness: float
    radius: float
    k: float
    source: str = "given"

    def __post_init__(self) -> None:
        _LENGTH.check(self.thickness, "thickness")
        _LENGTH.check(self.radius, "radius")
        _K.check(self.k)

    def _theta(self, fold_angle: ArrayLike) -> np.ndarray:
        a = np.asarray(fold_angle, float)
        if not np.all((a >= 0) & (a < 180)):
            bad = a[~((a >= 0) & (a < 180))].ravel()[0]
            _ANGLE.check(float(bad))
        return np.radians(a)

    @property
    def neutral_radius(self) -> float:
        """ρ = R + K t."""
        return self.radius + self.k * self.thickness

    def allowance(self, fold_angle: ArrayLike) -> np.ndarray:
        """BA = θ (R + K t) at fold angles θ in degrees."""
        return self._theta(fold_angle) * self.neutral_radius

    def deduction(self, fold_angle: ArrayLike) -> np.ndarray:
        """BD = 2 (R + t) tan(θ/2) − BA at fold angles θ in degrees."""
        theta = self._theta(fold_angle)
        return 2 * (self.radius + self.thickness) * np.tan(theta / 2) - self.allowance(fold_angle)

    def inset(self, fold_angle: ArrayLike) -> np.ndarray:
        """δ = ρ (tan(θ/2) − θ/2): how far each side of a crease moves in on the flat pattern of
        a design drawn on the neutral surface, at fold angles θ in degrees."""
        theta = self._theta(fold_angle)
        return self.neutral_radius * (np.tan(theta / 2) - theta / 2)


def bend_for(material: str, thickness: float, radius: float | None = None) -> Bend:
    """The bend of a named material's sheet (:data:`K_SOURCES`): inner radius R (default t), the
    K-factor of DIN 6935 for aluminium, the mid-surface's 0.5 for the others.

    Examples
    --------
    >>> bend_for("aluminium", 0.001).k, bend_for("plywood", 0.01).k
    (0.325, 0.5)
    >>> bend_for("steel", 0.001)
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: material must be one of aluminium, polypropylene,
    paperboard, plywood for a bend allowance, got 'steel'
    """
    if material not in K_SOURCES:
        raise InputError(
            f"material must be one of {', '.join(K_SOURCES)} for a bend allowance, got "
            f"{material!r}",
            parameter="material",
        )
    r = thickness if radius is None else radius
    k = din6935_k(r, thickness) if material == "aluminium" else 0.5
    return Bend(thickness, r, k, K_SOURCES[material])


def crease_insets(alpha: np.ndarray, bend: Bend) -> tuple[np.ndarray, np.ndarray]:
    """Bend allowance and inset along a crease whose fold angle is 2α(s) (α in radians, a
    crease's ``alpha`` at its samples): (BA(s), δ(s)), model
    units, each measured across the crease.

    Examples
    --------
    >>> ba, d = crease_insets(np.radians([0.0, 45.0]), Bend(0.001, 0.001, 0.5))
    >>> ba.round(9).tolist(), d.round(9).tolist()
    ([0.0, 0.002356194], [0.0, 0.000321903])
    """
    fold = np.degrees(2 * np.asarray(alpha, float))
    return bend.allowance(fold), bend.inset(fold)
