// The curvefold designer page: controls generated from the design schema, a 3D view that
// morphs between precomputed fold states, and the numbers, certificate, crease pattern and
// regression domain of the design. The design lives in this page's URL only.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const $ = (id) => document.getElementById(id);

// State of this page (exposed for scripts and tests as window.curvefold).
const state = { schema: null, kind: "vault", values: {}, mode: "parameters", preview: null };
window.curvefold = state;

const LABELS = {
  kappa0_s0: "κ0·s0", proportion_change: "proportion change", p_xz: "p_xz (apex)", span: "span", rise: "rise",
  tubes: "tubes", max_tubes: "max tubes", a: "a", p_xy: "p_xy", radius: "radius", cells: "cells",
  lattice_curves: "lattice curves", size_x: "size x", size_y: "size y", size_z: "size z",
  regression_margin: "regression margin", length: "length", fold_angle_start: "2α at start", fold_angle_end: "2α at end",
};
const fmt = (v) => (typeof v === "number" ? (Number.isInteger(v) ? String(v) : v.toPrecision(6)) : String(v));

// -- controls ------------------------------------------------------------------------------------

function sliderRange(spec) {
  // The spec's typical span if it names one; else its range when within ten times the
  // default, else a fifth to five times the default.
  const r = spec.range, d = Math.abs(Number(spec.default)) || 1;
  if (spec.typical) return [spec.typical.lo, spec.typical.hi];
  if (!r) return null;
  if (r.lo !== null && r.hi !== null && r.hi - r.lo <= 10 * d) return [r.lo, r.hi];
  const lo = Math.max(r.lo ?? -Infinity, d / 5), hi = Math.min(r.hi ?? Infinity, 5 * d);
  return [spec.kind === "real" ? lo : Math.max(1, Math.round(lo)), hi];
}

function specsOf(kind) {
  const s = state.schema, out = [];
  for (const section of ["", ...s.kinds[kind], "output"]) {
    for (const spec of s.sections[section]) out.push(spec);
  }
  return out;
}

function field(spec, extraClass = "") {
  const box = document.createElement("div");
  box.className = `field ${extraClass}`;
  box.dataset.key = spec.name;
  const label = document.createElement("label");
  label.title = spec.describe;
  label.innerHTML = `<span>${spec.name}</span><span class="unit">${spec.unit || ""}</span>`;
  const row = document.createElement("div");
  row.className = "row";
  const value = state.values[spec.name] ?? (spec.default === null ? "" : String(Array.isArray(spec.default) ? JSON.stringify(spec.default) : spec.default));
  let input;
  if (spec.kind === "choice") {
    input = document.createElement("select");
    for (const c of spec.choices) input.append(new Option(c, c, false, c === value));
  } else if (spec.kind === "flag") {
    input = document.createElement("input");
    input.type = "checkbox";
    input.checked = value === "true";
  } else {
    input = document.createElement("input");
    input.type = "text";
    input.value = value;
    input.className = ["real", "integer", "count"].includes(spec.kind) ? "value" : "text";
    input.placeholder = spec.default === null ? "(none)" : "";
    const range = ["real", "integer", "count"].includes(spec.kind) ? sliderRange(spec) : null;
    if (range) {
      const slider = document.createElement("input");
      slider.type = "range";
      slider.min = range[0];
      slider.max = range[1];
      slider.step = spec.kind === "real" ? (range[1] - range[0]) / 400 : 1;
      slider.value = Number(value) || range[0];
      slider.addEventListener("input", () => { input.value = slider.value; changed(spec, input.value); });
      input.addEventListener("input", () => { if (isFinite(Number(input.value))) slider.value = input.value; });
      row.append(slider);
    }
  }
  input.name = spec.name;
  input.addEventListener(spec.kind === "flag" || spec.kind === "choice" ? "change" : "input",
    () => changed(spec, spec.kind === "flag" ? String(input.checked) : input.value));
  row.prepend(input);
  if (spec.kind === "count") {
    const max = document.createElement("label");
    max.innerHTML = `<input type="checkbox" ${value === "max" ? "checked" : ""}> max`;
    max.firstChild.addEventListener("change", (e) => {
      input.value = e.target.checked ? "max" : String(state.preview?.numbers?.tubes ?? 1);
      changed(spec, input.value);
    });
    row.append(max);
  }
  const error = document.createElement("div");
  error.className = "error";
  box.append(label, row, error);
  return box;
}

