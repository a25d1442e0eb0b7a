// The controls, generated from the design schema: a field per parameter (a text box, with a
// slider for numbers, a list for choices, a box for flags), grouped by section.
import { byId, el } from "./dom.js";
import { unitShown } from "./format.js";
import { specsOf } from "./state.js";

const NUMBERS = ["real", "integer", "count"];

/**
 * The slider of a spec, `{lo, hi, step}`, or null without a range. Its span: the typical span
 * if the spec names one; else its range when within ten times the default; else from the
 * range's lower end (or a fifth of a nonzero default) to five times the default (or 5). Its
 * step, a power of ten near a 400th of the span (1 for whole numbers), so that round values
 * such as 0.5 lie on its grid; the span's ends are rounded inwards to the grid.
 */
export function sliderRange(spec) {
  const r = spec.range, d = Math.abs(Number(spec.default)) || 0;
  let lo, hi;
  if (spec.typical) [lo, hi] = [spec.typical.lo, spec.typical.hi];
  else if (!r) return null;
  else if (r.lo !== null && r.hi !== null && r.hi - r.lo <= 10 * Math.max(d, 1)) {
    [lo, hi] = [r.lo, r.hi];
  } else {
    lo = Math.max(r.lo ?? -Infinity, d > 0 ? d / 5 : 0);
    hi = Math.min(r.hi ?? Infinity, 5 * Math.max(d, 1));
  }
  if (spec.kind !== "real") {
    return { lo: Math.ceil(lo), hi: Math.floor(hi), step: 1 };
  }
  const power = Math.floor(Math.log10((hi - lo) / 400));
  const step = Number(`1e${power}`);
  // the grid's point at or inside an end (a value a hair off the grid counts as on it)
  const onGrid = (v, round) => {
    const q = v / step, near = Math.round(q);
    return Number(`${Math.abs(q - near) < 1e-9 ? near : round(q)}e${power}`);
  };
  return { lo: onGrid(lo, Math.ceil), hi: onGrid(hi, Math.floor), step };
}

function unitOf(state, spec) {
  if (spec.name === "width" && state.kind === "vault") return "× radius";
  return unitShown(state.schema, spec.unit || "");
}

function shownValue(state, spec) {
  if (state.values[spec.name] !== undefined) return state.values[spec.name];
  if (spec.default === null) return "";
  return String(Array.isArray(spec.default) ? JSON.stringify(spec.default) : spec.default);
}

// One parameter's field; `on.change(spec, text)` on every edit, `on.commit()` when one ends.
function field(state, spec, on, extraClass = "") {
  const box = el("div", { className: `field ${extraClass}`, dataset: { key: spec.name } });
  const id = `field-${spec.name}`, words = spec.label || spec.name;
  const label = el("label", { className: "name", title: spec.describe, htmlFor: id },
    el("span", {},
      el("span", { className: "words" }, words), " ",
      el("span", { className: "symbol" }, spec.name)),
    el("span", { className: "unit" }, unitOf(state, spec)));
  const row = el("div", { className: "row" });
  const value = shownValue(state, spec);
  let input;
  if (spec.kind === "choice") {
    input = el("select");
    if (spec.default === null) input.append(new Option("—", "", false, value === "")); // none
    for (const c of spec.choices) input.append(new Option(c, c, false, c === value));
  } else if (spec.kind === "flag") {
    input = el("input", { type: "checkbox", checked: value === "true" });
  } else {
    const numeric = NUMBERS.includes(spec.kind);
    input = el("input", { type: "text", value, className: numeric ? "value" : "text",
      placeholder: spec.default === null ? "(none)" : "" });
    const range = numeric ? sliderRange(spec) : null;
    if (range) {
      const slider = el("input", { type: "range", min: range.lo, max: range.hi,
        step: range.step });
      slider.setAttribute("aria-label", `${words}, slider`);
      // an optional value left empty: the slider at its lowest
      slider.value = value === "" || !isFinite(Number(value)) ? range.lo : Number(value);
      slider.addEventListener("input", () => {
        input.value = slider.value;
        on.change(spec, input.value);
      });
      slider.addEventListener("change", on.commit);
      input.addEventListener("input", () => {
        if (isFinite(Number(input.value)) && input.value !== "") slider.value = input.value;
      });
      row.append(slider);
    }
  }
  input.name = spec.name;
  input.id = id;
  input.setAttribute("aria-describedby", `${id}-error`);
  const live = spec.kind === "flag" || spec.kind === "choice";
  input.addEventListener(live ? "change" : "input",
    () => on.change(spec, spec.kind === "flag" ? String(input.checked) : input.value));
  input.addEventListener("change", on.commit);
  row.prepend(input);
  if (spec.kind === "count") {
    // "max": the count follows regression; the slider shows the count it gives
    const max = el("input", { type: "checkbox", checked: value === "max" });
    max.addEventListener("change", () => {
      input.value = max.checked ? "max" : String(state.preview?.numbers?.[spec.name] ?? 1);
      on.change(spec, input.value);
      on.commit();
      showCounts(state);
    });
    max.setAttribute("aria-label", `${words}: as many as regression allows (max)`);
    row.append(el("label", {}, max, " max"));
  }
  box.append(label, row, el("div", { className: "error", id: `${id}-error` }));
  return box;
}

/** A count set to "max" shows the count the design has, its slider disabled. */
export function showCounts(state) {
  const n = state.preview?.numbers;
  for (const box of document.querySelectorAll(".field")) {
    const max = box.querySelector("label:not(.name) input[type=checkbox]");
    if (!max) continue;
    const slider = box.querySelector("input[type=range]"), key = box.dataset.key;
    // the counts free of regression
    if (slider && n?.max_tubes && key === "tubes") slider.max = Math.max(n.max_tubes, 1);
    const isMax = (state.values[key] ?? "max") === "max";
    max.checked = isMax;
    if (slider) {
      slider.disabled = isMax;
      if (isMax && n?.[key] !== undefined) slider.value = n[key];
    }
  }
}

/** The fields of the state's kind and mode, in the form; `on` as for each field. */
export function buildControls(state, on) {
  const form = byId("fields");
  form.replaceChildren();
  const groups = {};
  const targets = state.kind === "vault" && state.mode === "targets";
  for (const spec of specsOf(state)) {
    const section = spec.section || "design";
    if (!groups[section]) {
      groups[section] = section === "output"
        ? el("details", {}, el("summary", {}, "output files"))
        : el("fieldset", {}, el("legend", {}, section));
      form.append(groups[section]);
    }
    const replaced = targets && state.schema.targets.some((t) => t.replaces === spec.name);
    const f = field(state, spec, on, replaced ? "solved" : "");
    if (replaced) f.querySelectorAll("input").forEach((i) => (i.disabled = true));
    groups[section].append(f);
  }
  if (targets) {
    form.prepend(el("fieldset", {}, el("legend", {}, "targets"),
      ...state.schema.targets.map((spec) => field(state, spec, on))));
  }
  byId("mode").hidden = state.kind !== "vault";
  document.querySelector(`input[name=mode][value=${state.mode}]`).checked = true;
  showCounts(state);
}
