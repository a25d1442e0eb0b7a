// The curvefold designer page: controls generated from the design schema, a 3D view that
// morphs between precomputed fold states with the span and rise drawn as dimensions, the
// numbers (beside those of a kept design to compare with), the design under load once a
// material is chosen, the certificate and crease pattern (coarse first, then full), the
// downloads at the slider's angle. The design lives in this page's URL only: every change
// is a step of the browser's history (Back undoes it).
//
// This module wires the others together and runs what follows a change; the page's state
// (state.js) is passed to each explicitly.
import * as api from "./api.js";
import { buildControls, showCounts } from "./controls.js";
import { busy } from "./busy.js";
import { byId } from "./dom.js";
import { fmt } from "./format.js";
import { resetDeploy, showDeployment } from "./curves.js";
import { createHistory, readURL } from "./history.js";
import { showAngle, showDownloads, showMarks, showNumbers } from "./numbers.js";
import { showCertificate, showImages, showMechanics, showPattern, why } from "./results.js";
import { createState, designQuery, loadKeys, underLoad } from "./state.js";
import { View } from "./view.js";

// -- a change: its preview, then what follows it -----------------------------------------------

/** The page: its state, 3D view and history, and the requests under way. */
function createPage() {
  const state = createState();
  const page = {
    state, history: createHistory(state),
    inflight: false, again: false, details: null, playing: null, // the requests, the play
  };
  page.view = state.view = new View(state, {
    canvas: byId("canvas"), container: byId("view"), legend: byId("legend"),
    onAngle: () => showAngle(state, page.view),
  });
  page.controls = {
    change: (spec, text) => changed(page, spec, text),
    commit: () => page.history.endGesture(),
  };
  return page;
}

function changed(page, spec, text) {
  const { state } = page;
  const def = spec.default === null ? "" : String(spec.default);
  // a target, or a material or load typed (even its default: it asks for the analysis), stays
  const kept = state.schema.targets.some((t) => t.name === spec.name)
    || (loadKeys(state).has(spec.name) && text !== "");
  if (text === def && !kept) delete state.values[spec.name];
  else state.values[spec.name] = text;
  state.input = performance.now();
  page.history.remember();
  request(page);
}

/** Ask for the preview of the state's design; a change made meanwhile is asked for next. */
async function request(page) {
  if (page.inflight) {
    page.again = true;
    return;
  }
  page.inflight = true;
  const { state } = page;
  const started = state.input ?? performance.now();
  const { ok, body } = await api.preview(state.kind, designQuery(state.values));
  page.inflight = false;
  if (page.again) { // a newer change waits: show that one
    page.again = false;
    request(page);
    return;
  }
  if (ok) show(page, body, started);
  else refuse(body);
}

/** A refused design: its message at the field at fault, or over the view; a time-out (503,
 * 504: not the design's fault) there as a notice, in the server's own words. */
function refuse(body) {
  clearErrors();
  const box = body.key && document.querySelector(`.field[data-key="${body.key}"]`);
  if (box && !body.stopped) {
    box.classList.add("invalid");
    box.querySelector(".error").textContent = body.error;
  } else {
    const message = byId("message");
    message.textContent = body.error;
    message.classList.toggle("notice", !!body.stopped);
    message.setAttribute("role", body.stopped ? "status" : "alert");
    message.hidden = false;
  }
}

function clearErrors() {
  byId("message").hidden = true;
  document.querySelectorAll(".field.invalid").forEach((f) => {
    f.classList.remove("invalid");
    f.querySelector(".error").textContent = "";
  });
}

function show(page, body, started) {
  const { state, view } = page;
  clearErrors();
  const previous = state.preview;
  state.preview = body;
  if (state.mode === "targets") { // the solved parameters
    for (const name of ["a", "p_xy", "radius", "tubes"]) {
      const input = document.querySelector(`.field[data-key="${name}"] input.value`);
      const solved = body.numbers[name] !== undefined && (name !== "tubes" || body.note);
      if (input && solved) input.value = fmt(body.numbers[name]);
    }
  }
  byId("note").textContent = body.note;
  byId("note").hidden = !body.note;
  const timing = {};
  state.contact = undefined;
  state.stopped = false;
  resetDeploy(state);
  for (const id of ["certificate-status", "certificate", "pattern", "domain", "mechanics"]) {
    byId(id).classList.add("stale");
  }
  follow(page, body, started, timing); // asked first: the server works while the page draws
  const fold = byId("fold");
  fold.max = body.motion.angles.at(-1);
  fold.disabled = body.motion.angles.length < 2;
  view.load(body, previous);
  timing.view = performance.now() - started;
  state.timings.push(timing);
  showCounts(state);
  showMarks(state);
  showNumbers(state, view);
  showDownloads(state, view);
}

