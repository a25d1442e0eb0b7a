"""OBJ / STL / PLY / GLB / 3dm writers, read back with readers curvefold did not write."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from _gltf import accessor, target_position, to_gltf
from _meshes import oblique_motion, strip_motion
from _node import run_node
from curvefold.geometry import Mesh
from curvefold.io import (
    GlbOptions,
    RhinoOptions,
    crease_polylines,
    write_3dm,
    write_glb,
    write_obj,
    write_ply,
    write_stl,
)
from curvefold.kernel import InputError


@pytest.fixture
def tube():
    """Square tube (4 panels, 2 rows) folding 0 → 90 degrees in 4 states; seams at both ends."""
    return strip_motion(4, 2, seam=True, offset=(0.25, -0.5, 0.125))


def _only(tmp_path: Path, name: str) -> None:
    """Exactly one file in the folder: ``name`` (no temporary file left over)."""
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]


def _validate_gltf(path: Path) -> dict:
    return run_node("validate_gltf.mjs", str(path))


# --- crease polylines ------------------------------------------------------------------------


def test_polylines_chain_straight_creases(tube):
    mesh = tube.state(2)
    folds = crease_polylines(mesh, "fold")
    assert len(folds) == 3 and all(len(p) == 3 for p in folds)
    x = mesh.vertices_coords
    for p in folds:  # each fold line runs along y at one x position of the crease pattern
        assert_allclose(
            tube.crease_pattern.vertices_coords[p, 0], tube.crease_pattern.vertices_coords[p[0], 0]
        )
        assert_allclose(np.diff(x[p, 1]) ** 2, 0.25)
    boundary = crease_polylines(mesh, "boundary")
    assert sorted(len(p) for p in boundary) == [5, 5]
    both = crease_polylines(mesh, ("boundary", "seam"))
    assert len(both) == 1 and both[0][0] == both[0][-1] and len(both[0]) == 13  # closed outline


def test_polylines_split_turning_rulings(tube):
    mesh = tube.state(2)  # 60-degree folds: a ruling turns at every fold line
    assert sorted(len(p) for p in crease_polylines(mesh, "ruling")) == [5]
    split = crease_polylines(mesh, "ruling", split_angle_deg=1e-3)
    assert len(split) == 4 and all(len(p) == 2 for p in split)
    flat = tube.state(0)
    assert [len(p) for p in crease_polylines(flat, "ruling", split_angle_deg=1e-3)] == [5]


def test_polylines_reject_unknown_kind(tube):
    with pytest.raises(InputError, match="kinds must be among"):
        crease_polylines(tube.crease_pattern, "crease")


# --- OBJ ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("up", ["y", "z"])
def test_obj_read_back_by_trimesh(tmp_path, tube, up):
    """Y-up by default, as OBJ readers expect: the model's +z is the file's +y (a rotation)."""
    trimesh = pytest.importorskip("trimesh")
    mesh = tube.state(2)
    write_obj(
        tmp_path / "m.obj",
        mesh,
        unit="mm",
        metadata={"panels": 4},
        **({} if up == "y" else {"up": "z"}),
    )
    _only(tmp_path, "m.obj")
    back = trimesh.load(tmp_path / "m.obj", force="mesh", process=False)
    assert back.vertices.shape == mesh.vertices_coords.shape
    assert back.faces.shape == mesh.faces_vertices.shape
    x = mesh.vertices_coords
    want = np.stack([x[:, 0], x[:, 2], -x[:, 1]], axis=1) if up == "y" else x
    assert_allclose(back.triangles, want[mesh.faces_vertices], atol=1e-6, rtol=0)
    assert ("# axes: +Y up" in (tmp_path / "m.obj").read_text()) is (up == "y")
    with pytest.raises(InputError, match="up must be"):
        write_obj(tmp_path / "n.obj", mesh, up="x")


def test_obj_line_groups(tmp_path, tube):
    mesh = tube.state(3)
    write_obj(tmp_path / "m.obj", mesh, unit="mm", metadata={"panels": 4})
    text = (tmp_path / "m.obj").read_text()
    assert "# unit: mm" in text and "# panels: 4" in text
    groups: dict[str, list[list[int]]] = {}
    current = None
    for line in text.splitlines():
        if line.startswith("g "):
            current = line[2:]
            groups[current] = []
        elif line.startswith("l "):
            groups[current].append([int(i) - 1 for i in line.split()[1:]])
    assert list(groups) == ["surface", "fold", "seam", "boundary"]
    assert len(groups["fold"]) == 3 and len(groups["seam"]) == 2
    for kind in ("fold", "seam", "boundary"):
        edges = {frozenset(pair) for line in groups[kind] for pair in zip(line, line[1:])}
        want = {frozenset(e) for e in mesh.edges_vertices[mesh.edges_kind == kind].tolist()}
        assert edges == want, kind


# --- STL / PLY -----------------------------------------------------------------------------------


def test_stl_read_back_by_trimesh(tmp_path, tube):
    trimesh = pytest.importorskip("trimesh")
    mesh = tube.state(1)
    write_stl(tmp_path / "m.stl", mesh)
    _only(tmp_path, "m.stl")
    # binary
    assert (tmp_path / "m.stl").read_bytes()[80:84] == np.uint32(len(mesh.faces_vertices)).tobytes()
    back = trimesh.load(tmp_path / "m.stl")
    assert len(back.faces) == len(mesh.faces_vertices)
    assert len(back.vertices) == len(mesh.vertices_coords)
    assert_allclose(back.triangles, mesh.vertices_coords[mesh.faces_vertices], atol=1e-6, rtol=0)


def test_stl_in_millimetres_says_its_unit_in_its_header(tmp_path, tube):
    """Slicers read STL lengths as millimetres: a model in metres (the model unit's convention)
    is written ×1000."""
    trimesh = pytest.importorskip("trimesh")
    mesh = tube.state(1)
    write_stl(tmp_path / "mm.stl", mesh, to_unit="mm")
    write_stl(tmp_path / "model.stl", mesh)
    header = (tmp_path / "mm.stl").read_bytes()[:80]
    # never "solid": binary
    assert header.rstrip().decode("ascii").endswith(", unit mm, z up") and header.startswith(
        b"curvefold "
    )
    assert b"unit model units (1 model unit = 1 m)" in (tmp_path / "model.stl").read_bytes()[:80]
    back, model = trimesh.load(tmp_path / "mm.stl"), trimesh.load(tmp_path / "model.stl")
    assert_allclose(back.triangles, 1000.0 * model.triangles, rtol=1e-6)
    assert_allclose(
        back.triangles, 1000.0 * mesh.vertices_coords[mesh.faces_vertices], rtol=1e-6, atol=1e-4
    )
    write_stl(tmp_path / "in.stl", mesh, unit="mm", to_unit="in")
    assert_allclose(
        trimesh.load(tmp_path / "in.stl").triangles,
        mesh.vertices_coords[mesh.faces_vertices] / 25.4,
        rtol=1e-6,
        atol=1e-7,
    )
    with pytest.raises(InputError, match="to_unit must be one of"):
        write_stl(tmp_path / "x.stl", mesh, to_unit="furlong")


def test_stl_at_a_print_scale_says_it_and_refuses_a_scale_that_is_not_one(tmp_path, tube):
    """``scale`` (mm per model unit, a crease pattern's) sizes the STL as a print of that
    scale in the file's unit, whatever the model unit counts as; the header states it."""
    trimesh = pytest.importorskip("trimesh")
    mesh = tube.state(1)
    true = mesh.vertices_coords[mesh.faces_vertices]
    for unit, factor in (("mm", 80.0), ("cm", 8.0), ("in", 80.0 / 25.4)):
        write_stl(tmp_path / f"{unit}.stl", mesh, to_unit=unit, scale=80.0)
        header = (tmp_path / f"{unit}.stl").read_bytes()[:80].decode("ascii").rstrip()
        assert header.endswith(f", unit {unit}, 1 model unit = {factor:.6g} {unit}, z up")
        back = trimesh.load(tmp_path / f"{unit}.stl").triangles
        assert_allclose(back, factor * true, rtol=1e-6, atol=1e-5)
    assert not np.allclose(trimesh.load(tmp_path / "mm.stl").triangles, 1000.0 * true)
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(InputError, match=f"scale must be a positive number of mm, got {bad}"):
            write_stl(tmp_path / "x.stl", mesh, to_unit="mm", scale=bad)


def test_ply_read_back_by_trimesh(tmp_path, tube):
    trimesh = pytest.importorskip("trimesh")
    mesh = tube.state(2)
    write_ply(tmp_path / "m.ply", mesh)
    _only(tmp_path, "m.ply")
    assert b"format binary_little_endian" in (tmp_path / "m.ply").read_bytes()[:100]
    back = trimesh.load(tmp_path / "m.ply", process=False)
    assert_array_equal(back.faces, mesh.faces_vertices)
    assert_allclose(back.vertices, mesh.vertices_coords, atol=1e-6, rtol=0)
    assert_array_equal(back.metadata["_ply_raw"]["face"]["data"]["group"], mesh.faces_group)


@pytest.mark.parametrize(("writer", "name"), [(write_stl, "m.stl"), (write_ply, "m.ply")])
def test_binary_mesh_writers_are_atomic(tmp_path, monkeypatch, tube, writer, name):
    from curvefold.io import _mesh3d as mesh3d

    def broken(*args, **kwargs):
        raise RuntimeError("exporter failed")

    monkeypatch.setattr(mesh3d, "stl_records", broken)
    monkeypatch.setattr(mesh3d, "ply_bytes", broken)
    with pytest.raises(RuntimeError, match="exporter failed"):
        writer(tmp_path / name, tube.state(1))
    assert list(tmp_path.iterdir()) == []


def test_mesh_writers_reject_non_finite(tmp_path, tube):
    bad = tube.crease_pattern.with_coords(
        np.full_like(tube.coords[0], np.nan), fold_angles_from_geometry=False
    )
    for writer in (write_obj, write_stl, write_ply):
        with pytest.raises(InputError, match="finite"):
            writer(tmp_path / "x", bad)
    assert list(tmp_path.iterdir()) == []


# --- GLB
# ---------------------------------------------------------------------------------------------


def _accessor_of(target, name: str) -> int:
    return target[name] if isinstance(target, dict) else getattr(target, name)


def test_glb_read_back_by_pygltflib(tmp_path, tube):
    pygltflib = pytest.importorskip("pygltflib")
    K = len(tube.angles_deg)
    write_glb(
        tmp_path / "m.glb",
        tube.crease_pattern,
        coords=tube.coords,
        angles_deg=tube.angles_deg,
        options=GlbOptions(unit="mm", metadata={"panels": 4}, seconds_per_state=0.5),
    )
    _only(tmp_path, "m.glb")
    gltf = pygltflib.GLTF2.load(str(tmp_path / "m.glb"))
    blob = gltf.binary_blob()
    extras = gltf.asset.extras["curvefold"]
    assert extras["scale_to_metres"] == 1e-3 and extras["unit"] == "mm" and extras["up_axis"] == "z"
    assert extras["angles_deg"] == tube.angles_deg.tolist() and extras["metadata"] == {"panels": 4}

    (surface,) = gltf.meshes  # one part without parts=
    assert [n.name for n in gltf.nodes] == ["surface"] and surface.name == "surface"
    assert [p.mode for p in surface.primitives] == [4, 1, 1, 1]
    colours = [
        gltf.materials[p.material].pbrMetallicRoughness.baseColorFactor
        for p in surface.primitives[1:]
    ]
    # fold red, seam blue, boundary black
    assert colours == [[1, 0, 0, 1], [0, 0, 1, 1], [0, 0, 0, 1]]
    assert all(len(prim.targets) == K - 1 for prim in surface.primitives)
    assert surface.extras["targetNames"] == [f"2α = {a:g}°" for a in tube.angles_deg[:-1]]
    assert extras["base_state"] == K - 1

    want = to_gltf(tube.coords, 1e-3)
    faces = tube.crease_pattern.faces_vertices
    prim = surface.primitives[0]
    base = accessor(gltf, blob, prim.attributes.POSITION)
    triangles = accessor(gltf, blob, prim.indices).reshape(-1, 3)
    # the last state (the design state) is the pose shown
    assert_allclose(base[triangles], want[-1][faces], atol=1e-6, rtol=0)
    assert_allclose(gltf.accessors[prim.attributes.POSITION].min, base.min(axis=0), rtol=0, atol=0)
    assert_allclose(gltf.accessors[prim.attributes.POSITION].max, base.max(axis=0), rtol=0, atol=0)
    for k, target in enumerate(prim.targets):
        assert_allclose(
            (base + accessor(gltf, blob, target_position(target)))[triangles],
            want[k][faces],
            atol=1e-6,
            rtol=0,
        )
    # normals: unit, on the side the triangles face, and split along the folds (a vertex of two
    # strips has two)
    normal = accessor(gltf, blob, prim.attributes.NORMAL)
    assert_allclose(np.linalg.norm(normal, axis=1), 1.0, atol=1e-6)
    a, b, c = (base[triangles[:, k]] for k in range(3))
    facing = np.cross(b - a, c - a)
    facing /= np.linalg.norm(facing, axis=1, keepdims=True)
    # flat panels: the vertex normal is the face normal
    assert (np.einsum("tkj,tj->tk", normal[triangles], facing) > 0.99).all()
    assert len(base) > len(tube.crease_pattern.vertices_coords)  # fold vertices copied per strip
    moved_normal = normal + accessor(gltf, blob, _accessor_of(prim.targets[0], "NORMAL"))
    flat_facing = np.cross(*(want[0][faces[:, k]] - want[0][faces[:, 0]] for k in (1, 2)))
    assert (
        np.einsum(
            "tkj,tj->tk",
            moved_normal[triangles],
            flat_facing / np.linalg.norm(flat_facing, axis=1, keepdims=True),
        )
        > 0.99
    ).all()

    fold_prim = surface.primitives[1]
    fold_edges = tube.crease_pattern.edges_vertices[tube.crease_pattern.edges_kind == "fold"]
    line_xyz = accessor(gltf, blob, fold_prim.attributes.POSITION)[
        accessor(gltf, blob, fold_prim.indices).reshape(-1, 2)
    ]
    assert_allclose(line_xyz, want[-1][fold_edges], atol=1e-6, rtol=0)
    delta = accessor(gltf, blob, target_position(fold_prim.targets[0]))[
        accessor(gltf, blob, fold_prim.indices).reshape(-1, 2)
    ]
    assert_allclose(line_xyz + delta, want[0][fold_edges], atol=1e-6, rtol=0)

    (anim,) = gltf.animations
    assert [c.target.node for c in anim.channels] == [0] and all(
        c.target.path == "weights" for c in anim.channels
    )
    (sampler,) = anim.samplers
    assert sampler.interpolation == "LINEAR"
    assert_allclose(accessor(gltf, blob, sampler.input), 0.5 * np.arange(2 * K - 1))
    weights = accessor(gltf, blob, sampler.output).reshape(2 * K - 1, K - 1)
    # it starts (and ends) on the design state, unfolds to the flat state (target 0) and folds back
    assert_array_equal(weights[0], 0) and assert_array_equal(weights[-1], 0)
    assert_array_equal(weights[1:K], np.eye(K - 1)[::-1])
    assert_array_equal(weights[K - 1 : -1], np.eye(K - 1))


def test_glb_has_a_named_node_and_mesh_per_part_and_further_morph_targets(tmp_path, tube):
    pygltflib = pytest.importorskip("pygltflib")
    mesh = tube.crease_pattern
    F, E = len(mesh.faces_vertices), len(mesh.edges_vertices)
    half = F // 2
    parts = [
        ("tube 1 · sheet A", np.arange(half), np.arange(E)),
        ("tube 1 · sheet B", np.arange(half, F), []),
    ]
    mode = np.zeros_like(mesh.vertices_coords)
    mode[:, 2] = 1.0  # one model unit up
    write_glb(
        tmp_path / "m.glb",
        mesh,
        coords=tube.coords,
        angles_deg=tube.angles_deg,
        morph_targets={"mode 1": mode},
        options=GlbOptions(unit="mm", parts=parts),
    )
    gltf = pygltflib.GLTF2.load(str(tmp_path / "m.glb"))
    blob = gltf.binary_blob()
    assert (
        [n.name for n in gltf.nodes]
        == [m.name for m in gltf.meshes]
        == ["tube 1 · sheet A", "tube 1 · sheet B"]
    )
    assert [n.mesh for n in gltf.nodes] == [0, 1] and gltf.scenes[0].nodes == [0, 1]
    K = len(tube.angles_deg)
    names = [f"2α = {a:g}°" for a in tube.angles_deg[:-1]] + ["mode 1"]
    for m in gltf.meshes:
        assert m.extras["targetNames"] == names and all(len(p.targets) == K for p in m.primitives)
    # lines only on the part given the edges
    assert [len(m.primitives) for m in gltf.meshes] == [4, 1]
    tri = accessor(gltf, blob, gltf.meshes[1].primitives[0].indices).reshape(-1, 3)
    assert len(tri) == F - half
    up = accessor(gltf, blob, target_position(gltf.meshes[1].primitives[0].targets[-1]))
    # model +z is glTF +y, in metres
    assert_allclose(up, np.tile([0.0, 1e-3, 0.0], (len(up), 1)), atol=1e-9)
    (anim,) = gltf.animations
    assert sorted(c.target.node for c in anim.channels) == [0, 1]
    weights = accessor(gltf, blob, anim.samplers[0].output).reshape(-1, K)
    assert_array_equal(weights[:, -1], 0)  # the further target is not animated
    with pytest.raises(
        InputError, match=r"morph_targets\['bad'\] must be finite displacements " r"of shape"
    ):
        write_glb(tmp_path / "n.glb", mesh, coords=tube.coords, morph_targets={"bad": mode[:2]})
    with pytest.raises(InputError, match=r"parts\[0\] must be a name and indices"):
        write_glb(
            tmp_path / "n.glb", mesh, coords=tube.coords, options=GlbOptions(parts=[("x", [F], [])])
        )


def test_glb_base_state_can_be_any_state(tmp_path, tube):
    pygltflib = pytest.importorskip("pygltflib")
    write_glb(
        tmp_path / "m.glb",
        tube.crease_pattern,
        coords=tube.coords,
        angles_deg=tube.angles_deg,
        base_state=0,
        options=GlbOptions(unit="mm"),
    )
    gltf = pygltflib.GLTF2.load(str(tmp_path / "m.glb"))
    blob = gltf.binary_blob()
    prim = gltf.meshes[0].primitives[0]
    triangles = accessor(gltf, blob, prim.indices).reshape(-1, 3)
    base = accessor(gltf, blob, prim.attributes.POSITION)
    assert_allclose(
        base[triangles],
        to_gltf(tube.coords, 1e-3)[0][tube.crease_pattern.faces_vertices],
        atol=1e-6,
        rtol=0,
    )
    assert gltf.meshes[0].extras["targetNames"] == [f"2α = {a:g}°" for a in tube.angles_deg[1:]]
    with pytest.raises(InputError, match="base_state"):
        write_glb(
            tmp_path / "n.glb", tube.crease_pattern, coords=tube.coords, base_state=len(tube.coords)
        )


def test_glb_single_state_has_no_animation(tmp_path):
    pygltflib = pytest.importorskip("pygltflib")
    motion = oblique_motion()
    write_glb(tmp_path / "m.glb", motion.state(2), options=GlbOptions(unit="m", up="y"))
    gltf = pygltflib.GLTF2.load(str(tmp_path / "m.glb"))
    assert gltf.animations == []
    assert all(p.targets in (None, []) for m in gltf.meshes for p in m.primitives)
    prim = gltf.meshes[0].primitives[0]
    blob = gltf.binary_blob()
    pos = accessor(gltf, blob, prim.attributes.POSITION)[
        accessor(gltf, blob, prim.indices).reshape(-1, 3)
    ]
    assert_allclose(
        pos, motion.coords[2][motion.state(2).triangulated().faces_vertices], atol=1e-6, rtol=0
    )
    assert [p.mode for p in gltf.meshes[0].primitives] == [4, 1, 1]  # fold and boundary, no seam


@pytest.mark.node
@pytest.mark.parametrize("states", ["motion", "single"])
def test_glb_khronos_validator(tmp_path, tube, states):
    coords = tube.coords if states == "motion" else None
    write_glb(
        tmp_path / "m.glb",
        tube.crease_pattern,
        coords=coords,
        options=GlbOptions(unit="mm", interpolation="STEP"),
    )
    report = _validate_gltf(tmp_path / "m.glb")
    assert report["errors"] == 0, report["messages"]
    assert report["warnings"] == 0, report["messages"]
    assert report["info"]["hasMorphTargets"] is (states == "motion")
    assert report["info"]["animationCount"] == (1 if states == "motion" else 0)
    assert report["info"]["totalTriangleCount"] == len(tube.crease_pattern.faces_vertices)


@pytest.mark.node
def test_khronos_validator_reports_errors(tmp_path, tube):
    """The validator check can fail: a GLB with a wrong POSITION max is reported."""
    pygltflib = pytest.importorskip("pygltflib")
    write_glb(
        tmp_path / "m.glb", tube.crease_pattern, coords=tube.coords, options=GlbOptions(unit="mm")
    )
    gltf = pygltflib.GLTF2.load(str(tmp_path / "m.glb"))
    gltf.accessors[gltf.meshes[0].primitives[0].attributes.POSITION].max = [9.0, 9.0, 9.0]
    gltf.save_binary(str(tmp_path / "broken.glb"))
    report = _validate_gltf(tmp_path / "broken.glb")
    assert report["errors"] > 0
    assert any(m["code"] == "ACCESSOR_MAX_MISMATCH" for m in report["messages"])


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        (dict(coords=np.zeros((2, 3, 3))), r"coords must have shape \(K, 15, 3\)"),
        (dict(coords=np.full((1, 15, 3), np.inf)), "finite"),
        (dict(angles_deg=[1, 2]), r"angles_deg must have shape \(1,\)"),
        (dict(options=GlbOptions(unit="furlong")), "give scale="),
        (dict(options=GlbOptions(scale=-1.0)), "scale must be a positive"),
        (dict(options=GlbOptions(seconds_per_state=0.0)), "seconds_per_state"),
        (dict(options=GlbOptions(interpolation="CUBICSPLINE")), "interpolation"),
        (dict(options=GlbOptions(up="x")), "up must be"),
        (dict(options=GlbOptions(crease_kinds=("ruling",))), "crease_kinds"),
    ],
)
def test_glb_rejects_bad_input(tmp_path, tube, kwargs, match):
    with pytest.raises(InputError, match=match):
        write_glb(tmp_path / "m.glb", tube.crease_pattern, **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_glb_is_what_pygltflib_writes(tmp_path, tube):
    """pygltflib reads the GLB of a motion and writes it back byte for byte: its objects,
    defaults, padding and chunks."""
    pygltflib = pytest.importorskip("pygltflib")
    from curvefold.io import _gltf as gltf

    def rewritten(glb: bytes) -> bytes:
        return b"".join(pygltflib.GLTF2.load_from_bytes(glb).save_to_bytes())

    mesh = tube.crease_pattern
    parts = [
        ("tube 1 · sheet A", np.arange(4), np.arange(len(mesh.edges_vertices))),
        ("tube 1 · sheet B", np.arange(4, len(mesh.faces_vertices)), []),
    ]
    data = write_glb(
        tmp_path / "m.glb",
        mesh,
        coords=tube.coords,
        angles_deg=tube.angles_deg,
        morph_targets={"up": np.ones((len(mesh.vertices_coords), 3))},
        options=GlbOptions(parts=parts, metadata={"panels": 4}),
    ).read_bytes()
    assert rewritten(data) == data
    # damaged: an accessor without the byteOffset pygltflib writes
    length = int.from_bytes(data[12:16], "little")
    document, blob = json.loads(data[20 : 20 + length]), data[28 + length :]
    del document["accessors"][0]["byteOffset"]
    assert rewritten(gltf._glb(document, blob)) != gltf._glb(document, blob)


def test_glb_writer_is_atomic(tmp_path, monkeypatch, tube):
    from curvefold.io import _gltf as gltf

    (tmp_path / "m.glb").write_bytes(b"old")

    def broken(*args):
        raise RuntimeError("packing failed")

    monkeypatch.setattr(gltf, "_glb", broken)
    with pytest.raises(RuntimeError, match="packing failed"):
        write_glb(tmp_path / "m.glb", tube.crease_pattern, coords=tube.coords)
    _only(tmp_path, "m.glb")
    assert (tmp_path / "m.glb").read_bytes() == b"old"


# --- Rhino 3dm
# -------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def real_tube():
    """A tube of the geometry at 2α = 90°: its quad mesh and topology, keeping 7 of its 13
    samples."""
    from curvefold import Crease, Lattice, SpaceCurve, Structure

    lattice = Lattice.from_crease(
        Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.3, 2.0, samples=13)), 0.2, 0.15
    )
    structure = Structure.tube(lattice)
    keep = [np.arange(0, 13, 2)]
    return (
        structure.state().mesh(faces="quads", keep=keep),
        structure.topology("quads", keep=keep),
        structure,
    )


