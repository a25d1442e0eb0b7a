"""Figures: expected axes, labels and artists; measured geometry in the sections; atomic output."""

import io
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
from PIL import ImageSequence  # noqa: E402

from curvefold.figures import _motion as motion  # noqa: E402
from curvefold.figures import _plot_data as plot_data  # noqa: E402
from curvefold.figures import _plots as plots  # noqa: E402
from curvefold.figures import _views as views  # noqa: E402
from curvefold.io._gif import COLOURS, write_gif  # noqa: E402


@pytest.fixture(scope="module")
def vault() -> Vault:
    return Vault.from_design(VaultDesign(a=0.3, p_xy=0.75, width=0.08, samples=101))


@pytest.fixture(scope="module")
def block() -> Structure:
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.3 * np.cos(1.5 * s), 3.0, samples=101
    )
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
    # limiting lines, coloured by t
    assert any(isinstance(c, LineCollection) for c in ax.collections)
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


# -- widths
# -----------------------------------------------------------------------------------------


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


# -- sections: the pantograph
# ------------------------------------------------------------------------


def test_sections_are_pantographs(vault, tmp_path):
    angles = (30.0, 60.0, 90.0)
    fig = plots.plot_sections(vault, (0.0, 0.5), fold_angles=angles)
    assert len(fig.axes) == 2
    assert "feet" in fig.axes[0].get_title() and "apex" in fig.axes[1].get_title()
    assert all("model units" in ax.get_xlabel() for ax in fig.axes)
    labels = legend_texts(fig)
    assert [t for t in labels if t.startswith("2α")] == [
        "2α = 30°",
        "2α = 60°",
        "2α = 90° (design)",
    ]
    lat = vault.lattice
    for ax, t in zip(fig.axes, (0.0, 0.5)):
        i = int(np.argmin(np.abs(lat.t - t)))
        wl, wr = lat.width_left[i], lat.width_right[i]
        collections = polys(ax)
        assert len(collections) == len(angles)
        for coll, f in zip(collections, angles):
            cells = np.array([p.vertices[:4] for p in coll.get_paths()])  # (K, 4, 2), corners 1–4
            assert len(cells) == len(vault.structure.cells)
            # corner 1 → 2: along v, width w_R
            side12 = np.linalg.norm(cells[:, 1] - cells[:, 0], axis=1)
            # corner 1 → 4: along u, width w_L
            side14 = np.linalg.norm(cells[:, 3] - cells[:, 0], axis=1)
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


