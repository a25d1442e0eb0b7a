"""The designer's web server: the page, its static files and a JSON API on one port, a service
one can leave running.

Routes (all GET; ``KIND`` is ``vault``, ``tube``, ``block`` or ``crease``, and the query
holds design parameters as :mod:`curvefold.app.designer.api` reads them):

================================  ===========================================================
``/``                             the designer page (its design lives in its own URL)
``/static/…``                     its script, style and the bundled three.js
``/api/schema``                   the design schema, the targets and the file formats
``/api/status``                   the workers, their jobs, the memory held, the limits
``/api/KIND``                     what ``curvefold KIND --json`` prints
``/api/KIND.FORMAT``              a file: a format of the registry, ``zip`` (the whole
                                  output folder) or ``toml`` (the design file); ``state``
                                  sets the fold angle of the state the files hold
``/api/KIND/preview``             derived numbers and the folding motion for the 3D view
``/api/vault/contact``            where the fold slider stops: the first contact
``/api/KIND/certificate``         the certificate's checks (``coarse=true``: at reduced samples)
``/api/KIND/mechanics``           the design under load: what ``curvefold load --json`` prints
``/api/KIND/deploy``              its deployment at 10° steps (:mod:`.curves`): the actuation
                                  curve, the largest stress, the distance from the rigid path
``/api/KIND/domain.svg``          the regression domain with the cells
``/api/KIND/pattern``             the crease-pattern pages as they will be cut (SVG;
                                  ``coarse=true``: a sketch of the sheets)
================================  ===========================================================

What it promises:

- **Every request within the budget.** Each request is estimated as the command line
  estimates a run (:mod:`curvefold.app._budget`) and refused above the budget, with the
  estimate and what to lower; the heavy jobs running at once hold at most the budget
  between them (a job waits for memory another frees; quick jobs are small, at most
  :data:`QUICK_WORKERS` at a time), and a worker that grows past its job's estimate by
  :data:`WORKER_ALLOWANCE` is stopped; one that a job leaves larger than :data:`RECYCLE_ABOVE` is
  replaced.
- **One request never blocks the others.** Everything that builds runs in worker processes
  (:mod:`curvefold.app._workers`): a quick lane answers previews and the first coarse
  answers; a heavy lane, of lower CPU priority, the rest. A job past its time limit, or
  whose client went away (heavy lane), is killed at once.
- **It stops when told.** SIGINT or SIGTERM kills the workers at once, answers what is
  waiting with 503 and ends the server within a second; its temporary files go with it.
- **Only its own pages use it.** A request whose ``Host`` is not the address it serves
  (DNS rebinding) or that another site starts (``Sec-Fetch-Site``, ``Origin``) is refused
  with 403; opening the page itself from a link is allowed.
- **One line, never a traceback.** A refused request answers 422 with
  ``{"error": one line, "key": the parameter or null}``, an unknown path 404, a bug 500
  with one line asking for a report. A time-out is not the design's fault: work past the
  time limit answers 504, a wait that long for a worker or for memory 503, both in the same
  form with a sentence that says what to lower. The server keeps no design between requests.
"""

import asyncio
import ipaddress
import json
import logging
import os
import shutil
import socket
import tempfile
import threading
import webbrowser
from collections import OrderedDict
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from urllib.parse import urlencode, urlsplit

from ...kernel._errors import CurvefoldError
from ...kernel._version import VERSION
from .._budget import memory_budget
from .._workers import JobError, Pool, Reservations, Stopped, resident_bytes
from . import SERVER_SPECS, api, jobs

__all__ = [
    "STATIC",
    "VENDOR",
    "TIME_LIMIT",
    "WORKER_ALLOWANCE",
    "SERVER_SPECS",
    "missing_bundle",
    "Designer",
    "bind",
    "serving",
    "serve",
]