def _by_layer(model) -> dict[str, list]:
    out: dict[str, list] = {}
    for obj in model.Objects:
        out.setdefault(model.Layers[obj.Attributes.LayerIndex].Name, []).append(
            (obj.Attributes.Name, obj.Geometry)
        )
    return out


def _xyz(p) -> list[float]:
    return [p.X, p.Y, p.Z]


def test_3dm_read_back_by_rhino3dm(tmp_path, real_tube):
    """Sheets as quad meshes, strips as ruled NURBS surfaces, creases as NURBS curves through the
    samples."""
    rhino3dm = pytest.importorskip("rhino3dm")
    mesh, topology, structure = real_tube
    options = RhinoOptions(unit="mm", metadata={"length": 2.0, "name": "tube"})
    write_3dm(tmp_path / "m.3dm", mesh, topology, options=options)
    _only(tmp_path, "m.3dm")
    model = rhino3dm.File3dm.Read(str(tmp_path / "m.3dm"))
    assert [layer.Name for layer in model.Layers] == [
        "Sheets",
        "Strips",
        "Fold",
        "Seam",
        "Boundary",
    ]
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Millimeters
    assert (
        model.Strings["curvefold:length"],
        model.Strings["curvefold:name"],
        model.Strings["curvefold:unit"],
    ) == ("2.0", "tube", "mm")

    layers = _by_layer(model)
    assert {k: len(v) for k, v in layers.items()} == {
        "Sheets": 2,
        "Strips": 4,
        "Fold": 2,
        "Seam": 2,
        "Boundary": 2,
    }
    x = mesh.vertices_coords
    for (name, sheet), want in zip(layers["Sheets"], topology.sheets):
        assert name == want.label and isinstance(sheet, rhino3dm.Mesh)
        # rhino3dm reads them back as floats
        assert_allclose([_xyz(p) for p in sheet.Vertices], x[want.vertices], atol=1e-6, rtol=0)
        # quads
        assert_array_equal([sheet.Faces[i] for i in range(sheet.Faces.Count)], want.faces_vertices)

    # Every kept sample is on the crease curves, at its t; every ruling at a kept sample on its
    # strip's surface.
    t = topology.vertex_sample / 12
    curves = structure.state().vertices[structure.cell_curves[0]]  # (4, 13, 3), corners 1-4
    for kind, corners in (("Fold", (0, 2)), ("Seam", (1, 3))):
        for (name, curve), c in zip(layers[kind], corners):
            assert (
                isinstance(curve, rhino3dm.NurbsCurve)
                and curve.Degree == 3
                and name.startswith(kind.lower())
            )
            assert_allclose(
                [_xyz(curve.PointAt(s)) for s in np.linspace(0, 1, 7)],
                curves[c, ::2],
                atol=1e-12,
                rtol=0,
            )
    for (name, surface), c in zip(layers["Strips"], range(4)):
        assert isinstance(surface, rhino3dm.NurbsSurface) and name == f"tube 1 · strip {c + 1}"
        for s_, p in zip(np.linspace(0, 1, 7), curves[:, ::2].swapaxes(0, 1)):
            for v, corner in ((0.0, c), (0.5, None), (1.0, (c + 1) % 4)):
                want = p[c] + v * (p[(c + 1) % 4] - p[c]) if corner is None else p[corner]
                assert_allclose(_xyz(surface.PointAt(s_, v)), want, atol=1e-12, rtol=0)
    assert all(curve.IsClosed for _, curve in layers["Boundary"])
    assert t.max() == 1


