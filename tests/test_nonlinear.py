"""Large displacements of the bar-and-hinge model: its tangent and forces, and the path following,
against closed forms.

Every check is a function of the quantity it checks, run once on the model as built and
once on a damaged one (a flipped hinge Hessian, a linear hinge, a first-order clamp, load
control), where it must fail.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from _mechanics import miura_mesh
from curvefold.kernel import InputError
from curvefold.mechanics import (
    MATERIALS,
    BarHingeModel,
    Loads,
    PathError,
    StructureModel,
    Supports,
    _elements,
    _nonlinear,
    _path,
    follow_load,
    static_response,
)
from curvefold.vault import Vault

AL = MATERIALS["aluminium"]
NO_HINGES = np.zeros((0, 4), np.int64)


@pytest.fixture(scope="module")
def models():
    tube = StructureModel.from_state(
        Vault.from_design(tubes=1, panels=4, samples=21).structure.state(), AL, 1e-3
    )
    miura = BarHingeModel.from_mesh(
        miura_mesh(1.0, 1.0, np.radians(60), np.radians(40)), AL, 1e-3, crease_stiffness=1.0
    )
    return {"tube": tube, "miura": miura}


def parts(model: BarHingeModel) -> dict[str, BarHingeModel]:
    """The model's bars and membranes alone, and its hinges alone: the hinges' share of a
    membrane model's tangent is too small to check within the whole."""
    return {
        "bars": replace(model, hinge_stiffness=np.zeros(len(model.hinges))),
        "hinges": replace(
            model,
            bar_stiffness=np.zeros(len(model.bars)),
            membrane_stiffness=np.zeros_like(model.membrane_stiffness),
        ),
    }


def derivative_errors(model: BarHingeModel) -> tuple[float, float]:
    """Relative errors of the tangent against central differences of the forces, and of the
    forces against central differences of the energy, at a large random displacement
    (2e-3 of the size per DOF: hinges turned by up to 0.4 rad).

    Step 1e-6 of the size: truncation ~1e-12, rounding ~1e-10 of the forces (measured
    1e-8 and 5e-7 at most).
    """
    rng = np.random.default_rng(1)
    u = 2e-3 * model.size * rng.standard_normal(model.dofs)
    v = rng.standard_normal(model.dofs)
    h = 1e-6 * model.size
    forces = _nonlinear.internal_forces
    fd = (forces(model, u + h * v) - forces(model, u - h * v)) / (2 * h)
    Kv = _nonlinear.tangent(model, u) @ v
    dU = (_nonlinear.energy(model, u + h * v) - _nonlinear.energy(model, u - h * v)) / (2 * h)
    fv = forces(model, u) @ v
    return float(np.linalg.norm(fd - Kv) / np.linalg.norm(Kv)), float(abs(dU - fv) / abs(fv))


@pytest.mark.parametrize("name", ["tube", "miura"])
def test_the_tangent_at_rest_is_the_linear_stiffness(models, name):
    model = getattr(models[name], "model", models[name])
    K0, K = _nonlinear.tangent(model, np.zeros(model.dofs)), model.stiffness
    assert abs(K0 - K).max() <= 1e-14 * abs(K).max()  # measured 9e-16 and 1e-16
    assert not _nonlinear.internal_forces(model, np.zeros(model.dofs)).any()


@pytest.mark.parametrize("name", ["tube", "miura"])
def test_the_forces_derive_the_energy_and_the_tangent_the_forces(models, name):
    model = getattr(models[name], "model", models[name])
    for part in parts(model).values():
        tangent_error, force_error = derivative_errors(part)
        assert tangent_error < 1e-6 and force_error < 1e-5


def test_a_flipped_hinge_hessian_or_a_linear_bar_law_fails_the_derivatives(models, monkeypatch):
    model = models["tube"].model
    hessian = _elements.dihedral_hessian
    monkeypatch.setattr(_elements, "dihedral_hessian", lambda x: -hessian(x))
    assert derivative_errors(parts(model)["hinges"])[0] > 1e-2
    monkeypatch.undo()
    monkeypatch.setattr(  # the engineering elongation ℓ − L in the energy, Green's in the rest
        _nonlinear,
        "elongations",
        lambda m, u: (
            np.linalg.norm(np.diff((m.nodes + u.reshape(-1, 3))[m.bars], axis=1), axis=2)[:, 0]
            - np.linalg.norm(np.diff(m.nodes[m.bars], axis=1), axis=2)[:, 0]
        ),
    )
    assert derivative_errors(parts(model)["bars"])[0] > 1e-2


