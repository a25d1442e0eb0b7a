"""The files of an output folder, each a job ``folder -> list of paths`` (see :mod:`curvefold.app.outputs`).

The requested formats are grouped by family (:data:`curvefold.io.formats.FAMILIES`), in
registry order; each family is one job calling the writer the registry names. The
pictures of the report are always written (PNG).

Every mesh written (FOLD, 3D models, crease patterns) keeps the samples of
:attr:`Built.sampling <curvefold.app.build.Built.sampling>`: as accurate as the default
tolerance asks, without sliver triangles; the resolution is recorded in the files'
metadata and in the report (:func:`resolution`).
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import time
from collections.abc import Callable, Collection, Iterable, Iterator
from functools import partial
from pathlib import Path

import numpy as np

from ..analysis.mechanism import certified_mechanism
from ..geometry.panels import PanelLattice
from ..io.formats import FORMATS, check_kind, formats_of
from .build import Built
from .folder import ENDING_SIGNALS

__all__ = ["jobs", "run_jobs", "resolution", "exported_fold_angles", "MOTION_STEPS"]

#: States of the folding motion in the GLB, from flat to the design angle.
MOTION_STEPS = 10
#: Unit of the FOLD and 3D files: the model unit (the fabrication scale applies to the crease patterns).
MODEL_UNIT = "unit"

Job = Callable[[Path], list]


def resolution(built: Built) -> dict:
    """The mesh resolution of the files, for the report (empty for a single crease)."""
    return {} if built.sampling is None else {"mesh": built.sampling.summary()}


def _metadata(built: Built) -> dict:
    design = built.design
    meta = {"kind": design.kind, "title": design.title or design.kind, "samples": design.samples}
    if built.sampling is not None:
        meta |= built.sampling.summary()
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


def exported_fold_angles(built: Built) -> np.ndarray:
    """2α of the frames the files hold (degrees): the folding motion, flat to the design angle."""
    return np.linspace(0.0, built.structure.lattice.crease.fold_angle, MOTION_STEPS)


def jobs(built: Built, formats: Collection[str], *, fold_angle: float | None = None) -> list[tuple[str, Job]]:
    """The jobs that write the requested formats of a built design and its pictures, longest first.

    ``fold_angle`` is 2α of the folded state the FOLD and 3D files hold (degrees; default
    the design angle); crease patterns, pictures and the GIF do not depend on it.

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
        angle = {"fold_angle": fold_angle} if family in _FOLDED else {}
        out.append((label, partial(write, built, names, **angle)))
    out.append(("pictures", partial(_pictures, built)))
    return sorted(out, key=lambda job: _LONGEST_FIRST.index(job[0]))


def _timed(job: Job, folder: Path) -> tuple[list, float]:
    started = time.perf_counter()
    files = job(folder)
    return files, time.perf_counter() - started


def run_jobs(jobs: list[tuple[str, Job]], folder: Path, *, workers: int | None = None) -> Iterable[tuple[str, list, float]]:
    """Start the jobs into ``folder`` on up to ``workers`` processes (default: one per CPU, at most 2).

    The jobs write distinct files, so they run side by side in forked processes where the
    platform has them, started before this returns: the caller can work meanwhile. Where
    there is no fork they run one after the other as the result is iterated.

    Returns
    -------
    iterable of (str, list, float)
        (label, files written, seconds the job took) in job order as each finishes in
        turn; a job's exception is raised there. Its ``close()`` stops the jobs still
        running (an interrupted run waits for none): use it in :func:`contextlib.closing`.
    """
    workers = min(len(jobs), os.cpu_count() or 1, 2) if workers is None else workers
    if workers < 2 or "fork" not in multiprocessing.get_all_start_methods():
        return ((label, *_timed(job, folder)) for label, job in jobs)
    # The ending signals wait while the workers are forked (a signal then would reach a
    # fork hook, or a child with the parent's handlers).
    held = signal.pthread_sigmask(signal.SIG_BLOCK, ENDING_SIGNALS)
    try:
        pool = multiprocessing.get_context("fork").Pool(workers, initializer=_worker_signals, initargs=(held,))
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)
    return _Running(pool, [(label, pool.apply_async(_timed, (job, folder))) for label, job in jobs])


class _Running:
    """Jobs running on a process pool: iterate for their results in job order; ``close()`` terminates the pool."""

    def __init__(self, pool, results: list) -> None:
        self._pool, self._results = pool, results

    def __iter__(self) -> Iterator[tuple[str, list, float]]:
        for label, result in self._results:
            yield (label, *result.get())

    def close(self) -> None:
        self._pool.terminate()
        self._pool.join()


