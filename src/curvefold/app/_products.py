"""The files of an output folder, each a job ``folder -> list of paths`` (see
:mod:`curvefold.app._outputs`).

The requested formats are grouped by family (:data:`curvefold.io._formats.FAMILIES`), in
registry order; each family is one job: the crease patterns and the 3D models by their
family's writer (which calls the registry's writer of each format), the FOLD file and the
GIF by the registry's writer. The pictures of the report are written (PNG) when matplotlib
is installed.

Every mesh written (FOLD, 3D models, crease patterns) keeps the samples of
:attr:`BuiltStructure.sampling <curvefold.app._build.BuiltStructure.sampling>`: as accurate as
the default tolerance asks, without sliver triangles; the resolution is recorded in the files'
metadata and in the report (:func:`resolution`).
"""

from __future__ import annotations

import gc
import importlib.util
import multiprocessing
import multiprocessing.connection
import os
import signal
import time
from collections.abc import Callable, Collection, Generator, Iterator, Sequence
from functools import partial
from pathlib import Path
from typing import Any, Protocol

from ..analysis._mechanism import certified_mechanism
from ..io._formats import FORMATS, check_kind, formats_of
from ..kernel._errors import InternalError
from ._build import (
    MOTION_STEPS,
    Built,
    BuiltCrease,
    BuiltStructure,
    BuiltVault,
    design_motion,
    exported_fold_angles,
)
from ._folder import ENDING_SIGNALS

__all__ = [
    "jobs",
    "run_jobs",
    "resolution",
    "design_motion",
    "exported_fold_angles",
    "picture_files",
    "can_draw",
    "pictures_left_out",
    "MOTION_STEPS",
    "PICTURES_NEED",
    "PICTURES_EXTRA",
]

#: Unit of the FOLD and 3D files: the model unit (the fabrication scale applies to the crease
#: patterns).
MODEL_UNIT = "unit"
#: The package the report's pictures are drawn with, and the extra that brings it.
PICTURES_NEED, PICTURES_EXTRA = "matplotlib", "plot"

Job = Callable[[Path], list]


class JobRun(Protocol):
    """Jobs started by :func:`run_jobs`: iterated for their results in job order, ``refill()``
    to run ``prepare`` and start those that have a place, ``close()`` to stop those still
    running."""

    def __iter__(self) -> Iterator[tuple[str, list, float]]: ...

    def refill(self) -> None: ...

    def close(self) -> None: ...


def resolution(built: Built) -> dict:
    """The mesh resolution of the files, for the report (empty for a single crease)."""
    return {"mesh": built.sampling.summary()} if isinstance(built, BuiltStructure) else {}


def _metadata(built: Built) -> dict:
    design = built.design
    meta = {"kind": design.kind, "title": design.title or design.kind, "samples": design.samples}
    meta["sheet_units"] = design.output.units  # the sheet files' units; the FOLD's are the model's
    if isinstance(built, BuiltStructure):
        meta |= built.sampling.summary()
    if isinstance(built, BuiltVault):
        v = built.vault
        meta |= {
            "a": v.design.a,
            "p_xy": v.design.p_xy,
            "width": v.design.width,
            "radius": v.design.radius,
            "fold_angle_deg": v.design.fold_angle,
            "tubes": v.summary()["tubes"] if v.design.tubes is None else int(v.design.tubes),
            "kappa0_s0": v.kappa0_s0,
            "p_xz": v.p_xz,
        }
    return meta