#: The page's own files.
STATIC = Path(__file__).with_name("static")
#: three.js, vendored at the version ``frontend/package-lock.json`` pins
#: (``scripts/build-designer.sh`` refreshes it).
VENDOR = STATIC / "vendor"
#: Files the page imports from :data:`VENDOR`.
VENDOR_FILES = ("three.module.js", "three.core.js", "addons/controls/OrbitControls.js")
#: Seconds a heavy request may take unless ``--time-limit`` says otherwise.
TIME_LIMIT = SERVER_SPECS[1].default
#: Seconds a quick request may take.
QUICK_TIME_LIMIT = 30.0
#: Workers of the quick lane: one per CPU of a laptop, so that several clients' previews run side by
#: side.
QUICK_WORKERS = 2
#: Resident bytes a worker may hold beyond its job's estimate (its own interpreter and caches).
WORKER_ALLOWANCE = 384 << 20
#: A worker holding more than this after a job is replaced by a fresh one (its caches go with it).
RECYCLE_ABOVE = 160 << 20
#: Answers kept by the server (bytes), and the largest one kept.
ANSWER_CACHE, LARGEST_ANSWER = 64 << 20, 8 << 20
#: Modules the workers start with (imported once, in the fork server).
PRELOAD = ("curvefold.app.designer.jobs", "curvefold.app._outputs")

log = logging.getLogger("curvefold.designer")


def missing_bundle() -> str | None:
    """None when the page's JavaScript is in place, else one line saying how to build it."""
    missing = [name for name in VENDOR_FILES if not (VENDOR / name).is_file()]
    if not missing:
        return None
    return (
        f"the designer's JavaScript is not built ({missing[0]} is missing from the package): "
        "run 'bash scripts/build-designer.sh' (it needs npm) in a curvefold checkout"
    )


def _one_line(message: str) -> str:
    return " ".join(str(message).split())


def _timed_out(err: Stopped, limit: float) -> tuple[int, str]:
    """The status and sentence of a request stopped at its time limit of ``limit`` seconds: 504
    when its work ran past the limit, 503 when it waited that long for a worker or for memory.
    Neither is the design's fault: the sentence says what to lower or to do instead."""
    lower = "lower samples or the number of tubes, cells or panels"
    if str(err).startswith("took longer"):
        return 504, (
            f"This design needs more than the designer's time limit of {limit:g} s: {lower}, "
            "or start the designer with a longer --time-limit, or use the command line."
        )
    return 503, (
        f"The designer was busy with other work for its whole time limit of {limit:g} s: "
        f"try again in a moment, or {lower}."
    )


def _bug(message: str) -> str:
    return (
        f"internal error: {_one_line(message)}. This is a bug in curvefold {VERSION}; please "
        "report it with the request"
    )


class _Answers:
    """Finished answers by job, least recently used first out, within :data:`ANSWER_CACHE` bytes."""

    def __init__(self, capacity: int = ANSWER_CACHE, largest: int = LARGEST_ANSWER) -> None:
        self.capacity, self.largest, self.size = capacity, largest, 0
        self._items: OrderedDict[tuple, tuple[bytes, str, str | None]] = OrderedDict()

    def get(self, key: tuple):
        found = self._items.get(key)
        if found is not None:
            self._items.move_to_end(key)
        return found

    def put(self, key: tuple, answer: tuple[bytes, str, str | None]) -> None:
        if len(answer[0]) > self.largest or key in self._items:
            return
        self._items[key] = answer
        self.size += len(answer[0])
        while self.size > self.capacity:
            self.size -= len(self._items.popitem(last=False)[1][0])


def allowed_hosts(host: str, port: int) -> tuple[frozenset[str], bool]:
    """The ``Host`` headers a server bound to ``host:port`` answers, and whether any IP-literal host
    with that port is allowed too (a wildcard address: a name still has to be this machine's)."""
    names = {host, host.strip("[]")}
    try:
        address = ipaddress.ip_address(host.strip("[]"))
    except ValueError:
        address = None
    if host in ("localhost",) or (address is not None and address.is_loopback):
        names |= {"localhost", "127.0.0.1", "::1"}
    wildcard = address is not None and address.is_unspecified
    if wildcard:
        names |= {socket.gethostname(), socket.getfqdn()}
    shown = {f"[{n}]" if ":" in n else n for n in names}
    return frozenset({f"{n}:{port}" for n in shown} | ({*shown} if port == 80 else set())), wildcard


