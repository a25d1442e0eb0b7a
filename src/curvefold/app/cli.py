"""The ``curvefold`` command line.

Every subcommand prints a short human summary, or with ``--json`` one strict JSON object
on stdout (no NaN or infinity: a non-finite result is an error). Exit statuses: 0 done;
1 a certificate check failed, or a bug (one line asking for a report with the version,
the traceback only with ``--debug``); 2 a user error (one line on stderr: what is wrong,
the allowed range, the value given), including a job over the memory budget
(:mod:`curvefold.app._budget`); 128 + n when stopped by signal n (SIGINT, SIGTERM, SIGHUP),
after removing what the run had started to write. Warnings are shown only with
``--debug``; text a user typed is printed with its control characters escaped. The output
folder is checked before any work and replaced only as :mod:`curvefold.app._folder` says.

A subcommand per registered kind of design (:mod:`curvefold.app._kinds`), its help the kind's.
The flags of those and of ``load``, their help and their checks are generated from the design
schema (:data:`curvefold.app._design.SCHEMA`): one flag per key, ``--fold-angle`` for
``fold_angle``, ``--no-glue-tabs`` for a key that is true by default. A flag's value is
checked by the key's spec and named as typed (``--page A9: page must be one of …``); a design
made of a file and flags is named by both (``design.toml --samples 10: …``).
"""

from __future__ import annotations

import argparse
import re
import signal
import sys
import traceback
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path

from ..kernel._threads import blas_loads_on_one_thread

# NumPy is loaded here; a command runs its BLAS on one thread (_run), so OpenBLAS starts none
with blas_loads_on_one_thread():
    import numpy as np

    from ..io._formats import FORMATS, check_kind, default_formats
    from ..kernel._errors import CurvefoldError, InputError
    from ..kernel._text import for_terminal
    from ..kernel._validate import Spec, from_text
    from ..vault._assembly import vault_samples
    from ._design import (
        OPTIONAL_SECTIONS,
        SCHEMA,
        Design,
        design_from_dict,
        kind_specs,
        load_design,
    )
    from ._folder import Interrupted, raise_if_interrupted, signals_interrupt
    from ._kinds import DesignKind, design_kind, design_kinds
    from .designer import SERVER_SPECS

__all__ = ["main"]

PROG = "curvefold"
#: The kind of design ``load`` analyses unless its design file says another: the paper's vault.
LOAD_KIND = "vault"
_DEBUG_HELP = "on an internal error, print the traceback and the warnings"
_FORCE_HELP = "replace the output folder if curvefold wrote it (or it is empty)"
_VAULT = SCHEMA["vault"]
#: Port of ``curvefold designer`` unless told.
DESIGNER_PORT = 8765


# -- argument helpers -------------------------------------------------------------------------


#: Values along one axis of the atlas grid.
_GRID_COUNT = Spec("count", "integer", 5, "[1, 200]")


