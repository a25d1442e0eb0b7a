// The curvefold designer page: controls generated from the design schema, a 3D view that
// morphs between precomputed fold states with the span and rise drawn as dimensions, the
// numbers (beside those of a kept design to compare with), the design under load once a
// material is chosen, the certificate and crease pattern (coarse first, then full), the
// downloads at the slider's angle. The design lives
// in this page's URL only: every change is a step of the browser's history (Back undoes it).
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const $ = (id) => document.getElementById(id);

// State of this page (exposed for scripts and tests as window.curvefold).
const state = {
  schema: null, kind: "vault", values: {}, mode: "parameters", preview: null, contact: undefined,
  kept: null, compareMode: "side", timings: [], frames: 0,
};
window.curvefold = state;

const fmt = (v) => (typeof v === "number" ? (Number.isInteger(v) ? String(v) : Math.abs(v) >= 1e-3 && Math.abs(v) < 1e6 ? String(Number(v.toPrecision(6))) : v.toExponential(3)) : String(v));
const escape = (text) => String(text).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c]));
const unitShown = (unit) => state.schema.units[unit] ?? unit;

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
  for (const section of ["", ...s.kinds[kind], "output"]) for (const spec of s.sections[section]) out.push(spec);
  return out;
}

function unitOf(spec) {
  if (spec.name === "width" && state.kind === "vault") return "× radius";
  return unitShown(spec.unit || "");
}

function field(spec, extraClass = "") {
  const box = document.createElement("div");
  box.className = `field ${extraClass}`;
  box.dataset.key = spec.name;
  const label = document.createElement("label");
  label.className = "name";
  label.title = spec.describe;
  label.innerHTML = `<span><span class="words">${escape(spec.label || spec.name)}</span> <span class="symbol">${escape(spec.name)}</span></span>`
    + `<span class="unit">${escape(unitOf(spec))}</span>`;
  const row = document.createElement("div");
  row.className = "row";
  const value = state.values[spec.name] ?? (spec.default === null ? "" : String(Array.isArray(spec.default) ? JSON.stringify(spec.default) : spec.default));
  let input;
  if (spec.kind === "choice") {
    input = document.createElement("select");
    if (spec.default === null) input.append(new Option("—", "", false, value === ""));  // none chosen
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
      slider.addEventListener("change", endGesture);
      input.addEventListener("input", () => { if (isFinite(Number(input.value)) && input.value !== "") slider.value = input.value; });
      row.append(slider);
    }
  }
  input.name = spec.name;
  const live = spec.kind === "flag" || spec.kind === "choice";
  input.addEventListener(live ? "change" : "input", () => changed(spec, spec.kind === "flag" ? String(input.checked) : input.value));
  input.addEventListener("change", endGesture);
  row.prepend(input);
  if (spec.kind === "count") {  // "max": the count follows regression; the slider shows the count it gives
    const max = document.createElement("label");
    max.innerHTML = `<input type="checkbox" ${value === "max" ? "checked" : ""}> max`;
    max.firstChild.addEventListener("change", (e) => {
      input.value = e.target.checked ? "max" : String(state.preview?.numbers?.[spec.name] ?? 1);
      changed(spec, input.value);
      endGesture();
      showCounts();
    });
    row.append(max);
  }
  const error = document.createElement("div");
  error.className = "error";
  box.append(label, row, error);
  return box;
}

function showCounts() {  // a count set to "max" shows the count the design has, its slider disabled
  for (const box of document.querySelectorAll(".field")) {
    const max = box.querySelector("label:not(.name) input[type=checkbox]");
    if (!max) continue;
    const slider = box.querySelector("input[type=range]"), key = box.dataset.key, n = state.preview?.numbers;
    if (slider && n?.max_tubes && key === "tubes") slider.max = Math.max(n.max_tubes, 1);  // the counts free of regression
    const isMax = (state.values[key] ?? "max") === "max";
    max.checked = isMax;
    if (slider) { slider.disabled = isMax; if (isMax && n?.[key] !== undefined) slider.value = n[key]; }
  }
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
  document.querySelector(`input[name=mode][value=${state.mode}]`).checked = true;
  showCounts();
}

function changed(spec, text) {
  const def = spec.default === null ? "" : String(spec.default);
  if (text === def && !state.schema.targets.some((t) => t.name === spec.name)) delete state.values[spec.name];
  else state.values[spec.name] = text;
  state.input = performance.now();
  remember();
  request();
}

