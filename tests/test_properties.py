"""Property-based checks: random smooth κ > 0, τ, fold angles and widths inside the domain.

Laws that hold exactly (widths, areas, closure) are checked to rounding. Quantities
measured by finite differences (developability, frame agreement, Eq. 19) vanish only up
to truncation, whose size depends on the drawn curve; for those each example is built at
two resolutions and the residual must fall at least 4× when h halves (fourth order gives
16× asymptotically; designs drawn close to regression are still pre-asymptotic at these
resolutions) unless it is already at rounding — a wrong formula leaves an O(1) residual
that does not fall.
"""

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from curvefold import Crease, Lattice, SpaceCurve, Structure, measure
from curvefold.geometry.lattice import Pattern, log_width_ratio

SAMPLES, LENGTH = 401, 2.0

coefficient = st.floats(-1.0, 1.0, allow_nan=False)
frequency = st.floats(0.2, 2.0, allow_nan=False)


@st.composite
def lattice_builders(draw):
    """A random design; returns build(samples) -> (Lattice, fold_angle)."""
    k0 = draw(st.floats(0.3, 2.0))
    k1 = draw(st.floats(0.0, 0.9)) * k0  # keeps κ > 0
    fk, ft = draw(frequency), draw(frequency)
    t0, t1 = draw(coefficient), draw(coefficient)
    phase = draw(st.floats(0, 2 * np.pi))
    fold_angle = draw(st.floats(15.0, 165.0))
    theta = draw(st.floats(0.1, np.pi / 2 - 0.1))
    fraction = draw(st.floats(0.05, 0.8))

    def build(samples: int = SAMPLES):
        curve = SpaceCurve.from_curvature(
            lambda s: k0 + k1 * np.sin(fk * s + phase), lambda s: t0 + t1 * np.cos(ft * s), LENGTH, samples=samples
        )
        crease = Crease.from_curve(curve, fold_angle=fold_angle)
        # Buildable designs: proportions that change less than 100× along the crease (a
        # design whose width shrinks 10⁸× has widths below coordinate rounding somewhere).
        log_ratio = log_width_ratio(crease)
        assume(np.ptp(log_ratio) < np.log(100.0))
        unit = Lattice(crease, Pattern.from_crease(crease, np.exp(-log_ratio), np.exp(log_ratio)))
        # widths at a fraction of the largest valid unit cell along a random direction
        d = np.array([np.cos(theta), np.sin(theta)]) / max(np.cos(theta), np.sin(theta))
        reach = min(float(unit.domain.extent(d)), float(unit.domain.extent([1, 0])) / d[0], float(unit.domain.extent([0, 1])) / d[1])
        scale = min(reach * fraction, 0.3 / k0)  # every corner of the unit cell inside
        return Lattice.from_crease(crease, scale * d[0], scale * d[1]), fold_angle

    return build


SETTINGS = settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def converges(fine: float, coarse: float, *, floor: float, order: int = 4) -> bool:
    """Truncation of the given order: halving h divides the residual by 2^order (a quarter asked)."""
    return fine < floor or fine * 2 ** (order - 2) < coarse


@SETTINGS
@given(lattice_builders())
def test_random_lattices_satisfy_the_geometry(build):
    lattice, _ = build()
    coarse, _ = build((SAMPLES + 1) // 2)
    assert converges(measure.developability_residual(lattice.crease), measure.developability_residual(coarse.crease), floor=1e-11)
    uv = [[0, 1], [1, 1], [1, 0]]
    assert converges(measure.frame_agreement(lattice, uv), measure.frame_agreement(coarse, uv), floor=1e-11)
    for a, b in (([0, 0], [0, 1]), ([0, 1], [1, 1])):
        assert converges(measure.eq19_residual(lattice, a, b), measure.eq19_residual(coarse, a, b), floor=1e-10)
    # exact laws, measured from coordinates of size |x|: rounding ~ε|x|/w relative to a width w
    rounding = 1e-14 * (np.abs(lattice.crease.curve.points).max() + LENGTH) / min(lattice.width_left.min(), lattice.width_right.min())
    assert measure.width_law_error(lattice) < 1e-12 + rounding
    assert measure.section_area_error(lattice) < 1e-12 + rounding
    closure, agreement = measure.tube_closure(lattice)
    size = np.abs(lattice.crease.curve.points).max() + LENGTH
    assert closure < 1e-13 * size and agreement < 1e-12 * size


@SETTINGS
@given(lattice_builders(), st.floats(0.0, 170.0))
def test_random_tubes_fold_isometrically(build, other_angle):
    errors = []
    for samples in (SAMPLES, (SAMPLES + 1) // 2):
        lattice, _ = build(samples)
        tube = Structure.tube(lattice)
        assert lattice.domain.contains(tube.curves_uv).all()
        errors.append(measure.isometry_error(tube.state(other_angle).mesh(), tube.state(0).mesh()).max_relative_edge_error)
    assert converges(errors[0], errors[1], floor=1e-12, order=2)
