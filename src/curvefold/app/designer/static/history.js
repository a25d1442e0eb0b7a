// The browser's history holds every design: the page's URL is the design (its kind, values
// and the kept design to compare with); Back undoes a change, Forward redoes it.

/** The page's URL for the state's design. */
export function pageURL(state) {
  const q = new URLSearchParams({ kind: state.kind });
  for (const [k, v] of Object.entries(state.values)) if (v !== "") q.append(k, v);
  if (state.kept) q.append("compare", state.kept.address);
  return `?${q}`;
}

/** Read the design of the page's URL into the state; returns the kept design's address, if any. */
export function readURL(state) {
  const params = new URLSearchParams(location.search);
  state.kind = state.schema.kinds[params.get("kind")] ? params.get("kind") : "vault";
  state.values = {};
  for (const [k, v] of params) if (k !== "kind" && k !== "compare") state.values[k] = v;
  const targets = state.schema.targets.some((t) => t.name in state.values);
  state.mode = state.kind === "vault" && targets ? "targets" : "parameters";
  return params.get("compare");
}

/**
 * The steps of the history: `remember` records a change, one step for a whole gesture (a
 * slider dragged, a value typed) until `endGesture`; `push` and `replace` record the state.
 */
export function createHistory(state) {
  let gesture = false;
  return {
    remember() {
      if (gesture) window.history.replaceState(null, "", pageURL(state));
      else {
        window.history.pushState(null, "", pageURL(state));
        gesture = true;
      }
    },
    endGesture() {
      gesture = false;
    },
    push() {
      window.history.pushState(null, "", pageURL(state));
    },
    replace() {
      window.history.replaceState(null, "", pageURL(state));
    },
  };
}