// -- the browser's history holds every design: Back undoes a change, Forward redoes it ---------------------

let gesture = false;  // a slider being dragged (or a value being typed) is one step of the history

function pageURL() {
  const q = new URLSearchParams({ kind: state.kind });
  for (const [k, v] of Object.entries(state.values)) if (v !== "") q.append(k, v);
  if (state.kept) q.append("compare", state.kept.address);
  return `?${q}`;
}

function remember() {
  if (gesture) history.replaceState(null, "", pageURL());
  else { history.pushState(null, "", pageURL()); gesture = true; }
}

function endGesture() { gesture = false; }

function readURL() {
  const params = new URLSearchParams(location.search);
  state.kind = state.schema.kinds[params.get("kind")] ? params.get("kind") : "vault";
  state.values = {};
  for (const [k, v] of params) if (k !== "kind" && k !== "compare") state.values[k] = v;
  state.mode = state.kind === "vault" && state.schema.targets.some((t) => t.name in state.values) ? "targets" : "parameters";
  return params.get("compare");
}

// -- requests ------------------------------------------------------------------------------------

function currentQuery() {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(state.values)) if (v !== "") q.append(k, v);
  return q.toString();
}

let inflight = false, again = false, details = null;

async function request() {
  if (inflight) { again = true; return; }
  inflight = true;
  const query = currentQuery(), kind = state.kind, started = state.input ?? performance.now();
  let response, body;
  try {
    response = await fetch(`/api/${kind}/preview?${query}`);
    body = await response.json();
  } catch (err) {
    body = { error: `the designer's server did not answer (${err.message}); is 'curvefold designer' still running?`, key: null };
  }
  inflight = false;
  if (again) { again = false; request(); return; }  // a newer change waits: show that one
  if (response?.ok) show(body, started);
  else refuse(body);
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

function show(body, started) {
  clearErrors();
  const previous = state.preview;
  state.preview = body;
  if (state.mode === "targets") {  // the solved parameters
    for (const name of ["a", "p_xy", "radius", "tubes"]) {
      const input = document.querySelector(`.field[data-key="${name}"] input.value`);
      if (input && body.numbers[name] !== undefined && (name !== "tubes" || body.note)) input.value = fmt(body.numbers[name]);
    }
  }
  $("note").textContent = body.note;
  $("note").hidden = !body.note;
  const timing = {};
  state.contact = undefined;
  for (const id of ["certificate-status", "certificate", "pattern", "domain", "mechanics"]) $(id).classList.add("stale");
  follow(body, started, timing);  // asked first: the server works while the page draws
  view.load(body, previous);
  timing.view = performance.now() - started;
  state.timings.push(timing);
  showCounts();
  showMarks();
  showNumbers();
  showDownloads();
}

// What follows a change: first the coarse certificate and pattern (within a second) and the first contact,
// which the quick lane answers in this order; then the regression domain and the full certificate and pattern,
// which the heavy lane computes side by side. A newer change aborts what is left of these requests, and the
// server stops their work.
async function follow(body, started, timing) {
  details?.abort();
  const controller = details = new AbortController();
  const current = () => state.preview === body && !controller.signal.aborted;
  const get = async (path, json = true) => {
    try {
      const r = await fetch(`/api/${body.kind}/${path}${path.includes("?") ? "&" : "?"}${body.query}`, { signal: controller.signal });
      if (!r.ok) return r.status === 422 ? { error: (await r.json()).error } : null;
      return json ? await r.json() : await r.text();
    } catch { return null; }
  };
  const when = (promise, then) => promise.then((found) => { if (current()) then(found); });
  const sheets = body.kind !== "crease";
  if (!sheets) {
    $("pattern").replaceChildren(); $("domain").replaceChildren();
    $("pattern-status").textContent = "(for tubes, blocks and vaults)";
  }
  const first = [
    when(get("certificate?coarse=true"), (found) => { showCertificate(found); timing.certificate = performance.now() - started; }),
    sheets && when(get("pattern?coarse=true"), (found) => { showPattern(found); timing.pattern = performance.now() - started; }),
    body.kind === "vault" && when(get("contact"), (found) => {  // where the fold slider stops
      if (!found || found.error) return;
      state.contact = found.first_contact;
      $("fold").max = state.contact ?? body.motion.angles.at(-1);
      if (view.angle > Number($("fold").max)) view.setAngle(Number($("fold").max));
      showMarks();
      showNumbers();
    }),
  ];
  await Promise.all(first);
  if (!current()) return;
  const loaded = underLoad();
  if (!loaded) showMechanics(null);
  else $("mechanics-status").textContent = "(computing: the bar-and-hinge model of the design)";
  await Promise.all([
    loaded && when(get("mechanics"), (found) => { showMechanics(found); timing.mechanics = performance.now() - started; }),
    sheets && when(get("domain.svg", false), (found) => { if (typeof found === "string") images($("domain"), [found]); }),
    when(get("certificate"), (found) => { showCertificate(found); timing.full_certificate = performance.now() - started; }),
    sheets && when(get("pattern"), (found) => { showPattern(found); timing.full_pattern = performance.now() - started; }),
  ]);
  if (current()) timing.settled = performance.now() - started;
}

function showCertificate(found) {
  const status = $("certificate-status");
  if (!found || found.error) {
    status.innerHTML = `<span class="bad">${escape(found?.error ?? "the certificate could not be computed")}</span>`;
    $("certificate").replaceChildren();
  } else {
    const checks = found.checks, passed = checks.filter((c) => c.passed).length;
    const unresolved = checks.filter((c) => c.status === "insufficient resolution").length;
    const where = found.coarse ? ` <span class="coarse">(coarse: ${found.samples} samples, flat and at the design angle; the full certificate follows)</span>` : ` at ${found.samples} samples, in ${found.fold_angles.length} frames`;
    status.innerHTML = `<span class="${passed === checks.length ? "ok" : found.coarse && passed + unresolved === checks.length ? "coarse" : "bad"}">${passed}/${checks.length} checks pass</span>${where}`;
    $("certificate").innerHTML = checks.map((c) => {
      const kind = c.passed ? "" : c.status === "fail" ? "fail" : "unresolved";
      const mark = c.passed ? "✓" : c.status === "fail" ? "✗" : "…";
      const value = c.value === null ? "—" : `${c.value.toExponential(2)} (tolerance ${c.tolerance.toExponential(1)})`;
      return `<li class="${kind}" title="${escape(c.name)}: ${escape(c.measures)}">${mark} ${escape(c.title)}: ${value}</li>`;
    }).join("");
  }
  status.classList.remove("stale");
  $("certificate").classList.remove("stale");
  state.certificate = found;
}

function showPattern(found) {
  if (!found || found.error) {
    $("pattern-status").textContent = found?.error ? `(${found.error})` : "(not available)";
    return;
  }
  images($("pattern"), found.pages);
  const n = found.pages.length;
  $("pattern-status").textContent = found.coarse ? `(sketch of the sheets at ${found.samples} samples; the pages follow)` : `(${n} page${n > 1 ? "s" : ""} as cut, ${found.samples} samples)`;
  state.pattern = found;
}

// -- the design under load: once a material (or a load) is given, what curvefold load says of it ----------

function underLoad() {  // whether the design says what it is made of or what loads it
  const keys = new Set((state.schema.optional[state.kind] ?? []).flatMap((s) => state.schema.sections[s].map((spec) => spec.name)));
  return Object.keys(state.values).some((k) => keys.has(k) && state.values[k] !== "");
}

function showMechanics(found) {
  const table = $("mechanics"), status = $("mechanics-status");
  table.classList.remove("stale");
  state.mechanics = found;
  if (!found || found.error) {
    table.innerHTML = "";
    status.textContent = found?.error ? `(${found.error})` : state.kind === "crease" ? "(for tubes, blocks and vaults)"
      : "(choose a material or a thickness under “material” to see whether it stands)";
    return;
  }
  const n = found.numbers, rows = [];
  const load = Math.max(...n.applied_load.map(Math.abs));
  const balanced = (forces) => forces.map((f) => (Math.abs(f) <= 1e-9 * load ? 0 : f));  // the rounding of forces that balance the load
  for (const [key, [words, unit, explained]] of Object.entries(found.labels)) {
    if (!(key in n)) continue;
    const v = key === "reactions" ? balanced(n[key]) : n[key];
    const shown = v === null ? (key === "buckling_factor" ? "none" : "unknown") : Array.isArray(v) ? v.map(fmt).join(", ") : fmt(v);
    rows.push(`<tr data-key="${escape(key)}" title="${escape(explained)}"><td>${escape(words)}</td><td class="num">${escape(shown)}</td>`
      + `<td class="unit">${escape(unit)}</td></tr>`);
  }
  const lowest = n.frequencies.slice(0, 3).map((f) => String(Number(f.toPrecision(3)))).join(", ");
  rows.push(`<tr data-key="frequencies" title="the lowest free modes' frequencies (the first is the folding motion)"><td>lowest free frequencies</td>`
    + `<td class="num">${lowest}</td><td class="unit">Hz</td></tr>`);
  table.innerHTML = rows.join("");
  status.textContent = `${n.material} ${fmt(n.thickness * 1e3)} mm, ${n.supports} at the ${n.supported}${n.buckling_resolved ? "" : "; the buckling mode is not resolved at these samples"}`;
}

function images(box, svgs) {
  box.querySelectorAll("img").forEach((img) => URL.revokeObjectURL(img.src));
  box.replaceChildren(...svgs.map((svg) => Object.assign(new Image(), { src: URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" })) })));
  box.classList.remove("stale");
}

// -- numbers: in words with their units, beside the kept design's ----------------------------------

function showNumbers() {
  const p = state.preview, k = state.kept?.preview, m = p.motion;
  const head = k ? `<tr><th></th><th class="num">this design</th><th class="num">kept</th><th></th></tr>` : "";
  const rows = Object.entries(p.numbers).map(([key, v]) => {
    const [words, unit] = p.labels[key] ?? [key, ""];
    const other = k ? `<td class="num">${k.numbers[key] === undefined ? "—" : fmt(k.numbers[key])}</td>` : "";
    return `<tr><td>${escape(words)}</td><td class="num">${fmt(v)}</td>${other}<td class="unit">${escape(unit)}</td></tr>`;
  });
  const blank = k ? "<td></td>" : "";
  rows.push(`<tr class="motion"><td>fold angle 2α (slider)</td><td class="num" id="angle-now">${view.angle.toFixed(1)}</td>${blank}<td class="unit">°</td></tr>`);
  if (m.lift_off) rows.push(`<tr class="motion"><td>lift-off of the feet at 2α</td><td class="num" id="lift-off">${liftOff()}</td>${blank}<td class="unit">m</td></tr>`);
  if (m.end === "first contact") {
    const c = state.contact, shown = c === undefined ? "…" : c === null ? "none up to 179" : c.toFixed(0);
    const other = k ? `<td class="num">${state.kept.contact == null ? "—" : state.kept.contact.toFixed(0)}</td>` : "";
    rows.push(`<tr class="motion"><td>first contact (where the slider ends)</td><td class="num" id="first-contact">${shown}</td>${other}<td class="unit">°</td></tr>`);
  }
  $("numbers").innerHTML = head + rows.join("");
}

const liftOff = () => view.sample(state.preview.motion.lift_off).toFixed(4);  // metres, to a tenth of a millimetre

function showMarks() {  // the design angle and the first contact, marked under the fold slider
  const m = state.preview.motion, max = Number($("fold").max) || 1;
  const at = (angle, text, cls = "") => `<span class="${cls}" style="left:${(100 * angle / max).toFixed(2)}%">${text}</span>`;
  let marks = at(m.design_angle, `design ${m.design_angle.toFixed(0)}°`);
  if (state.contact) marks += at(state.contact, `first contact ${state.contact.toFixed(0)}°`, "contact");
  else if (m.end === "first contact" && state.contact === null) marks += at(max, "no contact up to 179°", "contact");
  $("marks").innerHTML = marks;
}

// -- downloads: every format, the whole folder and the design; files at the slider's angle -----------

function showDownloads() {
  const p = state.preview, kind = p.kind, links = [];
  const atDesign = Math.abs(view.angle - p.motion.design_angle) < 0.05 || p.kind === "crease";
  const q = atDesign ? p.query : `${p.query}&state=${view.angle.toFixed(1)}`;
  for (const f of state.schema.formats) {
    if (f.kinds.includes(kind)) links.push(`<a href="/api/${kind}.${f.name}?${q}" download title="${escape(f.holds)}">${escape(f.title)}</a>`);
  }
  links.push(`<a href="/api/${kind}.zip?${q}" download title="the whole output folder, report included">folder (zip)</a>`);
  links.push(`<a href="/api/${kind}.toml?${p.query}" download title="the design file: curvefold ${kind} FILE rebuilds it">design (TOML)</a>`);
  $("downloads").innerHTML = links.join(" ");
  $("downloads-state").textContent = atDesign ? "Files folded at the design angle." : `Files folded at 2α = ${view.angle.toFixed(1)}° (the slider's angle); the crease patterns are flat.`;
}

// -- the 3D view ---------------------------------------------------------------------------------

const bytes = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0)).buffer;

function boxOf(states) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < states.length; i += 3) for (let c = 0; c < 3; c++) {
    lo[c] = Math.min(lo[c], states[i + c]); hi[c] = Math.max(hi[c], states[i + c]);
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
    this.material = new THREE.MeshStandardMaterial({ color: colour, side: THREE.DoubleSide, flatShading: true, roughness: 0.85,
      transparent: opacity < 1, opacity, depthWrite: opacity >= 1 });
    this.surface = new THREE.Mesh(surface, this.material);
    this.surface.frustumCulled = false;
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
    this.surface.geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(motion.triangles)), 1));
    this.lines.children.forEach((l) => l.geometry.dispose());
    this.lines.clear();
    for (const [kind, b64] of Object.entries(motion.lines)) {
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", this.positions);
      g.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(b64)), 1));
      const line = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: colours[kind] ?? "#3a3a3a", transparent: lineOpacity < 1, opacity: lineOpacity }));
      line.frustumCulled = false;
      this.lines.add(line);
    }
    this.box = boxOf(this.states);
  }

  bracket(angle) {  // where an angle falls between the precomputed states: (index, fraction)
    const a = this.motion.angles;
    let i = 0;
    while (i < a.length - 2 && a[i + 1] < angle) i++;
    return a.length < 2 ? [0, 0] : [i, Math.min(1, Math.max(0, (angle - a[i]) / (a[i + 1] - a[i])))];
  }

  setAngle(angle) {
    const [i, t] = this.bracket(angle);
    const n = this.positions.array.length, A = this.states, P = this.positions.array;
    const a = i * n, b = Math.min(i + 1, this.motion.angles.length - 1) * n;
    for (let j = 0; j < n; j++) P[j] = A[a + j] * (1 - t) + A[b + j] * t;
    this.positions.needsUpdate = true;
  }
}