# 2001: solved on the band (DENSE_POINTS)
@pytest.mark.parametrize("points", [2, 3, 4, 5, 8, 87, 2001])
@pytest.mark.parametrize("degree", [1, 2, 3])
def test_3dm_crease_spline_is_scipys_interpolating_spline(points, degree):
    """The creases' B-spline (knots and control points) is scipy's make_interp_spline through the
    samples."""
    interpolate = pytest.importorskip("scipy.interpolate")
    from curvefold.io._rhino import interpolating_spline

    rng = np.random.default_rng(points * 10 + degree)
    t = (
        np.r_[0.0, np.sort(rng.uniform(0.05, 0.95, points - 2)), 1.0]
        if points > 2
        else np.array([0.0, 1.0])
    )
    x = np.column_stack([np.cos(3 * t), np.sin(3 * t), t**2]) + rng.normal(0, 0.01, (points, 3))
    want = interpolate.make_interp_spline(t, x, k=min(degree, points - 1))
    knots, control = interpolating_spline(t, x, degree)
    assert_array_equal(knots, want.t)
    # control points of clustered parameters grow large (1.7e3 at 2001 points)
    scale = max(1.0, float(np.abs(want.c).max()))
    assert_allclose(control, want.c, rtol=0, atol=1e-12 * scale)
    # through the points
    assert_allclose(interpolate.BSpline(knots, control, want.k)(t), x, rtol=0, atol=1e-12)
    # damaged: a parameter moved by 1e-6 moves the control points beyond the tolerance
    if min(degree, points - 1) > 1:
        moved = t.copy()
        moved[1] += 1e-6
        assert not np.allclose(
            interpolating_spline(moved, x, degree)[1], want.c, rtol=0, atol=1e-12
        )


