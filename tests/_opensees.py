"""An independent finite-element model of a panel structure in OpenSees: shells for the panels,
springs for the creases.

Every panel (a planar quad of the structure's mesh; for a smooth structure a ruling quad) is
meshed by m × m shells (ASDShellQ4, ElasticMembranePlateSection: E, ν, t, ρ) on its own
nodes, or by m across (between its curves) × n along (``refine=(m, n)``). Where two panels
share an edge of the mesh (a crease, a seam, a fold line) the coincident nodes of the two
panels share their translations (equalDOF) and are joined by a zeroLength element whose
rotation about the edge is a spring of the crease stiffness times the node's share of
the edge, and whose other two rotations are stiff (the sheet is continuous across the
crease: it only turns about it). Across a ruling of a smooth structure (an edge between
ruling quads) the sheet is continuous: the three rotations are stiff, but for the ruling's
two ends, on the creases, where four quads meet and a crease turns about the tangents of its
two segments on either side: tied there, the rotations would lock the folding of a curved
crease (its segments' tangents differ). So one shell across a ruling quad leaves the
rulings hinged, and m across ties m − 1 nodes of each ruling. Panels of two tubes
bonded along a crease share the translations of their nodes only, as in the bar-and-hinge
model. Nothing here is taken
from curvefold.mechanics but the geometry (the state's mesh) and the material.

Refined along (n > 1), the shells' folding mode stiffens: at every crease vertex the quads
of a strip on either side of the ruling are left untied (above), a point where the sheet's
rotation jumps by the crease's turn between its two segments, and the plate energy of such a
jump grows as the mesh around the point is refined. Measured on the tube: ω₁² rises by
3.4 % from 8 × 1 to 8 × 2 on 81 samples, by 32 % from 2 × 1 to 2 × 2 on 21 (the turn per
segment grows as the samples fall), by 66 % and 26 % from 4 × 1 to 4 × 2 on the paper's
vault and the cellular block on 21; the deflection and the supported ω₁², which fold the
creases less, move by 1 % on the tube and the vault, 10 % on the block. The bar-and-hinge
model has one element between two samples along the strips, as n = 1: the comparison is
made there, and the move along is reported.

Co-rotational (:func:`load_path`, large displacements): the shells turn with their nodes but a
zeroLength keeps the axes it was built with, so a crease's two stiff rotations, about axes
that no longer lie across it, would resist its fold by the stiff spring times the square of
the angle it has turned through. A crease there has its spring about its axis alone (the
shared translations of its nodes tie the rest): the small vault's linear deflection moves by
0.7 % and agrees with the bar-and-hinge model to 7e-4, against 8e-3 with the stiff ties,
whose path stiffened well past the bar-and-hinge model's. A ruling's ties, stiff about
every axis, do not depend on the axes.

Supports: the feet (every shell node on z = 0: a vault's end sections) or the ends (every
shell node on a first or last ruling of a tube: a tube or block held at both ends), pinned.

Free eigenvalues: OpenSees's ARPACK needs a stiffness it can factorise, so six soft springs
hold the rigid motions, six eigenvalues about 1e-6 of the elastic ones. On such a spectrum
ARPACK, asked for two elastic values (eight in all), now and then returns a ghost: on the
81-sample tube, 8 × 4 shells, after twenty solves in one process, 0.011 rad²/s² (the sixth
soft value's, 0.0110, again) and 9803 for the elastic 996 and 11548; alone in a process the
same model gives the clean values. The start vector is random and runs on from one solve
to the next. :func:`free_eigenvalues` asks for four more, checks
that exactly six sit below the gap and that no two elastic ones coincide, and solves
again if not.
"""

from __future__ import annotations

import numpy as np

from curvefold.mechanics import StructureModel

#: Rotational stiffness of the zeroLength springs about the axes across a crease, per D: stiff
#: enough that the results move by 1e-5 between 1e4 and 1e5 (measured on the panel tube; 6e-5 from
#: 1e3).
RIGID = 1e4
#: The shell element.
SHELL = "ASDShellQ4"
#: Extra eigenvalues asked of ARPACK beyond the soft six and those wanted (module notes).
SPARE = 4


