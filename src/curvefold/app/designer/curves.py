"""The designer's two curves of large-displacement mechanics, as numbers the page draws itself:
the collapse path of ``load --nonlinear`` and the deployment of ``curvefold deploy``.

:func:`collapse_curve` reads the load–displacement curve off a collapse already computed
with the design under load (its load factor against the control displacement, in mm, the
columns of ``collapse.csv``). :func:`deployment` folds the design from 2α = 10° to its
design angle under its own weight at :data:`STEP` (:func:`curvefold.mechanics.deploy`,
with the material's crease stiffness, both feet carried along), a heavy job of its own.

The designer deploys designs of at most :data:`LARGEST_DEPLOYMENT` model nodes (the samples
the model keeps along a curve, times the strips) and refuses larger ones before any work,
with the command line to use instead. Measured (one process, aluminium 1 mm, 10° steps, 9
states, on two CPUs shared with other work): vaults of 41 samples × 2 tubes (328 nodes) in
1.7 CPU-s, 101 × 2 (808) in 3.2, 201 × 2 (1,608) in 5.5 CPU-s (0.17 GB), 101 × 4 (1,616) in
46 CPU-s (0.24 GB) and 201 × 4 (3,216) in 83 to 99 CPU-s (0.30 GB): more tubes take more
Newton iterations near flat, and the last is too near the designer's time limit of 120 s.
"""

from __future__ import annotations

import json
import math
from functools import lru_cache

import numpy as np

from ...kernel._errors import InputError
from .._design import Design

__all__ = ["STEP", "LARGEST_DEPLOYMENT", "collapse_curve", "check_deployment", "deployment"]

#: Degrees of 2α between the states of a deployment in the designer (coarse: the command
#: line's default is 1°).
STEP = 10.0
#: Largest deployment the designer runs, in model nodes (samples kept along a curve times
#: strips): a vault of 101 samples and 4 tubes has 1,616 and took 46 CPU-s (module notes).
LARGEST_DEPLOYMENT = 1_700


def collapse_curve(collapse) -> dict:
    """The load–displacement curve of a :class:`curvefold.mechanics.Collapse`: ``load_factor``
    (λ on the combination), ``control_displacement_mm`` (the control DOF's displacement,
    signed along its axis), ``stable`` (one per state), the ``control`` DOF, the
    ``linear_factor``, the collapse ``factor`` and ``at_collapse``, the state at collapse.

    Examples
    --------
    >>> from curvefold.mechanics._collapse import _strut
    >>> c = collapse_curve(_strut(1e-3))
    >>> c["load_factor"][0], c["control_displacement_mm"][0], c["control"], c["linear_factor"]
    (0.0, 0.0, {'node': 1, 'axis': 'x'}, 100.0)
    """
    path = collapse.path
    node, axis = divmod(path.control, 3)
    return {
        "load_factor": [float(v) for v in path.factors],
        "control_displacement_mm": [float(1e3 * v) for v in path.control_displacement],
        "stable": [bool(s) for s in path.stable],
        "control": {"node": int(node), "axis": "xyz"[axis]},
        "linear_factor": float(collapse.linear_factor),
        "factor": float(collapse.factor),
        "at_collapse": int(collapse.at_collapse),
    }


def _size(design: Design) -> tuple[int, int, int]:
    """The model's nodes of a deployment: (nodes, samples kept along a curve, strips)."""
    from ...mechanics import model_samples
    from .._budget import _strips

    panels = design.design_kind.panels(design)
    kept = panels + 1 if panels else len(model_samples(design.samples))
    strips = _strips(design)
    return kept * strips, kept, strips


def states(design: Design) -> int:
    """The fold angles a deployment of the design passes through at :data:`STEP`, from 10°."""
    from ...mechanics._deploy_specs import START

    angle = float(getattr(getattr(design, design.kind, None), "fold_angle", 90.0) or 90.0)
    return max(1, math.ceil((angle - START.default) / STEP - 1e-9) + 1)


def check_deployment(design: Design) -> None:
    """Refuse, before any work, a design the designer does not deploy: a single crease, or a
    model larger than :data:`LARGEST_DEPLOYMENT` nodes (one line, about ``samples``).

    Examples
    --------
    >>> from curvefold.app.designer import api
    >>> check_deployment(api.request_design("vault", {"samples": "41", "tubes": "2"}))
    >>> check_deployment(api.request_design("vault", {}))
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: the designer deploys models of at most 1700 nodes (samples kept along a curve × strips), got 25056 (261 × 96): lower samples, tubes or panels, or run curvefold deploy
    """  # noqa: E501
    if not design.design_kind.loaded:
        raise InputError(
            f"a {design.kind} has no end sections to hold: deploy a tube, block or vault"
        )
    nodes, kept, strips = _size(design)
    if nodes > LARGEST_DEPLOYMENT:
        raise InputError(
            f"the designer deploys models of at most {LARGEST_DEPLOYMENT} nodes "
            f"(samples kept along a curve × strips), got {nodes} ({kept} × "
            f"{strips}): lower samples, tubes or panels, or run curvefold deploy",
            parameter="samples",
        )


def deployment(design: Design) -> dict:
    """The design folded from 10° to its design angle at :data:`STEP` under its own weight.

    Returns
    -------
    dict
        ``angles_deg``, ``actuation_Nm_per_rad``, ``max_stress_MPa``, ``distance_mm`` (one per
        state reached), ``summary`` (:meth:`Deployment.summary
        <curvefold.mechanics.Deployment.summary>`), ``material``, ``thickness`` (m), ``step``
        (degrees) and ``error``: why it stopped before the design angle, or None.
    """
    return _deployment(json.dumps(design.with_mechanics().to_dict(), sort_keys=True))


@lru_cache(maxsize=2)
def _deployment(key: str) -> dict:
    from .._build import build
    from .._deployment import deploy_design
    from .._design import design_from_dict

    design = design_from_dict(json.loads(key), source="query")
    check_deployment(design)
    params = design.material
    assert params is not None  # with_mechanics gave it its defaults
    structure = getattr(build(design), "structure", None)
    if structure is None:
        raise InputError(f"a {design.kind} design has no end sections to hold")
    found, failure, material = deploy_design(structure, params, step=STEP)
    return {
        "angles_deg": _floats(found.angles),
        "actuation_Nm_per_rad": _floats(found.actuation),
        "max_stress_MPa": _floats(found.max_stress / 1e6),
        "distance_mm": _floats(found.distance * 1e3),
        "summary": found.summary(),
        "material": material.name,
        "thickness": float(params.thickness),
        "step": STEP,
        "error": failure,
    }


def _floats(values: np.ndarray) -> list[float]:
    return [float(v) for v in values]