def test_3dm_groups_user_text_and_named_views(tmp_path, real_tube):
    """A group per tube and per sheet with the right members; every object says its tube, sheet,
    kind and fold angle; three named views that frame the model."""
    rhino3dm = pytest.importorskip("rhino3dm")
    mesh, topology, structure = real_tube
    write_3dm(tmp_path / "m.3dm", mesh, topology, fold_angle=90.0, options=RhinoOptions(unit="mm"))
    model = rhino3dm.File3dm.Read(str(tmp_path / "m.3dm"))
    groups = {g.Name: g.Index for g in model.Groups}
    assert set(groups) == {"tube 1", "tube 1 · sheet A", "tube 1 · sheet B"}
    members = {
        name: sorted(o.Attributes.Name for o in model.Groups.GroupMembers(i))
        for name, i in groups.items()
    }
    # every object is in its tube
    assert members["tube 1"] == sorted(o.Attributes.Name for o in model.Objects)
    assert members["tube 1 · sheet A"] == sorted(
        ["tube 1 · sheet A", "tube 1 · strip 1", "tube 1 · strip 4", "fold 1"]
    )
    assert members["tube 1 · sheet B"] == sorted(
        ["tube 1 · sheet B", "tube 1 · strip 2", "tube 1 · strip 3", "fold 2"]
    )
    text = {o.Attributes.Name: dict(o.Attributes.GetUserStrings()) for o in model.Objects}
    assert text["tube 1 · sheet B"] == {
        "curvefold:tube": "1",
        "curvefold:kind": "sheet",
        "curvefold:sheet": "B",
        "curvefold:fold_angle_deg": "90",
    }
    # a seam belongs to both sheets
    assert text["seam 1"]["curvefold:kind"] == "seam" and "curvefold:sheet" not in text["seam 1"]
    # a crease's fold angle is measured on its edges: 2α at folds, 180° − 2α at seams (the
    # certificate's relation)
    # 7 samples along the crease
    assert float(text["fold 1"]["curvefold:fold_angle_deg"]) == pytest.approx(90.0, abs=1.0)
    assert float(text["seam 1"]["curvefold:fold_angle_deg"]) == pytest.approx(90.0, abs=1.0)
    views = {
        model.NamedViews[i].Name: model.NamedViews[i].Viewport for i in range(len(model.NamedViews))
    }
    assert list(views) == ["perspective", "plan", "section"]
    assert (
        views["perspective"].IsPerspectiveProjection
        and views["plan"].IsParallelProjection
        and views["section"].IsParallelProjection
    )
    assert _xyz(views["plan"].CameraDirection) == pytest.approx([0, 0, -1])
    # level, and from above
    assert (
        _xyz(views["section"].CameraDirection)[2] == 0
        and _xyz(views["perspective"].CameraDirection)[2] < 0
    )
    centre = 0.5 * (mesh.vertices_coords.min(axis=0) + mesh.vertices_coords.max(axis=0))
    for vp in views.values():  # each looks at the model's centre
        to_centre = centre - _xyz(vp.CameraLocation)
        direction = _xyz(vp.CameraDirection)
        assert np.linalg.norm(np.cross(to_centre, direction)) < 1e-9 * np.linalg.norm(to_centre)