function buildControls() {
  const form = $("fields");
  form.replaceChildren();
  const groups = {};
  const targets = state.kind === "vault" && state.mode === "targets";
  for (const spec of specsOf(state.kind)) {
    const section = spec.section || "design";
    if (!groups[section]) {
      groups[section] = document.createElement(section === "output" ? "details" : "fieldset");
      groups[section].innerHTML = section === "output" ? "<summary>output files</summary>" : `<legend>${section}</legend>`;
      form.append(groups[section]);
    }
    const replaced = targets && state.schema.targets.some((t) => t.replaces === spec.name);
    const f = field(spec, replaced ? "solved" : "");
    if (replaced) f.querySelectorAll("input").forEach((i) => (i.disabled = true));
    groups[section].append(f);
  }
  if (targets) {
    const box = document.createElement("fieldset");
    box.innerHTML = "<legend>targets</legend>";
    for (const spec of state.schema.targets) box.append(field(spec));
    form.prepend(box);
  }
  $("mode").hidden = state.kind !== "vault";
}

function changed(spec, text) {
  const def = spec.default === null ? "" : String(spec.default);
  if (text === def && !state.schema.targets.some((t) => t.name === spec.name)) delete state.values[spec.name];
  else state.values[spec.name] = text;
  request();
}

// -- requests ------------------------------------------------------------------------------------

function currentQuery() {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(state.values)) if (v !== "") q.append(k, v);
  return q.toString();
}

let inflight = false, again = false, detailsTimer = null;

async function request() {
  if (inflight) { again = true; return; }
  inflight = true;
  const query = currentQuery();
  let response, body;
  try {
    response = await fetch(`/api/${state.kind}/preview?${query}`);
    body = await response.json();
  } catch (err) {
    body = { error: `the designer's server did not answer (${err.message}); is 'curvefold designer' still running?`, key: null };
  }
  if (response?.ok) show(body, query);
  else refuse(body);
  inflight = false;
  if (again) { again = false; request(); }
}

function refuse(body) {
  clearErrors();
  const box = body.key && document.querySelector(`.field[data-key="${body.key}"]`);
  if (box) {
    box.classList.add("invalid");
    box.querySelector(".error").textContent = body.error;
  } else {
    $("message").textContent = body.error;
    $("message").hidden = false;
  }
}

function clearErrors() {
  $("message").hidden = true;
  document.querySelectorAll(".field.invalid").forEach((f) => { f.classList.remove("invalid"); f.querySelector(".error").textContent = ""; });
}

function show(body, query) {
  clearErrors();
  state.preview = body;
  history.replaceState(null, "", `?${new URLSearchParams({ kind: state.kind })}${query ? "&" + query : ""}`);
  if (state.mode === "targets") {  // the solved parameters
    for (const name of ["a", "p_xy", "radius"]) {
      const input = document.querySelector(`.field[data-key="${name}"] input.value`);
      if (input) input.value = fmt(body.numbers[name]);
    }
  }
  view.load(body.motion, body.colours);
  state.contact = undefined;
  const tubes = document.querySelector('.field[data-key="tubes"] input[type=range]');
  if (tubes && body.numbers.max_tubes) tubes.max = body.numbers.max_tubes;  // the counts free of regression
  showNumbers();
  showDownloads(body.query);
  clearTimeout(detailsTimer);
  for (const id of ["certificate-status", "pattern", "domain"]) $(id).classList.add("stale");
  detailsTimer = setTimeout(() => details(body.query), 350);
}

