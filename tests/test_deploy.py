"""Deployment (``curvefold.mechanics.deploy``, ``curvefold deploy``): a closed form, the energy
balance, the rigid path for stiff and soft sheets, the stops and the command line's errors."""

from __future__ import annotations

import csv
import json
from functools import cache

import numpy as np
import pytest

from _cli import run
from curvefold.kernel import InputError
from curvefold.mechanics import MATERIALS, Material
from curvefold.mechanics._deploy import GRAVITY, DeployError, deploy, follow_motion
from curvefold.mechanics._elements import dihedral_angle
from curvefold.mechanics._model import BarHingeModel
from curvefold.vault import Vault

SMALL = {"tubes": 1, "samples": 21}


@cache
def small_vault():
    return Vault.from_design(**SMALL).structure


def hinge_lift(degrees: np.ndarray, rest: float, k: float = 2.0, scale: float = 1.0):
    """A panel (its wing node l, 1 m from the edge) turned up about a hinge on the y axis by φ,
    against its weight (1 kg at l): frames, exact velocities and the rest angle θ(φ_rest)."""
    nodes = np.array([[0.0, 0, 0], [0, 1, 0], [-1, 0.5, 0], [1, 0.5, 0]])
    model = BarHingeModel(
        nodes, [[0, 1], [0, 2], [1, 2], [0, 3], [1, 3]], np.full(5, 1e6), [[0, 1, 2, 3]], [k],
        np.ones(4),
    )  # fmt: skip
    phi = np.radians(degrees)
    frames = np.repeat(nodes[None], len(phi), axis=0)
    frames[:, 3] = np.column_stack([np.cos(phi), np.full_like(phi, 0.5), np.sin(phi)])
    speed = np.zeros_like(frames)
    speed[:, 3] = scale * np.column_stack([-np.sin(phi), 0 * phi, np.cos(phi)])
    at_rest = nodes.copy()
    at_rest[3] = [np.cos(np.radians(rest)), 0.5, np.sin(np.radians(rest))]
    weight = np.zeros((4, 3))
    weight[3, 2] = -GRAVITY
    return model, frames, speed, dihedral_angle(at_rest[None, [0, 1, 2, 3]]), weight


def test_single_hinge_moment_is_spring_plus_weight_times_lever_arm():
    # Q = k (φ − φ_rest) + m g (1 m) cos φ, per radian of φ: every DOF driven, Q exact
    degrees = np.linspace(5.0, 85.0, 17)
    model, frames, speed, rest, weight = hinge_lift(degrees, rest=30.0)
    d = follow_motion(model, rest, frames, np.ones((4, 3), bool), weight, degrees,
                      velocities=speed)  # fmt: skip
    phi = np.radians(degrees)
    exact = 2.0 * (phi - np.radians(30.0)) + GRAVITY * np.cos(phi)
    assert np.allclose(d.actuation, exact, rtol=1e-9, atol=1e-9)
    # the crease's bending stress is zero only at its rest angle
    assert d.max_stress[np.argmin(np.abs(degrees - 30.0))] == pytest.approx(0.0, abs=1e-6)
    # a velocity 1 % off (a motion misread) breaks the closed form
    *_, wrong, _, _ = hinge_lift(degrees, rest=30.0, scale=1.01)
    bad = follow_motion(model, rest, frames, np.ones((4, 3), bool), weight, degrees,
                        velocities=wrong)  # fmt: skip
    assert not np.allclose(bad.actuation, exact, rtol=1e-3)


def test_energy_balance_to_the_steps_second_order():
    # ∫ Q d(2α) = ΔΠ (virtual work): the trapezoid's error falls 4× when the step halves
    errors = []
    for step in (4.0, 2.0):
        d = deploy(small_vault(), MATERIALS["aluminium"], 1e-3, step=step)
        work = np.trapezoid(d.actuation, np.radians(d.angles))
        change = d.energy[-1] - d.energy[0]
        errors.append(abs(work - change) / abs(change))
    assert errors[0] < 1e-2
    assert 3.0 < errors[0] / errors[1] < 5.0


