"""The files a person receives, read as their tools read them: the GLB's timeline, the FOLD
file's frames on the ground, the legend of a single fold."""

from __future__ import annotations

import html
import json
import re

import numpy as np
import pytest

from _cli import run
from _gltf import accessor
from curvefold.app._design import load_design
from curvefold.figures._report import describe_file
from curvefold.io._formats import FORMATS
from curvefold.io._gltf import LOOP_SECONDS

#: Blender's default timeline: frames 1–250 at 24 frames per second.
BLENDER_FRAMES, BLENDER_FPS = 250, 24


@pytest.fixture(scope="module")
def vault_folder(tmp_path_factory):
    root = tmp_path_factory.mktemp("files")
    result = run("vault", "--samples", "41", "--formats", "fold,glb,svg", "--out", "v", cwd=root)
    assert result.returncode in (0, 1), result.stderr  # 1: a certificate check failed
    return root / "v"


def test_the_glb_loop_fits_blenders_default_timeline(vault_folder):
    pygltflib = pytest.importorskip("pygltflib")
    gltf = pygltflib.GLTF2.load(str(vault_folder / "vault.glb"))
    blob = gltf.binary_blob()
    (animation,) = gltf.animations
    (sampler,) = animation.samplers
    times = accessor(gltf, blob, sampler.input)
    assert times[0] == 0 and np.all(np.diff(times) > 0)
    # the whole loop, and its last frame, within frames 1–250 (frame 1 at t = 0)
    assert times[-1] <= LOOP_SECONDS + 1e-6
    assert 1 + times[-1] * BLENDER_FPS <= BLENDER_FRAMES
    # it ends where it starts (the design state), so the timeline's wrap does not jump
    weights = accessor(gltf, blob, sampler.output).reshape(len(times), -1)
    np.testing.assert_array_equal(weights[0], weights[-1])
    record = json.loads(json.dumps(gltf.asset.extras))["curvefold"]
    assert record["seconds_per_state"] == pytest.approx(float(np.diff(times)[0]))


def test_every_frame_of_a_vault_stands_on_the_ground(vault_folder):
    doc = json.loads((vault_folder / "vault.fold").read_text(encoding="utf-8"))
    angles = doc["curvefold:design"]["fold_angles"]
    assert max(angles) > doc["curvefold:metadata"]["fold_angle_deg"]  # frames past the design
    lowest = [float(np.min(np.array(f["vertices_coords"])[:, 2])) for f in doc["file_frames"]]
    np.testing.assert_allclose(lowest, 0.0, atol=1e-9)
    # on both feet: the end sections, on the ground in the design frame, level in every frame
    frames = [np.array(f["vertices_coords"]) for f in doc["file_frames"]]
    design = frames[angles.index(doc["curvefold:metadata"]["fold_angle_deg"])]
    feet = np.flatnonzero(np.abs(design[:, 2]) <= 1e-9)
    far = design[feet, 1] >= design[feet, 1].mean()
    for x in frames:
        assert x[feet[~far], 2].mean() == pytest.approx(x[feet[far], 2].mean(), abs=1e-9)
    # both feet on the ground again: the start and end sections level in every frame
    check = run("check", str(vault_folder / "vault.fold"), "--rebuild")
    assert check.returncode == 0, check.stdout


def test_a_single_folds_legend_names_no_seam(tmp_path):
    assert run("crease", "--formats", "svg", "--out", "c", cwd=tmp_path).returncode in (0, 1)
    (pattern,) = (tmp_path / "c").glob("*.svg")
    assert "glue the edges named alike" not in pattern.read_text(encoding="utf-8")


def test_a_vaults_legend_names_its_seams(vault_folder):
    pages = sorted(vault_folder.glob("vault-pattern*.svg"))
    assert pages and all(
        "glue the edges named alike" in page.read_text(encoding="utf-8") for page in pages
    )


