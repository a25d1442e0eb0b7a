"""Values: read-only arrays, a fold-invariant pattern shared by reference, pickling.

Every array a curve, crease, lattice, structure, state, mesh, sheet or vault holds is
read-only, so a cached value cannot be changed behind its owner's back (it could: a
vault's vertices and a lattice's regression domain were writable, and writing to them
changed ``ground_error()`` and every refolded lattice). Everything built from data
pickles, for process pools and distributed sweeps; a user's lambda does not.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from curvefold import Crease, Lattice, RegressionDomain, SpaceCurve, Structure
from curvefold.geometry._sheets import flat_plane, sheets
from curvefold.vault import Vault, VaultDesign


def kappa(s):
    return 1.0 + 0.3 * np.sin(s)


def tau(s):
    return 0.3 * np.cos(1.5 * s)


def make_lattice(samples=61):
    curve = SpaceCurve.from_curvature(kappa, tau, 3.0, samples=samples)
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=60.0), 0.2, 0.15)


@pytest.fixture(scope="module")
def lattice():
    return make_lattice()


@pytest.fixture(scope="module")
def vault():
    return Vault.from_design(VaultDesign(samples=41, tubes=3))


# --------------------------------------------------------------------------------------
# one pattern, shared


def test_folding_shares_the_pattern_by_reference(lattice, vault):
    for angle in (0.0, 30.0, 120.0):
        folded = lattice.refold(angle)
        assert folded.pattern is lattice.pattern
        assert folded.refold(90.0, anchor="middle").pattern is lattice.pattern
        assert folded.domain is lattice.domain and folded.kappa_2d is lattice.kappa_2d
    structure = Structure.tube(lattice)
    assert structure.state(45.0).lattice.pattern is lattice.pattern
    assert vault.structure.state(70.0).lattice.pattern is vault.lattice.pattern


# --------------------------------------------------------------------------------------
# read-only


def test_defect_5_cached_arrays_cannot_be_written_through(lattice, vault):
    ground = vault.ground_error()
    with pytest.raises(ValueError, match="read-only"):
        vault.vertices[0, 0, 2] = 5.0
    assert vault.ground_error() == ground
    a0 = float(lattice.domain.a[0])
    with pytest.raises(ValueError, match="read-only"):
        lattice.domain.a[0] = 5.0
    assert lattice.refold(30.0).domain.a[0] == a0


def arrays_of(lattice: Lattice):
    """(name, array) for every array reachable from a structure built on ``lattice``."""
    structure = Structure.from_cells(lattice, [(0, 0), (1, 1)])
    state = structure.state(40.0)
    mesh = state.mesh()
    curve, pattern, topology = lattice.crease.curve, lattice.pattern, structure.topology()
    out = {f"curve.{k}": getattr(curve, k) for k in ("s", "points", "frames")}
    out["crease.kappa_2d"] = lattice.crease.kappa_2d
    out |= {
        f"pattern.{k}": getattr(pattern, k)
        for k in (
            "s",
            "beta_samples",
            "width_left",
            "width_right",
            "log_width_ratio",
            "kappa_2d_nodes",
            "log_width_rate_nodes",
        )
    }
    out |= {f"pattern.ruling_lengths[{i}]": a for i, a in enumerate(pattern.ruling_lengths)}
    out |= {f"pattern.regression_rates[{i}]": a for i, a in enumerate(pattern.regression_rates)}
    out |= {f"domain.{k}": getattr(lattice.domain, k) for k in ("t", "a", "b")}
    out |= {f"structure.{k}": getattr(structure, k) for k in ("cells", "curves_uv", "cell_curves")}
    out["state.vertices"] = state.vertices
    out |= {
        f"topology.{k}": getattr(topology, k)
        for k in ("vertex_curve", "faces_vertices", "edges_vertices", "edges_seam")
    }
    out |= {
        f"mesh.{k}": getattr(mesh, k)
        for k in (
            "vertices_coords",
            "edges_vertices",
            "edges_assignment",
            "edges_foldAngle",
            "faces_vertices",
            "edges_kind",
            "faces_group",
        )
    }
    sheet = sheets(structure)[0]
    out |= {
        "sheet.edges_seam": sheet.edges_seam,
        "sheet.mesh.vertices_coords": sheet.mesh.vertices_coords,
    }
    plane = flat_plane(structure.state(0.0))
    out |= {"plane.origin": plane.origin, "plane.axes": plane.axes}
    return out


def test_every_held_array_is_read_only(lattice):
    for name, array in arrays_of(lattice).items():
        assert not array.flags.writeable, name
        base = array.base
        while isinstance(base, np.ndarray):  # nor can it be written through what it views
            assert not base.flags.writeable, name
            base = base.base


def test_values_copy_the_arrays_they_are_given():
    t, a, b = np.linspace(0, 1, 3), np.array([0.1, 0.2, 0.3]), np.zeros(3)
    domain = RegressionDomain(t, a, b)
    a[0] = 9.0  # the caller's array stays the caller's
    assert a.flags.writeable and domain.a[0] == 0.1


# --------------------------------------------------------------------------------------
# pickling


def round_trip(value):
    return pickle.loads(pickle.dumps(value))


def same_functions(f, g, s):
    assert_array_equal(f(s), g(s))
    assert_array_equal(f.derivative(s), g.derivative(s))


@pytest.mark.parametrize(
    "build",
    [
        lambda: Crease.from_curve(
            SpaceCurve.from_curvature(kappa, tau, 3.0, samples=41), fold_angle=70.0
        ),
        lambda: Crease.from_curve(
            SpaceCurve.from_curvature(1.0, np.linspace(0.1, 0.4, 9), 2.0, samples=41),
            fold_angle=np.linspace(40, 80, 5),
        ),
        lambda: Crease.from_pattern(0.8, 85.0, 95.0, 2.0, fold_angle=90.0, samples=41),
    ],
    ids=["callables", "samples-and-varying-fold-angle", "from-pattern"],
)
def test_creases_pickle(build):
    crease = build()
    back = round_trip(crease)
    s = crease.s
    assert_array_equal(back.curve.points, crease.curve.points)
    assert_array_equal(back.curve.frames, crease.curve.frames)
    for name in ("alpha", "beta_left", "beta_right"):
        same_functions(getattr(crease, name), getattr(back, name), s)
    same_functions(crease.curve.kappa, back.curve.kappa, s)
    same_functions(crease.curve.tau, back.curve.tau, s)
    assert_array_equal(back.regression_rates(), crease.regression_rates())


def test_lattices_structures_states_and_meshes_pickle(lattice):
    folded = lattice.refold(100.0)
    back = round_trip(folded)
    assert_array_equal(back.points([[1, 1]]), folded.points([[1, 1]]))
    assert_array_equal(back.domain.a, folded.domain.a)
    same_functions(back.crease.curve.tau, folded.crease.curve.tau, lattice.s)
    assert_array_equal(
        back.fold_points([[0, 1]], [20.0, 50.0]), folded.fold_points([[0, 1]], [20.0, 50.0])
    )
    structure = Structure.diagonal(lattice, 2)
    state = structure.state(80.0)
    state_back, structure_back = round_trip(state), round_trip(structure)
    assert_array_equal(state_back.vertices, state.vertices)
    assert_array_equal(structure_back.state(30.0).vertices, structure.state(30.0).vertices)
    mesh = state.mesh(faces="quads")
    mesh_back = round_trip(mesh)
    for name in (
        "vertices_coords",
        "edges_vertices",
        "edges_assignment",
        "edges_foldAngle",
        "faces_vertices",
        "edges_kind",
        "faces_group",
    ):
        assert_array_equal(getattr(mesh_back, name), getattr(mesh, name))
        assert not getattr(mesh_back, name).flags.writeable


def test_vaults_pickle(vault):
    back = round_trip(vault)
    assert back.design == vault.design
    assert_array_equal(back.vertices, vault.vertices)
    assert not back.vertices.flags.writeable
    assert back.summary() == vault.summary()
    assert_array_equal(back.motion([30.0]), vault.motion([30.0]))


def test_a_users_lambda_does_not_pickle():
    curve = SpaceCurve.from_curvature(lambda s: 1.0 + 0 * s, 0.2, 1.0, samples=11)
    with pytest.raises((pickle.PicklingError, AttributeError)):
        pickle.dumps(curve)


def test_distinct_values_are_those_of_np_unique():
    """kernel's distinct is np.unique without its import of numpy.ma: the same values, dtype and
    order, for integers, floats (signed zeros among them) and empty arrays of any shape;
    damaged (one duplicate kept), it differs."""
    from curvefold.kernel._arrays import distinct

    rng = np.random.default_rng(7)
    cases = [rng.integers(-5, 6, size=shape) for shape in ((0,), (1,), (40,), (6, 7), (3, 0, 2))]
    cases += [
        rng.integers(0, 4, size=30).astype(float) * rng.choice([-1.0, 1.0], size=30) * 0.5,
        np.array([0.0, -0.0, 0.0]),
    ]
    for values in cases:
        ours, theirs = distinct(values), np.unique(values)
        assert (
            ours.dtype == theirs.dtype
            and np.array_equal(ours, theirs)
            and ours.tobytes() == theirs.tobytes()
        )
    damaged = np.sort(cases[2])
    assert not np.array_equal(
        damaged[np.r_[True, damaged[1:] != damaged[:-1]] | (np.arange(len(damaged)) == 1)],
        np.unique(cases[2]),
    )
