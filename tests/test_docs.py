"""Documentation and distribution: the tutorial stored without outputs, the site's offline link
check, the Rhino script's HTTP part against the real designer, one source of the version, the
licence and the citation file; the README and the docs against the program (every quoted command
line, the stable JSON keys, the figures quoted about the output folder, the guide's examples) and
the benchmarks' run record (the designer's JavaScript: test_frontend.py)."""

from __future__ import annotations

import argparse
import copy
import doctest
import importlib.metadata
import importlib.util
import json
import re
import shutil
import socket
import tomllib
from pathlib import Path

import pytest

from _cli import run, run_subprocess
from curvefold.app import _cli_flags, _cli_parser, cli
from curvefold.app._kinds import design_kinds
from curvefold.kernel._errors import CurvefoldError

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def _load(path: Path, name: str):
    """A script of the repository as a module (``__name__`` is not ``"__main__"``: nothing runs)."""
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None, path
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


check_links = _load(ROOT / "scripts" / "check_links.py", "check_links")


# -- the tutorial notebook
# ---------------------------------------------------------------------------


def stored_outputs(notebook: dict) -> list[str]:
    """Cells of a notebook that hold what running it made (outputs, execution counts)."""
    return [
        f"cell {i}"
        for i, cell in enumerate(notebook["cells"])
        if cell.get("outputs") or cell.get("execution_count") is not None
    ]


def test_the_tutorial_is_stored_without_outputs():
    notebook = json.loads((ROOT / "docs" / "tutorial.ipynb").read_text(encoding="utf-8"))
    code = [cell for cell in notebook["cells"] if cell["cell_type"] == "code"]
    assert len(code) >= 6 and stored_outputs(notebook) == []
    ran = copy.deepcopy(notebook)  # as a notebook saved after running it
    first = next(i for i, cell in enumerate(ran["cells"]) if cell["cell_type"] == "code")
    ran["cells"][first].update(
        execution_count=1,
        outputs=[{"output_type": "stream", "name": "stdout", "text": ["0.1.0\n"]}],
    )
    assert stored_outputs(ran) == [f"cell {first}"]


# -- the link check of the built site
# ----------------------------------------------------------------


def _site(root: Path, pages: dict[str, str]) -> Path:
    for name, body in pages.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(f"<!DOCTYPE html><html><body>{body}</body></html>", encoding="utf-8")
    return root


def test_link_check_passes_a_site_whose_internal_links_resolve(tmp_path):
    site = _site(
        tmp_path,
        {
            "index.html": '<a href="guide/a.html#eq-2">a</a> <a href="#top">top</a> <img '
            'src="_images/x.png"><a href="https://example.org/missing">external</a> <a '
            'href="guide/">folder</a> <p id="top"></p>',
            "guide/index.html": '<a href="../index.html">up</a>',
            "guide/a.html": '<h2 id="eq-2">Eq. 2</h2><a href="a.html#eq-2">self</a><a '
            'name="old"></a><a href="#old">old</a>',
            "_static/webpack-macros.html": "<a href=\"{{ pathto('x') }}\">a template, not a "
            "page</a>",
        },
    )
    (site / "_images").mkdir()
    (site / "_images" / "x.png").write_bytes(b"png")
    assert check_links.broken_links(site) == []


def test_link_check_finds_every_kind_of_broken_link(tmp_path):
    site = _site(
        tmp_path / "site",
        {
            "index.html": '<a href="missing.html">1</a> <a href="a.html#nowhere">2</a> <img '
            'src="_images/gone.png"><a href="empty/">3</a> <a href="../outside.html">4</a> <a '
            'href="#">5</a>',
            "a.html": '<p id="somewhere"></p>',
        },
    )
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


# -- the distribution
# ---------------------------------------------------------------------------------