def test_the_folder_holds_the_design_file_that_builds_it_again(vault_folder, tmp_path):
    report = json.loads((vault_folder / "report.json").read_text(encoding="utf-8"))
    design = load_design(vault_folder / "design.toml")
    assert "design.toml" in report["files"]
    assert design.to_dict()["vault"]["tubes"] == report["tubes"] == 9  # "max", resolved
    rebuilt = run("vault", str(vault_folder / "design.toml"), "--out", "again", cwd=tmp_path)
    assert rebuilt.returncode in (0, 1), rebuilt.stderr
    first, again = (
        json.loads((folder / "vault.fold").read_text(encoding="utf-8"))
        for folder in (vault_folder, tmp_path / "again")
    )
    assert [f["vertices_coords"] for f in first["file_frames"]] == [
        f["vertices_coords"] for f in again["file_frames"]
    ]
    assert first["vertices_coords"] == again["vertices_coords"]
    assert (tmp_path / "again" / "design.toml").read_text(encoding="utf-8") == (
        vault_folder / "design.toml"
    ).read_text(encoding="utf-8")


def test_the_report_shows_the_design_file_and_the_tubes_built(vault_folder):
    page = (vault_folder / "report.html").read_text(encoding="utf-8")
    assert "as a design file holds it" not in page
    text = (vault_folder / "design.toml").read_text(encoding="utf-8")
    assert html.escape(text) in page and "curvefold vault design.toml" in page
    tubes = re.search(r"<code>tubes</code></td><td[^>]*>([^<]*)<", page)
    assert tubes and tubes.group(1) == "9"
    report = json.loads((vault_folder / "report.json").read_text(encoding="utf-8"))
    counts = report["mesh"]["mesh_samples_per_crease"]
    assert isinstance(counts, list) and all(isinstance(n, int) for n in counts)
    assert counts[0] <= counts[1] <= report["mesh"]["samples_computed"]


def test_the_report_describes_the_assembly_guide_as_such():
    assert describe_file("assembly.pdf") == FORMATS["assembly"].holds
    assert describe_file("assembly.pdf").startswith("the assembly guide")
    assert describe_file("vault-pattern.pdf") == FORMATS["pdf"].holds
    assert describe_file("design.toml").startswith("the design file")


def test_a_single_folds_design_file_builds_it_again(tmp_path):
    assert run("crease", "--formats", "fold", "--out", "c", cwd=tmp_path).returncode in (0, 1)
    design = load_design(tmp_path / "c" / "design.toml")
    assert design.kind == "crease"
    again = run("crease", str(tmp_path / "c" / "design.toml"), "--json")
    first = json.loads((tmp_path / "c" / "report.json").read_text(encoding="utf-8"))
    assert again.returncode in (0, 1), again.stderr
    assert json.loads(again.stdout)["design"] == first["design"]


def test_frames_with_nothing_to_stand_on_are_left_as_they_are():
    from curvefold import Crease, Lattice, SpaceCurve, Structure
    from curvefold.geometry._fold_arrays import fold_arrays
    from curvefold.geometry._standing import standing_frames

    curve = SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)
    tube = Structure.tube(Lattice.from_crease(Crease.from_curve(curve), 0.1, 0.1))
    without_design = fold_arrays(tube, fold_angles=[0, 45])  # the design angle is 90°
    assert standing_frames(without_design) is without_design.folded
    # the design frame is there, but a tube touches z = 0 at one vertex only: no two feet
    floating = fold_arrays(tube, fold_angles=[45, 90])
    assert np.sum(np.abs(floating.folded[1][1].vertices_coords[:, 2]) <= 1e-9) == 1
    assert standing_frames(floating) is floating.folded
    assert standing_frames(floating, tol=-1.0) is floating.folded  # nothing on the ground


def _design_frame(fold_file) -> np.ndarray:
    """The vertices of a FOLD file's frame at the design angle (model units)."""
    doc = json.loads(fold_file.read_text(encoding="utf-8"))
    angles = doc["curvefold:design"]["fold_angles"]
    design = angles.index(doc["curvefold:metadata"]["fold_angle_deg"])
    return np.array(doc["file_frames"][design]["vertices_coords"])