# -- a single hinge ------------------------------------------------------------------------------
K_HINGE, ARM = 2.0, 1.0  # N·m/rad; wing l at 1 m from the edge


def hinge_model(rest: float = 0.0) -> BarHingeModel:
    """Edge i–j along y, wing k in z = 0 at x = 1, wing l at ARM from the edge, turned by rest
    from the plane; stiff bars (EA/L = 1e8 N/m)."""
    nodes = np.array(
        [
            [0.0, 0, 0],
            [0, 1, 0],
            [1, 0.5, 0],
            [-ARM * np.cos(rest), 0.5, ARM * np.sin(rest)],
        ]
    )
    bars = [[0, 1], [0, 2], [1, 2], [0, 3], [1, 3]]
    return BarHingeModel(nodes, bars, np.full(5, 1e8), [[0, 1, 2, 3]], [K_HINGE], np.ones(4))


def moment_errors(model: BarHingeModel, turns: np.ndarray) -> float:
    """The moment about the edge of the hinge's force on wing l, turned rigidly by each angle,
    against k φ: the largest error relative to k π."""
    errors = []
    for phi in turns:
        x = model.nodes.copy()
        r = x[3] - [0, 0.5, 0]
        c, s = np.cos(phi), np.sin(phi)
        x[3] = np.array([0, 0.5, 0]) + [c * r[0] + s * r[2], r[1], -s * r[0] + c * r[2]]
        f = _nonlinear.internal_forces(model, (x - model.nodes).ravel()).reshape(4, 3)
        moment = np.cross(x[3] - [0, 0.5, 0], f[3]) @ [0, 1.0, 0]
        errors.append(abs(abs(moment) - K_HINGE * abs(phi)) + (np.sign(moment) != np.sign(phi)))
    return float(max(errors) / (K_HINGE * np.pi))


def test_a_hinge_moment_is_k_times_its_rotation_to_a_half_turn(monkeypatch):
    turns = np.radians(np.linspace(-179, 179, 73))
    for rest in (0.0, np.radians(150)):  # flat, and folded near its limit: the rotation wraps
        assert moment_errors(hinge_model(rest), turns) < 1e-12  # measured 2e-16
    # the angle's change unwrapped: a folded hinge turned past the half turn jumps by 2π k
    monkeypatch.setattr(
        _nonlinear,
        "rotations",
        lambda m, u: (
            _elements.dihedral_angle((m.nodes + u.reshape(-1, 3))[m.hinges])
            - _elements.dihedral_angle(m.nodes[m.hinges])
        ),
    )
    assert moment_errors(hinge_model(np.radians(150)), turns) > 1


def hinge_path_errors(path, model) -> tuple[float, float, float]:
    """A dead upward force λ on wing l, edge and wing k held: the errors of k φ = λ |x_l|
    (equilibrium, relative to k φ) and of λ = k φ / (h cos φ) (the closed form with rigid
    bars), and the largest φ reached."""
    x = model.nodes[3] + path.displacements[:, 3]
    phi = np.arctan2(x[1:, 2], -x[1:, 0])
    lam = path.factors[1:]
    equilibrium = np.abs(K_HINGE * phi - lam * np.abs(x[1:, 0])) / (K_HINGE * phi)
    closed = np.abs(lam - K_HINGE * phi / (ARM * np.cos(phi))) / lam
    return float(equilibrium.max()), float(closed.max()), float(np.degrees(phi.max()))


def hinge_path() -> tuple:
    model = hinge_model()
    fixed = np.ones((4, 3), bool)
    fixed[3] = False
    forces = np.zeros((4, 3))
    forces[3, 2] = 1.0
    path = follow_load(
        model, forces, fixed, steps=300, max_factor=100.0, first=0.02, max_displacement=0.995
    )
    return path, model


