// The designer's numbers as its page writes them, checked in Node on the page's own modules
// (format.js, controls.js): the figures in an architect's units, the design table's four
// digits, the sliders' ranges and steps from the schema. Prints "ok" or throws.
import assert from "node:assert/strict";
import { architect, sig4 } from "../../src/curvefold/app/designer/static/format.js";
import { sliderRange } from "../../src/curvefold/app/designer/static/controls.js";

// "Under load" showed 9.876e-5 m, 77278.7 Pa and 0.00249286
assert.deepEqual(architect(9.876e-5, "m"), ["0.0988", "mm"]);
assert.deepEqual(architect(77278.7, "Pa"), ["77.3", "kPa"]);
assert.deepEqual(architect(2.5e8, "Pa"), ["250", "MPa"]);
assert.deepEqual(architect(0.00249286, "", { percent: true }), ["0.249", "%"]);
assert.deepEqual(architect([0, 0, 1234.5], "N"), ["0, 0, 1.23", "kN"]); // one unit for a list

// the design table: span 2.00812 m beside rise 1.3532 m, both to four digits
assert.deepEqual([2.00812, 1.3532].map(sig4), ["2.008", "1.353"]);
assert.deepEqual([9, 0.08, 3.16571746805, 1e-4, 2500000.5].map(sig4),
  ["9", "0.08", "3.166", "1.000e-4", "2.500e+6"]);

// the sliders: one range and step with the field; a round value on the grid, 0 inside
const onGrid = (r, v) => Math.abs((v - r.lo) / r.step - Math.round((v - r.lo) / r.step)) < 1e-9;
const a = sliderRange({ kind: "real", default: 0.3, typical: { lo: 0, hi: 1.2 },
  range: { lo: 0, hi: 1.27 } });
assert.deepEqual(a, { lo: 0, hi: 1.2, step: 0.001 });
assert.ok(onGrid(a, 0.5) && onGrid(a, 0.501));
assert.ok(!onGrid({ lo: 0, hi: 1.2, step: 0.0016 }, 0.501)); // the check can fail
for (const spec of [
  { kind: "real", default: 0, range: { lo: 0, hi: 1000 } }, // snow
  { kind: "real", default: 0, range: { lo: 0, hi: 1e9 } }, // point load
  { kind: "real", default: null, range: { lo: 0, hi: null } }, // scale
  { kind: "real", default: null, range: { lo: 0, hi: 100 } }, // perforation
]) {
  const r = sliderRange(spec);
  assert.equal(r.lo, 0, JSON.stringify(spec));
  assert.ok(r.hi > 0 && onGrid(r, 0) && onGrid(r, r.hi), JSON.stringify(r));
}
assert.deepEqual(sliderRange({ kind: "integer", default: 801, range: { lo: 9, hi: 200000 } }),
  { lo: 161, hi: 4005, step: 1 });
console.log("ok");
