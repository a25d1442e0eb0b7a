"""The designer as a service one can leave running: every request within the budget and a time
limit, heavy work that never blocks quick work and stops when its client goes away, a clean stop
on SIGTERM, only its own host and pages, one line for every refusal, and bounded memory.

Servers run on 127.0.0.1 (in this process, or as ``curvefold designer`` in a child); every wait is
bounded. The heavy request is a tube of 100,000 rigid panels (about 20 s of work, 0.5 GB measured,
within the budget): long enough that a quick request provably finishes while it runs.
"""

from __future__ import annotations

import io
import json
import os
import re
import signal
import socket
import subprocess
import sys
import time
import urllib.parse
import zipfile

import numpy as np
import psutil
import pytest

from _designer import get, get_json

pytest.importorskip("fastapi")
from curvefold.app.designer import server  # noqa: E402

#: A request that works for about 20 s in a heavy worker.
HEAVY = "api/tube?panels=100000"


@pytest.fixture(scope="module")
def url():
    with server.serving() as base:
        yield base


def status(url) -> dict:
    return get_json(url + "api/status")[1]


def until(condition, what: str, *, tries: int = 1200, pause: float = 0.05):
    """Wait for ``condition()`` to hold (at most tries × pause seconds); returns its value."""
    for _ in range(tries):
        found = condition()
        if found:
            return found
        time.sleep(pause)
    raise AssertionError(f"{what} did not happen within {tries * pause:.0f} s")


def open_request(url: str, path: str, headers: dict | None = None) -> socket.socket:
    """Send a GET and leave the connection open, unread (a client that may go away)."""
    parts = urllib.parse.urlsplit(url)
    sock = socket.create_connection((parts.hostname, parts.port), timeout=30)
    headers = {"Host": parts.netloc} | (headers or {})
    lines = [f"GET /{path} HTTP/1.1", *(f"{k}: {v}" for k, v in headers.items()), "", ""]
    sock.sendall("\r\n".join(lines).encode())
    return sock


def raw_get(url: str, path: str, headers: dict) -> tuple[int, dict]:
    """Status and JSON body of a GET with exactly these headers (Host among them)."""
    sock = open_request(url, path, headers | {"Connection": "close"})
    with sock:
        data = b""
        while chunk := sock.recv(65536):
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    return int(head.split()[1]), (json.loads(body) if body.startswith(b"{") else {})


# -- the budget
# -------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "path, message",
    [
        # accepted before: 20 minutes at up to 1.4 GB; the command line refuses 200,000 samples with
        # SVG
        (
            "api/tube.svg?samples=200000",
            r"this job needs about 2.3 GiB of memory \(200000 samples × "
            r"4 strips\), more than the budget of 2.0 GiB \(CURVEFOLD_MEMORY_BUDGET\); lower "
            r"samples \(at most \d+ fit\), the formats written",
        ),
        (
            "api/vault/preview?panels=100000&tubes=9&samples=201",
            r"\(201 samples \+ 100001 panel " r"vertices × 36 strips\).*lower samples, panels",
        ),
        (
            "api/vault/pattern?samples=100001&tubes=2",
            r"this job needs about [\d.]+ GiB of memory " r"\(100001 samples × 8 strips\)",
        ),
    ],
)
def test_every_request_is_estimated_before_any_work(url, path, message):
    before = status(url)["workers"]
    answer = get_json(url + path)
    assert (
        answer[0] == 422
        and re.search(message, answer[1]["error"])
        and answer[1]["key"] == "samples"
    )
    assert status(url)["workers"] == before  # no worker ran anything


# -- quick work is never blocked; heavy work stops when its client goes away
# ---------------------------------


def test_a_heavy_request_neither_blocks_a_quick_one_nor_outlives_its_client(url):
    heavy = status(url)["workers"]["heavy"]
    client = open_request(url, HEAVY)
    until(lambda: status(url)["workers"]["heavy"]["busy"] == 1, "the heavy job starting")
    # small requests of another design are answered while it runs (the regression domain waited for
    # it before)
    for path in (
        "api/vault/domain.svg?a=0.41",
        "api/vault/preview?a=0.41",
        "api/vault/certificate?a=0.41&coarse=true",
        "api/schema",
    ):
        assert get(url + path)[0] == 200, path
    assert status(url)["workers"]["heavy"]["busy"] == 1  # the heavy job still runs
    client.close()  # the client goes away: its job is killed, its worker replaced
    after = until(
        lambda: (
            (w := status(url)["workers"]["heavy"])["jobs"]["cancelled"] > heavy["jobs"]["cancelled"]
            and w["busy"] == 0
            and w
        ),
        "the heavy job's cancellation",
    )
    killed = set(heavy["pids"]) - set(after["pids"])
    assert len(killed) == 1 and not any(
        psutil.pid_exists(p) and psutil.Process(p).status() != psutil.STATUS_ZOMBIE for p in killed
    )


