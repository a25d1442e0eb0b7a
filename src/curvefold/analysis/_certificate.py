"""The geometric certificate: every check of the registry measured on the built geometry and judged.

Every check (:data:`curvefold.analysis.CHECKS`) measures a residual that the construction makes zero
in the continuum, from the built points (:mod:`curvefold.analysis._measure`), never from the formula
that built them: a wrong formula leaves a residual of order one, a correct design only the
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
    A structure of rigid planar panels (a lattice that is
    :attr:`~curvefold.geometry.StructureLattice.rigid`, such as
    :mod:`curvefold.geometry._panels`) is exact by construction: every folded state is the
    flat panels moved rigidly, so its residuals are rounding, whatever the number of panels. Its
    checks have order 0: the tolerance is the rounding floor alone (:attr:`CheckSpec.rounding`
    states it), with no half-sampled design. They are ``panel_isometry`` (sides and both diagonals
    of every panel), ``panel_planarity``, ``panel_ground_plane`` (a vault standing by the discrete
    Eq. 20), and the mechanism (:func:`curvefold.analysis.certified_mechanism`): ``mechanism_dof``
    (one internal degree of freedom at half and full design angle) and ``mechanism_clearance`` (how
    clearly the singular values count it). The smooth crease the panels sample
    (:attr:`~curvefold.geometry.StructureLattice.smooth`) is certified by the crease checks. The
    smooth frame and vault checks do not apply: ``frame_agreement``, ``eq19``, ``width_law``,
    ``regression``, ``tube_closure``, ``arch_condition`` and ``proportion_change`` take derivatives
    along the creases or compare with the smooth closed forms, which a polyline meets only to
    O(1/N²) (measured in ``tests/test_panels.py``); ``isometry``, ``ruling_quad_planarity`` and
    ``ground_plane`` have exact panel counterparts above; ``fold_angles`` compares every fold edge
    with 2α, and a panel's fold lines fold by their own angle (``tan(ρ/2) = sin(φ/2) / sin β · tan
    α``), which isometry and planarity hold to (a wrong ρ breaks the panels).

Adding a check is one entry in :data:`~curvefold.analysis.CHECKS`: a
:class:`~curvefold.analysis.CheckSpec` with a measurement ``frame -> Residual`` and its
order and cap; a test must damage a design so that it fails.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import cast

from ..geometry._contact import first_contact
from ..geometry._crease import Crease
from ..geometry._curve import SpaceCurve
from ..geometry._fold_angle import check_fold_angles
from ..geometry._lattice import Lattice
from ..geometry._lattice_pattern import Pattern
from ..geometry._structure import Structure
from ..geometry._thick import ThickPanels
from ..kernel._errors import InputError
from ..vault._assembly import Vault
from ._checks import CHECKS, CheckSpec, Residual
from ._frames import Frame, Shared
from ._mechanism import CertifiedMechanism, certified_mechanism

__all__ = ["Check", "Certificate", "certify", "certify_single_fold"]

#: Fewest samples of the half-sampled design: the measurements' 5-point stencils need room.
_MIN_COARSE = 9
#: The grid of :func:`~curvefold.geometry.first_contact`, degrees: the motion holds to one step
#: before it.
CONTACT_STEP = 1.0
#: Statuses, best first.
STATUSES = ("pass", "insufficient resolution", "fail")


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
        """tolerance / value: how many times the residual fits in its tolerance (None if it is 0
        or NaN)."""
        return self.tolerance / self.value if self.value > 0 and math.isfinite(self.value) else None

    def to_dict(self) -> dict:
        """JSON-ready (NaN as None)."""

        def finite(x):
            return x if x is None or math.isfinite(x) else None

        return {
            "name": self.name,
            "value": finite(self.value),
            "tolerance": finite(self.tolerance),
            "margin": finite(self.margin),
            "status": self.status,
            "passed": self.passed,
            "unit": self.unit,
            "where": self.where,
            "frames": self.frames,
            "samples_needed": self.samples_needed,
            "measures": self.measures,
            "model": self.model,
        }


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
        this sampling, and at most one degree before the first contact, when every check
        passes at every certified frame; None otherwise.
    samples : int
        Samples along curve 1 (vertices along each crease of a panel structure).
    mechanism : CertifiedMechanism or None
        A panel structure's mechanism: degrees of freedom and singular values.
    first_contact : float or None
        The first fold angle from the design angle on (degrees, on a 1° grid) where parts of
        the structure far apart touch (:func:`curvefold.geometry.first_contact`), or
        None if none do up to 179°: the motion ends there, and so does :attr:`holds_up_to`.
    thickness : dict or None
        For thick panels (:func:`certify`'s ``thick``): their range of motion, stack and
        checks (:func:`curvefold.analysis.thickness_checks`), JSON-ready.
    """

    checks: tuple[Check, ...]
    fold_angles: tuple[float, ...] = ()
    holds_up_to: float | None = None
    samples: int = 0
    mechanism: CertifiedMechanism | None = None
    first_contact: float | None = None
    thickness: dict | None = None

    @property
    def passed(self) -> bool:
        """Whether every check passed."""
        return all(c.passed for c in self.checks)


