// The page's state: one object, made by createState and passed explicitly to the modules that
// read or change it (scripts and tests see it as window.curvefold). The design itself lives in
// the page's URL (history.js); this is what the page holds while showing it.

/** A fresh state, before the schema has come. */
export function createState() {
  return {
    schema: null, // the design schema: GET /api/schema
    kind: "vault", // the kind of design shown
    values: {}, // the design's parameters as typed (strings); defaults are left out
    mode: "parameters", // "parameters", or "targets" (a vault from its span and rise)
    input: undefined, // when the latest change was made (performance.now())
    preview: null, // the preview shown
    contact: undefined, // fold angle of the first contact: undefined until known, null if none
    kept: null, // the design kept to compare with: {address, preview, contact}
    compareMode: "side", // the kept design "side" by side or "overlay"
    certificate: null, // the certificate shown (coarse, then full)
    pattern: null, // the crease pattern shown
    mechanics: null, // the design under load, when a material is chosen
    deployment: null, // the design's deployment, when asked for (the deploy button)
    deployRequest: null, // its request under way (an AbortController)
    stopped: false, // whether a time-out's sentence is shown for the design shown
    timings: [], // per change shown: milliseconds from the input to each answer
    frames: 0, // frames drawn by the fold slider's play
    view: null, // the 3D view (view.js)
  };
}

/** The specs of a kind's controls, in order: the common ones, the kind's sections, the output. */
export function specsOf(state, kind = state.kind) {
  const s = state.schema;
  return ["", ...s.kinds[kind], "output"].flatMap((section) => s.sections[section]);
}

/** The design's query string: its values, those left empty omitted. */
export function designQuery(values) {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(values)) if (v !== "") q.append(k, v);
  return q.toString();
}

/** The names of the kind's parameters of what it is made of and what loads it. */
export function loadKeys(state) {
  const sections = state.schema.optional[state.kind] ?? [];
  return new Set(sections.flatMap((s) => state.schema.sections[s].map((spec) => spec.name)));
}

/**
 * Whether the design says what it is made of or what loads it (then it is shown under load):
 * a value of these typed, even its default (a thickness of 1 mm typed asks for the analysis).
 */
export function underLoad(state) {
  const keys = loadKeys(state);
  return Object.keys(state.values).some((k) => keys.has(k) && state.values[k] !== "");
}
