"""Smoke test of an installed curvefold, run by scripts/check-dist.sh in a fresh virtual
environment.

    python smoke.py EXTRA      EXTRA: core, export, rhino, step, designer, dask or dev

Each run checks what its extra promises, from the installed package (run it outside the
source tree, so that ``import curvefold`` finds the wheel's copy): ``core`` builds a tube
and its FOLD file and checks them without matplotlib or any other extra installed, and
writes an output folder, its pictures left out with one line saying so; ``export`` writes
the 3D models and crease patterns; ``rhino`` writes a 3DM file and reads it back;
``step`` writes the STEP solids of a thick tube and reads them back with OpenCascade;
``designer`` serves the page with its bundled three.js and answers the JSON API; ``dask``
runs a sweep on a local cluster of two workers; ``dev`` runs all of these. Prints one line
per check and exits non-zero on the first failure.
"""

import importlib.metadata
import importlib.util
import json
import re
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

BIN = Path(sys.executable).parent
CURVEFOLD = str(BIN / "curvefold")


def run(*args: str) -> str:
    """Stdout of a curvefold command, which must exit 0."""
    done = subprocess.run([CURVEFOLD, *args], capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        sys.exit(f"curvefold {' '.join(args)} exited {done.returncode}: {done.stderr.strip()}")
    return done.stdout


def check(condition: bool, what: str) -> None:
    if not condition:
        sys.exit(f"FAILED: {what}")
    print(f"ok: {what}")


def small_tube():
    """A tube of 201 samples around a helix, built with the core alone."""
    from curvefold import Crease, Lattice, SpaceCurve, Structure

    curve = SpaceCurve.from_curvature(1.0, 0.3, 3.0, samples=201)
    return Structure.tube(Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.2, 0.2))


def core() -> None:
    import curvefold

    version = importlib.metadata.version("curvefold")
    check(
        curvefold.__version__ == version,
        f"curvefold.__version__ is the package's version {version}",
    )
    check(run("--version").split() == ["curvefold", version], "curvefold --version prints it")
    check(
        Path(sys.prefix) in Path(curvefold.__file__).resolve().parents,
        "curvefold is imported from the installation",
    )
    meta = importlib.metadata.metadata("curvefold")
    check(meta["License-Expression"] == "MIT", "the licence is the SPDX expression MIT")
    files = importlib.metadata.distribution("curvefold").files or []
    check(
        any(f.name == "LICENSE" and "licenses" in f.parts for f in files),
        "the licence file is installed with the metadata",
    )
    summary = json.loads(run("tube", "--json"))
    check(
        all(c["passed"] for c in summary["certificate"]),
        "curvefold tube: every check of its certificate passes",
    )
    from curvefold.io import write_structure_fold

    with tempfile.TemporaryDirectory() as tmp:
        path = write_structure_fold(f"{tmp}/tube.fold", small_tube())
        check(
            json.loads(path.read_text())["file_creator"] == f"curvefold {version}",
            "the API writes a FOLD file naming the version that wrote it",
        )
        check(json.loads(run("check", str(path), "--json"))["ok"], "curvefold check passes it")


def core_alone() -> None:
    core()
    check(importlib.util.find_spec("matplotlib") is None, "the core runs without matplotlib")
    with tempfile.TemporaryDirectory() as tmp:
        summary = run("tube", "--formats", "fold", "--out", f"{tmp}/tube")
        folder = Path(f"{tmp}/tube")
        names = {p.name for p in folder.iterdir()}
        check(
            {"tube.fold", "sheets", "report.json", "report.html"} <= names
            and not any(n.endswith(".png") for n in names),
            "without matplotlib, curvefold tube --out writes the folder but the pictures: "
            f"{sorted(names)}",
        )
        said = [line.strip() for line in summary.splitlines() if "pictures left out" in line]
        check(
            len(said) == 1 and "pip install 'curvefold[plot]'" in said[0],
            f"and one line says which pictures and which extra: {said}",
        )
        check(
            json.loads(run("check", str(folder / "tube.fold"), "--json"))["ok"],
            "curvefold check passes its FOLD file",
        )