def test_the_version_has_one_source():
    version = importlib.metadata.version("curvefold")
    import curvefold

    assert "version" not in PYPROJECT["project"] and "version" in PYPROJECT["project"]["dynamic"]
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {
        "attr": "curvefold.kernel._version.VERSION"
    }
    from curvefold.kernel._version import VERSION

    assert version == VERSION == curvefold.__version__
    assert run_subprocess("--version").stdout.split() == ["curvefold", version]
    # every version has its entry
    assert f"## [{version}]" in (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    from curvefold.io._tables import CREATOR

    assert CREATOR == f"curvefold {version}"


def test_licence_is_an_spdx_expression_and_its_file_ships():
    project = PYPROJECT["project"]
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    assert (ROOT / "LICENSE").read_text().startswith("MIT License")
    assert {"export", "rhino", "designer", "dask", "docs", "dev"} <= set(
        project["optional-dependencies"]
    )


def test_citation_cites_curvefold_and_the_paper():
    yaml = pytest.importorskip("yaml")
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert (
        cff["cff-version"] == "1.2.0"
        and cff["type"] == "software"
        and cff["title"].startswith("curvefold")
    )
    assert cff["license"] == PYPROJECT["project"]["license"]
    assert "version" not in cff  # one source of the version: pyproject.toml
    (paper,) = cff["references"]
    assert paper["title"] == "Composite Rigid-Foldable Curved Origami Structure"
    assert paper["authors"][0] == {"family-names": "Tachi", "given-names": "Tomohiro"}


# -- the Rhino script's HTTP part, against the real designer
# ------------------------------------------


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

    summary, paths = rhino_script.fetch(
        "vault",
        {"a": 0.4, "tubes": 2, "samples": 101},
        formats=("3dm", "fold"),
        server=designer_url,
        folder=str(tmp_path),
    )
    assert (
        summary["tubes"] == 2
        and summary["design"]["a"] == 0.4
        and all(c["passed"] for c in summary["certificate"])
    )
    assert [Path(p).name for p in paths] == ["vault.3dm", "vault.fold"]
    model = rhino3dm.File3dm.Read(paths[0])
    assert model.ApplicationName == f"curvefold {importlib.metadata.version('curvefold')}"
    from curvefold.io._rhino import LAYERS, PATTERN_LAYER

    names = [layer.Name for layer in model.Layers]
    assert (
        len(model.Objects) > 0
        and names[: len(LAYERS)] == [name for name, _ in LAYERS]
        and PATTERN_LAYER in names
    )
    assert check_fold(paths[1]).ok


def test_rhino_script_reports_a_refused_parameter_and_a_missing_designer(
    designer_url, rhino_script, tmp_path
):
    with pytest.raises(
        rhino_script.DesignError,
        match=r"^a must be in \[0, 1\.2707093728\) \(no "
        r"arch stands beyond it: Eq\. \(20\) has no root next to π there\), got 5",
    ) as refused:
        rhino_script.fetch("vault", {"a": 5}, server=designer_url, folder=str(tmp_path))
    assert refused.value.key == "a"
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        closed = f"http://127.0.0.1:{s.getsockname()[1]}"
    with pytest.raises(OSError):
        rhino_script.fetch("vault", {}, server=closed, folder=str(tmp_path), timeout=10)
    assert list(tmp_path.iterdir()) == []  # nothing written for a refused design


def test_rhino_script_run_outside_rhino_downloads_and_says_what_it_got(
    designer_url, rhino_script, monkeypatch, capsys
):
    monkeypatch.setattr(rhino_script, "SERVER", designer_url)
    # as typed after the script's name
    kind, parameters = rhino_script._parse(["tube", "samples=101", "width_left=0.2"])
    assert rhino_script.main(kind, parameters, inside_rhino=False) is None
    printed = capsys.readouterr().out.splitlines()
    assert printed[0].startswith("tube: ") and printed[0].endswith("certificate checks, all passed")
    assert Path(printed[1]).name == "tube.3dm" and Path(printed[1]).stat().st_size > 0
    shutil.rmtree(Path(printed[1]).parent)  # the script's own temporary folder
    assert rhino_script.main("tube", {"width_left": "-1"}, inside_rhino=False).startswith(
        "curvefold refused the design: width_left"
    )


# -- the README and the docs against the program ---------------------------------------------
#
# Every `curvefold ...` line quoted in README.md and docs/**/*.md goes through the command line's
# own parser; every key the command-line page calls stable is looked up in the JSON the command
# prints; every figure the README and the output-folder page quote about the paper's vault folder
# is compared with a folder built here. Each check is shown failing on a damaged copy of the text.


DOC_PAGES = sorted((ROOT / "docs").rglob("*.md"), key=str)
DOC_PAGES = [p for p in DOC_PAGES if "node_modules" not in p.parts and "_build" not in p.parts]
QUOTED = [ROOT / "README.md", *DOC_PAGES]
_FENCE = re.compile(r"^```([^\n`]*)\n(.*?)^```", re.M | re.S)
_SHELL = {"", "bash", "sh", "shell", "console", "text"}
#: A word standing for a value the reader chooses: FILE.fold, DIR, N, COMMAND (not A3 or mm).
_PLACEHOLDER = re.compile(r"^[A-Z][A-Z_]*(\.\w+)?$")


def quoted_commands(text: str) -> list[str]:
    """The ``curvefold ...`` lines a Markdown text quotes: in shell or text code blocks (a line
    and the indented ``[...]`` lines that continue it, without its ``# comment``) and in inline
    code."""
    found = []
    for lang, body in _FENCE.findall(text):
        if lang.strip() not in _SHELL:
            continue
        for line in body.splitlines():
            line = re.split(r"\s+#\s", line.strip().removeprefix("$ "))[0].rstrip()
            if line.startswith("curvefold "):
                found.append(line)
            elif line.startswith("[") and found and found[-1].startswith("curvefold "):
                found[-1] += " " + line
    prose = _FENCE.sub("", text)
    found += [m.strip() for m in re.findall(r"`(curvefold [^`\n]+)`", prose)]
    return found


def is_synopsis(command: str) -> bool:
    """A usage line (optional parts, alternatives, placeholders) rather than one to type."""
    words = command.split()
    return (
        any(c in command for c in "[|…")
        or "..." in command
        or bool({"--help", "-h", "--version"} & set(words))
        or any(_PLACEHOLDER.match(w) for w in words[1:] if not w.startswith("-"))
    )


def _subcommands() -> dict[str, argparse.ArgumentParser]:
    parser = cli.build_parser()
    (action,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(action.choices)


def _checked(command: str, argv: list[str]) -> None:
    """Parse ``curvefold command argv`` and check every value given as the command checks it."""
    args = cli.build_parser().parse_args([command, *argv])
    kinds = {kind.name for kind in design_kinds()}
    kind = command if command in kinds else _cli_parser.LOAD_KIND if command == "load" else None
    if kind is not None:
        _cli_flags._design_flags(kind, args)
        from curvefold.vault._targets import TARGET_SPECS

        for spec in TARGET_SPECS if kind == "vault" else ():
            if getattr(args, spec.name, None) is not None:
                _cli_flags._flag_value(spec, getattr(args, spec.name))
    elif command == "arch":
        for name in ("a", "p_xy", "fold_angle"):
            if getattr(args, name) is not None:
                _cli_flags._flag_value(_cli_parser._VAULT[name], getattr(args, name))


def command_problems(command: str) -> list[str]:
    """What in a quoted ``curvefold`` line the program does not accept (empty: all of it).

    A line to type is parsed by the command line's parser and its values checked; in a usage
    line every ``--flag`` must be one of its command's and every literal alternative of a value
    (``mm|cm|m|in``, ``N|max``) a value the flag accepts.
    """
    words = command.split()[1:]
    subs = _subcommands()
    if len(words) == 1 and not words[0].startswith(
        "-"
    ):  # a command named in prose: `curvefold check`
        return [] if words[0] in subs else [f"{command}: no command {words[0]!r}"]
    if not is_synopsis(command):
        try:
            _checked(words[0], words[1:])
        except CurvefoldError as err:
            return [f"{command}: {err}"]
        return []
    if words[0].startswith("-"):  # options of curvefold itself: --version, --help
        known = cli.build_parser()._option_string_actions
        return [
            f"{command}: curvefold has no flag {w}"
            for w in words
            if w.startswith("-") and w not in known
        ]
    names = [words[0]]
    while len(words) > len(names) * 2 and words[len(names) * 2 - 1] == "|":
        names.append(words[len(names) * 2])
    problems = []
    for name in names:
        if _PLACEHOLDER.match(name):  # curvefold COMMAND --help
            continue
        if name not in subs:
            problems.append(f"{command}: no command {name!r}")
            continue
        sub = subs[name]
        sub.format_help()  # adds the flags a command declares lazily
        for flag, value in re.findall(
            r"(--[a-z][a-z0-9-]*)(?:\s+([^\s\[\]|][^\s\[\]]*))?", command
        ):
            action = sub._option_string_actions.get(flag)
            if action is None:
                problems.append(f"{command}: {name} has no flag {flag}")
                continue
            if action.nargs == 0 or "|" not in value:
                continue
            positional = ["x.fold"] if name in ("check", "mechanism") else []
            for choice in value.split("|"):
                if _PLACEHOLDER.match(choice) or choice in ("…", "...", ""):
                    continue
                try:
                    _checked(name, [*positional, flag, choice])
                except CurvefoldError as err:
                    problems.append(f"{command}: {flag} {choice}: {err}")
    return problems


def test_every_quoted_command_line_is_one_the_program_accepts():
    quoted = {
        path.relative_to(ROOT).as_posix(): quoted_commands(path.read_text(encoding="utf-8"))
        for path in QUOTED
    }
    lines = [line for found in quoted.values() for line in found]
    assert len(quoted["README.md"]) >= 7 and len(lines) >= 60  # the extraction finds them
    assert sum(map(is_synopsis, lines)) >= 10 and sum(not is_synopsis(line) for line in lines) >= 40
    problems = [
        f"{name}: {p}"
        for name, found in quoted.items()
        for line in found
        for p in command_problems(line)
    ]
    assert problems == []


@pytest.mark.parametrize(
    ("damage", "message"),
    [
        (
            ("--p-xy 0.75 --out my-vault", "--pxy 0.75 --out my-vault"),
            r"unrecognized arguments: --pxy",
        ),
        (("--units mm ", "--units ft "), r"units must be one of"),
        (("--span 4", "--span -4"), r"span"),
        (("--units mm|cm|m|in", "--units mm|cm|m|in|ft"), r"--units ft: .*units must be one of"),
        (
            ("[--cutter print|laser|service]", "[--cutters print|laser|service]"),
            r"vault has no flag --cutters",
        ),
        (("[--tubes N|max]", "[--tubes N|most]"), r"--tubes most"),
        (("--supports pinned|roller", "--supports pinned|fixed"), r"--supports fixed"),
    ],
)
def test_a_quoted_command_line_the_program_refuses_is_found(damage, message):
    pages = ["README.md", "docs/guide/command-line.md"]
    text = "\n".join((ROOT / page).read_text(encoding="utf-8") for page in pages)
    assert damage[0] in text
    problems = [
        p
        for line in quoted_commands(text.replace(damage[0], damage[1]))
        for p in command_problems(line)
    ]
    assert len(problems) == 1 and re.search(message, problems[0]), problems


def test_quoted_commands_are_found_in_blocks_and_prose_with_their_continuations():
    text = (
        "Run `curvefold arch --json` or:\n\n```bash\n$ curvefold tube --samples 101   # a tube\n"
        "curvefold vault [--a A]\n    [--units mm|cm]\n```\n\n```python\ncurvefold --no\n```\n"
    )
    assert quoted_commands(text) == [
        "curvefold tube --samples 101",
        "curvefold vault [--a A] [--units mm|cm]",
        "curvefold arch --json",
    ]
    assert [is_synopsis(c) for c in quoted_commands(text)] == [False, True, False]
    assert is_synopsis("curvefold check FILE.fold") and not is_synopsis("curvefold tube --page A3")


# -- the stable keys of --json ----------------------------------------------------------------


def stable_keys(text: str) -> list[tuple[str, list[str]]]:
    """The rows of the command-line page's table of stable keys: the command and its keys."""
    rows = re.findall(r"^\| `(curvefold [^`]+)` \| ((?:`[^`]+`(?:, )?)+) \|$", text, re.M)
    return [(command, re.findall(r"`([^`]+)`", keys)) for command, keys in rows]


def missing_keys(payload, key: str) -> list[str]:
    """Where a key path (``a.b``, ``frames[].dof``) is absent from a JSON value."""
    head, _, rest = key.partition(".")
    each = head.endswith("[]")
    name = head.removesuffix("[]")
    if not isinstance(payload, dict) or name not in payload:
        return [key]
    value = payload[name]
    if each:
        if not isinstance(value, list) or not value:
            return [key]
        return [
            f"{name}[{i}].{m}"
            for i, item in enumerate(value)
            for m in (missing_keys(item, rest) if rest else [])
        ]
    return [f"{name}.{m}" for m in missing_keys(value, rest)] if rest else []


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The paper's vault folder as ``curvefold vault`` writes it (every format), its JSON, and a
    FOLD file of rigid panels."""
    for module in ("ezdxf", "rhino3dm", "matplotlib"):
        pytest.importorskip(module)  # every format and picture of the folder
    root = tmp_path_factory.mktemp("built")
    vault = run("vault", "--out", str(root / "vault"), "--json")
    assert vault.returncode == 0, vault.stderr
    panels = run(
        "vault", "--panels", "8", "--tubes", "2", "--formats", "fold", "--out", str(root / "panels")
    )
    assert panels.returncode == 0, panels.stderr
    return {
        "folder": root / "vault",
        "json": json.loads(vault.stdout),
        "FILE.fold": {
            "check": root / "vault" / "vault.fold",
            "mechanism": root / "panels" / "vault.fold",
        },
    }


def _json_of(command: str, built) -> dict:
    if command == "curvefold vault --json":  # what the fixture's build printed
        return built["json"]
    argv = command.split()[1:]
    argv = [str(built["FILE.fold"][argv[0]]) if word == "FILE.fold" else word for word in argv]
    result = run(*argv)
    assert result.returncode == 0, (command, result.stderr)
    return json.loads(result.stdout)


def test_every_key_the_docs_call_stable_is_in_the_json(built):
    rows = stable_keys((ROOT / "docs" / "guide" / "command-line.md").read_text(encoding="utf-8"))
    assert {command.split()[1] for command, _ in rows} == {
        "arch",
        "vault",
        "load",
        "check",
        "mechanism",
    }
    missing = {
        command: [m for key in keys for m in missing_keys(_json_of(command, built), key)]
        for command, keys in rows
    }
    assert missing == {command: [] for command, _ in rows}


def test_a_key_the_json_lacks_is_found(built):
    text = (ROOT / "docs" / "guide" / "command-line.md").read_text(encoding="utf-8")
    row = "| `curvefold arch --a 0.3 --json` | `kappa0_s0`, `proportion_change` |"
    assert row in text
    # the README once listed p_xz among arch's keys; arch prints it only with --p-xy
    (damaged,) = stable_keys(row.removesuffix(" |") + ", `p_xz` |")
    assert [m for key in damaged[1] for m in missing_keys(_json_of(damaged[0], built), key)] == [
        "p_xz"
    ]
    assert missing_keys({"frames": [{"dof": 1}, {"gap": 2}]}, "frames[].dof") == ["frames[1].dof"]
    assert missing_keys({"a": {"b": 1}}, "a.c") == ["a.c"] and missing_keys(
        {"frames": []}, "frames[].dof"
    ) == ["frames[].dof"]


# -- the figures quoted about the output folder -----------------------------------------------

#: Tolerances of the quoted figures: the folder's size one unit of its last digit (0.1 MB), the
#: smallest triangle corner 0.05° (quoted to 0.1°), the first contact 0.5° (quoted in whole
#: degrees); the samples kept and the tubes exactly.
SIZE_TOLERANCE_MB = 0.1
CORNER_TOLERANCE_DEG = 0.05
CONTACT_TOLERANCE_DEG = 0.5
_CLAIMS = {
    "size": re.compile(r"(?:folder of|folder weighs)\s+(\d+(?:\.\d+)?)\s+MB"),
    "samples": re.compile(r"(\d+)–(\d+) of the\s+(\d+)\s+samples"),
    "tubes": re.compile(r"2α = 90°, (\d+) tubes"),
    "first contact": re.compile(r"first contact\s+\((\d+)°\)"),
    "smallest corner": re.compile(
        r"`mesh_smallest_angle_deg`:\s+(\d+(?:\.\d+)?)° for the paper's vault"
    ),
}
#: The figures each page quotes (a check that found none of them would pass on anything).
QUOTED_FIGURES = {
    "README.md": {"size", "samples", "tubes", "first contact"},
    "docs/guide/output.md": set(_CLAIMS),
}


def folder_claims(text: str) -> dict[str, list[re.Match[str]]]:
    """The figures a text quotes about the paper's vault folder, by kind."""
    return {kind: list(pattern.finditer(text)) for kind, pattern in _CLAIMS.items()}


def folder_problems(text: str, folder: Path) -> list[str]:
    """The quoted figures a built folder of the paper's vault contradicts."""
    report = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    mesh = report["mesh"]
    size = sum(p.stat().st_size for p in folder.rglob("*") if p.is_file()) / 1e6
    fewest, most = mesh["mesh_samples_per_crease"]
    kept = f"{fewest}–{most} of {mesh['samples_computed']}"
    corner = mesh["mesh_smallest_angle_deg"]
    contact = report["certificate_frames"]["first_contact"]
    judged = {  # kind: (holds, what the folder says)
        "size": lambda c: (
            abs(float(c[0]) - size) <= SIZE_TOLERANCE_MB,
            f"the folder weighs {size:.2f} MB",
        ),
        "samples": lambda c: (
            f"{c[0]}–{c[1]} of {c[2]}" == kept,
            f"the meshes keep {kept} samples",
        ),
        "tubes": lambda c: (int(c[0]) == report["tubes"], f"the vault has {report['tubes']} tubes"),
        "first contact": lambda c: (
            abs(int(c[0]) - contact) <= CONTACT_TOLERANCE_DEG,
            f"the first contact is at {contact}°",
        ),
        "smallest corner": lambda c: (
            abs(float(c[0]) - corner) <= CORNER_TOLERANCE_DEG,
            f"the smallest triangle corner is {corner:.2f}°",
        ),
    }
    problems = []
    for kind, found in folder_claims(text).items():
        for claim in found:
            holds, fact = judged[kind](claim.groups())
            if not holds:
                problems.append(f"{fact}, quoted '{' '.join(claim.group(0).split())}'")
    return problems


def test_the_figures_quoted_about_the_output_folder_hold(built):
    texts = {page: (ROOT / page).read_text(encoding="utf-8") for page in QUOTED_FIGURES}
    for page, text in texts.items():
        assert {kind for kind, found in folder_claims(text).items() if found} == QUOTED_FIGURES[
            page
        ]
    assert {page: folder_problems(text, built["folder"]) for page, text in texts.items()} == {
        page: [] for page in texts
    }


@pytest.mark.parametrize(
    ("page", "damage", "message"),
    [
        (
            "README.md",
            ("folder of\n9.2 MB", "folder of\n8.0 MB"),
            r"weighs 9\.\d\d MB, quoted 'folder of 8\.0 MB'",
        ),
        (
            "README.md",
            ("keep 83–87 of the 801", "keep 80–87 of the 801"),
            r"keep 83–87 of 801 samples, quoted '80–87",
        ),
        ("README.md", ("2α = 90°, 9 tubes", "2α = 90°, 8 tubes"), r"has 9 tubes, quoted"),
        (
            "README.md",
            ("first contact\n(122°)", "first contact\n(125°)"),
            r"first contact is at 122",
        ),
        ("docs/guide/output.md", ("`: 3.5° for", "`: 5.3° for"), r"corner is 3\.54°, quoted"),
    ],
)
def test_a_figure_the_folder_contradicts_is_found(built, page, damage, message):
    text = (ROOT / page).read_text(encoding="utf-8")
    assert damage[0] in text
    (problem,) = folder_problems(text.replace(damage[0], damage[1]), built["folder"])
    assert re.search(message, problem), problem


# -- the guide's examples run -----------------------------------------------------------------


@pytest.mark.parametrize(
    "page",
    [p.relative_to(ROOT).as_posix() for p in DOC_PAGES if ">>> " in p.read_text(encoding="utf-8")],
)
def test_the_examples_of_a_guide_page_run(page):
    result = doctest.testfile(
        str(ROOT / page), module_relative=False, optionflags=doctest.ELLIPSIS, verbose=False
    )
    assert result.attempted >= 3 and result.failed == 0


# -- the benchmarks' record of a run ----------------------------------------------------------


def test_a_benchmark_run_is_recorded_as_its_printed_text_and_its_figures(tmp_path):
    import datetime
    from dataclasses import dataclass

    run_all = _load(ROOT / "benchmarks" / "run_all.py", "run_all")

    @dataclass(frozen=True)
    class Row:
        benchmark: str
        measure: str
        value: str
        target: str
        status: str

    rows = [Row("arch", "solve vs brentq", "13.4×", "≥ 10×", "pass")]
    started = datetime.datetime(2026, 12, 4, 20, 15, 14, tzinfo=datetime.UTC)
    env = {"curvefold": "0.1.0", "cpus": 2, "load_average": [0.4, 0.5, 0.6]}
    text, data = run_all.save_results(
        tmp_path / "results", started, ["arch"], rows, "## arch\n", env, 12.34
    )
    assert (text.name, data.name) == ("2026-12-04T201514.txt", "2026-12-04T201514.json")
    assert text.read_text(encoding="utf-8") == "## arch\n"
    record = json.loads(data.read_text(encoding="utf-8"))
    assert record == {
        "started": "2026-12-04T20:15:14+00:00",
        "seconds": 12.3,
        "benchmarks": ["arch"],
        **env,
        "rows": [
            {
                "benchmark": "arch",
                "measure": "solve vs brentq",
                "value": "13.4×",
                "target": "≥ 10×",
                "status": "pass",
            }
        ],
    }
    assert set(run_all.NAMES) == {
        p.stem.removeprefix("bench_") for p in (ROOT / "benchmarks").glob("bench_*.py")
    }


# -- the changelog --------------------------------------------------------------------------


def long_entries(changelog: str) -> list[str]:
    """Entries of the Unreleased section longer than two lines (their first words)."""
    unreleased = changelog.split("## [Unreleased]", 1)[1].split("\n## [", 1)[0]
    entries = re.split(r"^- ", unreleased, flags=re.M)[1:]
    return [entry[:40] for entry in entries if len(entry.split("\n\n")[0].strip().splitlines()) > 2]


def test_every_unreleased_change_is_told_in_one_or_two_lines():
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert long_entries(text) == []
    entry = "- The licence is declared as the SPDX expression `MIT`.\n"
    assert entry in text
    longer = entry + "  Measured: nothing, it is a declaration.\n  It reads `MIT`.\n"
    assert long_entries(text.replace(entry, longer)) == ["The licence is declared as the SPDX expr"]


# -- the README's links ---------------------------------------------------------------------


def missing_targets(markdown: str) -> list[str]:
    """The README's relative links and pictures (``[..](path)``, ``src="path"``) that name no file
    of the repository."""
    targets = re.findall(r"\]\(([^)\s#]+)(?:#[^)]*)?\)", markdown) + re.findall(
        r'src="([^"]+)"', markdown
    )
    return [t for t in targets if "://" not in t and not (ROOT / t).exists()]


def test_the_readmes_links_and_pictures_are_files_of_the_repository():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert missing_targets(text) == [] and len(re.findall(r"\]\(docs/", text)) >= 10
    for name in ("vault.png", "folding-motion.png", "crease-pattern.png", "designer.png"):
        assert f"docs/{name}" in text
    assert missing_targets(text.replace("(docs/guide/atlas.md)", "(docs/guide/sweeps.md)")) == [
        "docs/guide/sweeps.md"
    ]
    assert missing_targets('<img src="docs/gone.png">') == ["docs/gone.png"]
