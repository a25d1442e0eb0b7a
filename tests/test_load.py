"""``curvefold load`` and the output folders of a design under load, through the command line.

Designs stay small where the check allows (a vault of 3 tubes on 201 samples); the
command's numbers are held against the library's on the same structure, so the boundary
(flags, design files, kPa, supports by kind) is what these tests check.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _cli import run, run_subprocess
from curvefold.app import design_from_dict, parse_design
from curvefold.app._budget import estimate
from curvefold.kernel import readonly
from curvefold.mechanics import (
    ACROSS,
    HalfSnow,
    Loads,
    Material,
    PointLoad,
    SelfWeight,
    Snow,
    StructureModel,
    Supports,
    Wind,
    analyse_load,
)
from curvefold.vault import Vault

EXAMPLES = Path(__file__).parent.parent / "examples"
SMALL = ("--tubes", "3", "--samples", "201")
#: The keys of ``curvefold load --json`` that are stable (the README's).
STABLE = {
    "total_weight",
    "reactions",
    "max_displacement",
    "max_stress",
    "utilisation",
    "fold_mode_gap",
    "soft_modes",
    "buckling_factor",
    "modes",
}


def loaded(*argv: str, cwd=None, status: int | None = None) -> dict:
    """The JSON of ``curvefold load``, which exits ``status`` (1: the structure fails a check;
    None: either verdict, for what does not depend on it)."""
    r = run("load", *argv, "--json", cwd=cwd)
    assert r.returncode in ((0, 1) if status is None else (status,)) and r.stderr == "", r.stderr
    return json.loads(r.stdout)


def refused(r, match: str) -> None:
    lines = r.stderr.splitlines()
    assert (
        r.returncode == 2 and r.stdout == "" and len(lines) == 1 and "Traceback" not in r.stderr
    ), r.stderr
    assert re.search(match, lines[0]), lines[0]


def test_the_vault_stands_on_its_feet_as_the_library_says():
    d = loaded(*SMALL, status=0)
    assert STABLE <= set(d) and d["kind"] == "vault" and d["supported"] == "feet"
    assert (
        d["material"] == "polypropylene"
        and d["thickness"] == 1e-3
        and d["design"]["material"]["material"] == "polypropylene"
    )
    # the feet carry it all
    assert_allclose(d["reactions"], [0, 0, d["total_weight"]], atol=1e-12 * d["total_weight"])
    assert (
        d["soft_modes"] == 1
        and 0 < d["utilisation"] < 1
        and d["buckling_factor"] > 1
        and d["buckling_resolved"]
    )
    assert d["fold_mode_gap"] == pytest.approx(d["modes"][1] / d["modes"][0]) and d[
        "modes"
    ] == sorted(d["modes"])
    t0, t1 = (np.array(v) for v in d["reactions_by_end"].values())
    # the arch's thrust
    assert_allclose(t0[:2], -t1[:2], atol=1e-9 * d["total_weight"]) and abs(t0[1]) > 0.05 * d[
        "total_weight"
    ]
    library = analyse_load(
        Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=201), across=ACROSS.default
    ).to_dict()
    for key in STABLE - {"reactions"}:
        assert_allclose(d[key], library[key], rtol=1e-9, err_msg=key)
    lines = run("load", *SMALL).stdout.splitlines()  # the verdict, the title, then the load
    assert lines[2].startswith(
        "  under load         polypropylene 1 mm, self-weight, pinned at the feet"
    )
    assert any(line.startswith("  buckling_factor") for line in lines)


def test_the_material_and_loads_come_from_flags_and_design_files_alike(tmp_path):
    (tmp_path / "design.toml").write_text(
        'kind = "vault"\nsamples = 201\n[vault]\ntubes = '
        "3\n[material]\nyoungs_modulus = 70e9\npoisson = 0.33\ndensity = 2700.0\nthickness = "
        '0.002\n[loads]\nself_weight = false\nsnow = 0.5\nsupports = "roller"\n'
    )
    from_file = loaded("design.toml", cwd=tmp_path)
    from_flags = loaded(
        *SMALL,
        "--youngs-modulus",
        "70e9",
        "--poisson",
        "0.33",
        "--density",
        "2700",
        "--thickness",
        "0.002",
        "--no-self-weight",
        "--snow",
        "0.5",
        "--supports",
        "roller",
    )
    for key in STABLE | {"applied_load"}:
        assert from_file[key] == from_flags[key], key
    # snow in kPa at the boundary, Pa in the library; a material without a strength has no
    # utilisation
    own = Material.from_values(70e9, 0.33, 2700.0)
    library = analyse_load(
        Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=201),
        own,
        0.002,
        Loads.from_values(self_weight=False, snow=500.0),
        Supports("roller"),
        across=ACROSS.default,
    )
    assert_allclose(from_file["applied_load"], library.static.total_load, rtol=1e-12)
    assert from_file["utilisation"] is None and any(
        "no strength" in note for note in from_file["notes"]
    )
    # on rollers the feet carry the vertical only
    for reaction in from_file["reactions_by_end"].values():
        assert_allclose(reaction[:2], 0, atol=1e-9 * abs(from_file["applied_load"][2]))
    # a named material given by a flag replaces the file's own values; a point load sits on the apex
    named = loaded("design.toml", "--material", "aluminium", "--point-load", "10", cwd=tmp_path)
    assert (
        named["material"] == "aluminium"
        and named["design"]["material"].get("youngs_modulus") is None
    )
    assert_allclose(named["applied_load"][2], library.static.total_load[2] - 10.0, rtol=1e-12)


def test_the_load_cases_come_from_flags_keys_and_listed_cases_as_the_library_takes_them(tmp_path):
    """Snow on half the span and wind by their keys or flags (kPa), a point load anywhere listed
    as a case: the same applied load as the library's cases in Pa, the cases told in the JSON,
    and the design's cases kept through its dict."""
    (tmp_path / "design.toml").write_text(
        'kind = "vault"\nsamples = 201\n[vault]\ntubes = 3\n'
        '[loads]\nsnow_half = 0.4\nsnow_half_side = "start"\nwind = 0.6\nwind_cp = -0.8\n'
        '[[loads.case]]\ntype = "point"\nforce = 30.0\nat = [-0.1, 1.0, 1.1]\n'
        '[[loads.case]]\ntype = "snow"\nload = 0.2\n'
    )
    from_file = loaded("design.toml", cwd=tmp_path)
    cases = (
        SelfWeight(),
        HalfSnow(400.0, "start"),
        Wind(600.0, -0.8),
        PointLoad(30.0, (-0.1, 1.0, 1.1)),
        Snow(200.0),
    )
    library = analyse_load(
        Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=201),
        loads=Loads(cases),
        across=ACROSS.default,
    )
    assert_allclose(
        from_file["applied_load"],
        library.static.total_load,
        rtol=1e-12,
        atol=1e-12 * library.total_weight,
    )
    assert from_file["loads"]["described"] == [c.describe() for c in cases]
    assert from_file["design"]["loads"]["case"] == [c.to_dict() for c in cases[3:]]
    design = parse_design((tmp_path / "design.toml").read_text())
    assert design_from_dict(design.to_dict()) == design and design.loads.cases() == Loads(cases)
    flags = loaded(
        *SMALL,
        "--snow-half",
        "0.4",
        "--snow-half-side",
        "start",
        "--wind",
        "0.6",
        "--wind-cp",
        "-0.8",
    )
    keys = analyse_load(
        Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=201),
        loads=Loads(cases[:3]),
        across=ACROSS.default,
    )
    assert_allclose(
        flags["applied_load"], keys.static.total_load, rtol=1e-12, atol=1e-12 * keys.total_weight
    )
    assert (
        run("load", *SMALL, "--wind", "0.6")
        .stdout.splitlines()[2]
        .endswith("self-weight + wind 0.6 kPa × c_p 1 normal to the sheets, pinned at the feet")
    )