# -- 3D views
# ------------------------------------------------------------------------------------------


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
    red, blue = (
        np.array(Image.new("RGB", (1, 1), c).getpixel((0, 0))) / 255
        for c in (plot_data.KIND_COLORS["fold"], plot_data.KIND_COLORS["seam"])
    )
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
        (
            views.plot_vault(vault, angle=60.0),
            vault_scene(vault, colors=plot_data.KIND_COLORS, angle=60.0),
        ),
        (
            views.plot_structure(block, fold_angle=30.0),
            state_scene(block.state(30.0), colors=plot_data.KIND_COLORS),
        ),
    ):
        ax = fig.axes[0]
        (coll,) = polys(ax)
        drawn = [p.vertices for p in coll.get_paths()]
        assert len(drawn) == len(scene.paths) > 1000
        # the same polygons, in the same order
        assert all(np.array_equal(a, b) for a, b in zip(drawn, scene.paths))
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
    path = motion.write_motion_gif(
        vault, tmp_path / "fold.gif", angles=np.linspace(0, 90, 5), size=(200, 150)
    )
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
    """motion_frames draws RGB frames at one scale; write_gif only encodes what it is given, with
    one palette."""
    frames = motion.motion_frames(vault, angles=(0.0, 45.0, 90.0), size=(160, 120))
    assert [(f.mode, f.size) for f in frames] == [("RGB", (160, 120))] * 3
    # flat and folded differ
    assert not np.array_equal(np.asarray(frames[0]), np.asarray(frames[2]))
    path = write_gif(tmp_path / "plain.gif", frames, frame_seconds=0.5)
    with Image.open(path) as im:
        assert im.n_frames == 3 and im.info["duration"] == 500 and im.info["loop"] == 0
        im.seek(2)
        # one palette of COLOURS from the last frame: that frame comes back close (quantised, not
        # dithered)
        back = np.asarray(im.convert("RGB"), float)
    assert np.abs(back - np.asarray(frames[2], float)).mean() < 4.0
    palette = frames[-1].quantize(colors=COLOURS, method=Image.Quantize.MAXCOVERAGE)
    on_palette = [
        np.asarray(f.quantize(palette=palette, dither=Image.Dither.NONE).convert("RGB"))
        for f in frames
    ]
    with Image.open(path) as im:  # every frame decodes to exactly its pixels on that palette
        decoded = [np.asarray(im.convert("RGB")) for _ in ImageSequence.Iterator(im)]
    assert all(np.array_equal(d, f) for d, f in zip(decoded, on_palette, strict=True))
    # the first frame on a palette of its own: not what was written
    own = np.asarray(frames[0].quantize(colors=COLOURS).convert("RGB"))
    assert not np.array_equal(decoded[0], own)
    for name, given, played in (
        ("bounce", frames, [0, 1, 2, 1]),
        ("still", [frames[1], frames[1], frames[2]], [1, 1, 2]),
    ):
        # each frame is stored once: played backward, a frame is the same as played forward; a frame
        # that repeats the one before too
        with Image.open(write_gif(tmp_path / f"{name}.gif", given, bounce=name == "bounce")) as im:
            decoded = [np.asarray(im.convert("RGB")) for _ in ImageSequence.Iterator(im)]
        assert len(decoded) == len(played) and all(
            np.array_equal(d, on_palette[k]) for d, k in zip(decoded, played)
        )
    with pytest.raises(
        InputError, match=r"frame_seconds must be in \[0\.01, 10\] seconds, got " r"0\.0"
    ):
        write_gif(tmp_path / "x.gif", frames, frame_seconds=0.0)
    with pytest.raises(InputError, match="frames must all have one size"):
        write_gif(tmp_path / "x.gif", [frames[0], frames[1].resize((80, 60))])
    with pytest.raises(InputError, match="at least one image"):
        write_gif(tmp_path / "x.gif", [])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bounce.gif", "plain.gif", "still.gif"]


# -- saving
# -----------------------------------------------------------------------------------------


def test_save_figure_formats_and_reproducible_svg(vault, tmp_path):
    fig = plots.plot_width_proportion(vault.lattice)
    (pdf,) = plots.save_figure(fig, tmp_path / "w", formats=("pdf",))
    assert pdf.read_bytes().startswith(b"%PDF")
    # the same figure built twice gives the same SVG bytes (no date, fixed ids)
    a = plots.save_figure(
        plots.plot_width_proportion(vault.lattice), tmp_path / "a", formats=("svg",)
    )[0].read_bytes()
    b = plots.save_figure(
        plots.plot_width_proportion(vault.lattice), tmp_path / "b", formats=("svg",)
    )[0].read_bytes()
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
        "import sys\nfrom curvefold.vault import Vault, VaultDesign\nfrom curvefold.figures "
        "import _plots as plots, _views as views\nv = "
        "Vault.from_design(VaultDesign(samples=41))\nviews.plot_vault(v); "
        "plots.plot_sections(v); plots.plot_regression_domain(v.lattice, "
        "v.structure.cells)\nassert 'matplotlib.pyplot' not in sys.modules, 'pyplot "
        "imported'\n"
    )
    subprocess.run([sys.executable, "-W", "error", "-c", code], check=True, timeout=120)


# -- pictures drawn without matplotlib ------------------------------------------------------------

from curvefold.figures import _pictures as pictures  # noqa: E402
from curvefold.figures import _raster as raster  # noqa: E402


