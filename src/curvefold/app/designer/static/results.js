// What the server works out after a preview: the certificate, the crease pattern and the
// regression domain (SVG), the design under load.
import { showCollapse } from "./curves.js";
import { byId, el } from "./dom.js";
import { architect, fmt } from "./format.js";

/**
 * SVG documents shown as images in `box` (the images shown before are released), each with
 * the text `alt(k)` for those who do not see it; `wrap(img, k)` may put each in an element.
 */
export function showImages(box, svgs, alt, wrap = (img) => img) {
  box.querySelectorAll("img").forEach((img) => URL.revokeObjectURL(img.src));
  const url = (svg) => URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" }));
  box.replaceChildren(...svgs.map((svg, k) =>
    wrap(Object.assign(new Image(), { src: url(svg), alt: alt(k) }), k)));
  box.classList.remove("stale");
}

/** A page of the crease pattern opened large in its dialog (Escape or the button closes it). */
function openPage(img, title) {
  const dialog = byId("pattern-dialog");
  byId("pattern-dialog-title").textContent = title;
  byId("pattern-large").replaceChildren(Object.assign(new Image(), { src: img.src, alt: img.alt }));
  dialog.showModal();
}

/** The crease pattern's pages as buttons that open each one large. */
function showPages(box, found) {
  const n = found.pages.length;
  const what = found.coarse ? "sketch of the sheets" : "page";
  const title = (k) => (found.coarse ? "Crease pattern: sketch of the sheets"
    : `Crease pattern: page ${k + 1} of ${n}`);
  showImages(box, found.pages, (k) => (found.coarse ? `crease pattern, ${what}`
    : `crease pattern, ${what} ${k + 1} of ${n}`), (img, k) => {
    const button = el("button", { type: "button", className: "page" }, img);
    button.setAttribute("aria-label", `open ${img.alt} large`);
    button.addEventListener("click", () => openPage(img, title(k)));
    return button;
  });
}

/**
 * Why a panel has no answer (`found`: an error of the API, or null): the refusal; a time-out's
 * sentence in the first panel that meets one, a short note in the next (said once per design).
 */
export function why(state, found, otherwise) {
  if (!found?.error) return otherwise;
  if (!found.stopped) return found.error;
  if (state.stopped) return "not computed within the designer's time limit either";
  state.stopped = true;
  return found.error;
}

function checkItem(c) {
  const className = c.passed ? "" : c.status === "fail" ? "fail" : "unresolved";
  const mark = c.passed ? "✓" : c.status === "fail" ? "✗" : "…";
  const value = c.value === null ? "—"
    : `${c.value.toExponential(2)} (tolerance ${c.tolerance.toExponential(1)})`;
  return el("li", { className, title: `${c.name}: ${c.measures}` }, `${mark} ${c.title}: ${value}`);
}

/** The certificate's checks (coarse first, then full), or why there are none. */
export function showCertificate(state, found) {
  const status = byId("certificate-status");
  if (!found || found.error) {
    const text = why(state, found, "the certificate could not be computed");
    status.replaceChildren(el("span", { className: "bad" }, text));
    byId("certificate").replaceChildren();
  } else {
    const checks = found.checks, passed = checks.filter((c) => c.passed).length;
    const unresolved = checks.filter((c) => c.status === "insufficient resolution").length;
    const where = found.coarse
      ? [" ", el("span", { className: "coarse" }, `(coarse: ${found.samples} samples, `
        + "flat and at the design angle; the full certificate follows)")]
      : [` at ${found.samples} samples, in ${found.fold_angles.length} frames`];
    const className = passed === checks.length ? "ok"
      : found.coarse && passed + unresolved === checks.length ? "coarse" : "bad";
    const summary = el("span", { className }, `${passed}/${checks.length} checks pass`);
    status.replaceChildren(summary, ...where);
    byId("certificate").replaceChildren(...checks.map(checkItem));
  }
  status.classList.remove("stale");
  byId("certificate").classList.remove("stale");
  state.certificate = found;
}

