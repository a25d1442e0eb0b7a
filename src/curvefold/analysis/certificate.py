"""The geometric certificate: a registry of checks, each measured on the built geometry.

Every check measures a residual that the construction makes zero in the continuum, from
the built points (:mod:`curvefold.analysis.measure`), never from the formula that built
them: a wrong formula leaves a residual of order one, a correct design only the
discretisation error.

Error model, the same for every check
    A design sampled at step h leaves a residual r(h) ≈ C h^p (p the order of the check's
    measurement, or of the builder's integration) plus rounding. The design is built again
    at half the samples (step 2h, from the same functions) and measured the same way:
    r(2h) ≈ 2^p C h^p. The error at h is estimated by Richardson,
    e = ``|r(2h) − r(h)| / (2^p − 1)``; with the safety factor (2^p − 1) / 2,

        tolerance = ``|r(2h) − r(h)| / 2`` + rounding floor.

    A residual that is discretisation error falls 2^p-fold from 2h to h and passes with a
    margin of (2^p − 1)/2; one that falls less than three-fold (an error of the geometry,
    which does not shrink with h) fails, at any sampling. The rounding floor is
    :data:`ROUNDING` units in the last place of the largest coordinate, amplified as the
    measurement amplifies it (1/h per derivative, over the length it is compared with).

Resolution
    Each check has a cap on its tolerance, relative to its quantity's own scale: a
    tolerance above the cap means the sampling is too coarse for the check to say anything.
    The check then reports "insufficient resolution" (never a pass) with the sample count
    at which the tolerance, falling as h^p, would be a quarter of the cap; a residual
    larger than even that tolerance still fails.

The motion
    A structure is certified in every frame asked for (the exported ones) and at 0° and its
    design angle; the certificate also states the largest fold angle up to which every
    check still passes at this sampling (the error of a folded state grows as
    κ = κ_2D / cos α does).

Rigid panels
    A structure of rigid planar panels (:mod:`curvefold.geometry.panels`) is exact by
    construction: every folded state is the flat panels moved rigidly, so its residuals
    are rounding, whatever the number of panels. Its checks have order 0: the tolerance is
    the rounding floor alone (:attr:`CheckSpec.rounding` states it), with no half-sampled
    design. They are ``panel_isometry`` (sides and both diagonals of every panel),
    ``panel_planarity``, ``panel_ground_plane`` (a vault standing by the discrete Eq. 20),
    and the mechanism (:func:`curvefold.analysis.mechanism.certified_mechanism`):
    ``mechanism_dof`` (one internal degree of freedom at half and full design angle) and
    ``mechanism_clearance`` (how clearly the singular values count it). The smooth crease
    the panels sample is certified by the crease checks. The smooth frame and vault checks
    do not apply: ``frame_agreement``, ``eq19``, ``width_law``, ``section_area``,
    ``regression``, ``tube_closure``, ``arch_condition`` and ``proportion_change`` take
    derivatives along the creases or compare with the smooth closed forms, which a
    polyline meets only to O(1/N²) (measured in ``tests/test_panels.py``); ``isometry``,
    ``ruling_quad_planarity`` and ``ground_plane`` have exact panel counterparts above;
    ``fold_angles`` compares every fold edge with 2α, and a panel's fold lines fold by
    their own angle (``tan(ρ/2) = sin(φ/2) / sin β · tan α``), which isometry and
    planarity hold to (a wrong ρ breaks the panels).

Adding a check is one entry in :data:`CHECKS`: a :class:`CheckSpec` with a measurement
``frame -> Residual`` and its order and cap; a test must damage a design so that it fails.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..geometry.crease import Crease
from ..geometry.curve import SpaceCurve
from ..geometry.lattice import Lattice, Pattern
from ..geometry.mesh import edges_faces
from ..geometry.mesh import fold_angles as mesh_fold_angles
from ..geometry.panels import PanelLattice
from ..geometry.structure import State, Structure
from ..geometry.topology import CORNER_KINDS, CORNERS, STRIPS, Topology
from ..kernel.errors import InputError
from ..vault.assembly import Vault
from . import measure
from .mechanism import CertifiedMechanism, certified_mechanism

__all__ = ["Check", "CheckSpec", "Certificate", "Frame", "Residual", "Shared", "CHECKS", "ROUNDING", "certify"]

#: Units in the last place of the largest coordinate that a built sample may carry as rounding:
#: twice the largest noise measured in built rulings (16 ulps, tests/test_properties.py).
ROUNDING = 32.0
_EPS = float(np.finfo(float).eps)
#: Fewest samples of the half-sampled design: the measurements' 5-point stencils need room.
_MIN_COARSE = 9
#: Largest :attr:`Mechanism.clearance <curvefold.analysis.mechanism.Mechanism.clearance>` of a clear count.
CLEARANCE = 1e-3
#: Statuses, best first.
STATUSES = ("pass", "insufficient resolution", "fail")


# --------------------------------------------------------------------------------------
# the subjects measured: a crease, or a structure in one folded state


@dataclass(frozen=True, eq=False)
class Shared:
    """What every frame of one structure shares: its meshes' topology and its flat state.

    Attributes
    ----------
    structure : Structure
    """

    structure: Structure

    @cached_property
    def flat(self) -> State:
        """The flat state: the crease pattern."""
        return self.structure.state(0.0)

    @cached_property
    def topology(self) -> Topology:
        """The structure's topology (corners, strips, vertex numbering)."""
        return self.structure.topology()

    @cached_property
    def quads(self) -> np.ndarray:
        """The ruling quads (F, 4), in the vertex numbering of :attr:`Shared.topology`."""
        return self.structure.topology("quads").faces_vertices

    @cached_property
    def flat_coords(self) -> np.ndarray:
        """Vertex coordinates of the crease pattern (the flat state), (V, 3) model units."""
        return self.topology.coords(self.flat.vertices)

    @cached_property
    def flat_lengths(self) -> np.ndarray:
        """Edge lengths of the crease pattern, (E,)."""
        return measure.edge_lengths(self.flat_coords, self.topology.edges_vertices)

    @property
    def shortest_edge(self) -> float:
        """Length of the crease pattern's shortest edge, model units."""
        return float(self.flat_lengths.min())

    @cached_property
    def bars(self) -> np.ndarray:
        """Every edge, then both diagonals of every quad, (E + 2F, 2): what keeps a rigid panel's shape."""
        q = self.quads
        return np.concatenate([self.topology.edges_vertices, q[:, [0, 2]], q[:, [1, 3]]])

    @cached_property
    def bar_lengths(self) -> np.ndarray:
        """Lengths of :attr:`bars` in the crease pattern, (E + 2F,)."""
        return measure.edge_lengths(self.flat_coords, self.bars)

    @cached_property
    def creases(self) -> tuple[np.ndarray, np.ndarray]:
        """The fold and seam edges, and the two faces on each, (C,) and (C, 2)."""
        top = self.topology
        ids = np.flatnonzero(np.isin(top.edges_kind, ("fold", "seam")))
        return ids, edges_faces(top.faces_vertices, top.edges_vertices[ids])