def test_nice_ticks_are_round_and_inside():
    for lo, hi in ((-11.7, 11.7), (0.058, 0.083), (-0.02, 1.02), (0.64, 1.48), (3e-5, 7e-5)):
        ticks = raster.nice_ticks(lo, hi, 7)
        assert lo <= ticks[0] and ticks[-1] <= hi and 3 <= len(ticks) <= 8
        step = np.diff(ticks)
        assert_allclose(step, step[0])
        mantissa = step[0] / 10 ** np.floor(np.log10(step[0]))
        assert np.isclose(mantissa, [1, 2, 5]).any()
    assert raster.tick_label(-5.0, 5.0) == "−5" and raster.tick_label(0.065, 0.005) == "0.065"


def test_viridis_and_inks_match_matplotlib_and_pillow():
    import matplotlib
    from PIL import ImageDraw

    t = np.linspace(0, 1, 41)
    # 11 stops, linear between
    assert np.abs(raster.viridis(t) - matplotlib.colormaps["viridis"](t)[:, :3]).max() < 0.06
    draw = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    colours = np.array([[0, 0, 0], [1, 0.5, 0.25], [0.2, 0.9, 1]])
    assert raster.inks(colours) == [
        draw.draw.draw_ink(tuple(int(round(255 * v)) for v in c)) for c in colours
    ]


def test_dashes_follow_the_polyline():
    """Each dash runs from its start to its end along the line (interpolated there), through the
    vertices between."""
    rng = np.random.default_rng(5)
    line = np.cumsum(rng.normal(size=(60, 2)), axis=0)
    line[20] = line[19]  # a vertex twice
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(line, axis=0), axis=1))])
    dashes = raster._dashed(line, 3.0, 1.5)
    assert len(dashes) == len(np.arange(0.0, s[-1], 4.5))
    for a, dash in zip(np.arange(0.0, s[-1], 4.5), dashes):
        b = min(a + 3.0, s[-1])
        inside = line[(s > a) & (s < b)]
        expected = np.concatenate(
            [
                [[np.interp(a, s, line[:, 0]), np.interp(a, s, line[:, 1])]],
                inside,
                [[np.interp(b, s, line[:, 0]), np.interp(b, s, line[:, 1])]],
            ]
        )
        assert np.array_equal(dash, expected)
    # damaged: the line run backwards
    assert not np.array_equal(raster._dashed(line[::-1], 3.0, 1.5)[0], dashes[0])
    assert [d.tolist() for d in raster._dashed(line, 0.0, 0.0)] == [line.tolist()]


def test_wide_lines_have_pillows_joints_where_they_bend():
    """A bend gets Pillow's round joint (the same pixels); a smooth curve's joints, notches under
    a quarter pixel, are left out (under one of its pixels in a hundred differs); a
    translucent line is drawn as Pillow draws it."""
    from PIL import ImageDraw

    def drawn(points, ink, joints):
        image = Image.new("RGB", (120, 120), "white")
        draw = ImageDraw.Draw(image, "RGBA")
        if joints:
            draw.line(points.ravel().tolist(), fill=ink, width=9, joint="curve")
        else:
            raster._line(draw, points, ink, 9)
        return np.asarray(image, int)

    bend = np.array([[10.0, 100.0], [60.0, 20.0], [110.0, 100.0]])
    assert np.array_equal(drawn(bend, (0, 0, 255, 255), False), drawn(bend, (0, 0, 255, 255), True))
    t = np.linspace(0, np.pi, 200)
    arc = np.stack([60 + 45 * np.cos(t), 100 - 80 * np.sin(t)], axis=-1)
    with_joints = drawn(arc, (0, 0, 255, 255), True)
    differ = np.abs(drawn(arc, (0, 0, 255, 255), False) - with_joints).max(axis=-1)
    assert (differ > 0).sum() <= 0.01 * (with_joints[..., 0] < 255).sum()  # of the line's pixels
    assert np.array_equal(drawn(arc, (0, 0, 255, 128), False), drawn(arc, (0, 0, 255, 128), True))
    without = Image.new("RGB", (120, 120), "white")
    # damaged: no joint at the bend
    ImageDraw.Draw(without, "RGBA").line(bend.ravel().tolist(), fill=(0, 0, 255, 255), width=9)
    assert not np.array_equal(np.asarray(without, int), drawn(bend, (0, 0, 255, 255), True))


