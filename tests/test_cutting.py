"""Crease patterns for cutting machines: layers by operation, colour conventions, perforated
creases, kerf compensation, DXF linetype generation and extents.

Read back by readers we did not write: ``xml.etree`` for SVG, ``ezdxf`` for DXF (layers,
polyline flags, header), ``pdfplumber`` for PDF; geometry is checked against ``shapely``'s
own offsetting.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import replace

import numpy as np
import pytest
from shapely.geometry import LineString, Point, Polygon

from _sheets import tube_sheets
from curvefold.io._cutters import CUTTERS, LEGEND_LAYER, Cutter, aci, cutter, layer_name
from curvefold.io._cutting import MITRE_LIMIT, offset_outline, perforation_dashes, prepare_layout
from curvefold.io._legend import LEGEND
from curvefold.io._pattern import DEFAULT_LAYERS, layout_sheets, write_dxf, write_pdf, write_svg
from curvefold.kernel import InputError

SVG = "{http://www.w3.org/2000/svg}"
INK = "{http://www.inkscape.org/namespaces/inkscape}"


@pytest.fixture(scope="module")
def tube_layout():
    return layout_sheets(tube_sheets())


# --------------------------------------------------------------------------------------
# layers and conventions


def test_layer_names_say_the_operation_and_are_valid_dxf_names():
    from ezdxf.lldxf.validator import is_valid_layer_name

    names = [layer_name(k) for k in (*DEFAULT_LAYERS, "rulings", "legend")] + [
        layer_name(k, perforated=True) for k in ("mountain", "valley")
    ]
    assert names[:7] == [
        "reference - glue (not cut)",
        "score - seam",
        "score - valley",
        "score - mountain",
        "cut",
        "engrave - labels",
        "engrave - rulings",
    ]
    assert names[7:] == [LEGEND_LAYER, "perforate - mountain", "perforate - valley"]
    assert all(is_valid_layer_name(n) for n in names)
    assert not is_valid_layer_name("score: mountain")  # why the names use " - "
    with pytest.raises(InputError, match="layer must be one of"):
        layer_name("fold")


def test_a_convention_never_draws_anything_else_in_its_cut_colour():
    for c in CUTTERS.values():
        others = {k: v for k, v in c.colours.items() if k != "cut"}
        assert c.colours["cut"] not in others.values(), c.name
    bad = dict(CUTTERS["laser"].colours, legend=CUTTERS["laser"].colours["cut"])
    with pytest.raises(ValueError, match="only the cut layer may be drawn in the cut colour"):
        Cutter("bad", "", bad)
    with pytest.raises(
        InputError, match=r"cutter must be one of print, laser, service, got " r"'glowforge'"
    ) as err:
        cutter("glowforge")
    assert err.value.parameter == "cutter"
    # the laser convention's layers use exactly the six basic colours and black (colour-mapping
    # drivers match exactly); its footer's dark grey matches none of them
    basic = {"#ff0000", "#00ff00", "#0000ff", "#00ffff", "#ffff00", "#ff00ff", "#000000"}
    laser = dict(CUTTERS["laser"].colours)
    legend = laser.pop("legend")
    assert set(laser.values()) == basic and legend not in basic
    assert [
        aci(CUTTERS["laser"].colours[k])
        for k in ("cut", "glue", "valley", "seam", "mountain", "rulings", "labels", "legend")
    ] == [1, 2, 3, 4, 5, 6, 7, 8]
    assert all(c.source for name, c in CUTTERS.items() if name != "print")


def _contrast(code: str) -> float:
    """WCAG 2 contrast ratio of a colour against white paper (4.5 for readable small text)."""
    rgb = np.array([int(code[k : k + 2], 16) / 255.0 for k in (1, 3, 5)])
    linear = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    return 1.05 / (float(linear @ [0.2126, 0.7152, 0.0722]) + 0.05)


@pytest.mark.parametrize("name", list(CUTTERS))
def test_every_layer_has_its_conventions_colour_and_the_legend_shows_them(
    tmp_path, tube_layout, name
):
    """Each layer in its colour; the footer's text and scale bar in the reference colour, dark
    enough to read on paper (WCAG contrast at least 4.5, as the laser's former yellow, 1.07, was
    not) but the service convention's, whose yellow its service reads as "not processed"; each
    legend sample in the colour of the layer it names (the seam name S1 in the labels'), with the
    colour's code written beside it for a cutting machine and not for print; the same in the DXF,
    the samples' entities in their own colours and the text in the layer's."""
    ezdxf = pytest.importorskip("ezdxf")
    layout = replace(tube_layout, cutter=name)
    colours = CUTTERS[name].colours
    (svg,) = write_svg(tmp_path / "t.svg", layout)
    groups = {g.get(f"{INK}label"): g for g in ET.parse(svg).getroot().findall(f"{SVG}g")}
    for key in DEFAULT_LAYERS:
        assert re.findall(r"#[0-9a-f]{6}", groups[layer_name(key)].get("style")) == [
            colours[key]
        ], key
    legend = groups[LEGEND_LAYER]
    ink = colours["legend"]
    assert re.findall(r"fill:(#[0-9a-f]{6})", legend.get("style")) == [ink]
    assert (_contrast(ink) >= 4.5) is (name != "service") and _contrast("#ffff00") < 1.1
    shapes = [el for el in legend if el.tag in (f"{SVG}polygon", f"{SVG}polyline")]
    bar, samples = shapes[0], shapes[1:]
    assert re.findall(r"#[0-9a-f]{6}", bar.get("style")) == [ink]
    texts = [t for t in legend if t.tag == f"{SVG}text"]
    # the note, then each entry's words after its sample (S1 and its words for the labels)
    words = [t.text for t in texts[1:] if t.text != "S1"]
    named = [
        "cut",
        "mountain",
        "valley",
        "seam",
        "glue",
    ]  # what the tube's page draws, in legend order
    expected = [
        f"{LEGEND[k]} {colours[k]}" if name != "print" else LEGEND[k] for k in (*named, "labels")
    ]
    assert sorted(words) == sorted(expected)
    drawn = {
        LEGEND[k]: colours[k] for k in ("cut", "mountain", "valley", "seam", "glue", "rulings")
    }
    painted = [re.findall(r"#[0-9a-f]{6}", el.get("style"))[0] for el in samples]
    assert sorted(painted) == sorted(drawn[LEGEND[k]] for k in named)
    (seam,) = [t for t in texts if t.text == "S1"]
    assert seam.get("style") == f"fill:{colours['labels']}"
    assert all(t.get("style") is None for t in texts if t is not seam)  # the layer's ink
    doc = ezdxf.readfile(write_dxf(tmp_path / "t.dxf", layout))
    for key in (*DEFAULT_LAYERS, "legend"):
        entry = doc.layers.get(layer_name(key))
        assert "#{:02x}{:02x}{:02x}".format(*entry.rgb) == colours[key], key
        assert entry.color == aci(colours[key]), key
    entities = doc.modelspace().query(f'*[layer=="{LEGEND_LAYER}"]')
    own = sorted(
        "#{:02x}{:02x}{:02x}".format(*e.rgb)
        for e in entities
        if e.dxftype() != "TEXT" and e.dxf.hasattr("true_color")
    )
    assert own == sorted(drawn[LEGEND[k]] for k in named)
    plain = [e for e in entities if e.dxftype() == "TEXT" and e.dxf.text != "S1"]
    assert plain and all(e.dxf.color == 256 and not e.dxf.hasattr("true_color") for e in plain)


def test_the_footer_stays_in_its_band_whatever_its_rows():
    """Longer legend entries (with their colours) wrap into more rows; on a narrow page the rows
    close up rather than run into the margin, where printers do not print."""
    from _sheets import vault_sheets
    from curvefold.io._legend import page_footer
    from curvefold.io._pattern import LAYERS

    for page in ("A5", "A4", (120.0, 200.0)):
        layout = layout_sheets(vault_sheets(4), page=page)
        for i in range(len(layout.pages)):
            foot = page_footer(layout, i, LAYERS)
            boxes = (
                [t.corners() for t in foot.texts]
                + [points for _, points in foot.samples]
                + [foot.bar]
            )
            lo = min(float(b[:, 1].min()) for b in boxes)
            hi = max(float(b[:, 1].max()) for b in boxes)
            assert layout.margin - 1e-9 <= lo and hi <= layout.margin + layout.footer + 1e-9, (
                page,
                i,
                lo,
                hi,
            )


def test_the_pdf_draws_nothing_but_the_outlines_and_the_cut_sample_in_the_cut_colour(
    tmp_path, tube_layout
):
    """In the laser convention, red is the sheets' outlines and the legend's cut sample (a line
    in the footer band, clear of every sheet); the footer's text and bar are its dark grey."""
    pdfplumber = pytest.importorskip("pdfplumber")
    layout = replace(tube_layout, cutter="laser")
    mm = 72 / 25.4
    red = (1.0, 0.0, 0.0)
    with pdfplumber.open(write_pdf(tmp_path / "t.pdf", layout)) as doc:
        page = doc.pages[0]
        # pdfplumber's top runs down from the page's top
        band = page.height - (layout.margin + layout.footer) * mm
        footer = [o for o in page.curves + page.rects + page.lines + page.chars if o["top"] >= band]
        cut = [o for o in page.curves + page.lines if tuple(o.get("stroking_color") or ()) == red]

    def paint(o):
        return (
            o["non_stroking_color"]
            if o["object_type"] == "char" or o.get("fill")
            else o["stroking_color"]
        )

    grey = (0x59 / 255,) * 3
    chars = [o for o in footer if o["object_type"] == "char"]
    dark = [o for o in chars if tuple(paint(o)) == pytest.approx(grey, abs=1e-3)]
    # every character but the seam name that samples the labels, in black
    assert len(dark) > 100 and "".join(o["text"] for o in chars if o not in dark) == "S1"
    # the two sheets' outlines, and the cut sample in the footer
    inside = [o for o in cut if o["top"] < band]
    (sample,) = [o for o in cut if o["top"] >= band]
    assert len(inside) == 2 and sample["width"] / mm == pytest.approx(8.0, abs=1e-3)


# --------------------------------------------------------------------------------------
# DXF: linetype generation, extents in every file


def test_dxf_polylines_generate_their_linetype_across_vertices_and_the_header_holds_the_extents(
    tmp_path, tube_layout
):
    """One page starts at (0, 0, 0): ezdxf left $EXTMIN/$EXTMAX at its 1e20 defaults there."""
    ezdxf = pytest.importorskip("ezdxf")
    from ezdxf import bbox
    from ezdxf.lldxf.const import LWPOLYLINE_PLINEGEN

    assert len(tube_layout.pages) == 1
    doc = ezdxf.readfile(write_dxf(tmp_path / "tube.dxf", tube_layout))
    msp = doc.modelspace()
    polylines = msp.query("LWPOLYLINE")
    assert len(polylines) > 10 and all(p.dxf.flags & LWPOLYLINE_PLINEGEN for p in polylines)
    assert doc.header["$PLINEGEN"] == 1
    extents = bbox.extents(msp)
    assert (
        doc.header["$EXTMIN"][:2] == (0.0, 0.0)
        and doc.header["$EXTMAX"][:2] == tube_layout.page_size
    )
    assert tuple(extents.extmin)[:2] == pytest.approx((0.0, 0.0)) and tuple(extents.extmax)[
        :2
    ] == pytest.approx(tube_layout.page_size)


def test_dashed_creases_are_long_arcs_through_their_points(tmp_path):
    """LibreCAD restarts a dash pattern at every vertex whatever the flag: a crease of 2 mm chords
    drew solid there. Written as arcs (bulges), each dash pattern has room; ezdxf's own flattening
    of the arcs passes within the tolerance of every point of the crease."""
    ezdxf = pytest.importorskip("ezdxf")
    from ezdxf import path

    from _sheets import vault_sheets
    from curvefold.io._dxf import ARC_TOLERANCE
    from curvefold.io._planar import distance_to_segments, polyline_segments

    layout = layout_sheets(vault_sheets(3), page="A4")
    doc = ezdxf.readfile(write_dxf(tmp_path / "v.dxf", layout))
    msp = doc.modelspace()
    for key in ("mountain", "valley", "seam"):
        ours = [p.points for page in layout.pages for p in page.on_layer(key)]
        if not ours:
            continue
        theirs = msp.query(f'LWPOLYLINE[layer=="{layer_name(key)}"]')
        assert len(theirs) == len(ours)
        pattern = sum(
            doc.linetypes.get(
                doc.layers.get(layer_name(key)).dxf.linetype
            ).simplified_line_pattern()
        )
        for points, entity in zip(
            sorted(ours, key=lambda p: tuple(p[0])),
            sorted(theirs, key=lambda e: tuple(e.get_points("xy")[0])),
        ):
            assert len(entity) < len(points)  # fewer vertices than the chords
            # ezdxf reads the bulges as arcs
            flat = np.array([(v.x, v.y) for v in path.make_path(entity).flattening(1e-5)])
            gap = distance_to_segments(points, polyline_segments([(flat, False)]))
            assert gap.max() <= ARC_TOLERANCE + 1e-5
            vertices = np.array([v[:2] for v in entity.vertices()])
            along = np.linalg.norm(np.diff(flat, axis=0), axis=1).sum()
            # arcs longer than a dash pattern, on average
            assert along / (len(vertices) - 1) > pattern
    # the check can fail: the crease written as its chords lies within the tolerance but has no room
    # for a pattern
    chords = np.linalg.norm(np.diff(layout.pages[0].on_layer("mountain")[0].points, axis=0), axis=1)
    assert chords.mean() < 4.0


# --------------------------------------------------------------------------------------
# perforated creases


def test_perforation_dashes_have_the_asked_lengths_and_gaps():
    t = np.linspace(0.0, np.pi, 200)
    arc = 50.0 * np.stack([np.cos(t), np.sin(t)], axis=1)  # 157 mm of crease, chords 0.79 mm
    for mountain, pattern in ((False, (3.0,)), (True, (3.0, 1.0))):
        dashes = perforation_dashes(arc, 3.0, 1.5, mountain=mountain)
        lengths = np.array([LineString(d).length for d in dashes])
        full = lengths[:-1]  # the last may be cut short by the end
        assert_periodic = np.tile(pattern, len(full))[: len(full)]
        # chords of a 50 mm arc: sagitta < 2e-3 mm
        np.testing.assert_allclose(full, assert_periodic, rtol=0, atol=2e-3)
        # every dash lies on the crease; the gaps between are 1.5 mm along it, half a gap at each
        # end
        s = [np.arctan2(d[[0, -1], 1], d[[0, -1], 0]) * 50.0 for d in dashes]
        starts, ends = np.array([x[0] for x in s]), np.array([x[1] for x in s])
        along = np.sort(np.concatenate([starts, ends]))[::-1]
        gaps = -np.diff(along)[1::2]
        np.testing.assert_allclose(gaps, 1.5, atol=2e-3)
        assert (
            np.pi * 50 - along[0] == pytest.approx(0.75, abs=2e-3)
            and along[-1] <= np.pi * 50 - 0.75
        )
        assert all(np.abs(np.linalg.norm(d, axis=1) - 50.0).max() < 2e-3 for d in dashes)


def test_perforated_layout_cuts_dashes_on_their_own_layers(tmp_path, tube_layout):
    ezdxf = pytest.importorskip("ezdxf")
    perforated = prepare_layout(tube_layout, perforation=(3.0, 1.5))
    assert perforated.perforation == (3.0, 1.5)
    for key in ("mountain", "valley"):
        before = sum(LineString(p.points).length for p in tube_layout.pages[0].on_layer(key))
        dashes = perforated.pages[0].on_layer(key)
        cut = sum(LineString(p.points).length for p in dashes)
        # dash, gap (mountain: dash, gap, dash / 3, gap)
        share = 3.0 / 4.5 if key == "valley" else (3.0 + 1.0) / (3.0 + 1.5 + 1.0 + 1.5)
        assert len(dashes) > 10 and cut == pytest.approx(before * share, rel=0.05)
    doc = ezdxf.readfile(write_dxf(tmp_path / "p.dxf", perforated))
    for key in ("mountain", "valley"):
        layer = doc.layers.get(layer_name(key, perforated=True))
        # the dashes are geometry, not a line style
        assert layer.dxf.linetype.upper() == "CONTINUOUS"
        assert len(doc.modelspace().query(f'LWPOLYLINE[layer=="{layer.dxf.name}"]')) == len(
            perforated.pages[0].on_layer(key)
        )
    assert not doc.layers.has_entry(layer_name("mountain"))
    with pytest.raises(InputError, match="perforation dash and gap must be positive") as err:
        prepare_layout(tube_layout, perforation=(3.0, 0.0))
    assert err.value.parameter == "perforation"


# --------------------------------------------------------------------------------------
# kerf


def test_offset_outline_agrees_with_shapely_buffer_on_the_sheets_outlines(tube_layout):
    """Every cut outline of the tube (curved sheet sides, tapered glue tabs, concave and convex
    corners) moved out by 0.1 mm is shapely's mitred buffer of it, to 1e-6 mm² per mm of outline."""
    for placed in tube_layout.sheets():
        (outline,) = placed.on_layer("cut")
        for d in (0.05, 0.1, 0.25):
            ours = Polygon(offset_outline(outline.points, d))
            theirs = Polygon(outline.points).buffer(d, join_style="mitre", mitre_limit=MITRE_LIMIT)
            assert ours.is_valid
            assert ours.symmetric_difference(theirs).area < 1e-6 * theirs.length, (placed.label, d)
            assert ours.area - Polygon(outline.points).area == pytest.approx(
                d * Polygon(outline.points).length, rel=0.02
            )


def test_offset_outline_fails_on_a_wrong_offset_direction(tube_layout):
    """The check above can fail: the outline moved inward is not the buffer."""
    (outline,) = tube_layout.sheets()[0].on_layer("cut")
    inward = Polygon(offset_outline(outline.points, -0.1))
    assert (
        inward.symmetric_difference(Polygon(outline.points).buffer(0.1, join_style="mitre")).area
        > 1.0
    )
    clockwise = offset_outline(outline.points[::-1], 0.1)  # either turning sense moves outward
    assert Polygon(clockwise).area > Polygon(outline.points).area


def test_kerf_moves_only_the_cut_outlines_out_by_half_of_it(tube_layout):
    layout = prepare_layout(tube_layout, kerf=0.2)
    assert layout.kerf == 0.2
    for before, after in zip(tube_layout.sheets(), layout.sheets()):
        (a,), (b,) = before.on_layer("cut"), after.on_layer("cut")
        ring = Polygon(a.points).exterior
        corners = np.array([ring.distance(Point(p)) for p in b.points])
        sides = np.array(
            [ring.distance(Point(p)) for p in 0.5 * (b.points + np.roll(b.points, -1, axis=0))]
        )
        # mitred corners reach further
        assert corners.min() >= 0.1 - 1e-9 and corners.max() <= 0.1 * MITRE_LIMIT + 1e-9
        # each side moved parallel to itself by half the kerf
        assert np.median(sides) == pytest.approx(0.1, abs=1e-9)
        for key in ("mountain", "valley", "seam", "glue"):
            assert all(
                np.array_equal(p.points, q.points)
                for p, q in zip(before.on_layer(key), after.on_layer(key))
            )
    assert prepare_layout(tube_layout) is tube_layout
    with pytest.raises(InputError, match="kerf must be a non-negative number of mm, got -0.1"):
        prepare_layout(tube_layout, kerf=-0.1)


def test_the_command_line_writes_a_perforated_kerfed_laser_pattern(tmp_path):
    from _cli import run

    out = tmp_path / "t"
    r = run(
        "tube",
        "--samples",
        "81",
        "--formats",
        "svg,dxf",
        "--cutter",
        "laser",
        "--perforation",
        "2",
        "--perforation-gap",
        "1",
        "--kerf",
        "0.15",
        "--out",
        str(out),
    )
    assert r.returncode == 0, r.stderr
    text = "".join(p.read_text() for p in sorted(out.glob("tube-pattern*.svg")))
    assert (
        'inkscape:label="perforate - mountain"' in text
        and "stroke:#ff0000" in text
        and "stroke:#0000ff" in text
    )
    r = run(
        "tube",
        "--samples",
        "81",
        "--formats",
        "svg",
        "--cutter",
        "glowforge",
        "--out",
        str(tmp_path / "x"),
    )
    assert r.returncode == 2 and "cutter" in r.stderr and "glowforge" in r.stderr