@dataclass(frozen=True, eq=False)
class Frame:
    """What the measurements read: a single crease, or a structure folded to one angle.

    Attributes
    ----------
    crease : Crease
        Curve 1 in this state.
    shared : Shared or None
        The structure and what its frames share.
    state : State or None
        The structure at this fold angle.
    vault : Vault or None
        The vault whose parameters (a, κ₀ s₀, p_xy) the vault checks compare with.
    """

    crease: Crease
    shared: Shared | None = None
    state: State | None = None
    vault: Vault | None = None

    @property
    def structure(self) -> Structure:
        """The structure certified (shared by every frame)."""
        return self.shared.structure

    @property
    def samples(self) -> int:
        """Samples along curve 1 at this sampling."""
        return len(self.crease.curve.s)

    @property
    def step(self) -> float:
        """Arc-length step h of curve 1."""
        return float(self.crease.s[1] - self.crease.s[0])

    @property
    def alpha(self) -> float:
        """The frame's half fold angle α, radians."""
        return float(self.crease.alpha.constant)

    @property
    def inner_t(self) -> np.ndarray:
        """t of the samples 2 … n − 3 where differences are measured, (n − 4,)."""
        return self.crease.s[2:-2] / self.crease.curve.length

    @cached_property
    def ulp(self) -> float:
        """:data:`ROUNDING` units in the last place of the largest coordinate."""
        x = self.crease.curve.points if self.state is None else self.state.vertices
        return ROUNDING * _EPS * float(np.abs(x).max() + self.crease.curve.length)

    @cached_property
    def rulings(self) -> np.ndarray:
        """Ruling vectors ℓ_L r_L, ℓ_R r_R at curve 1 from its built neighbours (1, 0), (0, 1), (2, n, 3)."""
        if self.state is None:
            return np.stack(self.crease.rulings())
        x = self.state.lattice.points(np.array([[0, 0], [1, 0], [0, 1]], float))
        return x[1:] - x[0]

    @cached_property
    def tubes(self) -> np.ndarray:
        """Built curves at corners 1–4 of every tube, (K, 4, n, 3)."""
        return self.state.vertices[self.structure.cell_curves]

    @cached_property
    def coords(self) -> np.ndarray:
        """The mesh vertices of this state, (V, 3)."""
        return self.shared.topology.coords(self.state.vertices)

    @property
    def tangent(self) -> np.ndarray:
        """Curve 1's unit tangent T₁ (its built frame), (n, 3)."""
        return self.crease.curve.frames[:, :, 0]

    @cached_property
    def half_angles(self) -> np.ndarray:
        """α measured at corners 1–4 of every tube from its two strips, (K, 4, n − 4)."""
        X, h = self.tubes, self.step
        return np.stack([measure.crease_half_angle(X[:, c], X[:, (c - 1) % 4], X[:, (c + 1) % 4], h, kind=CORNER_KINDS[c])
                         for c in range(4)], axis=1)

    @cached_property
    def measured_alpha(self) -> np.ndarray:
        """α at curve 1 from its built rulings, (n − 4,)."""
        x = self.crease.curve.points
        return measure.crease_half_angle(x, x + self.rulings[0], x + self.rulings[1], self.step, kind="fold")

    @cached_property
    def strip_widths(self) -> np.ndarray:
        """Distance between the tangent lines of the two creases of every strip, (K, 4, n)."""
        X, T = self.tubes, self.tangent
        return np.stack([measure.tangent_line_distance(X[:, a], X[:, b], T) for a, b in STRIPS], axis=1)


# --------------------------------------------------------------------------------------
# residuals and checks


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
        """``|r(2h) − r(h)|``: pointwise at the t both sample (where they have t), else of the largest values."""
        if self.t is None or coarse.t is None:
            return abs(coarse.worst[0] - self.worst[0])
        k = np.clip(np.searchsorted(self.t, coarse.t), 0, len(self.t) - 1)
        same = np.abs(self.t[k] - coarse.t) < 0.25 * (self.t[1] - self.t[0])
        diff = np.abs(np.asarray(coarse.values)[..., same] - np.asarray(self.values)[..., k[same]])
        return float(np.max(diff)) if diff.size else math.inf


