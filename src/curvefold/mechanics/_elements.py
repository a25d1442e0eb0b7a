"""The elements of a bar-and-hinge model: bars, membrane triangles and hinges, as pure array
functions.

A bar measures the length change of a node pair, a hinge the change of a dihedral angle,
both to first order: their rows of the compatibility matrix. Every function takes the
positions of the element's nodes, batched over the leading axis, and is safe for complex
input, so that a complex step of the gradient gives the exact Hessian (the geometric
stiffness of a hinge carrying a moment).

Dihedral angle of a hinge (i, j, k, l): the edge runs from node i to node j, node k is the
third node of face A = (i, j, k) and l that of face B = (j, i, l). With e = x_j − x_i,
n_A = e × (x_k − x_i) and n_B = (x_l − x_i) × e, the angle is

    θ = atan2((n_A × n_B) · e / |e|, n_A · n_B),

0 when the faces are coplanar (the sheet flat across the edge), ±π when they fold onto
each other. Its gradient (Liu and Paulino 2017 give the same expressions in their notation):
∂θ/∂x_k = −|e| n_A / |n_A|², ∂θ/∂x_l = −|e| n_B / |n_B|², and for the edge's nodes the
combinations that make it invariant under rigid motions,
∂θ/∂x_i = −(1 − a) ∂θ/∂x_k − (1 − b) ∂θ/∂x_l, ∂θ/∂x_j = −a ∂θ/∂x_k − b ∂θ/∂x_l, where a and b
are the positions along e of the feet of the wings (a = (x_k − x_i)·e / |e|²).

Membrane triangle (the constant-strain triangle written in its bars' elongations): a
uniform in-plane strain ε (Voigt, engineering shear) stretches edge m of length ℓ_m and
unit direction n_m by δ_m = ℓ_m n_mᵀ ε n_m. The three elongations determine ε, ε = G δ,
so the plane-stress energy ½ t A εᵀ D ε is a quadratic form in the elongations with the
3 × 3 matrix t A Gᵀ D G: the exact membrane stiffness of the triangle, carried by its
three bars. (Filipov et al. 2017 fit one stiffness per bar instead, which needs panels of
moderate aspect ratio; a ruling strip sampled finely has triangles ten times longer than
wide, where a per-bar fit cannot hold the Poisson effect and shear.)
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "bar_rows",
    "face_bars",
    "face_membranes",
    "dihedral_angle",
    "dihedral_gradient",
    "dihedral_hessian",
    "dihedral_hessian_complex",
    "dihedral_hessian_action",
    "plane_stress",
    "triangle_strain",
    "quad_frame",
    "quad_membrane",
    "membrane_geometric",
    "triangle_areas",
]

#: Step of the complex-step derivative, relative to the element's size (exact to rounding
#: for analytic functions: no subtraction, so any small step will do).
COMPLEX_STEP = 1e-30


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (a * b).sum(axis=-1)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.stack(
        [
            a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
            a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
            a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0],
        ],
        axis=-1,
    )


def bar_rows(x: np.ndarray) -> np.ndarray:
    """First-order length change of bars (B, 2, 3) per unit nodal displacement, shape (B, 2, 3).

    Row ``(−ê, ê)``: the bar's unit vector at its second node, its opposite at the first.

    Examples
    --------
    >>> bar_rows(np.array([[[0.0, 0, 0], [2.0, 0, 0]]])).tolist()
    [[[-1.0, -0.0, -0.0], [1.0, 0.0, 0.0]]]
    """
    d = x[..., 1, :] - x[..., 0, :]
    e = d / np.sqrt(_dot(d, d))[..., None]
    return np.stack([-e, e], axis=-2)


def dihedral_angle(x: np.ndarray) -> np.ndarray:
    """The dihedral angle θ of hinges (H, 4, 3) (nodes i, j, k, l; module notes), radians, shape
    (H,).

    Examples
    --------
    A square folded by 90° about its diagonal:

    >>> x = np.array([[[0.0, 0, 0], [1, 1, 0], [1, 0, 0], [0.5, 0.5, -(2**-0.5)]]])
    >>> round(float(abs(dihedral_angle(x)[0])), 12) == round(np.pi / 2, 12)
    True
    """
    x = np.asarray(x, float)
    e = x[..., 1, :] - x[..., 0, :]
    na = _cross(e, x[..., 2, :] - x[..., 0, :])
    nb = _cross(x[..., 3, :] - x[..., 0, :], e)
    sine = _dot(_cross(na, nb), e) / np.linalg.norm(e, axis=-1)
    return np.arctan2(sine, _dot(na, nb))


def dihedral_gradient(x: np.ndarray) -> np.ndarray:
    """∂θ/∂x of hinges (H, 4, 3): the hinge's compatibility row, shape (H, 4, 3), 1/m.

    Analytic in x (no absolute values), so complex steps of it are exact.
    """
    e = x[..., 1, :] - x[..., 0, :]
    a = x[..., 2, :] - x[..., 0, :]
    b = x[..., 3, :] - x[..., 0, :]
    na, nb = _cross(e, a), _cross(b, e)
    ee = _dot(e, e)
    length = np.sqrt(ee)
    gk = -(length / _dot(na, na))[..., None] * na
    gl = -(length / _dot(nb, nb))[..., None] * nb
    fa, fb = (_dot(a, e) / ee)[..., None], (_dot(b, e) / ee)[..., None]
    gi = -(1 - fa) * gk - (1 - fb) * gl
    gj = -fa * gk - fb * gl
    return np.stack([gi, gj, gk, gl], axis=-2)


def dihedral_hessian(x: np.ndarray) -> np.ndarray:
    """∂²θ/∂x² of hinges (H, 4, 3), shape (H, 12, 12), 1/m², analytic, vectorised over hinges.

    The derivatives of :func:`dihedral_gradient`'s g_j, g_k, g_l in the edge e = x_j − x_i and
    the wings a = x_k − x_i, b = x_l − x_i: with n_a = e × a, P_a = I/|n_a|² − 2 n_a n_aᵀ/|n_a|⁴
    (the derivative of n/|n|²), [v]× the cross-product matrix and ℓ = |e|,

        ∂g_k/∂e = −n_a eᵀ/(ℓ |n_a|²) + ℓ P_a [a]×,    ∂g_k/∂a = −ℓ P_a [e]×,
        ∂g_l/∂e = −n_b eᵀ/(ℓ |n_b|²) − ℓ P_b [b]×,    ∂g_l/∂b = ℓ P_b [e]×,

    g_j = −f_a g_k − f_b g_l by the product rule (f_a = a·e/e·e), and node i's rows and
    columns minus the sums of the others' (θ does not change under a translation).
    Symmetrised; equal to :func:`dihedral_hessian_complex` to 2e-15 of its largest entry on
    random hinges (``tests/test_collapse.py``), at half its cost.
    """
    x = np.asarray(x, float)
    e = x[:, 1] - x[:, 0]
    a = x[:, 2] - x[:, 0]
    b = x[:, 3] - x[:, 0]
    na, nb = _cross(e, a), _cross(b, e)
    ee = _dot(e, e)
    ell = np.sqrt(ee)
    qa, qb = _dot(na, na), _dot(nb, nb)
    gk = -(ell / qa)[:, None] * na
    gl = -(ell / qb)[:, None] * nb
    fa, fb = _dot(a, e) / ee, _dot(b, e) / ee
    eye = np.eye(3)
    Pa = eye / qa[:, None, None] - 2 * na[:, :, None] * na[:, None, :] / (qa * qa)[:, None, None]
    Pb = eye / qb[:, None, None] - 2 * nb[:, :, None] * nb[:, None, :] / (qb * qb)[:, None, None]
    Ae, Aa, Ab = _skew(e), _skew(a), _skew(b)
    L = ell[:, None, None]
    outer = lambda u, v: u[:, :, None] * v[:, None, :]  # noqa: E731
    dk_e = -outer(na, e) / (ell * qa)[:, None, None] + L * Pa @ Aa
    dk_a = -L * Pa @ Ae
    dl_e = -outer(nb, e) / (ell * qb)[:, None, None] - L * Pb @ Ab
    dl_b = L * Pb @ Ae
    zero = np.zeros_like(dk_e)
    dfa_e = a / ee[:, None] - 2 * (fa / ee)[:, None] * e
    dfb_e = b / ee[:, None] - 2 * (fb / ee)[:, None] * e
    dfa_a, dfb_b = e / ee[:, None], e / ee[:, None]
    FA, FB = fa[:, None, None], fb[:, None, None]
    dj_e = -outer(gk, dfa_e) - FA * dk_e - outer(gl, dfb_e) - FB * dl_e
    dj_a = -outer(gk, dfa_a) - FA * dk_a
    dj_b = -outer(gl, dfb_b) - FB * dl_b
    # blocks [p][q] for p, q in (j, k, l): ∂g_p/∂x_q
    block = np.stack(
        [
            np.stack([dj_e, dj_a, dj_b], axis=1),
            np.stack([dk_e, dk_a, zero], axis=1),
            np.stack([dl_e, zero, dl_b], axis=1),
        ],
        axis=1,
    )  # (H, 3, 3, 3, 3)
    H = len(x)
    out = np.empty((H, 4, 4, 3, 3))
    out[:, 1:, 1:] = block
    out[:, 0, 1:] = -block.sum(axis=1)
    out[:, 1:, 0] = -block.sum(axis=2)
    out[:, 0, 0] = block.sum(axis=(1, 2))
    full = out.transpose(0, 1, 3, 2, 4).reshape(H, 12, 12)
    return 0.5 * (full + np.swapaxes(full, 1, 2))


def _skew(v: np.ndarray) -> np.ndarray:
    """The cross-product matrices [v]× (N, 3, 3) of vectors (N, 3): [v]× w = v × w."""
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def dihedral_hessian_complex(x: np.ndarray) -> np.ndarray:
    """∂²θ/∂x² of hinges (H, 4, 3), shape (H, 12, 12), 1/m², by complex steps of the gradient.

    Symmetrised (the complex step is exact to rounding, so the two halves agree to it).
    """
    x = np.asarray(x, float)
    H = x.shape[0]
    scale = np.abs(x - x[:, :1]).max(axis=(1, 2))  # the element's size
    h = COMPLEX_STEP * np.where(scale > 0, scale, 1.0)
    flat = x.reshape(H, 12).astype(complex)
    out = np.empty((H, 12, 12))
    for m in range(12):
        step = flat.copy()
        step[:, m] += 1j * h
        out[:, :, m] = dihedral_gradient(step.reshape(H, 4, 3)).reshape(H, 12).imag / h[:, None]
    return 0.5 * (out + np.swapaxes(out, 1, 2))


def dihedral_hessian_action(x: np.ndarray, v: np.ndarray) -> np.ndarray:
    """∂²θ/∂x² · v of hinges (H, 4, 3) along motions v (H, 4, 3), shape (H, 4, 3): one complex
    step of the gradient."""
    x = np.asarray(x, float)
    scale = np.abs(x - x[:, :1]).max(axis=(1, 2)) / np.maximum(np.abs(v).max(axis=(1, 2)), 1e-300)
    h = (COMPLEX_STEP * np.where(scale > 0, scale, 1.0))[:, None, None]
    return dihedral_gradient(x + 1j * h * v).imag / h


def triangle_areas(x: np.ndarray) -> np.ndarray:
    """Areas of triangles (T, 3, 3), shape (T,)."""
    n = _cross(x[..., 1, :] - x[..., 0, :], x[..., 2, :] - x[..., 0, :])
    return 0.5 * np.sqrt(_dot(n, n))


def triangle_strain(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The in-plane strain of triangles (T, 3, 3) from the elongations of their edges.

    Edge m joins corner m to corner m + 1 (mod 3). The strain is given in the triangle's
    own frame: x̂ along edge 0, ŷ in its plane toward corner 2.

    Returns
    -------
    G : (T, 3, 3) ndarray
        Voigt strain ``(ε_xx, ε_yy, γ_xy) = G δ`` from the edges' elongations δ (T, 3), 1/m.
    frame : (T, 2, 3) ndarray
        The unit vectors x̂, ŷ of every triangle's frame.
    """
    x = np.asarray(x, float)
    edges = np.roll(x, -1, axis=-2) - x  # edge m from corner m to m + 1
    lengths = np.linalg.norm(edges, axis=-1)
    ex = edges[:, 0] / lengths[:, :1]
    normal = _cross(edges[:, 0], -edges[:, 2])
    ey = _cross(normal / np.linalg.norm(normal, axis=-1, keepdims=True), ex)
    nx, ny = _dot(edges, ex[:, None]) / lengths, _dot(edges, ey[:, None]) / lengths
    rows = np.stack([nx * nx, ny * ny, nx * ny], axis=-1)  # edge strain n ε n as a row on Voigt ε
    G = np.linalg.inv(rows) / lengths[:, None, :]  # ε = rows⁻¹ (δ / ℓ)
    return G, np.stack([ex, ey], axis=1)


