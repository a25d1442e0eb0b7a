"""The mechanism of a FOLD file's folded frames, as another tool or curvefold wrote them.

:func:`analyse_fold` builds the :class:`~curvefold.analysis.Framework` of a FOLD
file (against its crease pattern, or each folded form against itself when the file holds
none) and counts the degrees of freedom of every folded frame, with the rank tolerance no
finer than the file's coordinates can resolve (:func:`coordinate_precision`).
"""

from __future__ import annotations

import os
from dataclasses import replace

import numpy as np

from ..kernel._arrays import distinct
from ..kernel._errors import InputError
from ._mechanism import RESIDUAL_TOL, RTOL, Framework, Mechanism, _check_size, mechanism

__all__ = ["PRECISION_FACTOR", "analyse_fold", "coordinate_precision"]


def analyse_fold(path, *, rtol: float = RTOL, name: str | None = None) -> tuple[Mechanism, ...]:
    """The mechanism of every folded frame of a FOLD file (a path, or a ``FoldFile`` read from
    ``name``).

    With a crease pattern, every folded frame is analysed against it, and vertices that
    coincide in every folded frame are welded (:meth:`Framework.from_fold`). Without one
    (a file of folded forms, as the FOLD repository's examples and Origami Simulator's
    exports are), each frame is its own reference: its own lengths, no vertex welded (a
    folded form alone does not say which touching points are one). Join (``J``) edges keep
    their two faces coplanar.

    A frame whose coordinates are rounded (a file written with 6 decimals) breaks its
    constraints by about that rounding: the residual a consistent frame may have is
    :data:`PRECISION_FACTOR` times the coordinates' precision (:func:`coordinate_precision`,
    over the shortest edge), and the rank tolerance ``rtol · σ_max`` is raised to
    :data:`PRECISION_FACTOR` times the frame's residual, which moves the singular values of
    its motions off zero by about as much. :attr:`Mechanism.note` says when, and when a
    frame is flat-folded or has no crease pattern.

    Raises
    ------
    InputError
        For a file curvefold cannot read, one without folded frames, a folded frame of
        another topology than the reference's, an edge of no length in the reference, or
        beyond :data:`MAX_UNKNOWNS`.
    """
    from ..io._fold_reading import FoldFile, read_fold

    if not 0 < rtol < 1:
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    doc = path if isinstance(path, FoldFile) else read_fold(path)
    where = f"{name}: " if name else "" if isinstance(path, FoldFile) else f"{os.fspath(path)}: "
    if not doc.folded:
        raise InputError(
            f"{where}no folded frame to analyse (the file holds only a crease pattern)"
        )
    cp = doc.crease_pattern
    ref = cp if cp is not None else doc.folded[0][1]
    for title, mesh in doc.folded:
        if not (
            mesh.vertices_coords.shape == ref.vertices_coords.shape
            and np.array_equal(mesh.edges_vertices, ref.edges_vertices)
            and np.array_equal(mesh.faces_vertices, ref.faces_vertices)
        ):
            raise InputError(
                f"{where}frame {title!r} has other vertices, edges or faces than "
                f"the {'crease pattern' if cp is not None else 'first folded frame'}; the "
                "mechanism is analysed on frames of one topology"
            )
    advice = (
        "use fewer panels, tubes or cells"
        if "curvefold:design" in doc.keys
        else "a coarser mesh of the same model fits"
    )
    joins = np.flatnonzero(ref.edges_assignment == "J")
    spatial = [mesh for i, (_, mesh) in enumerate(doc.folded) if not doc.is_flat_folded(i)]
    facets = _facet_edges(doc, ref, spatial)
    joins = distinct(np.concatenate([joins, facets]))
    declared = bool({"curvefold:seam_partners", "curvefold:bonds"} & doc.keys)
    # the layers of a flat fold touch everywhere: they weld nothing the file does not glue
    if cp is not None and (spatial or declared):
        pairs = np.concatenate([doc.seam_partners, doc.bonds])
        framework, first = Framework.from_fold(
            cp,
            spatial or [mesh for _, mesh in doc.folded],
            joins=joins,
            glued=distinct(cp.edges_vertices[pairs]) if declared else None,
        )
        welded = len(cp.vertices_coords) - framework.points
        note = (
            ""
            if declared or not welded
            else f"{welded} vertices welded where every folded frame puts them on another"
        )
        references = [(framework, first, note)] * len(doc.folded)
    elif cp is not None:
        framework = Framework.from_mesh(
            cp.vertices_coords,
            cp.edges_vertices,
            cp.faces_vertices,
            np.arange(len(cp.vertices_coords)),
            joins=joins,
        )
        references = [
            (
                framework,
                np.arange(len(cp.vertices_coords)),
                "no vertex welded (the layers of a flat fold touch)",
            )
        ] * len(doc.folded)
    else:
        references = [
            (
                Framework.from_mesh(
                    m.vertices_coords,
                    m.edges_vertices,
                    m.faces_vertices,
                    np.arange(len(m.vertices_coords)),
                    joins=joins,
                ),
                np.arange(len(m.vertices_coords)),
                "no crease pattern: the frame's own lengths, no vertex welded",
            )
            for _, m in doc.folded
        ]
    out = []
    for i, ((title, mesh), (framework, first, note)) in enumerate(zip(doc.folded, references)):
        _check_size(framework, advice)
        _check_lengths(framework, f"{where}frame {title!r}")
        x = mesh.vertices_coords[first]
        precision = (
            max(
                coordinate_precision(m.vertices_coords)
                for m in ([mesh] if cp is None else [mesh, cp])
            )
            / framework.shortest
        )
        residual = float(np.abs(framework.residual(x) / framework.scales).max())
        notes = [note] if note else []
        if facets.size:
            notes.append(
                f"{facets.size} F edges between coplanar faces in every frame read as no hinge: "
                "their faces are one panel, as across a J edge (a triangulated panel's facets)"
            )
        if doc.is_flat_folded(i):
            notes.append(
                "flat-folded: every lift of its layers that keeps the panels planar "
                "counts, to first order"
            )
        tol = max(rtol, PRECISION_FACTOR * residual)
        if tol > rtol and tol < 1:
            notes.append(
                f"rank tolerance raised to {tol:.1e} σ_max, {PRECISION_FACTOR:g} × the "
                f"frame's residual (its coordinates are given to {precision:.1e} of the "
                "shortest edge)"
            )
        m = mechanism(
            framework,
            x,
            rtol=tol if tol < 1 else rtol,
            label=title,
            residual_tol=max(RESIDUAL_TOL, PRECISION_FACTOR * precision),
        )
        out.append(replace(m, note="; ".join(notes)))
    return tuple(out)


