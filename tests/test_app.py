"""The application layer: flags generated from the schema, errors by kind, the output folder.

Each test here pins a defect that the application once had; the comment above it says
what used to happen.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import warnings
from importlib.metadata import entry_points

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _cli import run, run_subprocess
from curvefold import __version__
from curvefold.analysis._measure import developability_residual
from curvefold.app import _outputs as outputs
from curvefold.app import _products as products
from curvefold.app import cli
from curvefold.app._build import build
from curvefold.app._design import SCHEMA, SECTIONS_OF_KIND, default_design, parse_design
from curvefold.geometry import Crease
from curvefold.io._formats import FAMILIES, FORMATS
from curvefold.io._tables import PAGES
from curvefold.kernel import InputError, InternalError, as_function
from curvefold.vault import _atlas as atlas
from curvefold.vault._sweep import run_atlas

BETA_LEFT = "80 + 10*sin(pi*s/3)"
ALPHA_DESIGN = (
    f'kind = "crease"\nsamples = 401\n[crease]\nbeta_left = "{BETA_LEFT}"\nalpha = "40 + 5*s"\n'
)


def one_line(r) -> str:
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    return lines[0]


# --------------------------------------------------------------------------------------------
# [crease] alpha: accepted and written back, but the build never read it.


def test_crease_alpha_is_the_built_alpha_and_its_surfaces_are_developable():
    crease = build(parse_design(ALPHA_DESIGN)).crease
    s = crease.s
    # α is taken as given
    assert_allclose(np.degrees(crease.alpha(s)), 40 + 5 * s, rtol=0, atol=1e-12)
    # r'·p by fourth-order differences falls as h⁴: 1.2e-10 at 401 samples (1.9e-9 at 201)
    assert developability_residual(crease) < 1e-8
    # Eq. (3) integrated from 2α(0) with the derived β_R gives α back (measured 3e-14 rad)
    again = Crease.from_pattern(
        0.5,
        lambda t: 80 + 10 * np.sin(np.pi * t / 3),
        lambda t: np.degrees(crease.beta_right(t)),
        3.0,
        fold_angle=80.0,
        samples=401,
    )
    assert np.abs(again.alpha(s) - crease.alpha(s)).max() < 1e-10


def test_developability_fails_for_the_opposite_sign_of_alpha_prime():
    crease = build(parse_design(ALPHA_DESIGN)).crease
    a = np.radians(5.0)  # α' in rad per model unit
    wrong = as_function(
        lambda s: np.arctan2(
            1.0, 1 / np.tan(crease.beta_left(s)) + 2 * a / (0.5 * np.tan(crease.alpha(s)))
        ),
        name="beta_right",
        length=3.0,
    )
    # measured 0.33
    assert (
        developability_residual(Crease(crease.curve, crease.alpha, crease.beta_left, wrong)) > 0.1
    )


def test_crease_alpha_from_the_command_line(tmp_path):
    (tmp_path / "fold.toml").write_text(ALPHA_DESIGN)
    r = run("crease", "fold.toml", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["fold_angle_start_deg"] == pytest.approx(80.0, abs=1e-9)
    assert out["fold_angle_end_deg"] == pytest.approx(110.0, abs=1e-9)
    assert (
        out["design"]["crease"]["fold_angle"] == 80.0
        and "beta_right" not in out["design"]["crease"]
    )


@pytest.mark.parametrize(
    ("extra", "match"),
    [
        ("beta_right = 90\n", r"^design\.toml: \[crease\] give beta_right or alpha, not both"),
        (
            "fold_angle = 60\n",
            r"^design\.toml: \[crease\] fold_angle must equal 2 alpha\(0\) = "
            r"80 degrees or be left out, got 60\.0$",
        ),
    ],
)
def test_crease_alpha_refuses_what_it_determines(extra, match):
    with pytest.raises(InputError, match=match):
        parse_design(ALPHA_DESIGN + extra, source="design.toml")
    # agreeing is fine
    assert parse_design(ALPHA_DESIGN + "fold_angle = 80\n").crease.fold_angle == 80.0


# --------------------------------------------------------------------------------------------
# One table, one validator: --page A2 was listed by --help and refused; --samples 10 was
# refused with "got 11".


def test_page_units_are_printed_lengths_not_the_model_unit(tmp_path):
    """A crease pattern is printed: "unit" (the model unit, one metre by convention) would
    scale a page 1000-fold; it is refused, the printed units stay."""
    r = run("tube", "--units", "unit", "--out", "t", cwd=tmp_path)
    assert (
        r.returncode == 2
        and r.stderr.startswith("curvefold: error: --units unit: units must be one of")
        and "got unit" in r.stderr
    )
    assert not (tmp_path / "t").exists()


@pytest.mark.parametrize("page", list(PAGES))
def test_every_listed_page_is_accepted(page):
    assert page in cli.build_parser()._subparsers._group_actions[0].choices["tube"].format_help()
    assert default_design("tube").overrides(page=page.lower()).output.page == page


def test_page_a2_prints_at_its_size(tmp_path):
    r = run(
        "tube",
        "--samples",
        "41",
        "--page",
        "A2",
        "--formats",
        "svg",
        "--out",
        "t",
        "--json",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    svg = next(n for n in json.loads(r.stdout)["files"] if n.endswith(".svg") and "pattern" in n)
    assert 'width="420mm"' in (tmp_path / "t" / svg).read_text()


def test_a_custom_page_is_in_millimetres_whatever_the_units(tmp_path):
    # the page pair was read in the output units: 300 × 200 "cm"
    r = run(
        "tube",
        "--samples",
        "41",
        "--units",
        "cm",
        "--page",
        "300,200",
        "--formats",
        "svg",
        "--out",
        "t",
        "--json",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    svg = next(n for n in json.loads(r.stdout)["files"] if n.endswith(".svg") and "pattern" in n)
    assert 'width="300mm"' in (tmp_path / "t" / svg).read_text()


def test_flag_errors_show_the_value_typed(tmp_path):
    r = run("vault", "--samples", "10", "--json", cwd=tmp_path)
    assert r.returncode == 2
    line = one_line(r)
    assert line == (
        "curvefold: error: curvefold vault --samples 10: samples must be ≥ 21 for a vault (the "
        "apex is the middle sample), got 10"
    )
    r = run("tube", "--page", "A9", "--json", cwd=tmp_path)
    assert one_line(r).startswith(
        'curvefold: error: --page A9: page must be one of "A5", "A4", '
        '"A3", "A2", "A1", "A0", "Letter"'
    )
    assert one_line(r).endswith(", got A9")
    r = run("vault", "--layers", "2.5", "--json", cwd=tmp_path)
    assert one_line(r) == "curvefold: error: --layers: must be a whole number, got '2.5'"
    assert os.listdir(tmp_path) == []


def test_arch_checks_its_flags_with_the_vault_specs(tmp_path):
    # arch took any p_xy > 0, where a vault takes (0, 100]
    r = run("arch", "--p-xy", "150", cwd=tmp_path)
    assert one_line(r) == "curvefold: error: --p-xy 150: p_xy must be in (0, 100], got 150"
    r = run("arch", "--fold-angle", "180", cwd=tmp_path)
    assert (
        one_line(r)
        == "curvefold: error: --fold-angle 180: fold_angle must be in (0, 180) degrees, got 180"
    )


def test_file_keys_and_flags_are_named_as_typed(tmp_path):
    (tmp_path / "design.toml").write_text('kind = "vault"\n[vault]\na = 5.0\n')
    r = run("vault", "design.toml", "--json", cwd=tmp_path)
    assert one_line(r) == (
        "curvefold: error: design.toml: [vault] a must be in [0, 1.2707093728) (no arch stands "
        "beyond it: Eq. (20) has no root next to π there), got 5.0"
    )
    (tmp_path / "design.toml").write_text('kind = "vault"\n[vault]\na = 0.4\n')
    r = run(
        "vault",
        "design.toml",
        "--a",
        "0.5",
        "--samples",
        "200000",
        "--tubes",
        "20",
        "--json",
        cwd=tmp_path,
    )
    assert one_line(r).startswith(
        "curvefold: error: design.toml --samples 200000 --a 0.5 --tubes 20: this job needs about"
    )
    assert "<defaults>" not in r.stderr and "with overrides" not in r.stderr


@pytest.mark.parametrize("kind", ["vault", "tube", "block", "crease"])
def test_every_key_but_cells_is_a_flag_with_its_range_in_the_help(kind, capsys):
    with pytest.raises(SystemExit):
        cli.main([kind, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for section in ("", *SECTIONS_OF_KIND[kind], "output"):
        for name, spec in SCHEMA[section].items():
            if name in ("kind", "cells"):
                continue
            assert ("--no-" if spec.kind == "flag" and spec.default else "--") + name.replace(
                "_", "-"
            ) in text
            if spec.kind in ("real", "integer") and spec.range is not None:
                assert spec.requirement.replace(">=", "≥") in text, (name, spec.requirement)


# --------------------------------------------------------------------------------------------
# The certificate was computed twice per command-line run.


def test_the_certificate_is_computed_once_per_run(tmp_path, monkeypatch):
    calls = []
    certify = outputs.certify
    monkeypatch.setattr(outputs, "certify", lambda *a, **k: calls.append(a) or certify(*a, **k))
    r = run("tube", "--samples", "41", "--formats", "fold", "--out", "t", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert len(calls) == 1
    report = json.loads((tmp_path / "t" / "report.json").read_text())
    assert report["certificate"] == json.loads(r.stdout)["certificate"]


# --------------------------------------------------------------------------------------------
# Bugs were printed as user mistakes (exit 2); the atlas recorded them as invalid designs.


def _broken(*args, **kwargs):
    warnings.warn("overflow encountered in a kernel", RuntimeWarning, stacklevel=1)
    raise InternalError("lattice curves out of order")


def test_an_internal_error_asks_for_a_report(tmp_path, monkeypatch):
    monkeypatch.setattr(cli, "cmd_structure", _broken)
    r = run("tube", "--json", cwd=tmp_path)
    assert r.returncode == 1 and r.stdout == ""
    line = one_line(r)  # no warning before it, no traceback
    assert line.startswith("curvefold: internal error: InternalError: lattice curves out of order.")
    assert f"curvefold {__version__}" in line and "report" in line and "--debug" in line


def test_debug_shows_the_traceback_and_the_warnings(tmp_path, monkeypatch):
    monkeypatch.setattr(cli, "cmd_structure", _broken)
    r = run("--debug", "tube", "--json", cwd=tmp_path)
    assert r.returncode == 1
    assert r.stderr.startswith("curvefold: internal error: InternalError")
    assert "Traceback" in r.stderr and "RuntimeWarning: overflow encountered" in r.stderr
    # after the command too
    assert run("tube", "--debug", "--json", cwd=tmp_path).stderr.count("Traceback") == 1


def test_a_user_error_after_a_warning_is_one_line(tmp_path, monkeypatch):
    def refuse(*args, **kwargs):
        warnings.warn("invalid value encountered", RuntimeWarning, stacklevel=1)
        raise InputError("width must be > 0, got 0")

    monkeypatch.setattr(cli, "cmd_structure", refuse)
    r = run("tube", "--json", cwd=tmp_path)
    assert r.returncode == 2 and one_line(r) == "curvefold: error: width must be > 0, got 0"


def test_the_atlas_lets_bugs_propagate(monkeypatch):
    def broken(vault):
        raise InputError("a bug while drawing, not an invalid design")

    monkeypatch.setattr(atlas.Sketch, "from_vault", broken)
    with pytest.raises(InputError, match="a bug while drawing"):
        run_atlas([0.75], [0.3], samples=41, workers=1)
    # a refused design is still a record
    record = run_atlas([0.75], [1.5], samples=41, workers=1).records[0]
    assert record["valid"] is False and record["error"] == "ConvergenceError"


# --------------------------------------------------------------------------------------------
# Formats: a "png" format was checked that does not exist; requested formats were skipped
# silently (crease wrote no file whatever formats said, tube never wrote the GIF).


def test_every_family_has_a_job_and_every_writer_loads():
    assert set(products._FAMILY_JOBS) == set(FAMILIES)
    for f in FORMATS.values():
        assert callable(f.load_writer()) and f.extension == "." + (
            f.name if f.stem is None else "pdf"
        )
        assert f.media_type.count("/") == 1  # served by the designer as the registry says


@pytest.mark.parametrize("family", ["pattern", "model"])
def test_a_familys_writer_calls_the_writer_the_registry_names_for_each_format(
    tmp_path, monkeypatch, family
):
    """write_pattern and write_3d prepare once and hand each format to its registry writer, in
    the order asked: no branch on format names of their own."""
    from curvefold.io import Layout, write_pattern
    from curvefold.io._formats import FileFormat, formats_of
    from curvefold.io._models import FoldedModel, write_3d

    calls = []

    def recorder(self):
        def write(path, prepared, **options):
            calls.append((self.name, path.name, type(prepared).__name__))
            return path

        return write

    monkeypatch.setattr(FileFormat, "load_writer", recorder)
    structure = build(default_design("tube").overrides(samples=41)).structure
    asked = tuple(reversed(formats_of(family)))
    writer = write_pattern if family == "pattern" else write_3d
    written = writer(tmp_path / "t", structure, formats=asked)
    prepared = (Layout if family == "pattern" else FoldedModel).__name__
    assert calls == [(name, f"t{FORMATS[name].extension}", prepared) for name in asked]
    assert [p.name for p in written] == [name for _, name, _ in calls]


def test_unknown_formats_are_refused_not_skipped():
    built = build(default_design("crease").overrides(samples=41))
    with pytest.raises(InputError, match=r"^formats: unknown format 'png' \(allowed: svg, dxf"):
        products.jobs(built, ["png"])
    assert [label for label, _ in products.jobs(built, ())] == ["pictures"]


# --------------------------------------------------------------------------------------------
# Job processes: the files were written by a multiprocessing pool, whose terminate() hung
# about once in 40 signals (its task thread blocked sending a job into a pipe no stopped
# worker read), so an interrupted run never exited.


def _write(name: str, folder):
    (folder / name).write_text(name)
    return [folder / name]


def _fail(folder):
    raise InputError("this job refuses")


def _die(folder):
    os._exit(3)


def _sleep(folder):
    import time

    time.sleep(60)
    return []


def test_jobs_run_in_processes_and_come_back_in_job_order(tmp_path):
    from functools import partial

    jobs = [(f"job {k}", partial(_write, f"f{k}")) for k in range(5)]
    done = list(products.run_jobs(jobs, tmp_path, workers=2))
    assert [label for label, _, _ in done] == [label for label, _ in jobs]
    assert [files for _, files, _ in done] == [[tmp_path / f"f{k}"] for k in range(5)]
    assert sorted(os.listdir(tmp_path)) == [f"f{k}" for k in range(5)]


def _write_pid(name: str, folder):
    """Write the id of the process the job runs in."""
    (folder / name).write_text(str(os.getpid()))
    return [folder / name]


def test_the_small_file_jobs_run_in_this_process_while_it_waits_for_the_others(tmp_path):
    """The jobs of OWN_JOBS run here, the others each in a process of its own, and all come back
    in job order."""
    from functools import partial

    labels = ["pictures", "FOLD files", "crease patterns", "assembly guide"]
    done = list(
        products.run_jobs(
            [(label, partial(_write_pid, f"f{k}")) for k, label in enumerate(labels)],
            tmp_path,
            workers=2,
        )
    )
    assert [label for label, _, _ in done] == labels
    pids = [int((tmp_path / f"f{k}").read_text()) for k in range(4)]
    assert (
        [pid == os.getpid() for pid in pids]
        == [label in products.OWN_JOBS for label in labels]
        == [False, True, False, True]
    )
    assert len(set(pids)) == 3
    # an own job's error is raised in its turn, as a forked job's
    with pytest.raises(InputError, match="this job refuses"):
        list(
            products.run_jobs(
                [("pictures", lambda folder: []), ("FOLD files", _fail)], tmp_path, workers=2
            )
        )


def _write_frozen(name: str, folder):
    """Write how many objects the garbage collector leaves out (:func:`gc.get_freeze_count`)."""
    import gc

    (folder / name).write_text(str(gc.get_freeze_count()))
    return [folder / name]


@pytest.mark.parametrize("workers", [2, 1])
def test_a_job_process_leaves_what_it_inherits_out_of_its_collections(tmp_path, workers):
    """The objects a forked job inherits are frozen there, never in this process (nor in a job
    run here)."""
    import gc
    from functools import partial

    frozen = gc.get_freeze_count()
    list(
        products.run_jobs(
            [("a", partial(_write_frozen, "a")), ("b", partial(_write_frozen, "b"))],
            tmp_path,
            workers=workers,
        )
    )
    counts = [int((tmp_path / name).read_text()) for name in "ab"]
    assert gc.get_freeze_count() == frozen
    if workers == 2:  # forked: everything it inherited is frozen
        assert min(counts) > 1000
    else:  # run here: nothing is frozen for it (the check sees a job that is not forked)
        assert counts == [frozen, frozen]


def test_a_job_that_fails_or_dies_is_an_error_in_the_caller(tmp_path):
    with pytest.raises(InputError, match="this job refuses"):
        list(products.run_jobs([("a", _fail), ("b", _fail)], tmp_path, workers=2))
    with pytest.raises(InternalError, match="the job writing the b ended with exit code 3"):
        list(products.run_jobs([("a", lambda folder: []), ("b", _die)], tmp_path, workers=2))


def test_closing_the_jobs_kills_the_processes_still_running(tmp_path):
    import psutil

    before = set(psutil.Process().children())
    running = products.run_jobs([("a", _sleep), ("b", _sleep), ("c", _sleep)], tmp_path, workers=2)
    children = set(psutil.Process().children()) - before
    assert len(children) == 2  # two at a time, the third waits
    running.close()
    _, alive = psutil.wait_procs(children, timeout=10)
    assert alive == [] and set(psutil.Process().children()) <= before


# its pattern, FOLD file and models are written (tests/test_motion_files.py)
@pytest.mark.parametrize("fmt", ["gif"])
def test_a_crease_refuses_structure_formats_with_the_reason(tmp_path, fmt):
    r = run("crease", "--samples", "41", "--formats", fmt, "--out", "c", cwd=tmp_path)
    assert r.returncode == 2
    assert one_line(r).startswith(
        "curvefold: error: curvefold crease --samples 41 --formats "
        f'{fmt}: [output] formats: "{fmt}" is not written for a crease design: '
    )
    assert one_line(r).endswith("written for vault, tube and block designs")
    assert os.listdir(tmp_path) == []


def test_default_formats_are_the_ones_written():
    assert default_design("crease").output.formats == tuple(
        name for name in FORMATS if name not in ("gif", "assembly", "step")
    )
    for kind in ("vault", "tube", "block"):
        assert default_design(kind).output.formats == tuple(FORMATS)


def test_a_tube_writes_its_folding_gif(tmp_path):
    from PIL import Image

    r = run("tube", "--samples", "41", "--formats", "gif", "--out", "t", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "folding.gif" in json.loads(r.stdout)["files"]
    with Image.open(tmp_path / "t" / "folding.gif") as gif:
        assert gif.n_frames > 2


# --------------------------------------------------------------------------------------------
# Entry points


def test_console_script_is_the_cli():
    (script,) = [e for e in entry_points(group="console_scripts") if e.name == "curvefold"]
    assert script.load() is cli.run


def test_python_m_curvefold_reports_a_user_error_in_one_line(tmp_path):
    r = run_subprocess("vault", "--samples", "10", cwd=tmp_path)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.strip() == (
        "curvefold: error: curvefold vault --samples 10: samples must be ≥ 21 for a vault (the "
        "apex is the middle sample), got 10"
    )


# --------------------------------------------------------------------------------------------
# An install without the plot extra: the command line in a fresh interpreter where matplotlib
# cannot be imported (None in sys.modules makes every import of it fail, and find_spec say so)


_WITHOUT_MATPLOTLIB = (
    "import sys; sys.modules['matplotlib'] = None; from curvefold.app.cli import run; run()"
)


def _without_matplotlib(*argv: str, cwd) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", _WITHOUT_MATPLOTLIB, *argv],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
    )


def test_without_matplotlib_the_folder_is_written_and_one_line_says_which_pictures_are_left_out(
    tmp_path,
):
    r = _without_matplotlib(
        "tube", "--samples", "41", "--formats", "fold", "--out", "t", cwd=tmp_path
    )
    assert r.returncode == 0 and r.stderr == "", r.stderr
    note = (
        "pictures left out: regression-domain.png, width-proportion.png, tube.png (they need "
        "matplotlib: pip install 'curvefold[plot]')"
    )
    assert [line.strip() for line in r.stdout.splitlines() if "left out" in line] == [note]
    folder = tmp_path / "t"
    files = sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file())
    assert {"tube.fold", "report.json", "report.html", "sheets/tube-1-sheet-A.fold"} <= set(
        files
    ), files
    assert not [f for f in files if f.endswith(".png")]
    report = json.loads((folder / "report.json").read_text())
    assert report["notes"] == [note] and not [
        c for c in report["certificate"] if c["status"] == "fail"
    ]
    assert f"<p>{note}</p>".replace("'", "&#x27;") in (folder / "report.html").read_text()
    r = _without_matplotlib(
        "vault",
        "--samples",
        "41",
        "--tubes",
        "2",
        "--formats",
        "obj",
        "--json",
        "--out",
        "v",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["notes"] == [
        "pictures left out: regression-domain.png, "
        "width-proportion.png, vault.png, sections.png, folding-motion.png (they need "
        "matplotlib: pip install 'curvefold[plot]')"
    ]
    r = _without_matplotlib(
        "atlas",
        "--p-xy",
        "0.75",
        "--a",
        "0.3,1.5",
        "--samples",
        "41",
        "--workers",
        "1",
        "--out",
        "a",
        cwd=tmp_path,
    )
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert r.stdout.splitlines()[1:] == [
        "  pictures left out: atlas.png, atlas.svg (they need "
        "matplotlib: pip install 'curvefold[plot]')"
    ]
    assert sorted(os.listdir(tmp_path / "a")) == [".curvefold-output", "atlas.csv", "atlas.json"]


def test_without_matplotlib_a_format_that_needs_it_is_refused_before_any_work_naming_the_extra(
    tmp_path,
):
    r = _without_matplotlib(
        "tube", "--samples", "41", "--formats", "fold,gif", "--out", "t", cwd=tmp_path
    )
    assert (
        r.returncode == 2
        and r.stderr.strip()
        == "curvefold: error: formats: gif needs matplotlib: pip install 'curvefold[plot]'"
    )
    assert os.listdir(tmp_path) == []


def test_with_matplotlib_the_pictures_are_drawn_and_nothing_is_left_out(tmp_path):
    pytest.importorskip("matplotlib")
    r = run("tube", "--samples", "41", "--formats", "fold", "--out", "t", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    payload = json.loads(r.stdout)
    assert "notes" not in payload and {
        "regression-domain.png",
        "width-proportion.png",
        "tube.png",
    } <= set(payload["files"])


def test_an_output_folder_is_removed_whole_when_a_file_appears_during_the_walk(
    tmp_path, monkeypatch
):
    import shutil

    from curvefold.app import _folder

    folder, walks = tmp_path / "f", []
    folder.mkdir()
    real = shutil.rmtree

    def walk(path, ignore_errors=False):
        real(path, ignore_errors=ignore_errors)
        if not walks:  # a stopped job's last file, written as the first walk ended
            path.mkdir()
            (path / "late.png").write_bytes(b"x")
        walks.append(path)

    monkeypatch.setattr(_folder.shutil, "rmtree", walk)
    _folder._remove(folder)
    assert not folder.exists() and len(walks) == 2
