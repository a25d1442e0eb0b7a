"""Scenes without matplotlib: painter's order, colours by crease kind, SVG, no matplotlib import."""

import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from curvefold import Crease, InputError, Lattice, SpaceCurve, Structure
from curvefold.figures._scene import (
    RIM_COLOR,
    Scene,
    View,
    render_strips,
    rgba,
    state_scene,
    vault_scene,
)
from curvefold.vault import Vault, VaultDesign

COLORS = {"fold": "#d62728", "seam": "#1f77b4", "junction": "#7b3294", "edge": "#4d4d4d"}
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def vault() -> Vault:
    return Vault.from_design(VaultDesign(a=0.3, p_xy=0.75, width=0.08, tubes=3, samples=41))


@pytest.fixture(scope="module")
def scene(vault) -> Scene:
    return vault_scene(vault, colors=COLORS, segments=20)


def test_rendering_a_vault_to_svg_needs_no_matplotlib():
    code = (
        "import sys\nfrom curvefold.figures import vault_scene\nfrom curvefold.vault import "
        "Vault, VaultDesign\nsvg = vault_scene(Vault.from_design(VaultDesign(tubes=2, "
        "samples=41)), colors={'fold': '#ff0000', 'seam': '#0000ff', 'edge': "
        "'#000000'}).svg()\nassert svg.count('<polygon') > 100, svg[:200]\nloaded = "
        "sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib')\nassert not "
        "loaded, loaded\n"
    )
    subprocess.run([sys.executable, "-W", "error", "-c", code], check=True, timeout=120)


def test_scene_holds_every_strip_and_crease_segment_in_painters_order(vault, scene):
    tubes, segments = len(vault.structure.cells), 20
    strips = tubes * 4 * segments  # four strips a tube, one quad per segment
    curves = len(np.unique(vault.structure.cell_curves))
    roles = scene.roles.tolist()
    assert roles.count("strip") == strips == len(scene.strips)
    assert sum(roles.count(k) for k in ("fold", "seam")) == curves * segments
    assert roles.count("rim") == tubes * 4 * 2  # both end rulings of every strip
    assert (
        len(scene.paths) == len(roles) == len(scene.fill) == len(scene.stroke) == len(scene.widths)
    )
    # colours by kind: strips grey and shaded, creases in their kind's colour, no fill
    is_strip = scene.roles == "strip"
    assert np.ptp(scene.fill[is_strip, 0]) > 0.1  # shaded by the normal
    assert_allclose(scene.fill[is_strip, 0], scene.fill[is_strip, 1], atol=0.02)  # grey
    for kind in ("fold", "seam"):
        assert_allclose(
            scene.stroke[scene.roles == kind],
            np.broadcast_to(rgba(COLORS[kind]), (roles.count(kind), 4)),
        )
    assert_allclose(
        scene.stroke[scene.roles == "rim"],
        np.broadcast_to(rgba(RIM_COLOR), (roles.count("rim"), 4)),
    )
    assert (scene.fill[~is_strip, 3] == 0).all()
    # the ground is under the whole vault and inside the box
    assert scene.ground.shape == (4, 2)
    lo, hi = scene.box
    assert (scene.ground >= lo - 1e-12).all() and (scene.ground <= hi + 1e-12).all()
    assert scene.span == pytest.approx(
        float(np.ptp(vault.vertices.reshape(-1, 3), axis=0).max()), rel=1e-12
    )
    with pytest.raises(ValueError, match="read-only"):
        scene.fill[0, 0] = 0.0
    with pytest.raises(ValueError, match="read-only"):
        scene.paths[0][0, 0] = 0.0


def test_a_scene_draws_its_paths_points_held_at_once(scene):
    """A rendered scene's points, held in one array for drawing, are its paths', in order; a
    scene of paths given one by one gathers the same."""
    points, sizes = scene.flat
    assert sizes.tolist() == [len(p) for p in scene.paths]
    assert np.array_equal(points, np.concatenate(scene.paths))
    with pytest.raises(ValueError, match="read-only"):
        points[0, 0] = 0.0
    plain = Scene(
        tuple(np.array(p) for p in scene.paths),
        scene.roles,
        scene.fill,
        scene.stroke,
        scene.widths,
        scene.span,
        scene.ground,
    )
    assert np.array_equal(plain.flat[0], points) and np.array_equal(plain.flat[1], sizes)
    assert np.array_equal(plain.strips, scene.strips) and np.array_equal(plain.box, scene.box)
    # damaged: paths out of order
    shuffled = Scene(
        scene.paths[::-1], scene.roles, scene.fill, scene.stroke, scene.widths, scene.span
    )
    assert not np.array_equal(shuffled.flat[0], points)


