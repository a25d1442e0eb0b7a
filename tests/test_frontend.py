"""The designer's front end as the package carries it: the vendored three.js is the version
``frontend/package-lock.json`` pins and, where npm installed it, npm's very bytes; every file the
page loads is in the package and in its package data; ESLint passes over the page's modules."""

from __future__ import annotations

import glob
import json
import os
import re
import shutil
import subprocess
import tomllib
from pathlib import Path
from urllib.parse import urljoin, urlsplit

import pytest

from _designer import need

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "curvefold"
STATIC = PACKAGE / "app" / "designer" / "static"
FRONTEND = ROOT / "frontend"
#: The page's files are served under this path (``curvefold.app.designer.server``).
SERVED = "/static/"
_PAGE = "http://designer" + SERVED


# -- the checks ------------------------------------------------------------------------------


def pinned_three(lock: dict) -> str:
    """The version of three.js a lock file pins (``0.187.0``)."""
    return lock["packages"]["node_modules/three"]["version"]


def version_problems(vendor: Path, lock: dict) -> list[str]:
    """Where the vendored three.js is not the version ``lock`` pins (0.R.P says REVISION = 'R')."""
    version = pinned_three(lock)
    text = (vendor / "three.core.js").read_text(encoding="utf-8")
    found = re.search(r"\bREVISION = '(\d+)'", text)
    if found is None:
        return ["vendor/three.core.js states no REVISION"]
    if found[1] != version.split(".")[1]:
        return [f"vendor/three.core.js is three.js r{found[1]}, the lock file pins {version}"]
    return []


#: A static import or re-export (``import x from "m"``, ``export {x} from "m"``, ``import "m"``).
_IMPORT = re.compile(
    r"""^\s*(?:import|export)\b[^;'"]*?\bfrom\s*(['"])([^'"]+)\1|^\s*import\s*(['"])([^'"]+)\3""",
    re.M,
)
_MODULE_SCRIPT = re.compile(r"""<script\b[^>]*\btype="module"[^>]*\bsrc="([^"]+)\"""")
_STYLESHEET = re.compile(r"""<link\b[^>]*\brel="stylesheet"[^>]*\bhref="([^"]+)\"""")
_IMPORT_MAP = re.compile(r"""<script\b[^>]*\btype="importmap"[^>]*>(.*?)</script>""", re.S)


def page_files(static: Path) -> tuple[set[str], list[str]]:
    """The files the page loads (relative to ``static``), following every module's static
    imports through the page's import map, and what fails to resolve to a file, one line each."""
    html = (static / "index.html").read_text(encoding="utf-8")
    found = _IMPORT_MAP.search(html)
    imports: dict[str, str] = json.loads(found[1])["imports"] if found else {}
    page = urljoin(_PAGE, "index.html")
    files: set[str] = set()
    problems: list[str] = []

    def resolve(specifier: str, base: str, by: str) -> str | None:
        if specifier.startswith(("/", "./", "../")):
            url = urljoin(base, specifier)
        else:
            prefixes = [
                k
                for k in imports
                if k == specifier or (k.endswith("/") and specifier.startswith(k))
            ]
            if not prefixes:
                problems.append(f"{by} imports {specifier!r}, which the import map does not name")
                return None
            key = max(prefixes, key=len)
            url = urljoin(page, imports[key] + specifier[len(key) :])
        path = urlsplit(url).path
        name = path.removeprefix(SERVED)
        if name == path or not (static / name).is_file():
            problems.append(f"{by} loads {specifier!r}: no such file in the package ({path})")
            return None
        return name

    queue = [resolve(src, page, "index.html") for src in _MODULE_SCRIPT.findall(html)]
    styles = (resolve(href, page, "index.html") for href in _STYLESHEET.findall(html))
    files.update(name for name in styles if name)
    while queue:
        name = queue.pop()
        if name is None or name in files:
            continue
        files.add(name)
        text = (static / name).read_text(encoding="utf-8")
        for match in _IMPORT.finditer(text):
            queue.append(resolve(match[2] or match[4], urljoin(_PAGE, name), name))
    return files, problems


# -- the vendored three.js --------------------------------------------------------------------


def test_the_vendored_three_js_is_the_version_the_lock_file_pins(tmp_path):
    lock = json.loads((FRONTEND / "package-lock.json").read_text(encoding="utf-8"))
    assert version_problems(STATIC / "vendor", lock) == []
    other = json.loads(json.dumps(lock))
    other["packages"]["node_modules/three"]["version"] = "0.186.0"
    assert version_problems(STATIC / "vendor", other) == [
        "vendor/three.core.js is three.js r187, the lock file pins 0.186.0"
    ]
    (tmp_path / "three.core.js").write_text("const REVISION = '186';\n")
    assert version_problems(tmp_path, lock) == [
        "vendor/three.core.js is three.js r186, the lock file pins 0.187.0"
    ]
    (tmp_path / "three.core.js").write_text("// no revision\n")
    assert version_problems(tmp_path, lock) == ["vendor/three.core.js states no REVISION"]


def test_every_file_the_page_loads_is_in_the_package():
    files, problems = page_files(STATIC)
    assert problems == []
    vendored = {name.removeprefix("vendor/") for name in files if name.startswith("vendor/")}
    assert vendored == {"three.module.js", "three.core.js", "addons/controls/OrbitControls.js"}
    assert "designer.css" in files
    pytest.importorskip("fastapi")
    from curvefold.app.designer import server

    # what the command checks before serving is what the page loads
    assert set(server.VENDOR_FILES) == vendored
    # every module of the page is loaded (none left behind after a refactoring)
    modules = {p.relative_to(STATIC).as_posix() for p in STATIC.rglob("*.js")}
    assert modules == {name for name in files if name.endswith(".js")}