def test_a_bad_load_case_is_one_line_naming_its_entry(tmp_path):
    for entries, match in [
        (
            '[[loads.case]]\ntype = "hail"\n',
            r"design\.toml: \[\[loads\.case\]\] 1: type must be one of \"self_weight\", \"snow\", "
            r"\"snow_half\", \"wind\", \"wind_zones\", \"point\", got string 'hail'$",
        ),
        (
            '[[loads.case]]\ntype = "snow"\n[[loads.case]]\ntype = "wind"\ncp = 9\n',
            r"design\.toml: \[\[loads\.case\]\] 2: wind cp must be in \[-3, 3\] "
            r"\(EN 1991-1-4's coefficients lie within ±3\), got 9\.0$",
        ),
        (
            '[[loads.case]]\ntype = "point"\nforce = 1.0\nat = [0, 1]\n',
            r"design\.toml: \[\[loads\.case\]\] 1: point at must be a point \[x, y, z\] in m, "
            r"got array \[0, 1\]$",
        ),
        (
            '[[loads.case]]\ntype = "point"\nforce = 1.0\nat = [0, 1, -2]\n',
            r"point load at \[0, 1, -2\] m is 2\.\d+ m from the structure's nearest node, "
            r"farther than the 0\.104 m allowed",
        ),
        (
            "[loads]\ncase = 3\n",
            r"design\.toml: \[\[loads\.case\]\] must be an array of tables "
            r"\(\[\[loads\.case\]\] entries "
            r"with a type\), got 3$",
        ),
    ]:
        (tmp_path / "design.toml").write_text(
            f'kind = "vault"\nsamples = 201\n[vault]\ntubes = 3\n{entries}'
        )
        refused(run("load", "design.toml", cwd=tmp_path), match)
    refused(run("load", *SMALL, "--wind-cp", "-4"), r"--wind-cp -4: wind_cp must be in \[-3, 3\]")
    refused(
        run("load", *SMALL, "--snow-half", "2000"),
        r"--snow-half 2000: snow_half must be in \[0, 1000\] kPa",
    )