// What follows a change: first the coarse certificate and pattern (within a second) and the
// first contact, which the quick lane answers in this order; then the regression domain and
// the full certificate and pattern, which the heavy lane computes side by side. A newer
// change aborts what is left of these requests, and the server stops their work.
async function follow(page, body, started, timing) {
  const { state, view } = page;
  page.details?.abort();
  const controller = page.details = new AbortController();
  const current = () => state.preview === body && !controller.signal.aborted;
  const get = (path, json = true) =>
    api.detail(body.kind, path, body.query, { signal: controller.signal, json });
  const when = (promise, then) => promise.then((found) => { if (current()) then(found); });
  const sheets = body.kind !== "crease";
  if (!sheets) {
    byId("pattern").replaceChildren();
    byId("domain").replaceChildren();
    byId("pattern-status").textContent = "(for tubes, blocks and vaults)";
  }
  // show what was found and when (in timing[key]): the page's state holds the latest
  const shown = (showIt, key) => (found) => {
    showIt(state, found);
    timing[key] = performance.now() - started;
  };
  await Promise.all([
    when(get("certificate?coarse=true"), shown(showCertificate, "certificate")),
    sheets && when(get("pattern?coarse=true"), shown(showPattern, "pattern")),
    body.kind === "vault" && when(get("contact"), (found) => { // where the fold slider stops
      if (!found || found.error) return;
      state.contact = found.first_contact;
      const fold = byId("fold");
      fold.max = state.contact ?? body.motion.angles.at(-1);
      if (view.angle > Number(fold.max)) view.setAngle(Number(fold.max));
      showMarks(state);
      showNumbers(state, view);
    }),
  ]);
  if (!current()) return;
  const loaded = underLoad(state);
  if (!loaded) showMechanics(state, null);
  else byId("mechanics-status").textContent = "";
  // the heavy work, said as under way in its panel until its answer comes (or a newer change)
  const working = (id, name, promise) => promise.finally(busy(byId(id).closest("section"), name));
  await Promise.all([
    loaded && working("mechanics", state.values.nonlinear === "true"
      ? "Following the design to collapse (large displacements: slow)"
      : "Computing the design under load (bar-and-hinge model)",
      when(get("mechanics"), shown(showMechanics, "mechanics"))),
    sheets && working("domain", "Drawing the regression domain",
      when(get("domain.svg", false), (found) => {
        if (typeof found !== "string") return;
        showImages(byId("domain"), [found], () => "the regression domain of the design");
      })),
    working("certificate", "Checking the full certificate",
      when(get("certificate"), shown(showCertificate, "full_certificate"))),
    sheets && working("pattern", "Drawing the crease pattern pages",
      when(get("pattern"), shown(showPattern, "full_pattern"))),
  ]);
  if (current()) timing.settled = performance.now() - started;
}

/** Deploy the design shown (a heavy job on the button): its actuation curve and peaks. */
async function deploy(page) {
  const { state } = page, body = state.preview;
  if (!body) return;
  resetDeploy(state);
  const controller = state.deployRequest = new AbortController();
  const done = busy(byId("deployment"), "Deploying the design from 10° under its own weight");
  const found = await api.detail(body.kind, "deploy", body.query, { signal: controller.signal });
  done();
  if (!controller.signal.aborted && state.preview === body) showDeployment(state, found, why);
}

// -- the fold slider: plays in the browser, no request ------------------------------------------

