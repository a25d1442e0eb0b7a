// The 3D view: the design morphing between its precomputed fold states, the span and rise
// drawn as dimensions, and the kept design beside it or over it.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { sig4 } from "./format.js";

const bytes = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0)).buffer;

function boxOf(states) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < states.length; i += 3) {
    for (let c = 0; c < 3; c++) {
      lo[c] = Math.min(lo[c], states[i + c]);
      hi[c] = Math.max(hi[c], states[i + c]);
    }
  }
  return { lo, hi, size: Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) };
}

// One drawn design: its surface and crease lines, morphing between its precomputed states.
class Drawn {
  constructor(scene, colour, opacity) {
    this.positions = new THREE.BufferAttribute(new Float32Array(3), 3);
    const surface = new THREE.BufferGeometry();
    surface.setAttribute("position", this.positions);
    this.group = new THREE.Group();
    this.material = new THREE.MeshStandardMaterial({
      color: colour, side: THREE.DoubleSide, flatShading: true, roughness: 0.85,
      transparent: opacity < 1, opacity, depthWrite: opacity >= 1,
    });
    this.surface = new THREE.Mesh(surface, this.material);
    this.surface.frustumCulled = false;
    this.surface.castShadow = opacity >= 1; // the kept design, see-through, casts none
    this.lines = new THREE.Group();
    this.group.add(this.surface, this.lines);
    scene.add(this.group);
  }

  load(motion, colours, lineOpacity = 1) {
    this.motion = motion;
    this.states = new Float32Array(bytes(motion.positions));
    const n = motion.vertices * 3;
    if (this.positions.array.length !== n) {
      this.positions = new THREE.BufferAttribute(new Float32Array(n), 3);
      this.surface.geometry.setAttribute("position", this.positions);
    }
    const triangles = new Uint32Array(bytes(motion.triangles));
    this.surface.geometry.setIndex(new THREE.BufferAttribute(triangles, 1));
    this.lines.children.forEach((l) => l.geometry.dispose());
    this.lines.clear();
    for (const [kind, b64] of Object.entries(motion.lines)) {
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", this.positions);
      g.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(b64)), 1));
      const material = new THREE.LineBasicMaterial({
        color: colours[kind] ?? "#3a3a3a", transparent: lineOpacity < 1, opacity: lineOpacity,
      });
      const line = new THREE.LineSegments(g, material);
      line.frustumCulled = false;
      this.lines.add(line);
    }
    this.box = boxOf(this.states);
  }

  bracket(angle) { // where an angle falls between the precomputed states: (index, fraction)
    const a = this.motion.angles;
    let i = 0;
    while (i < a.length - 2 && a[i + 1] < angle) i++;
    if (a.length < 2) return [0, 0];
    return [i, Math.min(1, Math.max(0, (angle - a[i]) / (a[i + 1] - a[i])))];
  }

  setAngle(angle) {
    const [i, t] = this.bracket(angle);
    const n = this.positions.array.length, A = this.states, P = this.positions.array;
    const a = i * n, b = Math.min(i + 1, this.motion.angles.length - 1) * n;
    for (let j = 0; j < n; j++) P[j] = A[a + j] * (1 - t) + A[b + j] * t;
    this.positions.needsUpdate = true;
  }
}

function textSprite(text, height) { // a label that always faces the camera
  const canvas = document.createElement("canvas"), ctx = canvas.getContext("2d");
  ctx.font = "600 40px system-ui, sans-serif";
  canvas.width = Math.ceil(ctx.measureText(text).width) + 24;
  canvas.height = 56;
  ctx.font = "600 40px system-ui, sans-serif";
  ctx.fillStyle = "rgba(255,255,255,0.85)";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "#1a237e";
  ctx.textBaseline = "middle";
  ctx.fillText(text, 12, 29);
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: texture, depthTest: false }));
  sprite.scale.set(height * canvas.width / canvas.height, height, 1);
  sprite.renderOrder = 10;
  return sprite;
}

/**
 * The 3D view of the state's design (and its kept design) on a canvas inside `container`;
 * `legend` says which is which; `onAngle(angle)` follows every change of the fold angle.
 */
