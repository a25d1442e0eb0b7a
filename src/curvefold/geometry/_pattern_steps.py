"""The work of folding a crease from its pattern, bounded before it runs.

:meth:`Crease.from_pattern <curvefold.geometry.Crease.from_pattern>` integrates
``α' = ½ κ_2D tan α (cot β_L − cot β_R)`` with DOP853 and keeps its dense output: one
interpolant per step, so time and memory grow with the steps, which the sample count does
not set. The steps are about ``1.5 L · r`` with r the fastest relative change of κ_2D and
of cot β along the crease (measured at rtol 1e-12 for κ_2D = 0.5 + 0.25 sin(ωs), where
r = ω/√3, and β_L, β_R of ``examples/single-fold.toml``, L = 3: 3 115 steps = 1.8 L·r for
ω = 10³; 23 591 = 1.4 L·r for ω = 10⁴, 48 s and 16 MB). :func:`require_pattern_steps`
refuses an estimate past :data:`MAX_PATTERN_STEPS` before the integration; a change too
fast for the probes to see (an expression oscillating between them) is stopped by
:class:`StepGuard` once the integration has taken that many steps.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..kernel._errors import InputError
from ..kernel._functions import ScalarFunction

__all__ = ["MAX_PATTERN_STEPS", "pattern_steps", "require_pattern_steps", "StepGuard"]

#: Most DOP853 steps of a crease folded from its pattern (about 8 s and 3 MB of dense output
#: for an expression; a smooth design takes tens).
MAX_PATTERN_STEPS = 4_000
#: Right-hand side evaluations per step: 12 stages, 3 more for the dense output, a rejected
#: step now and then.
_CALLS_PER_STEP = 20
#: Points where the rates are read (an expression's derivative is a difference 1e-3 wide).
PROBES = 4001
_ADVICE = "make kappa_2d and beta_left/beta_right vary more slowly along the crease"


def pattern_steps(
    length: float, kappa_2d: ScalarFunction, beta_left: ScalarFunction, beta_right: ScalarFunction
) -> float:
    """About how many steps DOP853 takes: ``1.5 L · r``, r the largest of ``|κ_2D'| / κ_2D`` plus
    ``|β'| / sin² β`` on each side (the change of cot β) on :data:`PROBES` points.

    Examples
    --------
    >>> from curvefold.kernel import Constant
    >>> pattern_steps(3.0, Constant(0.5), Constant(1.4), Constant(1.7))
    0.0
    """
    probe = np.linspace(0.0, length, PROBES)
    with np.errstate(all="ignore"):
        rate = np.abs(kappa_2d.derivative(probe) / kappa_2d(probe))
        for beta in (beta_left, beta_right):
            rate = rate + np.abs(beta.derivative(probe)) / np.sin(beta(probe)) ** 2
    top = float(np.max(rate, initial=0.0))
    return 1.5 * length * (top if np.isfinite(top) else 0.0)


def require_pattern_steps(
    length: float, kappa_2d: ScalarFunction, beta_left: ScalarFunction, beta_right: ScalarFunction
) -> float:
    """:func:`pattern_steps`, or :class:`InputError` (parameter ``kappa_2d``) past the limit."""
    steps = pattern_steps(length, kappa_2d, beta_left, beta_right)
    if steps > MAX_PATTERN_STEPS:
        raise InputError(
            f"folding the crease from its pattern needs about {steps:.3g} integration steps "
            f"(κ_2D or cot β changes by its own size every {1.5 * length / steps:.3g} of the "
            f"length {length:g}), more than the {MAX_PATTERN_STEPS} curvefold takes; " + _ADVICE,
            parameter="kappa_2d",
        )
    return steps


class StepGuard:
    """A right-hand side that stops the integration with :class:`InputError` once it has been
    called for more than :data:`MAX_PATTERN_STEPS` steps."""

    def __init__(self, rhs: Callable[[float, np.ndarray], np.ndarray]) -> None:
        self.rhs, self.calls = rhs, 0

    def __call__(self, s: float, y: np.ndarray) -> np.ndarray:
        self.calls += 1
        if self.calls > _CALLS_PER_STEP * MAX_PATTERN_STEPS:
            raise InputError(
                f"folding the crease from its pattern took more than {MAX_PATTERN_STEPS} "
                f"integration steps by s = {s:.6g} (κ_2D or β changes faster than its "
                "probes showed); " + _ADVICE,
                parameter="kappa_2d",
            )
        return self.rhs(s, y)