@dataclass(frozen=True)
class CheckSpec:
    """One entry of the certificate's registry.

    Attributes
    ----------
    name : str
        Stable identifier (a JSON key).
    scope : {"crease", "frame", "vault", "panels", "panel_vault", "mechanism"}
        ``"crease"``: curve 1 of a single fold and of every frame of a smooth structure
        (the smooth crease a panel structure samples); ``"frame"``: every frame of a smooth
        structure; ``"vault"``: a smooth vault at its design angle; ``"panels"``: every
        frame of a structure of rigid panels; ``"panel_vault"``: a panel vault at its
        design angle; ``"mechanism"``: a panel structure's mechanism, once.
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
        return (f"error ∝ h{power}: tolerance = |r(2h) − r(h)|/2 + rounding (Richardson error "
                f"|r(2h) − r(h)|/{2**self.order - 1} × safety {(2**self.order - 1) / 2:g}); cap {self.cap:g} {self.unit}")


@dataclass(frozen=True)
class Check:
    """The outcome of one check over every frame it applies to.

    Attributes
    ----------
    name, unit, measures, model : str
        From the :class:`CheckSpec`.
    value : float
        The largest residual, in the frame with the smallest margin (NaN if it broke).
    tolerance : float
        Its tolerance there.
    status : {"pass", "insufficient resolution", "fail"}
    where : str
        Frame and place of that value.
    frames : int
        Frames measured.
    samples_needed : int or None
        For "insufficient resolution": the sample count that would do.
    """

    name: str
    value: float
    tolerance: float
    status: str
    unit: str
    measures: str
    model: str
    where: str = ""
    frames: int = 1
    samples_needed: int | None = None

    @property
    def passed(self) -> bool:
        """Whether the check passed (not a failure, nor insufficient resolution)."""
        return self.status == "pass"

    @property
    def margin(self) -> float | None:
        """tolerance / value: how many times the residual fits in its tolerance (None if it is 0 or NaN)."""
        return self.tolerance / self.value if self.value > 0 and math.isfinite(self.value) else None

    def to_dict(self) -> dict:
        """JSON-ready (NaN as None)."""
        def finite(x):
            return x if x is None or math.isfinite(x) else None

        return {"name": self.name, "value": finite(self.value), "tolerance": finite(self.tolerance), "margin": finite(self.margin),
                "status": self.status, "passed": self.passed, "unit": self.unit, "where": self.where, "frames": self.frames,
                "samples_needed": self.samples_needed, "measures": self.measures, "model": self.model}


@dataclass(frozen=True)
class Certificate:
    """Every check of a design, the frames certified and the fold-angle range where all hold.

    Attributes
    ----------
    checks : tuple of Check
    fold_angles : tuple of float
        2α of the certified frames, degrees (empty for a single curved fold).
    holds_up_to : float or None
        The largest fold angle 2α (degrees, to 1.5°) up to which every check passes at
        this sampling, when it passes at every certified frame; None otherwise.
    samples : int
        Samples along curve 1 (vertices along each crease of a panel structure).
    mechanism : CertifiedMechanism or None
        A panel structure's mechanism: degrees of freedom and singular values.
    """

    checks: tuple[Check, ...]
    fold_angles: tuple[float, ...] = ()
    holds_up_to: float | None = None
    samples: int = 0
    mechanism: CertifiedMechanism | None = None

    @property
    def passed(self) -> bool:
        """Whether every check passed."""
        return all(c.passed for c in self.checks)


# --------------------------------------------------------------------------------------
# the measurements


def _curve(uv: np.ndarray) -> Callable[[tuple[int, ...]], str]:
    return lambda i: f"curve {tuple(uv[i[0]].tolist())}"


def _strip(i: tuple[int, ...]) -> str:
    return f"tube {i[0] + 1}, strip {i[1] + 1}→{i[1] % 4 + 2}"


def _developability(frame: Frame) -> Residual:
    x, h = frame.crease.curve.points, frame.step
    rates = np.hypot(frame.crease.curve.kappa(frame.crease.s), frame.crease.curve.tau(frame.crease.s)).max()
    values = measure.ruling_twist(x, frame.rulings, h) / rates
    length = float(measure.norm(frame.rulings).min())
    return Residual(values, 1.5 * frame.ulp / (length * h * rates), lambda i: ("left", "right")[i[0]] + " rulings", frame.inner_t)


def _planar_curvature(frame: Frame) -> Residual:
    x, h = frame.crease.curve.points, frame.step
    if frame.shared is None:
        k2 = frame.crease.kappa_2d[2:-2]  # the crease pattern of a single fold is its input
    else:
        k2 = measure.curvature(frame.shared.flat.lattice.crease.curve.points, h)
    scale = float(np.abs(k2).max())
    values = np.abs(measure.curvature(x, h) * np.cos(frame.measured_alpha) - k2) / scale
    return Residual(values, 12 * frame.ulp / (h**2 * scale), lambda i: "", frame.inner_t)


def _frame_agreement(frame: Frame) -> Residual:
    uv = frame.structure.curves_uv
    values = measure.tangent_deviation(frame.state.vertices, frame.tangent, frame.step)
    f_min = float(frame.state.lattice.domain.factor(uv.astype(float)).min())
    return Residual(values, 1.5 * frame.ulp / (frame.step * f_min), _curve(uv), frame.inner_t)


def _eq19(frame: Frame) -> Residual | None:
    """κ_2D tan α cosec β ds of neighbouring creases, each factor measured at its own crease."""
    if frame.alpha == 0:
        return None  # both sides vanish in the flat state
    X, h = frame.tubes, frame.step
    alpha = frame.half_angles  # (K, 4, m)
    kappa = measure.curvature(X, h)  # (K, 4, m)
    speed = measure.norm(measure.derivative(X, h))
    ratios = []
    for a, b in STRIPS:
        ruling = X[:, b, 2:-2] - X[:, a, 2:-2]
        sides = []
        for c in (a, b):
            sin_beta = np.sin(measure.angle_between(ruling, measure.derivative(X[:, c], h)))
            sides.append(kappa[:, c] * np.sin(alpha[:, c]) * speed[:, c] / sin_beta)
        ratios.append(sides[0] / sides[1] - 1)
    values = np.abs(np.stack(ratios, axis=1))  # (K, 4 strips, m)
    length = float(measure.norm(X[:, 1] - X[:, 0]).min())
    floor = frame.ulp * (24 / (h**2 * float((kappa * speed**2).min())) + 6 / (h * length * math.sin(frame.alpha)))
    return Residual(values, floor, _strip, frame.inner_t)


def _isometry(frame: Frame) -> Residual:
    top = frame.shared.topology
    with np.errstate(invalid="ignore", divide="ignore"):
        values = np.abs(measure.edge_lengths(frame.coords, top.edges_vertices) / frame.shared.flat_lengths - 1)
    return Residual(values, 4 * frame.ulp / frame.shared.shortest_edge, lambda i: f"edge {i[0]} ({top.edges_kind[i[0]]})")


def _quad_planarity(frame: Frame) -> Residual:
    values = measure.quad_nonplanarity(frame.coords, frame.shared.quads)
    return Residual(values, 4 * frame.ulp / frame.shared.shortest_edge, lambda i: f"quad {i[0]} (strip {i[0] // (frame.samples - 1) + 1})")


def _fold_angles(frame: Frame) -> Residual:
    top = frame.shared.topology
    creases, faces = frame.shared.creases
    measured = mesh_fold_angles(frame.coords, top.faces_vertices, top.edges_vertices[creases], faces_of_edges=faces)
    values = measure.fold_angle_deviation(measured, top.edges_kind[creases], 2 * math.degrees(frame.alpha))
    return Residual(values, math.degrees(4 * frame.ulp / frame.shared.shortest_edge),
                    lambda i: f"edge {creases[i[0]]} ({top.edges_kind[creases[i[0]]]})")


#: The ruling family of every strip of a tube: "L" where it steps in u, "R" where in v.
_STRIP_SIDES = np.array(["L" if (CORNERS[b] - CORNERS[a])[0] else "R" for a, b in STRIPS])


def _width_law(frame: Frame) -> Residual:
    pattern = frame.state.lattice.pattern
    law = measure.width_integral(pattern.kappa_2d, pattern.beta, pattern.s)
    left = (_STRIP_SIDES == "L")[None, :, None]
    start = np.where(left, pattern.width_left[0], pattern.width_right[0])
    values = np.abs(np.log(frame.strip_widths / start) - np.where(left, -law, law))
    return Residual(values, 2 * frame.ulp / float(frame.strip_widths.min()), _strip, frame.crease.s / frame.crease.curve.length)


def _section_area(frame: Frame) -> Residual:
    widths = frame.strip_widths
    w_l, w_r = widths[:, 3, 2:-2], widths[:, 0, 2:-2]  # strips 4→1 (left) and 1→2 (right) around crease 1
    pattern = frame.state.lattice.pattern
    scale = pattern.width_left[0] * pattern.width_right[0]
    values = np.abs(w_l * w_r * np.sin(2 * frame.half_angles[:, 0]) - scale * math.sin(2 * frame.alpha)) / scale
    length = float(measure.norm(frame.tubes[:, 1] - frame.tubes[:, 0]).min())
    return Residual(values, frame.ulp * (4 / float(widths.min()) + 3 / (frame.step * length)), lambda i: f"tube {i[0] + 1}", frame.inner_t)


def _regression(frame: Frame) -> Residual:
    uv = frame.structure.curves_uv
    predicted = frame.state.lattice.domain.factor(uv.astype(float))
    margin = float(predicted.min())
    measured = measure.speed_factors(frame.state.vertices, frame.tangent, frame.step)
    values = np.abs(measured - predicted[:, 2:-2]) / margin
    return Residual(values, 1.5 * frame.ulp / (frame.step * margin), _curve(uv), frame.inner_t)


def _tube_closure(frame: Frame) -> Residual:
    X, h, a = frame.tubes, frame.step, frame.alpha
    values = []
    for c, (_, nxt) in enumerate(STRIPS):
        prev = (c - 1) % 4
        du, dv = CORNERS[nxt] - CORNERS[c]
        back = CORNERS[prev] - CORNERS[c]  # toward the previous crease: the other family, ±1 step
        side, sign = ("L", du) if du else ("R", dv)
        ruling = (X[:, prev] - X[:, c]) * (back[0] + back[1])  # oriented as r in Eqs. 5–6
        rebuilt = measure.rebuilt_strip(X[:, c], ruling, X[:, nxt], h, alpha=a, side=side, sign=float(sign))
        values.append(measure.norm(rebuilt - X[:, nxt, 2:-2]) / frame.strip_widths[:, c, 2:-2])
    kappa_min = float(frame.crease.curve.kappa(frame.crease.s).min())
    floor = 12 * frame.ulp / (h**2 * kappa_min * float(frame.strip_widths.min()))
    return Residual(np.stack(values, axis=1), floor, lambda i: f"tube {i[0] + 1}, crease {i[1] + 1} → {i[1] % 4 + 2}", frame.inner_t)


def _ground_plane(frame: Frame) -> Residual:
    vertices = frame.state.vertices
    size = float(np.abs(vertices).max())
    uv = frame.structure.curves_uv
    return Residual(np.abs(vertices[:, [0, -1], 2]) / size, _accumulated(frame) / size,
                    lambda i: f"curve {tuple(uv[i[0]].tolist())}, t = {i[1]}")


def _arch_condition(frame: Frame) -> Residual:
    """Eq. (20), the ends facing opposite ways, and the chord normal to T(0), on the built curve 1."""
    curve = frame.crease.curve
    T = curve.frames[:, :, 0]
    m = (len(curve.s) - 1) // 2
    values = np.array([abs(T[0] @ T[m]), measure.norm(T[0] + T[-1]), abs((curve.points[-1] - curve.points[0]) @ T[0]) / curve.length])
    labels = ("T(s0/2)·T(0) (Eq. 20)", "|T(0) + T(s1)|", "(x(s1) − x(0))·T(0) / s1")
    return Residual(values, _accumulated(frame) / curve.length, lambda i: labels[i[0]])


def _proportion_change(frame: Frame) -> Residual:
    vault = frame.vault
    widths = frame.strip_widths
    w_r, w_l = widths[0, 0], widths[0, 3]  # strips 1→2 and 4→1 of the base tube
    m = (frame.samples - 1) // 2
    values = np.abs(np.array([w_r[m] / w_r[0] / vault.proportion_change, w_r[m] / w_l[m] / vault.p_xz]) - 1)
    labels = ("w_R(s0/2)/w_R(0) against exp(a κ0 s0 cot α / π)", "p_xz = w_R/w_L at s0/2 against p_xy × change²")
    return Residual(values, _accumulated(frame) / float(widths.min()), lambda i: labels[i[0]])


def _panel_isometry(frame: Frame) -> Residual:
    shared = frame.shared
    values = np.abs(measure.edge_lengths(frame.coords, shared.bars) / shared.bar_lengths - 1)
    edges, kinds = len(shared.topology.edges_vertices), shared.topology.edges_kind

    def name(i: tuple[int, ...]) -> str:
        e = i[0]
        return f"edge {e} ({kinds[e]})" if e < edges else f"panel {(e - edges) % len(shared.quads)}, a diagonal"

    return Residual(values, 4 * frame.ulp / float(shared.bar_lengths.min()), name)


def _panel_ground_plane(frame: Frame) -> Residual:
    """``|z|`` of every foot over the vault's size; the floor adds the tilt the arch root's residual leaves."""
    vertices = frame.state.vertices
    size = float(np.abs(vertices).max())
    uv = frame.structure.curves_uv
    return Residual(np.abs(vertices[:, [0, -1], 2]) / size, frame.ulp / size + 3 * frame.vault.arch.residual,
                    lambda i: f"curve {tuple(uv[i[0]].tolist())}, " + ("first", "last")[i[1]] + " vertex")


def _generic_states(frame: Frame) -> tuple[CertifiedMechanism, tuple]:
    """The certified mechanism and its states away from the flat one (half and full design angle)."""
    analysis = certified_mechanism(frame.structure)
    return analysis, analysis.states[1:]


def _scope_note(analysis: CertifiedMechanism) -> str:
    return f" ({analysis.scope}: the dense SVD is bounded)" if analysis.scope else ""


def _mechanism_dof(frame: Frame) -> Residual:
    analysis, states = _generic_states(frame)
    flat = analysis.states[0]
    return Residual(np.array([abs(m.dof - 1) for m in states], float), 0.0,
                    lambda i: f"{states[i[0]].label}: {states[i[0]].dof} internal DOF (nullity {states[i[0]].nullity}){_scope_note(analysis)}; "
                              f"flat: {flat.dof}, first-order lifts of the flat sheets")


def _mechanism_clearance(frame: Frame) -> Residual:
    analysis, states = _generic_states(frame)
    return Residual(np.array([m.clearance for m in states]), CLEARANCE,
                    lambda i: f"{states[i[0]].label}: gap {states[i[0]].gap:.2g} between null and stiff singular values{_scope_note(analysis)}")


def _accumulated(frame: Frame) -> float:
    """Rounding accumulated over n integration steps: ROUNDING ulps × √n, in model units."""
    return frame.ulp * math.sqrt(frame.samples)


#: The registry: every check of the certificate, in report order.
CHECKS: tuple[CheckSpec, ...] = (
    CheckSpec("developability", "crease",
              "|r'·p| along both families of rulings of curve 1: r the unit ruling from the built neighbour creases "
              "(or the built ruling vectors of a single fold), p the normal of the plane of r and the measured tangent; "
              "the tangent plane must not turn along a ruling. Relative to the largest frame rate √(κ² + τ²)",
              "relative", 4, 1e-3, _developability),
    CheckSpec("eq2_planar_curvature", "crease",
              "Eq. (2): κ of the built curve 1 (differences of its points) times cos α measured from its built rulings, "
              "against κ_2D measured on the crease pattern (curve 1 of the flat state; a single fold's input pattern). "
              "Relative to the largest κ_2D",
              "relative", 4, 1e-3, _planar_curvature),
    CheckSpec("frame_agreement", "frame",
              "angle between every crease's measured tangent (differences of its points) and curve 1's T at equal t: "
              "the shared frame; a crease past its curve of regression runs backwards (π)",
              "rad", 4, 1e-3, _frame_agreement),
    CheckSpec("eq19", "frame",
              "the paper's Eq. (19) across every strip: κ_2D tan α cosec β ds/dt at its two creases, each factor "
              "measured at its own crease (κ and ds/dt from differences, α from the two strips' rulings, β between the "
              "crease's tangent and the strip's ruling); not defined in the flat state",
              "relative", 4, 1e-3, _eq19),
    CheckSpec("isometry", "frame",
              "|ℓ/ℓ₀ − 1| of every mesh edge against the crease pattern (the flat state): a triangle mesh is "
              "isometric exactly when every edge keeps its length; polyline chords shorten as (κ² − κ_2D²) h²/24",
              "relative", 2, 1e-3, _isometry),
    CheckSpec("ruling_quad_planarity", "frame",
              "distance of each ruling quad's fourth corner from the plane of the other three, over its diagonal: "
              "consecutive rulings of a developable are coplanar",
              "relative", 3, 1e-3, _quad_planarity),
    CheckSpec("fold_angles", "frame",
              "dihedral angle of the mesh at every crease edge against 2α (folds, mountain) and 180° − 2α (seams)",
              "°", 2, 0.1, _fold_angles),
    CheckSpec("width_law", "frame",
              "|ln(w/w(0)) ∓ ∫ κ_2D cot β ds| for every strip: w the distance between the tangent lines of its built "
              "creases (Eqs. 12–13 corrected); the integral by Gauss–Legendre on a grid 4× finer than the samples",
              "relative", 6, 1e-4, _width_law),
    CheckSpec("section_area", "frame",
              "w_L w_R sin 2α of every tube's section, widths measured between tangent lines and α from the built "
              "rulings, against w_L(0) w_R(0) sin 2α of the frame (constant in t). Relative to w_L(0) w_R(0)",
              "relative", 4, 1e-3, _section_area),
    CheckSpec("regression", "frame",
              "x'·T₁ of every crease (differences of its points along curve 1's arc length) against the Eq. (17) "
              "speed factor 1 − u w_L/w_lim_L − v w_R/w_lim_R of the regression domain (Eqs. 14–18) the design was "
              "accepted with; relative to the smallest factor, so a pass also says every crease runs forward",
              "relative", 4, 1e-3, _regression),
    CheckSpec("tube_closure", "frame",
              "each strip of every tube rebuilt from its first crease's own measured invariants (frame, κ, β, the "
              "width law from the measured width at t ≈ 0: the paper's construction step) lands on its second "
              "crease; the step from crease 4 closes the tube onto crease 1. Relative to the strip's width",
              "relative", 4, 1e-3, _tube_closure),
    CheckSpec("ground_plane", "vault",
              "|z| of both end sections of every crease at the design angle, relative to the vault's size",
              "relative", 6, 1e-6, _ground_plane),
    CheckSpec("arch_condition", "vault",
              "on the built curve 1: T(s0/2)·T(0) (Eq. 20), |T(0) + T(s1)| (the ends face opposite ways) and "
              "(x(s1) − x(0))·T(0)/s1 (the chord lies in the ground)",
              "", 6, 1e-6, _arch_condition),
    CheckSpec("proportion_change", "vault",
              "w_R(s0/2)/w_R(0) and p_xz = w_R/w_L at s0/2, measured between the tangent lines of the base tube's "
              "built creases, against exp(a κ0 s0 cot α/π) and p_xy × change²",
              "relative", 6, 1e-6, _proportion_change),
    CheckSpec("panel_isometry", "panels",
              "|ℓ/ℓ₀ − 1| of the four sides and both diagonals of every panel against the crease pattern (the flat "
              "state): each panel keeps its shape",
              "relative", 0, math.inf, _panel_isometry,
              rounding="4 × 32 ulps of the largest coordinate over the shortest side or diagonal (a length carries the "
                       "rounding of its two ends)"),
    CheckSpec("panel_planarity", "panels",
              "distance of each panel's fourth corner from the plane of the other three, over its diagonal: every panel "
              "stays planar",
              "relative", 0, math.inf, _quad_planarity,
              rounding="4 × 32 ulps of the largest coordinate over the shortest edge"),
    CheckSpec("panel_ground_plane", "panel_vault",
              "|z| of the first and last vertex of every polyline at the design angle, relative to the vault's size: "
              "both end sections stand on the ground (the discrete Eq. 20, (x_N − x_0)·n₀ = 0)",
              "relative", 0, math.inf, _panel_ground_plane,
              rounding="32 ulps of the largest coordinate over the size, plus 3 × the arch root's residual (the sine of "
                       "the chord's angle to the first end section, which tilts the far one by twice that)"),
    CheckSpec("mechanism_dof", "mechanism",
              "|DOF − 1| at half and full design angle: DOF = nullity − 6 of the Jacobian of every edge length, both panel "
              "diagonals and every panel's planarity, welded seams and bonds (curvefold.analysis.mechanism), counted "
              "below the rank tolerance 1e-9 σ_max. The flat state has more, first-order only (reported)",
              "DOF", 0, math.inf, _mechanism_dof,
              rounding="0: a count; the null singular values of a state built to rounding lie near 1e-15 σ_max"),
    CheckSpec("mechanism_clearance", "mechanism",
              "how near the rank tolerance (1e-9 σ_max) the nearest singular value lies, max min(σ/tol, tol/σ), at half "
              "and full design angle",
              "", 0, math.inf, _mechanism_clearance,
              rounding="1e-3: the count holds for any tolerance a thousand times larger or smaller; rounding puts the "
                       "null singular values near 1e-15 σ_max, a million times below it"),
)


# --------------------------------------------------------------------------------------
# certification


def _rebuilt(crease: Crease, structure: Structure | None, samples: int) -> tuple[Crease, Structure | None]:
    """The same design built again at another sample count, from the same functions."""
    c = crease.curve
    curve = SpaceCurve.from_curvature(c.kappa, c.tau, c.length, samples=samples, origin=c.points[0], frame=c.frames[0])
    coarse = Crease(curve, crease.alpha, crease.beta_left, crease.beta_right)
    if structure is None:
        return coarse, None
    lattice = structure.lattice
    pattern = Pattern.from_crease(coarse, float(lattice.width_left[0]), float(lattice.width_right[0]))
    return coarse, Structure(Lattice(coarse, pattern), structure.cells)


@dataclass(frozen=True)
class _Outcome:
    status: str
    value: float
    tolerance: float
    where: str
    samples_needed: int | None

    @property
    def ratio(self) -> float:
        return self.value / self.tolerance if math.isfinite(self.value) and self.tolerance > 0 else math.inf


def _judge(spec: CheckSpec, fine: Residual, coarse: Residual, samples: int, label: str) -> _Outcome:
    value, index = fine.worst
    where = label + (fine.locate(index) if index >= 0 else "")
    tolerance = fine.floor if spec.order == 0 else fine.change(coarse) / 2 + fine.floor
    if not (math.isfinite(value) and math.isfinite(tolerance)):
        return _Outcome("fail", math.nan, tolerance, where + " (not a number)", None)
    if spec.order == 0 or value > tolerance or tolerance <= spec.cap:  # exact, more than the discretisation explains, or certified
        return _Outcome("pass" if value <= tolerance else "fail", value, tolerance, where, None)
    if fine.floor >= spec.cap / 4:  # rounding alone fills the cap: more samples cannot help
        return _Outcome("insufficient resolution", value, tolerance, where + " (rounding)", None)
    needed = 1 + math.ceil((samples - 1) * (4 * (tolerance - fine.floor) / spec.cap) ** (1 / spec.order))
    return _Outcome("insufficient resolution", value, tolerance, where, max(needed, samples + 1))


def _worst(outcomes: list[_Outcome]) -> _Outcome:
    rank = max(STATUSES.index(o.status) for o in outcomes)
    pick = [o for o in outcomes if STATUSES.index(o.status) == rank]
    worst = max(pick, key=lambda o: o.ratio)
    needed = [o.samples_needed for o in pick if o.samples_needed is not None]
    return _Outcome(worst.status, worst.value, worst.tolerance, worst.where, max(needed) if needed else None)


def _frame(shared: Shared, vault: Vault | None, fold_angle: float | None) -> Frame:
    """The structure at a fold angle (refolded from its pattern), or as built (None)."""
    state = shared.structure.state(fold_angle)
    return Frame(state.lattice.crease, shared, state, vault)


def _measure(specs: Sequence[CheckSpec], fine: Frame, coarse: Frame | None, label: str) -> dict[str, _Outcome]:
    """Each spec's outcome on a frame (``coarse``, the half-sampled one, is read by orders > 0 only)."""
    out = {}
    for spec in specs:
        residual = spec.measure(fine)
        if residual is not None:
            out[spec.name] = _judge(spec, residual, spec.measure(coarse) if spec.order else None, fine.samples, label)
    return out