function showNumbers() {
  const rows = Object.entries(state.preview.numbers).map(([k, v]) => `<tr><td>${LABELS[k] ?? k}</td><td>${fmt(v)}</td></tr>`);
  const m = state.preview.motion;
  const angle = view.angle;
  rows.push(`<tr><td>fold angle 2α</td><td>${angle.toFixed(1)}°</td></tr>`);
  if (m.lift_off) rows.push(`<tr><td>lift-off of the feet</td><td id="lift-off">${fmt(view.sample(m.lift_off))}</td></tr>`);
  const end = m.end === "first contact" ? (state.contact === undefined ? "…" : state.contact === null ? "none up to 179°" : `${state.contact.toFixed(0)}°`)
    : `${m.angles[m.angles.length - 1].toFixed(1)}°`;
  rows.push(`<tr><td>fold range ends (${m.end})</td><td>${end}</td></tr>`);
  $("numbers").innerHTML = rows.join("");
}

function showDownloads(query) {
  const kind = state.kind, links = [];
  for (const f of state.schema.formats) {
    if (f.kinds.includes(kind)) links.push(`<a href="/api/${kind}.${f.name}?${query}" download title="${f.holds}">${f.name.toUpperCase()}</a>`);
  }
  links.push(`<a href="/api/${kind}.zip?${query}" download title="the whole output folder, report included">folder (zip)</a>`);
  links.push(`<a href="/api/${kind}.toml?${query}" download title="the design file: curvefold ${kind} FILE rebuilds it">design (TOML)</a>`);
  $("downloads").innerHTML = links.join(" ");
}

async function details(query) {
  const current = () => state.preview && state.preview.query === query;
  const get = async (path) => {
    const r = await fetch(`/api/${state.kind}/${path}?${query}`);
    return r.ok ? r : null;
  };
  if (state.kind === "vault") {  // where the fold slider stops
    const found = await get("contact");
    if (found && current()) {
      state.contact = (await found.json()).first_contact;
      const last = state.preview.motion.angles.at(-1);
      $("fold").max = state.contact ?? last;
      if (view.angle > Number($("fold").max)) view.setAngle(Number($("fold").max));
      showNumbers();
    }
  }
  const cert = await get("certificate");
  if (cert && current()) {
    const checks = await cert.json();
    const passed = checks.filter((c) => c.passed).length;
    $("certificate-status").innerHTML = `<span class="${passed === checks.length ? "ok" : "bad"}">${passed}/${checks.length} checks pass</span>`;
    $("certificate").innerHTML = checks.map((c) => `<li class="${c.passed ? "" : "fail"}" title="${c.meaning}">${c.passed ? "✓" : "✗"} ${c.name}: ${c.value.toExponential(2)} (tolerance ${c.tolerance.toExponential(1)})</li>`).join("");
    $("certificate-status").classList.remove("stale");
  }
  if (state.kind === "crease") {
    $("pattern").replaceChildren(); $("domain").replaceChildren();
    $("pattern-status").textContent = "(for tubes, blocks and vaults)";
    return;
  }
  const domain = await get("domain.svg");
  if (domain && current()) images($("domain"), [await domain.text()]);
  $("pattern-status").textContent = "(laying out…)";
  const pattern = await get("pattern");
  if (pattern && current()) {
    const pages = (await pattern.json()).pages;
    images($("pattern"), pages);
    $("pattern-status").textContent = `(${pages.length} page${pages.length > 1 ? "s" : ""}, preview samples)`;
  }
}

