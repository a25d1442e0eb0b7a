"""Binary glTF 2.0 (GLB) of a folding motion, as morph targets with an animation.

The file holds one node and one mesh per part, named by it (the sheets of a structure:
``"tube 1 · sheet A"``; a mesh given without parts is one part, ``"surface"``). Each mesh has

* one triangle primitive (double-sided grey material) with positions and normals; its
  vertices are split along the creases between its strips, so a folded crease shows as
  a sharp edge and a curved strip shades smoothly;
* one ``LINES`` primitive per crease kind on the part (fold red, seam blue, boundary
  black, from :data:`curvefold.io._tables.COLOURS`).

The base positions are the base state (``base_state``, by default the last: the design
state, which is what a viewer shows without playing the animation); every other state is
a morph target holding the position (and normal) differences to it, in state order, named
by its fold angle in the mesh's ``extras.targetNames`` (``"2α = 45°"``; three.js reads
them into ``morphTargetDictionary``). Further named morph targets (``morph_targets``: a
deformed shape, the modes of a mechanical analysis, as displacements from the base state)
follow the states, with weight 0 and outside the animation.

One animation drives the ``weights`` of every node: it starts at the base state, unfolds
to the first state (flat), folds to the last and returns to the base state, each step
``seconds_per_state`` long. Its first keyframe is the base state, which importers that
apply the first keyframe (Blender) therefore open. At keyframe times the weights select
one state exactly, so ``LINEAR`` interpolation blends linearly between neighbouring states
and ``STEP`` jumps between them.

Units and axes: glTF lengths are metres and +Y is up. Coordinates are multiplied by
``scale`` (metres per model unit; by default taken from ``unit``: ``"mm"`` → 0.001,
``"unit"`` → 1) and, with ``up="z"``, turned by the rotation ``(x, y, z) → (x, z, -y)``
so that the model's +Z points up in glTF viewers. Both are recorded in
``asset.extras["curvefold"]`` together with the fold angles of the states and the
design parameters. Positions are 32-bit floats; accessor ``min``/``max`` are those of
the stored 32-bit values.

The JSON document and its one binary buffer are written in the GLB container (glTF 2.0,
section 4.4) by a few lines here, with the objects and defaults ``pygltflib`` writes: its
serialisation takes 0.5 CPU-s for the paper's vault's 704 accessors, ten times the rest of
the file. The tests have ``pygltflib`` read every file and write it back byte for byte, and
the Khronos glTF validator check it.
"""

from __future__ import annotations

import json
import os
import struct
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import MappingProxyType

import numpy as np

from ..geometry._mesh import Mesh
from ..kernel._errors import InputError
from ..kernel._validate import check_integer
from ._atomic import atomic_write
from ._mesh3d import Y_UP, check_metadata
from ._tables import CREATOR, UNITS, rgba

__all__ = ["CREASE_COLOURS", "write_glb"]

#: RGBA colour of each crease kind drawn as lines (from :data:`curvefold.io._tables.COLOURS`).
CREASE_COLOURS = MappingProxyType({kind: rgba(kind) for kind in ("fold", "seam", "boundary")})

_FLOAT, _UINT32 = 5126, 5125
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963
_LINES, _TRIANGLES = 1, 4
_AXES = {"z": Y_UP["y"], "y": Y_UP["z"]}  # the model's up axis -> the rotation onto glTF's +Y up


class _Packer:
    """Collects 4-byte aligned buffer views and their accessors (glTF JSON objects) into one binary buffer."""

    def __init__(self):
        self.blob = bytearray()
        self.views: list[dict] = []
        self.accessors: list[dict] = []

    def add(self, data: np.ndarray, kind: str, *, target: int | None = None, min_max: bool = False) -> int:
        count = len(data) if kind != "SCALAR" or data.ndim == 1 else data.size
        bounds = (data.reshape(int(count), -1).max(axis=0), data.reshape(int(count), -1).min(axis=0)) if min_max else None
        return self._add(data, kind, target, bounds)

    def add_vec3(self, data: np.ndarray) -> list[int]:
        """Accessors of float32 vertex attributes, one per state of ``data`` (S, n, 3), with their bounds."""
        data = data.astype(np.float32)
        highs, lows = data.max(axis=1), data.min(axis=1)
        return [self._add(d, "VEC3", _ARRAY_BUFFER, bounds) for d, bounds in zip(data, zip(highs, lows))]

    def _add(self, data: np.ndarray, kind: str, target: int | None, bounds: tuple | None) -> int:
        raw = np.ascontiguousarray(data).tobytes()
        self.blob += b"\0" * (-len(self.blob) % 4)
        self.views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(raw), **({} if target is None else {"target": target})})
        self.blob += raw
        component = _FLOAT if data.dtype == np.float32 else _UINT32
        count = len(data) if kind != "SCALAR" or data.ndim == 1 else data.size
        accessor = {"bufferView": len(self.views) - 1, "byteOffset": 0, "componentType": component, "normalized": False,
                    "count": int(count), "type": kind}
        if bounds is not None:
            accessor |= {"max": bounds[0].tolist(), "min": bounds[1].tolist()}
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def _material(name: str, colour: tuple, *, double_sided: bool) -> dict:
    return {"pbrMetallicRoughness": {"baseColorFactor": list(colour), "metallicFactor": 0.0, "roughnessFactor": 1.0},
            "emissiveFactor": [0.0, 0.0, 0.0], "alphaMode": "OPAQUE", "doubleSided": double_sided, "name": name}