def certify(crease: Crease, structure: Structure | None = None, vault: Vault | None = None, *,
            fold_angles: Sequence[float] | None = None, degrees: bool = True) -> Certificate:
    """Measure every check that applies, in every frame, against its tolerance.

    Parameters
    ----------
    crease : Crease
        The single curved fold, or curve 1 of the structure (not read: the structure's own).
    structure : Structure, optional
        A tube, block or vault stack. It is certified as built (at its design angle) and
        refolded from its pattern to 0° (the crease pattern), to its design angle and to
        every angle of ``fold_angles``; then the largest fold angle where every check still
        passes is found. A structure of rigid panels gets the panel checks and its
        mechanism, and the smooth crease it samples the crease checks (see the module notes).
    vault : Vault, optional
        Adds the ground-plane, arch and proportion checks at the design angle.
    fold_angles : sequence of float, optional, keyword-only
        Further frames to certify, 2α in [0°, 180°) (e.g. the exported motion).
    degrees : bool, keyword-only

    Returns
    -------
    Certificate

    Raises
    ------
    InputError
        A fold angle outside [0°, 180°), or fold angles for a single curved fold.
    """
    if structure is not None and isinstance(structure.lattice, PanelLattice):
        return _certify_panels(structure, vault, _certified_angles(structure, fold_angles, degrees))
    if structure is not None:
        crease = structure.lattice.crease
    elif fold_angles is not None:
        raise InputError("fold_angles: a single curved fold is certified in the one state it is built in")
    n = len(crease.s)
    coarse_samples = (n - 1) // 2 + 1
    if coarse_samples < _MIN_COARSE:
        return _too_coarse(structure, vault, n)
    coarse_crease, coarse_structure = _rebuilt(crease, structure, coarse_samples)
    if structure is None:
        specs = [s for s in CHECKS if s.scope == "crease"]
        outcomes = _measure(specs, Frame(crease), Frame(coarse_crease), "")
        return Certificate(tuple(_check(spec, [outcomes[spec.name]]) for spec in specs), samples=n)

    angles = _certified_angles(structure, fold_angles, degrees)
    specs = [s for s in CHECKS if s.scope in ("crease", "frame") or (s.scope == "vault" and vault is not None)]
    run = _runner(specs, vault, Shared(structure), Shared(coarse_structure))
    outcomes = _over_frames(specs, run, angles, ("crease", "frame", "vault"), ("crease", "frame"))
    checks = tuple(_check(spec, outcomes[spec.name]) for spec in specs)
    motion_passes = all(c.passed for c, spec in zip(checks, specs) if spec.scope != "vault")
    return Certificate(checks, tuple(angles), _holds_up_to(run, max(angles), ("crease", "frame")) if motion_passes else None, n)


