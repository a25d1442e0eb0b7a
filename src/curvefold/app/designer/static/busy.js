// What the server is working on, said in the panel that waits for it: the work's name, an
// indeterminate progress bar and the seconds since it was asked for.
import { el } from "./dom.js";

/**
 * Show `name` as under way in `panel` (a section of the page) until the returned function is
 * called; the seconds count from `started` (performance.now()).
 */
export function busy(panel, name, started = performance.now()) {
  const bar = el("progress");
  bar.setAttribute("aria-label", name);
  const seconds = el("span", { className: "elapsed" });
  const line = el("p", { className: "busy", dataset: { work: name } }, bar,
    el("span", {}, `${name}…`), seconds);
  line.setAttribute("role", "status");
  const tick = () => {
    seconds.textContent = `${Math.floor((performance.now() - started) / 1000)} s`;
  };
  tick();
  const timer = setInterval(tick, 1000);
  panel.querySelector(":scope > h2").after(line);
  return () => {
    clearInterval(timer);
    line.remove();
  };
}