def test_far_strips_are_drawn_first_and_creases_after_their_nearest_strip():
    # two flat strips facing the viewer, one behind the other; a crease on each
    view = View(azim=0.0, elev=0.0)  # looking along −x: screen right is +y, depth is +x
    t = np.linspace(0.0, 1.0, 3)
    line = np.stack([np.zeros_like(t), t, np.zeros_like(t)], axis=1)
    up = np.array([0.0, 0.0, 1.0])
    # on screen the near one is 0.5 higher
    far, near = np.array([-1.0, 0.0, 0.0]), np.array([1.0, 0.2, 0.5])
    vertices = np.stack([line + far, line + far + up, line + near, line + near + up])
    scene = render_strips(
        vertices, np.array([[0, 1], [2, 3]]), ["fold", "edge", "seam", "edge"], view, colors=COLORS
    )
    roles = scene.roles.tolist()
    last_far_strip = max(
        i for i, p in enumerate(scene.paths) if roles[i] == "strip" and p[:, 1].min() < 0.25
    )
    first_near_strip = min(
        i for i, p in enumerate(scene.paths) if roles[i] == "strip" and p[:, 1].min() > 0.25
    )
    assert last_far_strip < first_near_strip
    # the far crease hides behind the near strip
    assert max(i for i, r in enumerate(roles) if r == "fold") < first_near_strip
    assert min(i for i, r in enumerate(roles) if r == "seam") > first_near_strip
    # reversing the view turns the order around
    back = render_strips(
        vertices,
        np.array([[0, 1], [2, 3]]),
        ["fold", "edge", "seam", "edge"],
        View(azim=180.0, elev=0.0),
        colors=COLORS,
    )
    assert back.roles.tolist().index("seam") < back.roles.tolist().index("fold")


def test_svg_is_xml_with_the_scene_in_projected_units(scene):
    text = scene.svg(pixels=600)
    assert text == scene.svg(pixels=600)  # deterministic
    root = ET.fromstring(text)
    assert root.tag == f"{SVG}svg" and root.get("width") == "600"
    lo, hi = scene.box
    pad = 0.02 * float(np.max(hi - lo))
    x, y, w, h = (float(v) for v in root.get("viewBox").split())
    assert_allclose(
        [x, y, w, h],
        [lo[0] - pad, -hi[1] - pad, hi[0] - lo[0] + 2 * pad, hi[1] - lo[1] + 2 * pad],
        rtol=1e-6,
    )
    assert float(root.get("height")) == pytest.approx(600 * h / w, rel=1e-6)
    elements = list(root.iter())
    polygons = [e for e in elements if e.tag == f"{SVG}polygon"]
    lines = [e for e in elements if e.tag == f"{SVG}line"]
    assert [p.get("class") for p in polygons[1:]] == ["strip"] * len(scene.strips)
    assert polygons[0].get("class") == "ground"
    assert len(lines) == len(scene.paths) - len(scene.strips)
    # the same paths in the same order (y turned down), to the 7 digits written
    drawn = [
        np.array([list(map(float, xy.split(","))) for xy in p.get("points").split()])
        for p in polygons[1:]
    ]
    assert_allclose(np.array(drawn) * [1, -1], scene.strips, atol=1e-6 * float(np.max(hi - lo)))
    segments = np.array(
        [[[float(e.get(f"{a}1")), float(e.get(f"{a}2"))] for a in "xy"] for e in lines]
    ).transpose(0, 2, 1)
    assert_allclose(
        segments * [1, -1],
        np.array([p for p in scene.paths if len(p) == 2]),
        atol=1e-6 * float(np.max(hi - lo)),
    )
    for kind in ("fold", "seam", "rim"):
        colours = {e.get("stroke") for e in lines if e.get("class") == kind}
        assert colours == {COLORS.get(kind, RIM_COLOR)}
    assert {e.get("class") for e in lines} == {"fold", "seam", "rim"}


def test_structures_and_bad_arguments():
    curve = SpaceCurve.from_curvature(1.0, 0.2, 3.0, samples=61)
    block = Structure.from_cells(
        Lattice.from_crease(Crease.from_curve(curve, fold_angle=60.0), 0.2, 0.15),
        [(0, 0), (0, 1), (1, 0)],
    )
    scene = state_scene(block.state(30.0), colors=COLORS, segments=10)
    assert scene.ground is None and "junction" in set(scene.roles)
    assert (
        len(ET.fromstring(scene.svg()).findall(f"{SVG}g/{SVG}polygon"))
        == len(scene.strips)
        == 3 * 4 * 10
    )
    assert replace(scene, ground=np.zeros((4, 2))).ground.flags.writeable is False
    with pytest.raises(InputError, match=r"a colour must be written '#rrggbb', got 'red'"):
        rgba("red")
    with pytest.raises(
        InputError,
        match=r"colors must give a colour for the crease kind 'fold' "
        r"or for 'edge', got one for \['seam'\]",
    ):
        state_scene(block.state(30.0), colors={"seam": "#0000ff"})
    with pytest.raises(InputError, match=r"pixels must be an integer in \[16, 16384\], got 0"):
        scene.svg(pixels=0)
    with pytest.raises(InputError, match=r"margin must be in \[0, 1\], got -1"):
        scene.svg(margin=-1)