function textSprite(text, height) {  // a label that always faces the camera
  const canvas = document.createElement("canvas"), ctx = canvas.getContext("2d");
  ctx.font = "600 40px system-ui, sans-serif";
  canvas.width = Math.ceil(ctx.measureText(text).width) + 24; canvas.height = 56;
  ctx.font = "600 40px system-ui, sans-serif";
  ctx.fillStyle = "rgba(255,255,255,0.85)"; ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "#1a237e"; ctx.textBaseline = "middle"; ctx.fillText(text, 12, 29);
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: texture, depthTest: false }));
  sprite.scale.set(height * canvas.width / canvas.height, height, 1);
  sprite.renderOrder = 10;
  return sprite;
}

const view = {
  angle: 90, fittedSize: null,

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
    this.main = new Drawn(this.scene, 0xdcdcd9, 1);
    this.kept = new Drawn(this.scene, 0x7aa6e0, 0.45);
    this.kept.group.visible = false;
    this.ground = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), new THREE.MeshStandardMaterial({ color: 0xece6da, roughness: 1 }));
    this.scene.add(this.ground);
    this.dimensions = new THREE.Group();
    this.scene.add(this.dimensions);
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

  get motion() { return this.main.motion; },

  load(body, previous) {
    const atDesign = !previous || Math.abs(this.angle - previous.motion.design_angle) < 1e-9;
    this.main.load(body.motion, body.colours);
    this.drawDimensions(body);
    const fold = $("fold"), last = body.motion.angles[body.motion.angles.length - 1];
    fold.max = last;
    fold.disabled = body.motion.angles.length < 2;
    this.placeKept();
    this.setAngle(atDesign ? body.motion.design_angle : Math.min(this.angle, last));
    // fit again when the design's size changed by more than a fifth (or it is the first one)
    const size = this.main.box.size;
    if (!this.fittedSize || Math.abs(size / this.fittedSize - 1) > 0.2 || previous?.kind !== body.kind) this.fit();
  },

  drawDimensions(body) {  // the span and the rise as dimension lines, labelled in metres
    this.dimensions.children.forEach((c) => { c.geometry?.dispose(); c.material?.map?.dispose(); });
    this.dimensions.clear();
    const d = body.dimensions;
    if (!d) return;
    const size = this.main.box.size, tick = 0.03 * size, points = [];
    const line = (a, b, across) => {
      points.push(...a, ...b);
      for (const p of [a, b]) points.push(p[0] - across[0] * tick, p[1] - across[1] * tick, p[2] - across[2] * tick,
        p[0] + across[0] * tick, p[1] + across[1] * tick, p[2] + across[2] * tick);
    };
    const lift = 0.004 * size, s0 = [d.span.from[0], d.span.from[1], lift], s1 = [d.span.to[0], d.span.to[1], lift];
    line(s0, s1, [1, 0, 0]);
    const r0 = [...d.rise.from], r1 = [...d.rise.to];
    line(r0, r1, [1, 0, 0]);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.Float32BufferAttribute(points, 3));
    const lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0x1a237e, depthTest: false }));
    lines.renderOrder = 9;
    this.dimensions.add(lines);
    const span = textSprite(`span ${fmt(d.span.value)} m`, 0.055 * size);
    span.position.set((s0[0] + s1[0]) / 2 + 0.06 * size, (s0[1] + s1[1]) / 2, lift + 0.04 * size);
    const rise = textSprite(`rise ${fmt(d.rise.value)} m`, 0.055 * size);
    rise.position.set(r1[0] + 0.06 * size, r1[1], (r0[2] + r1[2]) / 2);
    this.dimensions.add(span, rise);
  },

  placeKept() {  // the kept design beside this one (along x), or over it
    const k = state.kept?.preview;
    if (!this.main.motion) return;
    this.kept.group.visible = !!k;
    if (!k) { $("legend").textContent = ""; return; }
    if (this.kept.motion !== k.motion) this.kept.load(k.motion, k.colours, 0.6);
    const side = state.compareMode === "side";
    const shift = side ? this.main.box.hi[0] - this.kept.box.lo[0] + 0.25 * Math.max(this.main.box.size, this.kept.box.size) : 0;
    this.kept.group.position.set(shift, 0, 0);
    $("legend").textContent = side ? "grey: this design · blue, on the right: the kept design" : "grey: this design · blue: the kept design, overlaid";
  },

  groundUnder() {  // the ground under every state of both designs, grown by 8 % of its larger side
    const boxes = [this.main.box];
    if (this.kept.group.visible) {
      const b = this.kept.box, x = this.kept.group.position.x;
      boxes.push({ lo: [b.lo[0] + x, b.lo[1], b.lo[2]], hi: [b.hi[0] + x, b.hi[1], b.hi[2]] });
    }
    const lo = [0, 1, 2].map((c) => Math.min(...boxes.map((b) => b.lo[c]))), hi = [0, 1, 2].map((c) => Math.max(...boxes.map((b) => b.hi[c])));
    return { lo, hi, size: Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) };
  },

  fit() {  // look at the box of every state from the azimuth and elevation of the figures, the whole box in view
    const { lo, hi, size } = this.groundUnder();
    this.ground.visible = this.main.motion.ground;
    this.ground.scale.set(hi[0] - lo[0] + 0.16 * size, hi[1] - lo[1] + 0.16 * size, 1);
    this.ground.position.set((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, -1e-3 * size);
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
    this.fittedSize = this.main.box.size;
    this.render();
  },

  sample(values) {  // a per-state number at the current angle
    const [i, t] = this.main.bracket(this.angle);
    return values[i] * (1 - t) + values[Math.min(i + 1, values.length - 1)] * t;
  },

  setAngle(angle) {
    this.angle = angle;
    const m = this.main.motion;
    this.main.setAngle(angle);
    if (this.kept.group.visible) this.kept.setAngle(Math.min(angle, this.kept.motion.angles.at(-1)));
    this.dimensions.visible = Math.abs(angle - m.design_angle) < 0.5;  // span and rise are the design's
    $("fold").value = angle;
    $("fold-value").textContent = `${angle.toFixed(1)}°${Math.abs(angle - m.design_angle) < 0.05 ? " (design)" : state.contact && angle >= state.contact - 0.05 ? " (contact)" : ""}`;
    const now = $("angle-now");
    if (now) now.textContent = angle.toFixed(1);
    const lift = $("lift-off");
    if (lift && m.lift_off) lift.textContent = liftOff();
    this.render();
  },

  render() { if (this.renderer) this.renderer.render(this.scene, this.camera); },
};