def jobs(
    built: Built, formats: Collection[str], *, fold_angle: float | None = None, thick: bool = False
) -> list[tuple[str, Job]]:
    """The jobs that write the requested formats of a built design and its pictures (when
    :data:`PICTURES_NEED` is installed: see :func:`pictures_left_out`): the drawings first
    (:data:`DRAWN`: they need nothing ``prepare`` computes), then the files, longest first.

    ``fold_angle`` is 2α of the folded state the FOLD and 3D files hold (degrees; default
    the design angle); crease patterns, pictures and the GIF do not depend on it. With
    ``thick``, the assembly guide assembles the structure's thick panels (when it has them).

    Raises
    ------
    InputError
        A format that is not written for the design's kind, with the reason.
    """
    check_kind(formats, built.design.design_kind.formats_kind, "formats")
    families = dict.fromkeys(f.family for name, f in FORMATS.items() if name in formats)
    family_jobs: dict[str, tuple[str, Callable[..., list]]] = (
        _FAMILY_JOBS if isinstance(built, BuiltStructure) else _SINGLE_FOLD_JOBS
    )
    out: list[tuple[str, Job]] = []
    for family in families:
        label, write = family_jobs[family]
        names = tuple(name for name in formats_of(family) if name in formats)
        angle = {"fold_angle": fold_angle} if family in _FOLDED else {}
        angle |= {"thick": True} if thick and family == "guide" else {}
        out.append((label, partial(write, built, names, **angle)))
    if can_draw():
        out.append(("pictures", partial(_pictures, built)))
        if "motion" in families:
            # both drawings need them: imported once, here, before they fork
            for module in DRAWING_MODULES:
                importlib.import_module(module)
    return sorted(out, key=lambda job: _ORDER.index(job[0]))


def _timed(job: Job, folder: Path) -> tuple[list, float]:
    started = time.perf_counter()
    files = job(folder)
    return files, time.perf_counter() - started


def run_jobs(
    jobs: list[tuple[str, Job]],
    folder: Path,
    *,
    workers: int | None = None,
    prepare: Callable[[], None] | None = None,
) -> JobRun:
    """Start the jobs into ``folder`` on up to ``workers`` processes (default: one per CPU, at most
    2).

    ``prepare``, if given, runs in this process once, before the first job that is not one
    of :data:`DRAWN` starts (those start at once, and the others inherit what it computed).

    The jobs write distinct files, so they run side by side where the platform can fork:
    each in a process of its own, forked when a place is free, in job order, the first
    ones before this returns (the caller can work meanwhile). A forked process inherits
    its job, so nothing but its result crosses a pipe. The small jobs of :data:`OWN_JOBS`
    run in this process as the result is iterated, while it waits for the others. Where
    there is no fork they all run one after the other as the result is iterated.

    Returns
    -------
    JobRun
        An iterable of (label, files written, seconds the job took) in job order as each finishes in
        turn; a job's exception is raised there. Its ``close()`` stops the jobs still
        running (an interrupted run waits for none): use it in :func:`contextlib.closing`;
        its ``refill()`` runs ``prepare`` now and starts the jobs that have a place.
    """
    workers = min(len(jobs), os.cpu_count() or 1, 2) if workers is None else workers
    if workers < 2 or "fork" not in multiprocessing.get_all_start_methods():
        return _InTurn(jobs, folder, prepare)
    return _Running(jobs, folder, workers, prepare)


class _InTurn:
    """The jobs one after the other in this process, as they are iterated (where there is no
    fork)."""

    def __init__(
        self, jobs: list[tuple[str, Job]], folder: Path, prepare: Callable[[], None] | None
    ) -> None:
        self._prepare = prepare
        self._results = self._run(jobs, folder)

    def refill(self) -> None:
        if self._prepare is not None:
            prepare, self._prepare = self._prepare, None
            prepare()

    def _run(
        self, jobs: list[tuple[str, Job]], folder: Path
    ) -> Generator[tuple[str, list, float], None, None]:
        for label, job in jobs:
            if label not in DRAWN:
                self.refill()
            yield (label, *_timed(job, folder))

    def __iter__(self) -> Iterator[tuple[str, list, float]]:
        return self._results

    def close(self) -> None:
        self._results.close()