def opensees_model(
    sm: StructureModel,
    refine: int | tuple[int, int],
    *,
    shift: np.ndarray | None = None,
    corotational: bool = False,
):
    """Build the OpenSees model of a structure's state, each quad meshed by ``refine`` (m, or m
    across × n along); return the node tags at the model's nodes and the total mass.

    ``shift`` (P, 3) moves the model's nodes (an imperfection): a shell node on a model node
    moves by its shift, any other by the bilinear blend of its quad's corners'; the springs
    keep the axes and the weights the areas of the shape unshifted. ``corotational`` builds
    the shells with ASDShellQ4's co-rotational kinematics (large rotations).

    Returns
    -------
    at_node : (P,) ndarray of int
        An OpenSees node (the master of its coincident group) at every node of ``sm.model``.
    loads : dict of int to float
        Nodal weight (N) of every OpenSees node, lumped from its elements (a quarter each).
    ends : (E,) ndarray of int
        The OpenSees nodes on the first and last rulings of every tube (the end sections).
    """
    import openseespy.opensees as ops
    from scipy.spatial import cKDTree

    state = sm.state
    topology = state.structure.topology("quads")
    mesh = topology.mesh(state.vertices)
    x = mesh.vertices_coords
    curve = topology.vertex_curve
    sample = topology.vertex_sample
    last = state.vertices.shape[1] - 1
    faces = np.asarray(mesh.faces_vertices)
    # every quad from a corner whose next one is on its curve: side 0-1 along, 1-2 across
    along_first = curve[faces[:, 0]] == curve[faces[:, 1]]
    faces = np.where(along_first[:, None], faces, np.roll(faces, -1, axis=1))
    mat = sm.material
    t = sm.model.thickness
    D = mat.bending_stiffness(t)
    mv, mu = (int(refine), int(refine)) if np.ndim(refine) == 0 else map(int, refine)
    ku, kv = mu + 1, mv + 1
    per_face = ku * kv

    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.section("ElasticMembranePlateSection", 1, mat.youngs_modulus, mat.poisson, t, mat.density)
    ops.uniaxialMaterial("Elastic", 1, RIGID * D)
    if shift is not None:
        shift = np.asarray(shift, float).reshape(-1, 3)
        corner = shift[_nearest(sm.model.nodes, x)]
        tree, tol = cKDTree(sm.model.nodes), 1e-9 * sm.model.size
    coords = {}
    for f, (a, b, c, d) in enumerate(faces):
        for i, u in enumerate(np.linspace(0.0, 1.0, ku)):
            for j, v in enumerate(np.linspace(0.0, 1.0, kv)):
                w = np.array([(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v])
                p = w @ x[[a, b, c, d]]
                tag = 1 + f * per_face + i * kv + j
                at = p
                if shift is not None:
                    gap, near = tree.query(p)
                    at = p + (shift[near] if gap <= tol else w @ corner[[a, b, c, d]])
                ops.node(tag, *at.tolist())
                coords[tag] = p
    element = 1
    weight = {}
    g = 9.80665
    for f in range(len(faces)):
        for i in range(mu):
            for j in range(mv):
                n = [
                    1 + f * per_face + (i + di) * kv + (j + dj)
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1))
                ]
                ops.element(SHELL, element, *n, 1, *(["-corotational"] if corotational else []))
                element += 1
                p = np.array([coords[q] for q in n])
                area = 0.5 * (
                    np.linalg.norm(np.cross(p[1] - p[0], p[2] - p[0]))
                    + np.linalg.norm(np.cross(p[2] - p[0], p[3] - p[0]))
                )
                for q in n:
                    weight[q] = weight.get(q, 0.0) + mat.density * t * area * g / 4
    # coincident nodes share their translations
    tags = np.array(sorted(coords))
    pos = np.array([coords[q] for q in tags])
    size = float(np.ptp(pos, axis=0).max())
    key = np.round(pos / (1e-7 * size)).astype(np.int64)
    _, first, group = np.unique(key, axis=0, return_index=True, return_inverse=True)
    masters = tags[first][group.ravel()]
    for q, master in zip(tags, masters):
        if q != master:
            ops.equalDOF(int(master), int(q), 1, 2, 3)
    # crease springs between the panels on either side of every hinged edge
    sides = {}
    for f, quad in enumerate(faces):
        for c in range(4):
            a, b = int(quad[c]), int(quad[(c + 1) % 4])
            sides.setdefault((min(a, b), max(a, b)), []).append((f, c))
    kind_of = {
        tuple(sorted(e)): kind
        for e, kind in zip(mesh.edges_vertices.tolist(), mesh.edges_kind.tolist())
    }
    material = 2
    for edge, where in sides.items():
        kind = kind_of.get(edge)
        if len(where) != 2 or kind == "boundary":
            continue
        crease = kind in ("fold", "seam")
        a, b = x[edge[0]], x[edge[1]]
        length = float(np.linalg.norm(b - a))
        axis = (b - a) / length
        (f1, c1), (f2, c2) = where
        normal = np.cross(x[faces[f1][1]] - x[faces[f1][0]], x[faces[f1][3]] - x[faces[f1][0]])
        across = np.cross(normal, axis)
        across /= np.linalg.norm(across)
        nodes1, nodes2 = _side_nodes(f1, c1, ku, kv), _side_nodes(f2, c2, ku, kv)
        m = len(nodes1) - 1
        for q1 in nodes1:
            q2 = min(nodes2, key=lambda q: np.linalg.norm(coords[q] - coords[q1]))
            along = (coords[q1] - a) @ axis / length
            end = min(along, 1 - along) < 0.25 / m
            if not crease and end:
                continue  # a ruling's ends, on the creases: see the module notes
            share = length / m * (0.5 if end else 1.0)
            # a crease turns about itself; the sheet is continuous across a ruling
            turn = sm.crease_stiffness * share if crease else RIGID * D
            ops.uniaxialMaterial("Elastic", material, turn)
            # co-rotational: a crease's spring alone (module notes: fixed axes would turn its
            # stiff ties onto its fold)
            only = crease and corotational
            ops.element(
                "zeroLength",
                element,
                int(q1),
                int(q2),
                "-mat",
                *([material] if only else [material, 1, 1]),
                "-dir",
                *([4] if only else [4, 5, 6]),
                "-orient",
                *axis.tolist(),
                *across.tolist(),
            )
            element += 1
            material += 1
    # the end sections: the sides 1-2 and 3-0 (across) of quads whose corners there are on
    # the first or last sample
    ends = set()
    for f, quad in enumerate(faces):
        for c in (1, 3):
            s0, s1 = sample[quad[c]], sample[quad[(c + 1) % 4]]
            if s0 == s1 and s0 in (0, last):
                ends.update(_side_nodes(f, c, ku, kv))
    nearest = _nearest(pos, sm.model.nodes)
    end_tags = np.array(sorted(ends))
    return (
        masters[nearest],
        {int(q): w for q, w in weight.items()},
        end_tags,
    )


