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

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from ..geometry._contact import closest_far, contact_scales
from ..geometry._topology import CORNERS, STRIPS
from . import _measure as measure
from ._frames import STRIP_SIDES, Frame
from ._mechanism import CertifiedMechanism, certified_mechanism

__all__ = ["CHECKS", "TITLES", "CheckSpec", "Residual"]

#: Largest :attr:`Mechanism.clearance <curvefold.analysis.Mechanism.clearance>` of a clear count.
CLEARANCE = 1e-3


@dataclass(frozen=True)
class Residual:
    """A measured residual field, as the checks see it.

    Attributes
    ----------
    values : ndarray
        ``|residual|`` in the check's unit (NaN where the measurement broke). With ``t`` its
        last axis runs along the creases; without, every entry is an element (an edge, a
        face, a named quantity).
    floor : float
        Its rounding floor.
    name : callable
        Index (into the leading axes when ``t`` is given) -> what it is, for people
        (``"curve (1, 1)"``).
    t : (m,) ndarray or None
        Curve parameter t ∈ [0, 1] of the last axis.
    """

    values: np.ndarray
    floor: float
    name: Callable[[tuple[int, ...]], str]
    t: np.ndarray | None = None

    @property
    def worst(self) -> tuple[float, int]:
        """The largest value and its flat index; NaN wins (a broken measurement is the worst)."""
        v = np.asarray(self.values, float).ravel()
        if v.size == 0:
            return 0.0, -1
        top = int(np.argmax(v))
        # every value finite: the largest, first where it is
        if math.isfinite(v[top]) and math.isfinite(v.min()):
            return float(v[top]), top
        bad = np.flatnonzero(~np.isfinite(v))
        return (math.nan, int(bad[0])) if bad.size else (float(v.max()), int(np.argmax(v)))

    def locate(self, index: int) -> str:
        """Where the entry at a flat index is."""
        at = np.unravel_index(index, np.shape(self.values))
        if self.t is None:
            return self.name(tuple(int(i) for i in at))
        head = self.name(tuple(int(i) for i in at[:-1]))
        return f"{head}, t = {self.t[at[-1]]:.3g}" if head else f"t = {self.t[at[-1]]:.3g}"

    def change(self, coarse: Residual) -> float:
        """``|r(2h) − r(h)|``: pointwise at the t both sample (where they have t), else of the
        largest values."""
        if self.t is None or coarse.t is None:
            return abs(coarse.worst[0] - self.worst[0])
        k = np.clip(np.searchsorted(self.t, coarse.t), 0, len(self.t) - 1)
        same = np.abs(self.t[k] - coarse.t) < 0.25 * (self.t[1] - self.t[0])
        fine, rough = np.asarray(self.values), np.asarray(coarse.values)
        # every coarse t, evenly: slices
        if same.all() and len(k) > 1 and (np.diff(k) == k[1] - k[0]).all() and k[1] > k[0]:
            diff = np.abs(rough - fine[..., k[0] : k[-1] + 1 : k[1] - k[0]])
        else:
            diff = np.abs(rough[..., same] - fine[..., k[same]])
        return float(np.max(diff)) if diff.size else math.inf