class Guard:
    """ASGI middleware: refuse, with 403, a request for another host or one that another site
    started."""

    def __init__(self, app, hosts: frozenset[str], any_address: bool) -> None:
        self.app, self.hosts, self.any_address = app, hosts, any_address

    def refusal(self, scope) -> str | None:
        headers = {
            k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope.get("headers", [])
        }
        host = headers.get("host", "")
        if host not in self.hosts and not (self.any_address and _ip_host(host)):
            return (
                f"this designer answers requests for {sorted(self.hosts)[0]} only, not for "
                f"host {host!r}"
            )
        site, origin = headers.get("sec-fetch-site"), headers.get("origin")
        navigation = headers.get("sec-fetch-mode") == "navigate" and scope["path"] == "/"
        if site not in (None, "same-origin", "none") and not navigation:
            return (
                "the designer answers its own page only, not a request from another site "
                f"(Sec-Fetch-Site: {site})"
            )
        if origin is not None and urlsplit(origin).netloc != host:
            return f"the designer answers its own page only, not a request from {origin}"
        return None

    async def __call__(self, scope, receive, send) -> None:
        if scope["type"] == "http":
            refused = self.refusal(scope)
            if refused is not None:
                body = json.dumps({"error": refused, "key": None}).encode()
                await send(
                    {
                        "type": "http.response.start",
                        "status": 403,
                        "headers": [
                            (b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode()),
                        ],
                    }
                )
                await send({"type": "http.response.body", "body": body})
                return
        await self.app(scope, receive, send)


def _ip_host(host: str) -> bool:
    """Whether a ``Host`` header names an IP address (``10.0.0.5:8765``, ``[fe80::1]:8765``)."""
    name = host[1 : host.find("]")] if host.startswith("[") else host.rsplit(":", 1)[0]
    try:
        ipaddress.ip_address(name)
    except ValueError:
        return False
    return True


