"""Documentation and distribution: the tutorial stored without outputs, the site's offline link
check, the Rhino script's HTTP part against the real designer, one source of the version, the
licence and the citation file (the designer's JavaScript: test_frontend.py)."""

from __future__ import annotations

import copy
import importlib.metadata
import importlib.util
import json
import shutil
import socket
import tomllib
from pathlib import Path

import pytest

from _cli import run_subprocess

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def _load(path: Path, name: str):
    """A script of the repository as a module (``__name__`` is not ``"__main__"``: nothing runs)."""
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


check_links = _load(ROOT / "scripts" / "check_links.py", "check_links")


# -- the tutorial notebook ---------------------------------------------------------------------------


def stored_outputs(notebook: dict) -> list[str]:
    """Cells of a notebook that hold what running it made (outputs, execution counts)."""
    return [f"cell {i}" for i, cell in enumerate(notebook["cells"])
            if cell.get("outputs") or cell.get("execution_count") is not None]


def test_the_tutorial_is_stored_without_outputs():
    notebook = json.loads((ROOT / "docs" / "tutorial.ipynb").read_text(encoding="utf-8"))
    code = [cell for cell in notebook["cells"] if cell["cell_type"] == "code"]
    assert len(code) >= 6 and stored_outputs(notebook) == []
    ran = copy.deepcopy(notebook)  # as a notebook saved after running it
    first = next(i for i, cell in enumerate(ran["cells"]) if cell["cell_type"] == "code")
    ran["cells"][first].update(execution_count=1, outputs=[{"output_type": "stream", "name": "stdout", "text": ["0.1.0\n"]}])
    assert stored_outputs(ran) == [f"cell {first}"]


# -- the link check of the built site ----------------------------------------------------------------


def _site(root: Path, pages: dict[str, str]) -> Path:
    for name, body in pages.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(f"<!DOCTYPE html><html><body>{body}</body></html>", encoding="utf-8")
    return root


def test_link_check_passes_a_site_whose_internal_links_resolve(tmp_path):
    site = _site(tmp_path, {
        "index.html": '<a href="guide/a.html#eq-2">a</a> <a href="#top">top</a> <img src="_images/x.png">'
                      '<a href="https://example.org/missing">external</a> <a href="guide/">folder</a> <p id="top"></p>',
        "guide/index.html": '<a href="../index.html">up</a>',
        "guide/a.html": '<h2 id="eq-2">Eq. 2</h2><a href="a.html#eq-2">self</a><a name="old"></a><a href="#old">old</a>',
        "_static/webpack-macros.html": "<a href=\"{{ pathto('x') }}\">a template, not a page</a>",
    })
    (site / "_images").mkdir()
    (site / "_images" / "x.png").write_bytes(b"png")
    assert check_links.broken_links(site) == []


def test_link_check_finds_every_kind_of_broken_link(tmp_path):
    site = _site(tmp_path / "site", {
        "index.html": '<a href="missing.html">1</a> <a href="a.html#nowhere">2</a> <img src="_images/gone.png">'
                      '<a href="empty/">3</a> <a href="../outside.html">4</a> <a href="#">5</a>',
        "a.html": '<p id="somewhere"></p>',
    })
    (site / "empty").mkdir()
    (tmp_path / "outside.html").write_text("<html></html>")
    found = check_links.broken_links(site)
    assert found == [
        "index.html: missing.html (no such file)",
        "index.html: a.html#nowhere (no id 'nowhere' on that page)",
        "index.html: _images/gone.png (no such file)",
        "index.html: empty/ (a folder without index.html)",
        "index.html: ../outside.html (outside the site)",
    ]


# -- the distribution ---------------------------------------------------------------------------------


