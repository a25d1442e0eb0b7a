// The curves of large-displacement mechanics in the "Under load" panel, drawn by the page from
// the server's numbers: the collapse path (load factor against the control displacement) and,
// on the deploy button, the deployment's actuation curve with its largest stress and its
// distance from the rigid-folding path. An answer with a value that is not a finite number is
// not drawn: the panel says so.
import { byId, el } from "./dom.js";
import { fmt, sig3 } from "./format.js";
import { finite, linePlot } from "./plot.js";

const DAMAGED = "the server's answer holds a value that is not a finite number: not drawn";

/** The collapse path of the design under load (`found`: the mechanics answer), or nothing. */
export function showCollapse(found) {
  const box = byId("collapse-plot");
  const c = found?.collapse_curve;
  if (!c) {
    box.replaceChildren();
    return;
  }
  const x = c.control_displacement_mm, y = c.load_factor;
  if (!finite(x, y) || !finite([c.linear_factor, c.factor]) || !(c.at_collapse in x)) {
    box.replaceChildren(el("p", { className: "bad" }, DAMAGED));
    return;
  }
  const ends = [Math.min(...x), Math.max(...x)];
  const where = `node ${c.control.node}, ${c.control.axis}`;
  box.replaceChildren(linePlot({
    id: "collapse-curve",
    title: "Load–displacement curve to collapse",
    description: `${y.length} states: the load factor rises to `
      + `${fmt(Number(c.factor.toPrecision(4)))} at collapse, against the linear buckling `
      + `factor ${sig3(c.linear_factor)} (dashed); `
      + `the control displacement (${where}) reaches ${sig3(x.at(-1))} mm.`,
    xLabel: `control displacement, ${where} (mm)`,
    yLabel: "load factor λ",
    series: [
      { x, y, label: "path" },
      { x: ends, y: [c.linear_factor, c.linear_factor], label: "linear λcr", dashed: true },
      { x: [x[c.at_collapse]], y: [c.factor], label: "collapse", marker: true },
    ],
  }));
}

/** The deploy button and its answer, for a new design: enabled for a kind with feet. */
export function resetDeploy(state) {
  state.deployRequest?.abort();
  state.deployment = null;
  byId("deploy").disabled = state.kind === "crease";
  byId("deploy-status").textContent = state.kind === "crease"
    ? "(for tubes, blocks and vaults)" : "";
  byId("deploy-plot").replaceChildren();
  byId("deploy-rows").replaceChildren();
}

/** Show a deployment's answer (`found`: the API's, `{error}` or null) and its rows. */
export function showDeployment(state, found, why) {
  const status = byId("deploy-status"), plot = byId("deploy-plot"), rows = byId("deploy-rows");
  state.deployment = found;
  plot.replaceChildren();
  rows.replaceChildren();
  if (!found || found.error && !found.summary) {
    status.replaceChildren(el("span", { className: "bad" },
      why(state, found, "the deployment could not be computed")));
    return;
  }
  const x = found.angles_deg, q = found.actuation_Nm_per_rad;
  const s = found.summary;
  if (!finite(x, q, found.max_stress_MPa, found.distance_mm)
    || !finite([s.max_stress_MPa, s.max_distance_mm, s.max_distance_span, s.peak_actuation_Nm])) {
    status.replaceChildren(el("span", { className: "bad" }, DAMAGED));
    return;
  }
  const stopped = found.error ? ` Stopped: ${found.error}` : "";
  status.textContent = `${found.material} ${fmt(found.thickness * 1e3)} mm, both feet carried, `
    + `2α = ${fmt(x[0])}° to ${fmt(x.at(-1))}° at ${fmt(found.step)}° steps.${stopped}`;
  plot.append(linePlot({
    id: "actuation-curve",
    title: "Actuation curve of the deployment",
    description: `${x.length} states from ${fmt(x[0])}° to ${fmt(x.at(-1))}°: the moment `
      + `per unit fold rate peaks at ${sig3(s.peak_actuation_Nm)} N·m/rad at `
      + `${fmt(s.peak_actuation_at_deg)}°.`,
    xLabel: "fold angle 2α (°)",
    yLabel: "actuation Q (N·m/rad)",
    series: [{ x, y: q, label: "Q" }],
  }));
  const row = (key, title, words, shown, unit) => el("tr", { dataset: { key }, title },
    el("td", {}, words), el("td", { className: "num" }, shown),
    el("td", { className: "unit" }, unit));
  rows.append(
    row("max_stress", "the largest surface stress (membrane von Mises plus bending) on the way",
      "largest stress", `${sig3(s.max_stress_MPa)} at ${fmt(s.max_stress_at_deg)}°`, "MPa"),
    row("max_distance", "the largest distance of a node from its rigid-folding position at the "
      + "same angle", "off the rigid path", `${sig3(s.max_distance_mm)} (${sig3(
      100 * s.max_distance_span)} % of the span) at ${fmt(s.max_distance_at_deg)}°`, "mm"),
  );
}
