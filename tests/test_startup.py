"""Start-up: a quick command imports what it needs, not the heavy libraries of the others.

Each case runs in a fresh interpreter and lists which of :data:`HEAVY` ended up in
``sys.modules``; an eager import of one of them anywhere on the way (a package's
``__init__``, the command line's module, a spec a parser reads) makes the case fail. The
public names stay importable as before: the packages resolve them when first read
(:mod:`curvefold.kernel._exports`). Speed itself is measured in ``benchmarks/bench_startup.py``.
"""

from __future__ import annotations

import importlib
import json
import subprocess
import sys
import types

import pytest

import curvefold
import curvefold.io

#: Libraries only some commands need (fitting, plotting, meshes, DXF).
HEAVY = ("scipy", "matplotlib", "trimesh", "ezdxf")


def imported(code: str, names=HEAVY) -> list[str]:
    """Which of ``names`` (packages or modules) running ``code`` in a fresh interpreter imports."""
    probe = (
        f"{code}\nimport json, sys\nprint(json.dumps([n for n in {list(names)!r} if n in "
        "sys.modules]))"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.splitlines()[-1])


def test_the_probe_sees_an_eager_import():
    assert imported("import curvefold.app.cli\nimport scipy.optimize") == ["scipy"]
    assert imported("import matplotlib.figure, ezdxf") == ["matplotlib", "ezdxf"]
    assert imported("import curvefold.io._formats", ["curvefold.io._pattern"]) == []
    assert imported("import curvefold.io._pattern", ["curvefold.io._pattern"]) == [
        "curvefold.io._pattern"
    ]


CASES = {
    "import curvefold": "import curvefold",
    "import curvefold.app.cli": "import curvefold.app.cli",
    "curvefold --help": "import contextlib, io\nfrom curvefold.app.cli import main\nwith "
    "contextlib.redirect_stdout(io.StringIO()), contextlib.suppress(SystemExit):\n    "
    "main(['--help'])",
    "curvefold arch --json": "import contextlib, io\nfrom curvefold.app.cli import main\nwith "
    "contextlib.redirect_stdout(io.StringIO()):\n    assert main(['arch', '--a', '0.3', "
    "'--json']) == 0",
    "a name of curvefold and of curvefold.io": "from curvefold import Crease, Structure, "
    "measure\nfrom curvefold.io import FoldFile, CUTTERS",
}


@pytest.mark.parametrize("case", CASES)
def test_quick_commands_import_no_heavy_library(case):
    assert imported(CASES[case]) == []


#: What the command line's start does not need: the writers, the certificate, the FOLD
#: check and the package metadata (whose reader imports the email package).
NOT_AT_START = (
    "curvefold.io._pattern",
    "curvefold.io._fold",
    "curvefold.io._gltf",
    "curvefold.analysis._checks",
    "curvefold.analysis._foldcheck",
    "curvefold.vault._atlas",
    "curvefold.vault._sweep",
    "importlib.metadata",
    "tomllib",
)


def test_the_command_line_starts_without_what_other_commands_need():
    assert imported(CASES["curvefold --help"], NOT_AT_START) == []
    assert imported(CASES["curvefold arch --json"], NOT_AT_START) == []


@pytest.mark.parametrize("package", [curvefold, curvefold.io], ids=lambda p: p.__name__)
def test_public_names_resolve_to_their_modules(package):
    for name in package.__all__:
        value = getattr(package, name)
        home = getattr(value, "__module__", None)
        if isinstance(value, types.ModuleType):
            # a module, perhaps private
            assert value.__name__.rpartition(".")[2].lstrip("_") == name
        elif home is not None:  # a class or function: the object its module defines
            assert getattr(importlib.import_module(home), name) is value, name
        assert name in dir(package)
    with pytest.raises(
        AttributeError, match=f"module '{package.__name__}' has no attribute 'Nothing'"
    ):
        package.Nothing  # noqa: B018


def test_from_imports_work_as_before():
    from curvefold import Crease, InputError, __version__, measure
    from curvefold.geometry import Crease as defined
    from curvefold.io import write_svg
    from curvefold.io import write_svg as written
    from curvefold.kernel import InputError as raised

    assert (Crease, InputError, write_svg) == (defined, raised, written)
    assert (
        measure.__name__ == "curvefold.analysis._measure" and __version__ == curvefold.__version__
    )


#: What no job of the main job needs: its output folder is written with NumPy, Pillow, ezdxf and
#: rhino3dm alone (each import is paid again in every job process that makes it), and without
#: NumPy's masked arrays, which ``np.unique`` imports (``kernel._arrays.distinct`` does not).
NOT_IN_THE_MAIN_JOB = ("scipy", "matplotlib", "pygltflib", "trimesh", "numpy.ma")


@pytest.mark.slow
def test_the_main_job_imports_neither_scipy_nor_matplotlib(tmp_path):
    """Every file and picture of the paper's vault (at fewer samples), written in this one
    process."""
    code = (
        "from curvefold.app import default_design\n"
        "from curvefold.app._build import build\n"
        "from curvefold.app._folder import check_output\n"
        "from curvefold.app._outputs import write_outputs\n"
        "from dataclasses import replace\n"
        "design = replace(default_design('vault'), samples=201)\n"
        f"folder = check_output({str(tmp_path / 'v')!r}, force=True)\n"
        "files = write_outputs(build(design), folder, show_progress=False, workers=1)['files']\n"
        "assert {'vault.fold', 'vault.glb', 'vault.3dm', 'vault-pattern.dxf', 'folding.gif',\n"
        "        'vault.png'} <= set(files), files"
    )
    assert imported(code, NOT_IN_THE_MAIN_JOB) == []
    # the probe sees one (and its numpy.ma)
    assert "scipy" in imported(code + "\nimport scipy.sparse", NOT_IN_THE_MAIN_JOB)
    assert imported(
        code + "\nimport numpy as np\nnp.unique(np.arange(3))", NOT_IN_THE_MAIN_JOB
    ) == ["numpy.ma"]


def test_a_progress_bar_imports_rich_only_for_a_terminal():
    """The main job draws its progress on stderr when that is a terminal (a pseudo-terminal
    here); a log of stderr gets no bar, and the process does not import rich for one."""
    quiet = (
        "from curvefold.app._outputs import _bar, _progress\nassert _bar(True) is "
        "None\n_progress(True, 3)[0]('a')"
    )
    assert imported(quiet, ["rich"]) == []
    terminal = (
        "import os, sys\nfrom curvefold.app._outputs import _bar\n_, slave = "
        "os.openpty()\nsys.stderr = os.fdopen(slave, 'w')\nbar = _bar(True)\nassert bar is not "
        "None and bar.console.is_terminal"
    )
    assert imported(terminal, ["rich"]) == ["rich"]