def test_the_version_has_one_source():
    version = importlib.metadata.version("curvefold")
    import curvefold

    assert "version" not in PYPROJECT["project"] and "version" in PYPROJECT["project"]["dynamic"]
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "curvefold.kernel._version.VERSION"}
    from curvefold.kernel._version import VERSION

    assert version == VERSION == curvefold.__version__
    assert run_subprocess("--version").stdout.split() == ["curvefold", version]
    assert f"## [{version}]" in (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")  # every version has its entry
    from curvefold.io._tables import CREATOR

    assert CREATOR == f"curvefold {version}"


def test_licence_is_an_spdx_expression_and_its_file_ships():
    project = PYPROJECT["project"]
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    assert (ROOT / "LICENSE").read_text().startswith("MIT License")
    assert {"export", "rhino", "designer", "dask", "docs", "dev"} <= set(project["optional-dependencies"])


def test_citation_cites_curvefold_and_the_paper():
    yaml = pytest.importorskip("yaml")
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software" and cff["title"].startswith("curvefold")
    assert cff["license"] == PYPROJECT["project"]["license"]
    assert "version" not in cff  # one source of the version: pyproject.toml
    (paper,) = cff["references"]
    assert paper["title"] == "Composite Rigid-Foldable Curved Origami Structure"
    assert paper["authors"][0] == {"family-names": "Tachi", "given-names": "Tomohiro"}


# -- the Rhino script's HTTP part, against the real designer ------------------------------------------


@pytest.fixture(scope="module")
def designer_url():
    pytest.importorskip("fastapi")
    from curvefold.app.designer import server

    with server.serving() as url:
        yield url


@pytest.fixture(scope="module")
def rhino_script():
    return _load(ROOT / "docs" / "rhino" / "curvefold_rhino.py", "curvefold_rhino")


def test_rhino_script_downloads_a_design_that_rhino_reads(designer_url, rhino_script, tmp_path):
    rhino3dm = pytest.importorskip("rhino3dm")
    from curvefold.analysis import check_fold

    summary, paths = rhino_script.fetch("vault", {"a": 0.4, "tubes": 2, "samples": 101}, formats=("3dm", "fold"),
                                        server=designer_url, folder=str(tmp_path))
    assert summary["tubes"] == 2 and summary["design"]["a"] == 0.4 and all(c["passed"] for c in summary["certificate"])
    assert [Path(p).name for p in paths] == ["vault.3dm", "vault.fold"]
    model = rhino3dm.File3dm.Read(paths[0])
    assert model.ApplicationName == f"curvefold {importlib.metadata.version('curvefold')}"
    from curvefold.io._rhino import LAYERS, PATTERN_LAYER

    names = [layer.Name for layer in model.Layers]
    assert len(model.Objects) > 0 and names[: len(LAYERS)] == [name for name, _ in LAYERS] and PATTERN_LAYER in names
    assert check_fold(paths[1]).ok


def test_rhino_script_reports_a_refused_parameter_and_a_missing_designer(designer_url, rhino_script, tmp_path):
    with pytest.raises(rhino_script.DesignError, match=r"^a must be in \[0, 1\.2707093728\) \(no arch stands beyond it: Eq\. \(20\) has no root next to π there\), got 5") as refused:
        rhino_script.fetch("vault", {"a": 5}, server=designer_url, folder=str(tmp_path))
    assert refused.value.key == "a"
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        closed = f"http://127.0.0.1:{s.getsockname()[1]}"
    with pytest.raises(OSError):
        rhino_script.fetch("vault", {}, server=closed, folder=str(tmp_path), timeout=10)
    assert list(tmp_path.iterdir()) == []  # nothing written for a refused design


def test_rhino_script_run_outside_rhino_downloads_and_says_what_it_got(designer_url, rhino_script, monkeypatch, capsys):
    monkeypatch.setattr(rhino_script, "SERVER", designer_url)
    kind, parameters = rhino_script._parse(["tube", "samples=101", "width_left=0.2"])  # as typed after the script's name
    assert rhino_script.main(kind, parameters, inside_rhino=False) is None
    printed = capsys.readouterr().out.splitlines()
    assert printed[0].startswith("tube: ") and printed[0].endswith("certificate checks, all passed")
    assert Path(printed[1]).name == "tube.3dm" and Path(printed[1]).stat().st_size > 0
    shutil.rmtree(Path(printed[1]).parent)  # the script's own temporary folder
    assert rhino_script.main("tube", {"width_left": "-1"}, inside_rhino=False).startswith("curvefold refused the design: width_left")