function play(page) {
  const { state, view } = page;
  if (page.playing) {
    cancelAnimationFrame(page.playing);
    page.playing = null;
    byId("play").textContent = "▶";
    showDownloads(state, view);
    return;
  }
  byId("play").textContent = "❚❚";
  const end = Number(byId("fold").max), period = 6000, start = performance.now();
  const step = (now) => {
    const phase = ((now - start) % period) / period;
    view.setAngle(end * (phase < 0.5 ? 2 * phase : 2 - 2 * phase));
    state.frames += 1;
    page.playing = requestAnimationFrame(step);
  };
  page.playing = requestAnimationFrame(step);
}

// -- comparing: keep a design, see the next ones beside it --------------------------------------

async function keep(page, address) {
  const { state } = page;
  const kind = new URLSearchParams(address).get("kind");
  const { ok, body: preview } = await api.preview(kind, address.replace(/^kind=[^&]*&?/, ""));
  if (!ok) return;
  state.kept = { address, preview, contact: undefined };
  if (preview.kind === "vault") {
    const found = await api.detail("vault", "contact", preview.query);
    if (found && !found.error) state.kept.contact = found.first_contact;
  }
  showCompare(page);
}

function showCompare(page) {
  const { state, view } = page;
  byId("drop").hidden = byId("compare-mode").hidden = !state.kept;
  if (!state.preview) return; // the first preview places it
  view.placeKept();
  view.setAngle(view.angle);
  view.fit();
  showNumbers(state, view);
}

// -- start ---------------------------------------------------------------------------------------

/** A fresh start: the controls of the new kind or mode, its design asked for. */
function restart(page) {
  buildControls(page.state, page.controls);
  page.state.input = performance.now();
  page.history.remember();
  page.history.endGesture();
  request(page);
}

async function start() {
  const page = createPage();
  const { state, view } = page;
  window.curvefold = state;
  state.schema = await api.schema();
  const compare = readURL(state);
  const kind = byId("kind");
  for (const k of Object.keys(state.schema.kinds)) {
    kind.append(new Option(k, k, false, k === state.kind));
  }
  kind.addEventListener("change", () => {
    state.kind = kind.value;
    state.values = {};
    state.mode = "parameters";
    restart(page);
  });
  document.querySelectorAll("input[name=mode]").forEach((r) => r.addEventListener("change", () => {
    state.mode = r.value;
    const n = state.preview?.numbers ?? {};
    for (const t of state.schema.targets) {
      if (state.mode === "targets") {
        state.values[t.name] = fmt(n[t.name]);
        delete state.values[t.replaces];
      } else {
        delete state.values[t.name];
        if (n[t.replaces] !== undefined) state.values[t.replaces] = fmt(n[t.replaces]);
      }
    }
    restart(page);
  }));
  window.addEventListener("popstate", () => { // Back and Forward: the design of that step
    const kept = readURL(state);
    kind.value = state.kind;
    buildControls(state, page.controls);
    state.input = performance.now();
    request(page);
    if ((kept ?? null) !== (state.kept?.address ?? null)) {
      if (kept) keep(page, kept);
      else {
        state.kept = null;
        showCompare(page);
      }
    }
  });
  byId("fold").addEventListener("input", (e) => view.setAngle(Number(e.target.value)));
  byId("fold").addEventListener("change", () => showDownloads(state, view));
  byId("play").addEventListener("click", () => play(page));
  byId("to-design").addEventListener("click", () => {
    view.setAngle(view.motion.design_angle);
    showDownloads(state, view);
  });
  byId("deploy").addEventListener("click", () => deploy(page));
  byId("undo").addEventListener("click", () => window.history.back());
  byId("redo").addEventListener("click", () => window.history.forward());
  byId("fit").addEventListener("click", () => view.fit());
  byId("pattern-close").addEventListener("click", () => byId("pattern-dialog").close());
  byId("keep").addEventListener("click", async () => {
    await keep(page, `kind=${state.preview.kind}&${state.preview.query}`);
    page.history.push();
  });
  byId("drop").addEventListener("click", () => {
    state.kept = null;
    showCompare(page);
    page.history.push();
  });
  byId("compare-mode").addEventListener("change", (e) => {
    state.compareMode = e.target.value;
    showCompare(page);
  });
  buildControls(state, page.controls);
  page.history.replace();
  if (compare) await keep(page, compare);
  request(page);
}

start();