def test_a_request_past_the_time_limit_is_stopped_and_says_so():
    with server.serving(time_limit=2.0) as url:
        status_, answer = get_json(url + HEAVY)
        # not the user's error: a gateway time-out, with what to lower
        assert status_ == 504 and answer == {
            "error": "This design needs more than the designer's time limit of 2 s: lower "
            "samples or the number of tubes, cells or panels, or start the designer with a "
            "longer --time-limit, or use the command line.",
            "key": "samples",
        }
        assert status(url)["workers"]["heavy"]["jobs"]["time"] == 1
        # a fresh worker took its place
        assert get(url + "api/vault.toml?samples=101&tubes=2")[0] == 200


def test_a_request_kept_waiting_past_the_time_limit_is_told_the_designer_was_busy():
    with server.serving(time_limit=60.0, workers=1) as url:
        # one heavy worker, busy for longer than the next request's limit
        client = open_request(url, HEAVY)
        until(lambda: status(url)["workers"]["heavy"]["busy"] == 1, "the heavy job starting")
        url.designer.time_limit = 2.0
        status_, answer = get_json(url + HEAVY.replace("100000", "99999"))
        client.close()
    assert status_ == 503 and answer == {
        "error": "The designer was busy with other work for its whole time limit of 2 s: try "
        "again in a moment, or lower samples or the number of tubes, cells or panels.",
        "key": "samples",
    }


def test_a_worker_past_its_memory_limit_is_stopped(monkeypatch):
    """No allowance beyond the job's estimate: the worker's own interpreter passes it at once."""
    monkeypatch.setattr(server, "WORKER_ALLOWANCE", -(60 << 20))
    with server.serving() as url:
        status_, answer = get_json(url + "api/tube?samples=101")
        assert status_ == 422 and re.fullmatch(
            r"this request grew past its memory limit of \d+ " r"MiB; lower samples, .*",
            answer["error"],
        )
        assert status(url)["workers"]["heavy"]["jobs"]["memory"] == 1


# -- only its own host and pages
# ----------------------------------------------------------------------------


def test_only_its_own_host_and_pages(url):
    host = urllib.parse.urlsplit(url).netloc
    port = urllib.parse.urlsplit(url).port
    ok = {"Host": host}
    assert raw_get(url, "api/vault/contact?samples=101&tubes=2", ok)[0] == 200
    # DNS rebinding: another name for this address
    for headers in (
        {"Host": f"evil.example:{port}"},
        {"Host": host, "Origin": "http://evil.example"},
        {"Host": host, "Sec-Fetch-Site": "cross-site"},  # an <img src> on another site
        {"Host": host, "Sec-Fetch-Site": "same-site"},  # another port of this machine
        # navigating to the API
        {"Host": host, "Sec-Fetch-Site": "cross-site", "Sec-Fetch-Mode": "navigate"},
    ):
        code, body = raw_get(url, "api/vault.zip?samples=101&tubes=2", headers)
        assert code == 403 and body["error"].startswith(
            ("this designer answers requests for", "the designer answers its own page only")
        ), headers
    for path in ("", "static/designer.js"):
        assert raw_get(url, path, {"Host": f"evil.example:{port}"})[0] == 403
    # a link to the page
    assert (
        raw_get(
            url, "", {"Host": host, "Sec-Fetch-Site": "cross-site", "Sec-Fetch-Mode": "navigate"}
        )[0]
        == 200
    )
    for headers in (
        {"Host": f"localhost:{port}"},
        {"Host": host, "Origin": f"http://{host}", "Sec-Fetch-Site": "same-origin"},
        {"Host": host, "Sec-Fetch-Site": "none"},
    ):
        assert raw_get(url, "api/schema", headers)[0] == 200, headers