@pytest.mark.parametrize("scale", [None, 50.0])
def test_the_stl_has_the_crease_patterns_scale(tmp_path, scale):
    """trimesh reads the STL at the pattern's scale, given (``--scale 50``, mm per model unit) or
    fitted to the page (as the SVG's footer states it), not at 1000 mm per model unit: its
    extent is the FOLD file's design frame times that scale (to the STL's 32-bit floats), and
    its header says the scale. It is an open surface (trimesh: not watertight)."""
    trimesh = pytest.importorskip("trimesh")
    extra = () if scale is None else ("--scale", f"{scale:g}")
    result = run(
        "vault", "--samples", "41", "--formats", "fold,stl,svg", *extra, "--out", "v", cwd=tmp_path
    )
    assert result.returncode in (0, 1), result.stderr
    folder = tmp_path / "v"
    footer = (folder / "vault-pattern-p1.svg").read_text(encoding="utf-8")
    (stated,) = set(re.findall(r"1 model unit = ([0-9.]+) mm", footer))
    assert scale is None or float(stated) == scale
    header = (folder / "vault.stl").read_bytes()[:80].decode("ascii").rstrip()
    assert header.endswith(f", unit mm, 1 model unit = {stated} mm, z up")
    mesh = trimesh.load(folder / "vault.stl")
    model = _design_frame(folder / "vault.fold")
    np.testing.assert_allclose(
        np.ptp(mesh.vertices, axis=0), float(stated) * np.ptp(model, axis=0), rtol=1e-6
    )
    assert float(stated) < 500.0 and not mesh.is_watertight
    assert "not a solid" in describe_file("vault.stl")


def test_a_single_folds_3dm_has_the_crease_pattern_and_plain_names(tmp_path):
    """rhino3dm reads a single fold's 3dm as the vault's: the crease-pattern layers, one per
    operation, hold its pattern at its printed size; its objects make one group, the fold's,
    and its strips are the left and the right one, nothing named after a tube. The STL's
    surface (trimesh, mm²) has the area of the pattern's cut outline (the 3dm's, in the
    document's metres): folding keeps lengths and areas."""
    rhino3dm = pytest.importorskip("rhino3dm")
    trimesh = pytest.importorskip("trimesh")
    result = run("crease", "--formats", "3dm,stl,svg", "--out", "c", cwd=tmp_path)
    assert result.returncode in (0, 1), result.stderr
    model = rhino3dm.File3dm.Read(str(tmp_path / "c" / "crease.3dm"))
    layers = [layer.FullPath for layer in model.Layers]
    assert {
        "crease pattern::cut",
        "crease pattern::score - valley",
        "crease pattern::pages",
    } <= set(layers)
    assert [g.Name for g in model.Groups] == ["single fold"]
    names = {o.Attributes.Name for o in model.Objects}
    assert {"single fold", "left strip", "right strip"} <= names
    assert not any("tube" in n for n in names)
    assert not any(dict(o.Attributes.GetUserStrings()).get("curvefold:tube") for o in model.Objects)
    (cut,) = [
        o.Geometry
        for o in model.Objects
        if layers[o.Attributes.LayerIndex] == "crease pattern::cut"
    ]
    point = cut.Point  # a degree-1 NURBS curve: its control points are the outline's
    xy = 1000.0 * np.array([[point(i).X, point(i).Y] for i in range(cut.PointCount)])  # m to mm
    area = 0.5 * abs(np.dot(xy[:-1, 0], xy[1:, 1]) - np.dot(xy[1:, 0], xy[:-1, 1]))
    stl = trimesh.load(tmp_path / "c" / "crease.stl")
    # 3e-8 apart: the STL's 32-bit floats (the mesh's triangles and the flat outline share
    # their vertices, and each triangle keeps its area when folded)
    assert stl.area == pytest.approx(area, rel=1e-6)


def test_a_tubes_sheets_are_named_plainly(tmp_path):
    """A tube's sheet is "tube 1 · sheet A" on its pattern, not "tube · tube 1 · sheet A" (the kind
    said twice); a vault's keeps its kind ("vault · tube 1 · sheet A")."""
    from curvefold.geometry._sheets import sheets
    from curvefold.vault import Vault

    result = run("tube", "--formats", "svg", "--out", "t", cwd=tmp_path)
    assert result.returncode in (0, 1), result.stderr
    words = " ".join(p.read_text(encoding="utf-8") for p in (tmp_path / "t").glob("*.svg"))
    assert ">tube 1 · sheet A<" in words and "tube · tube" not in words
    structure = Vault.from_design(samples=21, tubes=1).structure
    assert sheets(structure, name="vault")[0].label == "vault · tube 1 · sheet A"
