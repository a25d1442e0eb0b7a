"""The ``curvefold`` command line.

Every subcommand prints a short human summary, or with ``--json`` one JSON object on
stdout. User errors print one line on stderr (what is wrong, the allowed range, the value
given) and exit with status 2; no traceback, no partial output files.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ..kernel.errors import CurvefoldError, InputError

__all__ = ["main"]

PROG = "curvefold"
DEFAULT_OUT = {"vault": "curvefold-vault", "tube": "curvefold-tube", "block": "curvefold-block", "crease": "curvefold-crease"}


# -- argument helpers -------------------------------------------------------------------------


def _tubes(text: str) -> int | str:
    if text == "max":
        return "max"
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number ≥ 1 or 'max', got {text!r}") from None


def _grid(text: str) -> np.ndarray:
    """``start:stop:count`` or a comma-separated list of numbers."""
    try:
        if ":" in text:
            start, stop, count = text.split(":")
            n = int(count)
            if not 1 <= n <= 200:
                raise argparse.ArgumentTypeError(f"count must be in [1, 200], got {n}")
            return np.linspace(float(start), float(stop), n)
        values = np.array([float(v) for v in text.split(",")])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected start:stop:count or a comma-separated list, got {text!r}") from None
    if values.size == 0 or values.size > 200 or not np.isfinite(values).all():
        raise argparse.ArgumentTypeError(f"expected 1 to 200 finite numbers, got {text!r}")
    return values


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line with exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise InputError(f"{self.prog}: {message}")


def _add_output(p: argparse.ArgumentParser, kind: str | None) -> None:
    g = p.add_argument_group("output")
    if kind is not None:
        g.add_argument("--out", metavar="DIR", type=Path, help=f"folder to write (default: ./{DEFAULT_OUT[kind]}; with --json and no --out nothing is written)")
        g.add_argument("--force", action="store_true", help="replace an existing output folder")
        g.add_argument("--formats", metavar="LIST", help="comma-separated subset of: svg,dxf,pdf,fold,glb,obj,stl,ply,3dm,gif (default: all; the report and its pictures are always written)")
        g.add_argument("--page", metavar="NAME", help="page for the crease patterns: A4, A3, A2, A1, A0, Letter, … (default A4)")
        g.add_argument("--scale", type=float, metavar="S", help="crease-pattern scale, output units per model unit (default: fit the largest sheet to the page)")
        g.add_argument("--units", choices=("mm", "cm", "in"), help="units of the crease patterns (default mm)")
        g.add_argument("--no-glue-tabs", dest="glue_tabs", action="store_false", default=None, help="leave the glue tabs off the crease patterns")
        g.add_argument("--rulings", action="store_true", default=None, help="draw the rulings on the crease patterns (for scoring or engraving)")
    g.add_argument("--json", action="store_true", help="print one JSON object on stdout instead of the summary")


def _design_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument("design", nargs="?", type=Path, help="a TOML design file (see examples/); flags override its values")
    p.add_argument("--samples", type=int, help="samples along curve 1 (default 801)")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog=PROG,
        description="Rigid-foldable, flat-foldable curved-crease tubes and deployable vaults from a space curve: "
        "geometry, folding motion, crease patterns and a measured certificate.",
        epilog="Run 'curvefold vault' with no arguments to build the paper's example vault into ./curvefold-vault.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__import__('curvefold').__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    p = sub.add_parser("vault", help="the composite deployable vault (the main job)", description="Build a vault of tubed arches stacked along the lattice diagonal, standing on z = 0 at the design fold angle, and write its files, pictures and report.")
    _design_arg(p)
    g = p.add_argument_group("design")
    g.add_argument("--a", type=float, help="torsion amplitude a in τ = a κ0 sin(2π s/s0), 0 ≤ a < 1.2707 (default 0.3)")
    g.add_argument("--p-xy", type=float, help="section proportion w_R(0)/w_L(0) at the feet (default 0.75)")
    g.add_argument("--width", type=float, help="width scale w_L(0)·κ0, dimensionless (default 0.08)")
    g.add_argument("--tubes", type=_tubes, help="number of tubes, or 'max' (default: max before regression, at most 24)")
    g.add_argument("--fold-angle", type=float, help="design fold angle 2α in degrees, in (0, 180) (default 90)")
    g.add_argument("--radius", type=float, help="1/κ0 in model units (default 1)")
    g.add_argument("--layers", type=int, help="parallel diagonals of tubes (default 1)")
    g.add_argument("--direction", choices=("+", "-"), help="stack in +u+v or −u−v (default +)")
    _add_output(p, "vault")

    for kind, text in (("tube", "a single tube around curve 1"), ("block", "a cellular block of lattice cells")):
        p = sub.add_parser(kind, help=text, description=f"Build {text} from a design file (kind = \"{kind}\") or the defaults, and write its files and report.")
        _design_arg(p)
        p.add_argument("--fold-angle", type=float, help="fold angle 2α (degrees) at which κ, τ are given")
        _add_output(p, kind)

    p = sub.add_parser("crease", help="a single curved fold from its crease pattern", description="Fold a single curved crease from its crease pattern (κ_2D, ruling angles, start fold angle): the paper's Fig. 08.")
    _design_arg(p)
    p.add_argument("--fold-angle", type=float, help="fold angle 2α(0) in degrees")
    _add_output(p, "crease")

    p = sub.add_parser("arch", help="solve the arch equation (Eq. 20) for κ0·s0", description="Solve T(s0/2)·T(0) = 0 for the arch κ = κ0, τ = a κ0 sin(2π s/s0).")
    p.add_argument("--a", type=float, default=0.3, help="torsion amplitude (default 0.3)")
    p.add_argument("--p-xy", type=float, help="section proportion at the feet, to report p_xz")
    p.add_argument("--fold-angle", type=float, default=90.0, help="design fold angle 2α in degrees (default 90)")
    _add_output(p, None)

    p = sub.add_parser("atlas", help="a grid of vault designs (the paper's Fig. 10)", description="Build vaults over a grid of p_xy and a; write a figure of their forms with the section slopes and a CSV/JSON of their metrics. Invalid designs are recorded with their reason.")
    p.add_argument("--p-xy", type=_grid, default=np.linspace(0.5, 1.5, 5), help="values of p_xy: start:stop:count or a list (default 0.5:1.5:5)")
    p.add_argument("--a", type=_grid, default=np.linspace(0.0, 1.2, 5), help="values of a (default 0:1.2:5)")
    p.add_argument("--width", type=float, default=0.08, help="width scale w_L(0)·κ0 (default 0.08)")
    p.add_argument("--samples", type=int, default=201, help="samples per crease (default 201)")
    p.add_argument("--workers", type=int, help="parallel processes (default: up to 2)")
    p.add_argument("--out", metavar="DIR", type=Path, default=Path("curvefold-atlas"), help="folder to write (default ./curvefold-atlas)")
    p.add_argument("--force", action="store_true", help="replace an existing output folder")
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


def _load_design(kind: str, args: argparse.Namespace):
    from .design import default_design, load_design

    design = load_design(args.design) if getattr(args, "design", None) else default_design(kind)
    if design.kind != kind:
        raise InputError(f"{args.design}: kind = {design.kind!r} but the command is {kind!r}; use 'curvefold {design.kind} {args.design}'")
    flags = {"samples": args.samples}
    if kind == "vault":
        flags |= {
            "a": args.a,
            "p_xy": args.p_xy,
            "width": args.width,
            "tubes": args.tubes,
            "fold_angle": args.fold_angle,
            "radius": args.radius,
            "layers": args.layers,
            "direction": args.direction,
        }
    elif getattr(args, "fold_angle", None) is not None:
        flags["fold_angle"] = args.fold_angle
    if getattr(args, "formats", None):
        flags["formats"] = [f.strip() for f in args.formats.split(",") if f.strip()]
    for key in ("page", "scale", "units", "glue_tabs", "rulings"):
        if getattr(args, key, None) is not None:
            flags[key] = getattr(args, key)
    return design.overrides(**flags) if any(v is not None for v in flags.values()) else design


def _emit(args: argparse.Namespace, payload: dict, lines: Sequence[str]) -> None:
    if args.json:
        print(json.dumps(payload, indent=2, default=_json_default))
    else:
        print("\n".join(lines))


def _json_default(value):
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")


def cmd_structure(kind: str, args: argparse.Namespace) -> int:
    from .build import build
    from .outputs import structure_payload, write_outputs

    design = _load_design(kind, args)
    built = build(design)
    payload = structure_payload(built)
    out = args.out if args.out is not None else (None if args.json else Path(DEFAULT_OUT[kind]))
    if out is not None:
        payload["files"] = write_outputs(built, out, force=args.force, show_progress=not args.json)
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
    from ..geometry.crease import half_angle
    from ..vault.arch import proportion_change, solve_symmetric_arch

    half_angle(args.fold_angle)
    root = solve_symmetric_arch(args.a)
    change = proportion_change(args.a, root.kappa0_s0, fold_angle=args.fold_angle)
    payload = {"a": args.a, "fold_angle": args.fold_angle, "kappa0_s0": root.kappa0_s0, "residual": root.residual, "proportion_change": change}
    lines = [f"arch a = {args.a:g}: κ0·s0 = {root.kappa0_s0:.12f} (|T(s0/2)·T(0)| = {root.residual:.1e}), proportion change {change:.6f}"]
    if args.p_xy is not None:
        if not np.isfinite(args.p_xy) or args.p_xy <= 0:
            raise InputError(f"--p-xy must be a finite number > 0, got {args.p_xy}")
        payload["p_xy"] = args.p_xy
        payload["p_xz"] = args.p_xy * change**2
        lines.append(f"p_xy = {args.p_xy:g} → p_xz = {payload['p_xz']:.6f}")
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
    from .outputs import write_atlas

    payload = write_atlas(args.p_xy, args.a, out=args.out, force=args.force, width=args.width, samples=args.samples, workers=args.workers, show_progress=not args.json)
    valid = sum(r["valid"] for r in payload["records"])
    _emit(args, payload, [f"atlas: {valid}/{len(payload['records'])} designs valid; wrote {len(payload['files'])} files to {args.out}/"])
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            parser.print_help()
            return 0
        if args.command in ("vault", "tube", "block", "crease"):
            return cmd_structure(args.command, args)
        return {"arch": cmd_arch, "reproduce": cmd_reproduce, "check": cmd_check, "atlas": cmd_atlas}[args.command](args)
    except CurvefoldError as err:
        print(f"{PROG}: error: {err}", file=sys.stderr)
        return 2
    except OSError as err:
        print(f"{PROG}: error: {err.strerror or err}: {err.filename or ''}".rstrip(": "), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130


def run() -> None:  # console-script entry point
    sys.exit(main())
