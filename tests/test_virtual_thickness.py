"""The paper's "virtual thickness" (benchmarks/virtual_thickness.py) on a reduced case: the plain
shell model against closed forms and OpenSees, each check failing on its damage, and the
headline ordering: the vault of thin sheets far stiffer than a plain shell of its mass, the
thickness a plain shell needs to match it following the shell's t³ law."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from curvefold.mechanics import MATERIALS, BarHingeModel, static_response

BENCHMARKS = Path(__file__).parents[1] / "benchmarks"
PP = MATERIALS["polypropylene"]
#: Reduced: the vault on 201 samples, 2 elements across; the shell on two coarse meshes.
REDUCED = ("--samples", "101", "--across", "2")
MESHES = ((24, 6), (48, 12), (96, 24))


@pytest.fixture(scope="module")
def vt():
    sys.path.insert(0, str(BENCHMARKS))  # its helpers (_bench)
    spec = importlib.util.spec_from_file_location(
        "virtual_thickness", BENCHMARKS / "virtual_thickness.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    yield module
    sys.path.remove(str(BENCHMARKS))


def test_the_plate_strip_is_the_closed_form_and_bends_as_t_cubed(vt):
    # pinned on two edges under its own weight: w = 5 q L⁴ / 384 D; the bar-and-hinge error is
    # measured 0.8 / N² (N quads along the span): 7.8e-4 at 32
    deflection, closed = vt.plate_strip(PP, 0.003, 1.6, 0.85, 32, 8)
    assert abs(deflection / closed - 1) < 1e-3
    assert abs(deflection / closed - 1 - 0.8 / 32**2) < 1e-5
    # own weight: q ∝ t, D ∝ t³, so w ∝ t⁻²
    thicker, _ = vt.plate_strip(PP, 0.006, 1.6, 0.85, 32, 8)
    assert thicker / deflection == pytest.approx(0.25, rel=1e-9)


def test_the_plate_strip_check_fails_on_a_damaged_sheet(vt):
    # the bending hinges across the span replaced by creases of half the sheet's stiffness:
    # the strip deflects about twice the closed form
    profile = np.column_stack([np.linspace(0.0, 1.6, 3), np.zeros(3)])
    mesh = vt.barrel(profile, 0.85, 32, 8)
    kinds = np.asarray(mesh.edges_kind).astype(object)
    x = np.asarray(mesh.vertices_coords)
    ends = x[np.asarray(mesh.edges_vertices)]
    across = (np.abs(ends[:, 0, 1] - ends[:, 1, 1]) < 1e-12) & (kinds == "ruling")
    kinds[across] = "fold"
    damaged = type(mesh)(
        vertices_coords=mesh.vertices_coords,
        edges_vertices=mesh.edges_vertices,
        edges_assignment=mesh.edges_assignment,
        edges_foldAngle=mesh.edges_foldAngle,
        faces_vertices=mesh.faces_vertices,
        edges_kind=kinds.tolist(),
        faces_group=mesh.faces_group,
    )
    t, span = 0.003, 1.6
    k = 0.5 * PP.bending_stiffness(t) / (span / 32)
    model = BarHingeModel.from_mesh(damaged, PP, t, crease_stiffness=k)
    y = model.nodes[:, 1]
    edge = (np.abs(y) < 1e-9) | (np.abs(y - span) < 1e-9)
    weight = np.zeros_like(model.nodes)
    weight[:, 2] = -model.masses * vt.G
    result, _ = static_response(model, weight, np.repeat(edge[:, None], 3, axis=1))
    closed = 5 * PP.density * t * vt.G * span**4 / (384 * PP.bending_stiffness(t))
    assert -result.displacements[:, 2].min() / closed > 1.5


def test_richardson_recovers_a_known_limit_and_order(vt):
    f = [1.0 + 0.3 * h**1.5 for h in (1.0, 0.5, 0.25)]
    limit, order, error = vt.richardson(f)
    assert limit == pytest.approx(1.0, abs=1e-12) and order == pytest.approx(1.5, abs=1e-12)
    assert error == pytest.approx(0.3 * 0.25**1.5, rel=1e-9)


def test_the_barrel_shell_converges_and_agrees_with_opensees(vt):
    pytest.importorskip("openseespy")
    profile, depth = vt.arch(201)
    shell = vt.converged_shell(profile, depth, PP, 0.003, MESHES)
    # measured: 1.5e-4 (own weight), 2.3e-3 (point load), 2.5e-5 (buckling) on the finest
    assert max(shell["errors"].values()) < 0.01
    ours = shell["runs"][1]
    theirs = vt.opensees_barrel(vt.barrel(profile, depth, *MESHES[1]), PP, 0.003, ours["node"])
    # ASDShellQ4 on the same 48 × 12 quads: 2.1 % (own weight) and 0.8 % (point load) apart
    assert ours["deflection"] == pytest.approx(theirs[0], rel=0.05)
    assert ours["point_deflection"] == pytest.approx(theirs[1], rel=0.05)
    # a shell 10 % too thin deflects about 23 % more: the agreement fails on it
    thin = vt.shell_response(vt.barrel(profile, depth, *MESHES[1]), PP, 0.0027)
    assert thin["deflection"] / theirs[0] - 1 > 0.05


def test_the_vault_of_thin_sheets_is_far_stiffer_than_a_plain_shell_of_its_mass(vt):
    result = vt.measure(
        plywood=(0.004, 0.01), meshes=MESHES, extra=REDUCED, thin_panels=False, opensees=False
    )
    vault, shell, stiff = result["rows"][:3]
    panels = result["rows"][3:]
    # same mass (to the coarse mesh's area: 0.1 %); the full case: the vault 203× stiffer, its
    # buckling factor 60× the shell's (which does not stand: λ < 1)
    assert shell["mass"] == pytest.approx(vault["mass"], rel=2e-3)
    assert vault["stiffness"] > 100 * shell["stiffness"]
    assert vault["buckling_factor"] > 10 * shell["buckling_factor"]
    assert shell["buckling_factor"] < 1 < vault["buckling_factor"]
    # the equivalent plain shell: its stiffness is the vault's, its thickness the cube root law
    # of a bending shell (measured exponent 2.98)
    assert stiff["stiffness"] == pytest.approx(vault["stiffness"], rel=0.01)
    ratio = vault["stiffness"] / shell["stiffness"]
    cube_root = result["mass_thickness"] * ratio ** (1 / 3)
    assert result["stiffness_thickness"] == pytest.approx(cube_root, rel=0.03)
    assert 2.8 < result["shell_exponent"] < 3.05
    # thick panels: stiffness nearly ∝ t (the tubes' depth, not the panels', carries bending)
    assert 0.9 < result["panel_exponent"] < 1.5
    assert all(p["stiffness"] > vault["stiffness"] for p in panels)