def quad_frame(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The plane of quads (Q, 4, 3): x̂ along the mean first side, the normal along the cross
    product of the diagonals.

    Returns
    -------
    frame : (Q, 2, 3) ndarray
        x̂, ŷ of every quad.
    local : (Q, 4, 2) ndarray
        The corners in that frame, about their mean.
    """
    x = np.asarray(x, float)
    ex = (x[:, 1] - x[:, 0]) + (x[:, 2] - x[:, 3])
    ex /= np.linalg.norm(ex, axis=1, keepdims=True)
    n = _cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1])
    ey = _cross(n / np.linalg.norm(n, axis=1, keepdims=True), ex)
    c = x - x.mean(axis=1, keepdims=True)
    return np.stack([ex, ey], axis=1), np.stack(
        [_dot(c, ex[:, None]), _dot(c, ey[:, None])], axis=-1
    )


#: Corners of the bilinear quad in (ξ, η).
_XI, _ETA = np.array([-1.0, 1.0, 1.0, -1.0]), np.array([-1.0, -1.0, 1.0, 1.0])
#: The 2 × 2 Gauss points.
_GAUSS = [(s, r) for s in (-(3**-0.5), 3**-0.5) for r in (-(3**-0.5), 3**-0.5)]


def _jacobian(local: np.ndarray, s: float, r: float) -> tuple[np.ndarray, np.ndarray]:
    """The Jacobian (Q, 2, 2) of bilinear quads at (ξ, η) = (s, r), J[a, b] = ∂x_b/∂ξ_a, and the
    shape derivatives (2, 4)."""
    dN = 0.25 * np.stack([_XI * (1 + _ETA * r), _ETA * (1 + _XI * s)])
    return np.einsum("an,qnb->qab", dN, local), dN


def _strain_rows(dNx: np.ndarray) -> np.ndarray:
    """Voigt strain rows (Q, 3, 8) on the corners' (u, v) from shape gradients (Q, 2, 4)."""
    B = np.zeros((len(dNx), 3, 8))
    B[:, 0, 0::2], B[:, 1, 1::2] = dNx[:, 0], dNx[:, 1]
    B[:, 2, 0::2], B[:, 2, 1::2] = dNx[:, 1], dNx[:, 0]
    return B


def quad_membrane(
    x: np.ndarray, youngs_modulus: float, poisson: float, thickness: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """In-plane stiffness of quads (Q, 4, 3) with two incompatible modes per direction (Wilson and
    Taylor's QM6).

    Bilinear displacements plus the modes ``1 − ξ²`` and ``1 − η²`` in each direction,
    their derivatives taken with the Jacobian at the centre (Taylor's correction, which
    passes the patch test on any convex quad), 2 × 2 Gauss points, the modes condensed out.
    A rectangle so modelled bends in its plane exactly; two constant-strain triangles lock.
    The quad is taken in its own plane (:func:`quad_frame`; a smooth ruling quad is planar
    to O(h³)).

    Returns
    -------
    K : (Q, 8, 8) ndarray
        On the in-plane displacements (u, v) of corners 0 … 3 in the quad's frame, N/m.
    strain : (Q, 3, 8) ndarray
        Voigt strain at the centre from the same displacements (the modes' vanish there), 1/m.
    frame : (Q, 2, 3) ndarray
        x̂, ŷ of every quad.
    """
    frame, local = quad_frame(x)
    D = plane_stress(youngs_modulus, poisson)
    J0 = _jacobian(local, 0.0, 0.0)[0]
    J0inv, det0 = np.linalg.inv(J0), np.linalg.det(J0)
    Q = len(local)
    Kuu, Kua, Kaa = np.zeros((Q, 8, 8)), np.zeros((Q, 8, 4)), np.zeros((Q, 4, 4))
    for s, r in _GAUSS:
        J, dN = _jacobian(local, s, r)
        det = np.linalg.det(J)
        B = _strain_rows(np.linalg.inv(J) @ dN)
        dP = (
            np.einsum("qab,pb->qpa", J0inv, np.array([[-2 * s, 0.0], [0.0, -2 * r]]))
            * (det0 / det)[:, None, None]
        )
        Gm = np.zeros((Q, 3, 4))  # modes: u·P1, u·P2, v·P1, v·P2
        Gm[:, 0, :2], Gm[:, 1, 2:] = dP[:, :, 0], dP[:, :, 1]
        Gm[:, 2, :2], Gm[:, 2, 2:] = dP[:, :, 1], dP[:, :, 0]
        w = (thickness * det)[:, None, None]
        Bt, DB, DG = np.swapaxes(B, 1, 2) * w, D @ B, D @ Gm
        Kuu += Bt @ DB
        Kua += Bt @ DG
        Kaa += (np.swapaxes(Gm, 1, 2) * w) @ DG
    K = Kuu - Kua @ np.linalg.solve(Kaa, np.swapaxes(Kua, 1, 2))
    B0 = _strain_rows(np.einsum("qab,bn->qan", J0inv, 0.25 * np.stack([_XI, _ETA])))
    return 0.5 * (K + np.swapaxes(K, 1, 2)), B0, frame


def membrane_geometric(x: np.ndarray, stress: np.ndarray, thickness: float) -> np.ndarray:
    """Geometric stiffness ``t ∫ ∇N_a · σ · ∇N_b dA`` of membranes under a uniform stress, shape (T,
    k, k), N/m.

    The same for each displacement component: the element's geometric stiffness is this
    times the 3 × 3 identity.

    Parameters
    ----------
    x : (T, k, 3) ndarray
        Triangles (k = 3, linear shape functions, in the frame of :func:`triangle_strain`)
        or quads (k = 4, bilinear, 2 × 2 Gauss points, in the frame of :func:`quad_frame`).
    stress : (T, 3) ndarray
        (σ_xx, σ_yy, τ_xy) in the same frames, Pa.
    """
    x = np.asarray(x, float)
    T, k = x.shape[:2]
    sigma = np.zeros((T, 2, 2))
    sigma[:, 0, 0], sigma[:, 1, 1] = stress[:, 0], stress[:, 1]
    sigma[:, 0, 1] = sigma[:, 1, 0] = stress[:, 2]
    if k == 3:
        frame = triangle_strain(x)[1]
        local = np.einsum("tnk,tak->tna", x - x[:, :1], frame)
        area2 = local[:, 1, 0] * local[:, 2, 1] - local[:, 2, 0] * local[:, 1, 1]
        y, z = local[..., 1], local[..., 0]
        grad = (
            np.stack(
                [np.roll(y, -1, 1) - np.roll(y, -2, 1), np.roll(z, -2, 1) - np.roll(z, -1, 1)],
                axis=1,
            )
            / area2[:, None, None]
        )
        scalar = (
            0.5
            * thickness
            * np.abs(area2)[:, None, None]
            * (np.swapaxes(grad, 1, 2) @ sigma @ grad)
        )
    else:
        _, local = quad_frame(x)
        scalar = np.zeros((T, 4, 4))
        for s, r in _GAUSS:
            J, dN = _jacobian(local, s, r)
            grad = np.linalg.inv(J) @ dN
            scalar += (
                thickness
                * np.linalg.det(J)[:, None, None]
                * (np.swapaxes(grad, 1, 2) @ sigma @ grad)
            )
    return scalar


def plane_stress(youngs_modulus: float, poisson: float) -> np.ndarray:
    """The plane-stress elasticity matrix D (Voigt, engineering shear), shape (3, 3), Pa.

    Examples
    --------
    >>> plane_stress(1.0, 0.0).tolist()
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.5]]
    """
    E, nu = float(youngs_modulus), float(poisson)
    return (
        E / (1 - nu * nu) * np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1 - nu)]])
    )