def _grid(flag: str, text: str, spec: Spec) -> np.ndarray:
    """``start:stop:count`` or a comma-separated list of numbers, each checked by ``spec``."""
    where = f"{flag} {text}: {spec.name}"
    parts = text.split(":")
    if len(parts) == 3:
        count = _GRID_COUNT.check(_from_text(_GRID_COUNT, parts[2], flag), f"{flag} {text}: count")
        start, stop = (
            spec.check(_from_text(spec, part, flag), where, shown=part) for part in parts[:2]
        )
        return np.linspace(start, stop, count)
    if len(parts) != 1:
        raise InputError(
            f"{flag}: expected start:stop:count or a comma-separated list of numbers, got {text!r}"
        )
    values = text.split(",")
    _GRID_COUNT.check(len(values), f"{flag} {text}: count")
    return np.array(
        [spec.check(_from_text(spec, part, flag), where, shown=part) for part in values]
    )


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line with exit status 2, and which
    reads ``--a -1e-3`` as a value (any number, not only ``-1`` or ``-.5``).

    A command's ``flags(parser)``, if given, adds its arguments when the command is parsed
    or its help shown: the modules their specs come from are imported only for that command.
    """

    def __init__(
        self, *args, flags: Callable[[argparse.ArgumentParser], None] | None = None, **kwargs
    ) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
        )
        self._flags = flags

    def _add_flags(self) -> None:
        if self._flags is not None:
            flags, self._flags = self._flags, None
            flags(self)

    def parse_known_args(self, args=None, namespace=None):
        self._add_flags()
        return super().parse_known_args(args, namespace)

    def format_help(self) -> str:
        self._add_flags()
        return super().format_help()

    def error(self, message: str) -> None:  # type: ignore[override]
        raise InputError(f"{self.prog}: {message}")


class _Version(argparse.Action):
    """``--version``: the installed version, read only when asked (the metadata reader is slow to
    import)."""

    def __init__(self, option_strings: Sequence[str], dest: str, **kwargs) -> None:
        super().__init__(
            option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, nargs=0, **kwargs
        )

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        from ..kernel._version import VERSION

        print(f"{parser.prog} {VERSION}")
        parser.exit()


# -- flags generated from the design schema --------------------------------------------------

#: Schema keys with no flag (a list of cells is written in a design file).
_NO_FLAG = ("cells",)


def _flag(spec: Spec) -> str:
    """``--fold-angle`` for ``fold_angle``; ``--no-glue-tabs`` for a key true by default."""
    dashed = spec.name.replace("_", "-")
    return f"--no-{dashed}" if spec.kind == "flag" and spec.default else f"--{dashed}"


def _from_text(spec: Spec, text: str, flag: str | None = None):
    """A flag's text as the value a design file would hold (checked by the spec afterwards);
    a number that does not read as one is refused here, naming the flag."""
    value = from_text(spec, text)
    types = {"real": (int, float), "integer": (int,), "count": (int,)}.get(spec.kind)
    unset = "max" if spec.kind == "count" else None  # a count's other value
    if types and not isinstance(value, types) and value != unset:
        least = "" if spec.range is None else f" ≥ {spec.range.lo:g}"
        form = {
            "real": f"a number ({spec.unit})" if spec.unit else "a number",
            "integer": "a whole number",
            "count": f"a whole number{least} or 'max'",
        }[spec.kind]
        raise InputError(f"{flag or _flag(spec)}: must be {form}, got {text!r}")
    return value


def _flag_value(spec: Spec, text: str):
    """A flag's text as a checked value; a function is checked later, on the design's sample
    grid."""
    value = _from_text(spec, text)
    return (
        value
        if spec.kind == "function"
        else spec.check(value, f"{_flag(spec)} {text}: {spec.name}", shown=text)
    )


def _flag_specs(kind: str) -> dict[str, Spec]:
    """The spec of every design flag of a kind, by argparse destination."""
    return {name: spec for name, spec in kind_specs(kind).items() if name not in _NO_FLAG}


def _formats_help(kind: str) -> str:
    names = default_formats(design_kind(kind).formats_kind)
    if not names:
        return (
            f"no file formats are written for a {kind} design (the report and its pictures "
            "always are)"
        )
    listed = "; ".join(f"{n}: {FORMATS[n].holds}" for n in names)
    return (
        "comma-separated formats to write besides the report and its pictures (default: all): "
        f"{listed}"
    )


def _add_design_flags(p: argparse.ArgumentParser, kind: str) -> None:
    """The design file argument and one flag per schema key of the kind, help from the spec."""
    p.add_argument(
        "design",
        nargs="?",
        type=Path,
        help="a TOML design file (see examples/); flags override its values",
    )
    groups = {"design": p.add_argument_group("design"), "output": p.add_argument_group("output")}
    if OPTIONAL_SECTIONS[kind]:
        groups["load"] = p.add_argument_group(
            "under load",
            "what the structure is made of and "
            "what loads it: with any of these its output folder holds its mechanics (curvefold "
            "load always analyses it)",
        )
    section = {
        spec.name: name
        for name in ("output", *OPTIONAL_SECTIONS[kind])
        for spec in SCHEMA[name].values()
    }
    for name, spec in _flag_specs(kind).items():
        group = groups[{"output": "output", None: "design"}.get(section.get(name), "load")]
        if spec.kind == "flag":
            text = (
                f"{'do not ' if spec.default else ''}{spec.help} (sets {name} = "
                f"{str(not spec.default).lower()})"
            )
            group.add_argument(
                _flag(spec),
                dest=name,
                action="store_const",
                const=not spec.default,
                default=None,
                help=text,
            )
        else:
            text = (_formats_help(kind) if spec.kind == "formats" else spec.describe()).replace(
                "%", "%%"
            )
            metavar = {
                "formats": "LIST",
                "page": "PAGE",
                "count": "N|max",
                "choice": "{" + ",".join(spec.choices) + "}",
            }
            group.add_argument(
                _flag(spec), dest=name, metavar=metavar.get(spec.kind, name.upper()), help=text
            )


def _design_flags(kind: str, args: argparse.Namespace) -> tuple[dict, list[str]]:
    """The given design flags as checked values, and the words the user typed for them.

    Raises
    ------
    InputError
        A flag's value, named as typed: ``--page A9: page must be one of …, got A9``.
    """
    values, typed = {}, []
    for name, spec in _flag_specs(kind).items():
        text = getattr(args, name)
        if text is None:
            continue
        if spec.kind == "flag":
            values[name] = text
            typed.append(_flag(spec))
        else:
            values[name] = _flag_value(spec, text)
            typed.append(f"{_flag(spec)} {text}")
    return values, typed


def _add_target_flags(p: argparse.ArgumentParser, kind: DesignKind) -> None:
    """A kind's targets as flags (a vault's --span, --rise, --p-xz), help and checks from specs."""
    if kind.targets is None:
        return
    g = p.add_argument_group("targets", kind.targets.help)
    for spec in kind.targets.specs():
        g.add_argument(
            _flag(spec),
            dest=spec.name,
            metavar=spec.name.upper(),
            help=spec.describe().replace("%", "%%"),
        )


def _fit_targets(design: Design, args: argparse.Namespace) -> Design:
    """The design with the parameters its kind's target flags replace solved for them."""
    fit = design.design_kind.targets
    specs = {} if fit is None else {spec.name: spec for spec in fit.specs()}
    given = {name: text for name in specs if (text := getattr(args, name, None)) is not None}
    if fit is None or not given:
        return design
    targets = {name: _flag_value(specs[name], text) for name, text in given.items()}
    flags = kind_specs(design.kind)
    for target, replaced in fit.replaces().items():
        if target in targets and getattr(args, replaced, None) is not None:
            raise InputError(
                f"{_flag(specs[target])} sets {replaced}: give {_flag(specs[target])} "
                f"or {_flag(flags[replaced])}, not both"
            )
    return fit.fit(design, source=design.source, **targets)[0]


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
        "CSV/JSON of their metrics. Invalid designs are recorded with their reason.",
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