def _certify_panels(structure: Structure, vault: Vault | None, angles: list[float]) -> Certificate:
    """:func:`certify` of a structure of rigid panels: its exact checks in every frame, its mechanism
    once, and the crease checks of the smooth crease it samples."""
    source = structure.lattice.source
    crease_checks = () if source is None else certify(source.crease).checks
    specs = [s for s in CHECKS if s.scope in ("panels", "mechanism") or (s.scope == "panel_vault" and vault is not None)]
    shared = Shared(structure)
    run = _runner(specs, vault, shared, None)
    outcomes = _over_frames(specs, run, angles, ("panels", "panel_vault"), ("panels",))
    mechanism = [s for s in specs if s.scope == "mechanism"]
    for name, outcome in _measure(mechanism, _frame(shared, vault, None), None, "").items():  # its states name themselves
        outcomes[name].append(outcome)
    checks = tuple(_check(spec, outcomes[spec.name]) for spec in specs)
    motion_passes = all(c.passed for c, spec in zip(checks, specs) if spec.scope == "panels")
    return Certificate(crease_checks + checks, tuple(angles), _holds_up_to(run, max(angles), ("panels",)) if motion_passes else None,
                       len(structure.lattice.s), certified_mechanism(structure))


def _certified_angles(structure: Structure, fold_angles: Sequence[float] | None, degrees: bool) -> list[float]:
    """2α of the certified frames, degrees, ascending: 0°, the design angle and ``fold_angles`` (validated)."""
    from ..geometry.sheets import _angles

    extra = [] if fold_angles is None else _angles(fold_angles, degrees, "fold_angles").tolist()
    return sorted({0.0, float(structure.lattice.crease.fold_angle), *map(float, extra)})


