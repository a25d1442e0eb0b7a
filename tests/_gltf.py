"""Reading GLB accessors back with pygltflib's model (shared by the 3D-file tests)."""

from __future__ import annotations

import numpy as np


def accessor(gltf, blob: bytes, index: int) -> np.ndarray:
    acc = gltf.accessors[index]
    view = gltf.bufferViews[acc.bufferView]
    dtype = {5126: np.float32, 5125: np.uint32}[acc.componentType]
    width = {"SCALAR": 1, "VEC3": 3}[acc.type]
    start = (view.byteOffset or 0) + (acc.byteOffset or 0)
    data = np.frombuffer(blob, dtype=dtype, count=acc.count * width, offset=start)
    return data.reshape(acc.count, width) if width > 1 else data


def target_position(target) -> int:
    # pygltflib reads targets as dicts
    return target["POSITION"] if isinstance(target, dict) else target.POSITION


def to_gltf(coords: np.ndarray, scale: float) -> np.ndarray:
    x = np.asarray(coords) * scale
    return np.stack([x[..., 0], x[..., 2], -x[..., 1]], axis=-1)
