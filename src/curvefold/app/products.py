"""The files of an output folder, each a job ``folder -> list of paths`` (see :mod:`curvefold.app.outputs`)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from .build import Built

__all__ = ["jobs", "MOTION_STEPS"]

#: States of the folding motion in the GLB and GIF, from flat to the design angle.
MOTION_STEPS = 10

Job = Callable[[Path], list]


def _metadata(built: Built) -> dict:
    design = built.design
    meta = {"kind": design.kind, "title": design.title or design.kind, "samples": design.samples}
    if built.vault is not None:
        v = built.vault
        meta |= {
            "a": v.design.a,
            "p_xy": v.design.p_xy,
            "width": v.design.width,
            "radius": v.design.radius,
            "fold_angle_deg": v.design.fold_angle,
            "tubes": int(v.design.tubes),
            "kappa0_s0": v.kappa0_s0,
            "p_xz": v.p_xz,
        }
    return meta


def jobs(built: Built, formats: set[str]) -> list[tuple[str, Job]]:
    """The jobs that write the requested formats for a built design, in order."""
    out: list[tuple[str, Job]] = []
    name = built.design.kind
    structure = built.structure
    design_angle = None if structure is None else structure.lattice.crease.fold_angle
    angles = None if design_angle is None else np.linspace(0.0, design_angle, MOTION_STEPS)
    meta = _metadata(built)
    unit = "unit"  # model units; fabrication scale applies to the crease patterns
    o = built.design.output
    if structure is not None:
        from ..io import fold as fold_io
        from ..io import models as model_io
        from ..io import pattern as pattern_io

        if "fold" in formats:
            out.append(("FOLD file", lambda d: [fold_io.write_structure_fold(d / f"{name}.fold", structure, title=meta["title"], fold_angles=[design_angle], unit=unit, metadata=meta)]))
            out.append(("sheet FOLD files", lambda d: _sheet_folds(structure, d / "sheets", unit)))
        pattern = [f for f in ("svg", "dxf", "pdf") if f in formats]
        if pattern:
            # the page is laid out in mm (cm, in as given); metres are drawn in mm
            units, scale = (o.units, o.scale) if o.units in ("mm", "cm", "in") else ("mm", None if o.scale is None else o.scale * (1000.0 if o.units == "m" else 1.0))
            out.append((
                "crease patterns",
                lambda d: list(pattern_io.write_pattern(d / f"{name}-pattern", structure, formats=pattern, page=o.page, units=units, scale=scale, glue_tabs=o.glue_tabs, rulings=o.rulings, name=name)),
            ))
        models = [f for f in ("glb", "obj", "stl", "ply", "3dm") if f in formats]
        if models:
            out.append(("3D models", lambda d: list(model_io.write_3d(d / name, structure, angles, formats=models, unit=unit, metadata=meta))))
    if "png" in formats or "gif" in formats or "report" in formats:
        out.append(("pictures", lambda d: _pictures(built, d, gif="gif" in formats)))
    return out


def _sheet_folds(structure, folder: Path, unit: str) -> list:
    """One FOLD file per sheet, flat with its target fold angles (loadable by Origami Simulator)."""
    from ..geometry.sheets import sheets
    from ..io.fold import write_sheet_fold

    folder.mkdir()
    files = []
    for sheet in sheets(structure):
        stem = sheet.label.replace(" · ", "-").replace(" ", "-")
        files.append(write_sheet_fold(folder / f"{stem}.fold", sheet.mesh, unit, title=sheet.label))
    return files


def _pictures(built: Built, folder: Path, *, gif: bool) -> list:
    """Plots for the report (PNG + SVG) and the folding animation (GIF)."""
    from ..figures import plots

    files: list = []
    structure = built.structure
    if structure is None:
        files += plots.save_figure(plots.plot_crease(built.crease), folder / "crease")
        return files
    lattice = structure.lattice
    files += plots.save_figure(plots.plot_regression_domain(lattice, structure.cells), folder / "regression-domain")
    files += plots.save_figure(plots.plot_width_proportion(lattice), folder / "width-proportion")
    if built.vault is not None:
        files += plots.save_figure(plots.plot_vault(built.vault), folder / "vault")
        files += plots.save_figure(plots.plot_sections(built.vault), folder / "sections")
        files += plots.save_figure(plots.plot_motion_strip(built.vault), folder / "folding-motion")
        if gif:
            files.append(plots.write_motion_gif(built.vault, folder / "folding.gif"))
    else:
        files += plots.save_figure(plots.plot_structure(structure), folder / built.design.kind)
    return files