export class View {
  constructor(state, { canvas, container, legend, onAngle }) {
    this.state = state;
    this.angle = 90;
    this.fittedSize = null;
    this.legend = legend;
    this.onAngle = onAngle;
    this.renderer = new THREE.WebGLRenderer({
      canvas, antialias: true, preserveDrawingBuffer: true,
    });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.shadowMap.enabled = true; // the design's shadow on its ground
    this.renderer.shadowMap.type = THREE.PCFSoftShadowMap;
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf6f5f2);
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.001, 1000);
    this.camera.up.set(0, 0, 1); // the model's z is up
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener("change", () => this.render());
    // lit as a modelling viewport: sky and ground light, and a sun high on the left that
    // shades each face by its normal (flat shading) and casts the shadow
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8d8470, 2.0));
    this.sun = new THREE.DirectionalLight(0xffffff, 1.6);
    this.sun.castShadow = true;
    this.sun.shadow.mapSize.set(2048, 2048);
    this.scene.add(this.sun, this.sun.target);
    this.main = new Drawn(this.scene, 0xdcdcd9, 1);
    this.kept = new Drawn(this.scene, 0x7aa6e0, 0.45);
    this.kept.group.visible = false;
    const ground = new THREE.MeshStandardMaterial({ color: 0xece6da, roughness: 1 });
    this.ground = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), ground);
    this.ground.receiveShadow = true;
    this.scene.add(this.ground);
    this.dimensions = new THREE.Group();
    this.scene.add(this.dimensions);
    this.container = container;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const box = this.container.getBoundingClientRect();
    this.renderer.setSize(box.width, box.height, false);
    this.camera.aspect = box.width / Math.max(box.height, 1);
    this.camera.updateProjectionMatrix();
    this.render();
  }

  get motion() { return this.main.motion; }

  /** Show a preview's design; `previous` is the preview shown before (null for the first). */
  load(body, previous) {
    const atDesign = !previous || Math.abs(this.angle - previous.motion.design_angle) < 1e-9;
    this.main.load(body.motion, body.colours);
    this.drawDimensions(body);
    this.placeKept();
    const last = body.motion.angles[body.motion.angles.length - 1];
    this.setAngle(atDesign ? body.motion.design_angle : Math.min(this.angle, last));
    // fit again when the design's size changed by more than a fifth (or it is the first one)
    const size = this.main.box.size;
    const resized = !this.fittedSize || Math.abs(size / this.fittedSize - 1) > 0.2;
    if (resized || previous?.kind !== body.kind) this.fit();
  }

  drawDimensions(body) { // the span and the rise as dimension lines, labelled in metres
    this.dimensions.children.forEach((c) => { c.geometry?.dispose(); c.material?.map?.dispose(); });
    this.dimensions.clear();
    const d = body.dimensions;
    if (!d) return;
    const size = this.main.box.size, tick = 0.03 * size, points = [];
    const line = (a, b, across) => {
      points.push(...a, ...b);
      for (const p of [a, b]) {
        points.push(p[0] - across[0] * tick, p[1] - across[1] * tick, p[2] - across[2] * tick,
          p[0] + across[0] * tick, p[1] + across[1] * tick, p[2] + across[2] * tick);
      }
    };
    const lift = 0.004 * size;
    const s0 = [d.span.from[0], d.span.from[1], lift], s1 = [d.span.to[0], d.span.to[1], lift];
    line(s0, s1, [1, 0, 0]);
    const r0 = [...d.rise.from], r1 = [...d.rise.to];
    line(r0, r1, [1, 0, 0]);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.Float32BufferAttribute(points, 3));
    const material = new THREE.LineBasicMaterial({ color: 0x1a237e, depthTest: false });
    const lines = new THREE.LineSegments(geometry, material);
    lines.renderOrder = 9;
    this.dimensions.add(lines);
    const span = textSprite(`span ${sig4(d.span.value)} m`, 0.055 * size);
    span.position.set((s0[0] + s1[0]) / 2 + 0.06 * size, (s0[1] + s1[1]) / 2, lift + 0.04 * size);
    const rise = textSprite(`rise ${sig4(d.rise.value)} m`, 0.055 * size);
    rise.position.set(r1[0] + 0.06 * size, r1[1], (r0[2] + r1[2]) / 2);
    this.dimensions.add(span, rise);
  }

  placeKept() { // the kept design beside this one (along x), or over it
    const k = this.state.kept?.preview;
    if (!this.main.motion) return;
    this.kept.group.visible = !!k;
    if (!k) {
      this.legend.textContent = "";
      return;
    }
    if (this.kept.motion !== k.motion) this.kept.load(k.motion, k.colours, 0.6);
    const side = this.state.compareMode === "side";
    const gap = 0.25 * Math.max(this.main.box.size, this.kept.box.size);
    const shift = side ? this.main.box.hi[0] - this.kept.box.lo[0] + gap : 0;
    this.kept.group.position.set(shift, 0, 0);
    this.legend.textContent = side
      ? "grey: this design · blue, on the right: the kept design"
      : "grey: this design · blue: the kept design, overlaid";
  }

  groundUnder() { // the ground under every state of both designs, grown by 8 % of its larger side
    const boxes = [this.main.box];
    if (this.kept.group.visible) {
      const b = this.kept.box, x = this.kept.group.position.x;
      boxes.push({ lo: [b.lo[0] + x, b.lo[1], b.lo[2]], hi: [b.hi[0] + x, b.hi[1], b.hi[2]] });
    }
    const lo = [0, 1, 2].map((c) => Math.min(...boxes.map((b) => b.lo[c])));
    const hi = [0, 1, 2].map((c) => Math.max(...boxes.map((b) => b.hi[c])));
    return { lo, hi, size: Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) };
  }

  fit() { // look at the box of every state from the figures' azimuth and elevation, all in view
    const { lo, hi, size } = this.groundUnder();
    this.ground.visible = this.main.motion.ground;
    this.ground.scale.set(hi[0] - lo[0] + 0.16 * size, hi[1] - lo[1] + 0.16 * size, 1);
    this.ground.position.set((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, -1e-3 * size);
    const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
    const radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    const fov = THREE.MathUtils.degToRad(this.camera.fov) / 2;
    const half = Math.min(fov, Math.atan(Math.tan(fov) * this.camera.aspect));
    const d = 1.05 * radius / Math.sin(half);
    const az = THREE.MathUtils.degToRad(-50), el = THREE.MathUtils.degToRad(22);
    this.camera.position.set(centre.x + d * Math.cos(el) * Math.cos(az),
      centre.y + d * Math.cos(el) * Math.sin(az), centre.z + d * Math.sin(el));
    this.camera.near = radius / 1000;
    this.camera.far = radius * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    this.light(centre, radius);
    this.fittedSize = this.main.box.size;
    this.render();
  }

  light(centre, radius) { // the sun's direction kept, its shadow's box around the design
    const sun = this.sun, box = sun.shadow.camera;
    sun.target.position.copy(centre);
    sun.position.copy(centre).add(new THREE.Vector3(-2, -3, 5).setLength(3 * radius));
    box.left = box.bottom = -1.5 * radius;
    box.right = box.top = 1.5 * radius;
    box.near = 0.5 * radius;
    box.far = 6 * radius;
    box.updateProjectionMatrix();
    sun.shadow.bias = -1e-4;
    sun.shadow.normalBias = 0.004 * radius;
  }

  sample(values) { // a per-state number at the current angle
    const [i, t] = this.main.bracket(this.angle);
    return values[i] * (1 - t) + values[Math.min(i + 1, values.length - 1)] * t;
  }

  setAngle(angle) {
    this.angle = angle;
    const m = this.main.motion;
    this.main.setAngle(angle);
    if (this.kept.group.visible) {
      this.kept.setAngle(Math.min(angle, this.kept.motion.angles.at(-1)));
    }
    // span and rise are the design's
    this.dimensions.visible = Math.abs(angle - m.design_angle) < 0.5;
    this.onAngle(angle);
    this.render();
  }

  render() { if (this.renderer) this.renderer.render(this.scene, this.camera); }
}
