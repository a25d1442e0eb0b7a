"""OBJ / STL / PLY / GLB / 3dm writers, read back with readers curvefold did not write."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from _meshes import oblique_motion, strip_motion
from _node import run_node
from curvefold.geometry.mesh import Mesh
from curvefold.io import crease_polylines, write_3dm, write_glb, write_obj, write_ply, write_stl
from curvefold.kernel.errors import InputError


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
        assert_allclose(tube.crease_pattern.vertices_coords[p, 0], tube.crease_pattern.vertices_coords[p[0], 0])
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


def test_obj_read_back_by_trimesh(tmp_path, tube):
    trimesh = pytest.importorskip("trimesh")
    mesh = tube.state(2)
    write_obj(tmp_path / "m.obj", mesh, unit="mm", metadata={"panels": 4})
    _only(tmp_path, "m.obj")
    back = trimesh.load(tmp_path / "m.obj", force="mesh", process=False)
    assert back.vertices.shape == mesh.vertices_coords.shape
    assert back.faces.shape == mesh.faces_vertices.shape
    assert_allclose(back.triangles, mesh.vertices_coords[mesh.faces_vertices], atol=1e-6, rtol=0)


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
    assert (tmp_path / "m.stl").read_bytes()[80:84] == np.uint32(len(mesh.faces_vertices)).tobytes()  # binary
    back = trimesh.load(tmp_path / "m.stl")
    assert len(back.faces) == len(mesh.faces_vertices)
    assert len(back.vertices) == len(mesh.vertices_coords)
    assert_allclose(back.triangles, mesh.vertices_coords[mesh.faces_vertices], atol=1e-6, rtol=0)


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
def test_trimesh_writers_are_atomic(tmp_path, monkeypatch, tube, writer, name):
    trimesh = pytest.importorskip("trimesh")

    def broken(*args, **kwargs):
        raise RuntimeError("exporter failed")

    monkeypatch.setattr(trimesh.exchange.stl, "export_stl", broken)
    monkeypatch.setattr(trimesh.exchange.ply, "export_ply", broken)
    with pytest.raises(RuntimeError, match="exporter failed"):
        writer(tmp_path / name, tube.state(1))
    assert list(tmp_path.iterdir()) == []


def test_mesh_writers_reject_non_finite(tmp_path, tube):
    bad = tube.crease_pattern.with_coords(np.full_like(tube.coords[0], np.nan), fold_angles_from_geometry=False)
    for writer in (write_obj, write_stl, write_ply):
        with pytest.raises(InputError, match="finite"):
            writer(tmp_path / "x", bad)
    assert list(tmp_path.iterdir()) == []


# --- GLB ---------------------------------------------------------------------------------------------


def _accessor(gltf, blob: bytes, index: int) -> np.ndarray:
    acc = gltf.accessors[index]
    view = gltf.bufferViews[acc.bufferView]
    dtype = {5126: np.float32, 5125: np.uint32}[acc.componentType]
    width = {"SCALAR": 1, "VEC3": 3}[acc.type]
    start = (view.byteOffset or 0) + (acc.byteOffset or 0)
    data = np.frombuffer(blob, dtype=dtype, count=acc.count * width, offset=start)
    return data.reshape(acc.count, width) if width > 1 else data


def _target_position(target) -> int:
    return target["POSITION"] if isinstance(target, dict) else target.POSITION  # pygltflib reads targets as dicts


def _to_gltf(coords: np.ndarray, scale: float) -> np.ndarray:
    x = np.asarray(coords) * scale
    return np.stack([x[..., 0], x[..., 2], -x[..., 1]], axis=-1)


def test_glb_read_back_by_pygltflib(tmp_path, tube):
    pygltflib = pytest.importorskip("pygltflib")
    K = len(tube.angles_deg)
    write_glb(tmp_path / "m.glb", tube.crease_pattern, coords=tube.coords, angles_deg=tube.angles_deg,
              unit="mm", metadata={"panels": 4}, seconds_per_state=0.5)
    _only(tmp_path, "m.glb")
    gltf = pygltflib.GLTF2.load(str(tmp_path / "m.glb"))
    blob = gltf.binary_blob()
    extras = gltf.asset.extras["curvefold"]
    assert extras["scale_to_metres"] == 1e-3 and extras["unit"] == "mm" and extras["up_axis"] == "z"
    assert extras["angles_deg"] == tube.angles_deg.tolist() and extras["metadata"] == {"panels": 4}

    surface, creases = gltf.meshes
    assert [p.mode for p in surface.primitives] == [4]
    assert [p.mode for p in creases.primitives] == [1, 1, 1]
    colours = [gltf.materials[p.material].pbrMetallicRoughness.baseColorFactor for p in creases.primitives]
    assert colours == [[1, 0, 0, 1], [0, 0, 1, 1], [0, 0, 0, 1]]  # fold red, seam blue, boundary black
    for prim in surface.primitives + creases.primitives:
        assert len(prim.targets) == K - 1

    want = _to_gltf(tube.coords, 1e-3)
    prim = surface.primitives[0]
    base = _accessor(gltf, blob, prim.attributes.POSITION)
    assert_allclose(base, want[0], atol=1e-6, rtol=0)
    assert_allclose(gltf.accessors[prim.attributes.POSITION].min, base.min(axis=0), rtol=0, atol=0)
    assert_allclose(gltf.accessors[prim.attributes.POSITION].max, base.max(axis=0), rtol=0, atol=0)
    assert_array_equal(_accessor(gltf, blob, prim.indices).reshape(-1, 3), tube.crease_pattern.faces_vertices)
    for k, target in enumerate(prim.targets, start=1):
        assert_allclose(base + _accessor(gltf, blob, _target_position(target)), want[k], atol=1e-6, rtol=0)

    fold_prim = creases.primitives[0]
    fold_edges = tube.crease_pattern.edges_vertices[tube.crease_pattern.edges_kind == "fold"]
    line_xyz = _accessor(gltf, blob, fold_prim.attributes.POSITION)[_accessor(gltf, blob, fold_prim.indices).reshape(-1, 2)]
    assert_allclose(line_xyz, want[0][fold_edges], atol=1e-6, rtol=0)
    delta = _accessor(gltf, blob, _target_position(fold_prim.targets[-1]))[_accessor(gltf, blob, fold_prim.indices).reshape(-1, 2)]
    assert_allclose(line_xyz + delta, want[-1][fold_edges], atol=1e-6, rtol=0)

    (anim,) = gltf.animations
    assert sorted(c.target.node for c in anim.channels) == [0, 1]
    assert all(c.target.path == "weights" for c in anim.channels)
    (sampler,) = anim.samplers
    assert sampler.interpolation == "LINEAR"
    assert_allclose(_accessor(gltf, blob, sampler.input), 0.5 * np.arange(K))
    weights = _accessor(gltf, blob, sampler.output).reshape(K, K - 1)
    assert_array_equal(weights[0], 0)
    assert_array_equal(weights[1:], np.eye(K - 1))


def test_glb_single_state_has_no_animation(tmp_path):
    pygltflib = pytest.importorskip("pygltflib")
    motion = oblique_motion()
    write_glb(tmp_path / "m.glb", motion.state(2), unit="m", up="y")
    gltf = pygltflib.GLTF2.load(str(tmp_path / "m.glb"))
    assert gltf.animations == []
    assert all(p.targets in (None, []) for m in gltf.meshes for p in m.primitives)
    pos = _accessor(gltf, gltf.binary_blob(), gltf.meshes[0].primitives[0].attributes.POSITION)
    assert_allclose(pos, motion.coords[2], atol=1e-6, rtol=0)
    assert [p.mode for p in gltf.meshes[1].primitives] == [1, 1]  # fold and boundary, no seam


@pytest.mark.node
@pytest.mark.parametrize("states", ["motion", "single"])
def test_glb_khronos_validator(tmp_path, tube, states):
    coords = tube.coords if states == "motion" else None
    write_glb(tmp_path / "m.glb", tube.crease_pattern, coords=coords, unit="mm", interpolation="STEP")
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
    write_glb(tmp_path / "m.glb", tube.crease_pattern, coords=tube.coords, unit="mm")
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
        (dict(unit="furlong"), "give scale="),
        (dict(scale=-1.0), "scale must be a positive"),
        (dict(seconds_per_state=0.0), "seconds_per_state"),
        (dict(interpolation="CUBICSPLINE"), "interpolation"),
        (dict(up="x"), "up must be"),
        (dict(crease_kinds=("ruling",)), "crease_kinds"),
    ],
)
def test_glb_rejects_bad_input(tmp_path, tube, kwargs, match):
    with pytest.raises(InputError, match=match):
        write_glb(tmp_path / "m.glb", tube.crease_pattern, **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_glb_writer_is_atomic(tmp_path, monkeypatch, tube):
    pygltflib = pytest.importorskip("pygltflib")
    (tmp_path / "m.glb").write_bytes(b"old")

    def broken(self):
        raise RuntimeError("packing failed")

    monkeypatch.setattr(pygltflib.GLTF2, "save_to_bytes", broken)
    with pytest.raises(RuntimeError, match="packing failed"):
        write_glb(tmp_path / "m.glb", tube.crease_pattern, coords=tube.coords)
    _only(tmp_path, "m.glb")
    assert (tmp_path / "m.glb").read_bytes() == b"old"


# --- Rhino 3dm -------------------------------------------------------------------------------------


def test_3dm_read_back_by_rhino3dm(tmp_path, tube):
    rhino3dm = pytest.importorskip("rhino3dm")
    mesh = tube.state(2)
    write_3dm(tmp_path / "m.3dm", mesh, unit="mm", metadata={"length": 4.0, "name": "tube"})
    _only(tmp_path, "m.3dm")
    model = rhino3dm.File3dm.Read(str(tmp_path / "m.3dm"))
    assert [layer.Name for layer in model.Layers] == ["Surface", "Fold", "Seam", "Boundary", "Rulings"]
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Millimeters
    assert model.Strings["curvefold:length"] == "4.0"
    assert model.Strings["curvefold:name"] == "tube"
    assert model.Strings["curvefold:unit"] == "mm"

    by_layer: dict[str, list] = {}
    for obj in model.Objects:
        by_layer.setdefault(model.Layers[obj.Attributes.LayerIndex].Name, []).append(obj.Geometry)
    assert {k: len(v) for k, v in by_layer.items()} == {"Surface": 1, "Fold": 3, "Seam": 2, "Boundary": 2, "Rulings": 4}
    (surface,) = by_layer["Surface"]
    assert isinstance(surface, rhino3dm.Mesh)
    assert len(surface.Vertices) == len(mesh.vertices_coords)
    assert surface.Faces.Count == len(mesh.faces_vertices)
    vertices = np.array([[p.X, p.Y, p.Z] for p in surface.Vertices])
    assert_allclose(vertices, mesh.vertices_coords, atol=1e-6, rtol=0)
    faces = np.array([surface.Faces[i][:3] for i in range(surface.Faces.Count)])
    assert_array_equal(faces, mesh.faces_vertices)
    for curve in by_layer["Fold"] + by_layer["Rulings"]:
        assert isinstance(curve, rhino3dm.PolylineCurve)
    assert sorted(c.PointCount for c in by_layer["Fold"]) == [3, 3, 3]
    ends = np.array([[c.PointAt(c.Domain.T0).X, c.PointAt(c.Domain.T0).Y, c.PointAt(c.Domain.T0).Z] for c in by_layer["Fold"]])
    starts = mesh.vertices_coords[[p[0] for p in crease_polylines(mesh, "fold")]]
    assert_allclose(ends, starts, atol=1e-9, rtol=0)


@pytest.mark.parametrize(("unit", "system"), [("unit", "None"), ("m", "Meters"), ("cm", "Centimeters"), ("in", "Inches")])
def test_3dm_unit_system(tmp_path, tube, unit, system):
    rhino3dm = pytest.importorskip("rhino3dm")
    write_3dm(tmp_path / "m.3dm", tube.state(1), unit=unit)
    model = rhino3dm.File3dm.Read(str(tmp_path / "m.3dm"))
    assert model.Settings.ModelUnitSystem == getattr(rhino3dm.UnitSystem, system)
    assert model.Strings["curvefold:unit"] == unit


def test_3dm_rejects_unknown_unit(tmp_path, tube):
    pytest.importorskip("rhino3dm")
    with pytest.raises(InputError, match="unit must be one of"):
        write_3dm(tmp_path / "m.3dm", tube.state(1), unit="furlong")
    assert list(tmp_path.iterdir()) == []


def test_3dm_writer_is_atomic(tmp_path, monkeypatch, tube):
    rhino3dm = pytest.importorskip("rhino3dm")
    real_write = rhino3dm.File3dm.Write

    def write_then_fail(self, path, version=0):
        real_write(self, path, version)  # a complete temporary file exists, then the run dies
        raise RuntimeError("interrupted")

    monkeypatch.setattr(rhino3dm.File3dm, "Write", write_then_fail)
    with pytest.raises(RuntimeError, match="interrupted"):
        write_3dm(tmp_path / "m.3dm", tube.state(1))
    assert list(tmp_path.iterdir()) == []


def test_3dm_write_returning_false_is_an_error(tmp_path, monkeypatch, tube):
    rhino3dm = pytest.importorskip("rhino3dm")
    monkeypatch.setattr(rhino3dm.File3dm, "Write", lambda self, path, version=0: False)
    with pytest.raises(OSError, match="could not write"):
        write_3dm(tmp_path / "m.3dm", tube.state(1))
    assert list(tmp_path.iterdir()) == []


def test_writers_accept_an_empty_mesh(tmp_path):
    empty = Mesh(vertices_coords=np.zeros((0, 3)), edges_vertices=np.zeros((0, 2), int), edges_assignment=np.zeros(0, "<U1"),
                 edges_foldAngle=np.zeros(0), faces_vertices=np.zeros((0, 3), int), edges_kind=np.zeros(0, "<U8"),
                 faces_group=np.zeros(0, int))
    write_obj(tmp_path / "e.obj", empty)
    assert "g surface" in (tmp_path / "e.obj").read_text()
