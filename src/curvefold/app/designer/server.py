"""The designer's web server: the page, its static files and a JSON API on one port.

Routes (all GET; ``KIND`` is ``vault``, ``tube``, ``block`` or ``crease``, and the query
holds design parameters as :mod:`curvefold.app.designer.api` reads them):

================================  ===========================================================
``/``                             the designer page (its design lives in its own URL)
``/static/…``                     its script, style and the bundled three.js
``/api/schema``                   the design schema, the targets and the file formats
``/api/KIND``                     what ``curvefold KIND --json`` prints
``/api/KIND.FORMAT``              a file: a format of the registry, ``zip`` (the whole
                                  output folder) or ``toml`` (the design file)
``/api/KIND/preview``             derived numbers and the folding motion for the 3D view
``/api/vault/contact``            where the fold slider stops: the first contact
``/api/KIND/certificate``         the certificate's checks
``/api/KIND/domain.svg``          the regression domain with the cells
``/api/KIND/pattern``             the crease-pattern pages as they will be cut (SVG)
================================  ===========================================================

A refused request answers 422 with ``{"error": one line, "key": the parameter or null}``;
an unknown path 404. A bug answers 500 with one line asking for a report, never a
traceback. The server keeps no design between requests.
"""

import logging
import socket
import threading
import webbrowser
from collections.abc import Iterator
from contextlib import contextmanager
from importlib.metadata import version
from pathlib import Path
from urllib.parse import urlencode

from ...kernel.errors import CurvefoldError, InputError
from . import api

__all__ = ["STATIC", "VENDOR", "missing_bundle", "create_app", "bind", "serving", "serve"]

#: The page's own files.
STATIC = Path(__file__).with_name("static")
#: The JavaScript libraries copied from npm by ``scripts/build-designer.sh``.
VENDOR = STATIC / "vendor"
#: Files the page imports from :data:`VENDOR`.
VENDOR_FILES = ("three.module.js", "three.core.js", "addons/controls/OrbitControls.js")

log = logging.getLogger("curvefold.designer")


def missing_bundle() -> str | None:
    """None when the page's JavaScript is in place, else one line saying how to build it."""
    missing = [name for name in VENDOR_FILES if not (VENDOR / name).is_file()]
    if not missing:
        return None
    return (f"the designer's JavaScript is not built ({missing[0]} is missing from the package): "
            "run 'bash scripts/build-designer.sh' (it needs npm) in a curvefold checkout")


def create_app():
    """The FastAPI application."""
    from fastapi import FastAPI, Request
    from fastapi.responses import FileResponse, JSONResponse, Response
    from fastapi.staticfiles import StaticFiles

    app = FastAPI(title="curvefold designer", version=version("curvefold"), docs_url=None, redoc_url=None, openapi_url=None)

    @app.middleware("http")
    async def one_line_errors(request: Request, call_next):
        try:
            return await call_next(request)
        except Exception as err:  # a bug: one line, to the client and the terminal
            line = (f"internal error: {type(err).__name__}: {err}. This is a bug in curvefold {version('curvefold')}; "
                    "please report it with the request")
            log.error("%s %s: %s", request.method, request.url.path, " ".join(line.split()))
            return JSONResponse({"error": " ".join(line.split()), "key": None}, status_code=500)

    @app.exception_handler(CurvefoldError)
    async def refused(request: Request, err: CurvefoldError):
        return JSONResponse({"error": " ".join(str(err).split()), "key": err.parameter}, status_code=422)

    def design(kind: str, request: Request):
        return api.request_design(kind, list(request.query_params.multi_items()))

    def json_bytes(content: bytes) -> Response:
        return Response(content, media_type="application/json", headers={"Cache-Control": "no-store"})

    @app.get("/")
    def page():
        return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-store"})

    @app.get("/api/schema")
    def schema():
        return api.schema()

    @app.get("/api/{name}")
    def structure(name: str, request: Request):
        kind, _, what = name.partition(".")
        if not what:
            return json_bytes(api.payload(design(kind, request)))
        filename, media, content = api.download(design(kind, request), what)
        return Response(content, media_type=media, headers={"Content-Disposition": f'attachment; filename="{filename}"'})

    @app.get("/api/{kind}/preview")
    def preview(kind: str, request: Request):
        return json_bytes(api.preview(design(kind, request)))

    @app.get("/api/{kind}/contact")
    def contact(kind: str, request: Request):
        return {"first_contact": api.contact(design(kind, request))}

    @app.get("/api/{kind}/certificate")
    def certificate(kind: str, request: Request):
        return api.certificate(design(kind, request))

    @app.get("/api/{kind}/domain.svg")
    def domain(kind: str, request: Request):
        return Response(api.domain_svg(design(kind, request)), media_type="image/svg+xml")

    @app.get("/api/{kind}/pattern")
    def pattern(kind: str, request: Request):
        return {"pages": api.pattern_pages(design(kind, request))}

    app.mount("/static", StaticFiles(directory=STATIC), name="static")
    return app


def bind(host: str, port: int) -> socket.socket:
    """A listening socket on ``host:port`` (port 0: a free one).

    Raises
    ------
    InputError
        The address cannot be had (in use, not this machine's), in one line.
    """
    if not 0 <= port <= 65535:
        raise InputError(f"--port must be in [0, 65535], got {port}")
    try:
        info = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
        sock = socket.socket(info[0], socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(info[4])
    except OSError as err:
        raise InputError(f"cannot serve on {host}:{port}: {err.strerror or err}; pick another --port or --host") from None
    sock.listen(128)
    return sock


def _server(sock: socket.socket):
    import uvicorn

    config = uvicorn.Config(create_app(), log_level="warning", access_log=False, lifespan="off")
    return uvicorn.Server(config)


def url_of(sock: socket.socket, query: list[tuple[str, str]] = ()) -> str:
    """The page's address on a bound socket, with the design ``query``."""
    host, port = sock.getsockname()[:2]
    shown = f"[{host}]" if ":" in host else host
    return f"http://{shown}:{port}/" + (f"?{urlencode(query)}" if query else "")


@contextmanager
def serving(host: str = "127.0.0.1", port: int = 0) -> Iterator[str]:
    """Serve the designer in a background thread; yields its URL and stops it on exit (tests, benchmarks)."""
    sock = bind(host, port)
    server = _server(sock)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    try:
        while not server.started and thread.is_alive():
            threading.Event().wait(0.01)
        yield url_of(sock)
    finally:
        server.should_exit = True
        thread.join(timeout=10)
        sock.close()


def serve(host: str, port: int, *, query: list[tuple[str, str]] = (), open_browser: bool = True, say=print) -> None:
    """Serve the designer until interrupted; open the page (with the design ``query``) in a browser."""
    sock = bind(host, port)
    url = url_of(sock, query)
    say(f"curvefold designer: {url}  (Ctrl+C to stop)")
    server = _server(sock)
    if open_browser:
        threading.Timer(0.5, webbrowser.open, args=(url,)).start()
    try:
        server.run(sockets=[sock])
    except KeyboardInterrupt:  # Ctrl+C is how a designer session ends
        say("curvefold designer: stopped")
    finally:
        sock.close()