def test_the_size_strength_and_creases_come_from_flags_as_the_library_takes_them():
    """--radius sizes the vault in metres (its sheet's area, so its weight, as the square),
    --strength and --crease-stiffness reach the library unchanged."""
    base = loaded(*SMALL)
    d = loaded(
        *SMALL,
        "--radius",
        "2",
        "--youngs-modulus",
        "1.5e9",
        "--poisson",
        "0.4",
        "--density",
        "900",
        "--strength",
        "2e7",
        "--crease-stiffness",
        "0.5",
    )
    own = Material.from_values(1.5e9, 0.4, 900.0, 2e7)
    library = analyse_load(
        Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=201, radius=2.0),
        own,
        1e-3,
        crease_stiffness=0.5,
        across=ACROSS.default,
    ).to_dict()
    for key in STABLE - {"reactions"}:
        assert_allclose(d[key], library[key], rtol=1e-9, err_msg=key)
    assert d["crease_stiffness"] == 0.5 and d["utilisation"] == pytest.approx(
        d["max_stress"] / 2e7, rel=1e-12
    )
    assert d["total_weight"] / base["total_weight"] == pytest.approx(4 * 900.0 / 905.0, rel=1e-9)


def test_a_design_file_s_bad_material_or_loads_is_one_line(tmp_path):
    for section, line, match in [
        (
            "material",
            "poisson = 0.6\nyoungs_modulus = 1e9\ndensity = 900.0",
            r"design\.toml: " r"\[material\] poisson must be in \(-1, 0\.5\)",
        ),
        (
            "material",
            "thickness = -0.001",
            r"design\.toml: \[material\] thickness must be in " r"\(0, 1\) m",
        ),
        (
            "loads",
            'supports = "glued"',
            r"design\.toml: \[loads\] supports must be one of "
            r"\"pinned\", \"roller\", got string 'glued'",
        ),
        ("loads", "snow = 0.5\nhail = 1", r"design\.toml: \[loads\] unknown key 'hail'"),
    ]:
        (tmp_path / "design.toml").write_text(
            f'kind = "vault"\nsamples = 201\n[vault]\ntubes = 3\n[{section}]\n{line}\n'
        )
        refused(run("load", "design.toml", cwd=tmp_path), match)
        # the same sections, checked the same way by every command
        refused(run("vault", "design.toml", cwd=tmp_path), match)