def test_a_hinge_under_a_dead_force_turns_as_its_closed_form_to_85_degrees(monkeypatch):
    path, model = hinge_path()
    equilibrium, closed, reached = hinge_path_errors(path, model)
    # bars stretch by λ/EA ≤ 4e-7 m: the closed form to 2e-6 (measured 2.3e-7), equilibrium
    # to the tolerance (measured 2e-14), up to 85.3°
    assert equilibrium < 1e-8 and closed < 2e-6 and reached > 85
    # the linear model (its stiffness, a constant tangent; the wing slides up its tangent to
    # z = 0.995 m, φ = 45°) strays by 11 %
    monkeypatch.setattr(_path, "internal_forces", lambda m, u: m.stiffness @ u)
    monkeypatch.setattr(_path, "tangent", lambda m, u: m.stiffness)
    path, model = hinge_path()
    assert hinge_path_errors(path, model)[1] > 0.05


# -- the von Mises truss ------------------------------------------------------------------------
A, H, EA = 1.0, 0.2, 1000.0  # half span, rise (m), axial stiffness (N)
L0 = np.hypot(A, H)


def truss_load(w: np.ndarray) -> np.ndarray:
    """The exact load of the St Venant–Kirchhoff von Mises truss at apex deflection w (N):
    P = 2 EA E sin(current angle) ℓ / L0 = (EA / L0³) (H² − (H − w)²)(H − w)."""
    return EA / L0**3 * (H**2 - (H - w) ** 2) * (H - w)


def truss(method: str = "displacement"):
    model = BarHingeModel(
        np.array([[-A, 0, 0], [A, 0, 0], [0, 0, H]]), [[0, 2], [1, 2]], [EA / L0] * 2, NO_HINGES,
        [], np.ones(3),
    )  # fmt: skip
    fixed = np.ones((3, 3), bool)
    fixed[2, 2] = False
    forces = np.zeros((3, 3))
    forces[2, 2] = -1.0
    return follow_load(
        model, forces, fixed, steps=300, max_factor=100.0, first=0.1, max_displacement=2.3 * H,
        method=method,
    )  # fmt: skip


def test_the_von_mises_truss_snaps_through_on_its_exact_path():
    path = truss()
    w = -path.control_displacement
    limit_w = H - H / np.sqrt(3)  # dP/dw = 0
    limit = float(truss_load(np.array(limit_w)))  # 2.903274 N
    # every state on the exact curve to the solver's tolerance (measured 2.4e-14 N)
    assert np.abs(path.factors - truss_load(w)).max() < 1e-9 * limit
    # past the limit point, down the descending branch through P = 0 at w = H to its minimum
    # −P_limit and up again past w = 2H where the truss is inverted
    assert w.max() > 2.3 * H and path.factors.min() < -0.98 * limit
    assert 0.98 * limit < path.limit <= limit
    # unstable exactly where the exact curve descends (the states at the extrema excepted)
    descending = np.gradient(truss_load(w), w) < 0
    clear = np.abs(np.abs(truss_load(w)) - limit) > 0.05 * limit
    assert (path.stable[clear] == ~descending[clear]).all()
    assert len(path.factors) < 80 and path.iterations.max() <= 6  # measured 48 states, 1 iteration


def test_load_control_stalls_at_the_limit_point_with_one_line_keeping_its_states():
    with pytest.raises(PathError) as error:
        truss("load")
    message = str(error.value)
    assert "\n" not in message and "load factor 2.9032" in message and "limit point" in message
    kept = error.value.path
    assert len(kept.factors) > 10 and abs(kept.factors.max() - 2.903274) < 1e-4
    assert np.abs(kept.factors - truss_load(-kept.control_displacement)).max() < 1e-8


