"""The ``curvefold`` parser: a command per registered kind of design, ``load``, ``arch``,
``atlas``, ``reproduce``, ``designer``, ``check`` and ``mechanism``.

A kind's command and ``load`` take the flags generated from the design schema
(:mod:`curvefold.app._cli_flags`); ``atlas``, ``check`` and ``mechanism`` add theirs only when
parsed, so that the modules their specs come from are imported only for them.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ._cli_flags import (
    _GRID_COUNT,
    PROG,
    _add_design_flags,
    _add_spec_flag,
    _add_target_flags,
    _flag,
    _load_specs,
    _Parser,
    _Version,
)
from ._design import SCHEMA
from ._kinds import design_kind, design_kinds
from .designer import SERVER_SPECS

#: The kind of design ``load`` analyses unless its design file says another: the paper's vault.
LOAD_KIND = "vault"
_DEBUG_HELP = "on an internal error, print the traceback and the warnings"
_FORCE_HELP = "replace the output folder if curvefold wrote it (or it is empty)"
_VAULT = SCHEMA["vault"]
#: Port of ``curvefold designer`` unless told.
DESIGNER_PORT = 8765


def _add_output(p: argparse.ArgumentParser, kind: str | None) -> None:
    g = p.add_argument_group("output")
    if kind is not None:
        default = "none: nothing is written"
        if kind != "load":
            folder = design_kind(kind).default_out
            default = f"./{folder}; with --json and no --out nothing is written"
        g.add_argument(
            "--out", metavar="DIR", type=Path, help=f"folder to write (default: {default})"
        )
        g.add_argument("--force", action="store_true", help=_FORCE_HELP)
    g.add_argument(
        "--json", action="store_true", help="print one JSON object on stdout instead of the summary"
    )
    p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=_DEBUG_HELP)


def build_parser() -> argparse.ArgumentParser:
    """The command line's parser: every command, its flags generated from the design schema."""
    parser = _Parser(
        prog=PROG,
        description="Rigid-foldable, flat-foldable curved-crease tubes and deployable vaults "
        "from a space curve: geometry, folding motion, crease patterns and a measured "
        "certificate.",
        epilog="Run 'curvefold vault' with no arguments to build the paper's example vault into "
        "./curvefold-vault.",
    )
    parser.add_argument("--version", action=_Version, help="show the version and exit")
    parser.add_argument("--debug", action="store_true", help=_DEBUG_HELP)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    for kind in design_kinds():
        p = sub.add_parser(kind.name, help=kind.help, description=kind.description)
        _add_design_flags(p, kind.name)
        _add_target_flags(p, kind)
        _add_output(p, kind.name)

    p = sub.add_parser(
        "load",
        help="will it stand? a vault, tube or block under load",
        description="Analyse a vault (the paper's by default), or a tube or block "
        "from its design file, under load: its weight, the support "
        "reactions, the largest deflection and stress (against the "
        "material's strength), the linear buckling factor, the free modes "
        "and the fold-mode gap, the soft modes. A vault stands on its feet "
        "(the end sections on the ground); a tube or block is held at both "
        "end sections, t = 0 and t = 1. Default: polypropylene 1 mm under "
        "its own weight, pinned. With --out, the output folder of the "
        "design with its mechanics in the report, report.json and the GLB.",
    )
    _add_design_flags(p, LOAD_KIND)
    _add_target_flags(p, design_kind(LOAD_KIND))
    _add_output(p, "load")
    from ._cli_deploy import add_deploy_parser

    add_deploy_parser(sub, LOAD_KIND, _add_output)

    p = sub.add_parser(
        "arch",
        help="solve the arch equation (Eq. 20) for κ0·s0",
        description="Solve T(s0/2)·T(0) = 0 for the arch κ = κ0, τ = a κ0 sin(2π s/s0).",
    )
    p.add_argument("--a", metavar="A", help=_VAULT["a"].describe().replace("%", "%%"))
    p.add_argument(
        "--p-xy",
        metavar="P_XY",
        help=f"{_VAULT['p_xy'].help}, {_VAULT['p_xy'].requirement}: reports p_xz",
    )
    p.add_argument("--fold-angle", metavar="FOLD_ANGLE", help=_VAULT["fold_angle"].describe())
    _add_output(p, None)

    sub.add_parser(
        "atlas",
        help="a grid of vault designs (the paper's Fig. 10)",
        description="Build vaults over "
        "a grid of p_xy and a; write a figure of their forms with the section slopes and a "
        "CSV/JSON of their metrics. Invalid designs are recorded with their reason. With "
        "--load, every vault is analysed under load on a coarse model (--load-samples, "
        "--across): its buckling factor, governing check and utilisation, deflection, mass "
        "and whether it stands; the figure marks the vaults that stand and the lightest.",
        flags=_add_atlas_flags,
    )

    p = sub.add_parser(
        "reproduce",
        help="the paper's example, paper vs computed",
        description="Reproduce the "
        "paper's vault example (a = 0.3, p_xy = 0.75, 2α = 90°) and compare with the printed "
        "values.",
    )
    _add_output(p, None)

    p = sub.add_parser(
        "designer",
        help="design live in the browser",
        description="Serve the "
        "designer, a local web page with a control for every design parameter, the 3D folding "
        "motion, the derived numbers, the certificate, the crease pattern and every file to "
        "download, and open it in the browser. Its JSON API (/api/vault?a=…) answers scripts "
        "too.",
    )
    p.add_argument(
        "design",
        nargs="?",
        type=Path,
        help="a TOML design file to start from (default: the paper's vault)",
    )
    p.add_argument(
        "--port",
        type=int,
        default=DESIGNER_PORT,
        help=f"port to serve on (default {DESIGNER_PORT}; 0 picks a free one)",
    )
    p.add_argument(
        "--host",
        default="127.0.0.1",
        help="address to serve on (default 127.0.0.1: this machine only)",
    )
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    for spec in SERVER_SPECS:
        p.add_argument(
            _flag(spec), metavar="N" if spec.kind == "integer" else "SECONDS", help=spec.describe()
        )
    p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=_DEBUG_HELP)

    p = sub.add_parser(
        "check",
        help="check a FOLD file",
        description="Check a FOLD file "
        "(curvefold's or another tool's) in every frame: topology, welds (seams and bonds), "
        "edge kinds against assignments, M/V/F assignments against the recorded and measured "
        "dihedral angles, the recorded fold angles, isometry to the crease pattern and face "
        "planarity; what the file does not hold (a crease pattern, curvefold's keys) is not "
        "run, with the reason. With --rebuild, every array against the design it records.",
        flags=_add_check_flags,
    )

    p = sub.add_parser(
        "mechanism",
        help="degrees of freedom of a FOLD file of rigid panels",
        description="Build the constraint Jacobian of every folded frame of a "
        "FOLD file (edge lengths, the diagonals and the planarity of every "
        "polygon, join edges flat, vertices welded where the frames agree: "
        "seams and bonds) and report its singular values and internal "
        "degrees of freedom (nullity - 6) with the gap between null and "
        "nonzero ones. The lengths are the crease pattern's, or the folded "
        "form's own when the file holds none. Write such a file with "
        "'curvefold tube|block|vault --panels N'.",
        flags=_add_mechanism_flags,
    )
    return parser