/** The crease pattern's pages (a coarse sketch first), or why there are none. */
export function showPattern(state, found) {
  const box = byId("pattern");
  box.querySelector("p.bad")?.remove();
  if (!found || found.error) { // why, in the panel (a sketch shown stays): not in its heading
    byId("pattern-status").textContent = !found?.error ? "(not available)"
      : box.querySelector("img") ? "(the sketch only)" : "";
    if (found?.error) box.append(el("p", { className: "bad" }, why(state, found, "")));
    box.classList.remove("stale");
    return;
  }
  showPages(box, found);
  const n = found.pages.length;
  byId("pattern-status").textContent = found.coarse
    ? `(sketch of the sheets at ${found.samples} samples; the pages follow)`
    : `(${n} page${n > 1 ? "s" : ""} as cut, ${found.samples} samples)`;
  state.pattern = found;
}

/** The design under load (what curvefold load says of it): its verdict first, then its
 * figures in an architect's units; or what to choose to see it. */
export function showMechanics(state, found) {
  const table = byId("mechanics"), status = byId("mechanics-status");
  const verdict = byId("mechanics-verdict");
  table.classList.remove("stale");
  state.mechanics = found;
  showCollapse(found?.error ? null : found);
  if (!found || found.error) {
    table.replaceChildren();
    verdict.replaceChildren();
    // the thickness field shows its default: say so, rather than ask for a thickness
    const thickness = document.querySelector('.field[data-key="thickness"] input.value')?.value;
    const shown = thickness ? `; ${fmt(Number(thickness) * 1e3)} mm is the thickness it will take`
      : "";
    status.textContent = found?.error ? `(${why(state, found, "")})`
      : state.kind === "crease" ? "(for tubes, blocks and vaults)"
        : `(choose a material, or type a thickness or a load, to see whether it stands${shown})`;
    return;
  }
  const n = found.numbers, rows = [];
  const stands = n.verdict === "stands";
  verdict.replaceChildren(el("span", { className: stands ? "ok" : "bad" },
    stands ? "Stands" : "Fails"), `: ${n.verdict_text.replace(/^(stands|fails): /, "")}`);
  const load = Math.max(...n.applied_load.map(Math.abs));
  // the rounding of forces that balance the load
  const balanced = (forces) => forces.map((f) => (Math.abs(f) <= 1e-9 * load ? 0 : f));
  const row = (key, title, words, shown, unit) => el("tr", { dataset: { key }, title },
    el("td", {}, words), el("td", { className: "num" }, shown),
    el("td", { className: "unit" }, unit));
  for (const [key, [words, unit, explained]] of Object.entries(found.labels)) {
    if (!(key in n)) continue;
    const v = key === "reactions" ? balanced(n[key]) : n[key];
    const [shown, shownUnit] = v === null ? [key === "buckling_factor" ? "none" : "unknown", unit]
      : architect(v, unit, { percent: key === "utilisation" });
    // its error, estimated against half the elements across (curvefold load's ± x %)
    const error = n.errors?.[key], percent = Math.max(100 * error, 0.01);
    const plus = typeof error !== "number" ? ""
      : ` ± ${percent >= 10 ? Math.round(percent) : percent.toPrecision(2)} %`;
    rows.push(row(key, explained, words, shown + plus, shownUnit));
  }
  const [lowest] = architect(n.frequencies.slice(0, 3), "Hz");
  rows.push(row("frequencies",
    "the lowest free modes' frequencies (the first is the folding motion)",
    "lowest free frequencies", lowest, "Hz"));
  const c = n.collapse; // followed to collapse (large displacements), if asked
  const sig = (v) => fmt(Number(v.toPrecision(4)));
  if (c) {
    const imperfect = c.imperfection_ratio ? `span / ${Math.round(1 / c.imperfection_ratio)}`
      : "none";
    rows.push(row("collapse_factor", `the governing combination (${c.combination}) followed `
      + `to collapse; imperfection ${imperfect}`, "collapse factor",
    `${sig(c.factor)} (${sig(c.knock_down)} × the linear ${sig(c.linear_factor)} `
      + `of ${c.combination})`, ""));
  }
  table.replaceChildren(...rows);
  const resolved = n.buckling_resolved ? ""
    : "; the buckling mode is not resolved at these samples";
  status.textContent = `${n.material} ${fmt(n.thickness * 1e3)} mm, `
    + `${n.supports} at the ${n.supported}${resolved}`;
}