# --------------------------------------------------------------------------------------
# certification


def _rebuilt(
    crease: Crease, structure: Structure | None, samples: int
) -> tuple[Crease, Structure | None]:
    """The same design built again at another sample count, from the same functions."""
    c = crease.curve
    curve = SpaceCurve.from_curvature(
        c.kappa, c.tau, c.length, samples=samples, origin=c.points[0], frame=c.frames[0]
    )
    coarse = Crease(curve, crease.alpha, crease.beta_left, crease.beta_right)
    if structure is None:
        return coarse, None
    lattice = structure.lattice
    pattern = Pattern.from_crease(
        coarse, float(lattice.width_left[0]), float(lattice.width_right[0])
    )
    # A Lattice is a StructureLattice: its crease's fold angle is constant (not Crease's)
    return coarse, Structure(Lattice(coarse, pattern), structure.cells)  # type: ignore[arg-type]


@dataclass(frozen=True)
class _Outcome:
    status: str
    value: float
    tolerance: float
    where: str
    samples_needed: int | None

    @property
    def ratio(self) -> float:
        return (
            self.value / self.tolerance
            if math.isfinite(self.value) and self.tolerance > 0
            else math.inf
        )


def _judge(
    spec: CheckSpec, fine: Residual, coarse: Residual | None, samples: int, label: str
) -> _Outcome:
    value, index = fine.worst
    where = label + (fine.locate(index) if index >= 0 else "")
    if spec.order == 0:
        tolerance = fine.floor
    else:
        assert coarse is not None, "a check of order > 0 is measured on the coarse frame too"
        tolerance = fine.change(coarse) / 2 + fine.floor
    if not (math.isfinite(value) and math.isfinite(tolerance)):
        return _Outcome("fail", math.nan, tolerance, where + " (not a number)", None)
    # exact, more than the discretisation explains, or certified
    if spec.order == 0 or value > tolerance or tolerance <= spec.cap:
        return _Outcome("pass" if value <= tolerance else "fail", value, tolerance, where, None)
    if fine.floor >= spec.cap / 4:  # rounding alone fills the cap: more samples cannot help
        return _Outcome("insufficient resolution", value, tolerance, where + " (rounding)", None)
    needed = 1 + math.ceil(
        (samples - 1) * (4 * (tolerance - fine.floor) / spec.cap) ** (1 / spec.order)
    )
    return _Outcome("insufficient resolution", value, tolerance, where, max(needed, samples + 1))


def _worst(outcomes: list[_Outcome]) -> _Outcome:
    rank = max(STATUSES.index(o.status) for o in outcomes)
    pick = [o for o in outcomes if STATUSES.index(o.status) == rank]
    worst = max(pick, key=lambda o: o.ratio)
    needed = [o.samples_needed for o in pick if o.samples_needed is not None]
    return _Outcome(
        worst.status, worst.value, worst.tolerance, worst.where, max(needed) if needed else None
    )