class _Running:
    """Jobs in forked processes, at most ``workers`` at once, and those of :data:`OWN_JOBS` in this
    one as it waits: iterate for their results in job order; ``close()`` kills the processes
    still running.

    A process per job rather than a :class:`multiprocessing.pool.Pool`: a pool's
    ``terminate()`` can wait forever on its task thread, blocked sending a job into a pipe
    that the stopped workers no longer read (seen about once in 40 signals). Here no
    thread sends anything and every process can be killed.
    """

    def __init__(
        self,
        jobs: list[tuple[str, Job]],
        folder: Path,
        workers: int,
        prepare: Callable[[], None] | None,
    ) -> None:
        self._context = multiprocessing.get_context("fork")
        self._folder, self._workers, self._prepare = folder, workers, prepare
        numbered = list(enumerate(jobs))
        self._waiting = [(i, job) for i, job in numbered if job[0] not in OWN_JOBS]
        # run here while the others run
        self._own = [(i, job) for i, job in numbered if job[0] in OWN_JOBS]
        self._running: dict[Any, tuple[int, Any]] = {}  # reader -> (index, process)
        self._results: dict[int, tuple[str, Any]] = {}
        self._labels = [label for label, _ in jobs]
        self._fill()

    def refill(self) -> None:
        """Run ``prepare`` now if it has not run, keep the outcomes of the jobs that have ended
        and start waiting jobs in their places, without waiting for any."""
        if self._prepare is not None:
            prepare, self._prepare = self._prepare, None
            prepare()
        self._collect(timeout=0)

    def _fill(self) -> None:
        while self._waiting and len(self._running) < self._workers:
            if self._prepare is not None and self._waiting[0][1][0] not in DRAWN:
                self.refill()  # forks what has a place, this job first
                continue
            index, (label, job) = self._waiting.pop(0)
            reader, writer = self._context.Pipe(duplex=False)
            # The ending signals wait while the process is forked (a signal then would reach
            # a child with the parent's handlers); the child sets its own, then takes them.
            held = signal.pthread_sigmask(signal.SIG_BLOCK, ENDING_SIGNALS)
            try:
                process = self._context.Process(
                    target=_job_process,
                    args=(job, self._folder, writer, held, label in DRAWN),
                    daemon=True,
                )
                process.start()
                # known to close() before a signal can come
                self._running[reader] = (index, process)
            finally:
                signal.pthread_sigmask(signal.SIG_SETMASK, held)
                writer.close()

    def _collect(self, timeout: float | None = None) -> None:
        """Wait for a running job to end (up to ``timeout`` seconds) and keep its outcome."""
        ready: list[Any] = multiprocessing.connection.wait(
            list(self._running), timeout
        )  # the pipes' readers
        for reader in ready:
            index, process = self._running.pop(reader)
            try:
                outcome = reader.recv()
            except EOFError:  # it died without a word
                process.join()
                outcome = (
                    "error",
                    InternalError(
                        f"the job writing the {self._labels[index]} "
                        f"ended with exit code {process.exitcode}"
                    ),
                )
            reader.close()
            process.join()
            self._results[index] = outcome
        self._fill()

    def __iter__(self) -> Iterator[tuple[str, list, float]]:
        for index, label in enumerate(self._labels):
            while index not in self._results:
                if self._own:
                    self.refill()  # what the own jobs read, first
                    own, (_, job) = self._own.pop(0)
                    try:
                        self._results[own] = ("done", _timed(job, self._folder))
                    except Exception as err:  # raised in job order, as a forked job's
                        self._results[own] = ("error", err)
                else:
                    self._collect()
            status, value = self._results.pop(index)
            if status == "error":
                raise value
            yield (label, *value)

    def close(self) -> None:
        running, self._running, self._waiting, self._own = self._running, {}, [], []
        for reader, (_, process) in running.items():
            process.kill()
            process.join()
            reader.close()


def _job_process(job: Job, folder: Path, conn, mask: set, drawn: bool) -> None:
    """A job process: it leaves signals to its parent (it ignores SIGINT, which the terminal
    sends to the whole group, and dies on SIGTERM and SIGHUP, whatever handlers it inherited),
    takes the parent's signal mask back, runs the job and sends its outcome.

    A drawing (``drawn``) runs at a lower priority (:data:`DRAWN_NICENESS`): nothing waits
    for it but the end, while the file jobs wait for what the parent computes meanwhile.

    The objects it inherits are left out of its garbage collections (:func:`gc.freeze`):
    they live on in the parent anyway, and a collection of the oldest generation would walk
    them all and copy every page that holds one (measured on the paper's vault: 20-27 ms and
    about 1,500 page faults in each job that makes such a collection)."""
    gc.freeze()
    if drawn:
        os.nice(DRAWN_NICENESS)
    for signum in ENDING_SIGNALS:
        signal.signal(signum, signal.SIG_IGN if signum == signal.SIGINT else signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_SETMASK, mask)
    outcome: tuple[str, Any]
    try:
        outcome = ("done", _timed(job, folder))
    except Exception as err:  # raised again in the parent
        outcome = ("error", err)
    try:
        conn.send(outcome)
    except Exception as err:  # an exception that does not pickle
        conn.send(
            (
                "error",
                InternalError(f"{type(outcome[1]).__name__}: {outcome[1]} (not picklable: {err})"),
            )
        )
    conn.close()