@pytest.mark.parametrize(
    ("example", "samples", "soft"), [("tube.toml", "201", 2), ("cellular-block.toml", "101", 1)]
)
def test_tubes_and_blocks_are_held_at_both_end_sections(example, samples, soft):
    # the tube buckles under its own weight, the block's factor is below 10: both fail (exit 1),
    # their figures printed all the same
    d = loaded(str(EXAMPLES / example), "--samples", samples, status=1)
    # a free tube warps its end sections too (the conjecture)
    assert d["supported"] == "ends" and d["soft_modes"] == soft
    # rounding (of forces summed over a soft structure: 2e-11 of its weight)
    assert d["equilibrium_error"] < 1e-14
    assert_allclose(d["reactions"], [0, 0, d["total_weight"]], atol=1e-10 * d["total_weight"])
    # both ends carry it
    assert all(r[2] > 0.1 * d["total_weight"] for r in d["reactions_by_end"].values())


@pytest.mark.parametrize(
    ("argv", "match"),
    [
        (
            ["--youngs-modulus", "-1", "--poisson", "0.3", "--density", "900"],
            r"--youngs-modulus -1: youngs_modulus must be in \[1000, 1e13\] Pa .*got -1$",
        ),
        (
            ["--thickness", "0"],
            r"--thickness 0: thickness must be in \(0, 1\) m \(a sheet, not a " r"block\), got 0$",
        ),
        (
            ["--youngs-modulus", "2e9", "--poisson", "0.5", "--density", "900"],
            r"poisson must be "
            r"in \(-1, 0\.5\) \(an isotropic solid is stable only there\), got 0\.5$",
        ),
        (
            ["--youngs-modulus", "2e9"],
            r"\[material\] your own material needs youngs_modulus, "
            r"poisson and density \(missing: poisson, density\)",
        ),
        (
            ["--material", "aluminium", "--density", "900"],
            r"\[material\] give material or your " r"own values \(density\), not both$",
        ),
        (
            ["--material", "steel"],
            r"--material steel: material must be one of \"polypropylene\", "
            r"\"paperboard\", \"aluminium\", \"plywood\", got steel$",
        ),
        (["--snow", "-1"], r"--snow -1: snow must be in \[0, 1000\] kPa"),
        (["--no-self-weight"], r"no load: give self-weight, snow or a point load$"),
        (
            ["--crease-stiffness", "0"],
            r"crease_stiffness must be > 0 N·m/rad/m \(a crease of no "
            r"stiffness leaves the folding motion free\), got 0$",
        ),
        (
            [str(EXAMPLES / "single-fold.toml")],
            r"kind = 'crease' but the command is 'load', " r"which takes vault, tube, block$",
        ),
        ([str(EXAMPLES / "tube.toml"), "--a", "0.4"], r"unknown option 'a' for kind 'tube'"),
    ],
)
def test_bad_input_is_one_line(argv, match):
    refused(run("load", *SMALL[2:], *argv), match)


def test_a_structure_still_a_mechanism_is_one_line_naming_the_free_motion(monkeypatch):
    """Both end sections held leave no design of the command line free; held at two nodes of a
    foot, a vault turns about them."""
    monkeypatch.setattr(StructureModel, "feet", property(lambda self: readonly(self.ends[:2])))
    refused(
        run("load", *SMALL),
        r"the structure is still a mechanism under these supports: a "
        r"rigid motion \(rotation about the axis along \[.*\] through \[.*\] m\) is free \(it "
        r"stretches no bar and turns no hinge\)",
    )


def test_the_budget_counts_the_mechanics_before_any_work(monkeypatch):
    design = parse_design('kind = "vault"\nsamples = 3201\n[vault]\ntubes = 9')
    assert (
        estimate(design.with_mechanics(), files=False).total
        > estimate(design, files=False).total + 150 * 2**20
    )
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "400M")
    argv = ("--samples", "3201", "--tubes", "9")
    assert run("vault", *argv, "--json").returncode == 0  # the geometry alone fits
    refused(
        run("load", *argv),
        r"^curvefold: error: curvefold load --samples 3201 --tubes 9: "
        r"this job needs about .* more than the budget of 400 MiB",
    )


