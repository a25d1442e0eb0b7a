"""The bend allowance of thick sheets (curvefold.geometry._bend) against a bent strip built and
measured independently: its neutral fibre sampled as a polyline, its outer mold lines crossed by
a linear solve."""

from __future__ import annotations

import numpy as np
import pytest

from curvefold import InputError
from curvefold.geometry._bend import Bend, bend_for, crease_insets, din6935_k


def bent_strip(bend: Bend, fold: float, legs: tuple[float, float], n: int) -> dict:
    """A strip bent by ``fold`` degrees: flat legs, then an arc of the inner radius, the
    neutral fibre K t inside it. The legs' lengths are the design's: along the neutral
    surface's sharp fold, to its virtual corner. Returns the neutral fibre as a polyline of n
    arc segments and the outer surface's two lines."""
    theta = np.radians(fold)
    rho = bend.radius + bend.k * bend.thickness
    outer = bend.radius + bend.thickness
    # the arc's centre at the origin; the bend turns from direction +x by theta
    phi = np.linspace(-np.pi / 2, -np.pi / 2 + theta, n + 1)
    arc = rho * np.c_[np.cos(phi), np.sin(phi)]
    d0, d1 = np.array([1.0, 0.0]), np.array([np.cos(theta), np.sin(theta)])
    # the design's sharp neutral fold: where the legs' lines cross (a linear solve)
    s, _ = np.linalg.solve(np.c_[d0, -d1], arc[-1] - arc[0])
    corner = arc[0] + s * d0
    start = corner - legs[0] * d0
    end = corner + legs[1] * d1
    fibre = np.vstack([start, arc, end])
    # the outer surface's lines: offset from the neutral ones by (1 − K) t, away from the centre
    o0 = arc[0] / rho * outer
    o1 = arc[-1] / rho * outer
    u, _ = np.linalg.solve(np.c_[d0, -d1], o1 - o0)
    outer_corner = o0 + u * d0
    n0 = start + (outer - rho) * arc[0] / rho  # the fibre's ends carried to the outer surface
    n1 = end + (outer - rho) * arc[-1] / rho
    return {
        "flat": np.linalg.norm(np.diff(fibre, axis=0), axis=1).sum(),
        "arc": np.linalg.norm(np.diff(arc, axis=0), axis=1).sum(),
        "mold": (np.linalg.norm(outer_corner - n0), np.linalg.norm(n1 - outer_corner)),
    }


@pytest.mark.parametrize(
    ("fold", "radius", "k"), [(90.0, 1.0, 0.325), (30.0, 2.0, 0.4), (150.0, 0.5, 0.5)]
)
def test_allowance_inset_and_deduction_match_a_bent_strip(fold, radius, k):
    """The polyline's length converges as 1/n² (Richardson from n and 2n): the measured flat
    length agrees with the closed forms to 1e-12 of the legs."""
    bend = Bend(1.0, radius, k)
    legs = (20.0, 30.0)
    coarse, fine = (bent_strip(bend, fold, legs, n) for n in (2000, 4000))
    flat = fine["flat"] + (fine["flat"] - coarse["flat"]) / 3
    arc = fine["arc"] + (fine["arc"] - coarse["arc"]) / 3
    assert arc == pytest.approx(float(bend.allowance(fold)), abs=1e-10)
    # the flat pattern of the design's legs, each side moved in by the inset
    assert flat == pytest.approx(sum(legs) - 2 * float(bend.inset(fold)), abs=1e-10)
    # the workshop's dimensions: the outer mold lines, less the deduction
    assert flat == pytest.approx(sum(fine["mold"]) - float(bend.deduction(fold)), abs=1e-10)
    # damaged: the K-factor forgotten (the inner radius taken as neutral) misses by K t θ
    wrong = Bend(1.0, radius, 0.0)
    miss = abs(sum(legs) - 2 * float(wrong.inset(fold)) - flat)
    assert miss > 1e-3


def test_small_folds_set_back_by_the_cube_of_the_angle():
    bend = Bend(0.001, 0.002, 0.5)
    theta = np.radians(np.array([0.1, 0.2]))
    d = bend.inset(np.degrees(theta))
    assert d == pytest.approx(bend.neutral_radius * theta**3 / 24, rel=2e-6)


def test_din6935_runs_from_the_inside_to_the_mid_surface():
    assert din6935_k(1.0, 1.0) == pytest.approx(0.325, abs=1e-15)  # k = 0.65 at R = t
    assert din6935_k(5.0, 1.0) == pytest.approx(0.5, abs=3e-4)  # meets k = 1 at R/t = 5
    assert din6935_k(6.0, 1.0) == 0.5
    assert bend_for("aluminium", 0.002).k == din6935_k(0.002, 0.002)
    assert (
        bend_for("plywood", 0.01, 0.02).k == 0.5 and "assumed" in bend_for("plywood", 0.01).source
    )


def test_crease_insets_follow_the_fold_angle_2_alpha():
    bend = bend_for("aluminium", 0.001)
    alpha = np.radians(np.linspace(0, 60, 7))
    ba, d = crease_insets(alpha, bend)
    assert ba == pytest.approx(2 * alpha * bend.neutral_radius, abs=1e-15)
    assert d[0] == 0 and np.all(np.diff(d) > 0)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: Bend(1.0, 1.0, 1.5), r"^k_factor must be in \[0, 1\] .*got 1\.5$"),
        (lambda: Bend(0.0, 1.0, 0.5), r"^thickness must be > 0 model units, got 0\.0$"),
        (lambda: Bend(1.0, 1.0, 0.5).allowance([10, 190]), r"^fold angle must be in \[0, 180\)"),
        (lambda: din6935_k(0.01, 1.0), r"^R/t must be ≥ 0\.05 .*got 0\.01$"),
        (lambda: bend_for("steel", 0.001), r"^material must be one of aluminium, .*got 'steel'$"),
    ],
)
def test_bad_bends_are_one_line(call, match):
    with pytest.raises(InputError, match=match) as info:
        call()
    assert "\n" not in str(info.value)