def test_png_bytes_hold_the_pictures_pixels(tmp_path):
    """The unfiltered PNG writer: Pillow reads back every pixel; a damaged byte of its data is
    refused."""
    rng = np.random.default_rng(3)
    pixels = rng.integers(0, 256, (37, 53, 3), dtype=np.uint8)
    pixels[10:20] = [236, 230, 218]  # flat runs, as in the pictures
    path = raster.write_png(Image.fromarray(pixels), tmp_path / "x.png")
    with Image.open(path) as im:
        assert (im.format, im.mode, im.size) == ("PNG", "RGB", (53, 37))
        assert np.array_equal(np.asarray(im), pixels)
    assert np.array_equal(
        np.asarray(
            Image.open(io.BytesIO(raster.png_bytes(Image.fromarray(pixels).convert("RGBA"))))
        ),
        pixels,
    )
    damaged = bytearray(path.read_bytes())
    damaged[60] ^= 0xFF  # inside the image data
    with pytest.raises(OSError, match="broken data stream"):
        Image.open(io.BytesIO(bytes(damaged))).load()


def test_the_domain_polygon_is_scipys_halfspace_intersection(vault, block):
    spatial = pytest.importorskip("scipy.spatial")
    for domain in (vault.lattice.domain, block.lattice.domain):
        for box in (0.5, 3.0, 11.7, 100.0):
            poly = domain.polygon(box=box)
            halfspaces = np.concatenate(
                [
                    np.stack([domain.a, domain.b, -np.ones_like(domain.a)], axis=1),
                    np.array([[1, 0, -box], [-1, 0, -box], [0, 1, -box], [0, -1, -box]], float),
                ]
            )
            pts = spatial.HalfspaceIntersection(halfspaces, np.zeros(2)).intersections
            reference = pts[spatial.ConvexHull(pts).vertices]
            # every vertex of one lies on the boundary of the other, to rounding
            for a, b in ((poly, reference), (reference, poly)):
                edges = np.roll(b, -1, axis=0) - b
                t = np.clip(
                    np.einsum("pek,ek->pe", a[:, None] - b[None], edges)
                    / np.einsum("ek,ek->e", edges, edges),
                    0,
                    1,
                )
                gap = np.linalg.norm(
                    a[:, None] - (b[None] + t[..., None] * edges[None]), axis=2
                ).min(axis=1)
                assert gap.max() < 1e-10 * box
            assert (poly @ np.stack([domain.a, domain.b])).max() < 1 + 1e-12


