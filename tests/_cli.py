"""Running the command line in tests: in this process (fast), or the real entry point in a
subprocess."""

from __future__ import annotations

import contextlib
import io
import os
import subprocess
import sys
from dataclasses import dataclass

from curvefold.app.cli import main


@dataclass(frozen=True)
class Result:
    """Exit status and output of one run."""

    returncode: int
    stdout: str
    stderr: str


def run(*argv: str, cwd=None) -> Result:
    """``curvefold *argv`` in this process, from folder ``cwd``: exit status, stdout and stderr."""
    out, err = io.StringIO(), io.StringIO()
    with (
        contextlib.chdir(cwd or os.getcwd()),
        contextlib.redirect_stdout(out),
        contextlib.redirect_stderr(err),
    ):
        code = main(list(argv))
    return Result(code, out.getvalue(), err.getvalue())


def run_subprocess(*argv: str, cwd=None) -> subprocess.CompletedProcess:
    """``python -m curvefold *argv``: exit codes and stderr exactly as a user sees them."""
    return subprocess.run(
        [sys.executable, "-m", "curvefold", *argv],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
    )
