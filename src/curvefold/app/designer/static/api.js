// The designer's JSON API as the page uses it (routes: curvefold.app.designer.server).

const NO_SERVER = (err) => `the designer's server did not answer (${err.message}); `
  + "is 'curvefold designer' still running?";

/** The design schema: every parameter's range, default, unit and help, the targets, the formats. */
export async function schema() {
  return (await fetch("/api/schema")).json();
}

/** The sentence of a refusal or time-out: the server's `detail` as it is, else its `error`. */
const sentence = (body) => String(body.detail ?? body.error);

/** Whether a status is a time-out: the server's time limit, not the design (503, 504). */
const timedOut = (status) => status === 503 || status === 504;

/**
 * The preview of a design (its numbers and folding motion): `{ok, body}`, where a refused
 * design's body is `{error, key}` (the parameter at fault, or null), and one that met the
 * server's time limit `{error, key, stopped: true}`.
 */
export async function preview(kind, query) {
  try {
    const response = await fetch(`/api/${kind}/preview?${query}`);
    const body = await response.json();
    if (response.ok) return { ok: true, body };
    const stopped = timedOut(response.status);
    return { ok: false, body: { error: sentence(body), key: body.key ?? null, stopped } };
  } catch (err) {
    return { ok: false, body: { error: NO_SERVER(err), key: null } };
  }
}

/**
 * What follows a preview (`path`: certificate, pattern, contact, mechanics, domain.svg, with
 * its own query if any): the answer (JSON, or text when `json` is false), `{error}` when the
 * design is refused, `{error, stopped: true}` when its work met the server's time limit (503,
 * 504), null when there is no answer (aborted, failed).
 */
export async function detail(kind, path, query, { signal, json = true } = {}) {
  try {
    const joined = `${path}${path.includes("?") ? "&" : "?"}${query}`;
    const r = await fetch(`/api/${kind}/${joined}`, { signal });
    if (r.status === 422) return { error: sentence(await r.json()) };
    if (timedOut(r.status)) return { error: sentence(await r.json()), stopped: true };
    if (!r.ok) return null;
    return json ? await r.json() : await r.text();
  } catch {
    return null;
  }
}

/** The address of a file of the design (a format's name, `zip` or `toml`). */
export const fileURL = (kind, format, query) => `/api/${kind}.${format}?${query}`;
