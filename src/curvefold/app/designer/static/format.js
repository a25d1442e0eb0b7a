// How numbers and units are written on the page.

/** A number as the page shows it: integers whole, else six significant digits or exponent form. */
export function fmt(v) {
  if (typeof v !== "number") return String(v);
  if (Number.isInteger(v)) return String(v);
  const a = Math.abs(v);
  return a >= 1e-3 && a < 1e6 ? String(Number(v.toPrecision(6))) : v.toExponential(3);
}

/** A unit of the schema as shown beside a value (the schema's words for it, if any). */
export const unitShown = (schema, unit) => schema.units[unit] ?? unit;