state.view = view;

// -- the fold slider: plays in the browser, no request ---------------------------------------------

let playing = null;
function play() {
  if (playing) { cancelAnimationFrame(playing); playing = null; $("play").textContent = "▶"; showDownloads(); return; }
  $("play").textContent = "❚❚";
  const end = Number($("fold").max), period = 6000, start = performance.now();
  const step = (now) => {
    const phase = ((now - start) % period) / period;
    view.setAngle(end * (phase < 0.5 ? 2 * phase : 2 - 2 * phase));
    state.frames += 1;
    playing = requestAnimationFrame(step);
  };
  playing = requestAnimationFrame(step);
}

// -- comparing: keep a design, see the next ones beside it ------------------------------------------

async function keep(address) {
  const response = await fetch(`/api/${new URLSearchParams(address).get("kind")}/preview?${address.replace(/^kind=[^&]*&?/, "")}`);
  if (!response.ok) return;
  const preview = await response.json();
  state.kept = { address, preview, contact: undefined };
  if (preview.kind === "vault") {
    const c = await fetch(`/api/vault/contact?${preview.query}`);
    if (c.ok) state.kept.contact = (await c.json()).first_contact;
  }
  showCompare();
}

function showCompare() {
  $("drop").hidden = $("compare-mode").hidden = !state.kept;
  if (!state.preview) return;  // the first preview places it
  view.placeKept();
  view.setAngle(view.angle);
  view.fit();
  if (state.preview) showNumbers();
}