# -- commands ---------------------------------------------------------------------------------


def _load_design(
    kind: str, args: argparse.Namespace, *, kinds: Sequence[str] | None = None
) -> Design:
    """The design file (or the kind's defaults) with the flags over it, named as the user typed it.

    The file's kind must be ``kind``, or one of ``kinds`` when given (the flags are then
    ``kind``'s, which the design's kind may refuse by name).
    """
    if args.design is not None:
        design = load_design(args.design)
        if design.kind not in (kinds or (kind,)):
            command = args.command
            raise InputError(
                f"{args.design}: kind = {design.kind!r} but the command is {command!r}"
                + (
                    f", which takes {', '.join(kinds)}"
                    if kinds
                    else f"; use 'curvefold {design.kind} {args.design}'"
                )
            )
    else:
        design = design_from_dict({"kind": kind}, source=f"{PROG} {args.command}")
    flags, typed = _design_flags(kind, args)
    return design.overrides(source=" ".join([design.source, *typed]), **flags) if flags else design


def _emit(args: argparse.Namespace, payload: dict, lines: Sequence[str]) -> None:
    """Print the result: strict JSON with ``--json``, else the lines (control characters
    escaped). A non-finite number in the result is an error either way
    (:func:`curvefold.kernel._json_text.strict_json`)."""
    from ..kernel._json_text import strict_json

    text = strict_json(payload, indent=2)
    print(text if args.json else "\n".join(map(for_terminal, lines)))


