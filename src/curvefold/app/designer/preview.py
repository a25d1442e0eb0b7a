"""What the designer's page shows first after a change: the numbers, the folding motion for
the 3D view with the span and rise drawn as dimensions, the first contact, and a coarse
sketch of the crease pattern.

Lengths are in model units, which the 3D files write as metres (:data:`curvefold.io._tables.UNITS`):
the page says metres. The motion is built at :data:`MOTION_SAMPLES` (the numbers at the
design's own samples), the sketch at :data:`~curvefold.app.designer.api.COARSE_SAMPLES`.
"""

from __future__ import annotations

import base64
import html
import json
import re
import secrets
from functools import lru_cache
from urllib.parse import urlencode

import numpy as np

from ...figures._report import QUANTITIES, UNITS_SHOWN
from ...geometry._structure import drawable
from ...geometry._topology import tube_strips
from ...io._tables import COLOURS
from ...kernel._arrays import distinct
from ...kernel._errors import InputError
from .._build import Built, BuiltStructure, BuiltVault
from .._design import Design
from .api import COARSE_SAMPLES, _design, _key, built, built_structure, design_query, resolve

__all__ = [
    "PREVIEW_SEGMENTS",
    "PREVIEW_CELLS",
    "MOTION_SAMPLES",
    "MOTION_STEP",
    "MAX_FOLD",
    "preview",
    "contact",
    "pattern_sketch",
    "caches",
]

#: Segments drawn along each crease in the 3D preview, and cells drawn at most.
PREVIEW_SEGMENTS, PREVIEW_CELLS = 40, 60
#: Samples along curve 1 of the preview's motion: one per drawn vertex, so that no state is folded
#: at samples it does not draw (odd, so a vault's apex is a sample; every 20th of the default 801).
MOTION_SAMPLES = PREVIEW_SEGMENTS + 1
#: Fold-angle step between the precomputed states of the 3D preview, degrees.
MOTION_STEP = 5.0
#: Largest fold angle of the preview's states, degrees (where the first-contact search of a vault
#: stops).
MAX_FOLD = 179.0


def _b64(array: np.ndarray, dtype) -> bytes:
    """The array's bytes in base64, as bytes: :func:`_json` writes them as a JSON string."""
    return base64.b64encode(np.ascontiguousarray(array, dtype=dtype).tobytes())


def _json(answer: dict) -> bytes:
    """``answer`` as JSON bytes, its bytes values (base64) written as strings and NumPy numbers as
    floats.

    Base64 has nothing JSON escapes, so each is spliced in after encoding rather than scanned
    by the encoder (about 200 MB/s: 3.4 ms for a vault's positions)."""
    token, blobs = secrets.token_hex(16), []

    def placeholder(value):
        if isinstance(value, bytes):
            blobs.append(value)
            return f"{token}{len(blobs) - 1}"
        return float(value)

    parts = re.split(
        f'"{token}(\\d+)"'.encode(),
        json.dumps(answer, default=placeholder, allow_nan=False).encode(),
    )
    parts[1::2] = [b'"' + blobs[int(i)] + b'"' for i in parts[1::2]]
    return b"".join(parts)


def _mesh(curves: np.ndarray, strips: np.ndarray, kinds: tuple[str, ...]) -> dict:
    """Triangles of the strips and line segments of each crease kind on curves (A, M, k, 3)."""
    k = curves.shape[-2]
    i = np.arange(k - 1)
    a0, b0 = strips[:, :1] * k + i, strips[:, 1:] * k + i
    triangles = np.stack([a0, a0 + 1, b0 + 1, a0, b0 + 1, b0], axis=-1).reshape(-1, 3)
    lines = {}
    for kind in dict.fromkeys(kinds):
        rows = np.flatnonzero(np.asarray(kinds) == kind)[:, None] * k + i
        lines[kind] = _b64(np.stack([rows, rows + 1], axis=-1).reshape(-1, 2), np.uint32)
    ends = np.array([0, k - 1])
    rims = np.stack([strips[:, :1] * k + ends, strips[:, 1:] * k + ends], axis=-1).reshape(-1, 2)
    lines["rim"] = _b64(rims, np.uint32)
    flat = curves.reshape(len(curves), -1, 3)
    return {
        "states": len(curves),
        "vertices": flat.shape[1],
        "positions": _b64(flat, np.float32),
        "triangles": _b64(triangles, np.uint32),
        "lines": lines,
    }


