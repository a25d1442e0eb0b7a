"""The command line under attack: every bad input of the catalogue, through the real entry point.

The promise: a user error is one line on stderr and exit status 2, never a traceback; no
partial output; a folder is replaced only with ``--force`` and only if curvefold wrote it
(or it is empty); a signal removes what the run had started and exits with 128 + its
number; results are strict JSON; memory is budgeted before any work.

Organised by class: flags, design files, FOLD files, paths, signals, concurrency,
resources, injection. Runs go through :func:`curvefold.app.cli.main` in this process
(``run``), and through ``python -m curvefold`` or the console script in a subprocess
where a real process matters (signals, concurrency, warnings, FIFOs).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import curvefold.app._build
from _cli import run, run_subprocess
from curvefold.app import _folder as folder
from curvefold.app import design_from_dict
from curvefold.app._budget import estimate

EXAMPLES = Path(__file__).parent.parent / "examples"


def refused(r, match: str, *, code: int = 2) -> str:
    """Assert one line on stderr matching ``match``, the exit status and nothing on stdout."""
    lines = r.stderr.splitlines()
    assert r.returncode == code, (r.returncode, r.stderr, r.stdout[:300])
    assert len(lines) == 1 and lines[0].startswith("curvefold: "), r.stderr
    assert "Traceback" not in r.stderr
    assert re.search(match, lines[0]), lines[0]
    assert r.stdout == ""
    return lines[0]


def listing(path: Path) -> list[str]:
    """Every entry of a folder, hidden ones too."""
    return sorted(os.listdir(path))


# ---------------------------------------------------------------------------------------------
# Flags


@pytest.mark.parametrize(
    ("argv", "match"),
    [
        (["tube", "--samples", "3"], r"--samples 3: samples must be an integer in \[9, 200000\]"),
        (
            ["tube", "--samples", "8"],
            r"samples must be an integer in \[9, 200000\] \(the "
            r"certificate's differences need 9",
        ),
        (["block", "--samples", "5"], r"samples must be an integer in \[9, 200000\]"),
        (["crease", "--samples", "8"], r"samples must be an integer in \[9, 200000\]"),
        (
            ["arch", "--a", "5000"],
            r"--a 5000: a must be in \[0, 1\.2707093728\) \(no arch stands "
            r"beyond it: Eq\. \(20\) has no root next to π there\), got 5000$",
        ),
        (
            ["arch", "--a", "1e154"],
            r"--a 1e154: a must be in \[0, 1\.2707093728\) \(no arch "
            r"stands beyond it: Eq\. \(20\) has no root next to π there\), got 1e154$",
        ),
        # was exit 0 with an invented root
        (
            ["arch", "--a", "1e10", "--json"],
            r"a must be in \[0, 1\.2707093728\) \(no arch stands "
            r"beyond it: Eq\. \(20\) has no root next to π there\), got 1e10$",
        ),
        (
            ["arch", "--a", "1e5", "--json"],
            r"a must be in \[0, 1\.2707093728\) \(no arch stands "
            r"beyond it: Eq\. \(20\) has no root next to π there\), got 1e5$",
        ),
        # was "expected one argument"
        (
            ["arch", "--a", "-1e-3"],
            r"--a -1e-3: a must be in \[0, 1\.2707093728\) \(no arch "
            r"stands beyond it: Eq\. \(20\) has no root next to π there\), got -1e-3$",
        ),
        (
            ["arch", "--a", "2"],
            r"--a 2: a must be in \[0, 1\.2707093728\) \(no arch stands "
            r"beyond it: Eq\. \(20\) has no root next to π there\), got 2$",
        ),
        (
            ["arch", "--a", "1.2", "--fold-angle", "0.1"],
            r"proportion change .* overflows for a = "
            r"1\.2 at fold angle 2α = 0\.1°: the fold angle must be at least 0\.481°$",
        ),
        (["arch", "--a", "nan"], r"a must be a finite number, got nan"),
        # blamed "length"
        (
            ["vault", "--radius", "1e308"],
            r"--radius 1e308: radius must be in \[0\.001, 1000000\] " r"model units",
        ),
        # blamed "count (tubes)"
        (
            ["vault", "--radius", "1e-308"],
            r"--radius 1e-308: radius must be in \[0\.001, " r"1000000\]",
        ),
        (["vault", "--tubes", "0"], r"--tubes 0: tubes must be an integer in \[1, 1000\]"),
        (
            ["atlas", "--a", "5000"],
            r"--a 5000: a must be in \[0, 2\.5414187456\] \(up to twice "
            r"1\.2707, where arches stop standing\), got 5000",
        ),
        (["atlas", "--a", "nan:1:3"], r"--a nan:1:3: a must be a finite number, got nan"),
        (["atlas", "--a", "0:inf:3"], r"--a 0:inf:3: a must be a finite number, got inf"),
        (
            ["atlas", "--a", "0:1:201"],
            r"--a 0:1:201: count must be an integer in \[1, 200\], got " r"201",
        ),
        (["atlas", "--p-xy", "1,2,x"], r"--p-xy: must be a number, got 'x'"),
        (
            ["atlas", "--p-xy", "0:1"],
            r"--p-xy: expected start:stop:count or a comma-separated " r"list",
        ),
        (
            ["atlas", "--workers", str(os.cpu_count() + 1)],  # 50 workers took 3 GB
            rf"--workers {os.cpu_count() + 1}: workers must be an integer in \[1, "
            rf"{os.cpu_count()}\] \(the {os.cpu_count()} CPUs? this process may use\)",
        ),
        (["atlas", "--workers", "0"], r"workers must be an integer in \[1, \d+\]"),
        (["atlas", "--samples", "10"], r"--samples 10: samples must be ≥ 21 for a vault"),
        (["atlas", "--width", "-1"], r"--width -1: width must be in \(0, 10\]"),
        # internal errors before: ZeroDivisionError in the certificate (zero-length panel sides),
        # OverflowError, NaN
        (
            [
                "tube",
                "--panels",
                "64",
                "--fold-angle",
                "5",
                "--width-left",
                "0.02",
                "--width-right",
                "0.02",
                "--json",
            ],
            r"width_left w\(t\) = 2\.32e-14 at s = 6 is below 1e-09 of the structure's size",
        ),
        (
            ["tube", "--width-left", "1e-300", "--width-right", "1e-300", "--json"],
            r"width_left " r"w\(t\) = .* is below 1e-09 of the structure's size",
        ),
        (
            ["tube", "--tau", "tan(s)", "--samples", "101", "--length", "6", "--json"],
            r"(is below 1e-09 " r"of the structure's size|passes the curve of regression)",
        ),
        (
            ["arch", "--a", "0", "--fold-angle", "5e-324"],
            r"fold_angle 2α = 5e-324° is 0 in " r"radians \(below the smallest positive float\)",
        ),
        (
            ["tube", "--fold-angle", "5e-324", "--json"],
            r"fold_angle must be in \(0°, 180°\), got " r"5e-324 \(0 in radians",
        ),
        # a crease pattern collapsed to one point, exit 0
        (
            ["tube", "--scale", "5e-324", "--formats", "svg", "--out", "t"],
            r"\[output\] scale: 4\.94066e-324 mm per model unit draws the 6-unit crease 2\.96e-323 "
            r"mm long, shorter than the 10 mm scale bar",
        ),
        # values in range that broke the solvers: an ARPACK internal error (exit 1), NaN in JSON
        (
            ["load", "--tubes", "1", "--samples", "41", "--thickness", "1e-9", "--json"],
            r"error: thickness 1e-09 m is too thin for elements of 0\.076 m: "
            r".* give at least 7\.6e-07 m$",
        ),
        (
            ["load", "--tubes", "1", "--samples", "41", "--crease-stiffness", "1e300"],
            r"error: crease_stiffness 1e\+300 N·m/rad/m is .* give at most 1\.7e\+11 N·m/rad/m$",
        ),
        (
            ["load", "--youngs-modulus", "1e300", "--poisson", "0.3", "--density", "900"],
            r"youngs_modulus must be in \[1000, 1e13\] Pa .*got 1e300$",
        ),
        (
            ["vault", "--scale", "0.001", "--units", "m", "--json"],
            r"scale: 0\.001 m per model " r"unit draws the 3\.14159-unit crease 3\.14 mm long",
        ),
    ],
)
def test_flags(tmp_path, argv, match):
    refused(run(*argv, cwd=tmp_path), match)
    assert listing(tmp_path) == []  # refused before any work: nothing written


def test_a_memory_budget_of_too_many_digits_is_a_user_error(tmp_path, monkeypatch):
    """400 digits overflowed to infinity: OverflowError, reported as a bug."""
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "9" * 400)
    refused(
        run("tube", "--json", cwd=tmp_path),
        r"CURVEFOLD_MEMORY_BUDGET must be a memory size "
        r".* at most 1 PiB, got '9{20}'… \(400 characters\)$",
    )
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "2048P")
    refused(run("tube", "--json", cwd=tmp_path), r"CURVEFOLD_MEMORY_BUDGET must be a memory size")


def test_a_page_too_small_for_the_scale_is_refused_before_tabs(tmp_path):
    # --scale 1e308 overflowed to NaN inside the layout; 1e6 placed millions of glue tabs
    for scale, size in (("1e308", "inf × inf"), ("1e6", r"4\.098e\+06 × 3\.093e\+06")):
        refused(
            run(
                "tube",
                "--samples",
                "41",
                "--scale",
                scale,
                "--formats",
                "svg",
                "--out",
                "t",
                cwd=tmp_path,
            ),
            rf"sheet 'tube 1 · sheet A' needs {size} mm before glue tabs .* lower the "
            r"scale or choose a larger page",
        )
    assert listing(tmp_path) == []


# ---------------------------------------------------------------------------------------------
# Design files


@pytest.mark.parametrize(
    ("kind", "text", "match"),
    [
        (
            "tube",
            "[curve]\nlength = 1e308",
            r"d\.toml: \[curve\] length must be in \[0\.001, "
            r"1000000\] model units \(numerical range\), got 1e\+308$",
        ),
        (
            "tube",
            "[curve]\nlength = 1e-300",
            r"d\.toml: \[curve\] length must be in \[0\.001, " r"1000000\]",
        ),
        (
            "crease",
            "[crease]\nlength = 1e-300",
            r"d\.toml: \[crease\] length must be in " r"\[0\.001, 1000000\]",
        ),
        (
            "tube",
            "samples = 101\n[curve]\nlength = 1e4",
            r"error: width_left w\(t\) = "
            r"w\(0\)·exp\(-∫ τ cot α ds\) leaves the range of float64 at s = ",
        ),
        (
            "tube",
            'title = "vault\\nv 999 999 999"',
            r"d\.toml: title must be one line of "
            r"printable text; character 6 is the control character U\+000A$",
        ),
        (
            "tube",
            'title = "\\u001b[2J\\u001b[31mred"',
            r"d\.toml: title must be one line " r".*control character U\+001B$",
        ),
        ("tube", 'title = "abc\\u202etxt.exe"', r"d\.toml: title .*control character U\+202E$"),
        (
            "tube",
            "[curve]\ntau = \"__import__('os').system('echo hacked')\"",
            r"d\.toml: " r"\[curve\] tau: only plain function names can be called",
        ),
        (
            "tube",
            '[curve]\ntau = "(lambda: 1)()"',
            r"d\.toml: \[curve\] tau: only plain " r"function names can be called",
        ),
        (
            "tube",
            '[curve]\ntau = "s.__class__"',
            r"d\.toml: \[curve\] tau: attribute access is " r"not allowed",
        ),
        (
            "tube",
            "[curve]\ntau = \"open('/etc/passwd')\"",
            r"d\.toml: \[curve\] tau: function " r"'open' is not allowed",
        ),
        (
            "tube",
            '[curve]\ntau = "9**9**9"',
            r"d\.toml: \[curve\] tau: constant exponent .* is " r"out of range",
        ),
        (
            "tube",
            '[curve]\ntau = "s' + "+(s" * 60 + ")" * 60 + '"',
            r"d\.toml: \[curve\] tau: " r"expression is nested too deeply",
        ),
    ],
)
def test_design_files(tmp_path, kind, text, match):
    (tmp_path / "d.toml").write_text(f'kind = "{kind}"\n{text}\n', encoding="utf-8")
    refused(run(kind, "d.toml", "--out", "o", cwd=tmp_path), match)
    assert listing(tmp_path) == ["d.toml"]


def test_a_byte_order_mark_is_skipped(tmp_path):
    # was "Invalid statement"
    (tmp_path / "d.toml").write_bytes(b'\xef\xbb\xbfkind = "crease"\nsamples = 41\n')
    r = run("crease", "d.toml", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["design"]["samples"] == 41


def test_a_flat_sum_of_many_terms_is_not_nested(tmp_path):
    flat = "+".join(["0.01*s"] * 51)  # was "nested too deeply"
    (tmp_path / "d.toml").write_text(
        f'kind = "crease"\nsamples = 41\n[crease]\nkappa_2d = "0.5 + {flat}"\n'
    )
    r = run("crease", "d.toml", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr


def test_a_duplicate_csv_column_is_refused(tmp_path):
    (tmp_path / "k.csv").write_text("s,kappa,kappa\n0,1,2\n6,1,2\n")  # was used silently
    (tmp_path / "d.toml").write_text(
        'kind = "tube"\n[curve]\nkappa = {csv = "k.csv", column = "kappa"}\n'
    )
    refused(
        run("tube", "d.toml", "--json", cwd=tmp_path),
        r"d\.toml: \[curve\] kappa \(k\.csv\): column 'kappa' appears twice in the header "
        r"\(fields 2 and 3\)$",
    )


def test_a_singular_torsion_fails_the_certificate_not_the_program(tmp_path):
    # tau = sqrt(s) has an infinite derivative at s = 0: the geometry cannot be accurate there
    (tmp_path / "d.toml").write_text(
        'kind = "tube"\nsamples = 101\n[curve]\ntau = "sqrt(s)"\n[output]\nformats = ["fold"]\n'
    )
    r = run("tube", "d.toml", "--out", "o", cwd=tmp_path)
    assert r.returncode == 1 and r.stderr == "", r.stderr
    assert (
        re.search(r"certificate +\d+/\d+ checks pass", r.stdout)
        and (tmp_path / "o" / "report.html").exists()
    )


# ---------------------------------------------------------------------------------------------
# FOLD files


def _fold(**frame) -> dict:
    doc = {
        "vertices_coords": [[0, 0], [1, 0], [1, 1], [0, 1]],
        "edges_vertices": [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        "edges_assignment": ["B", "B", "B", "B", "V"],
        "edges_foldAngle": [0, 0, 0, 0, 90],
        "faces_vertices": [[0, 1, 2], [0, 2, 3]],
    }
    return doc | frame


def _chained(n: int) -> dict:
    """n frames, each inheriting from the one before: all flat, so the check finds no error."""
    return _fold(
        edges_foldAngle=[0] * 5,
        file_frames=[{"frame_inherit": True, "frame_parent": i} for i in range(n)],
    )


def test_a_folded_frame_of_another_topology_is_a_failed_check_and_no_mechanism(tmp_path):
    """FOLD lets a frame have its own edges; check reports it, mechanism refuses it, neither
    prints a traceback."""
    (tmp_path / "f.fold").write_text(
        json.dumps(
            _fold(
                file_frames=[
                    {
                        "frame_inherit": True,
                        "edges_vertices": [[0, 1], [1, 2], [2, 3], [3, 0], [1, 3]],
                    }
                ]
            )
        )
    )
    r = run("check", "f.fold", cwd=tmp_path)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert re.search(
        r"topology +fail .*frame 1 .* has other edges or faces than the crease " r"pattern",
        r.stdout,
    )
    refused(
        run("mechanism", "f.fold", cwd=tmp_path),
        r"^curvefold: error: f\.fold: frame 'frame "
        r"1' has other vertices, edges or faces than the crease pattern",
    )


@pytest.mark.parametrize(
    ("content", "match"),
    [
        (
            _fold(
                edges_vertices=[],
                edges_assignment=[],
                edges_foldAngle=[],
                file_frames=[{"frame_inherit": True}],
            ),
            r"\(key frame\): edges_vertices is empty: a crease pattern needs edges",
        ),
        (_fold(faces_vertices=[]), r"faces_vertices is empty"),
        ("[" * 100_000 + "]" * 100_000, r"not valid JSON: nested too deeply$"),
        (
            '{"vertices_coords": [[%s, 0]]}' % ("9" * 5000),
            r"it holds an integer of more than " r"4300 digits$",
        ),
        (
            _fold(vertices_coords=[[int("9" * 4000), 0], [1, 0], [1, 1], [0, 1]]),
            r"vertices_coords\[0\] "
            r"must hold numbers within ±1e\+100, got an integer of 4000 digits",
        ),
        (
            _fold(edges_vertices=[[0, 10**30], [1, 2], [2, 3], [3, 0], [0, 2]]),
            r"edges_vertices " r"holds an integer too large for an index",
        ),
        (_chained(3000), r"3000 frames in file_frames, more than curvefold reads \(1000\)$"),
        (
            _fold(
                file_frames=[
                    {"frame_inherit": True, "frame_parent": 2},
                    {"frame_inherit": True, "frame_parent": 1},
                ]
            ),
            r"closes a cycle of inheriting frames",
        ),
        ("", r"FOLD file is empty$"),
        (b"\xff\xfe", r"not UTF-8 text"),
    ],
)
def test_fold_files(tmp_path, content, match):
    path = tmp_path / "f.fold"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content if isinstance(content, str) else json.dumps(content))
    refused(run("check", "f.fold", cwd=tmp_path), r"^curvefold: error: f\.fold.*" + match)


def test_a_long_chain_of_frames_is_read_without_recursion(tmp_path):
    (tmp_path / "f.fold").write_text(json.dumps(_chained(999)))  # was a RecursionError at 3000
    r = run("check", "f.fold", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["frames"] == 999


@pytest.mark.parametrize(
    ("path", "kind"),
    [
        ("/dev/zero", "a character device"),
        ("/dev/urandom", "a character device"),
        (".", "a folder"),
    ],
)
def test_only_regular_files_are_read(tmp_path, path, kind):
    if not os.path.exists(path):
        pytest.skip(f"{path} does not exist here")
    refused(
        run("check", path, cwd=tmp_path),
        rf"cannot read FOLD file: it is {kind}, not a " r"regular file$",
    )
    refused(
        run("tube", path, cwd=tmp_path),
        rf"cannot read design file: it is {kind}, not a " r"regular file$",
    )


def test_a_fifo_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "pipe")  # reading it blocked until a writer came
    for argv in (["check", "pipe"], ["vault", "pipe"]):
        r = subprocess.run(
            [sys.executable, "-m", "curvefold", *argv],
            capture_output=True,
            text=True,
            cwd=tmp_path,
            timeout=60,
        )
        refused(r, r"cannot read (FOLD|design) file: it is a FIFO, not a regular file$")


def test_a_kernel_file_is_not_read_past_its_size(tmp_path):
    if not os.path.exists("/proc/kmsg"):
        pytest.skip("no /proc/kmsg here")
    # it reports 0 bytes: read as empty (or refused for permissions), never waited on
    r = subprocess.run(
        [sys.executable, "-m", "curvefold", "vault", "/proc/kmsg"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    refused(
        r,
        r"/proc/kmsg: (missing required key 'kind'|cannot read design file: Permission "
        r"denied|cannot read design file: Operation not permitted)",
    )


def test_files_past_the_size_limits_are_refused_unread(tmp_path):
    from curvefold.io._columns import MAX_CSV_BYTES
    from curvefold.io._fold_reading import MAX_FOLD_BYTES

    with open(tmp_path / "big.fold", "wb") as f:  # sparse: no disk used
        f.truncate(MAX_FOLD_BYTES + 1)
    refused(
        run("check", "big.fold", cwd=tmp_path),
        r"big\.fold: FOLD file is "
        rf"{MAX_FOLD_BYTES + 1} bytes, more than the limit of {MAX_FOLD_BYTES} bytes$",
    )
    # a 64 MB CSV took 7.2 GB and 112 s before being refused
    with open(tmp_path / "k.csv", "wb") as f:
        f.truncate(MAX_CSV_BYTES + 1)
    (tmp_path / "d.toml").write_text('kind = "tube"\n[curve]\nkappa = {csv = "k.csv"}\n')
    refused(
        run("tube", "d.toml", "--json", cwd=tmp_path),
        r"\(k\.csv\): CSV file is " rf"{MAX_CSV_BYTES + 1} bytes, more than the limit",
    )


def test_a_csv_is_read_row_by_row_within_bounds(tmp_path):
    (tmp_path / "d.toml").write_text('kind = "tube"\n[curve]\nkappa = {csv = "k.csv"}\n')
    (tmp_path / "k.csv").write_text("kappa\n" + "1\n" * 200_001)
    refused(
        run("tube", "d.toml", "--json", cwd=tmp_path),
        r"\(k\.csv\): more than 200000 data " r"rows \(at line 200002\)$",
    )
    (tmp_path / "k.csv").write_text("kappa," + "x," * 6000 + "\n")
    refused(
        run("tube", "d.toml", "--json", cwd=tmp_path),
        r"\(k\.csv\): line 1 is longer than " r"10000 characters$",
    )


# ---------------------------------------------------------------------------------------------
# Paths


@pytest.mark.parametrize("out", [".", "..", "/", "sub/..", "../.."])
@pytest.mark.parametrize("force", [[], ["--force"]])
def test_the_current_folder_and_its_parents_are_never_targets(tmp_path, out, force):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "mine.txt").write_text("mine")
    before = listing(tmp_path.parent)
    refused(
        run("crease", "--samples", "41", "--out", out, *force, cwd=tmp_path / "sub"),
        r"output folder .* is the current folder or contains it; name a new folder, e\.g\. "
        r"--out curvefold-output$",
    )
    # no ..old.XXXX folders
    assert listing(tmp_path / "sub") == ["mine.txt"] and listing(tmp_path.parent) == before


def test_force_replaces_only_a_folder_curvefold_wrote(tmp_path):
    mine = tmp_path / "photos"
    mine.mkdir()
    (mine / "precious.txt").write_text("mine")
    for force in ([], ["--force"]):
        refused(
            run("crease", "--samples", "41", "--out", "photos", *force, cwd=tmp_path),
            r"output folder photos exists and was not written by curvefold \(it has no "
            r"\.curvefold-output file and is not empty\)",
        )
    assert (mine / "precious.txt").read_text() == "mine"
    (tmp_path / "empty").mkdir()  # nothing to lose in an empty folder
    assert (
        run("crease", "--samples", "41", "--out", "empty", "--force", cwd=tmp_path).returncode == 0
    )
    marker = json.loads((tmp_path / "empty" / ".curvefold-output").read_text())
    assert marker["curvefold"] and len(marker["id"]) == 32
    assert listing(tmp_path) == ["empty", "photos"]


def test_a_link_a_file_and_a_folder_holding_an_input_are_refused(tmp_path):
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to(tmp_path / "real", target_is_directory=True)
    refused(
        run("crease", "--samples", "41", "--out", "link", "--force", cwd=tmp_path),
        r"output folder " r"link is a symbolic link",
    )
    (tmp_path / "file").write_text("x")
    line = refused(
        run("crease", "--samples", "41", "--out", "file", cwd=tmp_path),
        r"output path file " r"exists and is not a folder; choose another folder$",
    )
    assert "--force" not in line  # it suggested --force, which then failed
    assert run("crease", "--samples", "41", "--out", "c", cwd=tmp_path).returncode == 0
    (tmp_path / "c" / "d.toml").write_text('kind = "crease"\nsamples = 41\n')
    refused(
        run("crease", "c/d.toml", "--out", "c", "--force", cwd=tmp_path),
        r"output folder c " r"holds c/d\.toml, which this run reads",
    )
    # a table the design reads from inside the folder
    (tmp_path / "c" / "k.csv").write_text("kappa_2d\n0.5\n0.6\n")
    (tmp_path / "d.toml").write_text(
        'kind = "crease"\nsamples = 41\n[crease]\nkappa_2d = {csv = "c/k.csv"}\n'
    )
    refused(
        run("crease", "d.toml", "--out", "c", "--force", cwd=tmp_path),
        r"output folder c " r"holds .*/c/k\.csv, which this run reads",
    )
    refused(
        run("crease", "--out", "missing/c", cwd=tmp_path),
        r"cannot write missing/c: its " r"parent folder missing does not exist",
    )


def test_control_characters_in_a_path_are_shown_not_obeyed(tmp_path):
    # a newline split the message over two lines
    r = run("check", "a\nb\x1b[31m.fold", cwd=tmp_path)
    line = refused(
        r,
        r"^curvefold: error: a\\nb\\x1b\[31m\.fold: cannot read FOLD file: No such "
        r"file or directory$",
    )
    assert "\x1b" not in line


# ---------------------------------------------------------------------------------------------
# Signals


def _wait_for_temporary(folder_: Path, process: subprocess.Popen, timeout: float = 120.0) -> None:
    """Poll until the run's temporary output folder exists."""
    deadline = time.monotonic() + timeout
    while not any(name.startswith(".t.curvefold-") for name in os.listdir(folder_)):
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "the temporary folder never appeared"
        time.sleep(0.02)


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_a_signal_leaves_nothing_behind(tmp_path, signum):
    process = subprocess.Popen(
        [sys.executable, "-m", "curvefold", "tube", "--samples", "401", "--out", "t"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    _wait_for_temporary(tmp_path, process)
    process.send_signal(signum)
    out, err = process.communicate(timeout=120)
    assert process.returncode == 128 + signum, err
    assert err == f"curvefold: interrupted by {signal.Signals(signum).name}\n"
    assert listing(tmp_path) == []  # the 15-30 MB hidden folders piled up


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_a_signal_while_the_files_are_written_stops_every_job_process(tmp_path, signum):
    """The files are written by two job processes: a signal to the command stops them too."""
    import psutil

    process = subprocess.Popen(
        [sys.executable, "-m", "curvefold", "tube", "--samples", "801", "--out", "t"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 120
    jobs: list = []
    while len(jobs) < 2:
        assert process.poll() is None and time.monotonic() < deadline, (
            "the command ended before its job processes started"
        )
        jobs = psutil.Process(process.pid).children()
        time.sleep(0.02)
    process.send_signal(signum)
    out, err = process.communicate(timeout=120)
    assert (process.returncode, err) == (
        128 + signum,
        f"curvefold: interrupted by {signal.Signals(signum).name}\n",
    )
    _, alive = psutil.wait_procs(jobs, timeout=30)
    assert alive == [] and listing(tmp_path) == []


class _SignalInFinalizer:
    """Sends SIGTERM to this process when collected: the handler's exception is raised in a
    finalizer, where Python ignores it (as when a signal lands in a library's ``__del__``)."""

    def __del__(self):
        signal.raise_signal(signal.SIGTERM)


def test_a_signal_raised_where_python_ignores_exceptions_still_stops_the_run(tmp_path, monkeypatch):
    """The atlas once finished a sweep and exited 0 after printing "Exception ignored ... 15"."""
    build = curvefold.app._build.build

    def build_then_signal(*args, **kwargs):
        _SignalInFinalizer()  # collected at once
        return build(*args, **kwargs)

    monkeypatch.setattr(curvefold.app._build, "build", build_then_signal)
    r = run("crease", "--samples", "41", "--out", "c", cwd=tmp_path)
    assert (r.returncode, r.stderr, r.stdout) == (
        128 + signal.SIGTERM,
        "curvefold: interrupted by SIGTERM\n",
        "",
    )
    assert listing(tmp_path) == []  # nothing installed after the signal


def test_a_signal_ignored_in_a_finalizer_stops_a_command_without_output_folder(monkeypatch):
    from curvefold.app import cli

    def arch_then_signal(args):
        _SignalInFinalizer()
        return 0

    monkeypatch.setattr(cli, "cmd_arch", arch_then_signal)
    r = run("arch")
    assert (r.returncode, r.stderr) == (128 + signal.SIGTERM, "curvefold: interrupted by SIGTERM\n")


def test_stale_temporary_folders_of_gone_processes_are_removed(tmp_path):
    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    gone.wait()
    marker = json.dumps({"curvefold": "0", "id": "x"})
    for pid, name in ((gone.pid, "stale"), (os.getppid(), "alive")):
        (tmp_path / f".{name}.curvefold-{pid}-abc123").mkdir()
        (tmp_path / f".{name}.curvefold-{pid}-abc123" / ".curvefold-output").write_text(marker)
    (tmp_path / f".mine.curvefold-{gone.pid}-abc123").mkdir()  # our naming but not ours: no marker
    (tmp_path / f".mine.curvefold-{gone.pid}-abc123" / "keep.txt").write_text("x")
    assert run("crease", "--samples", "41", "--out", "c", cwd=tmp_path).returncode == 0
    assert listing(tmp_path) == [
        f".alive.curvefold-{os.getppid()}-abc123",
        f".mine.curvefold-{gone.pid}-abc123",
        "c",
    ]


# ---------------------------------------------------------------------------------------------
# Concurrency


def _appears_during_the_build(monkeypatch, make):
    """Run ``make()`` (another process creating or changing the target) after the build."""
    build = curvefold.app._build.build

    def build_then_interfere(design):
        built = build(design)
        make()
        return built

    monkeypatch.setattr(curvefold.app._build, "build", build_then_interfere)


@pytest.mark.parametrize("noreplace", ["renameat2", "lock on the parent"])
def test_a_folder_that_appears_meanwhile_is_never_replaced(tmp_path, monkeypatch, noreplace):
    if noreplace != "renameat2":
        monkeypatch.setattr(folder, "_renameat2", None)
    elif folder._renameat2 is None:
        pytest.skip("no renameat2 here")

    def mkdir():  # curvefold vault --out v & sleep 3; mkdir v; echo mine > v/precious.txt
        (tmp_path / "v").mkdir()
        (tmp_path / "v" / "precious.txt").write_text("mine")

    _appears_during_the_build(monkeypatch, mkdir)
    for force in ([], ["--force"]):  # force replaces only what was checked: nothing was there
        refused(
            run("crease", "--samples", "41", "--out", "v", *force, cwd=tmp_path),
            r"output folder v appeared while curvefold was running; it was left as it is, "
            r"and the new output is in v\.new(-2)?$",
        )
        shutil.rmtree(tmp_path / "v")
    assert listing(tmp_path) == ["v.new", "v.new-2"]
    assert all((tmp_path / name / "report.html").exists() for name in ("v.new", "v.new-2"))


def test_a_folder_replaced_meanwhile_by_another_run_is_kept(tmp_path, monkeypatch):
    assert run("crease", "--samples", "41", "--out", "v", cwd=tmp_path).returncode == 0

    def another_run():
        (tmp_path / "v" / ".curvefold-output").write_text(
            json.dumps({"curvefold": "0", "id": "another run"})
        )

    _appears_during_the_build(monkeypatch, another_run)
    refused(
        run("crease", "--samples", "41", "--out", "v", "--force", cwd=tmp_path),
        r"output folder v changed while curvefold was running; it was left as it is, and the "
        r"new output is in v\.new$",
    )
    assert json.loads((tmp_path / "v" / ".curvefold-output").read_text())["id"] == "another run"
    assert listing(tmp_path) == ["v", "v.new"]


@pytest.mark.parametrize("noreplace", ["renameat2", "lock on the parent"])
def test_rename_noreplace_never_replaces(tmp_path, monkeypatch, noreplace):
    if noreplace != "renameat2":
        monkeypatch.setattr(folder, "_renameat2", None)
    (tmp_path / "new").mkdir()
    for existing in ("empty", "full", "file"):
        target = tmp_path / existing
        target.mkdir() if existing != "file" else target.write_text("x")
        if existing == "full":
            (target / "x").write_text("x")
        with pytest.raises(FileExistsError):
            folder.rename_noreplace(tmp_path / "new", target)
        assert (tmp_path / "new").is_dir() and target.exists()
    folder.rename_noreplace(tmp_path / "new", tmp_path / "free")
    assert (tmp_path / "free").is_dir() and not (tmp_path / "new").exists()


@pytest.mark.slow
def test_two_runs_to_one_folder_lose_no_result(tmp_path):
    argv = [sys.executable, "-m", "curvefold", "crease", "--samples", "201", "--out", "c"]
    runs = [
        subprocess.Popen(
            argv, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        for _ in range(2)
    ]
    results = [(p.wait(timeout=300), p.communicate()[1]) for p in runs]
    # both exited 0 and one result disappeared
    assert sorted(code for code, _ in results) == [0, 2], results
    (err,) = [err for code, err in results if code == 2]
    assert re.fullmatch(
        r"curvefold: error: (output folder c appeared while curvefold was "
        r"running; it was left as it is, and the new output is in c\.new|output folder c "
        r"exists; pass --force to replace it)\n",
        err,
    ), err
    names = listing(tmp_path)
    assert names in (["c"], ["c", "c.new"]) and all(
        (tmp_path / n / "report.html").exists() for n in names
    )


# ---------------------------------------------------------------------------------------------
# Resources


@pytest.mark.parametrize(
    ("argv", "match"),
    [
        (
            ["vault", "--samples", "199999"],
            r"this job needs about \d+\.\d GiB of memory \(199999 "
            r"samples × 96 strips\), more than the budget of 2\.0 GiB "
            r"\(CURVEFOLD_MEMORY_BUDGET\); lower samples \(at most \d+ fit\), \[vault\] tubes "
            r"or layers",
        ),
        (
            ["vault", "--samples", "199999", "--tubes", "max", "--json"],
            r"this job needs about .* " r"\(199999 samples × 96 strips\)",
        ),
        (
            ["tube", "--samples", "200000", "--formats", "svg"],
            r"needs about .* lower samples "
            r"\(at most \d+ fit\), the formats written \(the crease patterns cost most\)$",
        ),
    ],
)
def test_jobs_over_the_memory_budget_are_refused_before_starting(
    tmp_path, monkeypatch, argv, match
):
    monkeypatch.delenv("CURVEFOLD_MEMORY_BUDGET", raising=False)
    refused(run(*argv, cwd=tmp_path), match)
    assert listing(tmp_path) == []


def test_a_block_of_ten_thousand_cells_is_refused_before_starting(tmp_path, monkeypatch):
    monkeypatch.delenv("CURVEFOLD_MEMORY_BUDGET", raising=False)
    cells = ", ".join(f"[{i}, {j}]" for i in range(100) for j in range(100))
    (tmp_path / "d.toml").write_text(f'kind = "block"\n[block]\ncells = [{cells}]\n')
    refused(
        run("block", "d.toml", cwd=tmp_path),
        r"needs about .* \(801 samples × 40000 " r"strips\).* \[block\] cells",
    )


def test_the_largest_atlas_fits_the_budget_and_a_smaller_budget_refuses_it_before_starting(
    tmp_path, monkeypatch
):
    """Records stream to disk, so the 200 × 200 atlas (a MemoryError once) fits the default
    budget; its estimate is still checked, and refused before any work when over it."""
    from curvefold.app._budget import memory_budget, require_atlas_budget

    monkeypatch.delenv("CURVEFOLD_MEMORY_BUDGET", raising=False)
    assert require_atlas_budget(40_000, samples=201, workers=2) < memory_budget()
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "300M")
    refused(
        run("atlas", "--p-xy", "0.5:1.5:200", "--a", "0:1.2:200", cwd=tmp_path),
        r"this atlas needs about \d+ MiB of memory \(40000 designs, 201 samples, \d "
        r"processes\)",
    )
    assert listing(tmp_path) == []


def test_tubes_max_is_budgeted_like_the_cap():
    vault = {"kind": "vault", "samples": 1001}
    assert estimate(design_from_dict(vault | {"vault": {"tubes": "max"}}), files=True) == estimate(
        design_from_dict(vault | {"vault": {"tubes": 24}}), files=True
    )


def test_the_budget_is_set_by_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "50M")
    refused(
        run("crease", "--json", cwd=tmp_path),
        r"needs about \d+ MiB of memory .* more than " r"the budget of 50 MiB",
    )
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "lots")
    refused(
        run("crease", "--json", cwd=tmp_path),
        r"CURVEFOLD_MEMORY_BUDGET must be a memory "
        r"size such as 2G, 512M or a number of bytes, at most 1 PiB, got 'lots'",
    )


def test_out_of_memory_is_one_line(tmp_path, monkeypatch):
    def exhausted(design):
        raise MemoryError

    monkeypatch.setattr(curvefold.app._build, "build", exhausted)
    refused(
        run("crease", "--json", cwd=tmp_path),
        r"^curvefold: error: out of memory; lower " r"samples",
    )


def test_warnings_never_come_before_the_line(tmp_path, monkeypatch, capsys):
    # widths of e^±200 along the tube: NumPy warned in the measurements (up to 94 lines were
    # printed); such widths are now refused before any measurement, in one line
    (tmp_path / "d.toml").write_text('kind = "tube"\nsamples = 101\n[curve]\nlength = 1000.0\n')
    quiet = run_subprocess("tube", "d.toml", "--json", cwd=tmp_path)
    assert "Warning" not in quiet.stderr and len(quiet.stderr.splitlines()) == 1, quiet.stderr
    # a warning on the way to an error is kept back, and printed after the line with --debug
    from curvefold.app import cli
    from curvefold.kernel import InputError

    def noisy(kind, args):
        np.exp(np.array([1000.0]))  # overflow: a RuntimeWarning
        raise InputError("refused")

    monkeypatch.setattr(cli, "cmd_structure", noisy)
    assert (
        cli.main(["tube", "--json"]) == 2
        and capsys.readouterr().err == "curvefold: error: refused\n"
    )
    assert cli.main(["tube", "--json", "--debug"]) == 2
    loud = capsys.readouterr().err
    assert (
        loud.startswith("curvefold: error: refused\n")
        and "RuntimeWarning: overflow encountered in exp" in loud
    )


# ---------------------------------------------------------------------------------------------
# Injection: a title, a label or a path never acts in a file or on the terminal


HOSTILE = (
    "vault\nv 999 999 999\r\nmtllib ../../evil.mtl\x1b[2J\u202e <script>alert(1)</script> "
    "$\\frac{ %%c \\"
)


@pytest.fixture(scope="module")
def small_tube():
    from curvefold.geometry import Crease, Lattice, SpaceCurve, Structure

    curve = SpaceCurve.from_curvature(1.0, 0.2, 3.0, samples=41)
    return Structure.tube(Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.3, 0.3))


def _clean(text: str) -> None:
    assert not re.search("[\x00-\x08\x0b-\x1f\x7f\u202e]", text), repr(text)


def test_obj_comments_hold_one_line(tmp_path, small_tube):
    import trimesh

    from curvefold.io import write_obj

    mesh = small_tube.state().mesh()
    path = write_obj(tmp_path / "t.obj", mesh, metadata={"title": HOSTILE}, name=HOSTILE)
    text = path.read_text()
    _clean(text)
    assert not re.search(r"^(v 999|mtllib)", text, re.MULTILINE)  # the title injected both
    assert not any(line.endswith("\\") for line in text.splitlines())  # a line continuation
    assert len(trimesh.load(path, force="mesh", process=False).vertices) == len(
        mesh.vertices_coords
    )


def test_glb_3dm_and_fold_hold_the_title_on_one_line(tmp_path, small_tube):
    import pygltflib
    import rhino3dm

    from curvefold.io import (
        FoldOutput,
        GlbOptions,
        RhinoOptions,
        read_fold,
        write_3dm,
        write_glb,
        write_sheet_fold,
        write_structure_fold,
    )

    state = small_tube.state().mesh()
    glb = write_glb(tmp_path / "t.glb", state, options=GlbOptions(metadata={"title": HOSTILE}))
    title = pygltflib.GLTF2().load(str(glb)).asset.extras["curvefold"]["metadata"]["title"]
    _clean(title)
    # the text stays
    assert title.startswith("vault v 999 999 999 mtllib") and title.endswith("$\\frac{ %%c \\")
    topology = small_tube.topology("quads")
    quads = topology.mesh(small_tube.state().vertices)
    model = rhino3dm.File3dm.Read(
        str(
            write_3dm(
                tmp_path / "t.3dm",
                quads,
                topology,
                options=RhinoOptions(metadata={"title": HOSTILE}),
            )
        )
    )
    _clean(model.Strings["curvefold:title"])
    fold = write_structure_fold(
        tmp_path / "t.fold",
        small_tube,
        title=HOSTILE,
        output=FoldOutput(metadata={"title": HOSTILE}),
    )
    doc = json.loads(fold.read_text())
    _clean(doc["file_title"])
    _clean(doc["curvefold:metadata"]["title"])
    assert read_fold(fold).metadata["title"] == doc["curvefold:metadata"]["title"]
    from curvefold.geometry._sheets import sheets

    sheet = json.loads(
        write_sheet_fold(tmp_path / "s.fold", sheets(small_tube)[0].mesh, title=HOSTILE).read_text()
    )
    _clean(sheet["file_title"])


def test_pattern_pages_show_a_hostile_label_as_text(tmp_path, small_tube):
    import xml.etree.ElementTree as ET

    import ezdxf

    from curvefold.io import PatternOutput, write_pattern

    # "$\frac{" broke mathtext
    files = write_pattern(
        tmp_path / "p", small_tube, PatternOutput(name=HOSTILE), formats=("svg", "dxf", "pdf")
    )
    svg = next(f for f in files if str(f).endswith(".svg"))
    texts = [t.text for t in ET.parse(svg).iter("{http://www.w3.org/2000/svg}text")]
    assert any("<script>" in t for t in texts)  # parsed back as text, not as an element
    for t in texts:
        _clean(t)
    dxf = next(f for f in files if str(f).endswith(".dxf"))
    for entity in ezdxf.readfile(dxf).modelspace().query("TEXT"):
        _clean(entity.dxf.text)
    assert next(f for f in files if str(f).endswith(".pdf")).stat().st_size > 1000


def test_the_report_and_the_terminal_escape_a_title(tmp_path):
    from curvefold.figures import report_html

    html = report_html({"title": HOSTILE, "kind": "tube", "certificate": []})
    assert "<script>alert" not in html and "&lt;script&gt;" in html
    _clean(html.split("<title>")[1].split("</title>")[0])
    (tmp_path / "d.toml").write_text(
        'kind = "crease"\nsamples = 41\ntitle = "<script>alert(1)</script> $\\\\frac{ %%c"\n'
    )
    r = run("crease", "d.toml", "--out", "c", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("<script>alert(1)</script> $\\frac{ %%c\n")
    assert "&lt;script&gt;" in (tmp_path / "c" / "report.html").read_text()


# ---------------------------------------------------------------------------------------------
# Results: strict JSON, never a NaN, never an invented root


def test_a_non_finite_result_is_an_error_not_json(tmp_path, monkeypatch):
    import curvefold.vault._arch

    monkeypatch.setattr(curvefold.vault._arch, "proportion_change", lambda *a, **k: float("inf"))
    r = run("arch", "--json", cwd=tmp_path)  # printed "proportion_change": Infinity
    assert r.returncode == 1 and r.stdout == ""
    assert (
        "the result holds a number that is not finite: result.proportion_change = inf" in r.stderr
    )


def test_a_non_finite_result_is_never_written(tmp_path, monkeypatch):
    from curvefold.app import _outputs as outputs

    payload = outputs.structure_payload
    monkeypatch.setattr(
        outputs,
        "structure_payload",
        lambda built, **k: payload(built, **k) | {"span": float("nan")},
    )
    r = run("crease", "--samples", "41", "--out", "c", cwd=tmp_path)  # report.json held NaN
    assert (
        r.returncode == 1
        and "the result holds a number that is not finite: result.span = nan" in r.stderr
    )
    assert listing(tmp_path) == []


def test_the_smallest_fold_angle_named_works(tmp_path):
    r = run("arch", "--a", "1.2", "--fold-angle", "0.482", "--p-xy", "100", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert 1e300 < json.loads(r.stdout)["p_xz"] < np.inf


def test_json_output_is_strict(tmp_path):
    r = run("arch", "--a", "1.27", "--p-xy", "100", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout, parse_constant=lambda c: pytest.fail(f"not JSON: {c}"))
    assert out["residual"] <= 1e-12 and np.isfinite(out["p_xz"])


def test_the_console_script_keeps_the_promise(tmp_path):
    script = Path(sys.executable).with_name("curvefold")
    if not script.exists():
        pytest.skip("the console script is not installed next to this interpreter")
    r = subprocess.run(
        [str(script), "arch", "--a", "1e10", "--json"], capture_output=True, text=True, timeout=60
    )
    refused(
        r,
        r"^curvefold: error: --a 1e10: a must be in \[0, 1\.2707093728\) \(no arch stands "
        r"beyond it: Eq\. \(20\) has no root next to π there\), got 1e10$",
    )


def test_a_folder_name_of_255_bytes_is_written_and_nothing_is_left_beside_it(tmp_path):
    """The longest name a filesystem takes (255 bytes, here in two-byte characters) is written:
    the temporary folder beside it keeps 200 bytes of the name ("File name too long" before)."""
    name = "é" * 127 + "v"
    assert len(name.encode()) == 255
    r = run(
        "vault", "--samples", "101", "--tubes", "1", "--formats", "svg", "--out", name, cwd=tmp_path
    )
    assert r.returncode == 0, r.stderr
    assert listing(tmp_path) == [name] and (tmp_path / name / "report.html").is_file()
