"""Figures: expected axes, labels and artists; measured geometry in the sections; atomic output."""

import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from numpy.testing import assert_allclose

from curvefold import Crease, InputError, Lattice, SpaceCurve, Structure
from curvefold.vault import Vault, VaultDesign

pytest.importorskip("matplotlib")
Image = pytest.importorskip("PIL.Image")

from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402

from curvefold.figures import _motion as motion  # noqa: E402
from curvefold.figures import _plots as plots  # noqa: E402
from curvefold.figures import _views as views  # noqa: E402
from curvefold.io._gif import write_gif  # noqa: E402


@pytest.fixture(scope="module")
def vault() -> Vault:
    return Vault.from_design(VaultDesign(a=0.3, p_xy=0.75, width=0.08, samples=101))


@pytest.fixture(scope="module")
def block() -> Structure:
    curve = SpaceCurve.from_curvature(lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.3 * np.cos(1.5 * s), 3.0, samples=101)
    lattice = Lattice.from_crease(Crease.from_curve(curve, fold_angle=60.0), 0.2, 0.15)
    return Structure.from_cells(lattice, [(0, 0), (0, 1), (1, 0), (1, 1), (2, 1)])


def legend_texts(artist) -> list[str]:
    legends = [artist.get_legend()] if hasattr(artist, "get_legend") and artist.get_legend() else []
    if isinstance(artist, Figure):
        legends = list(artist.legends) + [ax.get_legend() for ax in artist.axes if ax.get_legend()]
    return [t.get_text() for lg in legends for t in lg.get_texts()]


def polys(ax) -> list[PolyCollection]:
    return [c for c in ax.collections if isinstance(c, PolyCollection)]


def check_saved(fig, tmp_path, name="fig", dpi=60):
    """Save PNG + SVG and check both files: size, content, XML, nothing else left behind."""
    before = set(tmp_path.iterdir())
    png, svg = plots.save_figure(fig, tmp_path / name, dpi=dpi)
    assert (png.name, svg.name) == (f"{name}.png", f"{name}.svg")
    assert set(tmp_path.iterdir()) - before == {png, svg}  # no temporary files left
    with Image.open(png) as im:
        im.load()
        assert im.format == "PNG"
        assert_allclose(im.size, fig.get_size_inches() * dpi, atol=1)
        pixels = np.asarray(im.convert("RGB")).reshape(-1, 3)
    assert len(np.unique(pixels, axis=0)) > 30  # not blank
    assert (pixels.min(axis=1) < 200).mean() > 0.01  # some ink on the page
    assert ET.parse(svg).getroot().tag.endswith("svg")
    return png, svg


# -- regression domain -------------------------------------------------------------------------


def test_regression_domain(vault, tmp_path):
    fig = plots.plot_regression_domain(vault.lattice, vault.structure.cells)
    ax = fig.axes[0]
    assert "u" in ax.get_xlabel() and "w_L" in ax.get_xlabel()
    assert "v" in ax.get_ylabel() and "w_R" in ax.get_ylabel()
    assert ax.get_aspect() == 1.0
    domain = [p for p in ax.patches if isinstance(p, Polygon)]
    assert len(domain) == 1
    # the shaded polygon is the valid set: its vertices are on the boundary (margin ≈ 0) or the box
    xy = domain[0].get_xy()
    margin = vault.lattice.domain.margin(xy)
    box = ax.get_xlim()[1]
    assert np.all((np.abs(margin) < 1e-9) | (np.abs(xy).max(axis=1) > box - 1e-9))
    assert any(isinstance(c, LineCollection) for c in ax.collections)  # limiting lines, coloured by t
    cells = polys(ax)[0]
    assert len(cells.get_paths()) == len(vault.structure.cells)
    labels = legend_texts(ax)
    assert any("fold" in t for t in labels) and any("seam" in t for t in labels)
    assert not any("past regression" in t for t in labels)
    # every stacked corner lies inside the window
    assert np.abs(vault.structure.curves_uv).max() < box
    check_saved(fig, tmp_path)