def _glb(document: dict, blob: bytes) -> bytes:
    """The binary glTF container (glTF 2.0, section 4.4) of a JSON document and its buffer: a
    12-byte header, the JSON chunk padded with spaces and the BIN chunk padded with zeros, each to 4 bytes."""
    text = json.dumps(document, allow_nan=False, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    return b"".join([b"glTF", struct.pack("<II", 2, 28 + len(text) + len(blob)), struct.pack("<I", len(text)), b"JSON", text,
                     struct.pack("<I", len(blob)), b"BIN\0", blob])


def _keyframes(count: int, base: int) -> np.ndarray:
    """The states of the animation's keyframes: from ``base`` down to 0, up to the last and back to ``base``.

    Examples
    --------
    >>> _keyframes(4, 3).tolist(), _keyframes(3, 0).tolist(), _keyframes(1, 0).tolist()
    ([3, 2, 1, 0, 1, 2, 3], [0, 1, 2, 1, 0], [0])
    """
    return np.array([*range(base, -1, -1), *range(1, count), *range(count - 2, base - 1, -1)], dtype=np.int64)


def _vertex_normals(pos: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Unit normals (..., n, 3) of vertices (..., n, 3), of every state at once: the area-weighted
    mean of their triangles' normals."""
    a, b, c = (pos[..., triangles[:, k], :] for k in range(3))
    face = np.cross(b - a, c - a).reshape(-1, len(triangles), 3)  # twice the area times the normal, per state
    n = pos.shape[-2]
    states = np.arange(len(face))[:, None] * n  # each state's vertices numbered after the previous state's
    out = np.stack([sum(np.bincount((states + triangles[:, k]).reshape(-1), face[..., j].reshape(-1), minlength=len(face) * n)
                        for k in range(3)) for j in range(3)], axis=-1).reshape(pos.shape)
    return out / np.maximum(np.linalg.norm(out, axis=-1, keepdims=True), 1e-300)


def _split_by_strip(faces: np.ndarray, groups: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A part's triangles (F, 3) with their vertices copied per strip: (mesh vertex of every copy, triangles in copies)."""
    key = groups[:, None] * (int(faces.max(initial=0)) + 1) + faces  # (strip, vertex) pairs
    pairs, local = np.unique(key.reshape(-1), return_inverse=True)
    return pairs % (int(faces.max(initial=0)) + 1), local.reshape(-1, 3)


def write_glb(
    path: str | os.PathLike,
    mesh: Mesh,
    *,
    coords: np.ndarray | None = None,
    angles_deg: np.ndarray | Sequence[float] | None = None,
    unit: str = "unit",
    scale: float | None = None,
    metadata: Mapping | None = None,
    base_state: int = -1,
    seconds_per_state: float = 1.0,
    interpolation: str = "LINEAR",
    up: str = "z",
    crease_kinds: Sequence[str] = ("fold", "seam", "boundary"),
    parts: Sequence[tuple[str, np.ndarray, np.ndarray]] | None = None,
    morph_targets: Mapping[str, np.ndarray] | None = None,
) -> Path:
    """Write a folding motion as an animated GLB (see the module notes).

    Parameters
    ----------
    path : path-like
    mesh : Mesh
        Topology (V vertices, polygon faces, triangulated for glTF) and edge kinds.
    coords : (K, V, 3) array_like, optional
        The states of the motion, in model units. Default: the single state
        ``mesh.vertices_coords`` (no morph targets, no animation).
    angles_deg : (K,) array_like, optional
        Design fold angle of each state, recorded in the asset extras.
    unit : str
        Model unit of ``coords``.
    scale : float, optional
        Metres per model unit. Default: from ``unit`` (see :data:`curvefold.io._tables.UNITS`).
    metadata : mapping, optional
        Design parameters, recorded in the asset extras.
    base_state : int
        The state whose positions are the meshes' own (index into ``coords``; default the last).
    seconds_per_state : float
        Animation time from one state to the next (> 0).
    interpolation : {"LINEAR", "STEP"}
        Animation sampler interpolation.
    up : {"z", "y"}
        Which model axis points up; ``"z"`` is rotated onto glTF's +Y.
    crease_kinds : sequence of str
        Kinds drawn as coloured lines (keys of :data:`CREASE_COLOURS`).
    parts : sequence of (str, (F_p,) array_like of int, (E_p,) array_like of int), optional
        The nodes: a name, the faces and the edges of the mesh on each (a structure's sheets:
        :attr:`SheetTopology.faces <curvefold.geometry.SheetTopology>` and ``edges``).
        Default: one node ``"surface"`` with every face and edge.
    morph_targets : mapping of str to (V, 3) array_like, optional
        Further morph targets by name: displacements of the vertices from the base state,
        in model units (a deformed shape less the base state, a mode shape).

    Returns
    -------
    Path

    Raises
    ------
    InputError
        On a wrong shape, non-finite coordinates, an unknown unit without ``scale`` or
        a bad option.
    """
    V = len(mesh.vertices_coords)
    states = np.asarray(mesh.vertices_coords if coords is None else coords, float)
    if states.ndim == 2:
        states = states[None]
    if states.ndim != 3 or states.shape[1:] != (V, 3) or len(states) == 0:
        raise InputError(f"coords must have shape (K, {V}, 3) with K >= 1, got {states.shape}")
    if not np.isfinite(states).all():
        raise InputError("coords must be finite")
    K = len(states)
    base_state = check_integer(base_state, "base_state", f"[{-K}, {K})", why="a state index") % K
    angles = None
    if angles_deg is not None:
        angles = np.asarray(angles_deg, float).reshape(-1)
        if angles.shape != (K,):
            raise InputError(f"angles_deg must have shape ({K},) like coords, got {np.shape(angles_deg)}")
    if scale is None:
        if unit not in UNITS:
            raise InputError(f"unit {unit!r} has no known size in metres; give scale= (metres per unit) or use one of {sorted(UNITS)}")
        scale = UNITS[unit].metres
    if not (np.isfinite(scale) and scale > 0):
        raise InputError(f"scale must be a positive number of metres per unit, got {scale}")
    if not (np.isfinite(seconds_per_state) and seconds_per_state > 0):
        raise InputError(f"seconds_per_state must be > 0, got {seconds_per_state}")
    if interpolation not in ("LINEAR", "STEP"):
        raise InputError(f"interpolation must be 'LINEAR' or 'STEP', got {interpolation!r}")
    if up not in _AXES:
        raise InputError(f"up must be 'z' or 'y', got {up!r}")
    bad = [k for k in crease_kinds if k not in CREASE_COLOURS]
    if bad:
        raise InputError(f"crease_kinds must be among {tuple(CREASE_COLOURS)}, got {bad}")
    meta = check_metadata(metadata)
    triangulated = mesh.triangulated()  # polygons split in place, in face order
    faces, groups = triangulated.faces_vertices, np.asarray(triangulated.faces_group)
    polygon_of = np.repeat(np.arange(len(mesh.faces_vertices)), mesh.face_sizes() - 2)  # the mesh face of every triangle
    parts = _check_parts(parts, len(mesh.faces_vertices), len(mesh.edges_vertices))
    extra = _check_morphs(morph_targets, V)

    rotation = _AXES[up]
    pos = (states * float(scale)) @ rotation.T  # (K, V, 3) metres, glTF axes
    others = np.array([k for k in range(K) if k != base_state], dtype=np.int64)  # the states of targets 0 … K − 2
    poses = np.concatenate([pos[others], pos[base_state] + (np.stack(list(extra.values())) * float(scale)) @ rotation.T]) if extra else pos[others]
    names = [f"2α = {angles[k]:g}°" if angles is not None else f"state {k}" for k in others] + list(extra)
    T = len(poses)  # morph targets

    pk = _Packer()
    materials = [_material("surface", rgba("surface"), double_sided=True)]
    kind_material: dict[str, int] = {}
    edges_kind = np.asarray(mesh.edges_kind)

    def vec3(data: np.ndarray) -> int:
        return pk.add_vec3(data[None])[0]

    meshes, nodes = [], []
    for name, part_faces, part_edges in parts:
        mine = np.flatnonzero(np.isin(polygon_of, part_faces))  # the part's triangles
        copies, triangles = _split_by_strip(faces[mine], groups[mine])
        base = pos[base_state][copies]
        normal = _vertex_normals(base, triangles)
        moved = poses[:, copies]
        moved_normals = _vertex_normals(moved, triangles) if T else moved
        # accessors in the order position, normal of each target
        pairs = pk.add_vec3(np.stack([moved - base, moved_normals - normal], axis=1).reshape(-1, *base.shape)) if T else []
        targets = [{"POSITION": p, "NORMAL": n} for p, n in zip(pairs[::2], pairs[1::2])]
        primitives = [{"attributes": {"POSITION": vec3(base), "NORMAL": vec3(normal)},
                       "indices": pk.add(triangles.astype(np.uint32).reshape(-1), "SCALAR", target=_ELEMENT_ARRAY_BUFFER),
                       "mode": _TRIANGLES, "material": 0, **({"targets": targets} if T else {})}]
        for kind in crease_kinds:
            edges = np.asarray(mesh.edges_vertices)[part_edges[edges_kind[part_edges] == kind]]
            if len(edges) == 0:
                continue
            if kind not in kind_material:
                materials.append(_material(kind, CREASE_COLOURS[kind], double_sided=False))
                kind_material[kind] = len(materials) - 1
            used, local = np.unique(edges, return_inverse=True)
            primitives.append({
                "attributes": {"POSITION": vec3(pos[base_state][used])},
                "indices": pk.add(local.astype(np.uint32).reshape(-1), "SCALAR", target=_ELEMENT_ARRAY_BUFFER),
                "mode": _LINES, "material": kind_material[kind],
                **({"targets": [{"POSITION": p} for p in pk.add_vec3(poses[:, used] - pos[base_state][used])]} if T else {})})
        meshes.append({"extras": {"targetNames": names}, "primitives": primitives, **({"weights": [0.0] * T} if T else {}), "name": name})
        nodes.append({"mesh": len(meshes) - 1, "name": name})

    animations = []
    if K > 1:
        order = _keyframes(K, base_state)
        times = (np.arange(len(order)) * float(seconds_per_state)).astype(np.float32)
        target_of = np.full(K, -1)
        target_of[others] = np.arange(K - 1)  # the base state has all weights 0
        weights = np.zeros((len(order), T), np.float32)
        shown = target_of[order] >= 0
        weights[np.flatnonzero(shown), target_of[order][shown]] = 1.0
        t_acc = pk.add(times, "SCALAR", min_max=True)
        w_acc = pk.add(weights.reshape(-1), "SCALAR")
        animations.append({
            "name": "fold",
            "channels": [{"sampler": 0, "target": {"node": n, "path": "weights"}} for n in range(len(nodes))],
            "samplers": [{"input": t_acc, "interpolation": interpolation, "output": w_acc}],
        })

    extras = {
        "unit": unit,
        "scale_to_metres": float(scale),
        "up_axis": up,
        "axis_mapping": "(x, y, z) -> (x, z, -y)" if up == "z" else "none",
        "states": K,
        "base_state": base_state,
        "morph_targets": names,
        "seconds_per_state": float(seconds_per_state),
        "metadata": meta,
    }
    if angles is not None:
        extras["angles_deg"] = angles.tolist()
    document = {
        "accessors": pk.accessors,
        **({"animations": animations} if animations else {}),
        "asset": {"extras": {"curvefold": extras}, "generator": CREATOR, "version": "2.0"},
        "bufferViews": pk.views,
        "buffers": [{"byteLength": len(pk.blob)}],
        "materials": materials,
        "meshes": meshes,
        "nodes": nodes,
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
    }
    return atomic_write(path, _glb(document, bytes(pk.blob)))


def _check_parts(parts, faces: int, edges: int) -> list[tuple[str, np.ndarray, np.ndarray]]:
    if parts is None:
        return [("surface", np.arange(faces), np.arange(edges))]
    out = []
    for i, part in enumerate(parts):
        try:
            name, f, e = part
            f, e = np.asarray(f, np.int64).reshape(-1), np.asarray(e, np.int64).reshape(-1)
        except (TypeError, ValueError):
            raise InputError(f"parts[{i}] must be (name, face indices, edge indices), got {part!r}") from None
        if not isinstance(name, str) or len(f) == 0 or f.min() < 0 or f.max() >= faces or (len(e) and (e.min() < 0 or e.max() >= edges)):
            raise InputError(f"parts[{i}] must be a name and indices of the mesh's {faces} faces (at least one) and {edges} edges")
        out.append((name, f, e))
    if not out:
        raise InputError("parts must hold at least one part")
    return out


def _check_morphs(morph_targets, vertices: int) -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    for name, delta in (morph_targets or {}).items():
        d = np.asarray(delta, float)
        if not isinstance(name, str) or d.shape != (vertices, 3) or not np.isfinite(d).all():
            raise InputError(f"morph_targets[{name!r}] must be finite displacements of shape ({vertices}, 3), got shape {d.shape}")
        out[name] = d
    return out
