"""The laws of a crease as functions of arc length: rulings, ruling angles, folded curvature.

The corrected Eqs. 2–6 of the paper as :class:`~curvefold.kernel._functions.ScalarFunction`
values (each with its derivative) that :class:`~curvefold.geometry._crease.Crease` holds: β
from the curve (constant or varying α), β_R from a prescribed α, and α, κ, τ of a crease
folded from its pattern.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..kernel._errors import InputError
from ..kernel._functions import Differenced, ScalarFunction, check_finite

__all__ = ["ruling_vectors"]


def ruling_vectors(
    frames: np.ndarray, alpha: ArrayLike, beta_left: ArrayLike, beta_right: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Rulings r_L, r_R (Eqs. 5–6) from frames (..., 3, 3) and angles (...,); each (..., 3)."""
    a = np.asarray(alpha, float)[..., None]
    bl = np.asarray(beta_left, float)[..., None]
    br = np.asarray(beta_right, float)[..., None]
    T, N, B = frames[..., 0], frames[..., 1], frames[..., 2]
    ca, sa = np.cos(a), np.sin(a)
    rl = np.cos(bl) * T + np.sin(bl) * (ca * N + sa * B)
    rr = np.cos(br) * T + np.sin(br) * (-ca * N + sa * B)
    return rl, rr


def _fold_angle_rate(
    kappa_2d: ScalarFunction,
    beta_left: ScalarFunction,
    beta_right: ScalarFunction,
    s: np.ndarray,
    alpha: np.ndarray,
) -> np.ndarray:
    """α' = ½ κ_2D tan α (cot β_L − cot β_R) (the corrected Eq. 3), shape of ``s``."""
    return (
        0.5 * kappa_2d(s) * np.tan(alpha) * (1 / np.tan(beta_left(s)) - 1 / np.tan(beta_right(s)))
    )


@dataclass(frozen=True)
class _RulingAngle(ScalarFunction):
    """β = atan2(κ sin α, τ) on both sides of a crease of constant α, with its exact derivative."""

    kappa: ScalarFunction
    tau: ScalarFunction
    sin_alpha: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return np.arctan2(self.kappa(s) * self.sin_alpha, self.tau(s))

    def derivative(self, s: np.ndarray) -> np.ndarray:
        k, t, sa = self.kappa(s), self.tau(s), self.sin_alpha
        return (
            sa
            * (self.kappa.derivative(s) * t - k * self.tau.derivative(s))
            / ((k * sa) ** 2 + t**2)
        )


@dataclass(frozen=True)
class _VaryingRulingAngle(Differenced):
    """β = atan2(κ sin α, τ + sign · α') for a varying α (sign +1 left, −1 right); β' by
    differences."""

    kappa: ScalarFunction
    tau: ScalarFunction
    alpha: ScalarFunction
    sign: float
    length: float
    step: float

    def value(self, s: np.ndarray) -> np.ndarray:
        return np.arctan2(
            self.kappa(s) * np.sin(self.alpha(s)),
            self.tau(s) + self.sign * self.alpha.derivative(s),
        )


def _check_pattern(probe: np.ndarray, *functions: tuple[str, ScalarFunction, float]) -> None:
    """Raise :class:`InputError` at the first probe where a (name, f, top) leaves (0, top), or is
    not finite."""
    for name, f, top in functions:
        v = f(probe)
        check_finite(v, name=name, s=probe)
        bad = np.flatnonzero(~((v > 0) & (v < top)))
        if bad.size:
            i = bad[0]
            need, shown = (
                ("> 0 everywhere", f"{v[i]:.6g}")
                if top == np.inf
                else (f"in (0°, {np.degrees(top):g}°)", f"{np.degrees(v[i]):.6g}°")
            )
            raise InputError(f"{name} must be {need}; at s = {probe[i]:.6g} it is {shown}")


@dataclass(frozen=True)
class _PrescribedRulingAngle(Differenced):
    """β_R of a crease with α(s) prescribed: cot β_R = cot β_L − 2α' / (κ_2D tan α) (corrected
    Eq. 3)."""

    kappa_2d: ScalarFunction
    beta_left: ScalarFunction
    alpha: ScalarFunction
    length: float
    step: float

    def value(self, s: np.ndarray) -> np.ndarray:
        a = self.alpha(s)
        cot = 1 / np.tan(self.beta_left(s)) - 2 * self.alpha.derivative(s) / (
            self.kappa_2d(s) * np.tan(a)
        )
        return np.arctan2(1.0, cot)


@dataclass(frozen=True, eq=False)
class _PatternFoldAngle(ScalarFunction):
    """α(s) of a crease folded from its pattern: the ODE's dense output, α' from the ODE itself.

    Attributes
    ----------
    solution : scipy.integrate.OdeSolution
        Dense output of α' = ½ κ_2D tan α (cot β_L − cot β_R) (picklable).
    kappa_2d, beta_left, beta_right : ScalarFunction
        The pattern, β in radians.
    """

    solution: Callable[[np.ndarray], np.ndarray]
    kappa_2d: ScalarFunction
    beta_left: ScalarFunction
    beta_right: ScalarFunction

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.solution(s.ravel())[0].reshape(s.shape)

    def derivative(self, s: np.ndarray) -> np.ndarray:
        s = np.asarray(s, float)
        return _fold_angle_rate(self.kappa_2d, self.beta_left, self.beta_right, s, self(s))


@dataclass(frozen=True)
class _PatternCurvature(ScalarFunction):
    """κ = κ_2D / cos α of a crease folded from its pattern (Eq. 2), with its exact derivative."""

    kappa_2d: ScalarFunction
    alpha: ScalarFunction

    def value(self, s: np.ndarray) -> np.ndarray:
        return self.kappa_2d(s) / np.cos(self.alpha(s))

    def derivative(self, s: np.ndarray) -> np.ndarray:
        a, ca = self.alpha(s), np.cos(self.alpha(s))
        return (
            self.kappa_2d.derivative(s) / ca
            + self.kappa_2d(s) * np.sin(a) * self.alpha.derivative(s) / ca**2
        )


@dataclass(frozen=True)
class _PatternTorsion(ScalarFunction):
    """τ = ½ κ_2D tan α (cot β_L + cot β_R) of a crease folded from its pattern (Eq. 4
    corrected)."""

    kappa_2d: ScalarFunction
    alpha: ScalarFunction
    beta_left: ScalarFunction
    beta_right: ScalarFunction

    def value(self, s: np.ndarray) -> np.ndarray:
        return (
            0.5
            * self.kappa_2d(s)
            * np.tan(self.alpha(s))
            * (1 / np.tan(self.beta_left(s)) + 1 / np.tan(self.beta_right(s)))
        )

    def derivative(self, s: np.ndarray) -> np.ndarray:
        k, a, bl, br = self.kappa_2d(s), self.alpha(s), self.beta_left(s), self.beta_right(s)
        cot_sum = 1 / np.tan(bl) + 1 / np.tan(br)
        d_cot_sum = (
            -self.beta_left.derivative(s) / np.sin(bl) ** 2
            - self.beta_right.derivative(s) / np.sin(br) ** 2
        )
        d_tan = self.alpha.derivative(s) / np.cos(a) ** 2
        return 0.5 * (
            (self.kappa_2d.derivative(s) * np.tan(a) + k * d_tan) * cot_sum
            + k * np.tan(a) * d_cot_sum
        )