# -- the elastica --------------------------------------------------------------------------------
def elastica_tip(lam: float) -> tuple[float, float]:
    """Tip displacement (along, down) of a cantilever of length 1 and EI = 1 under a dead tip
    load λ across it (Bisshopp and Drucker 1945), by quadrature.

    With θ' = √(2λ(sin θ_L − sin θ)) and sin θ = sin θ_L − v²: 1 = √(2/λ) ∫ dv / cos θ,
    x_L = √(2 sin θ_L / λ), y_L = √(2/λ) ∫ tan θ dv, v from 0 to √(sin θ_L).
    """

    def integrals(t):
        st = np.sin(t)
        cos = lambda v: np.sqrt(1 - (st - v * v) ** 2)  # noqa: E731
        top = np.sqrt(st)
        return (
            quad(lambda v: 1 / cos(v), 0, top, epsabs=0, epsrel=1e-13)[0],
            quad(lambda v: (st - v * v) / cos(v), 0, top, epsabs=0, epsrel=1e-13)[0],
        )

    t = brentq(lambda t: 2 * integrals(t)[0] ** 2 - lam, 1e-12, 1.5, xtol=1e-15)
    r = np.sqrt(2 / lam)
    return r * np.sqrt(np.sin(t)) - 1, r * integrals(t)[1]


def panel_strip(n: int, clamp: float = 2.0) -> tuple[BarHingeModel, np.ndarray, np.ndarray]:
    """A cantilever of n rigid panels (length 1, width 0.1) on hinges of EI/s, and a clamped
    panel before it; the clamp's hinge ``clamp`` times stiffer.

    A hinge at a panel joint stands for the bending of the sheet over the panel length s
    around it, the clamp's over the half panel beside it (2 EI/s): the panels' angles are
    then the exact angle at their middles to O(s²), and the tip's position too (a midpoint
    rule). Panels are held flat by stiff diagonal hinges (1e4 EI/s) and bars (EA = 1e7 N).
    """
    s, b = 1.0 / n, 0.1
    xs = np.arange(-1, n + 1) * s
    nodes = np.stack([np.repeat(xs, 2), np.tile([0.0, b], n + 2), np.zeros(2 * n + 4)], 1)
    at = lambda i, side: 2 * (i + 1) + side  # noqa: E731 (station i from −1 to n)
    bars, hinges, k = [], [], []
    for i in range(-1, n):
        p, q, r, t = at(i, 0), at(i + 1, 0), at(i + 1, 1), at(i, 1)
        bars += [[p, q], [t, r], [p, r]]
        hinges.append([p, r, q, t])
        k.append(1e4 / s)
    bars += [[at(i, 0), at(i, 1)] for i in range(-1, n + 1)]
    for i in range(n):
        hinges.append([at(i, 0), at(i, 1), at(i - 1, 0), at(i + 1, 1)])
        k.append((clamp if i == 0 else 1.0) / s)
    length = np.linalg.norm(np.diff(nodes[np.array(bars)], axis=1)[:, 0], axis=1)
    model = BarHingeModel(nodes, bars, 1e7 / length, hinges, k, np.ones(len(nodes)))
    fixed = np.zeros((len(nodes), 3), bool)
    fixed[:4] = True
    forces = np.zeros((len(nodes), 3))
    forces[-2:, 2] = -0.5
    return model, fixed, forces


def elastica_error(n: int, clamp: float = 2.0) -> float:
    """The largest distance of the strip's tip from the elastica's along its path to λ = 5
    (a tip rotation of 70°), m."""
    model, fixed, forces = panel_strip(n, clamp)
    path = follow_load(model, forces, fixed, steps=100, max_factor=5.0, first=0.25)
    assert path.factors[-1] >= 5.0
    tip = path.displacements[1:, -2]
    exact = np.array([elastica_tip(lam) for lam in path.factors[1:]])
    return float(np.hypot(tip[:, 0] - exact[:, 0], -tip[:, 2] - exact[:, 1]).max())


def test_a_strip_of_panels_bends_as_the_elastica_at_second_order():
    coarse, fine = elastica_error(8), elastica_error(16)
    # measured 5.6e-3 and 1.4e-3 m (the tip moves 0.8 m): O(s²)
    assert fine < 2e-3 and 3.5 < coarse / fine < 4.5
    # a clamp hinge of the interior stiffness is a first-order rule (measured 8.4e-2 and
    # 4.3e-2 m, a ratio of 1.95): the order check fails
    assert elastica_error(8, clamp=1.0) / elastica_error(16, clamp=1.0) < 2.5