def face_bars(faces: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """The bars of faces (F, k) as vertex pairs, shape (F, 5, 2): sides from corner m to m + 1,
    then a quad's diagonal 0–2; -1 pads."""
    F = len(faces)
    out = np.full((F, 5, 2), -1, np.int64)
    tri, quad = sizes == 3, sizes == 4
    out[tri, :3] = np.stack([faces[tri][:, :3], np.roll(faces[tri][:, :3], -1, axis=1)], axis=-1)
    if quad.any():
        q = faces[quad][:, :4]
        out[quad, :4] = np.stack([q, np.roll(q, -1, axis=1)], axis=-1)
        out[quad, 4] = q[:, [0, 2]]
    return out


def face_membranes(
    x: np.ndarray,
    faces: np.ndarray,
    sizes: np.ndarray,
    area: np.ndarray,
    youngs_modulus: float,
    poisson: float,
    t: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Every face's stiffness (F, 5, 5) and centre strain (F, 3, 5) on its bars
    (:func:`face_bars`)."""
    F = len(faces)
    S, strain = np.zeros((F, 5, 5)), np.zeros((F, 3, 5))
    D = plane_stress(youngs_modulus, poisson)
    tri, quad = sizes == 3, sizes == 4
    if tri.any():
        G, _ = triangle_strain(x[faces[tri][:, :3]])
        strain[tri, :, :3] = G
        S[tri, :3, :3] = t * area[tri][:, None, None] * (np.swapaxes(G, 1, 2) @ D @ G)
    if quad.any():
        corners = x[faces[quad][:, :4]]
        K8, B0, frame = quad_membrane(corners, youngs_modulus, poisson, t)
        # (Q, 4, 2)
        local = np.einsum("qnk,qak->qna", corners - corners.mean(axis=1, keepdims=True), frame)
        ends = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]])
        e = local[:, ends[:, 1]] - local[:, ends[:, 0]]
        e /= np.linalg.norm(e, axis=-1, keepdims=True)
        rows = np.zeros((len(corners), 5, 4, 2))
        rows[:, np.arange(5), ends[:, 0]] -= e
        rows[:, np.arange(5), ends[:, 1]] += e
        C = rows.reshape(-1, 5, 8)
        # (Q, 8, 5): Cᵀ(CCᵀ)⁻¹, C of full rank
        Cinv = np.swapaxes(C, 1, 2) @ np.linalg.inv(C @ np.swapaxes(C, 1, 2))
        S[quad] = np.swapaxes(Cinv, 1, 2) @ K8 @ Cinv
        strain[quad] = B0 @ Cinv
    return 0.5 * (S + np.swapaxes(S, 1, 2)), strain