def _writer(names: tuple[str, ...]) -> Callable:
    return FORMATS[names[0]].load_writer()


def _fold(
    built: BuiltStructure, names: tuple[str, ...], folder: Path, fold_angle: float | None = None
) -> list:
    """The structure's FOLD file: its folding motion (:func:`exported_fold_angles`), or flat to
    ``fold_angle`` when one is given; and one FOLD file per sheet, flat with its target fold angles
    (loadable by Origami Simulator)."""
    from ..geometry._fold_arrays import fold_arrays
    from ..io._fold import fold_model, write_model, write_sheet_fold
    from ..io._output import FoldOutput

    structure, meta, keep = built.structure, _metadata(built), built.sampling.keep
    angles = exported_fold_angles(built) if fold_angle is None else design_motion(built, fold_angle)
    # the structure's file (write_structure_fold) and its sheets
    arrays = fold_arrays(structure, fold_angles=angles, keep=keep)
    output = FoldOutput(
        unit=MODEL_UNIT,
        metadata=meta,
        keep=keep,
        design=built.design.to_dict(),
        ground=built.design.design_kind.grounded,
    )
    model = fold_model(structure, arrays, output)
    files = [write_model(folder / f"{built.design.kind}.fold", model, title=meta["title"])]
    (folder / "sheets").mkdir()
    for sheet in arrays.sheets:
        stem = sheet.label.replace(" · ", "-").replace(" ", "-")
        files.append(
            write_sheet_fold(
                folder / "sheets" / f"{stem}.fold", sheet.mesh, MODEL_UNIT, title=sheet.label
            )
        )
    return files


def _pattern(built: BuiltStructure | BuiltCrease, names: tuple[str, ...], folder: Path) -> list:
    """The crease patterns, from the one layout of the design
    (:attr:`~curvefold.app._build.Built.layout`)."""
    from ..io._pattern import write_layout

    return list(
        write_layout(
            folder / f"{built.design.kind}-pattern",
            built.layout,
            formats=names,
            rulings=built.design.output.rulings,
        )
    )


def _guide(
    built: BuiltStructure, names: tuple[str, ...], folder: Path, *, thick: bool = False
) -> list:
    """The assembly guide, on the pages of the design's crease pattern
    (:attr:`~curvefold.app._build.Built.layout`); with ``thick``, of its thick panels (if any)
    and their cut list."""
    from .. import figures  # noqa: F401  (registers the guide's writer, which figures draws)

    f, units = FORMATS[names[0]], built.design.output.units
    path = f.path(folder / built.design.kind)
    solids = built.thick if thick else None
    return [f.load_writer()(path, built.structure, built.layout, thick=solids, units=units)]


def _model(
    built: BuiltStructure, names: tuple[str, ...], folder: Path, fold_angle: float | None = None
) -> list:
    """The 3D files, folded at ``fold_angle`` (default the design angle); the GLB holds the
    folding motion, and at the design angle of a design under load its deflected shape and
    first modes (:meth:`curvefold.app._loading.Loaded.morph_targets`)."""
    from ..io._models import write_3d
    from ..io._output import ModelOutput

    loaded = built.mechanics if fold_angle is None else None  # the mechanics is the design state's
    morphs = None if loaded is None else loaded.morph_targets(built.structure, built.sampling.keep)
    output = ModelOutput(
        unit=MODEL_UNIT,
        metadata=_metadata(built),
        keep=built.sampling.keep,
        print_unit=built.design.output.units,
        print_scale=built.layout.scale if "stl" in names else None,
        pattern=built.layout if "3dm" in names else None,
        morph_targets=morphs,
    )
    return list(
        write_3d(
            folder / built.design.kind,
            built.structure,
            design_motion(built),
            output,
            formats=names,
            fold_angle=fold_angle,
        )
    )


