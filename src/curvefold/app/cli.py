"""The ``curvefold`` command line.

Every subcommand prints a short human summary, or with ``--json`` one strict JSON object
on stdout (no NaN or infinity: a non-finite result is an error). Exit statuses: 0 done;
1 a certificate check failed, or a bug (one line asking for a report with the version,
the traceback only with ``--debug``); 2 a user error (one line on stderr: what is wrong,
the allowed range, the value given), including a job over the memory budget
(:mod:`curvefold.app.budget`); 128 + n when stopped by signal n (SIGINT, SIGTERM, SIGHUP),
after removing what the run had started to write. Warnings are shown only with
``--debug``; text a user typed is printed with its control characters escaped. The output
folder is checked before any work and replaced only as :mod:`curvefold.app.folder` says.

The flags of ``vault``, ``tube``, ``block`` and ``crease``, their help and their checks
are generated from the design schema (:data:`curvefold.app.design.SCHEMA`): one flag per
key, ``--fold-angle`` for ``fold_angle``, ``--no-glue-tabs`` for a key that is true by
default. A flag's value is checked by the key's spec and named as typed
(``--page A9: page must be one of …``); a design made of a file and flags is named by both
(``design.toml --samples 10: …``).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re
import signal
import sys
import threading
import traceback
import warnings
from collections.abc import Sequence
from importlib.metadata import version
from pathlib import Path

import numpy as np

from ..io.formats import FORMATS, check_kind, default_formats
from ..kernel.errors import CurvefoldError, InputError
from ..kernel.text import for_terminal
from ..kernel.validate import Spec
from ..vault.assembly import vault_samples
from .design import SCHEMA, SECTIONS_OF_KIND, Design, design_from_dict, load_design

__all__ = ["main", "Interrupted"]

PROG = "curvefold"
DEFAULT_OUT = {"vault": "curvefold-vault", "tube": "curvefold-tube", "block": "curvefold-block", "crease": "curvefold-crease"}
_DEBUG_HELP = "on an internal error, print the traceback and the warnings"
_FORCE_HELP = "replace the output folder if curvefold wrote it (or it is empty)"
_VAULT = SCHEMA["vault"]


# -- argument helpers -------------------------------------------------------------------------


#: Values along one axis of the atlas grid.
_GRID_COUNT = Spec("count", "integer", 5, "[1, 200]")
#: Parallel processes of the atlas.
_WORKERS = Spec("workers", "integer", None, f"[1, {os.cpu_count() or 1}]", why="processors of this machine")


def _grid(flag: str, text: str, spec: Spec) -> np.ndarray:
    """``start:stop:count`` or a comma-separated list of numbers, each checked by ``spec``."""
    where = f"{flag} {text}: {spec.name}"
    parts = text.split(":")
    if len(parts) == 3:
        count = _GRID_COUNT.check(_from_text(_GRID_COUNT, parts[2], flag), f"{flag} {text}: count")
        start, stop = (spec.check(_from_text(spec, part, flag), where, shown=part) for part in parts[:2])
        return np.linspace(start, stop, count)
    if len(parts) != 1:
        raise InputError(f"{flag}: expected start:stop:count or a comma-separated list of numbers, got {text!r}")
    values = text.split(",")
    _GRID_COUNT.check(len(values), f"{flag} {text}: count")
    return np.array([spec.check(_from_text(spec, part, flag), where, shown=part) for part in values])


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line with exit status 2, and which
    reads ``--a -1e-3`` as a value (any number, not only ``-1`` or ``-.5``)."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)

    def error(self, message: str) -> None:  # type: ignore[override]
        raise InputError(f"{self.prog}: {message}")


# -- flags generated from the design schema --------------------------------------------------

#: Schema keys with no flag (a list of cells is written in a design file).
_NO_FLAG = ("kind", "cells")


def _flag(spec: Spec) -> str:
    """``--fold-angle`` for ``fold_angle``; ``--no-glue-tabs`` for a key true by default."""
    dashed = spec.name.replace("_", "-")
    return f"--no-{dashed}" if spec.kind == "flag" and spec.default else f"--{dashed}"


def _from_text(spec: Spec, text: str, flag: str | None = None):
    """A flag's text as the value a design file would hold (checked by the spec afterwards)."""
    try:
        if spec.kind == "real":
            return float(text)
        if spec.kind == "integer":
            return int(text)
        if spec.kind == "count":
            return text if text == "max" else int(text)
    except ValueError:
        form = {"real": f"a number ({spec.unit})" if spec.unit else "a number", "integer": "a whole number",
                "count": f"a whole number ≥ {spec.range.lo:g} or 'max'"}[spec.kind]
        raise InputError(f"{flag or _flag(spec)}: must be {form}, got {text!r}") from None
    if spec.kind == "function":
        try:
            return float(text)
        except ValueError:
            return text  # an expression in s
    if spec.kind == "formats":
        return [f.strip() for f in text.split(",") if f.strip()]
    if spec.kind == "page" and "," in text:
        try:
            return [float(v) for v in text.split(",")]
        except ValueError:
            return text
    return text