def test_regression_domain_picture_shades_the_valid_set(vault, tmp_path):
    plot = plot_data.domain_plot(vault.lattice, vault.structure.cells)
    picture = pictures.regression_domain_picture(vault.lattice, vault.structure.cells)
    assert picture.size == (960, 810) and picture.mode == "RGB"
    rng = np.random.default_rng(7)
    uv = rng.uniform(-plot.box, plot.box, (600, 2))
    cells = (uv[:, None] >= plot.cells.min(axis=1)[None] - 0.1) & (
        uv[:, None] <= plot.cells.max(axis=1)[None] + 0.1
    )
    free = ~cells.all(axis=2).any(axis=1)  # away from the cells drawn over the domain
    near = np.abs(vault.lattice.domain.margin(uv)) > 0.03  # and from its edge and the lines
    left, top, right, bottom = 100, 42, 790, 732
    legend = (uv[:, 0] < -plot.box + 0.45 * 2 * plot.box) & (
        uv[:, 1] > plot.box - 0.2 * 2 * plot.box
    )
    axes = (np.abs(uv) < 0.02 * plot.box).any(axis=1)
    keep = free & near & ~legend & ~axes
    uv, valid = uv[keep], vault.lattice.domain.contains(uv[keep])

    def green(image: np.ndarray) -> np.ndarray:
        px = (
            np.stack(
                [
                    left + (uv[:, 0] + plot.box) / (2 * plot.box) * (right - left),
                    top + (plot.box - uv[:, 1]) / (2 * plot.box) * (bottom - top),
                ],
                axis=-1,
            )
            .round()
            .astype(int)
        )
        rgb = image[px[:, 1], px[:, 0]].astype(int)
        return np.abs(rgb - np.array([0xCF, 0xE8, 0xCF])).max(axis=1) < 16

    shaded = green(np.asarray(picture))
    assert valid.any() and (~valid).any()
    # green where Eq. 18 holds, not where it fails (a limiting line may cross a point)
    assert (shaded == valid).mean() > 0.97
    # a picture of a damaged domain (the valid set mirrored) fails the same check
    damaged = pictures.regression_domain_picture(vault.lattice, vault.structure.cells).transpose(
        Image.Transpose.FLIP_LEFT_RIGHT
    )
    assert (green(np.asarray(damaged)) == valid).mean() < 0.9
    (path,) = pictures.write_picture(picture, tmp_path / "domain")
    with Image.open(path) as im:
        assert im.format == "PNG" and im.size == picture.size
        pixels = np.asarray(im.convert("RGB")).reshape(-1, 3)
    assert len(np.unique(pixels, axis=0)) > 30 and (pixels.min(axis=1) < 200).mean() > 0.01


def ink_columns(picture) -> np.ndarray:
    """Whether each column of a picture holds a dark pixel."""
    return (np.asarray(picture.convert("L")) < 128).any(axis=0)