def test_regression_domain_marks_cells_past_regression(vault):
    n = vault.max_tubes
    fig = plots.plot_regression_domain(vault.lattice, [(j, j) for j in range(n + 2)])
    assert any("past regression" in t for t in legend_texts(fig.axes[0]))
    fig = plots.plot_regression_domain(vault.lattice)  # no cells: the domain alone
    assert len(polys(fig.axes[0])) == 0
    with pytest.raises(InputError, match="box must be"):
        plots.plot_regression_domain(vault.lattice, box=-1.0)
    with pytest.raises(InputError, match="cells must be"):
        plots.plot_regression_domain(vault.lattice, [(0.5, 0.0)])


# -- widths -----------------------------------------------------------------------------------------


def test_width_proportion(vault, tmp_path):
    fig = plots.plot_width_proportion(vault.lattice)
    top, bottom = fig.axes
    assert "model units" in top.get_ylabel()
    assert "t" in bottom.get_xlabel()
    wl = top.lines[0].get_ydata()
    assert_allclose(wl, vault.lattice.width_left)
    notes = [t.get_text() for t in bottom.texts]
    assert f"{vault.design.p_xy:.4g} at t = 0" in notes
    assert f"{vault.p_xz:.4g} at t = ½" in notes  # the measured proportion at the apex is p_xz
    check_saved(fig, tmp_path)


# -- sections: the pantograph ------------------------------------------------------------------------


def test_sections_are_pantographs(vault, tmp_path):
    angles = (30.0, 60.0, 90.0)
    fig = plots.plot_sections(vault, (0.0, 0.5), fold_angles=angles)
    assert len(fig.axes) == 2
    assert "feet" in fig.axes[0].get_title() and "apex" in fig.axes[1].get_title()
    assert all("model units" in ax.get_xlabel() for ax in fig.axes)
    labels = legend_texts(fig)
    assert [t for t in labels if t.startswith("2α")] == ["2α = 30°", "2α = 60°", "2α = 90° (design)"]
    lat = vault.lattice
    for ax, t in zip(fig.axes, (0.0, 0.5)):
        i = int(np.argmin(np.abs(lat.t - t)))
        wl, wr = lat.width_left[i], lat.width_right[i]
        collections = polys(ax)
        assert len(collections) == len(angles)
        for coll, f in zip(collections, angles):
            cells = np.array([p.vertices[:4] for p in coll.get_paths()])  # (K, 4, 2), corners 1–4
            assert len(cells) == len(vault.structure.cells)
            side12 = np.linalg.norm(cells[:, 1] - cells[:, 0], axis=1)  # corner 1 → 2: along v, width w_R
            side14 = np.linalg.norm(cells[:, 3] - cells[:, 0], axis=1)  # corner 1 → 4: along u, width w_L
            assert_allclose(side12, wr, rtol=1e-9)
            assert_allclose(side14, wl, rtol=1e-9)
            d1, d2 = cells[:, 1] - cells[:, 0], cells[:, 3] - cells[:, 0]
            area = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
            assert_allclose(area, wl * wr * np.sin(np.radians(f)), rtol=1e-9)  # w_L w_R sin 2α
    check_saved(fig, tmp_path)


def test_sections_of_structures_and_states(block):
    fig = plots.plot_sections(block, (0.0, 0.3, 1.0))
    assert len(fig.axes) == 3 and "feet" not in fig.axes[0].get_title()
    fig = plots.plot_sections(block.state(45.0), (0.5,))
    assert any("45° (design)" in t for t in legend_texts(fig))
    with pytest.raises(InputError, match="t_values"):
        plots.plot_sections(block, (1.5,))
    with pytest.raises(InputError, match="fold_angle"):
        plots.plot_sections(block, fold_angles=(180.0,))
    with pytest.raises(InputError, match="expected a Vault, Structure or State"):
        plots.plot_sections(block.lattice)


# -- 3D views ------------------------------------------------------------------------------------------