def _flag_value(spec: Spec, text: str):
    """A flag's text as a checked value; a function is checked later, on the design's sample grid."""
    value = _from_text(spec, text)
    return value if spec.kind == "function" else spec.check(value, f"{_flag(spec)} {text}: {spec.name}", shown=text)


def _flag_specs(kind: str) -> dict[str, Spec]:
    """The spec of every design flag of a kind, by argparse destination."""
    return {spec.name: spec for section in ("", *SECTIONS_OF_KIND[kind], "output") for spec in SCHEMA[section].values()
            if spec.name not in _NO_FLAG}


def _formats_help(kind: str) -> str:
    names = default_formats(kind)
    if not names:
        return f"no file formats are written for a {kind} design (the report and its pictures always are)"
    listed = "; ".join(f"{n}: {FORMATS[n].holds}" for n in names)
    return f"comma-separated formats to write besides the report and its pictures (default: all): {listed}"


def _add_design_flags(p: argparse.ArgumentParser, kind: str) -> None:
    """The design file argument and one flag per schema key of the kind, help from the spec."""
    p.add_argument("design", nargs="?", type=Path, help="a TOML design file (see examples/); flags override its values")
    groups = {"design": p.add_argument_group("design"), "output": p.add_argument_group("output")}
    output = {spec.name for spec in SCHEMA["output"].values()}
    for name, spec in _flag_specs(kind).items():
        group = groups["output" if name in output else "design"]
        if spec.kind == "flag":
            text = f"{'do not ' if spec.default else ''}{spec.help} (sets {name} = {str(not spec.default).lower()})"
            group.add_argument(_flag(spec), dest=name, action="store_const", const=not spec.default, default=None, help=text)
        else:
            text = (_formats_help(kind) if spec.kind == "formats" else spec.describe()).replace("%", "%%")
            metavar = {"formats": "LIST", "page": "PAGE", "count": "N|max", "choice": "{" + ",".join(spec.choices) + "}"}
            group.add_argument(_flag(spec), dest=name, metavar=metavar.get(spec.kind, name.upper()), help=text)


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


