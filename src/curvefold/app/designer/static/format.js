// How numbers and units are written on the page.

/** A number as the page shows it: integers whole, else six significant digits or exponent form. */
export function fmt(v) {
  if (typeof v !== "number") return String(v);
  if (Number.isInteger(v)) return String(v);
  const a = Math.abs(v);
  return a >= 1e-3 && a < 1e6 ? String(Number(v.toPrecision(6))) : v.toExponential(3);
}

/**
 * A number of the design table: integers whole, else four significant digits (span 2.008 m
 * beside rise 1.353 m), in exponent form below 0.001 or from a million.
 */
export function sig4(v) {
  if (typeof v !== "number") return String(v);
  if (Number.isInteger(v)) return String(v);
  const a = Math.abs(v);
  return a >= 1e-3 && a < 1e6 ? String(Number(v.toPrecision(4))) : v.toExponential(3);
}

/** A unit of the schema as shown beside a value (the schema's words for it, if any). */
export const unitShown = (schema, unit) => schema.units[unit] ?? unit;

/** A number to three significant digits, in plain decimals ("0", "1230", "0.0456"). */
export const sig3 = (v) => (v === 0 ? "0" : String(Number(v.toPrecision(3))));

// the units a figure under load is shown in: [scale, unit] by its SI unit and size
const ARCHITECT = {
  m: () => [1e3, "mm"],
  Pa: (a) => (a >= 1e6 ? [1e-6, "MPa"] : [1e-3, "kPa"]),
  N: (a) => (a >= 1e3 ? [1e-3, "kN"] : [1, "N"]),
};

/**
 * A figure of the design under load as an architect reads it, `[shown, unit]`: lengths in
 * mm, stresses in kPa (MPa from 1 MPa), forces in N (kN from 1 kN), a utilisation in %, each
 * to three significant digits; the numbers of a list in one unit, chosen by the largest.
 */
export function architect(value, unit, { percent = false } = {}) {
  const values = Array.isArray(value) ? value : [value];
  const largest = Math.max(...values.map(Math.abs));
  const [scale, shownUnit] = percent ? [100, "%"] : ARCHITECT[unit]?.(largest) ?? [1, unit];
  return [values.map((v) => sig3(v * scale)).join(", "), shownUnit];
}