def cmd_structure(kind: str, args: argparse.Namespace) -> int:
    from ._budget import require_budget
    from ._build import build
    from ._folder import check_output
    from ._outputs import structure_payload, write_outputs

    design = _fit_targets(_load_design(kind, args), args)
    out = args.out or (None if args.json else Path(design.design_kind.default_out))
    target = None
    if out is not None:
        formats_kind = design.design_kind.formats_kind
        check_kind(design.output.formats, formats_kind, f"{design.source}: [output] formats")
        target = check_output(
            out,
            force=args.force,
            inputs=([] if args.design is None else [args.design]) + list(design.tables()),
        )
    require_budget(design, files=out is not None)
    built = build(design)
    if target is None:
        payload = structure_payload(built)
    else:
        payload = write_outputs(built, target, show_progress=not args.json) | {"out": str(out)}
    lines = [payload["title"]]
    for key in ("kappa0_s0", "proportion_change", "p_xz", "tubes", "max_tubes", "span", "rise"):
        if key in payload:
            lines.append(
                f"  {key:<18} {payload[key]:.10g}"
                if isinstance(payload[key], float)
                else f"  {key:<18} {payload[key]}"
            )
    lines += _certificate_lines(payload)
    if out is not None:
        lines.append(f"  wrote {len(payload['files'])} files to {out}/ (open {out}/report.html)")
        lines += [f"  {note}" for note in payload.get("notes", [])]
    _emit(args, payload, lines)
    return 1 if _certificate_failed(payload) else 0


def cmd_load(args: argparse.Namespace) -> int:
    from ._budget import require_budget
    from ._build import build
    from ._folder import check_output
    from ._outputs import default_title, write_outputs

    design = _load_design(LOAD_KIND, args, kinds=[k.name for k in design_kinds() if k.loaded])
    design = _fit_targets(design, args)
    design = design.with_mechanics()
    target = None
    if args.out is not None:
        formats_kind = design.design_kind.formats_kind
        check_kind(design.output.formats, formats_kind, f"{design.source}: [output] formats")
        target = check_output(
            args.out,
            force=args.force,
            inputs=([] if args.design is None else [args.design]) + list(design.tables()),
        )
    require_budget(design, files=target is not None)
    built = build(design)
    loaded = built.mechanics
    if loaded is None:  # with_mechanics gave it material and loads
        raise InputError(f"{design.source}: a {design.kind} design is not analysed under load")
    head = {
        "kind": design.kind,
        "title": design.title or default_title(built),
        "design": design.to_dict(),
    }
    lines = [f"{head['title']}", *loaded.lines()]
    if target is None:
        payload = head | loaded.to_dict()
        failed = False
    else:
        written = write_outputs(built, target, show_progress=not args.json)
        payload = (
            head
            | written.pop("mechanics")
            | {
                "certificate": written["certificate"],
                "files": written["files"],
                "out": str(args.out),
            }
        )
        lines += _certificate_lines(written) + [
            f"  wrote {len(written['files'])} files to {args.out}/ (open {args.out}/report.html)"
        ]
        failed = _certificate_failed(written)
    _emit(args, payload, lines)
    return 1 if failed else 0