def test_a_missing_or_unmapped_import_is_found(tmp_path):
    static = tmp_path / "static"
    shutil.copytree(STATIC, static)
    (static / "vendor" / "three.core.js").unlink()
    html = (static / "index.html").read_text(encoding="utf-8")
    html = html.replace('"three/addons/"', '"three/elsewhere/"')
    (static / "index.html").write_text(html, encoding="utf-8")
    _, problems = page_files(static)
    assert (
        "vendor/three.module.js loads './three.core.js': "
        "no such file in the package (/static/vendor/three.core.js)"
    ) in problems
    unmapped = (
        "imports 'three/addons/controls/OrbitControls.js', which the import map does not name"
    )
    assert any(p.endswith(unmapped) for p in problems)


def test_the_vendored_files_are_the_bytes_npm_installs():
    """Where ``npm ci --prefix frontend`` ran (scripts/build-designer.sh, scripts/test.sh): the
    vendored files are those it installed, and nothing else is vendored."""
    vendor = json.loads((FRONTEND / "package.json").read_text(encoding="utf-8"))["vendor"]
    modules = FRONTEND / "node_modules"
    need(
        (modules / "three").is_dir(),
        "the designer's npm packages are not installed (npm ci --prefix frontend)",
    )
    lock = json.loads((FRONTEND / "package-lock.json").read_text(encoding="utf-8"))
    installed = json.loads((modules / "three" / "package.json").read_text(encoding="utf-8"))
    assert installed["version"] == pinned_three(lock)
    different = [
        name
        for name, source in vendor.items()
        if (STATIC / "vendor" / name).read_bytes() != (modules / source).read_bytes()
    ]
    assert different == [], "run bash scripts/build-designer.sh and commit the vendored files"
    files = [p for p in (STATIC / "vendor").rglob("*") if p.is_file()]
    assert {p.relative_to(STATIC / "vendor").as_posix() for p in files} == set(vendor)


# -- the distribution ------------------------------------------------------------------------


def test_the_package_data_carries_every_file_of_the_page():
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    patterns = pyproject["tool"]["setuptools"]["package-data"]["curvefold"]
    matches = (glob.glob(pattern, root_dir=PACKAGE, recursive=True) for pattern in patterns)
    carried = {m for found in matches for m in found if (PACKAGE / m).is_file()}
    page = {p.relative_to(PACKAGE).as_posix() for p in STATIC.rglob("*") if p.is_file()}
    assert page and page <= carried
    assert "py.typed" in carried


def test_nothing_of_the_page_is_left_out_of_git():
    """The vendored files are kept in git: a clone installs without npm."""
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")

    def git(*args: str) -> list[str]:
        done = subprocess.run(
            ["git", "ls-files", *args, "--", str(STATIC)],
            cwd=ROOT,
            capture_output=True,
            text=True,
            check=True,
        )
        return done.stdout.split()

    tracked, ignored = git(), git("--others", "--ignored", "--exclude-standard")
    assert ignored == [] and any(name.endswith("vendor/three.core.js") for name in tracked)


# -- ESLint ----------------------------------------------------------------------------------


def _eslint(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess:
    """ESLint with the designer's configuration, from the checkout's root (as npm run lint)."""
    eslint = FRONTEND / "node_modules" / ".bin" / "eslint"
    need(
        eslint.is_file() and shutil.which("node") is not None,
        "the designer's ESLint is not installed (npm ci --prefix frontend)",
    )
    return subprocess.run(
        [str(eslint), "--config", "frontend/eslint.config.js", *args],
        cwd=ROOT,
        input=stdin,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "NO_COLOR": "1"},
    )


def test_eslint_passes_over_the_designers_modules():
    lint = json.loads((FRONTEND / "package.json").read_text(encoding="utf-8"))["scripts"]["lint"]
    static = STATIC.relative_to(ROOT).as_posix()
    assert lint.endswith(f"--config frontend/eslint.config.js {static}")  # what this test runs
    done = _eslint(static)
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.parametrize(
    "code, rule",
    [
        ("export const f = () => missing;\n", "no-undef"),
        ("export const f = (box, text) => { box.innerHTML = text; };\n", "no-restricted-syntax"),
        (
            "export const f = (box, t) => box.insertAdjacentHTML('end', t);\n",
            "no-restricted-syntax",
        ),
        ("const unused = 1;\n", "no-unused-vars"),
    ],
)
def test_eslint_refuses_what_it_is_there_for(code, rule):
    name = f"{STATIC.relative_to(ROOT).as_posix()}/probe.js"
    done = _eslint("--stdin", "--stdin-filename", name, stdin=code)
    assert done.returncode == 1 and rule in done.stdout, done.stdout + done.stderr


# -- the page's numbers, in Node ---------------------------------------------------------------


def test_the_pages_numbers_in_node():
    """format.js and controls.js run in Node (tests/node/designer_numbers.mjs): "Under load" in
    mm, kPa or MPa and %, the design table to four digits, sliders whose grid holds 0.5 and 0."""
    need(shutil.which("node") is not None, "Node.js is not installed (apt-get install nodejs)")
    done = subprocess.run(
        ["node", str(ROOT / "tests" / "node" / "designer_numbers.mjs")],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr
