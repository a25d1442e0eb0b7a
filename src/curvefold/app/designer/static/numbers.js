// The numbers in words with their units (beside the kept design's), the fold slider's angle
// and marks, and the downloads at the slider's angle.
import { fileURL } from "./api.js";
import { byId, el } from "./dom.js";
import { sig4 } from "./format.js";

/** The feet's lift-off at the slider's angle, in metres to a tenth of a millimetre. */
const liftOff = (state, view) => view.sample(state.preview.motion.lift_off).toFixed(4);

const row = (cells, props = {}) => el("tr", props, ...cells);
const num = (text, id) => el("td", { className: "num", id }, text);
const unit = (text) => el("td", { className: "unit" }, text);

/** The numbers: the design's, the kept design's beside them, the motion's at the slider. */
export function showNumbers(state, view) {
  const p = state.preview, k = state.kept?.preview, m = p.motion;
  const rows = [];
  if (k) {
    rows.push(row([el("th"), el("th", { className: "num" }, "this design"),
      el("th", { className: "num" }, "kept"), el("th")]));
  }
  for (const [key, v] of Object.entries(p.numbers)) {
    const [words, u] = p.labels[key] ?? [key, ""];
    const other = k ? num(k.numbers[key] === undefined ? "—" : sig4(k.numbers[key])) : null;
    rows.push(row([el("td", {}, words), num(sig4(v)), other, unit(u)].filter(Boolean)));
  }
  const blank = () => (k ? el("td") : null);
  const motion = (cells) => row(cells.filter(Boolean), { className: "motion" });
  rows.push(motion([el("td", {}, "fold angle 2α (slider)"), num(view.angle.toFixed(1), "angle-now"),
    blank(), unit("°")]));
  if (m.lift_off) {
    rows.push(motion([el("td", {}, "lift-off of the feet at 2α"),
      num(liftOff(state, view), "lift-off"), blank(), unit("m")]));
  }
  if (m.end === "first contact") {
    const c = state.contact;
    const shown = c === undefined ? "…" : c === null ? "none up to 179" : c.toFixed(0);
    const kept = state.kept?.contact;
    const other = k ? num(kept == null ? "—" : kept.toFixed(0)) : null;
    rows.push(motion([el("td", {}, "first contact (where the slider ends)"),
      num(shown, "first-contact"), other, unit("°")]));
  }
  byId("numbers").replaceChildren(...rows);
}

/** The fold slider and what follows its angle: its value, the numbers' motion rows. */
export function showAngle(state, view) {
  const angle = view.angle, m = view.motion;
  byId("fold").value = angle;
  const design = Math.abs(angle - m.design_angle) < 0.05;
  const contact = state.contact && angle >= state.contact - 0.05;
  const where = design ? " (design)" : contact ? " (contact)" : "";
  byId("fold-value").textContent = `${angle.toFixed(1)}°${where}`;
  const now = byId("angle-now");
  if (now) now.textContent = angle.toFixed(1);
  const lift = byId("lift-off");
  if (lift && m.lift_off) lift.textContent = liftOff(state, view);
}

/** The design angle and the first contact, marked under the fold slider. */
export function showMarks(state) {
  const m = state.preview.motion, max = Number(byId("fold").max) || 1;
  const at = (angle, text, className) =>
    el("span", { className, style: { left: `${(100 * angle / max).toFixed(2)}%` } }, text);
  const marks = [at(m.design_angle, `design ${m.design_angle.toFixed(0)}°`)];
  if (state.contact) {
    marks.push(at(state.contact, `first contact ${state.contact.toFixed(0)}°`, "contact"));
  } else if (m.end === "first contact" && state.contact === null) {
    marks.push(at(max, "no contact up to 179°", "contact"));
  }
  byId("marks").replaceChildren(...marks);
}

/** Links to every format of the design, its folder and design file, at the slider's angle. */
export function showDownloads(state, view) {
  const p = state.preview, kind = p.kind;
  const atDesign = Math.abs(view.angle - p.motion.design_angle) < 0.05 || p.kind === "crease";
  const q = atDesign ? p.query : `${p.query}&state=${view.angle.toFixed(1)}`;
  const link = (href, title, text) => el("a", { href, title, download: "" }, text);
  const links = state.schema.formats.filter((f) => f.kinds.includes(kind))
    .map((f) => link(fileURL(kind, f.name, q), f.holds, f.title));
  links.push(link(fileURL(kind, "zip", q), "the whole output folder, report included",
    "folder (zip)"));
  links.push(link(fileURL(kind, "toml", p.query),
    `the design file: curvefold ${kind} FILE rebuilds it`, "design (TOML)"));
  byId("downloads").replaceChildren(...links.flatMap((a, i) => (i ? [" ", a] : [a])));
  byId("downloads-state").textContent = atDesign ? "Files folded at the design angle."
    : `Files folded at 2α = ${view.angle.toFixed(1)}° (the slider's angle); `
      + "the crease patterns are flat.";
}