def _certificate_lines(payload: dict) -> list[str]:
    """The certificate in a few lines: passes, failures, and the samples that would resolve the
    rest."""
    cert = payload["certificate"]
    lines = [f"  certificate        {sum(c['passed'] for c in cert)}/{len(cert)} checks pass"]
    frames = payload.get("certificate_frames", {})
    if frames.get("holds_up_to") is not None:
        at = " (rigid panels)" if "mechanism" in payload else f" at {frames['samples']} samples"
        lines[0] += f" in every frame, and up to 2α = {frames['holds_up_to']:g}°{at}"
    if frames.get("first_contact") is not None:
        lines.append(
            f"  motion             flat to 2α = {frames['first_contact']:g}°, where it "
            "first touches itself (first contact)"
        )
    lines += [
        f"    {c['name']}: {c['status']} at {c['where']}"
        + (f"; use ≥ {c['samples_needed']} samples" if c["samples_needed"] else "")
        for c in cert
        if not c["passed"]
    ]
    shipped = payload.get("certificate_file")
    if shipped is not None:  # the file column: the FOLD file as written, read back
        ran = [c for c in shipped["checks"] if c["status"] != "not run"]
        lines.append(
            f"  shipped file       {sum(c['status'] == 'pass' for c in ran)}/{len(ran)} checks "
            f"pass on {shipped['file']} as written (the file column; the line above: the model)"
        )
        lines += [f"    {c['name']}: fail at {c['where']}" for c in ran if c["status"] == "fail"]
    return lines


def _certificate_failed(payload: dict) -> bool:
    """Whether a check of the certificate failed, in the model's column or the file's."""
    shipped = payload.get("certificate_file")
    return any(c["status"] == "fail" for c in payload["certificate"]) or (
        shipped is not None and not shipped["ok"]
    )


def cmd_arch(args: argparse.Namespace) -> int:
    from ..vault._arch import proportion_change, solve_symmetric_arch

    a = _VAULT["a"].default if args.a is None else _flag_value(_VAULT["a"], args.a)
    fold_angle = (
        _VAULT["fold_angle"].default
        if args.fold_angle is None
        else _flag_value(_VAULT["fold_angle"], args.fold_angle)
    )
    root = solve_symmetric_arch(a)
    change = proportion_change(a, root.kappa0_s0, fold_angle=fold_angle)
    payload = {
        "a": a,
        "fold_angle": fold_angle,
        "kappa0_s0": root.kappa0_s0,
        "residual": root.residual,
        "proportion_change": change,
    }
    lines = [
        f"arch a = {a:g}: κ0·s0 = {root.kappa0_s0:.12f} (|T(s0/2)·T(0)| = "
        f"{root.residual:.1e}), proportion change {change:.6f}"
    ]
    if args.p_xy is not None:
        p_xy = _flag_value(_VAULT["p_xy"], args.p_xy)
        payload["p_xy"] = p_xy
        payload["p_xz"] = p_xy * change**2
        lines.append(f"p_xy = {p_xy:g} → p_xz = {payload['p_xz']:.6f}")
    _emit(args, payload, lines)
    return 0


