"""The command line's messages as a person reads them: usage errors, a closed pipe, the help."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys

import pytest

from _cli import run
from curvefold.app.cli import main

#: A folded form of three triangles (the FOLD library's first example, cut down).
_FOLD = {
    "file_spec": 1,
    "frame_classes": ["foldedForm"],
    "vertices_coords": [[0, 1, 0], [0, 0, 1], [0, -1, 0], [1, 0, 0]],
    "faces_vertices": [[0, 1, 2], [0, 2, 3]],
    "edges_vertices": [[0, 2], [0, 1], [1, 2], [2, 3], [0, 3]],
    "edges_assignment": ["V", "B", "B", "B", "B"],
}


@pytest.mark.parametrize(
    ("argv", "line"),
    [
        (["vault", "--pxy", "0.8"], "unrecognized arguments: --pxy; did you mean --p-xy?"),
        (
            ["vault", "--fold_angle", "80"],
            "unrecognized arguments: --fold_angle; did you mean --fold-angle?",
        ),
        (
            ["tube", "--a", "0.5"],
            "unrecognized arguments: --a; --a is a flag of curvefold vault, curvefold load, "
            "curvefold deploy, curvefold arch and curvefold atlas, not of curvefold tube",
        ),
        (
            ["crease", "--panels", "4"],
            "unrecognized arguments: --panels; --panels is a flag of curvefold vault, curvefold "
            "tube, curvefold block, curvefold load and curvefold deploy, not of curvefold crease",
        ),
        (["--zz"], "unrecognized arguments: --zz"),
        # flags are taken whole: an abbreviation is not one of them
        (["vault", "--samp", "201"], "unrecognized arguments: --samp; did you mean --samples?"),
    ],
)
def test_an_unknown_flag_is_one_line_with_the_nearest_flag(argv, line):
    result = run(*argv)
    assert result.returncode == 2
    assert result.stderr == f"curvefold: error: {line}\n"


def test_a_command_usage_error_names_the_command_once():
    result = run("vault", "--samples")
    assert result.returncode == 2
    assert (
        result.stderr
        == "curvefold: error: curvefold vault: argument --samples: expected one argument\n"
    )


@pytest.mark.parametrize(
    ("argv", "status"),
    [
        (["check", "form.fold"], 141),
        (["arch"], 141),
        (["arch", "--json"], 141),
        (["reproduce"], 141),
        (["--help"], 0),  # argparse drops its help quietly when nobody reads it
    ],
)
def test_a_reader_that_stops_early_ends_the_run_quietly(tmp_path, argv, status):
    (tmp_path / "form.fold").write_text(json.dumps(_FOLD), encoding="utf-8")
    with subprocess.Popen(
        [sys.executable, "-m", "curvefold", *argv],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    ) as process:
        assert process.stdout is not None and process.stderr is not None
        process.stdout.close()  # the reader is gone before the first line (`| head -0`)
        stderr = process.stderr.read().decode()
        assert process.wait(timeout=120) == status
    assert stderr == ""


def test_a_flag_true_by_default_says_what_it_turns_off(capsys):
    with pytest.raises(SystemExit):
        main(["load", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "do not the" not in text
    assert (
        "--no-self-weight the sheet's own weight loads it by default; this flag turns it off "
        "(sets self_weight = false)"
    ) in text
    assert (
        "--no-glue-tabs draw glue tabs along the seams of the crease patterns by default; this "
        "flag turns it off (sets glue_tabs = false)"
    ) in text


@pytest.mark.parametrize("command", ["vault", "load"])
def test_the_output_folder_is_checked_before_the_inverse_design(tmp_path, monkeypatch, command):
    from curvefold.app import _cli_commands, cli

    def never(*args, **kwargs):
        raise AssertionError("the targets were fitted before the output folder was checked")

    monkeypatch.setattr(_cli_commands, "_fit_targets", never)
    monkeypatch.setattr(cli, "_fit_targets", never)
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("kept", encoding="utf-8")
    result = run(command, "--span", "2", "--rise", "1.4", "--out", "mine", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith(
        "curvefold: error: output folder mine exists and was not written by curvefold"
    )
    assert (tmp_path / "mine" / "notes.txt").read_text(encoding="utf-8") == "kept"


def test_out_of_reach_says_which_target_to_change_and_by_how_much():
    result = run("vault", "--span", "3", "--rise", "2.9", "--tubes", "9", "--samples", "41")
    assert result.returncode == 2 and result.stderr.count("\n") == 1
    line = result.stderr
    assert "reach rise/span from 0.52" in line and line.count(" from ") == 1  # one range
    change = re.search(
        r"to reach it, lower the rise to ([\d.]+) \(by ([\d.]+)\) for span 3, "
        r"or raise the span to ([\d.]+) \(by ([\d.]+)\) for rise 2.9",
        line,
    )
    assert change, line
    rise, by_rise, span, by_span = map(float, change.groups())
    assert math.isclose(rise + by_rise, 2.9, rel_tol=1e-5)
    assert math.isclose(span - by_span, 3.0, rel_tol=1e-5)
    # each change reaches: the family has a vault of that rise (or span)
    from curvefold.vault._assembly import VaultDesign
    from curvefold.vault._targets import fit_targets

    base = VaultDesign(tubes=9, samples=41)
    assert fit_targets(base, span=3.0, rise=rise).reached
    assert fit_targets(base, span=span, rise=2.9).reached