def _measure(
    specs: Sequence[CheckSpec], fine: Frame, coarse: Frame | None, label: str
) -> dict[str, _Outcome]:
    """Each spec's outcome on a frame (``coarse``, the half-sampled one, is read by orders > 0
    only)."""
    out = {}
    for spec in specs:
        residual = spec.measure(fine)
        if residual is not None:
            rough = spec.measure(coarse) if spec.order and coarse is not None else None
            out[spec.name] = _judge(spec, residual, rough, fine.samples, label)
    return out


def certify(
    crease: Crease,
    structure: Structure | None = None,
    vault: Vault | None = None,
    *,
    fold_angles: Sequence[float] | None = None,
    degrees: bool = True,
    thick: ThickPanels | None = None,
) -> Certificate:
    """Measure every check that applies, in every frame, against its tolerance.

    Parameters
    ----------
    crease : Crease
        The single curved fold, or curve 1 of the structure (not read: the structure's own).
    structure : Structure, optional
        A tube, block or vault stack. It is certified as built (at its design angle) and
        refolded from its pattern to 0° (the crease pattern), to its design angle and to
        every angle of ``fold_angles``; then the largest fold angle where every check still
        passes is found. A rigid structure gets the panel checks and its mechanism, and the
        smooth crease it samples the crease checks (see the module notes).
    vault : Vault, optional
        Adds the ground-plane, arch and proportion checks at the design angle.
    fold_angles : sequence of float, optional, keyword-only
        Further frames to certify, 2α in [0°, 180°) (e.g. the exported motion).
    degrees : bool, keyword-only
    thick : ThickPanels, optional, keyword-only
        The structure's panels made thick: adds the checks of scope ``"thick"`` (hinge axes
        on their creases, no interpenetration within the measured range, one degree of
        freedom; :func:`curvefold.analysis.thickness_checks`).

    Returns
    -------
    Certificate

    Raises
    ------
    InputError
        A fold angle outside [0°, 180°), or fold angles for a single curved fold.
    """
    if structure is not None and structure.lattice.rigid:
        cert = _certify_rigid(structure, vault, _certified_angles(structure, fold_angles, degrees))
        return cert if thick is None else _with_thickness(cert, thick)
    if thick is not None:
        raise InputError("thick: thick panels are certified with their structure of rigid panels")
    if structure is not None:
        crease = cast(Crease, structure.lattice.crease)  # not rigid: a smooth lattice's
    elif fold_angles is not None:
        raise InputError(
            "fold_angles: a single curved fold is certified in the one state it is built in"
        )
    n = len(crease.s)
    coarse_samples = (n - 1) // 2 + 1
    if coarse_samples < _MIN_COARSE:
        return _too_coarse(structure, vault, n)
    coarse_crease, coarse_structure = _rebuilt(crease, structure, coarse_samples)
    if structure is None:
        specs = [s for s in CHECKS if s.scope == "crease"]
        measured = _measure(specs, Frame(crease), Frame(coarse_crease), "")
        return Certificate(tuple(_check(spec, [measured[spec.name]]) for spec in specs), samples=n)

    angles = _certified_angles(structure, fold_angles, degrees)
    specs = [
        s
        for s in CHECKS
        if s.scope in ("crease", "frame", "motion") or (s.scope == "vault" and vault is not None)
    ]
    assert coarse_structure is not None  # rebuilt with the structure
    run = _runner(specs, vault, Shared(structure), Shared(coarse_structure))
    outcomes = _over_frames(
        specs,
        run,
        angles,
        ("crease", "frame", "vault", "motion"),
        ("crease", "frame"),
        structure.lattice.crease.fold_angle,
    )
    checks = tuple(_check(spec, outcomes[spec.name]) for spec in specs)
    return _with_range(checks, specs, structure, angles, run, ("crease", "frame"), n)