def _add_output(p: argparse.ArgumentParser, kind: str | None) -> None:
    g = p.add_argument_group("output")
    if kind is not None:
        g.add_argument("--out", metavar="DIR", type=Path, help=f"folder to write (default: ./{DEFAULT_OUT[kind]}; with --json and no --out nothing is written)")
        g.add_argument("--force", action="store_true", help=_FORCE_HELP)
    g.add_argument("--json", action="store_true", help="print one JSON object on stdout instead of the summary")
    p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=_DEBUG_HELP)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog=PROG,
        description="Rigid-foldable, flat-foldable curved-crease tubes and deployable vaults from a space curve: "
        "geometry, folding motion, crease patterns and a measured certificate.",
        epilog="Run 'curvefold vault' with no arguments to build the paper's example vault into ./curvefold-vault.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {version('curvefold')}")
    parser.add_argument("--debug", action="store_true", help=_DEBUG_HELP)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    descriptions = {
        "vault": ("the composite deployable vault (the main job)", "Build a vault of tubed arches stacked along the lattice diagonal, standing on z = 0 at the design fold angle, and write its files, pictures and report."),
        "tube": ("a single tube around curve 1", 'Build a single tube around curve 1 from a design file (kind = "tube") or the defaults, and write its files and report.'),
        "block": ("a cellular block of lattice cells", 'Build a cellular block of lattice cells from a design file (kind = "block") or the defaults, and write its files and report.'),
        "crease": ("a single curved fold from its crease pattern", "Fold a single curved crease from its crease pattern (kappa_2d, ruling angles, start fold angle or alpha(s)): the paper's Fig. 08."),
    }
    for kind, (short, long) in descriptions.items():
        p = sub.add_parser(kind, help=short, description=long)
        _add_design_flags(p, kind)
        _add_output(p, kind)

    p = sub.add_parser("arch", help="solve the arch equation (Eq. 20) for κ0·s0", description="Solve T(s0/2)·T(0) = 0 for the arch κ = κ0, τ = a κ0 sin(2π s/s0).")
    p.add_argument("--a", metavar="A", help=f"{_VAULT['a'].describe()}")
    p.add_argument("--p-xy", metavar="P_XY", help=f"{_VAULT['p_xy'].help}, {_VAULT['p_xy'].requirement}: reports p_xz")
    p.add_argument("--fold-angle", metavar="FOLD_ANGLE", help=_VAULT["fold_angle"].describe())
    _add_output(p, None)

    p = sub.add_parser("atlas", help="a grid of vault designs (the paper's Fig. 10)", description="Build vaults over a grid of p_xy and a; write a figure of their forms with the section slopes and a CSV/JSON of their metrics. Invalid designs are recorded with their reason.")
    grid = f"start:stop:count or a comma-separated list, count {_GRID_COUNT.range}"
    p.add_argument("--p-xy", metavar="GRID", default="0.5:1.5:5", help=f"values of p_xy {_VAULT['p_xy'].requirement}: {grid} (default 0.5:1.5:5)")
    p.add_argument("--a", metavar="GRID", default="0:1.2:5", help=f"values of a {_VAULT['a'].requirement}: {grid} (default 0:1.2:5)")
    p.add_argument("--width", metavar="WIDTH", help=_VAULT["width"].describe())
    p.add_argument("--samples", metavar="N", help=f"samples per crease, in [21, {SCHEMA['']['samples'].range.hi:g}] (default 201)")
    p.add_argument("--workers", metavar="N", help=f"parallel processes, {_WORKERS.requirement} (default: up to 2)")
    p.add_argument("--out", metavar="DIR", type=Path, default=Path("curvefold-atlas"), help="folder to write (default ./curvefold-atlas)")
    p.add_argument("--force", action="store_true", help=_FORCE_HELP)
    p.add_argument("--json", action="store_true", help="print the records as JSON")

    p = sub.add_parser("reproduce", help="the paper's example, paper vs computed", description="Reproduce the paper's vault example (a = 0.3, p_xy = 0.75, 2α = 90°) and compare with the printed values.")
    _add_output(p, None)

    p = sub.add_parser("check", help="certify an exported FOLD file", description="Measure a FOLD file's folded frames against its crease pattern: isometry, face planarity and fold angles.")
    p.add_argument("file", type=Path, help="a .fold file with a crease pattern and folded frames")
    p.add_argument("--isometry-tol", type=float, default=1e-4, help="largest relative edge-length change (default 1e-4)")
    p.add_argument("--planarity-tol", type=float, default=0.5, help="largest fold angle across quad diagonals, degrees (default 0.5)")
    p.add_argument("--fold-angle-tol", type=float, default=0.5, help="largest fold-angle error on creases, degrees (default 0.5)")
    _add_output(p, None)
    return parser


# -- commands ---------------------------------------------------------------------------------


def _load_design(kind: str, args: argparse.Namespace) -> Design:
    """The design file (or the kind's defaults) with the flags over it, named as the user typed it."""
    if args.design is not None:
        design = load_design(args.design)
        if design.kind != kind:
            raise InputError(f"{args.design}: kind = {design.kind!r} but the command is {kind!r}; use 'curvefold {design.kind} {args.design}'")
    else:
        design = design_from_dict({"kind": kind}, source=f"{PROG} {kind}")
    flags, typed = _design_flags(kind, args)
    return design.overrides(source=" ".join([design.source, *typed]), **flags) if flags else design