def _side_nodes(face: int, corner: int, ku: int, kv: int) -> list[int]:
    """The tags of a face's grid nodes (ku along × kv across) along its side from corner
    ``corner`` to the next."""
    ij = {
        0: [(i, 0) for i in range(ku)],
        1: [(ku - 1, j) for j in range(kv)],
        2: [(i, kv - 1) for i in range(ku - 1, -1, -1)],
        3: [(0, j) for j in range(kv - 1, -1, -1)],
    }[corner]
    return [1 + face * ku * kv + i * kv + j for i, j in ij]


def _nearest(points: np.ndarray, targets: np.ndarray) -> np.ndarray:
    from scipy.spatial import cKDTree

    return cKDTree(points).query(targets)[1]


def _pin(sm: StructureModel, ends: np.ndarray, at: str) -> None:
    """Pin the supported shell nodes: the feet (every node on z = 0) or the end sections."""
    import openseespy.opensees as ops

    if at == "feet":
        size = sm.model.size
        held = [q for q in ops.getNodeTags() if abs(ops.nodeCoord(q, 3)) <= 1e-9 * size]
    elif at == "ends":
        held = ends.tolist()
    else:
        raise ValueError(f"at must be feet or ends, got {at!r}")
    for q in held:
        ops.fix(int(q), 1, 1, 1, 0, 0, 0)


def static_deflection(
    sm: StructureModel, refine: int | tuple[int, int], at: str = "feet", *, every: bool = False
) -> np.ndarray:
    """Displacements (P, 3) of the model's nodes under self-weight, the supports pinned, m;
    of every shell node with ``every``.

    The feet are the end sections on the ground: every shell node on z = 0 is pinned, the
    edges between the model's feet with them (in the bar-and-hinge model those edges are
    bars between pinned nodes); the ends, every shell node of the end sections.
    """
    import openseespy.opensees as ops

    at_node, weight, ends = opensees_model(sm, refine)
    _pin(sm, ends, at)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for q, w in weight.items():
        ops.load(q, 0.0, 0.0, -w, 0.0, 0.0, 0.0)
    ops.system("UmfPack")
    ops.numberer("RCM")
    ops.constraints("Transformation")
    ops.integrator("LoadControl", 1.0)
    ops.algorithm("Linear")
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees static analysis failed")
    nodes = ops.getNodeTags() if every else at_node
    u = np.array([ops.nodeDisp(int(q))[:3] for q in nodes])
    ops.wipe()
    return u