# -- one line for what a user typed
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "query",
    [
        "kind=tube&tau=tan(s)",
        "kind=block&tau=tan(s)&samples=101",
        "kind=tube&tau=tan(s)&length=2",
        "kind=tube&width_left=1e-300",
        "kind=block&width_right=1e-300",
        "kind=vault&width=1e-300",
    ],
)
def test_what_a_user_typed_is_never_a_500(url, query):
    """τ = tan s and widths of 1e-300 raised ZeroDivisionError in the certificate (500); every
    route answers 422 with one line."""
    params = dict(urllib.parse.parse_qsl(query))
    kind = params.pop("kind")
    q = urllib.parse.urlencode(params)
    for path in (
        f"api/{kind}?{q}",
        f"api/{kind}/preview?{q}",
        f"api/{kind}/certificate?{q}",
        f"api/{kind}/certificate?{q}&coarse=true",
        f"api/{kind}/pattern?{q}&coarse=true",
        f"api/{kind}/pattern?{q}",
        f"api/{kind}/domain.svg?{q}",
        f"api/{kind}.fold?{q}",
    ):
        code, answer = get_json(url + path)
        assert (
            code == 422
            and "\n" not in answer["error"]
            and answer["error"].startswith(("widths: ", "width_left", "width_right"))
        ), (path, answer)


# -- the downloads
# ----------------------------------------------------------------------------------------------


def test_the_folder_download_holds_the_whole_output_folder(url):
    # answered 500 for every design before
    code, media, body = get(url + "api/vault.zip?samples=101&tubes=2")
    names = zipfile.ZipFile(io.BytesIO(body)).namelist()
    assert code == 200 and media == "application/zip"
    assert {
        "curvefold-vault/report.html",
        "curvefold-vault/report.json",
        "curvefold-vault/vault.fold",
        "curvefold-vault/vault.glb",
    } <= set(names)
    assert not any("/." in name for name in names)  # no temporary or marker files


def test_files_hold_the_state_at_the_fold_angle_asked(url, tmp_path):
    from curvefold.io import read_fold

    # the motion from flat to the state (on to the first contact by default)
    for state, expected in ((None, 90.0), (60, 60.0)):
        code, _, body = get(
            url
            + "api/vault.fold?samples=101&tubes=2"
            + ("" if state is None else f"&state={state}")
        )
        (tmp_path / "v.fold").write_bytes(body)
        angles = read_fold(tmp_path / "v.fold").design["fold_angles"]
        assert code == 200 and angles[:7] == pytest.approx(np.linspace(0.0, expected, 7).tolist())
        assert len(angles) == (7 if state is not None else len(angles)) and max(angles) >= expected
    code, answer = get_json(url + "api/vault.fold?state=180")
    assert code == 422 and answer == {
        "error": "state must be in [0, 180) degrees, got 180.0",
        "key": "state",
    }


# -- stopping
# -------------------------------------------------------------------------------------------------


def test_sigterm_during_heavy_work_stops_everything_at_once(tmp_path):
    """SIGTERM left the server computing for 13 minutes: now every process of the designer is
    gone within 5 s (measured far below: the workers are killed at once) and so are its
    temporary files."""
    env = dict(os.environ, TMPDIR=str(tmp_path))
    proc = subprocess.Popen(
        [sys.executable, "-m", "curvefold", "designer", "--no-browser", "--port", "0"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        url = re.search(r"(http://\S+/)", proc.stdout.readline()).group(1)
        client = open_request(url, HEAVY)
        until(lambda: status(url)["workers"]["heavy"]["busy"] == 1, "the heavy job starting")
        family = psutil.Process(proc.pid).children(recursive=True)
        assert len(family) >= 4  # the fork server and three workers
        started = time.monotonic()
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=5)
        elapsed = time.monotonic() - started
        client.close()
    finally:
        if proc.poll() is None:
            proc.kill()
        out, err = proc.communicate(timeout=30)
    assert proc.returncode == 128 + signal.SIGTERM, err
    assert err == "curvefold: interrupted by SIGTERM\n"
    assert psutil.wait_procs(family, timeout=5)[1] == []
    assert list(tmp_path.iterdir()) == []
    print(f"exited {elapsed:.2f} s after SIGTERM")