def _emit(args: argparse.Namespace, payload: dict, lines: Sequence[str]) -> None:
    """Print the result: strict JSON with ``--json``, else the lines (control characters
    escaped). A non-finite number in the result is an error either way
    (:func:`curvefold.app.outputs.strict_json`)."""
    from .outputs import strict_json

    text = strict_json(payload, indent=2)
    print(text if args.json else "\n".join(map(for_terminal, lines)))


def cmd_structure(kind: str, args: argparse.Namespace) -> int:
    from .budget import require_budget
    from .build import build
    from .folder import check_output
    from .outputs import structure_payload, write_outputs

    design = _load_design(kind, args)
    out = args.out if args.out is not None else (None if args.json else Path(DEFAULT_OUT[kind]))
    target = None
    if out is not None:
        check_kind(design.output.formats, kind, f"{design.source}: [output] formats")
        target = check_output(out, force=args.force, inputs=([] if args.design is None else [args.design]) + list(design.tables()))
    require_budget(design, files=out is not None)
    built = build(design)
    payload = structure_payload(built)
    if target is not None:
        payload["files"] = write_outputs(built, target, payload=payload, show_progress=not args.json)
        payload["out"] = str(out)
    lines = [payload["title"]]
    for key in ("kappa0_s0", "proportion_change", "p_xz", "tubes", "max_tubes", "span", "rise"):
        if key in payload:
            lines.append(f"  {key:<18} {payload[key]:.10g}" if isinstance(payload[key], float) else f"  {key:<18} {payload[key]}")
    cert = payload["certificate"]
    lines.append(f"  certificate        {sum(c['passed'] for c in cert)}/{len(cert)} checks pass")
    if out is not None:
        lines.append(f"  wrote {len(payload['files'])} files to {out}/ (open {out}/report.html)")
    _emit(args, payload, lines)
    return 0 if all(c["passed"] for c in cert) else 1


def cmd_arch(args: argparse.Namespace) -> int:
    from ..vault.arch import proportion_change, solve_symmetric_arch

    a = _VAULT["a"].default if args.a is None else _flag_value(_VAULT["a"], args.a)
    fold_angle = _VAULT["fold_angle"].default if args.fold_angle is None else _flag_value(_VAULT["fold_angle"], args.fold_angle)
    root = solve_symmetric_arch(a)
    change = proportion_change(a, root.kappa0_s0, fold_angle=fold_angle)
    payload = {"a": a, "fold_angle": fold_angle, "kappa0_s0": root.kappa0_s0, "residual": root.residual, "proportion_change": change}
    lines = [f"arch a = {a:g}: κ0·s0 = {root.kappa0_s0:.12f} (|T(s0/2)·T(0)| = {root.residual:.1e}), proportion change {change:.6f}"]
    if args.p_xy is not None:
        p_xy = _flag_value(_VAULT["p_xy"], args.p_xy)
        payload["p_xy"] = p_xy
        payload["p_xz"] = p_xy * change**2
        lines.append(f"p_xy = {p_xy:g} → p_xz = {payload['p_xz']:.6f}")
    _emit(args, payload, lines)
    return 0


def cmd_reproduce(args: argparse.Namespace) -> int:
    from ..vault.paper import paper_comparison

    rows = paper_comparison()
    payload = {"rows": rows}
    lines = [f"{'quantity':<20}{'paper':>10}{'computed':>18}   note"]
    for r in rows:
        lines.append(f"{r['quantity']:<20}{r['paper']:>10}{r['computed']:>18.12g}   {r['note']}")
    _emit(args, payload, lines)
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    from ..analysis.foldcheck import check_fold

    result = check_fold(args.file, isometry_tol=args.isometry_tol, planarity_tol=args.planarity_tol, fold_angle_tol=args.fold_angle_tol)
    payload = result.to_dict()
    lines = [
        f"{args.file}: {'OK' if result.ok else 'FAILED'} ({result.frames} folded frame{'s' * (result.frames != 1)})",
        f"  max isometry error        {result.max_isometry_error:.3e} (tolerance {args.isometry_tol:g})",
        f"  max face planarity error  {result.max_face_planarity_error:.3e}° (tolerance {args.planarity_tol:g}°)",
        f"  max fold angle error      {result.max_fold_angle_error:.3e}° (tolerance {args.fold_angle_tol:g}°)",
    ]
    _emit(args, payload, lines)
    return 0 if result.ok else 1