def cmd_reproduce(args: argparse.Namespace) -> int:
    from ..vault._paper import paper_comparison

    rows = paper_comparison()
    payload = {"rows": rows}
    lines = [f"{'quantity':<20}{'paper':>10}{'computed':>18}   note"]
    for r in rows:
        lines.append(f"{r['quantity']:<20}{r['paper']:>10}{r['computed']:>18.12g}   {r['note']}")
    _emit(args, payload, lines)
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    from ..analysis._foldcheck import CHECK_SPECS, check_fold
    from ..io._fold_reading import read_fold

    tolerances = {
        spec.name: _flag_value(spec, text)
        for spec in CHECK_SPECS
        if (text := getattr(args, spec.name)) is not None
    }
    doc = read_fold(args.file)
    frames = len(doc.classes) - 1  # file_frames, which the record's fold angles describe
    recorded = doc.design.get("fold_angles") if isinstance(doc.design, dict) else None
    mismatch = args.rebuild and isinstance(recorded, list) and len(recorded) != frames
    where = (
        f"curvefold:design records {len(recorded or [])} fold angles, the file holds "
        f"{frames} frames after the key frame: the record is not the file's (not rebuilt)"
    )
    try:
        reference = _rebuilt_fold(doc, args.file) if args.rebuild and not mismatch else None
    except _NotTheRecord as exc:  # built, but not into this file's arrays
        reference, mismatch, where = None, True, str(exc)
    result = check_fold(doc, reference=reference, **tolerances)
    if mismatch:  # not built: it cannot be the file's record
        from dataclasses import replace

        from ..analysis._foldcheck import FileCheck

        unbuilt = FileCheck("rebuild", "fail", where=where)
        result = replace(result, checks=result.checks + (unbuilt,))
    ran = [c for c in result.checks if c.status != "not run"]
    failed = [c for c in ran if c.status == "fail"]
    lines = [
        f"{args.file}: {'OK' if result.ok else 'FAILED'} ({result.frames} folded "
        f"frame{'s' * (result.frames != 1)}; {len(ran) - len(failed)}/{len(ran)} checks pass"
        + (f", {len(result.checks) - len(ran)} not run)" if len(ran) < len(result.checks) else ")")
    ]
    lines += [f"  note: {note}" for note in result.notes]
    for c in result.checks:
        if c.status == "not run":
            lines.append(f"  {c.name:<15} not run: {c.reason}")
        elif c.value is None:
            lines.append(f"  {c.name:<15} {c.status:<5} {c.where}".rstrip())
        else:
            measured = "NaN" if not np.isfinite(c.value) else f"{c.value:.3g}"
            lines.append(
                f"  {c.name:<15} {c.status:<5} {measured} "
                f"{'≤' if c.status == 'pass' else '>'} {c.tolerance:g} {c.unit}"
                + (f" at {c.where}" if c.where else "")
            )
    _emit(args, result.to_dict(), lines)
    return 0 if result.ok else 1


def cmd_designer(args: argparse.Namespace) -> int:
    import importlib.util

    missing = [m for m in ("fastapi", "uvicorn") if importlib.util.find_spec(m) is None]
    if missing:
        raise InputError(
            f"the designer needs {' and '.join(missing)}: pip install 'curvefold[designer]'"
        )
    from .designer.api import design_query
    from .designer.server import missing_bundle, serve

    problem = missing_bundle()
    if problem:
        raise InputError(problem)
    query = []
    if args.design is not None:
        design = load_design(args.design)
        query = [("kind", design.kind), *design_query(design)]
    options = {
        spec.name: _flag_value(spec, text)
        for spec in SERVER_SPECS
        if (text := getattr(args, spec.name)) is not None
    }
    if args.host not in ("127.0.0.1", "localhost", "::1"):
        _error(
            f"warning: serving on {args.host}: anyone who can reach this machine there can "
            "use the designer and make it compute"
        )
    serve(args.host, args.port, query=query, open_browser=not args.no_browser, **options)
    return 0


