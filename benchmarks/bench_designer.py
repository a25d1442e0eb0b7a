"""The designer as a service: how fast it answers a design change alone, under load and beside heavy
work, how much memory it holds, how fast it stops, and what the page shows after a change.

1. Server latency. ``curvefold designer --no-browser --port 0`` runs in its own process on
   127.0.0.1. A design change of the paper's vault (801 samples; a and p_xy moved by a
   seeded random step, so every request is a new design and misses the caches) is sent
   as ``GET /api/vault/preview``: by one client after another (one person dragging a
   slider), then by 8 concurrent clients × 200 requests each (capped at 300 s), then by
   one client while a heavy request runs (a tube of 100,000 rigid panels, about 20 s of
   work in a heavy worker). Reported: the 50th and 95th percentiles and the largest
   latency, the errors, and the memory of every process of the designer (``/api/status``:
   resident and proportional set sizes, the server, its fork server and its workers)
   after each quarter of the load.
2. Stopping. SIGTERM while the heavy request runs: the seconds until the server has exited,
   and whether any of its processes or temporary files is left.
3. The page, in a real headless browser (Debian's chromium driven by Playwright, WebGL by
   SwiftShader: no GPU) on a designer of its own: over 30 changes of the paper's vault (a
   new p_xy each), the time from the input to the 3D view, to the coarse certificate and
   pattern, and to the full ones; the folder downloaded; the memory of the designer's
   processes then; and the fold slider at two window sizes: the page's own work per frame
   and the frames per second while it plays.

What a user would otherwise do is run ``curvefold vault`` and open the folder: all files of the
paper's vault, timed once here before the designer starts; the ratios below are against that.
Targets: p95 ≤ 100 ms for one client and for 8 concurrent clients; quick requests beside heavy work
p95 ≤ 1 s; exit within 5 s of SIGTERM leaving nothing; coarse certificate and pattern p95 ≤ 1 s; a
frame's work within one 60 Hz frame.
"""

from __future__ import annotations

import json
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
from pathlib import Path
from urllib.parse import urlsplit

import numpy as np
from _bench import SummaryRow, machine_speed, markdown_table, summary_table, verdict

ROOT = Path(__file__).resolve().parents[1]
CURVEFOLD = ROOT / ".venv" / "bin" / "curvefold"
TARGET_P95, QUICK_P95 = 0.100, 1.0  # seconds
CLIENTS, REQUESTS, CAP, CHANGES = 8, 200, 300.0, 30
HEAVY = "api/tube?panels=100000"


def _designs(rng: np.random.Generator, n: int) -> list[str]:
    a = 0.3 + rng.uniform(-0.05, 0.05, n)
    p_xy = 0.75 + rng.uniform(-0.05, 0.05, n)
    return [f"api/vault/preview?a={x:.9f}&p_xy={y:.9f}" for x, y in zip(a, p_xy)]


def _get(url: str) -> tuple[float, int]:
    t0 = time.perf_counter()
    try:
        with urllib.request.urlopen(url, timeout=60) as r:
            r.read()
            status = r.status
    except Exception:  # noqa: BLE001 - an error is counted, whatever it is
        status = -1
    return time.perf_counter() - t0, status


def _status(url: str) -> dict:
    with urllib.request.urlopen(url + "api/status", timeout=30) as r:
        return json.loads(r.read())


def _memory(url: str) -> tuple[float, float]:
    """(resident, proportional) MB of every process of the designer."""
    m = _status(url)["memory"]
    return m["resident"] / 2**20, m["proportional"] / 2**20