def test_3dm_lays_the_crease_pattern_at_its_printed_size_on_its_layer(tmp_path):
    """The cut outlines of the 3dm's ``crease pattern`` layer, read back in the document's
    metres, are the layout's in millimetres: the same lengths, and each sheet's outline in its
    own place."""
    rhino3dm = pytest.importorskip("rhino3dm")
    from shapely.geometry import Polygon

    from curvefold.io import ModelOutput, PatternOutput, layout_pattern, write_3d
    from curvefold.io._cutters import layer_name
    from curvefold.io._rhino import PATTERN_LAYER
    from curvefold.vault import Vault

    structure = Vault.from_design(samples=101, tubes=2).structure
    layout = layout_pattern(structure, PatternOutput(name="vault", cutter="laser"))
    (path,) = write_3d(
        tmp_path / "v", structure, output=ModelOutput(pattern=layout), formats=("3dm",)
    )
    model = rhino3dm.File3dm.Read(str(path))
    paths = {layer.Index: layer.FullPath for layer in model.Layers}
    assert {
        f"{PATTERN_LAYER}::{layer_name(k)}" for k in ("cut", "mountain", "seam", "glue", "labels")
    } <= set(paths.values())
    colour = next(
        layer.Color for layer in model.Layers if layer.FullPath == f"{PATTERN_LAYER}::cut"
    )
    assert tuple(colour)[:3] == (255, 0, 0)  # the laser convention's cut colour
    cut = [
        o.Geometry
        for o in model.Objects
        if paths[o.Attributes.LayerIndex] == f"{PATTERN_LAYER}::cut"
    ]
    ours = [p.points for s in layout.sheets() for p in s.on_layer("cut")]
    assert len(cut) == len(ours) == 4
    theirs = [Polygon([_xyz(c.Point(i))[:2] for i in range(c.PointCount)]) for c in cut]
    assert all(c.IsClosed for c in cut)
    # metres in the document, millimetres on the page
    lengths = sorted(1000.0 * p.exterior.length for p in theirs)
    assert lengths == pytest.approx(sorted(Polygon(p).exterior.length for p in ours), rel=1e-9)
    assert sorted(1e6 * p.area for p in theirs) == pytest.approx(
        sorted(Polygon(p).area for p in ours), rel=1e-9
    )
    model_box = np.array(
        [
            _xyz(v)
            for o in model.Objects
            if isinstance(o.Geometry, rhino3dm.Mesh)
            for v in o.Geometry.Vertices
        ]
    )
    first = np.array([_xyz(c.Point(0)) for c in cut])
    # beside the model, on the ground
    assert (first[:, 0] > model_box[:, 0].max()).all() and (first[:, 2] == 0).all()


