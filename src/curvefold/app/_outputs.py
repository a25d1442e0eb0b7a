"""The output folder of the command line: files, pictures and the report.

The folder is checked before any work and written through
:func:`curvefold.app._folder.output_folder`: into a temporary folder beside the target,
renamed onto it at the end, never replacing what was not checked (see
:mod:`curvefold.app._folder`).
"""

from __future__ import annotations

import sys
from collections import Counter
from collections.abc import Callable, Iterator
from contextlib import closing, contextmanager
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..analysis._certificate import certify, certify_single_fold
from ..figures._report import UNITS_SHOWN, report_html
from ..io._atomic import atomic_write
from ..io._formats import formats_left_out, missing_dependencies
from ..kernel._errors import InputError
from ..kernel._json_text import strict_json
from ._build import Built, BuiltCrease, BuiltStructure, BuiltVault
from ._design import Design
from ._design_file import DESIGN_FILE, built_design, design_toml
from ._folder import OutputTarget, output_folder, raise_if_interrupted
from ._products import exported_fold_angles

if TYPE_CHECKING:  # pragma: no cover
    from ..vault._atlas import Measure

__all__ = ["structure_payload", "write_outputs", "write_atlas", "strict_json", "default_title"]


def structure_payload(built: Built, *, thick: bool = False) -> dict:
    """Design, derived quantities and certificate of a built design, JSON-ready; with ``thick``,
    a structure of thick panels (:attr:`BuiltStructure.thick
    <curvefold.app._build.BuiltStructure.thick>`) is certified with them and gains the
    ``thickness`` key (:func:`curvefold.app._thickness.thickness_payload`)."""
    design = built.design
    payload: dict = {
        "kind": design.kind,
        "title": design.title or default_title(built),
        "design": design.to_dict(),
    }
    if isinstance(built, BuiltVault):
        payload |= built.vault.summary()
        from ..vault._paper import paper_comparison

        payload["paper_comparison"] = paper_comparison()
    elif isinstance(built, BuiltStructure):
        V = built.structure.state().vertices
        payload |= {
            "cells": built.structure.cells.tolist(),
            "curves": built.structure.curves_uv.tolist(),
            "curve_kinds": list(built.structure.curve_kinds),
            "bounding_box": [
                V.reshape(-1, 3).min(axis=0).tolist(),
                V.reshape(-1, 3).max(axis=0).tolist(),
            ],
            "regression_margin": built.structure.regression_margin,
        }
    else:  # a single curved fold
        c = built.crease
        payload |= {
            "length": c.curve.length,
            "fold_angle_start_deg": float(np.degrees(2 * c.alpha(c.s[:1])[0])),
            "fold_angle_end_deg": float(np.degrees(2 * c.alpha(c.s[-1:])[0])),
        }
    if isinstance(
        built, BuiltCrease
    ):  # a single fold, in every state of its motion but the flat one
        fold = built.single_fold
        certificate = certify_single_fold(
            [(a, fold.at(a)) for a in exported_fold_angles(built) if a > 0]
        )
    elif isinstance(built, BuiltStructure):
        vault = built.vault if isinstance(built, BuiltVault) else None
        solids = built.thick if thick else None
        certificate = certify(
            built.crease,
            built.structure,
            vault,
            fold_angles=list(exported_fold_angles(built)),
            thick=solids,
        )
        if solids is not None:
            from ._thickness import thickness_payload

            payload["thickness"] = thickness_payload(solids, certificate, built.design)
    else:
        raise TypeError(f"no certificate for a {type(built).__name__}")
    payload["certificate"] = [c.to_dict() for c in certificate.checks]
    payload["certificate_frames"] = {
        "fold_angles": list(certificate.fold_angles),
        "holds_up_to": certificate.holds_up_to,
        "first_contact": certificate.first_contact,
        "samples": certificate.samples,
    }
    if certificate.mechanism is not None:  # rigid panels
        payload["mechanism"] = certificate.mechanism.to_dict()
    if built.mechanics is not None:  # the design says what it is made of or what loads it
        payload["mechanics"] = built.mechanics.to_dict()
    return payload