def _motion(built: BuiltStructure, names: tuple[str, ...], folder: Path) -> list:
    """The GIF of the folding motion, flat to the design angle and back."""
    from ..figures._motion import motion_frames

    frames = motion_frames(built.vault if isinstance(built, BuiltVault) else built.structure)
    return [_writer(names)(FORMATS[names[0]].path(folder / "folding"), frames, bounce=True)]


def _solids(built: BuiltStructure, names: tuple[str, ...], folder: Path) -> list:
    """The STEP file of the structure's thick panels at the design angle, in the output units:
    nothing for a structure without them, or without the package the format needs (a note says
    so: :func:`curvefold.io._formats.formats_left_out`)."""
    f = FORMATS[names[0]]
    thick = built.thick
    if thick is None or importlib.util.find_spec(f.dependency or "") is None:
        return []
    path = f.path(folder / f"{built.design.kind}_solids")
    return [f.load_writer()(path, thick, unit="m", to_unit=built.design.output.units)]


def _single_fold_fold(
    built: BuiltCrease, names: tuple[str, ...], folder: Path, fold_angle: float | None = None
) -> list:
    """A single fold's FOLD file (its motion, flat to the design angle or to ``fold_angle``) and its
    sheet's (loadable by Origami Simulator)."""
    from ..io._fold import write_model, write_sheet_fold
    from ..io._single_fold import single_fold_model

    fold, meta = built.single_fold, _metadata(built)
    model = single_fold_model(
        fold,
        design_motion(built, fold_angle),
        unit=MODEL_UNIT,
        metadata=meta,
        design=built.design.to_dict(),
    )
    (folder / "sheets").mkdir()
    return [
        write_model(FORMATS[names[0]].path(folder / built.design.kind), model, title=meta["title"]),
        write_sheet_fold(
            folder / "sheets" / "single-fold.fold",
            fold.pattern_sheet().mesh,
            MODEL_UNIT,
            title="single fold",
        ),
    ]


def _single_fold_model(
    built: BuiltCrease, names: tuple[str, ...], folder: Path, fold_angle: float | None = None
) -> list:
    """A single fold's 3D files, flat to the design angle or to ``fold_angle``; the GLB holds the
    folding motion."""
    from ..io._output import ModelOutput
    from ..io._single_fold import write_single_fold_3d

    output = ModelOutput(
        unit=MODEL_UNIT,
        metadata=_metadata(built),
        print_unit=built.design.output.units,
        print_scale=built.layout.scale if "stl" in names else None,
        pattern=built.layout if "3dm" in names else None,
    )
    return list(
        write_single_fold_3d(
            folder / built.design.kind,
            built.single_fold,
            design_motion(built, fold_angle),
            formats=names,
            output=output,
        )
    )


#: Progress label and job of every family of formats a single curved fold writes.
_SINGLE_FOLD_JOBS: dict[str, tuple[str, Callable[..., list]]] = {
    "fold": ("FOLD files", _single_fold_fold),
    "pattern": ("crease patterns", _pattern),
    "model": ("3D models", _single_fold_model),
}
#: Progress label and job of every family of formats.
_FAMILY_JOBS: dict[str, tuple[str, Callable[..., list]]] = {
    "fold": ("FOLD files", _fold),
    "pattern": ("crease patterns", _pattern),
    "guide": ("assembly guide", _guide),
    "model": ("3D models", _model),
    "motion": ("folding GIF", _motion),
    "solids": ("thick solids", _solids),
}
#: Families whose files hold a folded state (the others are flat or show the whole motion).
_FOLDED = ("fold", "model")
#: What the two drawings (the pictures and the GIF) import: Pillow's core, its drawing, fonts and
#: image files, and the drawing modules of curvefold (about 0.03 CPU-s that each would pay after it
#: forks).
DRAWING_MODULES = (
    "PIL.Image",
    "PIL.ImageDraw",
    "PIL.ImageFont",
    "PIL.ImageFile",
    "curvefold.figures._motion",
)
#: The jobs that draw the structure and need nothing ``prepare`` computes: they start first.
DRAWN = ("pictures", "folding GIF")
#: How much less the drawings' processes get of a shared CPU than the parent (``nice``): on
#: two CPUs, the two drawings and the parent's preparation of the file jobs run together.
DRAWN_NICENESS = 10
#: The file jobs that run in the parent process while it waits for the others, rather than in a
#: process of their own: they take less than what a forked process's first writes to the pages it
#: shares with its parent cost (the FOLD files 0.35 vs 0.43 CPU-s, the guide 0.16 vs 0.16, with
#: 8,000 and 3,700 page faults forked against 360 and 210, on the paper's vault).
OWN_JOBS = ("FOLD files", "assembly guide")
#: The order the jobs start in: the drawings, then the files by the time they take on the
#: paper's vault, longest first (crease patterns 0.41–0.45 CPU-s, 3D models 0.29–0.34, FOLD
#: 0.17–0.21, the guide 0.09–0.12, beside 0.43–0.48 for each drawing), so that the processes
#: finish about together.
_ORDER = DRAWN + ("crease patterns", "3D models", "FOLD files", "assembly guide", "thick solids")