def certify_single_fold(states: Sequence[tuple[float, Crease]]) -> Certificate:
    """The crease checks of a single curved fold in every state of its motion, judged as
    :func:`certify` judges them.

    Parameters
    ----------
    states : sequence of (float, Crease)
        The start angle 2α(0) (degrees) and the crease of every state: the fold as built and
        its crease pattern refolded (:meth:`curvefold.geometry.SingleFold.at`).

    Returns
    -------
    Certificate
        With ``fold_angles`` the states' start angles.
    """
    specs = [s for s in CHECKS if s.scope == "crease"]
    n = len(states[0][1].s)
    coarse_samples = (n - 1) // 2 + 1
    if coarse_samples < _MIN_COARSE:
        return _too_coarse(None, None, n)
    outcomes: dict[str, list[_Outcome]] = {s.name: [] for s in specs}
    for angle, crease in states:
        coarse, _ = _rebuilt(crease, None, coarse_samples)
        for name, outcome in _measure(
            specs, Frame(crease), Frame(coarse), f"2α(0) = {angle:g}°: "
        ).items():
            outcomes[name].append(outcome)
    return Certificate(
        tuple(_check(spec, outcomes[spec.name]) for spec in specs),
        tuple(a for a, _ in states),
        samples=n,
    )


def _certify_rigid(structure: Structure, vault: Vault | None, angles: list[float]) -> Certificate:
    """:func:`certify` of a structure of rigid panels: its exact checks in every frame, its
    mechanism once, and the crease checks of the smooth crease it samples."""
    smooth = structure.lattice.smooth
    crease_checks = () if smooth is None else certify(smooth.crease).checks
    specs = [
        s
        for s in CHECKS
        if s.scope in ("panels", "mechanism", "motion")
        or (s.scope == "panel_vault" and vault is not None)
    ]
    shared = Shared(structure)
    run = _runner(specs, vault, shared, None)
    outcomes = _over_frames(
        specs,
        run,
        angles,
        ("panels", "panel_vault", "motion"),
        ("panels",),
        structure.lattice.crease.fold_angle,
    )
    mechanism = [s for s in specs if s.scope == "mechanism"]
    # its states name themselves
    for name, outcome in _measure(mechanism, Frame.at(shared, None, vault), None, "").items():
        outcomes[name].append(outcome)
    checks = tuple(_check(spec, outcomes[spec.name]) for spec in specs)
    cert = _with_range(checks, specs, structure, angles, run, ("panels",), len(structure.lattice.s))
    return replace(
        cert, checks=crease_checks + cert.checks, mechanism=certified_mechanism(structure)
    )


def _with_thickness(cert: Certificate, thick: ThickPanels) -> Certificate:
    """The certificate with the checks of thick panels (scope ``"thick"``), measured on their
    solids by :func:`~curvefold.analysis.thickness_checks` and judged exactly: the value
    against its limit (a count against 1)."""
    from ._thick_checks import thickness_checks

    report = thickness_checks(thick)
    measured = {c["name"]: c for c in report["checks"]}
    r = report["range"]
    where = f"{len(report['states'])} states, 2α = {r['low']:.4g}° to {r['high']:.4g}°"
    checks = []
    for spec, name in zip(
        (s for s in CHECKS if s.scope == "thick"),
        ("hinges on creases", "no interpenetration", "one degree of freedom"),
    ):
        c = measured[name]
        if name == "one degree of freedom":
            value, tolerance = float(max(abs(d - 1) for d in c["value"])), 0.0
        else:
            value, tolerance = max(float(c["value"]), 0.0), float(c["limit"])
        status = "pass" if c["passed"] else "fail"
        checks.append(
            Check(spec.name, value, tolerance, status, spec.unit, spec.measures, spec.model, where)
        )
    return replace(cert, checks=cert.checks + tuple(checks), thickness=report)


def _with_range(
    checks: tuple[Check, ...],
    specs: Sequence[CheckSpec],
    structure: Structure,
    angles: list[float],
    run: Callable,
    scopes: tuple[str, ...],
    samples: int,
) -> Certificate:
    """The certificate of a structure with the range of its motion: where its checks hold, up to
    the last degree before its first contact (the bisection cannot look for a contact: past
    one, parts that went through each other can be far apart again)."""
    motion_passes = all(
        c.passed for c, spec in zip(checks, specs) if spec.scope in scopes + ("motion",)
    )
    contact = first_contact(structure)
    end = 180.0 if contact is None else contact - CONTACT_STEP
    holds = _holds_up_to(run, max(angles), end, scopes) if motion_passes else None
    return Certificate(checks, tuple(angles), holds, samples, first_contact=contact)