def _start(env: dict | None = None) -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen(
        [str(CURVEFOLD), "designer", "--no-browser", "--port", "0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    return proc, re.search(r"(http://\S+/)", proc.stdout.readline()).group(1)


def _heavy(url: str) -> socket.socket:
    """Send the heavy request and wait until a heavy worker runs it; closing the socket cancels
    it."""
    parts = urlsplit(url)
    sock = socket.create_connection((parts.hostname, parts.port))
    sock.sendall(f"GET /{HEAVY} HTTP/1.1\r\nHost: {parts.netloc}\r\n\r\n".encode())
    for _ in range(600):
        if _status(url)["workers"]["heavy"]["busy"]:
            break
        time.sleep(0.05)
    return sock


def _row(label: str, times: np.ndarray, errors: int, memory: str = "—") -> list[str]:
    p50, p95 = np.percentile(times, [50, 95])
    return [
        label,
        f"{1e3 * p50:.0f} ms",
        f"{1e3 * p95:.0f} ms",
        f"{1e3 * times.max():.0f} ms",
        str(errors),
        memory,
    ]


def _batch_seconds() -> float:
    """Wall seconds of one ``curvefold vault`` writing every file of the paper's vault (what a
    user would otherwise run)."""
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        subprocess.run(
            [str(CURVEFOLD), "vault", "--out", str(Path(tmp) / "vault")],
            check=True,
            capture_output=True,
        )
        return time.perf_counter() - t0


def server_latency() -> tuple[list[SummaryRow], list[list[str]], dict]:
    batch, speed = _batch_seconds(), machine_speed()
    proc, url = _start()
    try:
        rng = np.random.default_rng(2024)
        for path in _designs(rng, 10):  # warm up: the workers' first builds
            _get(url + path)
        idle = _memory(url)
        single = [_get(url + path) for path in _designs(rng, 200)]
        times = np.array([t for t, s in single])
        errors_single = sum(s != 200 for _, s in single)
        results: list[tuple[float, int]] = []
        memory = [_memory(url)]
        lock = threading.Lock()
        deadline = time.perf_counter() + CAP
        paths = [_designs(np.random.default_rng(c), REQUESTS) for c in range(CLIENTS)]

        def client(c: int) -> None:
            for k, path in enumerate(paths[c]):
                if time.perf_counter() > deadline:
                    return
                answer = _get(url + path)
                with lock:
                    results.append(answer)
                    if c == 0 and (k + 1) % (REQUESTS // 4) == 0:
                        memory.append(_memory(url))

        t0 = time.perf_counter()
        threads = [threading.Thread(target=client, args=(c,)) for c in range(CLIENTS)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        wall = time.perf_counter() - t0
        load = np.array([t for t, s in results])
        errors_load = sum(s != 200 for _, s in results)
        heavy = _heavy(url)
        beside = [_get(url + path) for path in _designs(rng, 50)]
        still = _status(url)["workers"]["heavy"]["busy"]
        heavy.close()
        quick = np.array([t for t, s in beside])
        errors_quick = sum(s != 200 for _, s in beside)
        peak = _memory(url)
    finally:
        proc.terminate()
        proc.communicate(timeout=10)
    shown = " → ".join(f"{r:.0f}/{p:.0f}" for r, p in memory)
    table = [
        _row("1 client, 200 changes", times, errors_single, f"{idle[0]:.0f}/{idle[1]:.0f} idle"),
        _row(
            f"{CLIENTS} clients × {REQUESTS} ({len(results)} in {wall:.0f} s)",
            load,
            errors_load,
            shown,
        ),
        _row(
            f"1 client, 50 changes beside a heavy request{'' if still else ' (it ended first)'}",
            quick,
            errors_quick,
            f"{peak[0]:.0f}/{peak[1]:.0f}",
        ),
    ]
    p95, q95 = np.percentile(times, 95), np.percentile(quick, 95)
    rows = [
        SummaryRow(
            "designer",
            "paper's vault changed, 1 client: p95 server answer (preview)",
            f"{1e3 * p95:.0f} ms ({batch / p95:.0f}× faster than a batch run, {batch:.1f} s)",
            f"≤ {1e3 * TARGET_P95:.0f} ms",
            verdict(p95 <= TARGET_P95 and errors_single == 0),
        ),
        SummaryRow(
            "designer",
            f"{CLIENTS} concurrent clients × {REQUESTS}: p95, errors, memory "
            "of every process (resident/proportional MB)",
            f"{1e3 * np.percentile(load, 95):.0f} ms, {len(results) / wall:.0f} "
            f"requests/s, {errors_load} errors, {shown} (load "
            f"{os.getloadavg()[0]:.1f}; `import numpy` {speed:.2f} CPU s)",
            f"p95 ≤ {1e3 * TARGET_P95:.0f} ms, no errors, flat memory",
            verdict(
                np.percentile(load, 95) <= TARGET_P95
                and errors_load == 0
                and memory[-1][1] <= 1.1 * memory[1][1]
            ),
        ),
        SummaryRow(
            "designer",
            "a change beside a heavy request (100,000 panels): p95",
            f"{1e3 * q95:.0f} ms",
            f"≤ {1e3 * QUICK_P95:.0f} ms",
            verdict(q95 <= QUICK_P95 and errors_quick == 0 and still),
        ),
    ]
    return rows, table, {"idle": idle, "load": memory, "beside_heavy": peak}


def stopping() -> tuple[list[SummaryRow], list[list[str]]]:
    with tempfile.TemporaryDirectory() as tmp:
        proc, url = _start(dict(os.environ, TMPDIR=tmp))
        heavy = _heavy(url)
        pids = [p for pool in _status(url)["workers"].values() for p in pool["pids"]]
        t0 = time.perf_counter()
        proc.send_signal(signal.SIGTERM)
        proc.communicate(timeout=60)
        seconds = time.perf_counter() - t0
        heavy.close()
        time.sleep(0.5)
        left = [p for p in pids if Path(f"/proc/{p}").exists()] + [
            str(p) for p in Path(tmp).iterdir()
        ]
    table = [
        [
            "SIGTERM during a heavy request: exit",
            f"{seconds:.2f} s",
            f"status {proc.returncode}",
            f"{len(left)} processes or files left",
        ]
    ]
    rows = [
        SummaryRow(
            "designer",
            "SIGTERM during heavy work: seconds to exit, what is left",
            f"{seconds:.2f} s, {len(left)} left",
            "≤ 5 s, nothing",
            verdict(seconds <= 5 and not left),
        )
    ]
    return rows, table


def page() -> tuple[list[SummaryRow], list[list[str]]]:
    from playwright.sync_api import sync_playwright

    sys.path.insert(0, str(ROOT / "tests"))
    from _designer import CHROMIUM, CHROMIUM_ARGS

    table, frame_ms, fps_at = [], 0.0, {}
    proc, url = _start()
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        tab = browser.new_page(viewport={"width": 1280, "height": 800})
        tab.goto(url + "?kind=vault")
        settled = "(t => t && t.settled !== undefined)(window.curvefold.timings.at(-1))"
        tab.wait_for_function(settled, timeout=120_000)
        slider = tab.locator('.field[data-key="p_xy"] input[type=range]')
        for k in range(CHANGES):
            slider.focus()
            tab.keyboard.press("ArrowRight")
            tab.wait_for_function(
                f"window.curvefold.timings.length === {k + 2} && {settled}", timeout=120_000
            )
        timings = tab.evaluate("window.curvefold.timings.slice(1)")
        with tab.expect_download(timeout=300_000):  # the whole folder, as a user would take it home
            tab.click("#downloads a:text-is('folder (zip)')")
        session = _memory(url)
        tab.close()
        after = {
            key: np.percentile([t[key] for t in timings], [50, 95])
            for key in ("view", "certificate", "pattern", "full_certificate", "full_pattern")
        }
        for key, (p50, p95) in after.items():
            table.append(
                [
                    f"input → {key.replace('_', ' ')} ({CHANGES} changes)",
                    f"{p50:.0f} ms",
                    f"{p95:.0f} ms",
                ]
            )
        for width, height in ((1280, 800), (960, 600)):
            tab = browser.new_page(viewport={"width": width, "height": height})
            tab.goto(url)
            tab.wait_for_function(settled, timeout=120_000)
            vertices = tab.evaluate("window.curvefold.preview.motion.vertices")
            # one frame of the slider: morph every vertex, render, and wait for WebGL to finish
            ms = tab.evaluate("""() => {
                const view = window.curvefold.view, gl = view.renderer.getContext();
                const t0 = performance.now();
                for (let k = 0; k < 100; k++) { view.setAngle(k % 120); gl.finish(); }
                return (performance.now() - t0) / 100;
            }""")
            tab.click("#play")
            start = tab.evaluate("window.curvefold.frames")
            tab.wait_for_timeout(5000)
            fps_at[width, height] = (tab.evaluate("window.curvefold.frames") - start) / 5.0
            tab.close()
            frame_ms = max(frame_ms, ms)
            table += [
                [
                    f"{width} × {height}: one frame (morph {vertices} vertices, render, finish)",
                    f"{ms:.2f} ms",
                    "",
                ],
                [f"{width} × {height}: frames/s while playing", f"{fps_at[width, height]:.0f}", ""],
            ]
        browser.close()
    peak = _memory(url)
    proc.terminate()
    proc.communicate(timeout=10)
    table.append(
        [
            f"memory of every process after the {CHANGES} changes and the folder, and "
            "after the slider (resident/proportional MB)",
            f"{session[0]:.0f}/{session[1]:.0f}",
            f"{peak[0]:.0f}/{peak[1]:.0f}",
        ]
    )
    coarse = max(after["certificate"][1], after["pattern"][1])
    rows = [
        SummaryRow(
            "designer",
            "input → 3D view, → coarse certificate and pattern, → full "
            "ones (p95, headless chromium)",
            f"{after['view'][1]:.0f} ms, {after['certificate'][1]:.0f} and "
            f"{after['pattern'][1]:.0f} ms, "
            f"{after['full_certificate'][1] / 1e3:.1f} and "
            f"{after['full_pattern'][1] / 1e3:.1f} s",
            "coarse ≤ 1 s",
            verdict(coarse <= 1e3 * QUICK_P95),
        ),
        SummaryRow(
            "designer",
            "fold slider in headless chromium (SwiftShader): the page's "
            "work per frame; frames/s at 1280 × 800, 960 × 600",
            f"{frame_ms:.1f} ms; {fps_at[1280, 800]:.0f} and {fps_at[960, 600]:.0f} frames/s",
            "≤ 16.7 ms (60 Hz)",
            verdict(frame_ms <= 1000 / 60),
        ),
    ]
    return rows, table


def run() -> list[SummaryRow]:
    rows, table, _ = server_latency()
    print(
        markdown_table(
            [
                "load",
                "p50",
                "p95",
                "max",
                "errors",
                "memory, every process (resident/proportional MB)",
            ],
            table,
        )
    )
    stop_rows, stop_table = stopping()
    print()
    print(markdown_table(["stopping", "time", "status", "left"], stop_table))
    page_rows, page_table = page()
    print()
    print(markdown_table(["the page", "p50", "p95"], page_table))
    return rows + stop_rows + page_rows


def main() -> None:
    rows = run()
    print()
    print(summary_table(rows))
    print(
        json.dumps(
            {"python": sys.version.split()[0], "cpus": os.cpu_count(), "load": os.getloadavg()}
        )
    )


if __name__ == "__main__":
    main()
