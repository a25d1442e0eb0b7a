"""The registry of design kinds: a kind registered here, nowhere in curvefold, reaches every front.

``ring`` is a short tube on a circle, with a section of its own (``[ring]``). Registered with
:func:`~curvefold.app._kinds.register_kind` in this file alone, it is a subcommand of the command
line (its help, its flags, its ``--json``), the memory budget estimates it, and the designer's API
gives its schema and its preview; once removed, a design of it is refused in one line.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
from dataclasses import dataclass, replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _cli import run
from curvefold.app import (
    BuiltStructure,
    DesignKind,
    Section,
    deregister_kind,
    design_kind,
    design_kinds,
    register_kind,
)
from curvefold.app._budget import estimate
from curvefold.app._build import build
from curvefold.app._design import (
    SCHEMA,
    SECTIONS_OF_KIND,
    VaultParams,
    default_design,
    design_from_dict,
)
from curvefold.app.cli import main
from curvefold.geometry import Crease, Lattice, SpaceCurve, Structure
from curvefold.kernel import InputError
from curvefold.kernel._validate import Spec


@dataclass(frozen=True)
class RingParams:
    """``[ring]``: the circle's radius, the arc the tube covers, its widths and fold angle."""

    radius: float
    arc: float
    width: float
    fold_angle: float


RING = Section.of(
    "ring",
    RingParams,
    Spec(
        "radius",
        "real",
        2.0,
        "(0, 100]",
        "model units",
        help="radius of the circle of curve 1",
        label="radius",
    ),
    Spec(
        "arc",
        "real",
        60.0,
        "(0, 180]",
        "degrees",
        help="angle of the circle the tube covers",
        label="arc",
    ),
    Spec(
        "width",
        "real",
        0.2,
        "(0, 10]",
        "model units",
        help="width on both sides of curve 1",
        label="width",
    ),
    Spec(
        "fold_angle",
        "real",
        90.0,
        "(0, 180)",
        "degrees",
        help="fold angle 2 alpha",
        label="fold angle",
    ),
)


def build_ring(design, like) -> BuiltStructure:
    """A single tube around an arc of a circle: κ = 1/radius, τ = 0."""
    ring = design.params(RingParams)
    length = ring.radius * math.radians(ring.arc)
    curve = SpaceCurve.from_curvature(1.0 / ring.radius, 0.0, length, samples=design.samples)
    crease = Crease.from_curve(curve, fold_angle=ring.fold_angle)
    return BuiltStructure(
        design, crease, Structure.tube(Lattice.from_crease(crease, ring.width, ring.width))
    )


RING_KIND = DesignKind(
    "ring",
    (RING,),
    build_ring,
    strips=lambda design: 4,
    crease_length=lambda values: values["ring"]["radius"] * math.radians(values["ring"]["arc"]),
    help="a short tube on a circle",
    description="Build a short tube around an arc of a circle.",
    formats_as="tube",
)


@pytest.fixture
def ring():
    register_kind(RING_KIND)
    try:
        yield RING_KIND
    finally:
        deregister_kind("ring")


def test_a_registered_kind_is_in_the_schema_and_builds(ring):
    assert design_kind("ring") is ring and design_kinds()[-1] is ring
    assert SECTIONS_OF_KIND["ring"] == ("ring",) and list(SCHEMA["ring"]) == [
        "radius",
        "arc",
        "width",
        "fold_angle",
    ]
    assert SCHEMA[""]["kind"].choices == ("vault", "tube", "block", "crease", "ring")
    design = design_from_dict({"kind": "ring", "samples": 41, "ring": {"radius": 3.0}})
    assert design.params(RingParams) == RingParams(
        3.0, 60.0, 0.2, 90.0
    ) and design.ring is design.params(RingParams)
    assert design.vault is None and design.to_dict()["ring"]["radius"] == 3.0
    built = build(design)
    points = built.crease.curve.points
    assert_allclose(
        np.linalg.norm(points[:, :2] - points[0, :2] - [0.0, 3.0], axis=1), 3.0, rtol=1e-6
    )  # on its circle
    with pytest.raises(
        InputError, match=r"section \[ring\] is used by kind 'ring', not by kind 'tube'"
    ):
        design_from_dict({"kind": "tube", "ring": {}})


