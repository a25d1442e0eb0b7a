"""The tolerances a curvefold FOLD file promises: its recorded mesh tolerance and its precision.

A FOLD file curvefold writes records how its meshes were sampled (``curvefold:metadata``:
``mesh_tolerance``, the largest relative change of an edge's length between the folded and the
flat state at the design angle; ``mesh_bend_bound_deg``, the largest fold across a ruling quad's
diagonal; ``design_fold_angle_deg``) and writes its numbers to a stated precision (coordinates to
:data:`~curvefold.io._fold.COORDINATE_RTOL` of each sheet's size, fold angles to
:data:`~curvefold.io._fold.ANGLE_DECIMALS` places). :func:`promised_tolerances` turns them into
the tolerances of :func:`~curvefold.analysis.check_fold`, so that the file is held to what it
says of itself:

``isometry_tol``
    the mesh tolerance (or the recorded ``mesh_stretch``, where the computed samples were too
    coarse to reach it), scaled to the most folded frame: a chord of a crease shortens by
    (κ² − κ_2D²) h²/24 relative, and κ = κ_2D / cos α, so the stretch of a mesh sampled at the
    design angle α_d grows as tan²α / tan²α_d (never below the tolerance itself); plus the
    rounding of a ratio of two lengths, 4√3 ε over the shortest edge (ε half the written
    coordinate unit).
``planarity_tol``
    the recorded bound of a fold across a diagonal, plus the rounding of a dihedral angle.
``fold_angle_tol``
    the rounding of a written angle (half its last place) plus that of a dihedral angle
    measured from rounded coordinates: 4√3 ε over the smallest triangle height, in degrees.
``crease_angle_tol``
    twice the recorded bend bound: each triangle beside a crease tilts from the sheet's tangent
    plane by at most the fold across its diagonal.
``weld_tol``
    glued vertices are one point rounded twice: 2√3 ε over the model's size.
``rebuild_tol``
    the default 1e-9 plus 2 ε over the size: a coordinate rounded to ε against the rebuilt one.

A file without that metadata (another tool's) promises nothing: the defaults of
:data:`~curvefold.analysis._foldcheck.CHECK_SPECS` hold.
"""

from __future__ import annotations

import math

import numpy as np

from ..geometry._mesh import Mesh, vector_areas
from ..io._fold_reading import FoldFile

__all__ = ["promised_tolerances", "written_precision"]

#: The share of a file's numbers a decimal place must hold to be the place they were written to:
#: not all, since a number computed from written ones (an edge split at its midpoint) may need a
#: place more, and is as accurate as they are.
HELD = 0.9
#: The rebuilt coordinates' own agreement, relative to the size (the default ``rebuild_tol``).
REBUILD_FLOOR = 1e-9
#: The metadata a file must record for its promise to be read.
PROMISE_KEYS = ("mesh_tolerance", "mesh_bend_bound_deg", "design_fold_angle_deg")


def written_precision(values: np.ndarray) -> float:
    """Half the unit of the last place ``values`` are written to: the largest rounding error of
    one written number, read off the numbers themselves.

    Numbers written to d decimals (curvefold writes coordinates to
    :data:`~curvefold.io._fold.COORDINATE_RTOL` of the size, angles to
    :data:`~curvefold.io._fold.ANGLE_DECIMALS` places; an editor may round them further) give
    ``0.5 × 10^-d``, d the fewest decimals that hold nearly every one (:data:`HELD`); numbers
    that no decimal place holds but single precision does (float32) give its half unit at the
    largest, 2⁻²⁴ × max ``|x|``; any other, double precision's, 2⁻⁵³ × max ``|x|``.

    Examples
    --------
    >>> written_precision(np.array([[0.125, 0.5], [2.0, 1.0]]))
    0.0005
    >>> float(written_precision(np.float32([0.1, 0.7]).astype(float)) / 2.0**-24)  # float32
    0.699999988079071
    """
    x = np.asarray(values, float).ravel()
    x = x[np.isfinite(x)]
    scale = float(np.abs(x).max()) if x.size else 0.0
    if not scale > 0:
        return 0.0
    parsed = 4 * np.spacing(np.abs(x))  # a decimal read into a double is off by an ulp or two
    # a decimal place within 64 ulps of the largest number is no place it was written to
    places = [d for d in range(17) if 10.0**-d >= 64 * float(np.spacing(scale))]
    for decimals in places:
        if np.mean(np.abs(np.round(x, decimals) - x) <= parsed) >= HELD:
            return 0.5 * 10.0**-decimals
    single = (x.astype(np.float32).astype(float) == x).all()
    return (2.0**-24 if single else 2.0**-53) * scale


