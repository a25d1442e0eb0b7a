"""The files of an output folder, each a job ``folder -> list of paths`` (see :mod:`curvefold.app.outputs`).

The requested formats are grouped by family (:data:`curvefold.io.formats.FAMILIES`), in
registry order; each family is one job calling the writer the registry names. The
pictures of the report are always written.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from functools import partial
from pathlib import Path

import numpy as np

from ..analysis.panels import certified_mechanism
from ..geometry.panels import PanelLattice
from ..io.formats import FORMATS, check_kind, formats_of
from .build import Built

__all__ = ["jobs", "MOTION_STEPS"]

#: States of the folding motion in the GLB, from flat to the design angle.
MOTION_STEPS = 10
#: Unit of the FOLD and 3D files: the model unit (the fabrication scale applies to the crease patterns).
MODEL_UNIT = "unit"

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


def jobs(built: Built, formats: Collection[str]) -> list[tuple[str, Job]]:
    """The jobs that write the requested formats of a built design, then its pictures.

    Raises
    ------
    InputError
        A format that is not written for the design's kind, with the reason.
    """
    check_kind(formats, built.design.kind, "formats")
    families = dict.fromkeys(f.family for name, f in FORMATS.items() if name in formats)
    out: list[tuple[str, Job]] = []
    for family in families:
        label, write = _FAMILY_JOBS[family]
        names = tuple(name for name in formats_of(family) if name in formats)
        out.append((label, partial(write, built, names)))
    out.append(("pictures", partial(_pictures, built)))
    return out


def _writer(names: tuple[str, ...]) -> Callable:
    return FORMATS[names[0]].load_writer()


def _fold(built: Built, names: tuple[str, ...], folder: Path) -> list:
    """The structure's FOLD file (folded at the design angle; a panel structure also flat and
    half folded), and one FOLD file per sheet, flat with its target fold angles (loadable
    by Origami Simulator)."""
    from ..geometry.sheets import sheets
    from ..io.fold import write_sheet_fold

    structure, meta = built.structure, _metadata(built)
    design = structure.lattice.crease.fold_angle
    # panels: the flat and half-folded states too, for `curvefold mechanism`
    angles = [0.0, 0.5 * design, design] if isinstance(structure.lattice, PanelLattice) else [design]
    files = [_writer(names)(folder / f"{built.design.kind}.fold", structure, title=meta["title"],
                            fold_angles=angles, unit=MODEL_UNIT, metadata=meta)]
    (folder / "sheets").mkdir()
    for sheet in sheets(structure):
        stem = sheet.label.replace(" · ", "-").replace(" ", "-")
        files.append(write_sheet_fold(folder / "sheets" / f"{stem}.fold", sheet.mesh, MODEL_UNIT, title=sheet.label))
    return files


def _pattern(built: Built, names: tuple[str, ...], folder: Path) -> list:
    """The crease patterns, laid out once for every pattern format."""
    from ..io.tables import mm_per_unit

    o, kind = built.design.output, built.design.kind
    page = o.page if isinstance(o.page, str) else tuple(side / mm_per_unit(o.units) for side in o.page)  # mm -> units
    return list(_writer(names)(folder / f"{kind}-pattern", built.structure, formats=names, page=page, units=o.units, scale=o.scale,
                               glue_tabs=o.glue_tabs, rulings=o.rulings, name=kind))


def _model(built: Built, names: tuple[str, ...], folder: Path) -> list:
    """The 3D files; the GLB holds the folding motion."""
    structure = built.structure
    angles = np.linspace(0.0, structure.lattice.crease.fold_angle, MOTION_STEPS)
    return list(_writer(names)(folder / built.design.kind, structure, angles, formats=names, unit=MODEL_UNIT, metadata=_metadata(built)))


def _motion(built: Built, names: tuple[str, ...], folder: Path) -> list:
    """The GIF of the folding motion."""
    return [_writer(names)(built.vault if built.vault is not None else built.structure, folder / "folding.gif")]


#: Progress label and job of every family of formats.
_FAMILY_JOBS = {
    "fold": ("FOLD files", _fold),
    "pattern": ("crease patterns", _pattern),
    "model": ("3D models", _model),
    "motion": ("folding GIF", _motion),
}


def _pictures(built: Built, folder: Path) -> list:
    """Plots for the report (PNG + SVG)."""
    from ..figures import plots

    files: list = []
    structure = built.structure
    if structure is None:
        return plots.save_figure(plots.plot_crease(built.crease), folder / "crease")
    lattice = structure.lattice
    if isinstance(lattice, PanelLattice):
        _, mechanisms = certified_mechanism(structure)  # the certificate's, cached
        if mechanisms is not None:
            files += plots.save_figure(plots.plot_singular_values(mechanisms), folder / "singular-values")
    files += plots.save_figure(plots.plot_regression_domain(lattice, structure.cells), folder / "regression-domain")
    files += plots.save_figure(plots.plot_width_proportion(lattice), folder / "width-proportion")
    if built.vault is not None:
        files += plots.save_figure(plots.plot_vault(built.vault), folder / "vault")
        files += plots.save_figure(plots.plot_sections(built.vault), folder / "sections")
        files += plots.save_figure(plots.plot_motion_strip(built.vault), folder / "folding-motion")
    else:
        files += plots.save_figure(plots.plot_structure(structure), folder / built.design.kind)
    return files