def _runner(specs: Sequence[CheckSpec], vault: Vault | None, fine: Shared,
            coarse: Shared | None) -> Callable[[float | None, tuple[str, ...]], dict[str, _Outcome]]:
    """``run(angle, scopes)``: the outcomes of the ``specs`` of ``scopes`` on the structure refolded
    to ``angle`` (None: as built), against the half-sampled one (``coarse``; None for order-0 checks)."""
    design = float(fine.structure.lattice.crease.fold_angle)

    def run(angle: float | None, scopes: tuple[str, ...]) -> dict[str, _Outcome]:
        label = f"2α = {design:g}° as built: " if angle is None else f"2α = {angle:g}°: "
        chosen = [s for s in specs if s.scope in scopes]
        return _measure(chosen, _frame(fine, vault, angle), None if coarse is None else _frame(coarse, vault, angle), label)

    return run


def _over_frames(specs: Sequence[CheckSpec], run: Callable[[float | None, tuple[str, ...]], dict[str, _Outcome]],
                 angles: Sequence[float], built: tuple[str, ...], folded: tuple[str, ...]) -> dict[str, list[_Outcome]]:
    """Every spec's outcomes: on the structure as built (the scopes ``built``), then refolded to each angle (``folded``)."""
    outcomes: dict[str, list[_Outcome]] = {s.name: [] for s in specs}
    for angle in (None, *angles):
        for name, outcome in run(angle, built if angle is None else folded).items():
            outcomes[name].append(outcome)
    return outcomes