function images(box, svgs) {
  box.querySelectorAll("img").forEach((img) => URL.revokeObjectURL(img.src));
  box.replaceChildren(...svgs.map((svg) => Object.assign(new Image(), { src: URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" })) })));
  box.classList.remove("stale");
}

// -- the 3D view ---------------------------------------------------------------------------------

const view = {
  angle: 90, motion: null, states: null, fitted: false,

  init() {
    const canvas = $("canvas");
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf6f5f2);
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.001, 1000);
    this.camera.up.set(0, 0, 1);  // the model's z is up
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener("change", () => this.render());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8d8470, 2.0));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(-2, -3, 5);
    this.scene.add(sun);
    this.positions = new THREE.BufferAttribute(new Float32Array(3), 3);
    const surface = new THREE.BufferGeometry();
    surface.setAttribute("position", this.positions);
    this.surface = new THREE.Mesh(surface, new THREE.MeshStandardMaterial({ color: 0xdcdcd9, side: THREE.DoubleSide, flatShading: true, roughness: 0.85 }));
    this.surface.frustumCulled = false;
    this.scene.add(this.surface);
    this.lines = new THREE.Group();
    this.scene.add(this.lines);
    this.ground = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), new THREE.MeshStandardMaterial({ color: 0xece6da, roughness: 1 }));
    this.scene.add(this.ground);
    new ResizeObserver(() => this.resize()).observe($("view"));
    this.resize();
  },

  resize() {
    const box = $("view").getBoundingClientRect();
    this.renderer.setSize(box.width, box.height, false);
    this.camera.aspect = box.width / Math.max(box.height, 1);
    this.camera.updateProjectionMatrix();
    this.render();
  },

  load(motion, colours) {
    const bytes = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0)).buffer;
    const atDesign = !this.motion || Math.abs(this.angle - this.motion.design_angle) < 1e-9;
    this.motion = motion;
    this.states = new Float32Array(bytes(motion.positions));
    const n = motion.vertices * 3;
    if (this.positions.array.length !== n) {
      this.positions = new THREE.BufferAttribute(new Float32Array(n), 3);
      this.surface.geometry.setAttribute("position", this.positions);
    }
    this.surface.geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(motion.triangles)), 1));
    this.lines.children.forEach((l) => l.geometry.dispose());
    this.lines.clear();
    for (const [kind, b64] of Object.entries(motion.lines)) {
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", this.positions);
      g.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(b64)), 1));
      const line = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: colours[kind] ?? "#3a3a3a" }));
      line.frustumCulled = false;
      this.lines.add(line);
    }
    // The ground under every state, grown by 8 % of its larger side.
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < this.states.length; i += 3) for (let c = 0; c < 3; c++) {
      lo[c] = Math.min(lo[c], this.states[i + c]); hi[c] = Math.max(hi[c], this.states[i + c]);
    }
    const size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    this.ground.visible = motion.ground;
    this.ground.scale.set(hi[0] - lo[0] + 0.16 * size, hi[1] - lo[1] + 0.16 * size, 1);
    this.ground.position.set((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, -1e-3 * size);
    const fold = $("fold");
    const last = motion.angles[motion.angles.length - 1];
    fold.max = last;
    fold.disabled = motion.angles.length < 2;
    this.setAngle(atDesign ? motion.design_angle : Math.min(this.angle, last));
    if (!this.fitted) this.fit(lo, hi);
  },

  fit(lo, hi) {  // look at the box of every state from the azimuth and elevation of the figures, the whole box in view
    const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
    const radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    const fov = THREE.MathUtils.degToRad(this.camera.fov) / 2;
    const d = 1.05 * radius / Math.sin(Math.min(fov, Math.atan(Math.tan(fov) * this.camera.aspect)));
    const az = THREE.MathUtils.degToRad(-50), el = THREE.MathUtils.degToRad(22);
    this.camera.position.set(centre.x + d * Math.cos(el) * Math.cos(az), centre.y + d * Math.cos(el) * Math.sin(az), centre.z + d * Math.sin(el));
    this.camera.near = radius / 1000; this.camera.far = radius * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    this.fitted = true;
  },

  // Where an angle falls between the precomputed states: (index, fraction).
  bracket(angle) {
    const a = this.motion.angles;
    let i = 0;
    while (i < a.length - 2 && a[i + 1] < angle) i++;
    return a.length < 2 ? [0, 0] : [i, Math.min(1, Math.max(0, (angle - a[i]) / (a[i + 1] - a[i])))];
  },

  sample(values) {  // a per-state number at the current angle
    const [i, t] = this.bracket(this.angle);
    return values[i] * (1 - t) + values[Math.min(i + 1, values.length - 1)] * t;
  },

  setAngle(angle) {
    this.angle = angle;
    const [i, t] = this.bracket(angle);
    const n = this.positions.array.length, A = this.states, P = this.positions.array;
    const a = i * n, b = Math.min(i + 1, this.motion.angles.length - 1) * n;
    for (let j = 0; j < n; j++) P[j] = A[a + j] * (1 - t) + A[b + j] * t;
    this.positions.needsUpdate = true;
    $("fold").value = angle;
    $("fold-value").textContent = `${angle.toFixed(1)}°${Math.abs(angle - this.motion.design_angle) < 0.05 ? " (design)" : ""}`;
    const lift = $("lift-off");
    if (lift && this.motion.lift_off) lift.textContent = fmt(this.sample(this.motion.lift_off));
    this.render();
  },

  render() { if (this.renderer) this.renderer.render(this.scene, this.camera); },
};