@cache
def panel_tube():
    return Vault.from_design(panels=4, **SMALL).structure


def test_distance_from_the_rigid_path_grows_as_the_sheet_softens():
    # rigid panels fold exactly isometrically; the same creases (k_c fixed), the sheet 10×
    # softer: its sag from the rigid path grows 10× (measured 9.0× near flat, 10.4× at 90°)
    paths = []
    for E in (1e10, 1e9):
        sheet = Material.from_values(E, 0.3, 1000.0)
        d = deploy(panel_tube(), sheet, 1e-3, crease_stiffness=1e-3, step=5.0)
        paths.append(d.relative_distance)
    stiff, soft = paths
    assert stiff.max() < 1e-4
    assert np.all((8.0 < soft / stiff) & (soft / stiff < 12.0))


def test_a_state_not_reached_says_where_and_keeps_the_states():
    with pytest.raises(DeployError) as caught:
        deploy(small_vault(), MATERIALS["polypropylene"], 1e-3, step=10.0, max_iterations=1)
    message = str(caught.value)
    assert "\n" not in message and "2α = " in message
    kept = caught.value.deployment
    assert len(kept.angles) < 9 and len(kept.angles) == len(kept.actuation)


def test_arguments_refused_in_one_line():
    with pytest.raises(InputError, match=r"step must be in \[0.05, 10\] degrees .* got 20"):
        deploy(small_vault(), MATERIALS["aluminium"], 1e-3, step=20.0)
    with pytest.raises(InputError, match="start must be below the design angle 90°, got 95"):
        deploy(small_vault(), MATERIALS["aluminium"], 1e-3, start=95.0)
    with pytest.raises(InputError, match="supports must be one of"):
        deploy(small_vault(), MATERIALS["aluminium"], 1e-3, supports="pinned")
    model, frames, speed, rest, weight = hinge_lift(np.array([10.0]), rest=0.0)
    with pytest.raises(InputError, match="shapes"):
        follow_motion(model, rest, frames[:, :3], np.ones((4, 3), bool), weight, [10.0])


@pytest.mark.parametrize(
    ("flags", "words"),
    [
        (["--step", "0"], "--step 0: step must be in [0.05, 10] degrees"),
        (["--step", "x"], "--step"),
        (["--supports", "pinned"], '--supports pinned: supports must be one of "feet", "foot"'),
        (["--rest-angle", "180"], "--rest-angle 180: rest_angle must be in (0, 180) degrees"),
        (["--start", "0"], "--start 0: start must be in (0, 180) degrees"),
    ],
)
def test_cli_errors_are_one_line_exit_2(flags, words):
    result = run("deploy", *flags)
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and words in result.stderr


def test_cli_writes_csv_and_picture(tmp_path):
    out = tmp_path / "deployed"
    flags = ["--tubes", "1", "--samples", "21", "--step", "10", "--material", "aluminium"]
    result = run("deploy", *flags, "--json", "--out", str(out))
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader((out / "deploy.csv").read_text().splitlines()))
    assert [float(r["fold_angle_deg"]) for r in rows] == [10.0 * i for i in range(1, 10)]
    assert (out / "deploy.png").stat().st_size > 1000
    summary = json.loads(result.stdout)["deployment"]
    assert summary["max_stress_MPa"] == pytest.approx(
        max(float(r["max_stress_MPa"]) for r in rows), rel=1e-6
    )


def test_cli_refuses_a_deployment_over_the_memory_budget_before_work(monkeypatch):
    monkeypatch.setenv("CURVEFOLD_MEMORY_BUDGET", "64M")
    result = run("deploy", "--tubes", "1", "--samples", "21")
    assert result.returncode == 2
    assert "this deployment needs about" in result.stderr and "64 MiB" in result.stderr
    assert result.stderr.count("\n") == 1