def _figures(built: Built) -> dict[str, Callable]:
    """The report's pictures by name, each a function that draws it (nothing is drawn here): a PIL
    image drawn without matplotlib, but for the single fold's and the pictures of a design under
    load."""
    from ..figures import _pictures as pictures

    if isinstance(built, BuiltCrease):
        from ..figures import _views as views

        fold = built.single_fold
        return {
            "crease": partial(
                views.plot_crease, built.crease, width=(fold.width_left, fold.width_right)
            )
        }
    if not isinstance(built, BuiltStructure):
        return {}
    structure = built.structure
    lattice = structure.lattice
    figures: dict[str, Callable] = {
        "regression-domain": partial(pictures.regression_domain_picture, lattice, structure.cells),
        "width-proportion": partial(pictures.width_proportion_picture, lattice),
    }
    if isinstance(built, BuiltVault):
        figures |= {
            "vault": partial(pictures.vault_picture, built.vault),
            "sections": partial(pictures.sections_picture, built.vault),
            "folding-motion": partial(pictures.motion_strip_picture, built.vault),
        }
    else:
        figures[built.design.kind] = partial(pictures.structure_picture, structure)
    if lattice.rigid:
        figures["singular-values"] = lambda: pictures.singular_values_picture(
            certified_mechanism(structure).states
        )
    loaded = built.mechanics
    if loaded is not None:
        from ..figures import _mechanics as mechanics

        figures |= {
            "deflection": partial(
                mechanics.plot_deflection, loaded.result, magnification=loaded.deflection_scale
            ),
            "modes": partial(mechanics.plot_modes, loaded.result, amplitude=loaded.mode_amplitude),
        }
        if loaded.collapse is not None:  # --nonlinear: the load path to collapse
            figures["collapse"] = partial(mechanics.plot_collapse, loaded.collapse)
    return figures


def _pictures(built: Built, folder: Path) -> list:
    """Plots for the report (PNG)."""
    from ..figures._pictures import write_picture

    return [
        path
        for name, draw in _figures(built).items()
        for path in write_picture(draw(), folder / name)
    ]


def picture_files(built: Built) -> list[str]:
    """The file names of the report's pictures of a built design."""
    return [f"{name}.png" for name in _figures(built)]


def can_draw() -> bool:
    """Whether :data:`PICTURES_NEED` is installed, so pictures can be drawn."""
    return importlib.util.find_spec(PICTURES_NEED) is not None


def pictures_left_out(files: Sequence[str]) -> str | None:
    """One line naming pictures that are not drawn because :data:`PICTURES_NEED` is not installed,
    and the extra that brings it; None when it is installed.

    Examples
    --------
    >>> pictures_left_out(["atlas.png"]) in (
    ...     None,
    ...     "pictures left out: atlas.png (they need matplotlib: pip install 'curvefold[plot]')",
    ... )
    True
    """
    if can_draw():
        return None
    return (
        f"pictures left out: {', '.join(files)} (they need {PICTURES_NEED}: pip install "
        f"'curvefold[{PICTURES_EXTRA}]')"
    )