def _worker_signals(mask: set) -> None:
    """A job process leaves signals to its parent: it ignores SIGINT (the terminal sends it to
    the whole group) and dies on SIGTERM and SIGHUP, whatever handlers it inherited; then it
    takes the parent's signal mask back."""
    for signum in ENDING_SIGNALS:
        signal.signal(signum, signal.SIG_IGN if signum == signal.SIGINT else signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_SETMASK, mask)


def _writer(names: tuple[str, ...]) -> Callable:
    return FORMATS[names[0]].load_writer()


def _fold(built: Built, names: tuple[str, ...], folder: Path, fold_angle: float | None = None) -> list:
    """The structure's FOLD file (folded at ``fold_angle``, default the design angle; a panel
    structure also flat and half folded), and one FOLD file per sheet, flat with its target
    fold angles (loadable by Origami Simulator)."""
    from ..geometry.sheets import sheets
    from ..io.fold import write_sheet_fold

    structure, meta, keep = built.structure, _metadata(built), built.sampling.keep
    design = structure.lattice.crease.fold_angle if fold_angle is None else fold_angle
    # panels: the flat and half-folded states too, for `curvefold mechanism`
    angles = [0.0, 0.5 * design, design] if isinstance(structure.lattice, PanelLattice) and design > 0 else [design]
    files = [_writer(names)(folder / f"{built.design.kind}.fold", structure, title=meta["title"], fold_angles=angles,
                            unit=MODEL_UNIT, metadata=meta, keep=keep, design=built.design.to_dict())]
    (folder / "sheets").mkdir()
    for sheet in sheets(structure, keep=keep):
        stem = sheet.label.replace(" · ", "-").replace(" ", "-")
        files.append(write_sheet_fold(folder / "sheets" / f"{stem}.fold", sheet.mesh, MODEL_UNIT, title=sheet.label))
    return files


def _pattern(built: Built, names: tuple[str, ...], folder: Path) -> list:
    """The crease patterns, laid out once for every pattern format."""
    from ..io.tables import mm_per_unit

    o, kind = built.design.output, built.design.kind
    page = o.page if isinstance(o.page, str) else tuple(side / mm_per_unit(o.units) for side in o.page)  # mm -> units
    return list(_writer(names)(folder / f"{kind}-pattern", built.structure, formats=names, page=page, units=o.units, scale=o.scale,
                               glue_tabs=o.glue_tabs, rulings=o.rulings, name=kind, keep=built.sampling.keep))


def _model(built: Built, names: tuple[str, ...], folder: Path, fold_angle: float | None = None) -> list:
    """The 3D files, folded at ``fold_angle`` (default the design angle); the GLB holds the folding motion."""
    return list(_writer(names)(folder / built.design.kind, built.structure, exported_fold_angles(built), formats=names, unit=MODEL_UNIT,
                               metadata=_metadata(built), keep=built.sampling.keep, fold_angle=fold_angle))


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
#: Families whose files hold a folded state (the others are flat or show the whole motion).
_FOLDED = ("fold", "model")
#: Jobs by the time they take on the paper's vault (1.75, 1.4, 0.66, 0.43 and 0.18 s), longest
#: first: started in this order, two processes finish about together.
_LONGEST_FIRST = ("crease patterns", "pictures", "folding GIF", "3D models", "FOLD files")


def _pictures(built: Built, folder: Path) -> list:
    """Plots for the report (PNG)."""
    from ..figures import plots

    structure = built.structure
    if structure is None:
        figures = {"crease": plots.plot_crease(built.crease)}
    else:
        lattice = structure.lattice
        figures = {"regression-domain": plots.plot_regression_domain(lattice, structure.cells),
                   "width-proportion": plots.plot_width_proportion(lattice)}
        if built.vault is not None:
            figures |= {"vault": plots.plot_vault(built.vault), "sections": plots.plot_sections(built.vault),
                        "folding-motion": plots.plot_motion_strip(built.vault)}
        else:
            figures[built.design.kind] = plots.plot_structure(structure)
        if isinstance(lattice, PanelLattice):
            figures["singular-values"] = plots.plot_singular_values(certified_mechanism(structure).states)
    return [path for name, fig in figures.items() for path in plots.save_figure(fig, folder / name, formats=("png",))]
