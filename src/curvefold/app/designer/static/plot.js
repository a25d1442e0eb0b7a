// Small line plots drawn by the page as inline SVG from the numbers the server sends: labelled
// axes with their units, round ticks, a dashed line for a reference, a name and a description
// for those who do not see it.

const NS = "http://www.w3.org/2000/svg";

function svg(tag, attrs = {}, text = null) {
  const node = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  if (text !== null) node.textContent = text;
  return node;
}

/** Whether every value of every array is a finite number and the arrays are as long, not empty. */
export function finite(...arrays) {
  const n = arrays[0]?.length;
  return n > 0 && arrays.every((a) => Array.isArray(a) && a.length === n
    && a.every((v) => typeof v === "number" && Number.isFinite(v)));
}

/** Round ticks covering [lo, hi]: about `n` of them, at 1, 2 or 5 × 10^k. */
export function ticks(lo, hi, n = 5) {
  const raw = (hi - lo) / n;
  const power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw);
  const out = [];
  for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) {
    out.push(Math.abs(v) < 1e-12 * step ? 0 : v);
  }
  return out;
}

const label = (v) => String(Number(v.toPrecision(4)));

/** The range shown for values `vs`: padded a little, never empty. */
function range(vs) {
  let lo = Math.min(...vs), hi = Math.max(...vs);
  if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) {
    lo -= 0.5 * Math.max(1, Math.abs(lo));
    hi += 0.5 * Math.max(1, Math.abs(hi));
  }
  const pad = 0.04 * (hi - lo);
  return [lo - pad, hi + pad];
}

/**
 * A line plot as an SVG element: `series` is a list of `{x, y, label, dashed, marker}` (finite
 * numbers, checked by the caller; a marker series is drawn as dots), the axes named `xLabel`
 * and `yLabel` (their units in brackets), the plot named `title` and described by
 * `description` (its numbers in words).
 */
export function linePlot({ id, title, description, xLabel, yLabel, series }) {
  const W = 320, H = 200, left = 52, right = 10, top = 22, bottom = 34;
  const [x0, x1] = range(series.flatMap((s) => s.x));
  const [y0, y1] = range(series.flatMap((s) => s.y));
  const px = (x) => left + ((x - x0) / (x1 - x0)) * (W - left - right);
  const py = (y) => H - bottom - ((y - y0) / (y1 - y0)) * (H - top - bottom);
  const root = svg("svg", {
    viewBox: `0 0 ${W} ${H}`, role: "img", class: "plot", id,
    "aria-labelledby": `${id}-title`, "aria-describedby": `${id}-desc`,
  });
  root.append(svg("title", { id: `${id}-title` }, title),
    svg("desc", { id: `${id}-desc` }, description));
  const frame = svg("g", { class: "axes" });
  frame.append(svg("rect", { x: left, y: top, width: W - left - right, height: H - top - bottom }));
  for (const t of ticks(x0, x1)) {
    frame.append(svg("line", { x1: px(t), x2: px(t), y1: H - bottom, y2: H - bottom + 4 }));
    frame.append(svg("text", { x: px(t), y: H - bottom + 14, "text-anchor": "middle" }, label(t)));
  }
  for (const t of ticks(y0, y1)) {
    frame.append(svg("line", { x1: left - 4, x2: left, y1: py(t), y2: py(t) }));
    frame.append(svg("text", { x: left - 6, y: py(t) + 3, "text-anchor": "end" }, label(t)));
  }
  if (y0 < 0 && y1 > 0) {
    frame.append(svg("line", { class: "zero", x1: left, x2: W - right, y1: py(0), y2: py(0) }));
  }
  frame.append(svg("text", { x: (left + W - right) / 2, y: H - 4, "text-anchor": "middle" },
    xLabel));
  frame.append(svg("text", { x: 4, y: 12 }, yLabel));
  root.append(frame);
  const kind = (s) => (s.marker ? "marker" : s.dashed ? "line dashed" : "line");
  for (const s of series) { // in order: the last on top
    if (s.marker) {
      s.x.forEach((x, i) => root.append(svg("circle", { class: kind(s), cx: px(x),
        cy: py(s.y[i]), r: 3.5 })));
    } else {
      const points = s.x.map((x, i) => `${px(x).toFixed(1)},${py(s.y[i]).toFixed(1)}`).join(" ");
      root.append(svg("polyline", { class: kind(s), points }));
    }
  }
  let lx = W - right; // the legend, right-aligned in the top margin
  for (const s of [...series].reverse()) {
    root.append(s.marker ? svg("circle", { class: kind(s), cx: lx - 7, cy: 9, r: 3 })
      : svg("line", { class: kind(s), x1: lx - 14, x2: lx, y1: 9, y2: 9 }));
    root.append(svg("text", { x: lx - 17, y: 12, "text-anchor": "end" }, s.label));
    lx -= 24 + 5.2 * s.label.length;
  }
  return root;
}