def free_eigenvalues(
    sm: StructureModel, refine: int | tuple[int, int], count: int, ground: np.ndarray, spring: float
) -> np.ndarray:
    """The lowest ``count`` elastic ω² (rad²/s²) of the free structure.

    The six rigid motions are held by soft springs of stiffness ``spring`` (N/m) at the
    DOFs ``ground`` ((6, 2): node of the model, axis), so that OpenSees's ARPACK can
    factorise; they appear as six eigenvalues far below the elastic ones and are dropped
    (module notes: ARPACK's ghosts are caught and solved again, up to three times).
    """
    import openseespy.opensees as ops

    at_node, _, _ = opensees_model(sm, refine)
    tag = 10_000_000
    ops.uniaxialMaterial("Elastic", 9_999_999, spring)
    for node, axis in ground:
        q = int(at_node[node])
        ops.node(tag, *ops.nodeCoord(q))
        ops.fix(tag, 1, 1, 1, 1, 1, 1)
        ops.element("zeroLength", tag, tag, q, "-mat", 9_999_999, "-dir", int(axis) + 1)
        tag += 1
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    for _ in range(3):
        values = np.sort(np.array(ops.eigen("-genBandArpack", count + 6 + SPARE)))
        if _clean(values):
            break
    else:
        ops.wipe()
        raise RuntimeError(f"ARPACK gives no clean spectrum: {values[:8]}")
    ops.wipe()
    return values[6 : 6 + count]


def _clean(values: np.ndarray) -> bool:
    """Six soft values 1e3 below the elastic ones, and no two elastic ones within 1e-7 of each
    other (a ghost: the soft springs are a millionth of the folding mode's stiffness)."""
    soft, elastic = values[:6], values[6:]
    return bool(soft.max() < 1e-3 * elastic.min() and np.all(np.diff(elastic) > 1e-7 * elastic[1:]))


def supported_eigenvalues(
    sm: StructureModel, refine: int | tuple[int, int], count: int, at: str = "feet"
) -> np.ndarray:
    """The lowest ``count`` ω² (rad²/s²) of the structure on its supports, pinned as in
    :func:`static_deflection` (no soft springs: the stiffness is regular)."""
    import openseespy.opensees as ops

    _, _, ends = opensees_model(sm, refine)
    _pin(sm, ends, at)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    values = np.sort(np.array(ops.eigen("-genBandArpack", count + SPARE)))
    ops.wipe()
    return values[:count]


def load_path(
    sm: StructureModel,
    refine: int | tuple[int, int],
    *,
    shift: np.ndarray,
    factor: float,
    control: int,
    increment: float,
    steps: int,
    at: str = "feet",
) -> tuple[np.ndarray, np.ndarray, float]:
    """The co-rotational shells' load path under λ × ``factor`` × self-weight, the shape moved by
    ``shift`` (P, 3), the supports pinned as in :func:`static_deflection`, by displacement
    control of the model's DOF ``control`` (3 node + axis) in ``steps`` steps of
    ``increment`` (m, signed).

    Returns
    -------
    factors, displacements : (n,) ndarray
        λ and the control DOF's displacement (m) of the states reached, from the unloaded one;
        the path stops at the first step Newton's method does not converge on, even split
        in eight.
    linear : float
        The control DOF's linear displacement per unit λ (one linear solve about the shifted
        shape).
    """
    import openseespy.opensees as ops

    node, axis = divmod(int(control), 3)

    def build() -> int:
        at_node, weight, ends = opensees_model(sm, refine, shift=shift, corotational=True)
        _pin(sm, ends, at)
        ops.timeSeries("Linear", 1)
        ops.pattern("Plain", 1, 1)
        for q, w in weight.items():
            ops.load(q, 0.0, 0.0, -factor * w, 0.0, 0.0, 0.0)
        ops.system("UmfPack")
        ops.numberer("RCM")
        ops.constraints("Transformation")
        return int(at_node[node])

    q = build()
    ops.integrator("LoadControl", 1.0)
    ops.algorithm("Linear")
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees linear analysis failed")
    linear = float(ops.nodeDisp(q, axis + 1))
    q = build()
    # a displacement increment's tenth of a micrometre: rounding of the shells' rotations
    # stalls Newton's method near 1e-8 m
    ops.test("NormDispIncr", 1e-7 * sm.model.size, 40)
    ops.algorithm("KrylovNewton")
    ops.integrator("DisplacementControl", q, axis + 1, float(increment))
    ops.analysis("Static")
    factors, displacements = [0.0], [0.0]
    for _ in range(int(steps)):
        for split in (1, 2, 4, 8):  # a step that fails is tried again in smaller ones
            ops.integrator("DisplacementControl", q, axis + 1, float(increment) / split)
            if all(ops.analyze(1) == 0 for _ in range(split)):
                break
        else:
            break
        factors.append(float(ops.getLoadFactor(1)))
        displacements.append(float(ops.nodeDisp(q, axis + 1)))
    ops.wipe()
    return np.array(factors), np.array(displacements), linear
