"""The command line's messages as a person reads them: usage errors, a closed pipe, the help."""

from __future__ import annotations

import json
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
            "curvefold arch and curvefold atlas, not of curvefold tube",
        ),
        (
            ["crease", "--panels", "4"],
            "unrecognized arguments: --panels; --panels is a flag of curvefold vault, curvefold "
            "tube, curvefold block and curvefold load, not of curvefold crease",
        ),
        (["--zz"], "unrecognized arguments: --zz"),
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