def _motion(found: Built) -> dict:
    """The folding motion from flat through the design angle to 179° (a vault: :func:`contact`
    then says where it stops) or halfway to 180° (a tube or block): precomputed states the
    browser morphs between."""
    if not isinstance(found, BuiltStructure):  # a single curved fold: its two surfaces, one state
        crease = found.crease
        limits = [float(np.min(w)) for w in crease.regression_limits()]
        left, right = (min(0.15 * crease.curve.length, 0.6 * lim) for lim in limits)
        widths = (left, right)
        surface = crease.surface("L+R+", width=widths, rulings=2)
        idx = distinct(np.linspace(0, len(crease.s) - 1, PREVIEW_SEGMENTS + 1).round().astype(int))
        curves = np.stack([surface[0, 0], surface[0, 1], surface[1, 1]])[:, idx][None]
        angle = float(np.degrees(2 * crease.alpha(crease.s[:1])[0]))
        return {
            "angles": [angle],
            "design_angle": angle,
            "end": "the design",
            "ground": False,
            "lift_off": None,
            **_mesh(curves, np.array([[0, 1], [0, 2]]), ("fold", "edge", "edge")),
        }
    structure = found.structure
    design_angle = float(structure.lattice.crease.fold_angle)
    grounded = found.design.design_kind.grounded
    end, reason = (
        (MAX_FOLD, "first contact")
        if grounded
        else (0.5 * (design_angle + 180.0), "halfway to 180°")
    )
    angles = distinct(
        np.concatenate(
            [
                np.linspace(0.0, design_angle, int(np.ceil(design_angle / MOTION_STEP)) + 1),
                np.linspace(
                    design_angle, end, int(np.ceil((end - design_angle) / MOTION_STEP)) + 1
                ),
            ]
        )
    )
    vertices = structure.lattice.fold_points(structure.curves_uv, angles)
    curves, cells, kinds = drawable(
        structure, vertices, segments=PREVIEW_SEGMENTS, max_cells=PREVIEW_CELLS
    )
    lift = np.abs(vertices[:, :, [0, -1], 2]).max(axis=(1, 2)) if grounded else None
    return {
        "angles": angles.tolist(),
        "design_angle": design_angle,
        "end": reason,
        "ground": grounded,
        "lift_off": None if lift is None else lift.tolist(),
        **_mesh(curves, tube_strips(cells), kinds),
    }


def _dimensions(found: Built, numbers: dict) -> dict | None:
    """A vault's span (between the feet of curve 1, on the ground) and rise (from the ground to the
    highest crease point) at the design angle, its :func:`_numbers` given: the ends of each
    dimension line, model units."""
    if not isinstance(found, BuiltVault):
        return None
    points = found.crease.curve.points
    vertices = found.vault.vertices.reshape(-1, 3)
    top = vertices[np.argmax(vertices[:, 2])]
    return {
        "span": {"from": points[0].tolist(), "to": points[-1].tolist(), "value": numbers["span"]},
        "rise": {
            "from": [float(top[0]), float(top[1]), 0.0],
            "to": top.tolist(),
            "value": numbers["rise"],
        },
    }


#: The derived numbers shown beside the 3D view, in order.
NUMBERS = ("span", "rise", "kappa0_s0", "proportion_change", "p_xz", "tubes", "max_tubes")


