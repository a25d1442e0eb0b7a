"""Measurements: the numbers that certify a curved-crease structure.

Every function returns numbers computed from the built geometry (points, frames, meshes),
not from the formulas that built it, so each one can fail. Derivatives along a curve are
taken by fourth-order central differences on the uniform samples (truncation ~h⁴), so a
residual that should vanish comes out at the discretisation level, and a wrong formula
(for instance the paper's sign of τ in Eq. 9) comes out at order one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.crease import Crease
from ..geometry.curve import gauss_nodes, integrate_frenet
from ..geometry.lattice import Lattice
from ..geometry.mesh import Mesh
from ..geometry.structure import State
from ..kernel.lie import GAUSS3_NODES, GAUSS3_WEIGHTS, cross

__all__ = [
    "derivative",
    "developability_residual",
    "IsometryError",
    "isometry_error",
    "ruling_quad_planarity",
    "frame_agreement",
    "width_law_error",
    "section_area_error",
    "eq19_residual",
    "chained_tube",
    "tube_closure",
    "fold_angle_error",
]


def derivative(values: np.ndarray, step: float) -> np.ndarray:
    """d/dq of samples along axis 0 by fourth-order central differences.

    Parameters
    ----------
    values : (n, ...) ndarray
        Samples at uniform spacing ``step``; n ≥ 5.
    step : float

    Returns
    -------
    (n - 4, ...) ndarray
        The derivative at samples 2 … n - 3.
    """
    v = np.asarray(values, float)
    return (v[:-4] - 8 * v[1:-3] + 8 * v[3:-1] - v[4:]) / (12.0 * step)


def developability_residual(crease: Crease) -> float:
    """Largest |r'·p| on both sides of a crease (zero for developable surfaces).

    r' is differentiated numerically from the built rulings; with p the surface normal,
    r'·p = 0 says the tangent plane does not turn along a ruling.
    """
    h = crease.s[1] - crease.s[0]
    worst = 0.0
    for r, p in zip(crease.rulings(), crease.normals()):
        worst = max(worst, float(np.abs(np.einsum("ij,ij->i", derivative(r, h), p[2:-2])).max()))
    return worst


@dataclass(frozen=True)
class IsometryError:
    """How far a folded mesh is from its flat crease pattern.

    Attributes
    ----------
    max_edge_error : float
        Largest |length − flat length| over all edges, model units.
    max_relative_edge_error : float
        The same divided by the flat length.
    max_angle_error : float
        Largest change of a triangle corner angle, radians.
    """

    max_edge_error: float
    max_relative_edge_error: float
    max_angle_error: float


def _corner_angles(mesh: Mesh) -> np.ndarray:
    x = mesh.vertices_coords[mesh.faces_vertices]  # (F, 3, 3)
    out = np.empty(x.shape[:2])
    for k in range(3):
        a = x[:, (k + 1) % 3] - x[:, k]
        b = x[:, (k + 2) % 3] - x[:, k]
        out[:, k] = np.arctan2(np.linalg.norm(cross(a, b), axis=-1), np.einsum("ij,ij->i", a, b))
    return out


def isometry_error(folded: Mesh, flat: Mesh) -> IsometryError:
    """Compare edge lengths and corner angles of two meshes of the same topology."""
    lf, l0 = folded.edge_lengths(), flat.edge_lengths()
    diff = np.abs(lf - l0)
    return IsometryError(
        max_edge_error=float(diff.max()),
        max_relative_edge_error=float((diff / l0).max()),
        max_angle_error=float(np.abs(_corner_angles(folded) - _corner_angles(flat)).max()),
    )


def ruling_quad_planarity(state: State) -> float:
    """Largest non-planarity of the quads between consecutive rulings of every strip.

    On the quad faces of the state's mesh (``state.mesh(faces="quads")``): for the quad
    a_j, a_{j+1}, b_{j+1}, b_j the distance of b_{j+1} from the plane of the other three,
    divided by the length of the quad's diagonal (dimensionless).
    """
    mesh = state.mesh(faces="quads")
    p = mesh.vertices_coords[mesh.faces_vertices]  # (F, 4, 3)
    n = cross(p[:, 1] - p[:, 0], p[:, 3] - p[:, 0])
    diagonal = p[:, 2] - p[:, 0]
    dist = np.abs(np.einsum("ij,ij->i", diagonal, n)) / np.linalg.norm(n, axis=-1)
    return float((dist / np.linalg.norm(diagonal, axis=-1)).max())


def frame_agreement(lattice: Lattice, uv: np.ndarray) -> float:
    """Largest angle (rad) between a lattice curve's numerical tangent and curve 1's T."""
    X = lattice.points(np.asarray(uv, float).reshape(-1, 2))
    h = lattice.t[1] - lattice.t[0]
    T = lattice.crease.curve.tangent[2:-2]
    worst = 0.0
    for x in X:
        d = derivative(x, h)
        sin = np.linalg.norm(cross(d, T), axis=-1) / np.linalg.norm(d, axis=-1)
        worst = max(worst, float(np.arcsin(np.clip(sin, 0, 1)).max()))
    return worst


def _tangent_line_distance(x: np.ndarray, y: np.ndarray, T: np.ndarray) -> np.ndarray:
    d = y - x
    return np.linalg.norm(d - np.einsum("ij,ij->i", d, T)[:, None] * T, axis=-1)


def width_law_error(lattice: Lattice) -> float:
    """Largest relative deviation of the built widths from the closed-form width law.

    Widths are measured as distances between the parallel tangent lines of curve 1 and
    of curves (1, 0) and (0, 1), and compared with ``w(0) exp(∓∫ κ_2D cot β ds)``
    evaluated independently (trapezoid-free: 3-point Gauss on a 4× finer grid).
    """
    X = lattice.points(np.array([[0, 0], [1, 0], [0, 1]], float))
    T = lattice.crease.curve.tangent
    wl, wr = _tangent_line_distance(X[0], X[1], T), _tangent_line_distance(X[0], X[2], T)
    fine = np.linspace(0.0, lattice.crease.curve.length, 4 * (len(lattice.s) - 1) + 1)
    nodes = gauss_nodes(fine)
    integrand = lattice.kappa_2d(nodes) / np.tan(lattice.crease.beta_left(nodes))
    log_ratio = np.concatenate([[0.0], np.cumsum(np.diff(fine) * (integrand @ GAUSS3_WEIGHTS))])[::4]
    expect_l, expect_r = wl[0] * np.exp(-log_ratio), wr[0] * np.exp(log_ratio)
    return float(max(np.abs(wl / expect_l - 1).max(), np.abs(wr / expect_r - 1).max()))


def section_area_error(lattice: Lattice) -> float:
    """Largest relative deviation of the section parallelogram's area from its value at t = 0.

    The section is curves (0,0), (0,1), (1,1), (1,0) at equal t projected along T; the
    paper's Fig. 03 claims the area constant (it is w_L w_R sin 2α).
    """
    X = lattice.points(np.array([[0, 0], [0, 1], [1, 0]], float))
    T = lattice.crease.curve.tangent
    e1, e2 = X[1] - X[0], X[2] - X[0]
    area = np.abs(np.einsum("ij,ij->i", cross(e1, e2), T))
    return float(np.abs(area / area[0] - 1).max())


def _curvature_and_speed(x: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    d1 = derivative(x, h)
    d2 = derivative(derivative(x, h), h)
    d1 = d1[2:-2]
    speed = np.linalg.norm(d1, axis=-1)
    kappa = np.linalg.norm(cross(d1, d2), axis=-1) / speed**3
    return kappa, speed


def eq19_residual(lattice: Lattice, uv_a: np.ndarray, uv_b: np.ndarray) -> float:
    """Largest |ratio − 1| of the paper's Eq. (19) between two neighbouring lattice curves.

    ``κ_a,2D tan α cosec β ds_a / (κ_b,2D tan α cosec β ds_b) = 1``: the surface shared by
    neighbouring creases must bend the same way seen from both. κ and ds/dt of each curve
    are measured from its built points by finite differences; α and β are shared.
    """
    X = lattice.points(np.array([uv_a, uv_b], float))
    h = lattice.t[1] - lattice.t[0]
    (ka, sa), (kb, sb) = (_curvature_and_speed(x, h) for x in X)
    # tan α and cosec β are common to both curves and cancel.
    return float(np.abs((ka * sa) / (kb * sb) - 1).max())


def chained_tube(lattice: Lattice) -> np.ndarray:
    """Curves 1 … 5 of the unit tube, each integrated from its predecessor's invariants.

    Curve k+1 starts at ``x_k(0) ± ℓ r(0)`` and is integrated with the Frenet equations in
    t from its own curvature ``κ_{k+1} = κ₁ σ₁/σ_{k+1}``, torsion ``τ_{k+1} = τ₁ σ₁/σ_{k+1}``
    and speed ``σ_{k+1} = σ_k (1 − w / w_lim,k)`` (Eq. 16), where ``w_lim,k`` comes from
    curve k's own κ_2D and dβ/ds_k (Eqs. 14–15) and the widths from Eqs. 12–13. Nothing
    here uses the lattice formula (Eq. 11), so comparing the two checks both.

    Returns
    -------
    (5, n, 3) ndarray
        Curves 1 (the crease itself), 2, 3, 4 and 5 (which should be curve 1 again).
    """
    crease = lattice.crease
    L = crease.curve.length
    t = lattice.t
    s_nodes = gauss_nodes(t) * L
    a = crease.alpha.constant
    k2 = lattice.kappa_2d(s_nodes)
    beta = crease.beta_left(s_nodes)
    dbeta = crease.beta_left.derivative(s_nodes)
    log_ratio = _cumulative_nodes(t, L * k2 / np.tan(beta))
    width = {"L": lattice.width_left[0] * np.exp(-log_ratio), "R": lattice.width_right[0] * np.exp(log_ratio)}
    rate = {"L": (dbeta + k2) / np.sin(beta) ** 2, "R": (dbeta - k2) / np.sin(beta) ** 2}  # 1/w_lim of curve 1
    ruling = dict(zip("LR", crease.rulings()))
    ell = dict(zip("LR", lattice.ruling_lengths))
    kappa1, tau1 = k2 / np.cos(a), k2 * np.tan(a) / np.tan(beta)
    sigma = np.full_like(s_nodes, L)
    curves = [crease.curve.points]
    for side, sign in (("R", 1.0), ("L", 1.0), ("R", -1.0), ("L", -1.0)):
        # Curve k's own 1/w_lim is (σ₁/σ_k) × curve 1's, so σ_{k+1} = σ_k − sign·w·σ₁·rate₁.
        sigma = sigma - sign * width[side] * L * rate[side]
        start = curves[-1][0] + sign * ell[side][0] * ruling[side][0]
        pts, _ = integrate_frenet(t, kappa1 * L / sigma, tau1 * L / sigma, speed_nodes=sigma, origin=start, frame=crease.curve.frames[0])
        curves.append(pts)
    return np.stack(curves)


def tube_closure(lattice: Lattice) -> tuple[float, float]:
    """How well a tube built crease by crease closes and matches the lattice formula.

    Returns
    -------
    closure : float
        Largest |x₅(t) − x₁(t)| of :func:`chained_tube`, model units.
    agreement : float
        Largest distance between chained curves 2–4 and the lattice curves (0,1), (1,1), (1,0).
    """
    chain = chained_tube(lattice)
    lattice_curves = lattice.points(np.array([[0, 1], [1, 1], [1, 0]], float))
    closure = float(np.linalg.norm(chain[4] - chain[0], axis=-1).max())
    agreement = float(np.linalg.norm(chain[1:4] - lattice_curves, axis=-1).max())
    return closure, agreement


def _cumulative_nodes(t: np.ndarray, rate_nodes: np.ndarray) -> np.ndarray:
    """∫₀^{node} rate dt at every Gauss node, from the rate at the nodes, shape (n-1, 3).

    Integrates the 3-point interpolating polynomial of each interval exactly up to each node.
    """
    h = np.diff(t)
    whole = h * (rate_nodes @ GAUSS3_WEIGHTS)
    before = np.concatenate([[0.0], np.cumsum(whole)])[:-1]
    c = GAUSS3_NODES
    # Weights W[i, j] = ∫₀^{c_i} ℓ_j(x) dx for the Lagrange basis ℓ_j on the nodes c.
    V = np.vander(c, 3, increasing=True)
    coeffs = np.linalg.inv(V)  # columns: monomial coefficients of ℓ_j
    powers = np.stack([c ** (k + 1) / (k + 1) for k in range(3)], axis=1)  # (3 nodes, 3 monomials)
    W = powers @ coeffs
    return before[:, None] + h[:, None] * (rate_nodes @ W.T)


def fold_angle_error(mesh: Mesh, fold_angle: float) -> float:
    """Largest |measured − expected| fold angle (degrees) on the fold and seam edges.

    Expected for a fold angle 2α (degrees): 2α on the folds (creases 1, 3) and 180° − 2α
    on the seams (2, 4), mountains seen from outside the tubes.
    """
    expect = np.where(mesh.edges_kind == "fold", -fold_angle, -(180.0 - fold_angle))
    sel = np.isin(mesh.edges_kind, ("fold", "seam"))
    return float(np.abs(mesh.edges_foldAngle[sel] - expect[sel]).max())