def test_motion_strip(vault, tmp_path):
    angles = (0.0, 30.0, 60.0, 90.0)
    fig = views.plot_motion_strip(vault, angles)
    assert len(fig.axes) == len(angles)
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == ["2α = 0°", "2α = 30°", "2α = 60°", "2α = 90° (design)"]
    spans = np.array([[np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim())] for ax in fig.axes])
    assert_allclose(spans, np.broadcast_to(spans[0], spans.shape))  # one scale in every panel
    notes = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert "ends off the ground: 0.000 model units" in notes  # at the design angle
    lift = vault.lift_off(np.array(angles))
    assert f"ends off the ground: {lift[1].max():.3f} model units" in notes
    for ax in fig.axes:
        assert [p for p in ax.patches if isinstance(p, Polygon)]  # the ground plane
        assert len(polys(ax)) == 1
    check_saved(fig, tmp_path)


def test_vault_view(vault, tmp_path):
    fig = views.plot_vault(vault)
    ax = fig.axes[0]
    assert "a = 0.3" in ax.get_title() and "9 tubes" in ax.get_title() and "90°" in ax.get_title()
    labels = legend_texts(ax)
    assert any(t.startswith("fold") for t in labels) and any(t.startswith("seam") for t in labels)
    (coll,) = polys(ax)
    edges = coll.get_edgecolors()
    red, blue = (np.array(Image.new("RGB", (1, 1), c).getpixel((0, 0))) / 255 for c in (plots.KIND_COLORS["fold"], plots.KIND_COLORS["seam"]))
    assert np.isclose(edges[:, :3], red, atol=1e-3).all(axis=1).any()
    assert np.isclose(edges[:, :3], blue, atol=1e-3).all(axis=1).any()
    faces = coll.get_facecolors()
    grey = faces[faces[:, 3] > 0][:, :3]
    assert np.ptp(grey[:, 0]) > 0.1  # shaded by the normal
    assert np.allclose(grey[:, 0], grey[:, 1], atol=0.02)  # grey
    check_saved(fig, tmp_path)
    # drawing into given axes returns their figure
    host = Figure()
    axes = host.subplots(1, 2)
    assert views.plot_vault(vault, angle=45.0, ax=axes[1]) is host
    assert "45°" in axes[1].get_title()


def test_figures_draw_the_polygons_of_their_scenes(vault, block):
    from curvefold.figures import state_scene, vault_scene

    for fig, scene in (
        (views.plot_vault(vault, angle=60.0), vault_scene(vault, colors=plots.KIND_COLORS, angle=60.0)),
        (views.plot_structure(block, fold_angle=30.0), state_scene(block.state(30.0), colors=plots.KIND_COLORS)),
    ):
        ax = fig.axes[0]
        (coll,) = polys(ax)
        drawn = [p.vertices for p in coll.get_paths()]
        assert len(drawn) == len(scene.paths) > 1000
        assert all(np.array_equal(a, b) for a, b in zip(drawn, scene.paths))  # the same polygons, in the same order
        assert_allclose(coll.get_facecolors(), scene.fill)
        assert_allclose(coll.get_edgecolors(), scene.stroke)
        assert_allclose(coll.get_linewidths(), scene.widths)
        ground = [p.get_xy()[:4] for p in ax.patches if isinstance(p, Polygon)]
        assert_allclose(ground, [] if scene.ground is None else [scene.ground])
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        lo, hi = scene.box
        assert x0 < lo[0] and hi[0] < x1 and y0 < lo[1] and hi[1] < y1  # all in view


def test_structure_and_crease_views(block, tmp_path):
    fig = views.plot_structure(block)
    assert "Cellular block of 5 cells" in fig.axes[0].get_title()
    assert any("junction" in t for t in legend_texts(fig.axes[0]))
    check_saved(fig, tmp_path, "block")
    fig = views.plot_structure(Structure.tube(block.lattice), fold_angle=30.0)
    assert fig.axes[0].get_title().startswith("Tube") and "30°" in fig.axes[0].get_title()
    fig = views.plot_crease(block.lattice.crease)
    assert len(fig.axes) == 3
    assert any("κ(s)" in t for t in legend_texts(fig)) and "angle" in fig.axes[2].get_ylabel()
    check_saved(fig, tmp_path, "crease")


