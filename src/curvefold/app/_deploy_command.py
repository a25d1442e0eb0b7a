"""``curvefold deploy``: the command (its flags: :mod:`curvefold.app._cli_deploy`)."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from ..kernel._errors import InputError
from ._cli_deploy import CSV_COLUMNS, deploy_flags

__all__ = ["cmd_deploy"]


def cmd_deploy(args: argparse.Namespace, kind: str) -> int:
    """Run ``curvefold deploy`` (module notes); 0 when the design angle is reached."""
    from ..figures._plots import new_figure, save_figure
    from ..mechanics._deploy import START, STEP
    from ._budget import require_deploy_budget
    from ._build import build
    from ._cli_commands import _checked_output, _emit, _load_design
    from ._deployment import deploy_design
    from ._folder import output_folder
    from ._kinds import design_kinds
    from ._outputs import _progress_bar, default_title

    own = deploy_flags(args)  # its flags checked first, then the design's
    design = _load_design(kind, args, kinds=[k.name for k in design_kinds() if k.loaded])
    target = None if args.out is None else _checked_output(design, args, args.out)
    loaded = design.with_mechanics()
    step = own.get("step", STEP.default)
    angle = float(getattr(getattr(design, design.kind, None), "fold_angle", 90.0) or 90.0)
    start = own.get("start", START.default)
    states = max(1, math.ceil((angle - start) / step - 1e-9) + 1)
    require_deploy_budget(design, states)
    built = build(design)
    structure = getattr(built, "structure", None)
    if structure is None:
        raise InputError(f"{design.source}: a {design.kind} design has no end sections to hold")
    params = loaded.material
    assert params is not None  # with_mechanics gave it its defaults
    with _progress_bar(not args.json, "deploy", states) as progress:
        result, failure, material = deploy_design(structure, params, progress=progress, **own)
    summary = result.summary()
    head = {"kind": design.kind, "title": design.title or default_title(built)}
    payload: dict[str, Any] = head | {"design": design.to_dict(), "deployment": summary}
    if failure:
        payload["error"] = failure
    lines = [f"{head['title']}", *_lines(summary, material.name, params.thickness)]
    if failure:
        lines.append(f"  stopped: {failure}")
    if target is not None:
        with output_folder(target) as folder:
            _write_csv(folder / "deploy.csv", result)
            fig = _figure(result, new_figure)
            save_figure(fig, folder / "deploy", ("png",))
        payload["files"] = ["deploy.csv", "deploy.png"]
        payload["out"] = str(args.out)
        lines.append(f"  wrote deploy.csv and deploy.png to {args.out}/")
    _emit(args, payload, lines)
    return 1 if failure else 0


def _lines(s: dict, material: str, thickness: float) -> list[str]:
    if s["states"] == 0:
        return ["  no state reached"]
    return [
        f"  deployed 2α = {s['start_deg']:g}° → {s['end_deg']:g}° ({s['states']} states), "
        f"{material} {thickness * 1e3:g} mm, supports {s['supports']}",
        f"  peak actuation     {s['peak_actuation_Nm']:.4g} N·m/rad at "
        f"{s['peak_actuation_at_deg']:g}°",
        f"  largest stress     {s['max_stress_MPa']:.4g} MPa at {s['max_stress_at_deg']:g}°",
        f"  off the rigid path {s['max_distance_mm']:.4g} mm ({s['max_distance_span']:.2e} of "
        f"the span) at {s['max_distance_at_deg']:g}°",
    ]


def _write_csv(path: Path, d) -> None:
    rows = [",".join(CSV_COLUMNS)]
    for i in range(len(d.angles)):
        rows.append(
            f"{d.angles[i]:.6g},{d.actuation[i]:.9g},{d.max_stress[i] / 1e6:.9g},"
            f"{d.distance[i] * 1e3:.9g},{int(d.iterations[i])}"
        )
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")


def _figure(d, new_figure):
    fig = new_figure(figsize=(7.0, 5.0))
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot(d.angles, d.actuation, color="C0")
    top.axhline(0.0, color="0.6", linewidth=0.8)
    top.set_ylabel("actuation Q (N·m/rad)")
    top.set_title("deployment under self-weight")
    bottom.semilogy(d.angles, d.distance * 1e3, color="C3")
    bottom.set_ylabel("distance from rigid path (mm)")
    bottom.set_xlabel("fold angle 2α (°)")
    fig.tight_layout()
    return fig