def _add_atlas_flags(p: argparse.ArgumentParser) -> None:
    from ..mechanics._atlas_load import LOAD_SAMPLES
    from ..vault._atlas import GRID_A
    from ..vault._cluster import LOCAL_CLUSTER_FROM, workers_spec

    grid = f"start:stop:count or a comma-separated list, count {_GRID_COUNT.range}"
    p.add_argument(
        "--p-xy",
        metavar="GRID",
        default="0.5:1.5:5",
        help=f"values of p_xy {_VAULT['p_xy'].requirement}: {grid} (default 0.5:1.5:5)",
    )
    p.add_argument(
        "--a",
        metavar="GRID",
        default="0:1.2:5",
        help=f"values of a {GRID_A.requirement}: {grid} (default 0:1.2:5)".replace("%", "%%"),
    )
    p.add_argument("--width", metavar="WIDTH", help=_VAULT["width"].describe())
    most = SCHEMA[""]["samples"].range
    text = f"samples per crease, in [21, {most.hi if most else float('inf'):g}] (default 201)"
    p.add_argument("--samples", metavar="N", help=text)
    p.add_argument(
        "--workers",
        metavar="N",
        help="processes of a local Dask cluster, "
        f"{workers_spec().requirement}; 1 runs in this process (default: up to 2 for grids of "
        f"{LOCAL_CLUSTER_FROM} designs or more when Dask is installed, else 1)",
    )
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run on the existing Dask cluster of "
        "this scheduler, e.g. tcp://10.0.0.5:8786 (its workers need this curvefold version)",
    )
    g = p.add_argument_group(
        "under load",
        "with --load, every vault is analysed as curvefold load analyses it (same flags, same "
        "defaults: polypropylene 1 mm under its own weight, pinned), on a model of "
        "--load-samples samples",
    )
    g.add_argument(
        "--load",
        action="store_true",
        help="analyse every vault under load: the mechanics columns and the marks of the "
        "vaults that stand",
    )
    g.add_argument(
        _flag(LOAD_SAMPLES),
        metavar="N",
        help=LOAD_SAMPLES.describe().replace("%", "%%"),
    )
    for name, spec in _load_specs(LOAD_KIND).items():
        _add_spec_flag(g, name, spec, LOAD_KIND)
    p.add_argument(
        "--out",
        metavar="DIR",
        type=Path,
        default=Path("curvefold-atlas"),
        help="folder to write (default ./curvefold-atlas)",
    )
    p.add_argument("--force", action="store_true", help=_FORCE_HELP)
    p.add_argument(
        "--json",
        action="store_true",
        help="print a summary as JSON (the records are in atlas.json)",
    )


def _add_check_flags(p: argparse.ArgumentParser) -> None:
    from ..analysis._foldcheck import CHECK_SPECS

    p.add_argument("file", type=Path, help="a .fold file: a crease pattern, folded frames or both")
    for spec in CHECK_SPECS:
        p.add_argument(
            _flag(spec),
            dest=spec.name,
            metavar=spec.name.upper(),
            help=spec.describe().replace("%", "%%"),
        )
    p.add_argument(
        "--rebuild",
        action="store_true",
        help="build the design the file records "
        "(curvefold:design) again, within the memory budget, and compare every array of every "
        "frame",
    )
    _add_output(p, None)


def _add_mechanism_flags(p: argparse.ArgumentParser) -> None:
    from ..analysis._mechanism import RTOL

    p.add_argument(
        "file", type=Path, help="a .fold file with folded frames (and a crease pattern, or not)"
    )
    p.add_argument(
        "--rtol",
        type=float,
        default=RTOL,
        help=f"rank tolerance relative to the largest singular value (default {RTOL:g})",
    )
    _add_output(p, None)