def test_pictures_are_drawn_from_the_figures_content(vault, block, tmp_path):
    for picture, size in (
        (pictures.width_proportion_picture(vault.lattice), (960, 780)),
        (pictures.sections_picture(vault), (1440, 720)),
        (pictures.vault_picture(vault), (1050, 780)),
        (pictures.motion_strip_picture(vault), (1065, 1020)),
        (pictures.structure_picture(block), (960, 780)),
        (pictures.sections_picture(block, (0.0, 0.3, 1.0)), (2130, 720)),
    ):
        assert picture.size == size
        pixels = np.asarray(picture).reshape(-1, 3)
        assert len(np.unique(pixels, axis=0)) > 100  # not blank: shaded, antialiased
        dark = ink_columns(picture)
        assert (
            dark[: size[0] // 3].any() and dark[-size[0] // 3 :].any()
        )  # drawn across the picture
        # nothing cut at the sides
        assert (np.asarray(picture)[:, :2] > 250).all() and (
            np.asarray(picture)[:, -2:] > 250
        ).all()
    # the vault's strips are shaded grey, its creases red and blue as in the figure
    rgb = np.asarray(pictures.vault_picture(vault)).reshape(-1, 3).astype(int)
    assert ((rgb[:, 0] > 200) & (rgb[:, 1] < 60) & (rgb[:, 2] < 60)).sum() > 500
    assert ((rgb[:, 2] > 200) & (rgb[:, 0] < 60) & (rgb[:, 1] < 60)).sum() > 500
    grey = rgb[(np.ptp(rgb, axis=1) < 6) & (rgb.max(axis=1) < 200) & (rgb.max(axis=1) > 60)]
    assert len(grey) > 20000 and np.ptp(grey[:, 0]) > 60


def test_the_width_plot_and_its_picture_agree(vault):
    plot = plot_data.width_plot(vault.lattice)
    assert_allclose(plot.ratio, vault.lattice.width_right / vault.lattice.width_left)
    assert [text for text, _ in plot.notes] == [
        f"{vault.design.p_xy:.4g} at t = 0",
        f"{vault.p_xz:.4g} at t = ½",
    ]
    assert_allclose(plot.mark_ratio, [[0.0, vault.design.p_xy], [0.5, vault.p_xz]], rtol=1e-9)
    assert plots.mathtext(plot.top_curves[0][0]) == "$w_L$(t)"


def test_singular_values_picture(tmp_path):
    from curvefold.analysis._mechanism import Mechanism  # noqa: F401

    class State:  # the fields the plot reads
        def __init__(self, label, values, tolerance):
            self.label, self.singular_values, self.tolerance = (
                label,
                np.asarray(values, float),
                tolerance,
            )
            self.dof, self.nullity, self.gap = 1, 7, 1e8

    states = [
        State("flat", np.logspace(0, -16, 30), 1e-10),
        State("design", np.logspace(0, -15, 30), 1e-10),
    ]
    plot = plot_data.singular_values_plot(states)
    assert_allclose(plot.values[0][-1], 1.0) and plot.labels[0].startswith(
        "flat: 1 internal DOF (7 null), gap 1.0e+08"
    )
    picture = pictures.singular_values_picture(states)
    assert (
        picture.size == (960, 690)
        and len(np.unique(np.asarray(picture).reshape(-1, 3), axis=0)) > 30
    )
    with pytest.raises(InputError, match="at least one"):
        pictures.singular_values_picture([])


def test_the_pictures_job_imports_neither_matplotlib_nor_scipy(tmp_path):
    code = (
        "import sys\nfrom pathlib import Path\nfrom curvefold.app import default_design\nfrom "
        "curvefold.app._build import build\nfrom curvefold.app import _products as "
        "products\nbuilt = build(default_design('vault'))\njobs = "
        "dict(products.jobs(built, built.design.output.formats))\nbefore = "
        f"{{m for m in sys.modules if m.startswith('scipy')}}\nfiles = "
        f"jobs['pictures'](Path({str(tmp_path)!r})) + jobs['folding "
        f"GIF'](Path({str(tmp_path)!r}))\nassert 'matplotlib' not in sys.modules, "
        "'matplotlib imported'\nassert "
        f"{{m for m in sys.modules if m.startswith('scipy')}} == before, 'scipy "
        "imported'\nprint(sorted(f.name for f in files))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == [
        "['folding-motion.png',",
        "'folding.gif',",
        "'regression-domain.png',",
        "'sections.png',",
        "'vault.png',",
        "'width-proportion.png']",
    ]


@pytest.mark.parametrize(("snow", "unit"), [(0.0, "µm"), (1000.0, "mm")])
def test_the_deflection_is_shown_in_the_unit_it_reads_in_and_the_modes_have_a_colour_bar(
    snow, unit
):
    """A deflection under a millimetre in µm, past it in mm (not "1.98e+03 µm"), the title and
    the colour bar alike; the modes' picture carries its colour bar too."""
    from curvefold.figures._mechanics import plot_deflection, plot_modes
    from curvefold.mechanics import SelfWeight, Snow, analyse_load

    loads = (SelfWeight(), Snow(snow)) if snow else None  # 1 kPa on 0.2 mm: 93 mm
    r = analyse_load(Vault.from_design(tubes=1, samples=21), thickness=2e-4, loads=loads)
    largest = r.static.max_displacement
    assert (largest < 1e-3) == (unit == "µm")
    fig = plot_deflection(r, magnification=1.0)
    title = fig.axes[0].get_title()
    scale = 1e6 if unit == "µm" else 1e3
    assert f"(largest {largest * scale:.3g} {unit})" in title, title
    assert fig.axes[1].get_ylabel() == f"displacement ({unit})"
    modes = plot_modes(r, amplitude=0.05, count=2)
    assert len(modes.axes) == 3 and modes.axes[2].get_ylabel() == "displacement (mm)"