state.view = view;

// -- the fold slider: plays in the browser, no request ---------------------------------------------

let playing = null;
function play() {
  if (playing) { cancelAnimationFrame(playing); playing = null; $("play").textContent = "▶"; return; }
  $("play").textContent = "❚❚";
  const end = Number($("fold").max), period = 6000, start = performance.now();
  const step = (now) => {
    const phase = ((now - start) % period) / period;
    view.setAngle(end * (phase < 0.5 ? 2 * phase : 2 - 2 * phase));
    state.frames = (state.frames ?? 0) + 1;
    playing = requestAnimationFrame(step);
  };
  playing = requestAnimationFrame(step);
}

// -- start ----------------------------------------------------------------------------------------

async function start() {
  state.schema = await (await fetch("/api/schema")).json();
  const params = new URLSearchParams(location.search);
  state.kind = state.schema.kinds[params.get("kind")] ? params.get("kind") : "vault";
  for (const [k, v] of params) if (k !== "kind") state.values[k] = v;
  state.mode = state.schema.targets.some((t) => t.name in state.values) ? "targets" : "parameters";
  document.querySelector(`input[name=mode][value=${state.mode}]`).checked = true;
  const kind = $("kind");
  for (const k of Object.keys(state.schema.kinds)) kind.append(new Option(k, k, false, k === state.kind));
  kind.addEventListener("change", () => {
    state.kind = kind.value; state.values = {}; state.mode = "parameters"; view.fitted = false;
    document.querySelector("input[name=mode][value=parameters]").checked = true;
    buildControls(); request();
  });
  document.querySelectorAll("input[name=mode]").forEach((r) => r.addEventListener("change", () => {
    state.mode = r.value;
    const n = state.preview?.numbers ?? {};
    for (const t of state.schema.targets) {
      if (state.mode === "targets") { state.values[t.name] = fmt(n[t.name]); delete state.values[t.replaces]; }
      else { delete state.values[t.name]; if (n[t.replaces] !== undefined) state.values[t.replaces] = fmt(n[t.replaces]); }
    }
    if (state.mode === "targets" && (state.values.tubes ?? "max") === "max") state.values.tubes = String(n.tubes);
    buildControls(); request();
  }));
  $("fold").addEventListener("input", (e) => view.setAngle(Number(e.target.value)));
  $("play").addEventListener("click", play);
  $("to-design").addEventListener("click", () => view.setAngle(view.motion.design_angle));
  view.init();
  buildControls();
  request();
}

start();
