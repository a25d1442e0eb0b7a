"""The ``curvefold`` commands: each reads its parsed arguments, does its work and prints its
result (``_emit``) or raises a :class:`~curvefold.kernel.CurvefoldError` for the user.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ..io._formats import check_kind
from ..kernel._errors import InputError
from ..kernel._text import for_terminal
from ..vault._assembly import vault_samples
from ._cli_flags import _design_flags, _fit_targets, _flag_value, _from_text, _grid
from ._cli_parser import _VAULT, PROG
from ._design import SCHEMA, Design, design_from_dict, load_design
from ._folder import OutputTarget
from .designer import SERVER_SPECS


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


def _checked_output(design: Design, args: argparse.Namespace, out: Path) -> OutputTarget:
    """The output folder to write, checked (:func:`curvefold.app._folder.check_output`) with the
    formats the design asks for, before any work."""
    from ._folder import check_output

    formats_kind = design.design_kind.formats_kind
    check_kind(design.output.formats, formats_kind, f"{design.source}: [output] formats")
    return check_output(
        out,
        force=args.force,
        inputs=([] if args.design is None else [args.design]) + list(design.tables()),
    )


def cmd_structure(kind: str, args: argparse.Namespace) -> int:
    from ._budget import require_budget
    from ._build import build
    from ._outputs import structure_payload, write_outputs
    from ._thickness import thickness_lines

    design = _load_design(kind, args)
    out = args.out or (None if args.json else Path(design.design_kind.default_out))
    target = None if out is None else _checked_output(design, args, out)
    design = _fit_targets(design, args)  # the output checked first: a fit takes a while
    require_budget(design, files=out is not None)
    built = build(design)
    if target is None:
        payload = structure_payload(built, thick=True)
    else:
        written = write_outputs(built, target, show_progress=not args.json, thick=True)
        payload = written | {"out": str(out)}
    lines = [payload["title"]]
    for key in ("kappa0_s0", "proportion_change", "p_xz", "tubes", "max_tubes", "span", "rise"):
        if key in payload:
            lines.append(
                f"  {key:<18} {payload[key]:.10g}"
                if isinstance(payload[key], float)
                else f"  {key:<18} {payload[key]}"
            )
    lines += thickness_lines(payload) + _certificate_lines(payload)
    if out is not None:
        lines.append(f"  wrote {len(payload['files'])} files to {out}/ (open {out}/report.html)")
        lines += [f"  {note}" for note in payload.get("notes", [])]
    _emit(args, payload, lines)
    return 1 if _certificate_failed(payload) else 0


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
        anchor=record.get("anchor", "start"),
        faces=record.get("faces", "triangles"),
        keep=kept,
        ground=record.get("ground") is True,
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
        # no singular value at or under the tolerance: every constraint independent, and the
        # nullity is unknowns − constraints, with no gap to measure
        independent = m.nullity == max(0, m.unknowns - m.constraints)
        gap = (
            "every constraint independent"
            if independent and not np.isfinite(m.gap)
            else f"gap {m.gap:.2e}".replace("inf", "∞")
        )
        state = (
            ""
            if m.consistent
            else f"; INCONSISTENT: the frame breaks its constraints by {m.residual:.2e} (relative)"
        )
        # no gap between null and stiff singular values: no count to state
        count = (
            f"{m.dof} internal DOF (nullity {m.nullity})"
            if np.isfinite(m.gap) or independent
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
    load = _atlas_load(args)
    target = check_output(args.out, force=args.force)
    require_atlas_budget(len(p_xy) * len(a), samples=samples, workers=workers, load=load)
    payload = write_atlas(
        p_xy,
        a,
        out=target,
        width=width,
        samples=samples,
        load=load,
        workers=workers,
        scheduler=args.scheduler,
        show_progress=not args.json,
    )
    payload["out"] = str(args.out)
    lines = [
        f"atlas: {payload['valid']}/{payload['designs']} designs valid; wrote "
        f"{len(payload['files'])} files to {args.out}/"
    ]
    if load is not None:
        lines.append(_lightest_line(payload))
    _emit(args, payload, lines + [f"  {note}" for note in payload.get("notes", [])])
    return 0


def _atlas_load(args: argparse.Namespace):
    """The mechanics of every design of an atlas from ``--load`` and the load flags, or None.

    The flags are ``curvefold load``'s, read into a vault design's ``[material]`` and
    ``[loads]`` and checked there; a load flag without ``--load`` is refused.
    """
    from ..mechanics._atlas_load import LOAD_SAMPLES
    from ._cli_flags import _load_specs
    from ._cli_parser import LOAD_KIND
    from ._loading import atlas_load

    specs = _load_specs(LOAD_KIND)
    flags, typed = _design_flags(LOAD_KIND, args, specs)
    if args.load_samples is not None:
        typed.append(f"--load-samples {args.load_samples}")
    if not args.load:
        if typed:
            raise InputError(
                f"{typed[0].split()[0]} sets the mechanics columns, which only --load adds: "
                f"add --load, or leave out {typed[0]}"
            )
        return None
    samples = (
        LOAD_SAMPLES.default
        if args.load_samples is None
        else LOAD_SAMPLES.check(
            _from_text(LOAD_SAMPLES, args.load_samples, "--load-samples"),
            f"--load-samples {args.load_samples}: load_samples",
            shown=args.load_samples,
        )
    )
    source = " ".join([f"{PROG} atlas --load", *typed])
    design = design_from_dict({"kind": LOAD_KIND}, source=source)
    design = (design.overrides(source=source, **flags) if flags else design).with_mechanics()
    assert design.material is not None and design.loads is not None  # with_mechanics fills them
    # a coarse model screens the grid: one element across unless --across says more
    given = any(t.startswith("--across") for t in typed)
    return atlas_load(design.material, design.loads, samples=samples, across=None if given else 1)


def _lightest_line(payload: dict) -> str:
    """The summary's line of the mechanics: how many stand and the lightest of them."""
    light = payload["lightest"]
    head = f"  under load: {payload['stands']}/{payload['valid']} valid designs stand"
    if light is None:
        return head + "; none stands (see atlas.csv: governing, utilisation)"
    return (
        f"{head}; the lightest: a = {light['a']:g}, p_xy = {light['p_xy']:g} "
        f"(row {light['row']}, column {light['col']}), {light['mass']:.4g} kg, {light['tubes']} "
        f"tube{'s' * (light['tubes'] != 1)}, governed by {light['governing']} (utilisation "
        f"{light['utilisation']:.3g})"
    )


def _error(text: str) -> None:
    """One line on stderr, whatever the text holds."""
    print(f"{PROG}: " + for_terminal(text), file=sys.stderr)