def test_glb_parts_of_a_polygon_mesh_hold_their_polygons_triangles(tmp_path, real_tube):
    """Parts name the mesh's own faces; on a quad mesh each part gets both triangles of each of
    its quads."""
    pygltflib = pytest.importorskip("pygltflib")
    mesh, topology, _ = real_tube
    parts = [(s.label, s.faces, s.edges) for s in topology.sheets]
    write_glb(tmp_path / "q.glb", mesh, options=GlbOptions(unit="m", parts=parts))
    gltf = pygltflib.GLTF2.load(str(tmp_path / "q.glb"))
    blob = gltf.binary_blob()
    for sheet, m in zip(topology.sheets, gltf.meshes):
        prim = m.primitives[0]
        corners = accessor(gltf, blob, prim.attributes.POSITION)[
            accessor(gltf, blob, prim.indices).reshape(-1, 3)
        ]
        # (q, 4, 3), fans (0, 1, 2) and (0, 2, 3)
        quads = mesh.vertices_coords[mesh.faces_vertices[sheet.faces]]
        want = np.stack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]], axis=1).reshape(-1, 3, 3)
        assert_allclose(corners, to_gltf(want, 1.0), atol=1e-6, rtol=0)


def test_3dm_refuses_a_mesh_of_other_faces(tmp_path, real_tube):
    pytest.importorskip("rhino3dm")
    mesh, topology, structure = real_tube
    with pytest.raises(InputError, match="ruling quads"):
        write_3dm(tmp_path / "m.3dm", structure.state().mesh(keep=[np.arange(0, 13, 2)]), topology)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("unit", "system"),
    [("unit", "Meters"), ("m", "Meters"), ("cm", "Centimeters"), ("in", "Inches")],
)
def test_3dm_unit_system(tmp_path, real_tube, unit, system):
    """Rhino needs a unit system: the model unit is taken as one metre, as in every file."""
    rhino3dm = pytest.importorskip("rhino3dm")
    write_3dm(tmp_path / "m.3dm", *real_tube[:2], options=RhinoOptions(unit=unit))
    model = rhino3dm.File3dm.Read(str(tmp_path / "m.3dm"))
    assert model.Settings.ModelUnitSystem == getattr(rhino3dm.UnitSystem, system)
    assert model.Strings["curvefold:unit"] == unit


