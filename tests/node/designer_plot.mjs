// The designer's plots' arithmetic, checked in Node on the page's own module (plot.js): an
// answer drawn only when every value is a finite number, round ticks. Prints "ok" or throws.
import assert from "node:assert/strict";
import { finite, ticks } from "../../src/curvefold/app/designer/static/plot.js";

// what is drawn: finite numbers, arrays as long, not empty
assert.equal(finite([10, 20, 30], [-1, -2, -3]), true);
for (const damaged of [[-1, null, -3], [-1, NaN, -3], [-1, Infinity, -3], [-1, "2", -3], [-1, -2]]) {
  assert.equal(finite([10, 20, 30], damaged), false, JSON.stringify(damaged));
}
assert.equal(finite([], []), false);
assert.equal(finite([1], undefined), false);

// ticks at 1, 2 or 5 × 10^k inside the range shown: the deployment's 10° to 90°, padded, and
// its actuation; the collapse path's load factor to its linear factor 893
assert.deepEqual(ticks(6.8, 93.2), [20, 40, 60, 80]);
assert.deepEqual(ticks(-157, -17), [-150, -100, -50]);
assert.deepEqual(ticks(-35.7, 929), [0, 200, 400, 600, 800]);
assert.deepEqual(ticks(-0.5, 0.5), [-0.4, -0.2, 0, 0.2, 0.4]);
console.log("ok");