def parameter_rows(design: Design) -> list[dict]:
    """Every parameter of a design for the report: ``name``, ``label`` (in words, from the
    schema), ``value`` and ``unit``."""
    from ._design import SCHEMA

    rows = []
    for section, values in design.to_dict().items():
        for name, value in values.items() if isinstance(values, dict) else [(section, values)]:
            spec = SCHEMA["" if not isinstance(values, dict) else section][name]
            unit = (
                "× radius"
                if (section, name) == ("vault", "width")
                else UNITS_SHOWN.get(spec.unit, spec.unit)
            )
            rows.append({"name": name, "label": spec.label or name, "value": value, "unit": unit})
    return rows


def default_title(built: Built) -> str:
    """The title of a design that gives none: its kind and main parameters."""
    if isinstance(built, BuiltVault):
        d = built.vault.design
        return (
            f"vault: a = {d.a:g}, p_xy = {d.p_xy:g}, width = {d.width:g}, {d.tubes} tubes, 2α "
            f"= {d.fold_angle:g}°"
        )
    if isinstance(built, BuiltStructure):
        return (
            f"{built.design.kind}: {len(built.structure.cells)} cell(s), 2α = "
            f"{built.structure.lattice.crease.fold_angle:g}°"
        )
    return f"single curved fold, length {built.crease.curve.length:g}"


def _progress(show: bool, total: int) -> tuple[Callable[[str], None], Callable[[], None]]:
    """A progress bar on stderr (rich) when it is a terminal, or nothing (and rich is not
    imported)."""
    bar = _bar(
        show,
        lambda rich: (
            rich.TextColumn("{task.description:<28}"),
            rich.BarColumn(),
            rich.TextColumn("{task.completed}/{task.total}"),
            rich.TimeElapsedColumn(),
        ),
    )
    if bar is None:
        return (lambda label: None), (lambda: None)
    bar.start()
    task = bar.add_task("writing", total=total)

    def step(label: str) -> None:
        bar.update(task, description=label, advance=1)

    return step, bar.stop


def _bar(show: bool, columns: Callable = lambda rich: ()):
    """A transient rich progress bar on stderr if ``show`` and stderr is a terminal, else
    None (and rich is not imported): stdout is for the result, and a log of stderr gets
    nothing but errors. ``columns`` makes its columns from the module ``rich.progress``
    (none: rich's own)."""
    if not show or not sys.stderr.isatty():
        return None
    import rich.progress
    from rich.console import Console

    console = Console(stderr=True)
    return (
        rich.progress.Progress(*columns(rich.progress), transient=True, console=console)
        if console.is_terminal
        else None
    )