def test_3dm_rejects_unknown_unit(tmp_path, real_tube):
    pytest.importorskip("rhino3dm")
    with pytest.raises(InputError, match="unit must be one of"):
        write_3dm(tmp_path / "m.3dm", *real_tube[:2], options=RhinoOptions(unit="furlong"))
    with pytest.raises(InputError, match=r"^degree must be 1 or 3, got 2$"):
        write_3dm(tmp_path / "m.3dm", *real_tube[:2], degree=2)
    assert list(tmp_path.iterdir()) == []


def test_3dm_writer_is_atomic(tmp_path, monkeypatch, real_tube):
    rhino3dm = pytest.importorskip("rhino3dm")
    real_write = rhino3dm.File3dm.Write

    def write_then_fail(self, path, version=0):
        real_write(self, path, version)  # a complete temporary file exists, then the run dies
        raise RuntimeError("interrupted")

    monkeypatch.setattr(rhino3dm.File3dm, "Write", write_then_fail)
    with pytest.raises(RuntimeError, match="interrupted"):
        write_3dm(tmp_path / "m.3dm", *real_tube[:2])
    assert list(tmp_path.iterdir()) == []


def test_3dm_write_returning_false_is_an_error(tmp_path, monkeypatch, real_tube):
    rhino3dm = pytest.importorskip("rhino3dm")
    monkeypatch.setattr(rhino3dm.File3dm, "Write", lambda self, path, version=0: False)
    with pytest.raises(OSError, match="could not write"):
        write_3dm(tmp_path / "m.3dm", *real_tube[:2])
    assert list(tmp_path.iterdir()) == []