def _numbers(found: Built) -> dict:
    if isinstance(found, BuiltVault):
        summary = found.vault.summary()
        d = found.vault.design
        return {k: summary[k] for k in NUMBERS} | {
            "a": d.a,
            "p_xy": d.p_xy,
            "radius": d.radius,
            "width_at_feet": d.width * d.radius,
        }
    if isinstance(found, BuiltStructure):
        s = found.structure
        V = s.state().vertices.reshape(-1, 3)
        size = V.max(axis=0) - V.min(axis=0)
        return {
            "cells": len(s.cells),
            "lattice_curves": len(s.curves_uv),
            "size_x": size[0],
            "size_y": size[1],
            "size_z": size[2],
            "regression_margin": s.regression_margin,
        }
    c = found.crease
    return {
        "length": c.curve.length,
        "fold_angle_start_deg": float(np.degrees(2 * c.alpha(c.s[:1])[0])),
        "fold_angle_end_deg": float(np.degrees(2 * c.alpha(c.s[-1:])[0])),
    }


#: Words and units of the numbers as the page shows them, where they differ from the report's
#: (:data:`~curvefold.figures._report.QUANTITIES`): a plain name first, the paper's symbol as a
#: hint after it.
_PLAIN = {
    "a": ("torsion amplitude (a)", ""),
    "p_xy": ("section proportion at the feet (p_xy)", ""),
    "radius": ("radius of the arch curve (1/κ0)", "model units"),
    "width_at_feet": ("tube width at the feet (w_L(0))", "model units"),
    "lattice_curves": ("lattice curves", ""),
    "size_x": ("size along x", "model units"),
    "size_y": ("size along y", "model units"),
    "size_z": ("size along z", "model units"),
    "kappa0_s0": ("arch constant (κ0·s0, Eq. 20)", ""),
    "proportion_change": ("tube widening, feet to apex, predicted (w_R(s0/2)/w_R(0))", ""),
    "p_xz": ("section proportion at the apex (p_xz)", ""),
    "regression_margin": ("margin from regression (speed factor, Eq. 17; > 0 is free)", ""),
    "fold_angle_start_deg": ("fold angle at the start (2α)", "°"),
    "fold_angle_end_deg": ("fold angle at the end (2α)", "°"),
}


def _labels(numbers: dict) -> dict[str, list[str]]:
    """Every number's words and unit as the page shows them."""
    words = {**QUANTITIES, **_PLAIN}
    return {key: [words[key][0], UNITS_SHOWN.get(words[key][1], words[key][1])] for key in numbers}


@lru_cache(maxsize=32)
def _preview(key: str, targets: tuple) -> bytes:
    design, note = resolve(key, targets)
    numbers = _numbers(built(design))
    return _json(
        {
            "kind": design.kind,
            "design": design.to_dict(),
            "query": urlencode(design_query(design)),
            "note": note,
            "numbers": numbers,
            "labels": _labels(numbers),
            "colours": {
                kind: COLOURS.get(kind, "#3a3a3a")
                for kind in ("fold", "seam", "junction", "edge", "rim")
            },
            "dimensions": _dimensions(built(design), numbers),
            "motion": _motion(built(design, samples=MOTION_SAMPLES)),
        }
    )


def preview(design: Design, targets: tuple = ()) -> bytes:
    """The designer's answer to a design change, JSON bytes.

    ``design`` (as resolved, targets solved) and its ``query`` (URL-encoded), ``note`` (what
    a fit chose, or ""), ``numbers`` (derived quantities at the design's samples: a vault's
    span, rise, κ0·s0, proportion change, p_xz, tubes, max tubes, a, p_xy, radius and the
    tube width at the feet), ``labels`` (each number's words and unit), ``colours`` of the crease
    kinds, ``dimensions`` (a vault's span and rise lines: ``from``, ``to``, ``value``) and
    ``motion``: the fold angles of the precomputed states (degrees, flat first), the design angle,
    why the range ends, the lift-off of a vault per state (the largest ``|z|`` of its end sections,
    model units; zero at the design angle), and the mesh: ``positions`` (states × vertices × 3
    float32, base64), ``triangles`` (uint32 triples) and ``lines`` per crease kind (uint32 pairs),
    at :data:`MOTION_SAMPLES`.
    """
    return _preview(_key(design), tuple(targets))