def test_the_real_entry_point_prints_strict_json_and_refuses_in_one_line():
    r = run_subprocess("load", "--tubes", "2", "--samples", "101", "--json")
    assert r.returncode == 0, r.stderr
    assert STABLE <= set(json.loads(r.stdout))
    r = run_subprocess(
        "load",
        "--tubes",
        "2",
        "--samples",
        "101",
        "--poisson",
        "0.7",
        "--youngs-modulus",
        "1e9",
        "--density",
        "1",
    )
    assert (
        r.returncode == 2
        and r.stderr.count("\n") == 1
        and "poisson must be in (-1, 0.5)" in r.stderr
    )


def test_the_output_folder_holds_the_mechanics(tmp_path):
    pygltflib = pytest.importorskip("pygltflib")
    r = run("load", *SMALL, "--formats", "glb", "--out", "v", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    printed, folder = json.loads(r.stdout), tmp_path / "v"
    report = json.loads((folder / "report.json").read_text())
    for key in STABLE:
        assert report["mechanics"][key] == printed[key], key
    page = (folder / "report.html").read_text()
    assert (
        "Under load: will it stand?" in page
        and 'src="deflection.png"' in page
        and 'src="modes.png"' in page
    )
    assert (folder / "deflection.png").is_file() and (folder / "modes.png").is_file()
    gltf = pygltflib.GLTF2.load(str(folder / "vault.glb"))
    names = gltf.meshes[0].extras["targetNames"]
    scale = printed["deflection_scale"]
    assert f"deflection × {scale:g}" in names and [n for n in names if n.startswith("mode ")][
        0
    ].startswith("mode 1 (0.")
    from _gltf import accessor, target_position

    blob = gltf.binary_blob()
    k = names.index(f"deflection × {scale:g}")
    moved = np.concatenate(
        [
            np.linalg.norm(
                accessor(gltf, blob, target_position(m.primitives[0].targets[k])), axis=1
            )
            for m in gltf.meshes
        ]
    )
    # glTF y is up
    base = np.concatenate(
        [accessor(gltf, blob, m.primitives[0].attributes.POSITION)[:, 1] for m in gltf.meshes]
    )
    assert (
        moved.max() <= scale * printed["max_displacement"] * (1 + 1e-5)
        and moved.max() > 0.5 * scale * printed["max_displacement"]
    )
    assert moved[np.abs(base) < 1e-9].max() < 1e-6 * moved.max()  # the pinned feet do not move
    # each mode at the stated amplitude: its largest nodal displacement, the mesh's samples among
    # the model's nodes
    amplitude = printed["mode_amplitude"]
    for k in (names.index(n) for n in names if n.startswith("mode ")):
        mode = np.concatenate(
            [
                np.linalg.norm(
                    accessor(gltf, blob, target_position(m.primitives[0].targets[k])), axis=1
                )
                for m in gltf.meshes
            ]
        )
        assert amplitude * (1 - 1e-5) < mode.max() <= amplitude * (1 + 1e-5)
    assert len([n for n in names if n.startswith("mode ")]) == 3
    # the reactions balance the weight: their rounding is shown as 0, the arch's thrust at each end
    # as measured
    assert f'<td class="num">(0, 0, {printed["total_weight"]:.6g})</td>' in page
    # a vault with a material writes the same section; without one, none
    r = run(
        "vault",
        *SMALL,
        "--formats",
        "fold",
        "--material",
        "aluminium",
        "--out",
        "a",
        "--json",
        cwd=tmp_path,
    )
    assert r.returncode == 0 and json.loads(r.stdout)["mechanics"]["material"] == "aluminium"
    r = run("vault", *SMALL, "--formats", "fold", "--out", "b", "--json", cwd=tmp_path)
    assert (
        "mechanics" not in json.loads(r.stdout) and not (tmp_path / "b" / "deflection.png").exists()
    )
    # a tube whose design file says what loads it is held at both end sections, in its report too
    (tmp_path / "tube.toml").write_text(
        (EXAMPLES / "tube.toml").read_text() + "\n[loads]\nsnow = 0.1\n"
    )
    r = run(
        "tube",
        "tube.toml",
        "--samples",
        "101",
        "--formats",
        "fold",
        "--out",
        "t",
        "--json",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    assert (
        json.loads((tmp_path / "t" / "report.json").read_text())["mechanics"]["supported"] == "ends"
    )
    assert "held at both end sections of every tube" in (tmp_path / "t" / "report.html").read_text()