class Designer:
    """The designer's service on a bound socket: its worker pools, limits, answers and web
    application.

    Parameters
    ----------
    sock : socket.socket
        Bound and listening (:func:`bind`).
    host : str
        The address as the user named it (the ``Host`` headers answered follow from it).
    workers : int, keyword-only
        Heavy-lane workers (the quick lane has :data:`QUICK_WORKERS`).
    time_limit : float, keyword-only
        Seconds a heavy request may take.
    """

    def __init__(
        self,
        sock: socket.socket,
        host: str,
        *,
        workers: int = SERVER_SPECS[0].default,
        time_limit: float = TIME_LIMIT,
    ) -> None:
        self.sock, self.time_limit = sock, float(time_limit)
        self.scratch = tempfile.mkdtemp(prefix="curvefold-designer-")
        self.budget = memory_budget()
        self.reservations = Reservations(self.budget)
        self.answers = _Answers()
        self.pools = {
            "quick": Pool(
                QUICK_WORKERS,
                name="quick",
                scratch=self.scratch,
                preload=PRELOAD,
                recycle_above=RECYCLE_ABOVE,
            ),
            "heavy": Pool(
                workers,
                name="heavy",
                scratch=self.scratch,
                preload=PRELOAD,
                niceness=10,
                recycle_above=RECYCLE_ABOVE,
            ),
        }
        self.hosts, self.any_address = allowed_hosts(host, sock.getsockname()[1])
        self.app = Guard(self._fastapi(), self.hosts, self.any_address)

    def close(self) -> None:
        """Kill the workers now (callable from a signal handler)."""
        for pool in self.pools.values():
            pool.close()

    def join(self) -> None:
        """Close, wait for the workers to be gone and remove the temporary files."""
        for pool in self.pools.values():
            pool.join()
        shutil.rmtree(self.scratch, ignore_errors=True)

    # -- answering -----------------------------------------------------------------------------

    async def answer(self, route: str, kind: str, request, what: str | None = None):
        """Plan, run (or find) the job of a request and answer it; every failure as one line."""
        from fastapi.responses import JSONResponse, Response
        from starlette.concurrency import run_in_threadpool

        def refused(message: str, key=None, status: int = 422):
            return JSONResponse(
                {"error": _one_line(message), "key": key},
                status_code=status,
                headers={"Cache-Control": "no-store"},
            )

        started = asyncio.get_running_loop().time()  # the time limit counts every wait
        try:
            plan = await run_in_threadpool(
                jobs.plan, route, kind, list(request.query_params.multi_items()), what=what
            )
        except CurvefoldError as err:
            return refused(str(err).removeprefix(f"{api.SOURCE}: "), err.parameter)
        except Exception as err:  # a bug: one line, to the client and the terminal
            log.error("%s: %s", request.url.path, _bug(f"{type(err).__name__}: {err}"))
            return refused(_bug(f"{type(err).__name__}: {err}"), status=500)
        found = self.answers.get(plan.args)
        if found is None:
            try:
                found = await self._run(plan, request, started)
            except JobError as err:
                if not err.refused:
                    log.error("%s: %s", request.url.path, _bug(str(err)))
                return (
                    refused(str(err).removeprefix(f"{api.SOURCE}: "), err.parameter)
                    if err.refused
                    else refused(_bug(str(err)), status=500)
                )
            except Stopped as err:
                if err.reason == "time":
                    limit = self.time_limit if plan.lane == "heavy" else QUICK_TIME_LIMIT
                    status, message = _timed_out(err, limit)
                    return refused(message, "samples", status=status)
                if err.reason == "memory":
                    lower = (
                        "lower samples, the number of tubes, cells or panels, or use the "
                        "command line"
                    )
                    return refused(f"this request {err}; {lower}", "samples")
                if err.reason == "died":
                    return refused(_bug(str(err)), status=500)
                return refused(str(err), status=503)  # closed, or cancelled (no one reads it)
            self.answers.put(plan.args, found)
        content, media, filename = found
        headers = {"Cache-Control": "no-store"}
        if filename is not None:
            headers["Content-Disposition"] = f'attachment; filename="{filename}"'
        return Response(content, media_type=media, headers=headers)

    async def _run(self, plan: jobs.Plan, request, started: float):
        """The job of ``plan``, within the time limit from ``started`` (the request's arrival):
        waiting for memory and for a worker count towards it."""
        heavy = plan.lane == "heavy"
        loop = asyncio.get_running_loop()
        deadline = started + (self.time_limit if heavy else QUICK_TIME_LIMIT)

        async def gone() -> None:  # returns when the client has closed the connection
            while (await request.receive())["type"] != "http.disconnect":
                pass

        memory = plan.estimate.total

        def run():
            return self.pools[plan.lane].run(
                jobs.run,
                *plan.args,
                timeout=max(0.0, deadline - loop.time()),
                memory_limit=memory + WORKER_ALLOWANCE,
                cancelled=gone if heavy else None,
            )

        # small (at most QUICK_STRIP_SAMPLES), QUICK_WORKERS at a time: never kept waiting for
        # memory
        if not heavy:
            return await run()
        await self.reservations.hold(memory, max(0.0, deadline - loop.time()))
        try:
            return await run()
        finally:
            await self.reservations.release(memory)

    def status(self) -> dict:
        """The workers (process ids, jobs by outcome), the memory held and measured, the limits."""
        server = os.getpid()
        workers = [pid for pool in self.pools.values() for pid in pool.pids()]
        # the workers and their fork server
        processes = sorted({*workers, *(_parent(pid) for pid in workers)} - {server, 0})
        return {
            "version": VERSION,
            "workers": {
                lane: {
                    "size": pool.size,
                    "busy": pool.busy,
                    "pids": pool.pids(),
                    "jobs": dict(pool.counts),
                }
                for lane, pool in self.pools.items()
            },
            "limits": {
                "time_limit": self.time_limit,
                "quick_time_limit": QUICK_TIME_LIMIT,
                "budget": self.budget,
                "worker_allowance": WORKER_ALLOWANCE,
                "recycle_above": RECYCLE_ABOVE,
                "answer_cache": ANSWER_CACHE,
                "hosts": sorted(self.hosts),
            },
            "memory": {
                "reserved": self.reservations.held,
                "answers": self.answers.size,
                "processes": 1 + len(processes),
                "resident": resident_bytes(server) + sum(resident_bytes(p) for p in processes),
                "proportional": _pss(server) + sum(_pss(p) for p in processes),
            },
        }

    # -- the web application ----------------------------------------------------------------------

    def _fastapi(self):
        from fastapi import FastAPI, Request
        from fastapi.responses import FileResponse, JSONResponse
        from fastapi.staticfiles import StaticFiles

        app = FastAPI(
            title="curvefold designer",
            version=VERSION,
            docs_url=None,
            redoc_url=None,
            openapi_url=None,
        )

        @app.get("/")
        def page():
            return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-store"})

        @app.get("/api/schema")
        def schema():
            return api.schema()

        @app.get("/api/status")
        def status():
            return JSONResponse(self.status(), headers={"Cache-Control": "no-store"})

        @app.get("/api/{name}")
        async def structure(name: str, request: Request):
            kind, _, what = name.partition(".")
            return await (
                self.answer("file", kind, request, what)
                if what
                else self.answer("payload", kind, request)
            )

        @app.get("/api/{kind}/{route}")
        async def route(kind: str, route: str, request: Request):
            if route not in jobs.ROUTES or route in ("payload", "file"):
                return JSONResponse({"detail": "Not Found"}, status_code=404)
            return await self.answer(route, kind, request)

        app.mount("/static", StaticFiles(directory=STATIC), name="static")
        return app


