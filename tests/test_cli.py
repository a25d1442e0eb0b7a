"""The command line: stable JSON keys, one-line errors, no partial output.

The command line runs in this process (:func:`run`); a few smoke tests run the real
entry points in a subprocess (:func:`run_subprocess`).
"""

import json
import os

import pytest

from _cli import run, run_subprocess
from curvefold.app.cli import main


def test_arch_json_keys():
    r = run_subprocess("arch", "--a", "0.3", "--p-xy", "0.75", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert abs(out["kappa0_s0"] - 3.16571746805) < 1e-10
    assert abs(out["proportion_change"] - 1.3529721297) < 1e-9
    assert abs(out["p_xz"] - 1.3729001878) < 1e-9


def test_vault_json_without_out_writes_nothing(tmp_path):
    r = run("vault", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    for key in ("kappa0_s0", "proportion_change", "p_xz", "tubes", "max_tubes", "span", "rise"):
        assert key in out
    assert out["tubes"] == out["max_tubes"] == 9
    assert all(c["passed"] for c in out["certificate"])
    assert os.listdir(tmp_path) == []


def test_reproduce_prints_the_paper_table(capsys):
    assert main(["reproduce", "--json"]) == 0
    rows = {r["quantity"]: r for r in json.loads(capsys.readouterr().out)["rows"]}
    assert rows["kappa0_s0"]["paper"] == 3.305
    assert round(rows["kappa0_s0"]["computed"], 11) == 3.16571746805
    assert round(rows["p_xz"]["from_paper_kappa0_s0"], 2) == 1.41


@pytest.mark.parametrize(
    "argv,message",
    [
        (["vault", "--fold-angle", "180"], r"fold_angle must be in \(0, 180\) degrees, got 180"),
        (["vault", "--fold-angle", "nan"], r"fold_angle"),
        (["vault", "--tubes", "50"], r"tubes must be ≤ 9 \(the maximum before regression"),
        (["vault", "--width", "5"], r"width = 5 is past regression for the base tube"),
        (
            ["vault", "--a", "1.5"],
            r"--a 1.5: a must be in \[0, 1\.2707093728\) \(no arch stands "
            r"beyond it: Eq\. \(20\) has no root next to π there\), got 1.5$",
        ),
        (["vault", "--tubes", "many"], r"--tubes: must be a whole number ≥ 1 or 'max', got 'many'"),
        (["vault", "--samples", "100000000"], r"samples"),
        (
            ["arch", "--a", "-1"],
            r"--a -1: a must be in \[0, 1\.2707093728\) \(no arch stands "
            r"beyond it: Eq\. \(20\) has no root next to π there\), got -1",
        ),
        (["check", "missing.fold"], r"missing.fold"),
        (["tube", "nonexistent.toml"], r"nonexistent.toml"),
        (["frobnicate"], r"invalid choice: 'frobnicate'"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(tmp_path, argv, message):
    r = run(*argv, cwd=tmp_path)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("curvefold"), r.stderr
    assert "Traceback" not in r.stderr
    import re

    assert re.search(message, lines[0]), lines[0]
    assert r.stdout == ""
    assert os.listdir(tmp_path) == []  # nothing written, not even a temporary folder


def test_design_file_errors_name_their_location(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('kind = "vault"\n[vault]\nradios = 2.0\n')
    r = run_subprocess("vault", str(bad), "--json", cwd=tmp_path)
    assert r.returncode == 2
    assert "unknown key 'radios'" in r.stderr and "bad.toml" in r.stderr
    evil = tmp_path / "evil.toml"
    evil.write_text(
        "kind = \"tube\"\n[curve]\nkappa = \"__import__('os').system('echo hacked')\"\n"
    )
    r = run_subprocess("tube", str(evil), "--json", cwd=tmp_path)
    assert r.returncode == 2 and r.stdout == ""  # refused, never run: nothing echoed
    assert len(r.stderr.strip().splitlines()) == 1


@pytest.fixture(scope="module")
def tube_folder(tmp_path_factory):
    """A tube from the example design, built at a light sampling, written by the CLI."""
    root = tmp_path_factory.mktemp("cli")
    r = run(
        "tube",
        "examples/tube.toml".replace(
            "examples", os.path.join(os.path.dirname(__file__), "..", "examples")
        ),
        "--samples",
        "121",
        "--out",
        str(root / "tube"),
        "--json",
    )
    assert r.returncode == 0, r.stderr
    return root / "tube", json.loads(r.stdout)


def test_tube_output_folder_is_complete(tube_folder):
    folder, out = tube_folder
    names = set(os.listdir(folder))
    for expected in (
        "report.html",
        "report.json",
        "tube.fold",
        "tube.obj",
        "tube-pattern.dxf",
        "regression-domain.png",
        "width-proportion.png",
        "sheets",
    ):
        assert expected in names, expected
    assert any(n.startswith("tube-pattern") and n.endswith(".svg") for n in names)
    report = json.loads((folder / "report.json").read_text())
    assert all(c["passed"] for c in report["certificate"])
    assert set(report["files"]) >= {"tube.fold", "tube.obj"}
    assert (folder / "report.html").read_text().count("<tr class='pass head'>") == len(
        report["certificate"]
    )
    assert oct((folder / "tube.fold").stat().st_mode & 0o777) != oct(0o600)  # ordinary file modes


def test_check_certifies_the_written_fold_file(tube_folder):
    folder, _ = tube_folder
    r = run("check", str(folder / "tube.fold"), "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["ok"] is True
    assert out["max_isometry_error"] < 1e-4
    assert out["max_face_planarity_error"] < 0.5
    # a corrupted file fails the check: move one vertex of the folded frame
    doc = json.loads((folder / "tube.fold").read_text())
    doc["file_frames"][0]["vertices_coords"][5][2] += 0.05
    bad = folder.parent / "corrupt.fold"
    bad.write_text(json.dumps(doc))
    r = run("check", str(bad), "--json")
    assert r.returncode == 1 and json.loads(r.stdout)["ok"] is False


def test_existing_folder_needs_force(tmp_path):
    target = tmp_path / "out"
    r = run("crease", "--samples", "101", "--out", str(target))
    assert r.returncode == 0, r.stderr
    (target / "keep.txt").write_text("mine")
    r = run("crease", "--samples", "101", "--out", str(target))
    assert r.returncode == 2 and "exists; pass --force" in r.stderr
    assert (target / "keep.txt").read_text() == "mine"
    # a folder curvefold wrote
    r = run("crease", "--samples", "101", "--out", str(target), "--force")
    assert r.returncode == 0, r.stderr
    assert not (target / "keep.txt").exists() and (target / "report.html").exists()
    assert os.listdir(tmp_path) == ["out"]  # no leftovers


def test_unwritable_output_is_one_line(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    r = run("crease", "--samples", "101", "--out", str(blocker / "sub"))
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "parent folder" in r.stderr


@pytest.mark.parametrize(
    "kind,text,message",
    [
        (
            "tube",
            'kind = "tube"\n[curve]\nkappa = "cos(s)"\nlength = 4.0\n',
            r"kappa .*> 0.*at s " r"= 1\.5",
        ),
        ("tube", 'kind = "tube"\n[curve]\nkappa = "1/(s - 1)"\nlength = 2.0\n', r"kappa"),
        ("tube", 'kind = "tube"\n[curve\nkappa = 1\n', r"design\.toml.*line 2"),
        ("tube", 'kind = "tube"\n[curve]\ntau = "9**9**9"\n', r"exponent"),
        (
            "tube",
            'kind = "tube"\n[curve]\ntau = "s.__class__"\n',
            r"attribute access is not " r"allowed",
        ),
        (
            "tube",
            'kind = "tube"\n[tube]\nwidth_left = 50.0\nwidth_right = 50.0\n',
            r"passes the curve " r"of regression",
        ),
        (
            "vault",
            'kind = "vault"\n[vault]\ntubes = 1000\n',
            r"this job needs about .* lower " r"samples .*, \[vault\] tubes or layers",
        ),
        ("vault", 'kind = "vault"\n[vault]\ntubes = 20\n', r"tubes must be ≤ 9"),
        (
            "vault",
            'kind = "vault"\n[vault]\nfold_angle = 0\n',
            r"fold_angle must be in \(0, " r"180\) degrees, got 0",
        ),
        (
            "vault",
            'kind = "vault"\nsamples = 100000000\n',
            r"samples must be an integer in \[9, " r"200000\] \(.*\), got 100000000",
        ),
    ],
)
def test_bad_design_files_are_one_line(tmp_path, kind, text, message):
    import re

    design = tmp_path / "design.toml"
    design.write_text(text)
    r = run(kind, str(design), "--out", str(tmp_path / "out"))
    assert r.returncode == 2, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr
    assert re.search(message, lines[0]), lines[0]
    assert sorted(os.listdir(tmp_path)) == ["design.toml"]  # no output, no temporary folder


def test_atlas_records_invalid_designs_and_goes_on(tmp_path):
    out = tmp_path / "atlas"
    r = run(
        "atlas",
        "--p-xy",
        "0.75,1.0",
        "--a",
        "0.3,1.5",
        "--samples",
        "51",
        "--workers",
        "1",
        "--out",
        str(out),
        "--json",
    )
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout)
    assert (summary["designs"], summary["valid"], summary["invalid"]) == (
        4,
        2,
        {"ConvergenceError": 2},
    )
    records = json.loads((out / "atlas.json").read_text())["records"]
    assert len(records) == 4
    bad = [rec for rec in records if not rec["valid"]]
    assert len(bad) == 2 and all("no standing arch for a = 1.5" in rec["reason"] for rec in bad)
    assert {"atlas.csv", "atlas.json", "atlas.png", "atlas.svg"} <= set(os.listdir(out))


def test_output_flags_override_the_design(tmp_path):
    r = run(
        "tube",
        "--samples",
        "101",
        "--page",
        "A3",
        "--scale",
        "80",
        "--formats",
        "svg",
        "--out",
        str(tmp_path / "t"),
        "--json",
    )
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["design"]["output"]["page"] == "A3" and out["design"]["output"]["scale"] == 80.0
    svg = next(n for n in out["files"] if n.endswith(".svg") and "pattern" in n)
    assert 'width="297mm"' in (tmp_path / "t" / svg).read_text()
    r = run("tube", "--page", "B9", "--json")
    assert r.returncode == 2 and "page" in r.stderr


def test_pattern_flags_tabs_and_rulings(tmp_path):
    def pattern_svg(*flags):
        out = tmp_path / ("p" + "".join(flags).replace("-", ""))
        r = run("tube", "--samples", "81", "--formats", "svg", "--out", str(out), *flags)
        assert r.returncode == 0, r.stderr
        return "".join(p.read_text() for p in sorted(out.glob("tube-pattern*.svg")))

    plain, bare, ruled = pattern_svg(), pattern_svg("--no-glue-tabs"), pattern_svg("--rulings")
    assert 'inkscape:label="reference - glue (not cut)"' in plain
    assert plain.count("<polygon") > bare.count("<polygon") or plain.count(
        "<polyline"
    ) > bare.count("<polyline")
    assert ruled.count("<polyline") > plain.count("<polyline")  # the ruling lines