def _rebuilt_fold(doc, path: Path):
    """The FOLD file of the design a file records (``curvefold:design``), built again and read as
    the file is.

    The design and its frames are estimated within the memory budget before it is built.
    """
    from ..io._fold import model_document, to_fold
    from ..io._fold_reading import parse_fold
    from ..io._output import FoldOutput
    from ._budget import require_rebuild_budget
    from ._build import BuiltCrease, BuiltStructure, build

    record = doc.design
    where = f"{path}: curvefold:design"
    if record is None:
        raise InputError(
            f"{path}: --rebuild needs the design the file was built from "
            "(curvefold:design), and this file does not record one"
        )
    if not isinstance(record.get("design"), dict) or not isinstance(
        record.get("fold_angles"), list
    ):
        raise InputError(
            f"{where} must hold 'design' (an object) and 'fold_angles' (a list), "
            f"got keys {sorted(record)}"
        )
    design = design_from_dict(record["design"], source=where, base_dir=path.parent)
    require_rebuild_budget(design, len(record["fold_angles"]))
    built = build(design)
    if isinstance(built, BuiltCrease):  # a single curved fold
        from ..io._single_fold import single_fold_model

        return parse_fold(
            model_document(single_fold_model(built.single_fold, record["fold_angles"])),
            f"{where} (rebuilt)",
        )
    if not isinstance(built, BuiltStructure):
        raise InputError(f"{where}: a {design.kind} design has no FOLD file to rebuild")
    keep = record.get("keep")
    kept = None if keep is None else [np.asarray(k, dtype=np.int64) for k in keep]
    output = FoldOutput(
        anchor=record.get("anchor", "start"), faces=record.get("faces", "triangles"), keep=kept
    )
    try:
        model = to_fold(built.structure, output, fold_angles=record["fold_angles"])
    except InputError as exc:  # the samples the record keeps are not the built design's
        raise _NotTheRecord(
            f"{where}: the recorded design does not build this file (not rebuilt): {exc}"
        ) from exc
    return parse_fold(model_document(model), f"{where} (rebuilt)")


class _NotTheRecord(InputError):
    """The design a FOLD file records builds, but not into the file's arrays: a failed rebuild,
    not an error of the command."""


def cmd_mechanism(args: argparse.Namespace) -> int:
    from ..analysis._fold_mechanism import analyse_fold
    from ..analysis._fold_record import records_smooth_design
    from ..io._fold_reading import read_fold

    doc = read_fold(args.file)
    if records_smooth_design(doc):  # what the count applies to
        raise InputError(
            f"{args.file}: mechanism counts the degrees of freedom of rigid panels, and this file "
            "records a design of smooth curved sheets (panels = 0), which bend between their "
            "samples; check it with 'curvefold check', or build it with --panels N"
        )
    frames = analyse_fold(doc, rtol=args.rtol, name=str(args.file))
    payload = {"file": args.file, "frames": [m.to_dict() for m in frames], "notes": list(doc.notes)}
    lines = [
        f"{args.file}: {len(frames)} folded frame{'s' * (len(frames) != 1)}, "
        f"{frames[0].unknowns} unknowns, {frames[0].constraints} constraints"
    ]
    lines += [f"  note: {note}" for note in doc.notes]
    for m in frames:
        gap = f"gap {m.gap:.2e}".replace("inf", "∞")
        state = (
            ""
            if m.consistent
            else f"; INCONSISTENT: the frame breaks its constraints by {m.residual:.2e} (relative)"
        )
        # no gap between null and stiff singular values: no count to state
        count = (
            f"{m.dof} internal DOF (nullity {m.nullity})"
            if np.isfinite(m.gap)
            else f"no clear count (nullity {m.nullity} at the rank tolerance)"
        )
        lines.append(
            f"  {m.label:<24} {count}, {gap}, "
            f"residual {m.residual:.1e}{state}" + (f" ({m.note})" if m.note else "")
        )
    _emit(args, payload, lines)
    return 0 if all(m.consistent for m in frames) else 1


