"""The assembly guide, read back by pdfplumber (text, rectangles, colours) and pdftoppm (pixels)."""

from __future__ import annotations

import re
import shutil
import subprocess
from dataclasses import replace

import numpy as np
import pytest

from _cli import run
from curvefold.figures._assembly import HIGHLIGHT_RGB, assembly_plan, write_assembly
from curvefold.figures._scene import GROUND_COLOR
from curvefold.io import PatternOutput, layout_pattern, write_pdf
from curvefold.io._tables import rgb8
from curvefold.vault import Vault

pdfplumber = pytest.importorskip("pdfplumber")
pytestmark = pytest.mark.skipif(
    shutil.which("pdftotext") is None, reason="pdftotext (poppler) not installed"
)
MM = 72 / 25.4


@pytest.fixture(scope="module")
def vault():
    structure = Vault.from_design(samples=101, tubes=3).structure
    return structure, layout_pattern(structure, PatternOutput(name="vault", page="A5"))


@pytest.fixture(scope="module")
def guide(vault, tmp_path_factory):
    folder = tmp_path_factory.mktemp("guide")
    structure, layout = vault
    return write_assembly(folder / "assembly.pdf", structure, layout), write_pdf(
        folder / "pattern.pdf", layout
    )


def _text(path, page: int) -> str:
    """Page ``page`` (1-based) as poppler's pdftotext reads it, in the order it was drawn
    (rotated labels included)."""
    return subprocess.run(
        ["pdftotext", "-raw", "-f", str(page), "-l", str(page), str(path), "-"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout


def _pages(path):
    with pdfplumber.open(path) as doc:
        return [
            (p.width, p.height, _text(path, n), p.rects + p.curves)
            for n, p in enumerate(doc.pages, start=1)
        ]


def _seams(text: str) -> set[str]:
    return set(re.findall(r"\bS\d+\b", text))


def test_the_guide_names_every_sheet_and_seam_as_the_pattern_prints_them(guide, vault):
    path, pattern = guide
    structure, layout = vault
    guide_text = "\n".join(t for *_, t, _ in _pages(path))
    pattern_text = "\n".join(t for *_, t, _ in _pages(pattern))
    labels = [
        t.text
        for s in sorted(layout.sheets(), key=lambda s: s.index)
        for t in s.labels
        if t.kind == "sheet"
    ]
    assert len(labels) == 6 and all(label in guide_text for label in labels)
    assert _seams(guide_text) == _seams(pattern_text) == {f"S{i}" for i in range(6)}
    plan = assembly_plan(structure, layout)
    assert [(s.id, s.tabs, s.onto) for s in plan.seams] == [
        (2 * k + j, labels[2 * k], labels[2 * k + 1]) for k in range(3) for j in (0, 1)
    ]
    # the check can fail: a pattern whose seam labels differ from the guide's is told apart
    damaged = replace(
        layout,
        pages=tuple(
            replace(
                p,
                sheets=tuple(
                    replace(
                        s,
                        labels=tuple(
                            replace(t, text="S9") if t.kind == "seam" and t.seam == 0 else t
                            for t in s.labels
                        ),
                    )
                    for s in p.sheets
                ),
            )
            for p in layout.pages
        ),
    )
    damaged_path = write_pdf(path.with_name("damaged.pdf"), damaged)
    assert _seams("\n".join(t for *_, t, _ in _pages(damaged_path))) != _seams(guide_text)


def test_the_steps_go_tube_by_tube_gluing_seams_then_neighbours(guide, vault):
    path, _ = guide
    structure, layout = vault
    text = "\n".join(t for *_, t, _ in _pages(path))
    starts = [text.index(f"Step {k}: tube {k}") for k in (1, 2, 3)]
    assert starts == sorted(starts)
    plan = assembly_plan(structure, layout)
    for step in plan.steps:
        k = step.tube
        said = " ".join(step.lines)
        assert {f"S{2 * k}", f"S{2 * k + 1}"} == _seams(said)  # its two seams, no other
        # glued to the tube before it
        assert ("crease 1" in said and f"tube {k}'s crease 3" in said) == (k > 0)
    assert plan.sheets[0].page == 1 and {s.page for s in plan.sheets} <= set(
        range(1, len(layout.pages) + 1)
    )


def test_every_page_is_a_pattern_page_with_its_10_mm_scale_bar(guide, vault):
    path, _ = guide
    _, layout = vault
    pages = _pages(path)
    assert len(pages) >= 2
    for width, height, text, shapes in pages:
        assert (width / MM, height / MM) == pytest.approx(layout.page_size)
        bars = [
            s
            for s in shapes
            if s.get("fill")
            and abs(s["width"] - 10 * MM) < 0.01
            and abs(s["height"] - 1.2 * MM) < 0.01
        ]
        assert len(bars) == 1
        assert "10 mm: print at 100 %" in text and "assembly guide, page" in text


def test_each_step_has_a_picture_with_its_new_tube_picked_out(guide):
    """One ground (the vault stands on z = 0) per step on each page, and strips in the
    highlight's hue in it."""
    path, _ = guide
    ground = tuple(c / 255 for c in rgb8(GROUND_COLOR))
    steps = 0
    for *_, text, shapes in _pages(path):
        here = len(re.findall(r"Step \d+: tube \d+", text))
        fills = [tuple(s["non_stroking_color"]) for s in shapes if s.get("fill")]
        grounds = sum(np.allclose(f, ground, atol=2e-3) for f in fills)
        # shaded HIGHLIGHT_RGB
        orange = [f for f in fills if len(f) == 3 and f[0] > f[1] > f[2] and f[0] - f[2] > 0.25]
        assert grounds == here and (len(orange) > 0) == (here > 0)
        steps += here
    assert steps == 3 and HIGHLIGHT_RGB[0] > HIGHLIGHT_RGB[1] > HIGHLIGHT_RGB[2]


def test_the_guide_renders_and_the_new_tube_shows(guide, tmp_path):
    path, _ = guide
    subprocess.run(["pdftoppm", "-r", "40", "-png", str(path), str(tmp_path / "g")], check=True)
    from matplotlib.image import imread

    pngs = sorted(tmp_path.glob("g-*.png"))
    shown = 0
    for png in pngs:
        img = imread(png)[..., :3]
        orange = (
            (img[..., 0] > img[..., 2] + 0.25) & (img[..., 0] > 0.6) & (img[..., 1] > img[..., 2])
        )
        shown += orange.sum() > 30
    assert shown >= 1 and len(pngs) >= 2


def test_the_main_job_writes_the_guide(tmp_path):
    out = tmp_path / "v"
    r = run(
        "vault", "--samples", "101", "--tubes", "2", "--formats", "assembly,pdf", "--out", str(out)
    )
    assert r.returncode == 0, r.stderr
    assert (out / "assembly.pdf").exists() and (out / "vault-pattern.pdf").exists()
    text = "\n".join(t for *_, t, _ in _pages(out / "assembly.pdf"))
    assert "Vault: assembly guide" in text and "Step 2: tube 2" in text


def test_the_pictures_colours_and_the_lines_are_those_of_the_one_by_one_definitions():
    """The guide writes every colour of a picture at once and wraps lines by summing word widths:
    the same codes as the scene's one-colour ``_hex`` (halves rounded to even, as ``round``) and
    the same lines as measuring each trial line whole."""
    from curvefold.figures._assembly import _hex_codes, _wrap
    from curvefold.figures._scene import _hex
    from curvefold.io._pdf import text_advance

    rng = np.random.default_rng(3)
    colours = np.concatenate(
        [
            rng.uniform(-0.1, 1.1, size=(500, 4)),
            np.array([[0.5, 1.5, 2.5, 1.0]]) / 255,
            np.zeros((1, 4)),
        ]
    )
    assert _hex_codes(colours) == [_hex(c) for c in colours]
    # the comparison sees a channel off by one
    assert _hex_codes(colours[:1] + 1 / 255) != [_hex(colours[0])]

    def wrapped(text, size, width):
        lines, line = [], ""
        for word in text.split():
            trial = f"{line} {word}".strip()
            if line and text_advance(trial, size) > width:
                lines.append(line)
                line = word
            else:
                line = trial
        return lines + ([line] if line else [])

    words = [
        "Glue",
        "seam",
        "S12:",
        "fold",
        "the",
        "tabs",
        "of",
        "tube 3 left · A",
        "under",
        "W",
        "i",
        "—",
        "°",
    ]
    for _ in range(200):
        text = " ".join(rng.choice(words, size=int(rng.integers(0, 40))))
        size, width = float(rng.uniform(2.0, 5.0)), float(rng.uniform(5.0, 150.0))
        assert _wrap(text, size, width) == wrapped(text, size, width)
    # ... and a line broken elsewhere
    assert _wrap("a b c", 3.2, 100.0) != wrapped("a b c", 3.2, 1.0)


def _swapped(layout):
    """The layout with every crease drawn as the other fold (mountain ↔ valley)."""
    other = {"mountain": "valley", "valley": "mountain"}
    return replace(
        layout,
        pages=tuple(
            replace(
                page,
                sheets=tuple(
                    replace(
                        sheet,
                        polylines=tuple(
                            replace(p, layer=other.get(p.layer, p.layer)) for p in sheet.polylines
                        ),
                    )
                    for sheet in page.sheets
                ),
            )
            for page in layout.pages
        ),
    )


def test_the_guide_says_which_fold_is_mountain_and_which_valley(guide, vault, tmp_path):
    """pdftotext reads the key (seen from the printed side, a mountain fold is the red dash-dot
    line and a valley fold the blue dashed one) and each sheet's fold; pdfplumber reads the
    pattern's creases as those lines: one red dash-dot crease a sheet (dashes 4, 1.2, 0.7,
    1.2 mm), no blue dashed one, as every sheet of the vault folds its crease as a mountain
    seen from its printed side. A pattern drawn with the folds swapped is said the other way."""
    structure, layout = vault
    path, pattern = guide
    text = " ".join(_text(path, 1).split())
    assert (
        "Folds, seen from the printed side: a mountain fold (red dash-dot line) rises toward you, "
        "so fold the sheet away from you along it; a valley fold (blue dashed line) sinks away "
        "from you, so fold the sheet toward you along it." in text
    )
    sheets = [s.label for s in layout.sheets()]
    for label in sheets:
        assert re.search(
            rf"{re.escape(label)}: pattern page \d+; seams [^;]+; a mountain fold", text
        )
    whole = " ".join(" ".join(_text(path, n).split()) for n in range(1, len(_pages(path)) + 1))
    assert whole.count("a mountain fold on both, seen from the printed side") == 3
    band = (layout.margin + layout.footer) * MM  # the footer's band, above the bottom margin
    with pdfplumber.open(pattern) as doc:
        lines = [c for p in doc.pages for c in p.curves + p.lines if c["bottom"] < p.height - band]
    creases = [c for c in lines if tuple(c.get("stroking_color") or ()) == (1.0, 0.0, 0.0)]
    blue = rgb8_unit("#1f4fe0")
    valleys = [c for c in lines if tuple(c.get("stroking_color") or ()) == pytest.approx(blue)]
    assert len(creases) == len(sheets) and not valleys
    dash = creases[0]["dash"][0]
    # in the content's user space, which the page scales to millimetres
    assert list(dash) == pytest.approx([4.0, 1.2, 0.7, 1.2], abs=1e-9)
    swapped = assembly_plan(structure, _swapped(layout))
    assert {s.folds for s in swapped.sheets} == {("valley",)}
    assert {s.folds for s in assembly_plan(structure, layout).sheets} == {("mountain",)}
    laser = write_assembly(tmp_path / "laser.pdf", structure, replace(layout, cutter="laser"))
    assert "a mountain fold (blue dash-dot line)" in " ".join(_text(laser, 1).split())


def rgb8_unit(code: str) -> tuple[float, ...]:
    """``#rrggbb`` as PDF colour components in [0, 1]."""
    return tuple(c / 255 for c in rgb8(code))
