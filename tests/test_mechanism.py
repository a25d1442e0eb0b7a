"""The mechanism analysis (curvefold.analysis._mechanism): degrees of freedom measured, and able to
fail.

Sizes stay small (a tube of 8 panels has 108 unknowns): the dense SVD is the cost.
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import least_squares

from _cli import run
from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.analysis import analyse_fold
from curvefold.analysis._mechanism import (
    CERTIFY_UNKNOWNS,
    MAX_UNKNOWNS,
    RESIDUAL_TOL,
    Framework,
    analyse,
    certified_mechanism,
    follow,
    mechanism,
)
from curvefold.geometry import PanelLattice
from curvefold.io import write_structure_fold
from curvefold.kernel import InputError
from curvefold.vault import Vault, VaultDesign

EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def smooth():
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=161
    )
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)


@pytest.fixture(scope="module")
def tube(smooth):
    return Structure.tube(PanelLattice.from_lattice(smooth, 8))


def points_of(structure: Structure, angle: float) -> np.ndarray:
    """The distinct vertices of a state, in the order of its framework."""
    _, rows = Framework.from_structure(structure)
    return structure.state(angle).vertices.reshape(-1, 3)[rows]


def test_panel_tube_and_vault_move_with_one_degree_of_freedom(tube):
    vault = Vault.from_design(VaultDesign(panels=8, tubes=2))
    for structure, angles in ((tube, (1.0, 30.0, 90.0, 150.0)), (vault.structure, (45.0, 90.0))):
        for m in analyse(structure, angles):
            assert m.consistent and m.residual < 64 * EPS, m.to_dict()
            assert m.dof == 1 and m.nullity == 7, m.to_dict()
            # null values ~1e-15 σ_max, the stiffest left ≳ 1e-3 σ_max
            assert m.gap > 1e10 and m.clearance < 1e-5, m.to_dict()
    # 7 lattice polylines of 9 vertices, welded
    assert analyse(vault.structure, (90.0,))[0].unknowns == 3 * 7 * 9


def test_the_flat_state_reports_its_extra_first_order_modes(tube):
    flat, near, off = analyse(tube, (0.0, 1e-4, 1e-2))
    assert flat.consistent and flat.gap > 1e10
    # measured: one per row of fold lines across the flat tube
    assert flat.dof == tube.lattice.pattern.panels + 1
    assert flat.label == "2α = 0° (flat)"
    # next to it those modes are barely stiff: the count is right but not clear, and the clearance
    # says so
    assert near.dof == off.dof == 1 and near.clearance > 1e-3 > off.clearance


def test_a_perturbed_pattern_of_the_same_topology_has_no_consistent_motion(tube):
    """Counting alone does not make the tube move: the same topology with random vertices (seeded)
    cannot fold.

    Each crease pattern is refolded by least squares from the design state, with one more bar
    across the first section (its length at the design state) to hold the fold angle: the
    built pattern gets there exactly, the perturbed ones do not (their residual is of the
    size of the perturbation), and at the state they reach they are rigid.
    """
    topology = tube.topology()
    n = len(tube.lattice.s)
    rows, weld = np.unique(topology.vertex_curve * n + topology.vertex_sample, return_inverse=True)
    flat = tube.state(0.0).vertices.reshape(-1, 3)[rows]
    normal = tube.lattice.refold(0.0).crease.curve.frames[0][:, 2]
    design = points_of(tube, 90.0)
    corners = tube.cell_curves[0]
    i, j = np.searchsorted(rows, [corners[3] * n, corners[1] * n])  # x_0 + L_0 and x_0 + R_0
    brace = np.linalg.norm(design[i] - design[j])
    h = float(tube.lattice.pattern.edge_lengths.min())
    rng = np.random.default_rng(12)
    for size in (0.0, 1e-5, 1e-3):
        noise = rng.standard_normal(flat.shape) * size * h
        noise -= np.outer(noise @ normal, normal)  # in the plane: still a flat crease pattern
        framework = Framework.from_mesh(
            (flat + noise)[weld], topology.edges_vertices, topology.faces_vertices, weld
        )
        braced = replace(
            framework,
            bars=np.concatenate([framework.bars, [[i, j]]]),
            lengths=np.append(framework.lengths, brace),
        )
        x = least_squares(
            braced.residual,
            design.ravel(),
            jac=braced.jacobian,
            method="lm",
            xtol=1e-15,
            ftol=1e-15,
            gtol=1e-15,
        ).x
        m = mechanism(framework, x)
        if size == 0:
            assert m.consistent and m.dof == 1
        else:  # measured: residual 1–4 × the perturbation, and rigid there
            assert not m.consistent and m.residual > 0.3 * size and m.dof == 0, m.to_dict()


def test_broken_constraint_sets_and_states_are_reported(tube):
    framework, rows = Framework.from_structure(tube)
    design = points_of(tube, 90.0)
    # without the planarity rows the count changes (a planar quad with six bars flexes out of its
    # plane)
    loose = replace(
        framework,
        quads=framework.quads[:0],
        diagonals=framework.diagonals[:0],
        sides=framework.sides[:0],
    )
    assert mechanism(loose, design).dof == 2  # measured
    # without the diagonals the quads shear
    edges = len(np.unique(np.sort(tube.topology().edges_vertices, axis=1), axis=0))
    sheared = replace(framework, bars=framework.bars[:edges], lengths=framework.lengths[:edges])
    assert mechanism(sheared, design).dof > 2
    # a state moved off its constraints is flagged
    moved = design.copy()
    moved[5] += 1e-7
    m = mechanism(framework, moved)
    assert not m.consistent and m.residual > 100 * RESIDUAL_TOL


def _aligned(a: np.ndarray, b: np.ndarray) -> float:
    """Largest distance between points b and the best rigid motion of points a (Kabsch)."""
    ca, cb = a.mean(axis=0), b.mean(axis=0)
    u, _, vt = np.linalg.svd((a - ca).T @ (b - cb))
    d = np.diag([1.0, 1.0, np.sign(np.linalg.det(u @ vt))])
    return float(np.abs((a - ca) @ (u @ d @ vt) + cb - b).max())


def test_following_the_null_space_reproduces_the_constructed_motion(tube):
    framework, _ = Framework.from_structure(tube)
    design = points_of(tube, 90.0)
    curves = len(tube.curves_uv), len(tube.lattice.s)
    toward_flat = (points_of(tube, 89.0) - design).ravel()
    # measured: 90° down to 12°
    path = follow(framework, design, steps=14, step=0.08, toward=toward_flat)
    topology, size = tube.topology(), float(np.ptp(design, axis=0).max())
    creases = (topology.edges_kind == "fold") & (
        topology.vertex_curve[topology.edges_vertices[:, 0]]
        == topology.vertex_curve[topology.edges_vertices[:, 1]]
    )
    angles = []
    for x in path:
        measured = -topology.mesh(x.reshape(curves + (3,))).edges_foldAngle[creases]
        assert np.ptp(measured) < 1e-9  # one fold angle along the creases, as constructed
        angle = float(measured.mean())
        assert _aligned(points_of(tube, angle), x) < 1e-8 * size
        angles.append(angle)
    assert (
        angles[0] == pytest.approx(90.0, abs=1e-9)
        and angles[-1] < 20.0
        and (np.diff(angles) < 0).all()
    )


def test_the_size_of_the_dense_svd_is_bounded(smooth):
    big = Structure.tube(PanelLattice.from_lattice(smooth, 300))
    with pytest.raises(
        InputError,
        match=r"^the mechanism analysis takes a dense SVD .* bounded "
        rf"to {MAX_UNKNOWNS} unknowns .* this structure has 3612 \(1204 vertices\): use fewer "
        r"panels",
    ):
        analyse(big, (90.0,))
    # the certificate analyses what fits: the first panels of the tube, which fold as they do in it
    part = certified_mechanism(big)
    n = CERTIFY_UNKNOWNS // 12 - 1
    assert (
        part.scope == f"the first {n} of the 300 panels of tube 1"
        and part.states[1].unknowns == 12 * (n + 1) <= CERTIFY_UNKNOWNS
    )
    assert [m.dof for m in part.states] == [n + 1, 1, 1]
    # equal to rounding (the prefix products of the rigid motions group otherwise)
    for angle in (0.0, 45.0, 90.0):
        head, whole = part.part.state(angle).vertices, big.state(angle).vertices
        assert np.abs(head - whole[:, : n + 1]).max() <= 16 * EPS * np.abs(whole).max()
    with pytest.raises(
        InputError, match=r"^panels must be in \[1, 300\] for the head of this " r"pattern, got 0$"
    ):
        big.lattice.head(0)


def test_the_certificate_analyses_the_first_tubes_that_fit():
    vault = Vault.from_design(VaultDesign(panels=16, tubes=9))
    part = certified_mechanism(vault.structure)
    k = len(part.part.cells)
    assert part.scope == f"the first {k} of the 9 tubes" and 1 <= k < 9
    more = Structure.from_cells(vault.lattice, vault.structure.cells[: k + 1])
    # one tube more would not fit
    assert part.states[2].unknowns <= CERTIFY_UNKNOWNS < Framework.from_structure(more)[0].unknowns
    assert [m.dof for m in part.states[1:]] == [1, 1]


# -- FOLD files and the command line
# ----------------------------------------------------------------------


def test_fold_file_analysis_agrees_with_the_structure(tmp_path, tube):
    path = write_structure_fold(tmp_path / "tube.fold", tube, fold_angles=[0.0, 45.0, 90.0])
    from_file = analyse_fold(path)
    direct = analyse(tube, (0.0, 45.0, 90.0))
    assert [m.dof for m in from_file] == [m.dof for m in direct] == [9, 1, 1]
    assert [m.unknowns for m in from_file] == [m.unknowns for m in direct]
    for a, b in zip(from_file, direct):
        assert a.consistent and a.gap > 1e10
        assert_allclose(
            a.singular_values, b.singular_values, rtol=1e-8, atol=1e-12 * b.singular_values[0]
        )


def test_command_line_reports_every_frame_and_flags_broken_ones(tmp_path, tube):
    path = write_structure_fold(tmp_path / "tube.fold", tube, fold_angles=[0.0, 90.0])
    ok = run("mechanism", str(path))
    assert ok.returncode == 0, ok.stderr
    assert (
        "fold angle 0°" in ok.stdout
        and "9 internal DOF (nullity 15)" in ok.stdout
        and "1 internal DOF (nullity 7)" in ok.stdout
    )
    payload = json.loads(run("mechanism", str(path), "--json").stdout)
    assert [f["dof"] for f in payload["frames"]] == [9, 1]
    assert (
        payload["frames"][1]["gap"] > 1e10
        and len(payload["frames"][1]["smallest_singular_values"]) == 12
    )
    doc = json.loads(path.read_text())
    doc["file_frames"][1]["vertices_coords"][3][0] += 1e-4  # a frame that breaks its own panels
    path.write_text(json.dumps(doc))
    broken = run("mechanism", str(path))
    assert broken.returncode == 1 and "INCONSISTENT" in broken.stdout.splitlines()[2]
    missing = run("mechanism", str(tmp_path / "nothing.fold"))
    assert missing.returncode == 2 and missing.stderr.count("\n") == 1
    assert (
        run("mechanism", str(path), "--rtol", "2")
        .stderr.strip()
        .endswith("rtol must be in (0, 1), got 2.0")
    )


def test_a_smooth_sampled_tube_is_no_mechanism_of_rigid_panels(tmp_path, smooth):
    """Its folded frames keep the strips' lengths only to O(h²): the analysis says so."""
    coarse = Lattice.from_crease(
        Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.3, 3.0, samples=9), fold_angle=90),
        0.1,
        0.08,
    )
    path = write_structure_fold(
        tmp_path / "smooth.fold", Structure.tube(coarse), fold_angles=[90.0]
    )
    (m,) = analyse_fold(path)
    assert not m.consistent and m.residual > 1e-4