def _holds_up_to(run: Callable[[float, tuple[str, ...]], dict[str, _Outcome]], start: float, scopes: tuple[str, ...]) -> float:
    """Largest 2α ≥ ``start`` (to 1.5°) where every check of ``scopes`` passes, by bisection."""
    lo, hi = start, 180.0
    while hi - lo > 1.5:
        mid = 0.5 * (lo + hi)
        ok = all(o.status == "pass" for o in run(mid, scopes).values())
        lo, hi = (mid, hi) if ok else (lo, mid)
    return round(lo, 1)


def _check(spec: CheckSpec, outcomes: list[_Outcome]) -> Check:
    worst = _worst(outcomes)
    return Check(spec.name, worst.value, worst.tolerance, worst.status, spec.unit, spec.measures, spec.model,
                 worst.where, len(outcomes), worst.samples_needed)


def _too_coarse(structure: Structure | None, vault: Vault | None, samples: int) -> Certificate:
    """Every check "insufficient resolution": the half-sampled design would not hold a stencil."""
    scopes = ("crease",) if structure is None else ("crease", "frame") + (("vault",) if vault is not None else ())
    needed = 2 * (_MIN_COARSE - 1) + 1
    checks = tuple(Check(s.name, math.nan, math.nan, "insufficient resolution", s.unit, s.measures, s.model,
                         f"{samples} samples; the check compares them with half as many", 0, needed)
                   for s in CHECKS if s.scope in scopes)
    return Certificate(checks, samples=samples)