@dataclass(frozen=True)
class CheckSpec:
    """One entry of the certificate's registry.

    Attributes
    ----------
    name : str
        Stable identifier (a JSON key).
    title : str
        What a pass says, in plain words (the report's and the designer's name for it).
    scope : {"crease", "frame", "vault", "panels", "panel_vault", "mechanism", "motion"}
        ``"crease"``: curve 1 of a single fold and of every frame of a smooth structure
        (the smooth crease a panel structure samples); ``"frame"``: every frame of a smooth
        structure; ``"vault"``: a smooth vault at its design angle; ``"panels"``: every
        frame of a structure of rigid panels; ``"panel_vault"``: a panel vault at its
        design angle; ``"mechanism"``: a panel structure's mechanism, once; ``"motion"``: every
        structure, as built and in every frame from its design angle on.
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


# --------------------------------------------------------------------------------------
# the measurements


def _curve(uv: np.ndarray) -> Callable[[tuple[int, ...]], str]:
    return lambda i: f"curve {tuple(uv[i[0]].tolist())}"


def _strip(i: tuple[int, ...]) -> str:
    return f"tube {i[0] + 1}, strip {i[1] + 1}→{i[1] % 4 + 2}"


def _developability(frame: Frame) -> Residual:
    crease, h = frame.smooth_crease, frame.step
    x = crease.curve.points
    rates = np.hypot(crease.curve.kappa(crease.s), crease.curve.tau(crease.s)).max()
    values = measure.ruling_twist(x, frame.rulings, h) / rates
    length = float(measure.norm(frame.rulings).min())
    return Residual(
        values,
        1.5 * frame.ulp / (length * h * rates),
        lambda i: ("left", "right")[i[0]] + " rulings",
        frame.inner_t,
    )


def _planar_curvature(frame: Frame) -> Residual:
    x, h = frame.crease.curve.points, frame.step
    if frame.shared is None:
        k2 = frame.smooth_crease.kappa_2d[2:-2]  # the crease pattern of a single fold is its input
    else:
        k2 = measure.curvature(frame.common.flat.lattice.crease.curve.points, h)
    scale = float(np.abs(k2).max())
    values = np.abs(measure.curvature(x, h) * np.cos(frame.measured_alpha) - k2) / scale
    return Residual(values, 12 * frame.ulp / (h**2 * scale), lambda i: "", frame.inner_t)


def _frame_agreement(frame: Frame) -> Residual:
    uv = frame.structure.curves_uv
    # measure.tangent_deviation, the same numbers
    d1, tangent = frame.curve_derivatives[0], frame.tangent_components[:, None, 2:-2]
    values = np.arctan2(measure.norm3(measure.cross3(d1, tangent)), frame.speeds_along_tangent)
    f_min = float(frame.common.speed_factors.min())
    return Residual(values, 1.5 * frame.ulp / (frame.step * f_min), _curve(uv), frame.inner_t)


def _eq19(frame: Frame) -> Residual | None:
    """κ_2D tan α cosec β ds of neighbouring creases, each factor measured at its own crease."""
    if frame.alpha == 0:
        return None  # both sides vanish in the flat state
    h = frame.step
    alpha = frame.half_angles  # (K, 4, m)
    d1 = frame.tube_tangents
    speed, kappa = frame.tube_frenet[0], frame.tube_frenet[4]  # (K, 4, m)
    nxt = [b for _, b in STRIPS]
    ruling = frame.strip_vectors[..., 2:-2]  # strip a → b of every tube, (3, K, 4, m)
    bend = np.sin(alpha)
    bend *= kappa
    bend *= speed  # κ sin α ds/dt = κ_2D tan α ds/dt at every corner
    sides = [bend[:, c] / np.sin(measure.angle3(ruling, d1[:, :, c])) for c in (slice(None), nxt)]
    values = np.abs(sides[0] / sides[1] - 1)  # (K, 4 strips, m)
    length = float(measure.norm3(frame.strip_vectors[:, :, 0]).min())
    floor = frame.ulp * (
        24 / (h**2 * float((kappa * speed**2).min())) + 6 / (h * length * math.sin(frame.alpha))
    )
    return Residual(values, floor, _strip, frame.inner_t)


def _isometry(frame: Frame) -> Residual:
    top = frame.common.topology
    with np.errstate(invalid="ignore", divide="ignore"):
        values = np.abs(frame.edge_lengths / frame.common.flat_lengths - 1)
    return Residual(
        values,
        4 * frame.ulp / frame.common.shortest_edge,
        lambda i: f"edge {i[0]} ({top.edges_kind[i[0]]})",
    )


def _quad_planarity(frame: Frame) -> Residual:
    # every strip's quads (a_j, a_(j+1), b_(j+1), b_j): its edges, the same numbers
    if frame.common.tube_mesh:
        (along, ruling, diagonal), (_, _, length) = frame.strip_edges, frame.strip_edge_lengths
        values = measure.corner_nonplanarity3(along, ruling[..., :-1], diagonal, length).reshape(-1)
    elif (sides := frame.common.quad_sides) is None:
        values = measure.quad_nonplanarity(frame.coords, frame.common.quads)
    else:  # the quads' sides and diagonals are edges: their vectors and lengths, the same numbers
        side, other, diagonal = (np.take(frame.edge_vectors, side, axis=1) for side in sides)
        length = np.take(frame.edge_lengths, sides[2])
        values = measure.corner_nonplanarity3(side, other, diagonal, length)
    return Residual(
        values,
        4 * frame.ulp / frame.common.shortest_edge,
        lambda i: f"quad {i[0]} (strip {i[0] // (frame.samples - 1) + 1})",
    )


def _fold_angles(frame: Frame) -> Residual:
    top = frame.common.topology
    creases, faces = frame.common.creases
    # every strip's curve edges, between its second triangles and the previous strip's first ones
    if frame.common.tube_mesh:
        (along, ruling, diagonal), (length, _, _) = frame.strip_edges, frame.strip_edge_lengths
        first, second = (
            measure.unit3(measure.cross3(*sides))
            for sides in ((diagonal, ruling[..., :-1]), (along, diagonal))
        )
        measured = measure.hinge_angles3(
            second, first[:, :, [(c - 1) % 4 for c in range(4)]], along, length
        ).reshape(-1)
    else:
        measured = measure.dihedral_angles3(
            frame.face_areas,
            faces,
            np.take(frame.edge_vectors, creases, axis=1),
            np.take(frame.edge_lengths, creases),
        )
    values = measure.fold_angle_deviation(
        measured, frame.common.crease_folds, 2 * math.degrees(frame.alpha)
    )
    return Residual(
        values,
        math.degrees(4 * frame.ulp / frame.common.shortest_edge),
        lambda i: f"edge {creases[i[0]]} ({top.edges_kind[creases[i[0]]]})",
    )


#: The step of every strip along its ruling family: +1 along +r, −1 along −r.
_STRIP_SIGNS = np.array([float((CORNERS[b] - CORNERS[a]).sum()) for a, b in STRIPS])
#: The step from every corner back to the previous one along the other family, ±1, broadcasting
#: against (3, K, 4, n).
_BACK = np.array([float((CORNERS[(c - 1) % 4] - CORNERS[c]).sum()) for c in range(4)])[:, None]


def _width_law(frame: Frame) -> Residual:
    start, law = frame.common.width_law
    values = np.abs(np.log(frame.strip_widths / start) - law)
    return Residual(
        values,
        2 * frame.ulp / float(frame.strip_widths.min()),
        _strip,
        frame.crease.curve.s / frame.crease.curve.length,
    )


def _regression(frame: Frame) -> Residual:
    uv = frame.structure.curves_uv
    predicted = frame.common.speed_factors
    margin = float(predicted.min())
    measured = frame.speeds_along_tangent  # measure.speed_factors, the same numbers
    values = np.abs(measured - predicted[:, 2:-2]) / margin
    return Residual(values, 1.5 * frame.ulp / (frame.step * margin), _curve(uv), frame.inner_t)


def _tube_closure(frame: Frame) -> Residual:
    X, h = frame.tubes, frame.step
    following = frame.next_corners
    # toward the previous crease, oriented as r in Eqs. 5–6
    ruling = -frame.strip_vectors[:, :, [(c - 1) % 4 for c in range(4)]] * _BACK
    rebuilt = measure.rebuilt_strip3(
        X,
        ruling,
        following,
        h,
        alpha=frame.alpha,
        side=STRIP_SIDES[:, None],
        sign=_STRIP_SIGNS[:, None],
        frenet_frame=frame.tube_frenet,
    )
    values = measure.norm3(rebuilt - following[..., 2:-2]) / frame.strip_widths[:, :, 2:-2]
    crease = frame.smooth_crease
    kappa_min = float(crease.curve.kappa(crease.s).min())
    floor = 12 * frame.ulp / (h**2 * kappa_min * float(frame.strip_widths.min()))
    return Residual(
        values,
        floor,
        lambda i: f"tube {i[0] + 1}, crease {i[1] + 1} → {i[1] % 4 + 2}",
        frame.inner_t,
    )


def _ground_plane(frame: Frame) -> Residual:
    vertices = frame.folded.vertices
    size = float(np.abs(vertices).max())
    uv = frame.structure.curves_uv
    return Residual(
        np.abs(vertices[:, [0, -1], 2]) / size,
        _accumulated(frame) / size,
        lambda i: f"curve {tuple(uv[i[0]].tolist())}, t = {i[1]}",
    )


def _arch_condition(frame: Frame) -> Residual:
    """Eq. (20), the ends facing opposite ways, and the chord normal to T(0), on the built curve
    1."""
    curve = frame.crease.curve
    T = curve.frames[:, :, 0]
    m = (len(curve.s) - 1) // 2
    values = np.array(
        [
            abs(T[0] @ T[m]),
            measure.norm(T[0] + T[-1]),
            abs((curve.points[-1] - curve.points[0]) @ T[0]) / curve.length,
        ]
    )
    labels = ("T(s0/2)·T(0) (Eq. 20)", "|T(0) + T(s1)|", "(x(s1) − x(0))·T(0) / s1")
    return Residual(values, _accumulated(frame) / curve.length, lambda i: labels[i[0]])


def _proportion_change(frame: Frame) -> Residual:
    vault = frame.compared_vault
    widths = frame.strip_widths
    w_r, w_l = widths[0, 0], widths[0, 3]  # strips 1→2 and 4→1 of the base tube
    m = (frame.samples - 1) // 2
    values = np.abs(
        np.array([w_r[m] / w_r[0] / vault.proportion_change, w_r[m] / w_l[m] / vault.p_xz]) - 1
    )
    labels = (
        "w_R(s0/2)/w_R(0) against exp(a κ0 s0 cot α / π)",
        "p_xz = w_R/w_L at s0/2 against p_xy × change²",
    )
    return Residual(values, _accumulated(frame) / float(widths.min()), lambda i: labels[i[0]])


def _panel_isometry(frame: Frame) -> Residual:
    shared = frame.common
    values = np.abs(measure.edge_lengths(frame.coords, shared.bars) / shared.bar_lengths - 1)
    edges, kinds = len(shared.topology.edges_vertices), shared.topology.edges_kind

    def name(i: tuple[int, ...]) -> str:
        e = i[0]
        return (
            f"edge {e} ({kinds[e]})"
            if e < edges
            else f"panel {(e - edges) % len(shared.quads)}, a diagonal"
        )

    return Residual(values, 4 * frame.ulp / float(shared.bar_lengths.min()), name)


def _panel_ground_plane(frame: Frame) -> Residual:
    """``|z|`` of every foot over the vault's size; the floor adds the tilt the arch root's
    residual leaves."""
    vertices = frame.folded.vertices
    size = float(np.abs(vertices).max())
    uv = frame.structure.curves_uv
    return Residual(
        np.abs(vertices[:, [0, -1], 2]) / size,
        frame.ulp / size + 3 * frame.compared_vault.arch.residual,
        lambda i: f"curve {tuple(uv[i[0]].tolist())}, " + ("first", "last")[i[1]] + " vertex",
    )


def _generic_states(frame: Frame) -> tuple[CertifiedMechanism, tuple]:
    """The certified mechanism and its states away from the flat one (half and full design
    angle)."""
    analysis = certified_mechanism(frame.structure)
    return analysis, analysis.states[1:]


def _scope_note(analysis: CertifiedMechanism) -> str:
    return f" ({analysis.scope}: the dense SVD is bounded)" if analysis.scope else ""


def _mechanism_dof(frame: Frame) -> Residual:
    analysis, states = _generic_states(frame)
    flat = analysis.states[0]
    return Residual(
        np.array([abs(m.dof - 1) for m in states], float),
        0.0,
        lambda i: (
            f"{states[i[0]].label}: {states[i[0]].dof} internal DOF (nullity "
            f"{states[i[0]].nullity}){_scope_note(analysis)}; flat: {flat.dof}, "
            "first-order lifts of the flat sheets"
        ),
    )


def _mechanism_clearance(frame: Frame) -> Residual:
    analysis, states = _generic_states(frame)
    return Residual(
        np.array([m.clearance for m in states]),
        CLEARANCE,
        lambda i: (
            f"{states[i[0]].label}: gap {states[i[0]].gap:.2g} between null "
            f"and stiff singular values{_scope_note(analysis)}"
        ),
    )


def _contact(frame: Frame) -> Residual:
    """How far the closest two far-apart parts are inside half the smallest width of each other:
    0 when none are."""
    state, uv = frame.folded, frame.structure.curves_uv
    lattice = state.lattice
    radius, reach = contact_scales(lattice)
    distance, where = closest_far(state.vertices, uv, radius=radius, reach=reach)
    if where is None:  # none, or a point that is not a number (NaN fails)
        return Residual(
            np.full(1, 0.0 if distance == np.inf else np.nan),
            0.0,
            lambda i: f"no far-apart parts within {radius:.3g} (half the smallest width)",
        )
    a, i, b, j = where
    t = lattice.t
    return Residual(
        np.array([1 - distance / radius]),
        0.0,
        lambda _: (
            f"curves {tuple(uv[a].tolist())} at t = {t[i]:.3g} and "
            f"{tuple(uv[b].tolist())} at t = {t[j]:.3g} are {distance:.3g} apart "
            f"(half the smallest width: {radius:.3g})"
        ),
    )


def _accumulated(frame: Frame) -> float:
    """Rounding accumulated over n integration steps: ROUNDING ulps × √n, in model units."""
    return frame.ulp * math.sqrt(frame.samples)


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
        _developability,
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
        _planar_curvature,
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
        _frame_agreement,
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
        _eq19,
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
        _isometry,
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
        _quad_planarity,
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
        _fold_angles,
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
        _width_law,
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
        _regression,
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
        _tube_closure,
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
        _ground_plane,
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
        _arch_condition,
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
        _proportion_change,
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
        _panel_isometry,
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
        _quad_planarity,
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
        _panel_ground_plane,
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
        _mechanism_dof,
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
        _mechanism_clearance,
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
        _contact,
        rounding="0: any contact fails (the curves resampled to 201 points along t, each "
        "pair's distance measured)",
    ),
)

#: What each check says when it passes, in plain words, by name.
TITLES: Mapping[str, str] = MappingProxyType({spec.name: spec.title for spec in CHECKS})