def test_mechanism_says_it_counts_rigid_panels_and_states_no_count_without_a_gap(tmp_path):
    """It printed "2 internal DOF … gap ∞ … INCONSISTENT" and exited 1 on curvefold's own smooth
    tube, whose file check passes."""
    out = tmp_path / "tube"
    assert run("tube", "--samples", "101", "--formats", "fold", "--out", str(out)).returncode == 0
    refused = run("mechanism", str(out / "tube.fold"))
    assert refused.returncode == 2 and "counts the degrees of freedom of rigid panels" in (
        refused.stderr
    )
    doc = json.loads((out / "tube.fold").read_text())
    del doc["curvefold:design"]  # as another tool keeps it: analysed, and judged
    path = tmp_path / "plain.fold"
    path.write_text(json.dumps(doc))
    result = run("mechanism", str(path))
    frames = json.loads(run("mechanism", str(path), "--json").stdout)["frames"]
    lines = result.stdout.splitlines()[1:]
    assert len(lines) == len(frames) and any(not np.isfinite(f["gap"] or np.inf) for f in frames)
    for line, frame in zip(lines, frames):
        independent = frame["nullity"] == max(0, frame["unknowns"] - frame["constraints"])
        assert ("internal DOF" in line) == (frame["gap"] is not None or independent), line
        assert "∞" not in line or "internal DOF" not in line, line
