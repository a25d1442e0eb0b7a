"""Scalar functions of arc length: data, not closures; derivatives that stay in the domain."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from curvefold.kernel._functions import (
    Constant,
    Sampled,
    Scaled,
    UserFunction,
    as_function,
    difference_derivative,
    difference_step,
)


def square_root_near_zero(s):
    """√(s + 0.5): smooth on [0, 1], undefined left of −0.5."""
    return np.sqrt(s + 0.5)


def test_derivatives_never_sample_outside_the_domain():
    seen = []

    def f(s):
        seen.append(np.asarray(s, float).copy())
        return np.sin(3 * s)

    s = np.concatenate([np.linspace(0.0, 2.0, 201), [1e-17, 2.0 - 1e-16]])
    d = as_function(f, name="f", length=2.0).derivative(s)
    seen = np.concatenate(seen)
    assert seen.min() >= 0.0 and seen.max() <= 2.0
    assert_allclose(d, 3 * np.cos(3 * s), rtol=0, atol=1e-10)


def test_a_sqrt_type_derivative_is_finite_and_sixth_order_at_both_ends():
    """The defect: the central stencil sampled κ = 1 + √s at s < 0 and got NaN at s = 0.

    Near the ends the stencil shifts into the domain and keeps its order: on √(s + 0.5) at
    s = 0 and its mirror image √(1.5 − s) at s = 1, halving h divides the error by about
    2⁶ (orders 5.6, 5.8: the one-sided stencil's h⁷ term still shows at h = 0.02).
    """
    d = as_function(lambda s: 1 + np.sqrt(s), name="kappa", length=2.0).derivative(
        np.array([0.0, 2.0])
    )
    assert np.isfinite(d).all() and d[0] > 10  # the true slope at 0 is infinite
    assert_allclose(d[1], 0.5 / np.sqrt(2.0), rtol=1e-9)
    for f, end, exact in (
        (square_root_near_zero, 0.0, 0.5 / np.sqrt(0.5)),
        (lambda s: np.sqrt(1.5 - s), 1.0, -0.5 / np.sqrt(0.5)),
    ):
        errors = np.array(
            [
                abs(difference_derivative(f, np.array([end]), length=1.0, step=h)[0] - exact)
                for h in (0.02, 0.01, 0.005)
            ]
        )
        orders = np.log2(errors[:-1] / errors[1:])
        assert ((orders > 5.5) & (orders < 6.5)).all(), orders
    # at the default step the error is at the rounding level
    ends = np.array([0.0, 1.0])
    assert_allclose(
        as_function(square_root_near_zero, name="f", length=1.0).derivative(ends),
        0.5 / np.sqrt(ends + 0.5),
        rtol=1e-11,
    )


def test_difference_step_leaves_room_for_the_stencil():
    assert difference_step(5.0) == 5e-3 and difference_step(0.5) == 1e-3
    short = 1e-3
    h = difference_step(short)
    assert 6 * h < short
    assert_allclose(
        as_function(np.exp, name="f", length=short).derivative(np.array([0.0, short])),
        np.exp([0.0, short]),
        rtol=1e-6,
    )


@pytest.mark.parametrize(
    "f",
    [
        Constant(2.5),
        Sampled(np.linspace(1.0, 2.0, 7) ** 2, 3.0),
        UserFunction(square_root_near_zero, 3.0, difference_step(3.0)),
        Scaled(Sampled(np.array([1.0, 3.0, 2.0, 5.0]), 3.0), -0.5),
    ],
    ids=["constant", "samples", "callable", "scaled"],
)
def test_scalar_functions_are_picklable_data(f):
    s = np.linspace(0.0, 3.0, 13)
    back = pickle.loads(pickle.dumps(f))
    assert type(back) is type(f) and back.constant == f.constant
    assert_array_equal(back(s), f(s))
    assert_array_equal(back.derivative(s), f.derivative(s))


def test_constants_and_samples_keep_their_meaning():
    assert as_function(2.0, name="k", length=1.0).constant == 2.0
    assert as_function(2.0, name="k", length=1.0).scaled(3.0).constant == 6.0
    samples = np.array([1.0, 2.0, 4.0])
    f = as_function(samples, name="k", length=2.0)
    samples[0] = 7.0  # the function keeps its own read-only copy
    assert f(np.array([0.0]))[0] == 1.0 and not f.samples.flags.writeable
    assert as_function(f, name="k", length=2.0) is f