def _smallest_height(mesh: Mesh) -> float:
    """The smallest height of a triangle with an area (a height over 1e-9 of the mesh's size: a
    fan triangle beside a vertex on a straight side, as where an edge was split, has none),
    over the mesh's faces split into fans."""
    triangles = mesh.triangulated()
    corners = triangles.vertices_coords[triangles.faces_vertices]  # (F, 3, d)
    twice_area = np.linalg.norm(
        vector_areas(triangles.vertices_coords, triangles.faces_vertices), axis=-1
    )
    longest = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=-1).max(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        heights = twice_area / longest
    size = float(np.ptp(triangles.vertices_coords, axis=0).max()) if len(corners) else 0.0
    heights = heights[np.isfinite(heights) & (heights > 1e-9 * size)]
    return float(heights.min()) if heights.size else math.inf


def _most_folded(doc: FoldFile) -> float:
    """The largest |fold angle| of a fold crease recorded in a folded frame, degrees (0 if
    none)."""
    angles = [
        float(np.abs(mesh.edges_foldAngle[mesh.edges_kind == "fold"]).max(initial=0.0))
        for _, mesh in doc.folded
    ]
    return max(angles, default=0.0)


def promised_tolerances(doc: FoldFile) -> tuple[dict[str, float], dict[str, str]]:
    """The tolerances a curvefold FOLD file promises, and how each was derived.

    Parameters
    ----------
    doc : FoldFile
        The file as read.

    Returns
    -------
    tolerances : dict of str to float
        ``isometry_tol``, ``planarity_tol``, ``fold_angle_tol`` and ``weld_tol`` (see the module
        notes); empty for a file that records no mesh tolerance.
    sources : dict of str to str
        For each, the derivation in words with its numbers.
    """
    meta = doc.metadata
    if not all(isinstance(meta.get(key), (int, float)) for key in PROMISE_KEYS):
        return {}, {}
    meshes = ([doc.crease_pattern] if doc.crease_pattern is not None else []) + [
        m for _, m in doc.folded
    ]
    eps = max(written_precision(m.vertices_coords) for m in meshes)
    last_place = max(written_precision(m.edges_foldAngle) for m in meshes)
    size = max(float(np.ptp(m.vertices_coords, axis=0).max()) for m in meshes)
    shortest = float(meshes[0].edge_lengths().min())
    height = _smallest_height(meshes[0])
    design = math.radians(float(meta["design_fold_angle_deg"])) / 2
    most = math.radians(min(_most_folded(doc), 179.999)) / 2
    growth = max(1.0, math.tan(most) ** 2 / math.tan(design) ** 2)
    # a design sampled too coarsely for the tolerance records the stretch it reached instead
    stretch = meta.get("mesh_stretch")
    reached = float(stretch) if isinstance(stretch, (int, float)) else 0.0
    tolerance_asked = float(meta["mesh_tolerance"])
    tolerance = max(tolerance_asked, reached)
    length_rounding = 4 * math.sqrt(3) * eps / shortest
    angle_rounding = math.degrees(4 * math.sqrt(3) * eps / height)
    tolerances = {
        "isometry_tol": tolerance * growth + length_rounding,
        "planarity_tol": float(meta["mesh_bend_bound_deg"]) + angle_rounding,
        "fold_angle_tol": last_place + angle_rounding,
        "crease_angle_tol": 2 * float(meta["mesh_bend_bound_deg"]) + angle_rounding,
        "weld_tol": 2 * math.sqrt(3) * eps / size,
        "rebuild_tol": REBUILD_FLOOR + 2 * eps / size,
    }
    sources = {
        "isometry_tol": f"{'mesh_stretch' if reached > tolerance_asked else 'mesh_tolerance'} "
        f"{tolerance:.3g} × tan²α/tan²α_d = {growth:.4g} (2α up "
        f"to {math.degrees(2 * most):.4g}°, designed at {math.degrees(2 * design):.4g}°) + "
        f"4√3 ε / shortest edge = {length_rounding:.2g} (ε = {eps:.2g}, half the last written "
        "place of a coordinate)",
        "planarity_tol": f"mesh_bend_bound_deg {float(meta['mesh_bend_bound_deg']):g}° + "
        f"4√3 ε / smallest triangle height = {angle_rounding:.2g}°",
        "fold_angle_tol": f"half the last written place of an angle ({last_place:.2g}°) + "
        f"4√3 ε / smallest triangle height ({height:.3g}) = {angle_rounding:.2g}°",
        "weld_tol": f"2√3 ε / size = {tolerances['weld_tol']:.2g}",
        "rebuild_tol": f"{REBUILD_FLOOR:g} + 2 ε / size = {tolerances['rebuild_tol']:.2g}",
        "crease_angle_tol": f"2 × mesh_bend_bound_deg {float(meta['mesh_bend_bound_deg']):g}° "
        "(each triangle beside a crease tilts from the sheet by at most the fold across its "
        f"diagonal) + {angle_rounding:.2g}°",
    }
    return tolerances, sources
