"""Build a curvefold design through the designer's HTTP API and import its files into Rhino 8.

Start the designer first, in a terminal: ``curvefold designer --no-browser``. Then, in
Rhino 8, open the script editor (command ``ScriptEditor``), open this file as a Python 3
script, set ``KIND``, ``PARAMETERS`` and ``FORMATS`` below, and run it. The design's files
are downloaded into a temporary folder and imported into the open document, on the
layers the 3dm file names.

The HTTP part (:func:`fetch`) uses the standard library only, so it runs anywhere Python
3.9 or newer runs; outside Rhino the script only downloads:

    python curvefold_rhino.py vault a=0.4 tubes=6
"""

import json
import os
import sys
import tempfile
import urllib.error
import urllib.parse
import urllib.request

#: The designer's address (``curvefold designer --port 8765``, the default).
SERVER = "http://127.0.0.1:8765"
#: What to build: "vault", "tube", "block" (or "crease", which has no model files).
KIND = "vault"
#: Any key of a design file (``curvefold vault --help`` lists them, with their ranges).
PARAMETERS = {"a": 0.3, "p_xy": 0.75, "tubes": 6, "fold_angle": 90}
#: Files to import: "3dm" (meshes, NURBS strips and crease curves, in metres), "obj", "stl", ...
FORMATS = ("3dm",)


class DesignError(Exception):
    """The designer refused the design: its one-line message, and the parameter at fault (or
    None)."""

    def __init__(self, message, key=None):
        super().__init__(message)
        self.key = key


def _get(url, timeout):
    try:
        with urllib.request.urlopen(url, timeout=timeout) as answer:
            return answer.read()
    except urllib.error.HTTPError as err:
        body = err.read()
        try:
            refusal = json.loads(body)
        except ValueError:
            raise DesignError(f"HTTP {err.code} from {url}") from None
        raise DesignError(refusal.get("error", f"HTTP {err.code}"), refusal.get("key")) from None


def fetch(kind=KIND, parameters=None, formats=FORMATS, server=SERVER, folder=None, timeout=300):
    """Build a design on the designer and download its files.

    Parameters
    ----------
    kind : str
        "vault", "tube", "block" or "crease".
    parameters : dict, optional
        Design parameters by their design-file key (``{"a": 0.4, "tubes": 6}``).
    formats : sequence of str
        File formats to download, by the names ``--formats`` takes ("3dm", "obj", "fold", ...).
    server : str
        The designer's address.
    folder : str, optional
        Where to write the files; default a new temporary folder.
    timeout : float
        Seconds to wait for each answer.

    Returns
    -------
    summary : dict
        What ``curvefold KIND --json`` prints for the design (derived numbers, certificate).
    paths : list of str
        The downloaded files, one per format.

    Raises
    ------
    DesignError
        The designer refused a parameter (the message says which, its range and the value).
    OSError
        The designer is not running at ``server``.
    """
    query = urllib.parse.urlencode(parameters or {})
    base = f"{server.rstrip('/')}/api/{kind}"
    summary = json.loads(_get(f"{base}?{query}", timeout))
    folder = folder or tempfile.mkdtemp(prefix="curvefold-")
    paths = []
    for name in formats:
        path = os.path.join(folder, f"{kind}.{name}")
        with open(path, "wb") as out:
            out.write(_get(f"{base}.{name}?{query}", timeout))
        paths.append(path)
    return summary, paths


def import_into_rhino(paths):
    """Import files into the active Rhino document (Rhino 8) and redraw."""
    import Rhino  # only inside Rhino

    doc = Rhino.RhinoDoc.ActiveDoc
    for path in paths:
        if not doc.Import(path):
            raise RuntimeError("Rhino could not import " + path)
    doc.Views.Redraw()


def _parse(arguments):
    """``KIND key=value ...`` from a command line."""
    kind = arguments[0] if arguments else KIND
    return kind, dict(item.split("=", 1) for item in arguments[1:])


def main(kind, parameters, inside_rhino):
    """Build, download and (inside Rhino) import; None when done, else the one-line reason why
    not."""
    try:
        summary, paths = fetch(kind, parameters, server=SERVER)
    except DesignError as err:
        return f"curvefold refused the design: {err}"
    except OSError as err:
        return (
            f"no curvefold designer at {SERVER} ({err}): start it with 'curvefold designer "
            "--no-browser'"
        )
    checks = summary.get("certificate", [])
    failed = [c["name"] for c in checks if c.get("passed") is False]
    print(
        f"{kind}: {len(checks)} certificate checks, "
        + ("failed: " + ", ".join(failed) if failed else "all passed")
    )
    if inside_rhino:
        import_into_rhino(paths)
    print("\n".join(paths))
    return None


if __name__ == "__main__":
    try:
        import Rhino  # noqa: F401

        inside_rhino = True
    except ImportError:
        inside_rhino = False
    kind, parameters = (KIND, PARAMETERS) if inside_rhino else _parse(sys.argv[1:])
    problem = main(kind, parameters, inside_rhino)
    if problem and inside_rhino:
        print(problem)  # the script editor shows it; exiting would only add a traceback
    elif problem:
        sys.exit(problem)
