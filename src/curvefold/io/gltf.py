"""Binary glTF 2.0 (GLB) of a folding motion, as morph targets with an animation.

The file holds two meshes that move together:

* ``surface``: the triangles (double-sided grey material). Its base positions are the
  base state (``base_state``, by default the last: the design state, which is what a
  viewer shows without playing the animation); every other state is a morph target
  holding the position differences to it, in state order, named by its fold angle in
  the mesh's ``extras.targetNames`` (``"2α = 45°"``; three.js reads them into
  ``morphTargetDictionary``).
* ``creases``: one ``LINES`` primitive per crease kind present, with a material of the
  kind's colour (fold red, seam blue, boundary black) and the same morph targets.

One animation drives the ``weights`` of both nodes: at time ``k * seconds_per_state``
the weights select state k exactly (all zero for the base state, the unit vector of the
state's target otherwise), so ``LINEAR`` interpolation blends linearly from each state
to the next and ``STEP`` jumps between them.

Units and axes: glTF lengths are metres and +Y is up. Coordinates are multiplied by
``scale`` (metres per model unit; by default taken from ``unit``: ``"mm"`` → 0.001,
``"unit"`` → 1) and, with ``up="z"``, turned by the rotation ``(x, y, z) → (x, z, -y)``
so that the model's +Z points up in glTF viewers. Both are recorded in
``asset.extras["curvefold"]`` together with the fold angles of the states and the
design parameters. Positions are 32-bit floats; accessor ``min``/``max`` are those of
the stored 32-bit values. Normals are not written (viewers shade flat).

Written with ``pygltflib`` (an optional dependency, imported when called).
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import MappingProxyType

import numpy as np

from ..geometry.mesh import Mesh
from ..kernel.errors import InputError
from ..kernel.validate import check_integer
from .atomic import atomic_write
from .mesh3d import Y_UP, check_metadata
from .tables import CREATOR, UNITS, rgba

__all__ = ["CREASE_COLOURS", "write_glb"]

#: RGBA colour of each crease kind drawn as lines (from :data:`curvefold.io.tables.COLOURS`).
CREASE_COLOURS = MappingProxyType({kind: rgba(kind) for kind in ("fold", "seam", "boundary")})

_FLOAT, _UINT32 = 5126, 5125
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963
_LINES, _TRIANGLES = 1, 4
_AXES = {"z": Y_UP["y"], "y": Y_UP["z"]}  # the model's up axis -> the rotation onto glTF's +Y up


class _Packer:
    """Collects 4-byte aligned buffer views and their accessors into one binary buffer."""

    def __init__(self, gltf_module):
        self.g = gltf_module
        self.blob = bytearray()
        self.views: list = []
        self.accessors: list = []

    def add(self, data: np.ndarray, kind: str, *, target: int | None = None, min_max: bool = False) -> int:
        raw = np.ascontiguousarray(data).tobytes()
        self.blob += b"\0" * (-len(self.blob) % 4)
        self.views.append(self.g.BufferView(buffer=0, byteOffset=len(self.blob), byteLength=len(raw), target=target))
        self.blob += raw
        component = _FLOAT if data.dtype == np.float32 else _UINT32
        count = len(data) if kind != "SCALAR" or data.ndim == 1 else data.size
        accessor = self.g.Accessor(bufferView=len(self.views) - 1, componentType=component, count=int(count), type=kind)
        if min_max:
            flat = data.reshape(int(count), -1)
            accessor.min = [float(v) for v in flat.min(axis=0)]
            accessor.max = [float(v) for v in flat.max(axis=0)]
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def _material(g, name: str, colour: tuple, *, double_sided: bool):
    return g.Material(
        name=name,
        doubleSided=double_sided,
        pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=list(colour), metallicFactor=0.0, roughnessFactor=1.0),
    )


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
) -> Path:
    """Write a folding motion as an animated GLB.

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
        Metres per model unit. Default: from ``unit`` (see :data:`curvefold.io.tables.UNITS`).
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

    Returns
    -------
    Path

    Raises
    ------
    InputError
        On a wrong shape, non-finite coordinates, an unknown unit without ``scale`` or
        a bad option.
    """
    try:
        import pygltflib as g
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("writing GLB needs pygltflib: pip install 'curvefold[export]'") from exc

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

    pos = (states * float(scale)) @ _AXES[up].T  # (K, V, 3) metres, glTF axes
    others = np.array([k for k in range(K) if k != base_state], dtype=np.int64)  # the states of targets 0 … K − 2
    base = pos[base_state].astype(np.float32)
    deltas = (pos[others] - pos[base_state]).astype(np.float32)  # (K-1, V, 3)
    names = [f"2α = {angles[k]:g}°" if angles is not None else f"state {k}" for k in others]

    pk = _Packer(g)
    materials = [_material(g, "surface", rgba("surface"), double_sided=True)]

    def primitive(vertex_ids: np.ndarray, indices: np.ndarray, mode: int, material: int):
        position = pk.add(base[vertex_ids], "VEC3", target=_ARRAY_BUFFER, min_max=True)
        targets = [g.Attributes(POSITION=pk.add(d[vertex_ids], "VEC3", target=_ARRAY_BUFFER, min_max=True)) for d in deltas]
        idx = pk.add(indices.astype(np.uint32).reshape(-1), "SCALAR", target=_ELEMENT_ARRAY_BUFFER)
        return g.Primitive(attributes=g.Attributes(POSITION=position), indices=idx, mode=mode, material=material, targets=targets)

    surface = g.Mesh(
        name="surface",
        primitives=[primitive(np.arange(V), mesh.triangulated().faces_vertices, _TRIANGLES, 0)],
        weights=[0.0] * (K - 1),
        extras={"targetNames": names},
    )
    line_primitives = []
    for kind in crease_kinds:
        edges = np.asarray(mesh.edges_vertices)[np.asarray(mesh.edges_kind) == kind]
        if len(edges) == 0:
            continue
        used, local = np.unique(edges, return_inverse=True)
        materials.append(_material(g, kind, CREASE_COLOURS[kind], double_sided=False))
        line_primitives.append(primitive(used, local.reshape(-1, 2), _LINES, len(materials) - 1))

    meshes = [surface]
    nodes = [g.Node(name="surface", mesh=0)]
    if line_primitives:
        meshes.append(g.Mesh(name="creases", primitives=line_primitives, weights=[0.0] * (K - 1), extras={"targetNames": names}))
        nodes.append(g.Node(name="creases", mesh=1))

    animations = []
    if K > 1:
        times = (np.arange(K) * float(seconds_per_state)).astype(np.float32)
        weights = np.zeros((K, K - 1), np.float32)
        weights[others, np.arange(K - 1)] = 1.0  # the base state has all weights 0
        t_acc = pk.add(times, "SCALAR", min_max=True)
        w_acc = pk.add(weights.reshape(-1), "SCALAR")
        animations.append(g.Animation(
            name="fold",
            samplers=[g.AnimationSampler(input=t_acc, output=w_acc, interpolation=interpolation)],
            channels=[g.AnimationChannel(sampler=0, target=g.AnimationChannelTarget(node=n, path="weights")) for n in range(len(nodes))],
        ))

    extras = {
        "unit": unit,
        "scale_to_metres": float(scale),
        "up_axis": up,
        "axis_mapping": "(x, y, z) -> (x, z, -y)" if up == "z" else "none",
        "states": K,
        "base_state": base_state,
        "seconds_per_state": float(seconds_per_state),
        "metadata": meta,
    }
    if angles is not None:
        extras["angles_deg"] = angles.tolist()
    gltf = g.GLTF2(
        asset=g.Asset(version="2.0", generator=CREATOR, extras={"curvefold": extras}),
        scene=0,
        scenes=[g.Scene(nodes=list(range(len(nodes))))],
        nodes=nodes,
        meshes=meshes,
        materials=materials,
        accessors=pk.accessors,
        bufferViews=pk.views,
        buffers=[g.Buffer(byteLength=len(pk.blob))],
        animations=animations,
    )
    gltf.set_binary_blob(bytes(pk.blob))
    return atomic_write(path, b"".join(gltf.save_to_bytes()))