def cmd_atlas(args: argparse.Namespace) -> int:
    from .budget import require_atlas_budget
    from .folder import check_output
    from .outputs import write_atlas

    p_xy, a = _grid("--p-xy", args.p_xy, _VAULT["p_xy"]), _grid("--a", args.a, _VAULT["a"])
    width = _VAULT["width"].default if args.width is None else _flag_value(_VAULT["width"], args.width)
    samples = 201 if args.samples is None else vault_samples(_flag_value(SCHEMA[""]["samples"], args.samples), where=f"--samples {args.samples}: samples")
    workers = None if args.workers is None else _WORKERS.check(_from_text(_WORKERS, args.workers, "--workers"), f"--workers {args.workers}: workers")
    target = check_output(args.out, force=args.force)
    require_atlas_budget(len(p_xy) * len(a), samples=samples, workers=workers)
    payload = write_atlas(p_xy, a, out=target, width=width, samples=samples, workers=workers, show_progress=not args.json)
    valid = sum(r["valid"] for r in payload["records"])
    _emit(args, payload, [f"atlas: {valid}/{len(payload['records'])} designs valid; wrote {len(payload['files'])} files to {args.out}/"])
    return 0


class Interrupted(BaseException):
    """A signal that ends the run (SIGINT, SIGTERM, SIGHUP): raised in the main thread, so
    every ``finally`` runs and the temporary output folder is removed."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


_SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name))


@contextlib.contextmanager
def _signals_interrupt():
    """The first of SIGINT, SIGTERM or SIGHUP raises :class:`Interrupted`; later ones are
    ignored while the run unwinds. Previous handlers are restored afterwards."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    fired: list[int] = []

    def handler(signum, frame):
        if not fired:
            fired.append(signum)
            raise Interrupted(signum)

    previous = {signum: signal.signal(signum, handler) for signum in _SIGNALS}
    try:
        yield
    finally:
        for signum, old in previous.items():
            signal.signal(signum, old)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (see the module doc).

    A :class:`~curvefold.kernel.errors.CurvefoldError` (a user error), an unreadable or
    unwritable file, a missing optional package or running out of memory prints one line
    and returns 2. A signal returns 128 + its number. Any other exception is a bug: one
    line asking for a report, status 1; ``--debug`` adds the traceback and the warnings,
    which are otherwise never printed.
    """
    debug = "--debug" in (sys.argv[1:] if argv is None else argv)
    with warnings.catch_warnings(record=True) as caught, _signals_interrupt():
        warnings.simplefilter("always")
        try:
            return _run(build_parser(), argv)
        except CurvefoldError as err:
            _error(f"error: {err}")
            return 2
        except OSError as err:
            _error(f"error: {err.filename}: {err.strerror}" if err.filename and err.strerror else f"error: {err}")
            return 2
        except ImportError as err:
            _error(f"error: {err}")
            return 2
        except MemoryError:
            _error("error: out of memory; lower samples, the number of tubes or cells, or the formats written "
                   "(see CURVEFOLD_MEMORY_BUDGET in the README)")
            return 2
        except (Interrupted, KeyboardInterrupt) as err:
            signum = err.signum if isinstance(err, Interrupted) else signal.SIGINT
            _error(f"interrupted by {signal.Signals(signum).name}")
            return 128 + int(signum)
        except Exception as err:
            hint = "" if debug else " (rerun with --debug for the traceback)"
            _error(f"internal error: {type(err).__name__}: {err}. This is a bug in curvefold {version('curvefold')}; "
                   f"please report it with the command you ran{hint}")
            if debug:
                traceback.print_exc()
            return 1
        finally:
            if debug:
                for w in caught:
                    print(warnings.formatwarning(w.message, w.category, w.filename, w.lineno).rstrip(), file=sys.stderr)


def _error(text: str) -> None:
    """One line on stderr, whatever the text holds."""
    print(f"{PROG}: " + for_terminal(text), file=sys.stderr)


def _run(parser: argparse.ArgumentParser, argv: Sequence[str] | None) -> int:
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    if args.command in DEFAULT_OUT:
        return cmd_structure(args.command, args)
    return {"arch": cmd_arch, "reproduce": cmd_reproduce, "check": cmd_check, "atlas": cmd_atlas}[args.command](args)


def run() -> None:  # console-script entry point
    sys.exit(main())