# -- the linear limit ----------------------------------------------------------------------------
def linear_errors(model, forces, fixed, linear, factors=(100.0, 200.0)) -> list[float]:
    """|u(λ) − λ u_lin| / |λ u_lin| at two load factors, from one step each."""
    out = []
    for lam in factors:
        path = follow_load(model, forces, fixed, steps=1, max_factor=lam)
        got = path.factors[-1] * linear
        out.append(float(np.abs(path.displacements[-1].ravel() - got).max() / np.abs(got).max()))
    return out


def test_at_small_load_the_path_is_the_linear_response_to_second_order(models):
    tube = models["tube"]
    model, forces, fixed = tube.model, Loads().forces(tube.model), Supports().fixed(tube)
    linear = static_response(model, forces, fixed)[0].displacements.ravel()
    small, large = linear_errors(model, forces, fixed, linear)
    # measured 4.4e-3 and 8.8e-3: the difference grows as λ², relative as λ
    assert large < 1.5e-2 and 1.9 < large / small < 2.1
    # a linear response 1 % off differs at first order: its relative error does not grow
    small, large = linear_errors(model, forces, fixed, 1.01 * linear)
    assert not 1.9 < large / small < 2.1


# -- MERLIN under Octave (optional) --------------------------------------------------------------
MERLIN = os.environ.get("CURVEFOLD_MERLIN", "")


@pytest.mark.octave
@pytest.mark.skipif(
    shutil.which("octave-cli") is None or not Path(MERLIN, "PathAnalysis.m").exists(),
    reason="needs octave-cli and MERLIN's code (its folder in CURVEFOLD_MERLIN)",
)
def test_merlins_miura_folding_under_octave_is_our_path(tmp_path, monkeypatch):
    benchmarks = Path(__file__).parents[1] / "benchmarks"
    monkeypatch.syspath_prepend(str(benchmarks))  # its helpers
    spec = importlib.util.spec_from_file_location("bench_merlin", benchmarks / "bench_merlin.py")
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    data = bench.merlin_path(Path(MERLIN), "folding", tmp_path / "folding.mat")
    model, path, _ = bench.curvefold_path(data)
    # measured 4e-10: strains below 1e-4, where Ogden's law and St Venant–Kirchhoff's agree
    assert bench.compare(data, model).max() < 1e-7
    # creases 1 % too stiff: the comparison sees it
    data["kpf"] = 1.01 * data["kpf"]
    model, path, _ = bench.curvefold_path(data)
    assert bench.compare(data, model).max() > 1e-3


# -- arguments ---------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "change, message",
    [
        ({"steps": 0}, r"^steps must be an integer in \[1, 100000\], got 0$"),
        ({"max_factor": -1.0}, r"^max_factor must be > 0, got -1\.0$"),
        ({"method": "arc"}, r"^method must be one of displacement, load, got 'arc'$"),
        (
            {"tolerance": 1.0},
            r"^tolerance must be in \[1e-14, 0\.01\] \(rounding to rough\), got 1\.0$",
        ),
        ({"forces": np.zeros((2, 3))}, r"^forces and fixed must have shape \(3, 3\), got \(2, 3\)"),
        ({"forces": np.zeros((3, 3))}, r"^forces must load a free DOF, got none$"),
    ],
)
def test_a_wrong_argument_is_one_line_naming_it_its_range_and_value(change, message):
    model = BarHingeModel(
        np.array([[-A, 0, 0], [A, 0, 0], [0, 0, H]]), [[0, 2], [1, 2]], [EA / L0] * 2, NO_HINGES,
        [], np.ones(3),
    )  # fmt: skip
    fixed = np.ones((3, 3), bool)
    fixed[2, 2] = False
    forces = np.zeros((3, 3))
    forces[2, 2] = -1.0
    arguments = {"forces": forces} | change
    forces = arguments.pop("forces")
    with pytest.raises(InputError, match=message):
        follow_load(model, forces, fixed, **arguments)