def test_writers_accept_an_empty_mesh(tmp_path):
    empty = Mesh(
        vertices_coords=np.zeros((0, 3)),
        edges_vertices=np.zeros((0, 2), int),
        edges_assignment=np.zeros(0, "<U1"),
        edges_foldAngle=np.zeros(0),
        faces_vertices=np.zeros((0, 3), int),
        edges_kind=np.zeros(0, "<U8"),
        faces_group=np.zeros(0, int),
    )
    write_obj(tmp_path / "e.obj", empty)
    assert "g surface" in (tmp_path / "e.obj").read_text()


# --- what the writers import --------------------------------------------------------------------

_WRITE_ALL = """
import sys, tempfile, pathlib
import numpy as np
from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.io import FoldOutput, ModelOutput, write_3d, write_sheet_fold, write_structure_fold
from curvefold.geometry._sheets import sheets
curve = SpaceCurve.from_curvature(1.0, 0.3, 2.0, samples=13)
structure = Structure.tube(Lattice.from_crease(Crease.from_curve(curve), 0.2, 0.15))
keep = [np.arange(0, 13, 2)]
before = set(sys.modules)
folder = pathlib.Path(tempfile.mkdtemp())
write_3d(folder / "m", structure, output=ModelOutput(keep=keep))
write_structure_fold(folder / "m.fold", structure, FoldOutput(keep=keep), fold_angles=[0, 45, 90])
for k, sheet in enumerate(sheets(structure, keep=keep)):
    write_sheet_fold(folder / f"s{k}.fold", sheet.mesh)
{probe}
print(sorted(set(sys.modules) - before))
"""


def _imported_by_writers(probe: str = "") -> list[str]:
    import json
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, "-c", _WRITE_ALL.replace("{probe}", probe)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.splitlines()[-1].replace("'", '"'))


def test_the_3d_and_fold_writers_import_no_scipy_nor_pygltflib():
    """The GLB, the 3dm's splines and the FOLD files' sheets need neither (each file job pays
    what it imports)."""
    heavy = ("scipy.interpolate", "scipy.sparse.csgraph", "pygltflib")
    assert [m for m in _imported_by_writers() if m in heavy] == []
    # the probe sees such an import
    assert [
        m for m in _imported_by_writers("import scipy.interpolate, pygltflib") if m in heavy
    ] == ["pygltflib", "scipy.interpolate"]