def _certified_angles(
    structure: Structure, fold_angles: Sequence[float] | None, degrees: bool
) -> list[float]:
    """2α of the certified frames, degrees, ascending: 0°, the design angle and ``fold_angles``
    (validated)."""
    extra = [] if fold_angles is None else check_fold_angles(fold_angles, degrees=degrees).tolist()
    return sorted({0.0, float(structure.lattice.crease.fold_angle), *map(float, extra)})


def _runner(
    specs: Sequence[CheckSpec], vault: Vault | None, fine: Shared, coarse: Shared | None
) -> Callable[[float | None, tuple[str, ...]], dict[str, _Outcome]]:
    """``run(angle, scopes)``: the outcomes of the ``specs`` of ``scopes`` on the structure refolded
    to ``angle`` (None: as built), against the half-sampled one (``coarse``; None for order-0
    checks)."""
    design = float(fine.structure.lattice.crease.fold_angle)

    def run(angle: float | None, scopes: tuple[str, ...]) -> dict[str, _Outcome]:
        label = f"2α = {design:g}° as built: " if angle is None else f"2α = {angle:g}°: "
        chosen = [s for s in specs if s.scope in scopes]
        return _measure(
            chosen,
            Frame.at(fine, angle, vault),
            None if coarse is None else Frame.at(coarse, angle, vault),
            label,
        )

    return run


def _over_frames(
    specs: Sequence[CheckSpec],
    run: Callable[[float | None, tuple[str, ...]], dict[str, _Outcome]],
    angles: Sequence[float],
    built: tuple[str, ...],
    folded: tuple[str, ...],
    design: float,
) -> dict[str, list[_Outcome]]:
    """Every spec's outcomes: on the structure as built (the scopes ``built``), then refolded to
    each angle (``folded``, and ``"motion"`` from the ``design`` angle on)."""
    outcomes: dict[str, list[_Outcome]] = {s.name: [] for s in specs}
    for angle in (None, *angles):
        scopes = built if angle is None else folded + (("motion",) if angle >= design else ())
        for name, outcome in run(angle, scopes).items():
            outcomes[name].append(outcome)
    return outcomes


def _holds_up_to(
    run: Callable[[float, tuple[str, ...]], dict[str, _Outcome]],
    start: float,
    end: float,
    scopes: tuple[str, ...],
) -> float:
    """Largest 2α in [``start``, ``end``] (to 1.5°) where every check of ``scopes`` passes:
    ``end`` (below 180°: one step before the first contact) if they pass there, else found by
    bisection."""

    def passes(angle: float) -> bool:
        return all(o.status == "pass" for o in run(angle, scopes).values())

    if end <= start or (end < 180.0 and passes(end)):
        return round(end, 1)
    lo, hi = start, end
    while hi - lo > 1.5:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if passes(mid) else (lo, mid)
    return round(lo, 1)


def _check(spec: CheckSpec, outcomes: list[_Outcome]) -> Check:
    worst = _worst(outcomes)
    return Check(
        spec.name,
        worst.value,
        worst.tolerance,
        worst.status,
        spec.unit,
        spec.measures,
        spec.model,
        worst.where,
        len(outcomes),
        worst.samples_needed,
    )


def _too_coarse(structure: Structure | None, vault: Vault | None, samples: int) -> Certificate:
    """Every check "insufficient resolution": the half-sampled design would not hold a stencil."""
    scopes = (
        ("crease",)
        if structure is None
        else ("crease", "frame") + (("vault",) if vault is not None else ())
    )
    needed = 2 * (_MIN_COARSE - 1) + 1
    checks = tuple(
        Check(
            s.name,
            math.nan,
            math.nan,
            "insufficient resolution",
            s.unit,
            s.measures,
            s.model,
            f"{samples} samples; the check compares them with half as many",
            0,
            needed,
        )
        for s in CHECKS
        if s.scope in scopes
    )
    return Certificate(checks, samples=samples)