def test_motion_gif(vault, block, tmp_path):
    path = motion.write_motion_gif(vault, tmp_path / "fold.gif", angles=np.linspace(0, 90, 5), size=(200, 150))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fold.gif"]
    with Image.open(path) as im:
        assert im.format == "GIF" and im.size == (200, 150)
        assert im.n_frames == 5 + 3  # forward, then back without repeating the ends
        im.seek(4)
        assert len(np.unique(np.asarray(im.convert("RGB")).reshape(-1, 3), axis=0)) > 10
    motion.write_motion_gif(block, tmp_path / "block.gif", angles=(20.0, 60.0), size=(120, 100))
    with pytest.raises(InputError, match="anchor"):
        motion.write_motion_gif(vault, tmp_path / "x.gif", anchor="apex")


def test_the_frames_are_drawn_by_figures_and_encoded_by_io(vault, tmp_path):
    """motion_frames draws RGB frames at one scale; write_gif only encodes what it is given, with one palette."""
    frames = motion.motion_frames(vault, angles=(0.0, 45.0, 90.0), size=(160, 120))
    assert [(f.mode, f.size) for f in frames] == [("RGB", (160, 120))] * 3
    assert not np.array_equal(np.asarray(frames[0]), np.asarray(frames[2]))  # flat and folded differ
    path = write_gif(tmp_path / "plain.gif", frames, frame_seconds=0.5)
    with Image.open(path) as im:
        assert im.n_frames == 3 and im.info["duration"] == 500 and im.info["loop"] == 0
        im.seek(2)
        # one palette of COLOURS from the last frame: that frame comes back close (quantised, not dithered)
        back = np.asarray(im.convert("RGB"), float)
    assert np.abs(back - np.asarray(frames[2], float)).mean() < 4.0
    with pytest.raises(InputError, match=r"frame_seconds must be in \[0\.01, 10\] seconds, got 0\.0"):
        write_gif(tmp_path / "x.gif", frames, frame_seconds=0.0)
    with pytest.raises(InputError, match="frames must all have one size"):
        write_gif(tmp_path / "x.gif", [frames[0], frames[1].resize((80, 60))])
    with pytest.raises(InputError, match="at least one image"):
        write_gif(tmp_path / "x.gif", [])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plain.gif"]


# -- saving -----------------------------------------------------------------------------------------


def test_save_figure_formats_and_reproducible_svg(vault, tmp_path):
    fig = plots.plot_width_proportion(vault.lattice)
    (pdf,) = plots.save_figure(fig, tmp_path / "w", formats=("pdf",))
    assert pdf.read_bytes().startswith(b"%PDF")
    # the same figure built twice gives the same SVG bytes (no date, fixed ids)
    a = plots.save_figure(plots.plot_width_proportion(vault.lattice), tmp_path / "a", formats=("svg",))[0].read_bytes()
    b = plots.save_figure(plots.plot_width_proportion(vault.lattice), tmp_path / "b", formats=("svg",))[0].read_bytes()
    assert a == b and b"<dc:date>" not in a
    with pytest.raises(InputError, match="formats must be"):
        plots.save_figure(fig, tmp_path / "w", formats=("bmpx",))
    with pytest.raises(InputError, match="dpi must be"):
        plots.save_figure(fig, tmp_path / "w", dpi=0)


def test_save_figure_is_atomic(vault, tmp_path, monkeypatch):
    fig = plots.plot_width_proportion(vault.lattice)
    target = tmp_path / "w.png"
    target.write_bytes(b"old")

    def failing(fname, **kwargs):
        with open(fname, "wb") as f:
            f.write(b"partial")
        raise OSError("disk full")

    monkeypatch.setattr(fig, "savefig", failing)
    with pytest.raises(OSError, match="disk full"):
        plots.save_figure(fig, tmp_path / "w", formats=("png",))
    assert target.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["w.png"]


def test_plots_leave_pyplot_alone():
    code = (
        "import sys\n"
        "from curvefold.vault import Vault, VaultDesign\n"
        "from curvefold.figures import _plots as plots, _views as views\n"
        "v = Vault.from_design(VaultDesign(samples=41))\n"
        "views.plot_vault(v); plots.plot_sections(v); plots.plot_regression_domain(v.lattice, v.structure.cells)\n"
        "assert 'matplotlib.pyplot' not in sys.modules, 'pyplot imported'\n"
    )
    subprocess.run([sys.executable, "-W", "error", "-c", code], check=True, timeout=120)