def contact(design: Design) -> float | None:
    """The first fold angle past the design angle where parts of a vault touch (degrees, on a
    1° grid; :meth:`Vault.first_contact <curvefold.vault.Vault.first_contact>`), or None
    up to :data:`MAX_FOLD`: where the fold slider stops."""
    if not design.design_kind.grounded:
        raise InputError(f"the first contact is searched for vaults, not for a {design.kind}")
    return _contact(_key(design))


@lru_cache(maxsize=32)
def _contact(key: str) -> float | None:
    found = built(_design(key))
    if not isinstance(found, BuiltVault):
        raise InputError(f"the first contact is searched for vaults, not for a {found.design.kind}")
    return found.vault.first_contact(max_angle=MAX_FOLD)


# -- the coarse crease pattern
# ------------------------------------------------------------------------

#: Width of the sketch in SVG units (pixels at 1:1), and the gap between sheets.
_SKETCH_WIDTH, _GAP = 640.0, 12.0


def pattern_sketch(design: Design) -> str:
    """The developed sheets at :data:`~curvefold.app.designer.api.COARSE_SAMPLES`, side by side
    in one SVG (outlines, seams and folds; no glue tabs, labels or page layout): the crease
    pattern shown while the pages as they will be cut are laid out."""
    if not design.design_kind.structure:
        raise InputError(
            "a single curved fold has no sheets to lay out: crease patterns are "
            "drawn for tubes, blocks and vaults"
        )
    return _sketch(_key(design))


@lru_cache(maxsize=8)
def _sketch(key: str) -> str:
    from ...geometry._sheets import sheets

    design = _design(key)
    found = built_structure(design, samples=min(COARSE_SAMPLES, design.samples))
    drawn = [(sheet.label, sheet.mesh) for sheet in sheets(found.structure, name=design.kind)]
    boxes = [
        (m.vertices_coords[:, :2].min(axis=0), m.vertices_coords[:, :2].max(axis=0))
        for _, m in drawn
    ]
    widest = max(float((hi - lo).max()) for lo, hi in boxes)
    columns = max(1, min(len(drawn), int(np.ceil(np.sqrt(len(drawn) / 2)))))
    cell = (_SKETCH_WIDTH - _GAP * (columns + 1)) / columns
    scale = cell / widest
    rows_h = [
        max(float(hi[1] - lo[1]) for lo, hi in boxes[r : r + columns]) * scale
        for r in range(0, len(drawn), columns)
    ]
    parts, y = [], _GAP
    for r, height in enumerate(rows_h):
        for c, ((label, mesh), (lo, _hi)) in enumerate(
            zip(drawn[r * columns : (r + 1) * columns], boxes[r * columns : (r + 1) * columns])
        ):
            x0 = _GAP + c * (cell + _GAP)
            xy = (mesh.vertices_coords[:, :2] - lo) * scale
            xy[:, 1] = height - xy[:, 1]  # SVG's y runs down
            xy += [x0, y]
            for kind, width in (("boundary", 1.0), ("seam", 1.2), ("fold", 1.2)):
                edges = mesh.edges_vertices[mesh.edges_kind == kind]
                if len(edges):
                    d = "".join(
                        f"M{xy[a, 0]:.1f},{xy[a, 1]:.1f}L{xy[b, 0]:.1f},{xy[b, 1]:.1f}"
                        for a, b in edges
                    )
                    parts.append(
                        f'<path d="{d}" stroke="{COLOURS[kind]}" stroke-width="{width}" '
                        'fill="none"/>'
                    )
            parts.append(
                f'<text x="{x0:.1f}" y="{y + height + 11:.1f}" font-size="10" '
                f'fill="#555">{html.escape(label)}</text>'
            )
        y += height + 16 + _GAP
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_SKETCH_WIDTH:.0f}" '
        f'height="{y:.0f}" viewBox="0 0 {_SKETCH_WIDTH:.0f} {y:.0f}"><rect width="100%" '
        f'height="100%" fill="#fff"/>{"".join(parts)}</svg>'
    )


def caches() -> dict[str, object]:
    """This module's LRU caches by name."""
    return {"preview": _preview, "contact": _contact, "sketch": _sketch}