// -- start ----------------------------------------------------------------------------------------

async function start() {
  state.schema = await (await fetch("/api/schema")).json();
  const compare = readURL();
  const kind = $("kind");
  for (const k of Object.keys(state.schema.kinds)) kind.append(new Option(k, k, false, k === state.kind));
  kind.addEventListener("change", () => {
    state.kind = kind.value; state.values = {}; state.mode = "parameters";
    buildControls(); state.input = performance.now(); remember(); endGesture(); request();
  });
  document.querySelectorAll("input[name=mode]").forEach((r) => r.addEventListener("change", () => {
    state.mode = r.value;
    const n = state.preview?.numbers ?? {};
    for (const t of state.schema.targets) {
      if (state.mode === "targets") { state.values[t.name] = fmt(n[t.name]); delete state.values[t.replaces]; }
      else { delete state.values[t.name]; if (n[t.replaces] !== undefined) state.values[t.replaces] = fmt(n[t.replaces]); }
    }
    buildControls(); state.input = performance.now(); remember(); endGesture(); request();
  }));
  window.addEventListener("popstate", () => {  // Back and Forward: the design of that step
    const kept = readURL();
    kind.value = state.kind;
    buildControls();
    state.input = performance.now();
    request();
    if ((kept ?? null) !== (state.kept?.address ?? null)) { if (kept) keep(kept); else { state.kept = null; showCompare(); } }
  });
  $("fold").addEventListener("input", (e) => view.setAngle(Number(e.target.value)));
  $("fold").addEventListener("change", showDownloads);
  $("play").addEventListener("click", play);
  $("to-design").addEventListener("click", () => { view.setAngle(view.motion.design_angle); showDownloads(); });
  $("undo").addEventListener("click", () => history.back());
  $("redo").addEventListener("click", () => history.forward());
  $("fit").addEventListener("click", () => view.fit());
  $("keep").addEventListener("click", async () => {
    await keep(`kind=${state.preview.kind}&${state.preview.query}`);
    history.pushState(null, "", pageURL());
  });
  $("drop").addEventListener("click", () => { state.kept = null; showCompare(); history.pushState(null, "", pageURL()); });
  $("compare-mode").addEventListener("change", (e) => { state.compareMode = e.target.value; showCompare(); });
  view.init();
  buildControls();
  history.replaceState(null, "", pageURL());
  if (compare) await keep(compare);
  request();
}

start();
