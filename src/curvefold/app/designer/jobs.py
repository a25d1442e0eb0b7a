"""The designer's work as jobs for worker processes: what each route computes, in which lane,
within which bounds.

Every route that builds geometry is a job: :func:`run`, executed in a worker process
(:mod:`curvefold.app._workers`). Before a job is sent, :func:`plan` reads the request (the
design, its targets and the route's own parameters), estimates its memory as the command
line estimates a run (:func:`curvefold.app._budget.require_budget`, refused over the
budget with the estimate and what to lower) and chooses its lane:

``quick``
    the preview, the first contact, the coarse certificate and crease pattern and the
    regression domain, of a design of at most :data:`QUICK_STRIP_SAMPLES` strip samples
    without targets to solve: sub-second work that answers every change first;
``heavy``
    the rest (full certificates and crease patterns, files, the JSON payload, the design
    under load and its deployment, target fits, larger designs), on workers of lower CPU
    priority, cancelled when the client goes away.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...kernel._errors import CurvefoldError, InputError
from ...kernel._json_text import strict_json
from ...kernel._validate import Spec
from .._budget import Estimate, require_budget, require_deploy_budget
from . import api, curves, preview

__all__ = ["ROUTES", "QUICK_STRIP_SAMPLES", "COARSE", "Plan", "plan", "run"]

#: Largest design the quick lane builds, in strip samples (the paper's vault with ``tubes = "max"``,
#: counted as 24 tubes, has 801 × 96).
QUICK_STRIP_SAMPLES = 100_000
#: The certificate's and the crease pattern's switch to their coarse answer.
COARSE = Spec(
    "coarse",
    "flag",
    False,
    help="answer at reduced samples first (the page shows it until the full one comes)",
    label="coarse",
)
#: Routes that run as jobs, and the route parameters each takes besides the design's.
ROUTES = {
    "preview": (),
    "contact": (),
    "certificate": (COARSE,),
    "pattern": (COARSE,),
    "domain.svg": (),
    "payload": (),
    "mechanics": (),
    "deploy": (),
    "file": (api.STATE,),
}
#: Routes that go to the quick lane when their design is small (the coarse answers only, for the two
#: with COARSE).
_QUICK = ("preview", "contact", "domain.svg", "certificate", "pattern")


@dataclass(frozen=True)
class Plan:
    """A job ready to send: its lane, the arguments of :func:`run` and its memory estimate.

    Attributes
    ----------
    lane : {"quick", "heavy"}
    args : tuple
        ``(route, design key, targets, option, state)`` for :func:`run`.
    estimate : Estimate
        Of the command line's budget.
    """

    lane: str
    args: tuple
    estimate: Estimate


def plan(route: str, kind: str, query, *, what: str | None = None) -> Plan:
    """Read a request to ``route`` and plan its job (``what``: the file of a ``file`` route).

    Raises
    ------
    InputError
        A parameter refused, a file the kind has no writer for, or a job over the memory
        budget (the message gives the estimate and what to lower).
    """
    request, extras = api.read_request(kind, query, extra=ROUTES[route])
    design = request.design
    coarse = bool(extras.get("coarse"))
    files = None
    if route == "file":
        what = what or ""  # the route gives it: /api/KIND.FORMAT
        api.check_download(design, what)
        files = (
            design
            if what in ("zip", "toml")
            else design.overrides(source=design.source, formats=[what])
        )
    elif route == "pattern" and not coarse:
        api.check_download(design, "svg")
        files = design.overrides(source=design.source, formats=["svg"])
    # as curvefold load analyses it
    loaded = design.with_mechanics() if route in ("mechanics", "deploy") else design
    if route == "deploy":  # refused above the designer's size before the budget
        curves.check_deployment(loaded)
    try:
        estimate = require_budget(files or loaded, files=files is not None)
        if route == "deploy":
            total = require_deploy_budget(design, curves.states(design))
            estimate = Estimate(total, estimate.strip_samples, "mechanics")
    except CurvefoldError as err:
        raise InputError(str(err).removeprefix(f"{api.SOURCE}: "), parameter="samples") from None
    small = estimate.strip_samples <= QUICK_STRIP_SAMPLES and not request.targets
    quick = small and route in _QUICK and (coarse or route not in ("certificate", "pattern"))
    option = what if route == "file" else "coarse" if coarse else None
    return Plan(
        "quick" if quick else "heavy",
        (route, request.key, request.targets, option, extras.get("state")),
        estimate,
    )


def run(
    route: str, key: str, targets: tuple, option: str | None, state: float | None
) -> tuple[bytes, str, str | None]:
    """A job, in a worker: the answer's content, media type and file name (None but for files)."""
    design, _ = api.resolve(key, targets)
    if route == "preview":
        return preview.preview(api._design(key), targets), "application/json", None
    if route == "contact":
        return _json({"first_contact": preview.contact(design)}), "application/json", None
    if route == "certificate":
        return _json(api.certificate(design, coarse=option == "coarse")), "application/json", None
    if route == "pattern":
        if option == "coarse":
            return (
                _json(
                    {
                        "coarse": True,
                        "samples": min(api.COARSE_SAMPLES, design.samples),
                        "pages": [preview.pattern_sketch(design)],
                    }
                ),
                "application/json",
                None,
            )
        return (
            _json({"coarse": False, "samples": design.samples, "pages": api.pattern_pages(design)}),
            "application/json",
            None,
        )
    if route == "domain.svg":
        return api.domain_svg(design).encode(), "image/svg+xml", None
    if route == "payload":
        return api.payload(design), "application/json", None
    if route == "mechanics":
        return _json(api.mechanics(design)), "application/json", None
    if route == "deploy":
        return _json(curves.deployment(design)), "application/json", None
    name, media, content = api.download(design, option or "", state=state)
    return content, media, name


def _json(value) -> bytes:
    """Strict JSON: a number that is not finite is a bug (500), never a ``NaN`` the page cannot
    parse."""
    return strict_json(value).encode()
