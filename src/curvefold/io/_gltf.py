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
``seconds_per_state`` long, or shorter so that the loop lasts at most :data:`LOOP_SECONDS`
(Blender's default timeline holds it whole). Its first keyframe is the base state, which
importers that apply the first keyframe (Blender) therefore open. At keyframe times the
weights select one state exactly, so ``LINEAR`` interpolation blends linearly between
neighbouring states and ``STEP`` jumps between them.

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
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from ..geometry._mesh import Mesh
from ..kernel._errors import InputError
from ..kernel._validate import check_integer
from ._atomic import atomic_write
from ._mesh3d import Y_UP, check_metadata
from ._tables import CREATOR, UNITS, rgba

__all__ = ["CREASE_COLOURS", "GlbOptions", "write_glb"]

#: The longest the folding loop lasts, s: within Blender's default timeline (frames 1–250 at
#: 24 frames per second, 10.4 s), which a longer animation would leave mid-loop.
LOOP_SECONDS = 10.0

#: RGBA colour of each crease kind drawn as lines (from :data:`curvefold.io._tables.COLOURS`).
CREASE_COLOURS = MappingProxyType({kind: rgba(kind) for kind in ("fold", "seam", "boundary")})

_FLOAT, _UINT32 = 5126, 5125
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963
_LINES, _TRIANGLES = 1, 4
_AXES = {"z": Y_UP["y"], "y": Y_UP["z"]}  # the model's up axis -> the rotation onto glTF's +Y up


class _Packer:
    """Collects 4-byte aligned buffer views and their accessors (glTF JSON objects) into one
    binary buffer."""

    def __init__(self):
        self.blob = bytearray()
        self.views: list[dict] = []
        self.accessors: list[dict] = []

    def add(
        self, data: np.ndarray, kind: str, *, target: int | None = None, min_max: bool = False
    ) -> int:
        count = len(data) if kind != "SCALAR" or data.ndim == 1 else data.size
        bounds = (
            (data.reshape(int(count), -1).max(axis=0), data.reshape(int(count), -1).min(axis=0))
            if min_max
            else None
        )
        return self._add(data, kind, target, bounds)

    def add_vec3(self, data: np.ndarray) -> list[int]:
        """Accessors of float32 vertex attributes, one per state of ``data`` (S, n, 3), with
        their bounds."""
        data = data.astype(np.float32)
        highs, lows = data.max(axis=1), data.min(axis=1)
        return [
            self._add(d, "VEC3", _ARRAY_BUFFER, bounds) for d, bounds in zip(data, zip(highs, lows))
        ]

    def _add(self, data: np.ndarray, kind: str, target: int | None, bounds: tuple | None) -> int:
        raw = np.ascontiguousarray(data).tobytes()
        self.blob += b"\0" * (-len(self.blob) % 4)
        self.views.append(
            {
                "buffer": 0,
                "byteOffset": len(self.blob),
                "byteLength": len(raw),
                **({} if target is None else {"target": target}),
            }
        )
        self.blob += raw
        component = _FLOAT if data.dtype == np.float32 else _UINT32
        count = len(data) if kind != "SCALAR" or data.ndim == 1 else data.size
        accessor = {
            "bufferView": len(self.views) - 1,
            "byteOffset": 0,
            "componentType": component,
            "normalized": False,
            "count": int(count),
            "type": kind,
        }
        if bounds is not None:
            accessor |= {"max": bounds[0].tolist(), "min": bounds[1].tolist()}
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def _material(name: str, colour: tuple, *, double_sided: bool) -> dict:
    return {
        "pbrMetallicRoughness": {
            "baseColorFactor": list(colour),
            "metallicFactor": 0.0,
            "roughnessFactor": 1.0,
        },
        "emissiveFactor": [0.0, 0.0, 0.0],
        "alphaMode": "OPAQUE",
        "doubleSided": double_sided,
        "name": name,
    }


def _glb(document: dict, blob: bytes) -> bytes:
    """The binary glTF container (glTF 2.0, section 4.4) of a JSON document and its buffer: a
    12-byte header, the JSON chunk padded with spaces and the BIN chunk padded with zeros, each
    to 4 bytes."""
    text = json.dumps(document, allow_nan=False, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    return b"".join(
        [
            b"glTF",
            struct.pack("<II", 2, 28 + len(text) + len(blob)),
            struct.pack("<I", len(text)),
            b"JSON",
            text,
            struct.pack("<I", len(blob)),
            b"BIN\0",
            blob,
        ]
    )


def _keyframes(count: int, base: int) -> np.ndarray:
    """The states of the animation's keyframes: from ``base`` down to 0, up to the last and back to
    ``base``.

    Examples
    --------
    >>> _keyframes(4, 3).tolist(), _keyframes(3, 0).tolist(), _keyframes(1, 0).tolist()
    ([3, 2, 1, 0, 1, 2, 3], [0, 1, 2, 1, 0], [0])
    """
    return np.array(
        [*range(base, -1, -1), *range(1, count), *range(count - 2, base - 1, -1)], dtype=np.int64
    )


def _vertex_normals(pos: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Unit normals (..., n, 3) of vertices (..., n, 3), of every state at once: the area-weighted
    mean of their triangles' normals."""
    a, b, c = (pos[..., triangles[:, k], :] for k in range(3))
    # twice the area times the normal, per state
    face = np.cross(b - a, c - a).reshape(-1, len(triangles), 3)
    n = pos.shape[-2]
    # each state's vertices numbered after the previous state's
    states = np.arange(len(face))[:, None] * n
    out = np.stack(
        [
            sum(
                np.bincount(
                    (states + triangles[:, k]).reshape(-1),
                    face[..., j].reshape(-1),
                    minlength=len(face) * n,
                )
                for k in range(3)
            )
            for j in range(3)
        ],
        axis=-1,
    ).reshape(pos.shape)
    return out / np.maximum(np.linalg.norm(out, axis=-1, keepdims=True), 1e-300)


def _split_by_strip(faces: np.ndarray, groups: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A part's triangles (F, 3) with their vertices copied per strip: (mesh vertex of every
    copy, triangles in copies)."""
    key = groups[:, None] * (int(faces.max(initial=0)) + 1) + faces  # (strip, vertex) pairs
    pairs, local = np.unique(key.reshape(-1), return_inverse=True)
    return pairs % (int(faces.max(initial=0)) + 1), local.reshape(-1, 3)


@dataclass(frozen=True, eq=False)
class GlbOptions:
    """How :func:`write_glb` writes a motion: units and axes, nodes, lines and the animation.

    Attributes
    ----------
    unit : str
        Model unit of the coordinates.
    scale : float or None
        Metres per model unit. None: from ``unit`` (see :data:`curvefold.io._tables.UNITS`).
    metadata : mapping or None
        Design parameters, recorded in the asset extras.
    seconds_per_state : float
        Animation time from one state to the next (> 0), at most: a longer loop is played
        faster, to last :data:`LOOP_SECONDS`.
    interpolation : {"LINEAR", "STEP"}
        Animation sampler interpolation.
    up : {"z", "y"}
        Which model axis points up; ``"z"`` is rotated onto glTF's +Y.
    crease_kinds : sequence of str
        Kinds drawn as coloured lines (keys of :data:`CREASE_COLOURS`).
    parts : sequence of (str, (F_p,) array_like of int, (E_p,) array_like of int), or None
        The nodes: a name, the faces and the edges of the mesh on each (a structure's sheets:
        :attr:`SheetTopology.faces <curvefold.geometry.SheetTopology>` and ``edges``).
        None: one node ``"surface"`` with every face and edge.
    """

    unit: str = "unit"
    scale: float | None = None
    metadata: Mapping[str, Any] | None = None
    seconds_per_state: float = 1.0
    interpolation: str = "LINEAR"
    up: str = "z"
    crease_kinds: Sequence[str] = ("fold", "seam", "boundary")
    parts: Sequence[tuple[str, Any, Any]] | None = None


@dataclass(frozen=True, eq=False)
class _Motion:
    """The states of a motion, checked and turned into glTF's frame: what every node and the
    animation read."""

    states: int  # K
    base_state: int
    positions: np.ndarray  # (K, V, 3) metres, glTF axes
    others: np.ndarray  # the states of morph targets 0 … K − 2, all but the base
    poses: np.ndarray  # (T, V, 3) the morph targets' positions: other states, further targets
    names: list[str]  # (T,) the morph targets' names
    angles: np.ndarray | None  # (K,) degrees

    @property
    def base(self) -> np.ndarray:
        """The base state's positions (V, 3)."""
        return self.positions[self.base_state]

    @property
    def targets(self) -> int:
        """Number of morph targets, T."""
        return len(self.poses)


def write_glb(
    path: str | os.PathLike,
    mesh: Mesh,
    *,
    coords: np.ndarray | None = None,
    angles_deg: np.ndarray | Sequence[float] | None = None,
    base_state: int = -1,
    morph_targets: Mapping[str, np.ndarray] | None = None,
    options: GlbOptions = GlbOptions(),
) -> Path:
    """Write a folding motion as an animated GLB (see the module notes).

    Parameters
    ----------
    path : path-like
    mesh : Mesh
        Topology (V vertices, polygon faces, triangulated for glTF) and edge kinds.
    coords : (K, V, 3) array_like, optional, keyword-only
        The states of the motion, in model units. Default: the single state
        ``mesh.vertices_coords`` (no morph targets, no animation).
    angles_deg : (K,) array_like, optional, keyword-only
        Design fold angle of each state, recorded in the asset extras.
    base_state : int, keyword-only
        The state whose positions are the meshes' own (index into ``coords``; default the last).
    morph_targets : mapping of str to (V, 3) array_like, optional, keyword-only
        Further morph targets by name: displacements of the vertices from the base state,
        in model units (a deformed shape less the base state, a mode shape).
    options : GlbOptions, keyword-only
        Unit and scale, up axis, metadata, nodes (``parts``), crease lines and animation timing.

    Returns
    -------
    Path

    Raises
    ------
    InputError
        On a wrong shape, non-finite coordinates, an unknown unit without ``scale`` or
        a bad option.
    """
    if not isinstance(options, GlbOptions):
        raise InputError(
            f"options must be a GlbOptions, got {type(options).__name__}", parameter="options"
        )
    scale = _check_options(options)
    meta = check_metadata(options.metadata)
    parts = _check_parts(options.parts, len(mesh.faces_vertices), len(mesh.edges_vertices))
    motion = _motion(mesh, coords, angles_deg, base_state, morph_targets, scale, options.up)

    pk = _Packer()
    materials = [_material("surface", rgba("surface"), double_sided=True)]
    meshes = [_part_mesh(pk, materials, mesh, motion, part, options.crease_kinds) for part in parts]
    nodes = [{"mesh": i, "name": m["name"]} for i, m in enumerate(meshes)]
    animations = _animations(pk, motion, len(nodes), options) if motion.states > 1 else []
    extras = _extras(motion, options, scale, meta)
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


def _check_options(options: GlbOptions) -> float:
    """The options' metres per model unit, once every option is checked."""
    scale = options.scale
    if scale is None:
        if options.unit not in UNITS:
            raise InputError(
                f"unit {options.unit!r} has no known size in metres; give scale= "
                f"(metres per unit) or use one of {sorted(UNITS)}"
            )
        scale = UNITS[options.unit].metres
    if not (np.isfinite(scale) and scale > 0):
        raise InputError(f"scale must be a positive number of metres per unit, got {scale}")
    seconds = options.seconds_per_state
    if not (np.isfinite(seconds) and seconds > 0):
        raise InputError(f"seconds_per_state must be > 0, got {seconds}")
    if options.interpolation not in ("LINEAR", "STEP"):
        raise InputError(f"interpolation must be 'LINEAR' or 'STEP', got {options.interpolation!r}")
    if options.up not in _AXES:
        raise InputError(f"up must be 'z' or 'y', got {options.up!r}")
    bad = [k for k in options.crease_kinds if k not in CREASE_COLOURS]
    if bad:
        raise InputError(f"crease_kinds must be among {tuple(CREASE_COLOURS)}, got {bad}")
    return float(scale)


def _motion(
    mesh: Mesh,
    coords: np.ndarray | None,
    angles_deg: np.ndarray | Sequence[float] | None,
    base_state: int,
    morph_targets: Mapping[str, np.ndarray] | None,
    scale: float,
    up: str,
) -> _Motion:
    """The states checked, in metres and glTF's axes, and the morph targets they and
    ``morph_targets`` make."""
    V = len(mesh.vertices_coords)
    states = np.asarray(mesh.vertices_coords if coords is None else coords, float)
    if states.ndim == 2:
        states = states[None]
    if states.ndim != 3 or states.shape[1:] != (V, 3) or len(states) == 0:
        raise InputError(f"coords must have shape (K, {V}, 3) with K >= 1, got {states.shape}")
    if not np.isfinite(states).all():
        raise InputError("coords must be finite")
    K = len(states)
    base = check_integer(base_state, "base_state", f"[{-K}, {K})", why="a state index") % K
    angles = None
    if angles_deg is not None:
        angles = np.asarray(angles_deg, float).reshape(-1)
        if angles.shape != (K,):
            raise InputError(
                f"angles_deg must have shape ({K},) like coords, got {np.shape(angles_deg)}"
            )
    extra = _check_morphs(morph_targets, V)
    rotation = _AXES[up]
    pos = (states * scale) @ rotation.T  # (K, V, 3) metres, glTF axes
    others = np.array([k for k in range(K) if k != base], dtype=np.int64)  # targets 0 … K − 2
    poses = pos[others]
    if extra:
        further = (np.stack(list(extra.values())) * scale) @ rotation.T
        poses = np.concatenate([poses, pos[base] + further])
    names = [f"2α = {angles[k]:g}°" if angles is not None else f"state {k}" for k in others] + list(
        extra
    )
    return _Motion(K, base, pos, others, poses, names, angles)


def _part_mesh(
    pk: _Packer,
    materials: list[dict],
    mesh: Mesh,
    motion: _Motion,
    part: tuple[str, np.ndarray, np.ndarray],
    crease_kinds: Sequence[str],
) -> dict:
    """The glTF mesh of one part: its triangles, then a line primitive per crease kind on it
    (materials added as first used)."""
    name, part_faces, part_edges = part
    primitives = [_surface(pk, mesh, motion, part_faces)]
    edges_kind = np.asarray(mesh.edges_kind)
    for kind in crease_kinds:
        edges = np.asarray(mesh.edges_vertices)[part_edges[edges_kind[part_edges] == kind]]
        if len(edges) == 0:
            continue
        if all(m["name"] != kind for m in materials):
            materials.append(_material(kind, CREASE_COLOURS[kind], double_sided=False))
        material = next(i for i, m in enumerate(materials) if m["name"] == kind)
        primitives.append(_lines(pk, motion, edges, material))
    T = motion.targets
    weights = {"weights": [0.0] * T} if T else {}
    return {
        "extras": {"targetNames": motion.names},
        "primitives": primitives,
        **weights,
        "name": name,
    }


def _surface(pk: _Packer, mesh: Mesh, motion: _Motion, part_faces: np.ndarray) -> dict:
    """The triangle primitive of a part's faces, its vertices split between strips, with its
    morph targets."""
    triangulated = mesh.triangulated()  # polygons split in place, in face order
    faces, groups = triangulated.faces_vertices, np.asarray(triangulated.faces_group)
    # the mesh face of every triangle
    polygon_of = np.repeat(np.arange(len(mesh.faces_vertices)), mesh.face_sizes() - 2)
    mine = np.flatnonzero(np.isin(polygon_of, part_faces))  # the part's triangles
    copies, triangles = _split_by_strip(faces[mine], groups[mine])
    base = motion.base[copies]
    normal = _vertex_normals(base, triangles)
    T = motion.targets
    moved = motion.poses[:, copies]
    moved_normals = _vertex_normals(moved, triangles) if T else moved
    # accessors in the order position, normal of each target
    deltas = np.stack([moved - base, moved_normals - normal], axis=1).reshape(-1, *base.shape)
    pairs = pk.add_vec3(deltas) if T else []
    targets = [{"POSITION": p, "NORMAL": n} for p, n in zip(pairs[::2], pairs[1::2])]
    attributes = {"POSITION": pk.add_vec3(base[None])[0], "NORMAL": pk.add_vec3(normal[None])[0]}
    indices = pk.add(
        triangles.astype(np.uint32).reshape(-1), "SCALAR", target=_ELEMENT_ARRAY_BUFFER
    )
    return {
        "attributes": attributes,
        "indices": indices,
        "mode": _TRIANGLES,
        "material": 0,
        **({"targets": targets} if T else {}),
    }


def _lines(pk: _Packer, motion: _Motion, edges: np.ndarray, material: int) -> dict:
    """The ``LINES`` primitive of a part's edges (E, 2) of one kind, with its morph targets."""
    used, local = np.unique(edges, return_inverse=True)
    base = motion.base[used]
    position = pk.add_vec3(base[None])[0]
    indices = pk.add(local.astype(np.uint32).reshape(-1), "SCALAR", target=_ELEMENT_ARRAY_BUFFER)
    moved = pk.add_vec3(motion.poses[:, used] - base) if motion.targets else None
    targets = None if moved is None else [{"POSITION": p} for p in moved]
    return {
        "attributes": {"POSITION": position},
        "indices": indices,
        "mode": _LINES,
        "material": material,
        **({"targets": targets} if targets is not None else {}),
    }


def _animations(pk: _Packer, motion: _Motion, nodes: int, options: GlbOptions) -> list[dict]:
    """The one animation of the weights of every node: from the base state to flat, to the last
    and back."""
    K, T = motion.states, motion.targets
    order = _keyframes(K, motion.base_state)
    times = (np.arange(len(order)) * _step_seconds(motion, options)).astype(np.float32)
    target_of = np.full(K, -1)
    target_of[motion.others] = np.arange(K - 1)  # the base state has all weights 0
    weights = np.zeros((len(order), T), np.float32)
    shown = target_of[order] >= 0
    weights[np.flatnonzero(shown), target_of[order][shown]] = 1.0
    t_acc = pk.add(times, "SCALAR", min_max=True)
    w_acc = pk.add(weights.reshape(-1), "SCALAR")
    return [
        {
            "name": "fold",
            "channels": [
                {"sampler": 0, "target": {"node": n, "path": "weights"}} for n in range(nodes)
            ],
            "samplers": [{"input": t_acc, "interpolation": options.interpolation, "output": w_acc}],
        }
    ]


def _step_seconds(motion: _Motion, options: GlbOptions) -> float:
    """Seconds from one keyframe to the next: ``seconds_per_state``, or less where the loop would
    last longer than :data:`LOOP_SECONDS`."""
    steps = len(_keyframes(motion.states, motion.base_state)) - 1
    return min(float(options.seconds_per_state), LOOP_SECONDS / max(steps, 1))


def _extras(motion: _Motion, options: GlbOptions, scale: float, meta: dict) -> dict:
    """The asset's ``extras["curvefold"]``: units, axes, states, morph targets, timing and the
    design."""
    extras = {
        "unit": options.unit,
        "scale_to_metres": scale,
        "up_axis": options.up,
        "axis_mapping": "(x, y, z) -> (x, z, -y)" if options.up == "z" else "none",
        "states": motion.states,
        "base_state": motion.base_state,
        "morph_targets": motion.names,
        "seconds_per_state": _step_seconds(motion, options),
        "metadata": meta,
    }
    if motion.angles is not None:
        extras["angles_deg"] = motion.angles.tolist()
    return extras


def _check_parts(parts, faces: int, edges: int) -> list[tuple[str, np.ndarray, np.ndarray]]:
    if parts is None:
        return [("surface", np.arange(faces), np.arange(edges))]
    out = []
    for i, part in enumerate(parts):
        try:
            name, f, e = part
            f, e = np.asarray(f, np.int64).reshape(-1), np.asarray(e, np.int64).reshape(-1)
        except (TypeError, ValueError):
            raise InputError(
                f"parts[{i}] must be (name, face indices, edge indices), got {part!r}"
            ) from None
        if (
            not isinstance(name, str)
            or len(f) == 0
            or f.min() < 0
            or f.max() >= faces
            or (len(e) and (e.min() < 0 or e.max() >= edges))
        ):
            raise InputError(
                f"parts[{i}] must be a name and indices of the mesh's {faces} faces "
                f"(at least one) and {edges} edges"
            )
        out.append((name, f, e))
    if not out:
        raise InputError("parts must hold at least one part")
    return out


def _check_morphs(morph_targets, vertices: int) -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    for name, delta in (morph_targets or {}).items():
        d = np.asarray(delta, float)
        if not isinstance(name, str) or d.shape != (vertices, 3) or not np.isfinite(d).all():
            raise InputError(
                f"morph_targets[{name!r}] must be finite displacements of shape "
                f"({vertices}, 3), got shape {d.shape}"
            )
        out[name] = d
    return out
