"""The checks of the certificate: each a measurement of a built frame, its error model and its
scope.

:data:`CHECKS` is the registry: a :class:`CheckSpec` per check, in report order, with the
measurement ``Frame -> Residual`` (:mod:`curvefold.analysis._frames`), the order p of its
error and its cap, and the scope it applies to (a crease, every frame of a smooth
structure, a smooth vault, every frame of a rigid one, a rigid vault, the mechanism).
:func:`curvefold.analysis.certify` measures them and judges every residual
against its tolerance (the error model is in its module notes).

Adding a check is one entry in :data:`CHECKS`; a test must damage a design so that it fails.
"""

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from . import _check_measures as measures
from ._frames import Frame
from ._residual import Residual

__all__ = ["CHECKS", "TITLES", "CheckSpec", "Residual"]


@dataclass(frozen=True)
class CheckSpec:
    """One entry of the certificate's registry.

    Attributes
    ----------
    name : str
        Stable identifier (a JSON key).
    title : str
        What a pass says, in plain words (the report's and the designer's name for it).
    scope : {"crease", "frame", "vault", "panels", "panel_vault", "mechanism", "motion", "thick"}
        ``"crease"``: curve 1 of a single fold and of every frame of a smooth structure
        (the smooth crease a panel structure samples); ``"frame"``: every frame of a smooth
        structure; ``"vault"``: a smooth vault at its design angle; ``"panels"``: every
        frame of a structure of rigid panels; ``"panel_vault"``: a panel vault at its
        design angle; ``"mechanism"``: a panel structure's mechanism, once; ``"motion"``: every
        structure, as built and in every frame from its design angle on; ``"thick"``: the
        thick panels of a rigid structure, once (their own measurement).
    measures : str
        What is measured, from which built geometry, against what.
    unit : str
        Unit of the values (after normalising by the quantity's scale).
    order : int
        p: the residual of a correct design falls as h^p; 0 for an exact construction,
        whose residual is rounding: the tolerance is then the residual's floor alone.
    cap : float
        Largest meaningful tolerance, in ``unit`` (infinite for order 0).
    measure : callable
        ``Frame -> Residual``; None when the check does not apply to that frame.
    rounding : str
        For order 0, the floor in words: the rounding model the tolerance is.
    """

    name: str
    title: str
    scope: str
    measures: str
    unit: str
    order: int
    cap: float
    measure: Callable[[Frame], Residual | None] = field(repr=False)
    rounding: str = ""

    @property
    def model(self) -> str:
        """The error model in words."""
        if self.order == 0:
            return f"exact construction, the residual is rounding: tolerance = {self.rounding}"
        power = str(self.order).translate(str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹"))
        return (
            f"error ∝ h{power}: tolerance = |r(2h) − r(h)|/2 + rounding (Richardson error "
            f"|r(2h) − r(h)|/{2**self.order - 1} × safety {(2**self.order - 1) / 2:g}); cap "
            f"{self.cap:g} {self.unit}"
        )


def _not_a_frame(frame: Frame) -> None:
    """The thick panels' checks measure the solids (:func:`certify`'s ``thick``), not a frame."""
    return None


#: The registry: every check of the certificate, in report order.
CHECKS: tuple[CheckSpec, ...] = (
    CheckSpec(
        "developability",
        "the sheets stay developable (the tangent plane keeps along each ruling)",
        "crease",
        "|r'·p| along both families of rulings of curve 1: r the unit ruling from the "
        "built neighbour creases (or the built ruling vectors of a single fold), p "
        "the normal of the plane of r and the measured tangent; the tangent plane "
        "must not turn along a ruling. Relative to the largest frame rate √(κ² + τ²)",
        "relative",
        4,
        1e-3,
        measures.developability,
    ),
    CheckSpec(
        "eq2_planar_curvature",
        "Eq. (2): the crease's curvature times cos α is its flat curvature",
        "crease",
        "Eq. (2): κ of the built curve 1 (differences of its points) times cos α measured "
        "from its built rulings, against κ_2D measured on the crease pattern (curve "
        "1 of the flat state; a single fold's input pattern). Relative to the "
        "largest κ_2D",
        "relative",
        4,
        1e-3,
        measures.planar_curvature,
    ),
    CheckSpec(
        "frame_agreement",
        "every crease shares curve 1's frame",
        "frame",
        "angle between every crease's measured tangent (differences of its points) and "
        "curve 1's T at equal t: the shared frame; a crease past its curve of "
        "regression runs backwards (π)",
        "rad",
        4,
        1e-3,
        measures.frame_agreement,
    ),
    CheckSpec(
        "eq19",
        "Eq. (19): the two creases of every strip agree",
        "frame",
        "the paper's Eq. (19) across every strip: κ_2D tan α cosec β ds/dt at its two "
        "creases, each factor measured at its own crease (κ and ds/dt from "
        "differences, α from the two strips' rulings, β between the crease's tangent "
        "and the strip's ruling); not defined in the flat state",
        "relative",
        4,
        1e-3,
        measures.eq19,
    ),
    CheckSpec(
        "isometry",
        "folding stretches no edge (isometric to the crease pattern)",
        "frame",
        "|ℓ/ℓ₀ − 1| of every mesh edge against the crease pattern (the flat state): a "
        "triangle mesh is isometric exactly when every edge keeps its length; "
        "polyline chords shorten as (κ² − κ_2D²) h²/24",
        "relative",
        2,
        1e-3,
        measures.isometry,
    ),
    CheckSpec(
        "ruling_quad_planarity",
        "the quads between rulings stay planar",
        "frame",
        "distance of each ruling quad's fourth corner from the plane of the other three, "
        "over its diagonal: consecutive rulings of a developable are coplanar",
        "relative",
        3,
        1e-3,
        measures.quad_planarity,
    ),
    CheckSpec(
        "fold_angles",
        "the creases fold by 2α, the seams by 180° − 2α",
        "frame",
        "dihedral angle of the mesh at every crease edge against 2α (folds, mountain) and "
        "180° − 2α (seams)",
        "°",
        2,
        0.1,
        measures.fold_angles,
    ),
    CheckSpec(
        "width_law",
        "the widths follow the width law (Eqs. 12–13, corrected)",
        "frame",
        "|ln(w/w(0)) ∓ ∫ κ_2D cot β ds| for every strip: w the distance between the "
        "tangent lines of its built creases (Eqs. 12–13 corrected); the integral by "
        "Gauss–Legendre on a grid 4× finer than the samples",
        "relative",
        6,
        1e-4,
        measures.width_law,
    ),
    CheckSpec(
        "regression",
        "every crease stays clear of its curve of regression (Eq. 17)",
        "frame",
        "x'·T₁ of every crease (differences of its points along curve 1's arc length) "
        "against the Eq. (17) speed factor 1 − u w_L/w_lim_L − v w_R/w_lim_R of the "
        "regression domain (Eqs. 14–18) the design was accepted with; relative to "
        "the smallest factor, so a pass also says every crease runs forward",
        "relative",
        4,
        1e-3,
        measures.regression,
    ),
    CheckSpec(
        "tube_closure",
        "each tube closes onto its first crease",
        "frame",
        "each strip of every tube rebuilt from its first crease's own measured invariants "
        "(frame, κ, β, the width law from the measured width at t ≈ 0: the paper's "
        "construction step) lands on its second crease; the step from crease 4 "
        "closes the tube onto crease 1. Relative to the strip's width",
        "relative",
        4,
        1e-3,
        measures.tube_closure,
    ),
    CheckSpec(
        "ground_plane",
        "the feet stand on the ground",
        "vault",
        "|z| of both end sections of every crease at the design angle, relative to the "
        "vault's size",
        "relative",
        6,
        1e-6,
        measures.ground_plane,
    ),
    CheckSpec(
        "arch_condition",
        "the arch condition (Eq. 20): the ends face opposite ways",
        "vault",
        "on the built curve 1: T(s0/2)·T(0) (Eq. 20), |T(0) + T(s1)| (the ends face "
        "opposite ways) and (x(s1) − x(0))·T(0)/s1 (the chord lies in the ground)",
        "",
        6,
        1e-6,
        measures.arch_condition,
    ),
    CheckSpec(
        "proportion_change",
        "the section proportion changes as predicted from feet to apex",
        "vault",
        "w_R(s0/2)/w_R(0) and p_xz = w_R/w_L at s0/2, measured between the tangent lines "
        "of the base tube's built creases, against exp(a κ0 s0 cot α/π) and p_xy × "
        "change²",
        "relative",
        6,
        1e-6,
        measures.proportion_change,
    ),
    CheckSpec(
        "panel_isometry",
        "every panel keeps its sides and diagonals",
        "panels",
        "|ℓ/ℓ₀ − 1| of the four sides and both diagonals of every panel against the crease "
        "pattern (the flat state): each panel keeps its shape",
        "relative",
        0,
        math.inf,
        measures.panel_isometry,
        rounding="4 × 32 ulps of the largest coordinate over the shortest side or diagonal "
        "(a length carries the rounding of its two ends)",
    ),
    CheckSpec(
        "panel_planarity",
        "every panel stays planar",
        "panels",
        "distance of each panel's fourth corner from the plane of the other three, over "
        "its diagonal: every panel stays planar",
        "relative",
        0,
        math.inf,
        measures.quad_planarity,
        rounding="4 × 32 ulps of the largest coordinate over the shortest edge",
    ),
    CheckSpec(
        "panel_ground_plane",
        "the panel vault's feet stand on the ground",
        "panel_vault",
        "|z| of the first and last vertex of every polyline at the design angle, relative "
        "to the vault's size: both end sections stand on the ground (the discrete "
        "Eq. 20, (x_N − x_0)·n₀ = 0)",
        "relative",
        0,
        math.inf,
        measures.panel_ground_plane,
        rounding="32 ulps of the largest coordinate over the size, plus 3 × the arch "
        "root's residual (the sine of the chord's angle to the first end section, "
        "which tilts the far one by twice that)",
    ),
    CheckSpec(
        "mechanism_dof",
        "the panels fold with exactly one degree of freedom",
        "mechanism",
        "|DOF − 1| at half and full design angle: DOF = nullity − 6 of the Jacobian of "
        "every edge length, both panel diagonals and every panel's planarity, welded "
        "seams and bonds (curvefold.analysis._mechanism), counted below the rank "
        "tolerance 1e-9 σ_max. The flat state has more, first-order only (reported)",
        "DOF",
        0,
        math.inf,
        measures.mechanism_dof,
        rounding="0: a count; the null singular values of a state built to rounding lie "
        "near 1e-15 σ_max",
    ),
    CheckSpec(
        "mechanism_clearance",
        "that count is clear of the rank tolerance",
        "mechanism",
        "how near the rank tolerance (1e-9 σ_max) the nearest singular value lies, max "
        "min(σ/tol, tol/σ), at half and full design angle",
        "",
        0,
        math.inf,
        measures.mechanism_clearance,
        rounding="1e-3: the count holds for any tolerance a thousand times larger or "
        "smaller; rounding puts the null singular values near 1e-15 σ_max, a million "
        "times below it",
    ),
    CheckSpec(
        "contact",
        "the motion ends before its parts touch (the first contact)",
        "motion",
        "parts of the structure far apart (curves two lattice steps apart, or points more "
        "than four of the largest strip widths apart along both their curves) closer "
        "than half the smallest strip width, at the design angle and in every "
        "certified frame past it: how far inside that half width they are, relative "
        "to it",
        "relative",
        0,
        math.inf,
        measures.contact,
        rounding="0: any contact fails (the curves resampled to 201 points along t, each "
        "pair's distance measured)",
    ),
    # thick panels (curvefold.analysis._thick_checks): measured on the solids, not on a frame
    CheckSpec(
        "thick_hinges",
        "every thick panel's hinge axis lies on its crease",
        "thick",
        "largest distance of a hinge axis end, placed by its panel's frame, from the crease "
        "line of the zero-thickness state, at the range's ends, its middle and the design angle",
        "model units",
        0,
        math.inf,
        _not_a_frame,
        rounding="1e-12 × the structure's size (measured at most 1.3e-15 of a size about 1)",
    ),
    CheckSpec(
        "thick_contact",
        "no two thick panels interpenetrate within the stated range",
        "thick",
        "largest penetration depth of two solids (separating axes) at nine states across the "
        "stated range of motion with thickness",
        "model units",
        0,
        math.inf,
        _not_a_frame,
        rounding="1e-9 t: neighbours on a hinge touch at depth 0 to rounding",
    ),
    CheckSpec(
        "thick_dof",
        "the thick panels' linkage moves with one degree of freedom",
        "thick",
        "|DOF − 1| of the solids joined by their hinge axes (each solid a rigid body of its "
        "hinge ends and a top point), at the states across the range but flat",
        "DOF",
        0,
        math.inf,
        _not_a_frame,
        rounding="0: a count, below the rank tolerance 1e-9 σ_max",
    ),
)

#: What each check says when it passes, in plain words, by name.
TITLES: Mapping[str, str] = MappingProxyType({spec.name: spec.title for spec in CHECKS})