def write_outputs(
    built: Built,
    out: OutputTarget,
    *,
    show_progress: bool = True,
    fold_angle: float | None = None,
    workers: int | None = None,
    thick: bool = False,
) -> dict:
    """Write every file of a built design into the folder ``out`` (see the module doc).

    The files are written by job processes while this process computes what they share
    (:meth:`Built.prepare <curvefold.app._build.Built.prepare>` before any job forks, then
    :meth:`~curvefold.app._build.Built.prepare_files` while the pictures are drawn) and the
    certificate.

    Parameters
    ----------
    built : Built
    out : OutputTarget
        The folder, checked by :func:`curvefold.app._folder.check_output` before the work.
    show_progress : bool, keyword-only
    fold_angle : float, optional, keyword-only
        2α of the folded state the FOLD and 3D files hold (degrees); default the design angle.
    workers : int, optional, keyword-only
        Processes for the files (:func:`curvefold.app._products.run_jobs`; 1: this process).
    thick : bool, keyword-only
        Thick panels, for a structure that has them (:mod:`curvefold.app._thickness`): their
        solids and cut list, certificate checks and ``thickness`` key.

    Returns
    -------
    dict
        :func:`structure_payload` of ``built`` with ``"files"``: the names written,
        relative to ``out``, sorted; and ``"notes"``, lines saying what was left out and
        why (the pictures, without matplotlib), when anything was.

    Raises
    ------
    InputError
        A requested format that is not written for the design's kind or whose optional
        package is missing, or an output folder that cannot be written; nothing is written.
    """
    from . import _products as products

    formats = built.design.output.formats
    jobs = products.jobs(built, formats, fold_angle=fold_angle, thick=thick)
    missing = missing_dependencies(formats)
    if missing:
        raise InputError("formats: " + "; ".join(missing))
    left_out = products.pictures_left_out(products.picture_files(built))
    notes = {} if left_out is None else {"notes": [left_out]}
    solids = built.thick if thick and isinstance(built, BuiltStructure) else None  # refusals first
    if solids is not None and formats_left_out(formats):  # the STEP file, without OCP
        notes = {"notes": [*notes.get("notes", []), *formats_left_out(formats)]}
    built.prepare()  # what every job shares, before any forks
    step, stop = _progress(show_progress, len(jobs))
    written: list[str] = []
    try:
        prepare = partial(built.prepare_files, formats)
        # closed at once on any exception
        with (
            output_folder(out) as tmp,
            closing(products.run_jobs(jobs, tmp, workers=workers, prepare=prepare)) as done,
        ):
            # what the file jobs share, computed here while the drawings are drawn; then the file
            # jobs start
            done.refill()
            payload = structure_payload(built, thick=solids is not None)
            if solids is not None:
                from ._thickness import write_thick_files

                o = built.design.output
                files = write_thick_files(solids, tmp, built.design.kind, o.formats, o.units)
                written += [f.name for f in files]
            made = built_design(built)  # the design file that builds this folder again
            design_text = design_toml(made)
            atomic_write(tmp / DESIGN_FILE, design_text)
            written.append(DESIGN_FILE)
            collapsed = built.mechanics and built.mechanics.collapse
            if collapsed:  # --nonlinear: the load path to collapse as data
                atomic_write(tmp / "collapse.csv", collapsed.csv())
                written.append("collapse.csv")
            report = (
                dict(payload, timings={}, parameters=parameter_rows(made))
                | products.resolution(built)
                | notes
            )
            if isinstance(built, BuiltStructure):  # numbers for programs: the fewest, the most
                counts = built.sampling.vertices_per_crease
                report["mesh"] = report["mesh"] | {
                    "mesh_samples_per_crease": [int(min(counts)), int(max(counts))]
                }
            for label, files, seconds in done:
                step(label)
                written += [str(Path(f).relative_to(tmp)) for f in files]
                report["timings"][label] = round(seconds, 3)
            report["files"] = sorted(written)
            report |= _file_certificate(tmp, built.design.kind, written)
            atomic_write(tmp / "report.json", strict_json(report, indent=2))
            page = report_html(report | {"design_toml": design_text})
            if solids is not None:
                from ._thickness import thickness_html

                page = thickness_html(page, report)
            atomic_write(tmp / "report.html", page)
            written += ["report.json", "report.html"]
    finally:
        stop()
    shipped = {
        key: report[key] for key in ("certificate_file", "certificate_columns") if key in report
    }
    return payload | shipped | {"files": sorted(written)} | notes


def _file_certificate(folder: Path, kind: str, written: list[str]) -> dict:
    """The certificate's file column (:func:`curvefold.analysis._file_column.file_column`) of the
    FOLD file written into ``folder``, with what each column measures; {} if none was written."""
    from ..analysis._file_column import COLUMNS, file_column

    name = f"{kind}.fold"
    if name not in written:
        return {}
    return {"certificate_file": file_column(folder / name), "certificate_columns": COLUMNS}