def cmd_atlas(args: argparse.Namespace) -> int:
    from ..vault._atlas import GRID_A
    from ..vault._cluster import workers_spec
    from ._budget import require_atlas_budget
    from ._folder import check_output
    from ._outputs import write_atlas

    p_xy, a = _grid("--p-xy", args.p_xy, _VAULT["p_xy"]), _grid("--a", args.a, GRID_A)
    width = (
        _VAULT["width"].default if args.width is None else _flag_value(_VAULT["width"], args.width)
    )
    samples = (
        201
        if args.samples is None
        else vault_samples(
            _flag_value(SCHEMA[""]["samples"], args.samples),
            where=f"--samples {args.samples}: samples",
        )
    )
    workers = (
        None
        if args.workers is None
        else workers_spec().check(
            _from_text(workers_spec(), args.workers, "--workers"),
            f"--workers {args.workers}: workers",
        )
    )
    target = check_output(args.out, force=args.force)
    require_atlas_budget(len(p_xy) * len(a), samples=samples, workers=workers)
    payload = write_atlas(
        p_xy,
        a,
        out=target,
        width=width,
        samples=samples,
        workers=workers,
        scheduler=args.scheduler,
        show_progress=not args.json,
    )
    payload["out"] = str(args.out)
    _emit(
        args,
        payload,
        [
            f"atlas: {payload['valid']}/{payload['designs']} designs valid; wrote "
            f"{len(payload['files'])} files to {args.out}/",
            *(f"  {note}" for note in payload.get("notes", [])),
        ],
    )
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (see the module doc).

    A :class:`~curvefold.kernel.CurvefoldError` (a user error), an unreadable or
    unwritable file, a missing optional package or running out of memory prints one line
    and returns 2. A signal returns 128 + its number. Any other exception is a bug: one
    line asking for a report, status 1; ``--debug`` adds the traceback and the warnings,
    which are otherwise never printed.
    """
    debug = "--debug" in (sys.argv[1:] if argv is None else argv)
    with warnings.catch_warnings(record=True) as caught, signals_interrupt():
        warnings.simplefilter("always")
        try:
            status = _run(build_parser(), argv)
            # a signal whose exception Python ignored (raised in a finalizer)
            raise_if_interrupted()
            return status
        except CurvefoldError as err:
            _error(f"error: {err}")
            return 2
        except OSError as err:
            _error(
                f"error: {err.filename}: {err.strerror}"
                if err.filename and err.strerror
                else f"error: {err}"
            )
            return 2
        except ImportError as err:
            _error(f"error: {err}")
            return 2
        except MemoryError:
            _error(
                "error: out of memory; lower samples, the number of tubes or cells, or the "
                "formats written (see CURVEFOLD_MEMORY_BUDGET in the README)"
            )
            return 2
        except (Interrupted, KeyboardInterrupt) as err:
            signum = err.signum if isinstance(err, Interrupted) else signal.SIGINT
            _error(f"interrupted by {signal.Signals(signum).name}")
            return 128 + int(signum)
        except Exception as err:
            from ..kernel._version import VERSION

            hint = "" if debug else " (rerun with --debug for the traceback)"
            _error(
                f"internal error: {type(err).__name__}: {err}. This is a bug in curvefold "
                f"{VERSION}; please report it with the command you ran{hint}"
            )
            if debug:
                traceback.print_exc()
            return 1
        finally:
            if debug:
                for w in caught:
                    print(
                        warnings.formatwarning(
                            w.message, w.category, w.filename, w.lineno
                        ).rstrip(),
                        file=sys.stderr,
                    )


def _error(text: str) -> None:
    """One line on stderr, whatever the text holds."""
    print(f"{PROG}: " + for_terminal(text), file=sys.stderr)


def _run(parser: argparse.ArgumentParser, argv: Sequence[str] | None) -> int:
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    from ..kernel._threads import one_blas_thread

    # a command's matrices are small: more BLAS threads only wait (kernel.threads)
    with one_blas_thread():
        if args.command in {kind.name for kind in design_kinds()}:
            return cmd_structure(args.command, args)
        return {
            "load": cmd_load,
            "arch": cmd_arch,
            "reproduce": cmd_reproduce,
            "check": cmd_check,
            "mechanism": cmd_mechanism,
            "atlas": cmd_atlas,
            "designer": cmd_designer,
        }[args.command](args)


def run() -> None:
    """The ``curvefold`` console script: :func:`main` on the command line's arguments, its status
    as the exit status."""
    sys.exit(main())
