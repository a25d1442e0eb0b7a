"""The geometric certificate of a built structure: every invariant measured against a tolerance.

Tolerances are stated with the reason for their size. Finite-difference measurements
(developability, frame agreement, Eq. 19) converge at fourth order in the sample spacing h;
chord lengths of the polyline creases change with curvature at second order; the width,
area and closure laws and the ground plane hold to rounding.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..geometry.crease import Crease
from ..geometry.panels import PanelLattice
from ..geometry.structure import Structure
from ..vault.assembly import Vault
from . import measure
from .panels import panel_checks

__all__ = ["Check", "certify"]


@dataclass(frozen=True)
class Check:
    """One measured invariant.

    Attributes
    ----------
    name : str
        Short identifier (stable, used as a JSON key).
    value : float
        The measured number.
    tolerance : float
        The largest accepted value (for ``regression_margin``: the smallest).
    unit : str
    passed : bool
    meaning : str
        What was measured and why the tolerance is what it is.
    """

    name: str
    value: float
    tolerance: float
    unit: str
    passed: bool
    meaning: str

    def to_dict(self) -> dict:
        return asdict(self)


def _check(name: str, value: float, tolerance: float, unit: str, meaning: str, *, at_least: bool = False) -> Check:
    passed = bool(value >= tolerance) if at_least else bool(value <= tolerance)
    return Check(name, float(value), float(tolerance), unit, passed, meaning)


def certify(crease: Crease, structure: Structure | None = None, vault: Vault | None = None) -> list[Check]:
    """Measure every invariant that applies and compare it with its tolerance.

    Parameters
    ----------
    crease : Crease
        Curve 1 (or the single curved fold).
    structure : Structure, optional
        The tube, block or vault stack built on the crease's lattice.
    vault : Vault, optional
        Adds the vault's ground-plane and proportion checks.
    """
    h = float(crease.s[1] - crease.s[0])
    kh = float(np.max(crease.curve.kappa(crease.s)) * h)
    checks = [
        _check(
            "developability",
            measure.developability_residual(crease),
            max(1e-6, 100 * kh**4),
            "rad per unit length",
            "|r'·p| on both sides of curve 1: the tangent plane must not turn along a ruling; "
            "fourth-order differences leave ~(κh)⁴",
        )
    ]
    # Eq. (2): the crease's curvature measured from its built points, times cos α, is κ_2D.
    x = crease.curve.points
    d1 = measure.derivative(x, h)[2:-2]
    d2 = measure.derivative(measure.derivative(x, h), h)
    kappa = np.linalg.norm(np.cross(d1, d2), axis=1) / np.linalg.norm(d1, axis=1) ** 3
    s_in = crease.s[4:-4]
    k2 = crease.curve.kappa(s_in) * np.cos(crease.alpha(s_in))
    checks.append(
        _check(
            "eq2_planar_curvature",
            float(np.max(np.abs(kappa * np.cos(crease.alpha(s_in)) / k2 - 1))),
            max(1e-6, 100 * kh**4),
            "relative",
            "κ of the built crease (differences of its points) times cos α against κ_2D of the crease pattern (Eq. 2)",
        )
    )
    if structure is None:
        return checks
    if isinstance(structure.lattice, PanelLattice):  # rigid panels: their own checks (analysis.panels)
        return checks + [Check(**row) for row in panel_checks(structure, vault)]
    lattice = structure.lattice
    state = structure.state()
    flat = structure.state(0.0)
    size = float(np.abs(state.vertices).max() + crease.curve.length)
    far = structure.curves_uv[np.argmax(np.abs(structure.curves_uv).sum(axis=1))]
    iso = measure.isometry_error(state.mesh(), flat.mesh())
    kappa_max = float(np.max(lattice.crease.curve.kappa(lattice.s)))
    chord = (1.5 * kappa_max * h) ** 2 / 24
    aspect = max(float(np.max(length)) for length in lattice.ruling_lengths) / h
    closure, agreement = measure.tube_closure(lattice)
    checks += [
        _check(
            "frame_agreement",
            measure.frame_agreement(lattice, [[0, 1], [1, 1], [1, 0], far]),
            max(1e-6, 100 * kh**4),
            "rad",
            "angle between each lattice curve's tangent and curve 1's at equal t (shared frames); fourth-order differences",
        ),
        _check(
            "isometry_edges",
            iso.max_relative_edge_error,
            chord,
            "relative",
            "edge lengths of every strip at the design angle against the flat crease pattern; a polyline "
            "chord of an arc of curvature κ is shorter by (κh)²/24, which bounds the change",
        ),
        _check(
            "isometry_angles",
            iso.max_angle_error,
            chord * aspect,
            "rad",
            "triangle corner angles against the flat crease pattern: first order in the edge error, "
            "amplified at most by the triangles' aspect ratio (longest ruling / step)",
        ),
        _check(
            "ruling_quad_planarity",
            measure.ruling_quad_planarity(state),
            max(1e-6, 10 * kh**3),
            "relative",
            "distance of each ruling quad's fourth corner from the plane of the other three, over its diagonal; "
            "consecutive rulings of a developable are coplanar to third order",
        ),
        _check("width_law", measure.width_law_error(lattice), 1e-10, "relative", "widths between parallel tangent lines against exp(∓∫ τ cot α ds)"),
        _check("section_area", measure.section_area_error(lattice), 1e-10, "relative", "area of the section parallelogram along t (constant, w_L w_R sin 2α)"),
        _check(
            "eq19",
            max(measure.eq19_residual(lattice, [0, 0], [0, 1]), measure.eq19_residual(lattice, [0, 1], [1, 1])),
            max(1e-6, 100 * kh**4),
            "relative",
            "the paper's Eq. (19) between neighbouring creases, with κ and ds measured from the built curves",
        ),
        _check("tube_closure", closure / size, 1e-12, "relative", "a tube built crease by crease from each crease's own invariants closes onto curve 1"),
        _check("chain_vs_lattice", agreement / size, 1e-11, "relative", "curves built crease by crease agree with the lattice formula (Eq. 11)"),
        _check(
            "fold_angles",
            measure.fold_angle_error(state.mesh(), lattice.crease.fold_angle),
            0.05 + 10 * np.degrees(kh) * kh,
            "degrees",
            "mesh fold angles on the creases against 2α (folds) and 180° − 2α (seams); polyline creases deviate ~(κh)²",
        ),
        _check(
            "regression_margin",
            float(lattice.domain.margin(structure.curves_uv.astype(float)).min()),
            0.0,
            "",
            "smallest speed factor 1 − u w_L/w_lim_L − v w_R/w_lim_R over every crease (Eq. 17); must stay positive",
            at_least=True,
        ),
    ]
    if vault is not None:
        p_xy, change = vault.measured_proportions()
        checks += [
            _check("ground_plane", vault.ground_error() / size, 1e-13, "relative", "largest |z| of every end section at the design angle"),
            _check(
                "proportion_change",
                abs(change / vault.proportion_change - 1),
                1e-10,
                "relative",
                "w_R(s0/2)/w_R(0) measured between tangent lines against exp(a κ0 s0 cot α / π)",
            ),
        ]
    return checks