def write_atlas(
    p_xy_values,
    a_values,
    *,
    out: OutputTarget,
    width: float,
    samples: int,
    load: Measure | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    show_progress: bool,
) -> dict:
    """Run the design atlas and write it into the folder ``out`` (checked by
    :func:`curvefold.app._folder.check_output`).

    ``atlas.csv`` and ``atlas.json`` hold every design's record, written as the designs
    finish (in grid order), so memory stays flat whatever the grid's size; the figure
    (``atlas.png``, ``atlas.svg``) shows every k-th row and column of a grid larger than
    :data:`~curvefold.figures._atlas.MAX_VIEWS` per axis. ``load`` (such as
    :class:`curvefold.mechanics.AtlasLoad`) adds its columns to every record and the figure
    marks the designs that stand. ``workers`` and ``scheduler`` are those of
    :func:`curvefold.vault.sweep`.

    Returns
    -------
    dict
        ``shape`` (rows, columns), ``designs``, ``valid``, ``invalid`` (count per error
        class) and ``files`` (names written); without matplotlib the figure is left out
        and ``notes`` says so. With ``load``: ``stands`` (how many designs stand),
        ``lightest`` (the record of the lightest that stands, or None) and ``load`` (what
        loads the designs and the model's samples and elements across).
    """
    from ..figures._atlas import atlas_figure, view_step
    from ..figures._plots import save_figure
    from ..io._records import csv_records, json_records
    from ..vault._atlas import Atlas, AtlasGrid, thin
    from ..vault._sweep import sweep
    from ._products import can_draw, pictures_left_out

    grid = AtlasGrid.of(p_xy_values, a_values, width=width, samples=samples, load=load)
    fields = grid.fields
    step = view_step(grid.shape)
    header = {
        "format": "curvefold-atlas",
        "version": 1,
        "units": "model units (radius 1), angles in degrees"
        + ("" if load is None else "; under load: m (metres: radius 1 m), kg"),
        **grid.to_dict(),
        "fields": list(fields),
    }
    errors: Counter[str | None] = Counter()
    standing = _Lightest()
    with output_folder(out) as tmp:
        with (
            _progress_bar(show_progress, "atlas", grid.size) as progress,
            closing(
                sweep(
                    grid, workers=workers, scheduler=scheduler, progress=progress, sketch_step=step
                )
            ) as results,
            csv_records(tmp / "atlas.csv", fields) as csv_row,
            json_records(tmp / "atlas.json", header, fields) as json_row,
        ):

            def written():
                for record, sketch in results:
                    raise_if_interrupted()
                    csv_row(record)
                    json_row(record)
                    errors[record["error"]] += 1
                    standing.add(record)
                    yield record, sketch

            shown = Atlas.from_results(grid.every(step), thin(written(), step))
        rows, cols = grid.shape
        note = (
            None
            if step == 1
            else (
                f"one in {step} values of a and of p_xy shown; all {rows} × {cols} designs are in "
                "atlas.csv and atlas.json"
            )
        )
        files = (
            [Path(p).name for p in save_figure(atlas_figure(shown, note=note), tmp / "atlas")]
            if can_draw()
            else []
        )
    valid = errors.pop(None, 0)
    left_out = pictures_left_out(["atlas.png", "atlas.svg"])
    notes = ([] if load is None else load.notes()) + ([] if left_out is None else [left_out])
    return (
        {
            "shape": [rows, cols],
            "designs": grid.size,
            "valid": valid,
            "invalid": dict(errors),
            "files": ["atlas.csv", "atlas.json", *files],
        }
        | (
            {}
            if load is None
            else {"stands": standing.count, "lightest": standing.record, "load": load.to_dict()}
        )
        | ({"notes": notes} if notes else {})
    )


class _Lightest:
    """The count of the designs that stand and the record of the lightest (the first of equal
    mass, in grid order), as the records stream past."""

    def __init__(self) -> None:
        self.count: int = 0
        self.record: dict | None = None

    def add(self, record: dict) -> None:
        if record.get("stands") is not True:
            return
        self.count += 1
        if self.record is None or record["mass"] < self.record["mass"]:
            self.record = dict(record)


@contextmanager
def _progress_bar(
    show: bool, label: str, total: int
) -> Iterator[Callable[[int, int], None] | None]:
    """``progress(done, total)`` drawing a bar on stderr (when it is a terminal) while the block
    runs, or None."""
    bar = _bar(show)
    if bar is None:
        yield None
        return
    with bar:
        task = bar.add_task(label, total=total)
        yield lambda done, total: bar.update(task, completed=done)