def helped(*argv: str) -> str:
    """What ``curvefold *argv --help`` prints."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit, match="0"):
        main([*argv, "--help"])
    return out.getvalue()


def test_a_registered_kind_is_a_subcommand_with_help_and_json(ring, tmp_path):
    assert "a short tube on a circle" in helped()
    shown = " ".join(helped("ring").split())  # as the terminal's width wraps it
    for text in (
        "Build a short tube around an arc of a circle.",
        "--radius RADIUS",
        "--arc ARC",
        "./curvefold-ring",
    ):
        assert text in shown, text
    done = run("ring", "--json", "--samples", "41", "--arc", "45", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    payload = json.loads(done.stdout)
    assert (
        payload["kind"] == "ring"
        and payload["design"]["ring"]["arc"] == 45.0
        and payload["cells"] == [[0, 0]]
    )
    assert payload["certificate"] and all(c["passed"] for c in payload["certificate"])
    refused = run("ring", "--arc", "270", "--json", cwd=tmp_path)
    assert (
        refused.returncode == 2 and "--arc 270: arc must be in (0, 180] degrees" in refused.stderr
    )


def test_the_budget_estimates_a_registered_kind(ring):
    design = design_from_dict({"kind": "ring", "samples": 1001})
    found = estimate(design, files=False)
    assert found.strip_samples == 4 * 1001 and found.largest == "geometry"
    assert estimate(design.overrides(samples=2001), files=True).total > found.total


def test_the_designer_api_gives_a_registered_kinds_schema_and_preview(ring):
    from curvefold.app.designer import api, jobs

    schema = api.schema()
    assert schema["kinds"]["ring"] == ["ring"] and schema["optional"]["ring"] == []
    assert [spec["name"] for spec in schema["sections"]["ring"]] == [
        "radius",
        "arc",
        "width",
        "fold_angle",
    ]
    plan = jobs.plan("preview", "ring", {"samples": "41", "radius": "1.5"})
    content, media, _ = jobs.run(*plan.args)
    preview = json.loads(content)
    assert (
        media == "application/json"
        and preview["kind"] == "ring"
        and preview["design"]["ring"]["radius"] == 1.5
    )
    assert preview["numbers"]["cells"] == 1 and preview["motion"]["ground"] is False
    with pytest.raises(InputError, match="unknown parameter 'span' for a ring"):
        api.read_request("ring", {"span": "2"})


def test_an_unregistered_kind_is_refused_in_one_line(tmp_path):
    assert "ring" not in {kind.name for kind in design_kinds()}
    (tmp_path / "ring.toml").write_text('kind = "ring"\n[ring]\nradius = 2.0\n')
    for argv in (("ring", "--json"), ("tube", "ring.toml")):
        r = run(*argv, cwd=tmp_path)
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 2 and len(lines) == 1 and r.stdout == "", r.stderr
    assert "invalid choice: 'ring'" in run("ring", cwd=tmp_path).stderr
    assert (
        'ring.toml: kind must be one of "vault", "tube", "block", "crease", got string \'ring\''
        in lines[0]
    )
    with pytest.raises(
        InputError, match=r"^unknown kind 'ring' \(allowed: vault, tube, block, crease\)$"
    ):
        design_kind("ring")
    from curvefold.app.designer import api

    with pytest.raises(InputError, match="unknown kind 'ring'"):
        api.parameters("ring")


def test_a_kind_is_registered_once_and_shares_a_section_only_as_it_is():
    with pytest.raises(InputError, match="kind 'tube' is registered already"):
        register_kind(design_kind("tube"))
    other_tube = Section.of("tube", RingParams, *RING.specs.values())
    with pytest.raises(
        InputError, match=r"section \[tube\] of kind 'ring' differs from kind 'tube''s"
    ):
        register_kind(replace(RING_KIND, sections=(other_tube,)))
    output = Section.of("output", RingParams, *RING.specs.values())
    with pytest.raises(InputError, match=r"kind 'ring': section \[output\] is every kind's"):
        register_kind(replace(RING_KIND, sections=(output,)))
    with pytest.raises(InputError, match=r"optional section \[wind\] must be one of material"):
        register_kind(replace(RING_KIND, optional=("wind",)))
    assert "ring" not in {kind.name for kind in design_kinds()}
    shared = register_kind(
        replace(RING_KIND, name="arc", sections=(design_kind("tube").sections[0], RING))
    )  # [curve], as it is
    try:
        assert SECTIONS_OF_KIND["arc"] == ("curve", "ring")
    finally:
        deregister_kind(shared.name)
    tube = default_design("tube")
    assert tube.design_kind is design_kind("tube")
    with pytest.raises(InputError, match="<defaults>: a tube design has no VaultParams"):
        tube.params(VaultParams)


def test_a_kind_says_which_of_its_keys_replace_others():
    """A crease's ``alpha`` and ``beta_right`` are alternatives (its kind's ``alternatives``): the
    one an override gives drops the other, and with ``alpha`` the fold angle follows from it."""
    by_alpha = default_design("crease").overrides(alpha="30 + s")
    assert (by_alpha.crease.beta_right, by_alpha.crease.fold_angle) == (None, 60.0)
    by_beta = by_alpha.overrides(beta_right=80.0, fold_angle=50.0)
    crease = by_beta.crease
    assert (crease.alpha, crease.beta_right, crease.fold_angle) == (None, 80.0, 50.0)
    with pytest.raises(InputError, match="give beta_right or alpha, not both"):
        by_alpha.overrides(alpha="30", beta_right=80.0)


def test_the_designer_schema_says_which_kinds_stand_and_whose_targets_are_whose():
    from curvefold.app.designer import api

    schema = api.schema()
    assert schema["grounded"] == ["vault"]
    targets = {(t["design_kind"], t["name"]) for t in schema["targets"]}
    assert targets == {("vault", "span"), ("vault", "rise"), ("vault", "p_xz")}