#: How many times the coordinates' precision (over the shortest edge) the rank tolerance and
#: a consistent residual are at least: a coordinate error δ moves a singular value by about
#: δ / ℓ times the few constraints a vertex is in.
PRECISION_FACTOR = 100.0


def coordinate_precision(coords: np.ndarray) -> float:
    """The rounding of coordinates as written, in model units, read off their digits: half the
    step of the fewest decimals that give every one of them back, or of single precision
    (float32) if they all are, else of double precision.

    A dyadic fraction of few digits (an integer, a half, a quarter, … 1/1024: a drawn grid) is
    exact as written, not rounded: such coordinates say nothing of the precision, and a file
    of them alone is exact (its rounding is double precision's).

    Examples
    --------
    >>> coordinate_precision(np.array([[0.25, 0.466968, -0.124197]]))
    5e-07
    >>> coordinate_precision(np.array([[1 / 3, 0.0, 0.0]])) < 1e-16
    True
    >>> coordinate_precision(np.array([[0.5, 0.25, 2.0]])) < 1e-15  # exact, not 0.005
    True
    """
    x = np.asarray(coords, float).ravel()
    scale = float(np.abs(x).max()) if x.size else 0.0
    if scale == 0:
        return 0.0
    ulp = float(np.spacing(scale))
    x = x[x * 1024 != np.round(x * 1024)]  # the dyadic fractions are exact
    if not x.size:
        return ulp
    single = np.array_equal(x.astype(np.float32).astype(float), x)
    # single precision's values need 8 or more decimals: they are read as single precision
    for d in range(0, 8 if single else 16):
        if np.all(np.abs(np.round(x, d) - x) <= 4 * np.spacing(np.abs(x))):
            return max(0.5 * 10.0**-d, ulp)
    if single:
        return max(float(np.spacing(np.float32(scale))) / 2, ulp)
    return ulp


#: Largest dihedral angle, in degrees, across an F edge whose faces are one panel; at least
#: :data:`PRECISION_FACTOR` times the angle the coordinates' rounding can make.
FACET_ANGLE = 1e-6


def _facet_edges(doc, ref, spatial) -> np.ndarray:
    """The F edges of a file without curvefold's edge kinds whose two faces are coplanar in
    every folded frame that is not flat-folded: the facet edges of triangulated panels (as
    Origami Simulator writes a sheet), not hinges."""
    from ..geometry._mesh import edges_faces
    from ..geometry._mesh import fold_angles as dihedral_angles

    if not spatial or "edges_curvefold:kind" in doc.keys:
        return np.zeros(0, np.int64)
    edges = np.flatnonzero(ref.edges_assignment == "F")
    sides = edges_faces(ref.faces_vertices, ref.edges_vertices[edges])
    edges = edges[(sides >= 0).all(axis=1)]
    for mesh in spatial:
        if not edges.size:
            break
        x = mesh.vertices_coords
        shortest = float(mesh.edge_lengths().min()) if len(mesh.edges_vertices) else 1.0
        rounding = np.degrees(PRECISION_FACTOR * coordinate_precision(x) / max(shortest, 1e-300))
        angle = dihedral_angles(x, mesh.faces_vertices, mesh.edges_vertices[edges])
        edges = edges[np.abs(angle) <= max(FACET_ANGLE, rounding)]
    return edges.astype(np.int64)


def _check_lengths(framework: Framework, where: str) -> None:
    """Every bar and quad of the reference has a length: a zero one makes the rows undefined."""
    bad = np.flatnonzero(~(framework.lengths > 0))
    if bad.size:
        raise InputError(
            f"{where}: vertices {framework.bars[bad[0]].tolist()} coincide in the "
            "reference (an edge or diagonal of length 0): the mechanism of a degenerate panel "
            "is not defined"
        )
    bad = np.flatnonzero(~(framework.diagonals > 0))
    if bad.size:
        raise InputError(
            f"{where}: the polygon of vertices {framework.quads[bad[0]].tolist()} "
            "has a diagonal of length 0 in the reference"
        )
