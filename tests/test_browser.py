"""Our files and report in a browser: three.js (GLTFLoader) in headless Chromium, the report at
390 and 1280 px."""

from __future__ import annotations

import re

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _browser import chromium_page, served
from _cli import run
from curvefold.geometry import choose_sampling
from curvefold.io import ModelOutput, write_3d
from curvefold.vault import Vault

_THREE_PAGE = """<!doctype html><html><head><meta charset="utf-8">
<script type="importmap">{"imports": {
  "three": "/node_modules/three/build/three.module.js",
  "three/addons/": "/node_modules/three/examples/jsm/"}}</script></head><body>
<script type="module">
import * as THREE from "three";
import { GLTFLoader } from "three/addons/loaders/GLTFLoader.js";
new GLTFLoader().load("/vault.glb", (gltf) => {
  const sheets = gltf.scene.children.map(
    (node) => node.children.find((c) => c.isMesh && !c.isLineSegments) ?? node);
  const mixer = new THREE.AnimationMixer(gltf.scene);
  const clip = gltf.animations[0];
  const action = mixer.clipAction(clip);
  action.setLoop(THREE.LoopOnce);
  action.clampWhenFinished = true;
  action.play();
  // a sheet's triangle corners as the animation poses them at a time
  const posed = (surface, time) => {
    mixer.setTime(time);
    const base = surface.geometry.attributes.position.array;
    const out = Float64Array.from(base);
    surface.morphTargetInfluences.forEach((w, k) => {
      const delta = surface.geometry.morphAttributes.position[k].array;
      for (let i = 0; i < out.length; i += 1) out[i] += w * delta[i];
    });
    const corners = [];
    for (const i of surface.geometry.index.array) {
      corners.push(out[3 * i], out[3 * i + 1], out[3 * i + 2]);
    }
    return corners;
  };
  window.result = {
    nodes: gltf.scene.children.map((n) => n.name),
    names: Object.entries(sheets[0].morphTargetDictionary)
      .sort((a, b) => a[1] - b[1]).map((e) => e[0]),
    normals: sheets.every((m) => m.geometry.attributes.normal !== undefined),
    clips: gltf.animations.map((a) => [a.name, a.duration]),
    start: sheets.map((m) => posed(m, 0)),
    middle: sheets.map((m) => posed(m, clip.duration / 2)),
    end: sheets.map((m) => posed(m, clip.duration)),
  };
}, undefined, (error) => { window.result = { error: String(error) }; });
</script></body></html>
"""


def test_three_js_opens_the_glb_at_the_design_state_with_a_node_per_sheet(tmp_path):
    """GLTFLoader gives a named node per sheet with normals; the morph targets are named by fold
    angle; the animation starts at the design state (what Blender opens, as it applies the
    first keyframe), unfolds to the flat state half-way and folds back."""
    vault = Vault.from_design(samples=201)
    structure = vault.structure
    keep = choose_sampling(structure).keep
    angles = np.linspace(0.0, 90.0, 4)
    write_3d(tmp_path / "vault", structure, angles, ModelOutput(keep=keep), formats=("glb",))
    (tmp_path / "index.html").write_text(_THREE_PAGE)
    with served(tmp_path) as url, chromium_page() as page:
        page.goto(f"{url}/index.html")
        page.wait_for_function("window.result !== undefined", timeout=60_000)
        result = page.evaluate("window.result")
    assert "error" not in result, result
    to_gltf = lambda x: np.stack([x[..., 0], x[..., 2], -x[..., 1]], axis=-1)  # noqa: E731 (z up → y up)
    topology = structure.topology(keep=keep)
    faces = structure.state().mesh(keep=keep).faces_vertices
    design = to_gltf(structure.state().mesh(keep=keep).vertices_coords)
    flat = to_gltf(structure.state(0.0).mesh(keep=keep).vertices_coords)
    # three.js turns spaces in node names into underscores (PropertyBinding.sanitizeNodeName)
    assert (
        result["nodes"] == [s.label.replace(" ", "_") for s in topology.sheets]
        and len(result["nodes"]) == 2 * vault.design.tubes
    )
    assert result["names"] == ["2α = 0°", "2α = 30°", "2α = 60°"] and result["normals"]
    assert result["clips"] == [["fold", 6.0]]
    # 32-bit floats of coordinates up to ~2: within 1e-6
    for k, sheet in enumerate(topology.sheets):
        corners = lambda x, sheet=sheet: x[faces[sheet.faces]].reshape(-1, 3)  # noqa: E731
        assert_allclose(np.reshape(result["start"][k], (-1, 3)), corners(design), atol=1e-6, rtol=0)
        assert_allclose(np.reshape(result["middle"][k], (-1, 3)), corners(flat), atol=1e-6, rtol=0)
        assert_allclose(np.reshape(result["end"][k], (-1, 3)), corners(design), atol=1e-6, rtol=0)
    assert np.abs(design - flat).max() > 0.5  # the two poses differ: the checks above can fail


@pytest.fixture(scope="module")
def vault_folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("report") / "vault"
    done = run("vault", "--samples", "201", "--out", str(folder))
    assert done.returncode == 0, done.stderr
    return folder


@pytest.mark.parametrize("width", [390, 1280])
def test_the_report_reads_at_phone_and_desktop_widths(vault_folder, width):
    with served(vault_folder) as url, chromium_page(width, 800) as page:
        page.goto(f"{url}/report.html")
        page.wait_for_load_state("load")
        layout = page.evaluate("""() => ({
            overflow: document.documentElement.scrollWidth - window.innerWidth,
            body: document.body.clientWidth,
            images: [...document.images].map(
                (i) => [i.getAttribute('src'), i.naturalWidth, i.getBoundingClientRect().width]),
            files: [...document.querySelectorAll('h2 + table a')].map((a) => a.textContent),
            tables: [...document.querySelectorAll('table')].map(
                (t) => t.scrollWidth - t.clientWidth),
            viewport: document.querySelector('meta[name=viewport]')?.content,
        })""")
    assert layout["overflow"] <= 0  # nothing wider than the screen
    # a phone: every table reads without sliding sideways (one card per row), every figure's text
    # readable
    if width == 390:
        assert max(layout["tables"]) <= 1, layout["tables"]
        from PIL import Image

        for src, _, shown_width in layout["images"]:
            # 7 pt text at 150 dpi is 14.6 px in the picture: at least 9 px on the screen
            if src.endswith(".png"):
                with Image.open(vault_folder / src) as picture:
                    pixels = picture.width
                assert 14.6 * shown_width / pixels >= 9, (src, pixels, shown_width)
    assert layout["viewport"] == "width=device-width, initial-scale=1"
    assert all(natural > 0 for _, natural, _ in layout["images"])  # every picture loads
    shown = {src: (natural, w) for src, natural, w in layout["images"]}
    # the folding motion (four panels in a square) is shown at least 340 px wide, or its own size
    # (it was 530 × 147 px)
    natural, width = shown["folding-motion.png"]
    assert width >= min(natural, 340) and width >= 0.45 * min(layout["body"], 1100)
    pages = [f for f in layout["files"] if re.fullmatch(r"vault-pattern-p\d+\.svg", f)]
    # p2 before p10
    assert pages == sorted(pages, key=lambda f: int(re.search(r"\d+", f)[0])) and len(pages) >= 10
