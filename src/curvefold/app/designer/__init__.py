"""The designer: a local web page to design a vault (or a tube, block or crease) live.

``curvefold designer`` serves it (:mod:`.server`, FastAPI on uvicorn); :mod:`.api` reads
its requests and answers them without the web framework, :mod:`.preview` gives the page's
first view of a design, :mod:`.curves` its collapse path and deployment, :mod:`.jobs` runs
that work in worker processes; ``static/`` holds the page and its ES modules, with three.js
vendored in ``static/vendor/`` at the version ``frontend/package-lock.json`` pins. Needs the
``designer`` extra:
``pip install 'curvefold[designer]'``.
"""

from ...kernel._validate import Spec

__all__ = ["SERVER_SPECS"]

#: The options of ``curvefold designer`` that shape the service (``--workers``, ``--time-limit``).
SERVER_SPECS = (
    Spec(
        "workers",
        "integer",
        2,
        "[1, 16]",
        help="worker processes for heavy requests (files, "
        "full certificates and patterns); one more answers the quick ones",
        label="heavy workers",
    ),
    Spec(
        "time_limit",
        "real",
        120.0,
        "(0, 3600]",
        "seconds",
        help="time a heavy request may take before it is stopped",
        label="time limit",
    ),
)
