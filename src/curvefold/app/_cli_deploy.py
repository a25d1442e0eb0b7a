"""``curvefold deploy``: a vault, tube or block folded from near flat to its design angle under
its own weight (:func:`curvefold.mechanics.deploy`).

It takes the design input of ``curvefold load`` (a design file, the design flags, the
material and thickness) and the deployment's own flags (``--step``, ``--start``,
``--supports``, ``--rest-angle``). It prints the peaks (or ``--json``), and with ``--out``
writes, atomically (:mod:`curvefold.app._folder`), ``deploy.csv`` (a row per fold angle) and
``deploy.png`` (the actuation and the distance from the rigid-folding path).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ._cli_flags import _add_spec_flag, _flag_specs, _flag_value
from ._design import SCHEMA

__all__ = ["add_deploy_parser", "deploy_flags", "CSV_COLUMNS"]

#: The columns of ``deploy.csv``, with their units.
CSV_COLUMNS = (
    "fold_angle_deg",
    "actuation_Nm_per_rad",
    "max_stress_MPa",
    "path_distance_mm",
    "newton_iterations",
)
#: The design keys ``deploy`` leaves out: the loads (its load is the self-weight, its supports
#: its own) and the files (it writes its own).
_SKIPPED = ("loads", "output")


def _deploy_specs():
    from ..mechanics._deploy_specs import DEPLOY_SUPPORTS, REST_ANGLE, START, STEP

    return {
        "step": STEP,
        "start": START,
        "deploy_supports": DEPLOY_SUPPORTS,
        "rest_angle": REST_ANGLE,
    }


def _skipped(kind: str) -> set[str]:
    return {key for section in _SKIPPED for key in SCHEMA[section]} & set(_flag_specs(kind))


def add_deploy_parser(sub, kind: str, add_output) -> None:
    """The ``deploy`` subcommand: the design and material flags of ``kind`` and its own."""
    p = sub.add_parser(
        "deploy",
        help="fold a vault, tube or block from flat to its design angle under its own weight",
        description="Follow the folding motion of a vault (the paper's by default), or a "
        "tube or block from its design file, from 2α = 10° (--start) to its design angle, "
        "under its own weight, with the material's crease stiffness and the creases resting "
        "at the angle they were creased at: the actuation (the moment along the fold angle, "
        "N·m/rad), the largest stress and the distance from the rigid-folding path at every "
        "angle. With --out, deploy.csv and deploy.png.",
    )
    p.add_argument(
        "design",
        nargs="?",
        type=Path,
        help="a TOML design file (see examples/); flags override its values",
    )
    group = p.add_argument_group("design and material")
    skipped = _skipped(kind)
    for name, spec in _flag_specs(kind).items():
        if name not in skipped:
            _add_spec_flag(group, name, spec, kind)
    p.set_defaults(**dict.fromkeys(skipped))
    own = p.add_argument_group("deployment")
    for name, spec in _deploy_specs().items():
        metavar = "{" + ",".join(spec.choices) + "}" if spec.choices else name.upper()
        own.add_argument(
            f"--{spec.name.replace('_', '-')}",
            dest=name,
            metavar=metavar,
            help=spec.describe().replace("%", "%%"),
        )
    add_output(p, "load")


def deploy_flags(args: argparse.Namespace) -> dict:
    """The deployment's own flags as checked keyword arguments of :func:`deploy`."""
    values = {}
    for name, spec in _deploy_specs().items():
        text = getattr(args, name)
        if text is not None:
            values[spec.name] = _flag_value(spec, text)
    return values
