"""The measurements of the certificate's checks: each ``Frame -> Residual`` (or None where it does
not apply), with its rounding floor and the names of its elements.

:data:`curvefold.analysis._checks.CHECKS` says what each measures, its error model and its
scope.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..geometry._contact import closest_far, contact_scales
from ..geometry._topology import CORNERS, STRIPS
from ..kernel._errors import InputError
from . import _measure as measure
from ._frames import STRIP_SIDES, Frame
from ._mechanism import CertifiedMechanism, certified_mechanism
from ._residual import Residual

__all__ = [
    "developability",
    "planar_curvature",
    "frame_agreement",
    "eq19",
    "isometry",
    "quad_planarity",
    "fold_angles",
    "width_law",
    "regression",
    "tube_closure",
    "ground_plane",
    "arch_condition",
    "proportion_change",
    "panel_isometry",
    "panel_ground_plane",
    "mechanism_dof",
    "mechanism_clearance",
    "contact",
    "CLEARANCE",
]

#: Largest :attr:`Mechanism.clearance <curvefold.analysis.Mechanism.clearance>` of a clear count.
CLEARANCE = 1e-3


def _curve(uv: np.ndarray) -> Callable[[tuple[int, ...]], str]:
    return lambda i: f"curve {tuple(uv[i[0]].tolist())}"


def _strip(i: tuple[int, ...]) -> str:
    return f"tube {i[0] + 1}, strip {i[1] + 1}→{i[1] % 4 + 2}"


def _smallest_width(frame: Frame) -> float:
    """The smallest strip width, which the residuals relative to a width divide by.

    Raises
    ------
    InputError
        A strip of no width (its creases' tangent lines meet): nothing is relative to it.
    """
    widths = frame.strip_widths
    at = tuple(int(i) for i in np.unravel_index(int(np.argmin(widths)), widths.shape))
    least = float(widths[at])
    if least == 0:  # (a NaN is measured and fails its check as not a number)
        t = frame.crease.curve.s[at[2]] / frame.crease.curve.length
        raise InputError(
            f"the width of {_strip(at[:2])} is {least:g} at t = {t:.4g}: its two creases meet "
            "there, so the design has no strip to certify; change kappa, tau or the widths so "
            "that every strip keeps a width > 0"
        )
    return least


def developability(frame: Frame) -> Residual:
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


def planar_curvature(frame: Frame) -> Residual:
    x, h = frame.crease.curve.points, frame.step
    if frame.shared is None:
        k2 = frame.smooth_crease.kappa_2d[2:-2]  # the crease pattern of a single fold is its input
    else:
        k2 = measure.curvature(frame.common.flat.lattice.crease.curve.points, h)
    scale = float(np.abs(k2).max())
    values = np.abs(measure.curvature(x, h) * np.cos(frame.measured_alpha) - k2) / scale
    return Residual(values, 12 * frame.ulp / (h**2 * scale), lambda i: "", frame.inner_t)


def frame_agreement(frame: Frame) -> Residual:
    uv = frame.structure.curves_uv
    # measure.tangent_deviation, the same numbers
    d1, tangent = frame.curve_derivatives[0], frame.tangent_components[:, None, 2:-2]
    values = np.arctan2(measure.norm3(measure.cross3(d1, tangent)), frame.speeds_along_tangent)
    f_min = float(frame.common.speed_factors.min())
    return Residual(values, 1.5 * frame.ulp / (frame.step * f_min), _curve(uv), frame.inner_t)


def eq19(frame: Frame) -> Residual | None:
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


def isometry(frame: Frame) -> Residual:
    top = frame.common.topology
    with np.errstate(invalid="ignore", divide="ignore"):
        values = np.abs(frame.edge_lengths / frame.common.flat_lengths - 1)
    return Residual(
        values,
        4 * frame.ulp / frame.common.shortest_edge,
        lambda i: f"edge {i[0]} ({top.edges_kind[i[0]]})",
    )


def quad_planarity(frame: Frame) -> Residual:
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


def fold_angles(frame: Frame) -> Residual:
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


def width_law(frame: Frame) -> Residual:
    least = _smallest_width(frame)
    start, law = frame.common.width_law
    values = np.abs(np.log(frame.strip_widths / start) - law)
    return Residual(
        values,
        2 * frame.ulp / least,
        _strip,
        frame.crease.curve.s / frame.crease.curve.length,
    )


def regression(frame: Frame) -> Residual:
    uv = frame.structure.curves_uv
    predicted = frame.common.speed_factors
    margin = float(predicted.min())
    measured = frame.speeds_along_tangent  # measure.speed_factors, the same numbers
    values = np.abs(measured - predicted[:, 2:-2]) / margin
    return Residual(values, 1.5 * frame.ulp / (frame.step * margin), _curve(uv), frame.inner_t)


def tube_closure(frame: Frame) -> Residual:
    least = _smallest_width(frame)  # before the residuals divided by the widths
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
    floor = 12 * frame.ulp / (h**2 * kappa_min * least)
    return Residual(
        values,
        floor,
        lambda i: f"tube {i[0] + 1}, crease {i[1] + 1} → {i[1] % 4 + 2}",
        frame.inner_t,
    )


def ground_plane(frame: Frame) -> Residual:
    vertices = frame.folded.vertices
    size = float(np.abs(vertices).max())
    uv = frame.structure.curves_uv
    return Residual(
        np.abs(vertices[:, [0, -1], 2]) / size,
        _accumulated(frame) / size,
        lambda i: f"curve {tuple(uv[i[0]].tolist())}, t = {i[1]}",
    )


def arch_condition(frame: Frame) -> Residual:
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


def proportion_change(frame: Frame) -> Residual:
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
    return Residual(values, _accumulated(frame) / _smallest_width(frame), lambda i: labels[i[0]])


def panel_isometry(frame: Frame) -> Residual:
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


def panel_ground_plane(frame: Frame) -> Residual:
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


def mechanism_dof(frame: Frame) -> Residual:
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


def mechanism_clearance(frame: Frame) -> Residual:
    analysis, states = _generic_states(frame)
    return Residual(
        np.array([m.clearance for m in states]),
        CLEARANCE,
        lambda i: (
            f"{states[i[0]].label}: gap {states[i[0]].gap:.2g} between null "
            f"and stiff singular values{_scope_note(analysis)}"
        ),
    )


def contact(frame: Frame) -> Residual:
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