def export() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        run("tube", "--out", f"{tmp}/tube", "--formats", "glb,obj,stl,ply,svg,dxf,pdf")
        folder = Path(f"{tmp}/tube")
        names = {p.suffix for p in folder.iterdir()}
        check(
            {".glb", ".obj", ".stl", ".ply", ".svg", ".dxf", ".pdf", ".png"} <= names,
            f"export writes every model and pattern format and the pictures: {sorted(names)}",
        )
        creator = f"curvefold {importlib.metadata.version('curvefold')}".encode()
        check(
            all(
                creator in p.read_bytes()
                for p in folder.glob("*.*")
                if p.suffix in (".glb", ".pdf")
            ),
            "the GLB and PDF files name the version that wrote them",
        )


def rhino() -> None:
    import rhino3dm

    from curvefold.io import write_3d

    with tempfile.TemporaryDirectory() as tmp:
        (path,) = write_3d(f"{tmp}/tube", small_tube(), formats=("3dm",))
        model = rhino3dm.File3dm.Read(str(path))
        check(
            model is not None and len(model.Objects) > 0,
            "rhino writes a 3DM file that rhino3dm reads back",
        )
        check(
            model.ApplicationName == f"curvefold {importlib.metadata.version('curvefold')}",
            "the 3DM file names the version that wrote it",
        )


def step() -> None:
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    with tempfile.TemporaryDirectory() as tmp:
        run(
            "tube",
            "--panels",
            "4",
            "--thickness",
            "0.002",
            "--formats",
            "step",
            "--out",
            tmp + "/t",
        )
        reader = STEPControl_Reader()
        reader.ReadFile(f"{tmp}/t/tube_solids.step")
        reader.TransferRoots()
        found, solids = TopExp_Explorer(reader.OneShape(), TopAbs_SOLID), 0
        while found.More():
            solids, _ = solids + 1, found.Next()
        check(solids == 16, f"step writes a solid per panel that OpenCascade reads back: {solids}")


def designer() -> None:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    server = subprocess.Popen(
        [CURVEFOLD, "designer", "--no-browser", "--port", str(port)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    base = f"http://127.0.0.1:{port}"
    try:
        for _ in range(600):
            try:
                with urllib.request.urlopen(base + "/", timeout=5) as r:
                    page = r.read().decode()
                break
            except OSError:
                if server.poll() is not None:
                    sys.exit(
                        f"the designer exited {server.returncode}: "
                        f"{server.stderr.read().decode().strip()}"
                    )
                time.sleep(0.1)
        else:
            sys.exit("the designer did not answer within a minute")
        check("vendor/three.module.js" in page, "the designer serves its page")
        for name in ("three.module.js", "three.core.js", "addons/controls/OrbitControls.js"):
            with urllib.request.urlopen(f"{base}/static/vendor/{name}", timeout=60) as r:
                check(
                    r.status == 200 and len(r.read()) > 10_000,
                    f"the wheel's bundled {name} is served",
                )
        # the page's own modules, from the one it loads through those each imports
        modules, served = re.findall(r'<script type="module" src="/static/([^"]+)"', page), set()
        while modules:
            name = modules.pop()
            if name not in served:
                with urllib.request.urlopen(f"{base}/static/{name}", timeout=60) as r:
                    modules += re.findall(r'from "\./([^"]+)"', r.read().decode())
                served.add(name)
        check(len(served) > 5, f"the page's {len(served)} modules are served: {sorted(served)}")
        with urllib.request.urlopen(f"{base}/api/vault?tubes=2", timeout=300) as r:
            check("kappa0_s0" in json.loads(r.read()), "the JSON API builds a vault")
    finally:
        server.terminate()
        server.wait(timeout=60)


def dask() -> None:
    import numpy as np

    from curvefold.vault import AtlasGrid, sweep

    grid = AtlasGrid.of(np.linspace(0.5, 1.0, 2), np.linspace(0.0, 0.3, 2), samples=101)
    records = [record for record, _ in sweep(grid, workers=2)]
    serial = [record for record, _ in sweep(grid, workers=1)]
    check(
        records == serial and len(records) == 4,
        "a sweep on a local Dask cluster of two workers gives the serial records",
    )


CHECKS = {
    "core": [core_alone],
    "export": [core, export],
    "rhino": [core, rhino],
    "step": [core, step],
    "designer": [core, designer],
    "dask": [core, dask],
    "dev": [core, export, rhino, step, designer, dask],
}

if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] not in CHECKS:
        sys.exit(f"usage: python smoke.py {{{','.join(CHECKS)}}}")
    for step in CHECKS[sys.argv[1]]:
        step()