def _parent(pid: int) -> int:
    """The parent of a process (Linux ``/proc``; 0 if unknown)."""
    try:
        return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])
    except (OSError, ValueError, IndexError):
        return 0


def _pss(pid: int) -> int:
    """Proportional set size of a process in bytes (shared pages split between their users), 0 if
    unknown."""
    try:
        for line in Path(f"/proc/{pid}/smaps_rollup").read_text().splitlines():
            if line.startswith("Pss:"):
                return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def bind(host: str, port: int) -> socket.socket:
    """A listening socket on ``host:port`` (port 0: a free one).

    Raises
    ------
    InputError
        The address cannot be had (in use, not this machine's), in one line.
    """
    from ...kernel._errors import InputError

    if not 0 <= port <= 65535:
        raise InputError(f"--port must be in [0, 65535], got {port}")
    try:
        info = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
        sock = socket.socket(info[0], socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(info[4])
    except OSError as err:
        raise InputError(
            f"cannot serve on {host}:{port}: {err.strerror or err}; pick another --port or --host"
        ) from None
    sock.listen(128)
    return sock


def _server(designer: Designer):
    import uvicorn

    class Server(uvicorn.Server):
        # a signal: stop the work at once, then the server
        def handle_exit(self, sig, frame) -> None:
            designer.close()
            super().handle_exit(sig, frame)

    config = uvicorn.Config(
        designer.app,
        log_level="warning",
        access_log=False,
        lifespan="off",
        proxy_headers=False,
        timeout_graceful_shutdown=1,
    )
    return Server(config)


def url_of(sock: socket.socket, query: Sequence[tuple[str, str]] = ()) -> str:
    """The page's address on a bound socket, with the design ``query``."""
    host, port = sock.getsockname()[:2]
    shown = f"[{host}]" if ":" in host else host
    return f"http://{shown}:{port}/" + (f"?{urlencode(query)}" if query else "")


@contextmanager
def serving(host: str = "127.0.0.1", port: int = 0, **options) -> Iterator[str]:
    """Serve the designer in a background thread; yields its URL and stops it on exit (tests,
    benchmarks). ``options`` are those of :class:`Designer`; the designer itself is the URL's
    ``designer`` attribute."""
    sock = bind(host, port)
    designer = Designer(sock, host, **options)
    server = _server(designer)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    try:
        while not server.started and thread.is_alive():
            threading.Event().wait(0.01)
        yield _Url(url_of(sock), designer)
    finally:
        designer.close()
        server.should_exit = True
        thread.join(timeout=10)
        sock.close()
        designer.join()


class _Url(str):
    """The URL of a served designer, with the designer it reaches."""

    designer: Designer

    def __new__(cls, url: str, designer: Designer):
        self = super().__new__(cls, url)
        self.designer = designer
        return self


def serve(
    host: str,
    port: int,
    *,
    query: Sequence[tuple[str, str]] = (),
    open_browser: bool = True,
    say=print,
    **options,
) -> None:
    """Serve the designer until interrupted; open the page (with the design ``query``) in a browser.
    ``options`` are those of :class:`Designer`."""
    sock = bind(host, port)
    designer = Designer(sock, host, **options)
    url = url_of(sock, query)
    say(f"curvefold designer: {url}  (Ctrl+C to stop)")
    server = _server(designer)
    if open_browser:
        threading.Timer(0.5, webbrowser.open, args=(url,)).start()
    try:
        server.run(sockets=[sock])
    except KeyboardInterrupt:  # Ctrl+C is how a designer session ends
        say("curvefold designer: stopped")
    finally:
        designer.close()
        sock.close()
        designer.join()
