"""Benchmark: the playground in a real browser (issue 17): how long Python and plclab take to
load in the page, and how many scans of the tank program per second the page runs, beside the
same Session in CPython; and, with the program in a Web Worker (issue 39), how long the page's
own thread is ever blocked while a 200,000-iteration loop runs (the longest gap of a 10 ms
timer in the page) and how long Stop takes to answer (the goals: 100 ms and 200 ms).

Run ``python benchmarks/site_bench.py [--site DIR] [--repeat N] [--seconds S] [--edition ru]``.
Without ``--site`` the site is built first (into a temporary folder) and the build's time is
printed; ``--build-only`` stops there (the build time of both editions, ADR 0071), and
``--edition ru`` measures the Russian edition's playground (the same Python, its own texts). Each load is a fresh browser
context (an empty cache: what a first visit costs); the table prints the median and the range.
Needs Debian's Chromium at /usr/bin/chromium and Playwright.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from plclab.site import playground_api as api  # noqa: E402
from plclab.site.build import build  # noqa: E402
from plclab.site.serve import serve_in_thread  # noqa: E402

GAPS: list[float] = []
STOPS: list[float] = []


def cpython_scans_per_second(seconds: float) -> float:
    s = api.Session(api.TANK_EXAMPLE, "st", "tank")
    t = time.perf_counter()
    s.advance(seconds, every=0.1)
    return s.scans / (time.perf_counter() - t)


LONG_LOOP = ("PROGRAM Busy\nVAR i : DINT; x : DINT; END_VAR\n"
             "FOR i := 1 TO 200000 DO x := x + 1; END_FOR;\nEND_PROGRAM\n")


def responsiveness(page) -> tuple[float, float]:
    """Run LONG_LOOP for 60 s of virtual time, watch the page's thread for 2 s, press Stop:
    (the longest gap between ticks of a 10 ms timer, the time Stop took), in ms."""
    page.fill("#pg-code", LONG_LOOP)
    page.evaluate("""() => { window.__gap = 0; let last = performance.now();
        setInterval(() => { const n = performance.now();
            window.__gap = Math.max(window.__gap, n - last); last = n; }, 10); }""")
    page.click("#pg-run60")
    page.wait_for_function("window.plclabPlayground.state.scans > 2", timeout=120000)
    page.evaluate("window.__gap = 0")  # from here on: the run is under way
    page.wait_for_timeout(2000)
    stop_ms = page.evaluate("""async () => { const t = performance.now();
        await window.plclabPlayground.stop(); return performance.now() - t; }""")
    return page.evaluate("window.__gap"), stop_ms


def browser_numbers(base: str, repeat: int, seconds: float,
                    edition: str = "") -> tuple[list[float], list[float]]:
    from playwright.sync_api import sync_playwright

    loads, rates = [], []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        for _ in range(repeat):
            ctx = browser.new_context()
            page = ctx.new_page()
            t0 = time.perf_counter()
            page.goto(base + edition + "playground/")
            page.wait_for_function("document.getElementById('pg-status').dataset.state=='ready'",
                                   timeout=180000)
            loads.append(time.perf_counter() - t0)
            r = page.evaluate(f"window.plclabPlayground.run({seconds})")
            rates.append(r["scansPerSecond"])
            gap, stop = responsiveness(page)
            GAPS.append(gap)
            STOPS.append(stop)
            ctx.close()
        browser.close()
    return loads, rates


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--site", type=Path, help="a site built by plclab site build")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--seconds", type=float, default=600.0, help="virtual time per run")
    ap.add_argument("--edition", choices=["en", "ru"], default="en",
                    help="whose playground page to load (default en)")
    ap.add_argument("--build-only", action="store_true", help="build the site, print its time")
    ns = ap.parse_args()
    site = ns.site
    if site is None:
        site = Path(tempfile.mkdtemp(prefix="plclab-site-bench-")) / "site"
        t = time.perf_counter()
        rep = build(site)
        print(f"site built in {time.perf_counter() - t:.1f} s: {rep.pages} pages, "
              f"{sum(1 for _ in site.rglob('index.html'))} HTML pages "
              f"({sum(1 for _ in (site / 'ru').rglob('index.html'))} of them Russian)")
    if ns.build_only:
        return
    server, base = serve_in_thread(site)
    try:
        loads, rates = browser_numbers(base, ns.repeat, ns.seconds,
                                       "" if ns.edition == "en" else f"{ns.edition}/")
    finally:
        server.shutdown()
    native = cpython_scans_per_second(ns.seconds)
    med = statistics.median(rates)
    print(f"\nplayground ({ns.edition}), {ns.repeat} cold loads, tank program on the tank plant, "
          "20 ms scans")
    print(f"{'':34}{'median':>12}{'min':>12}{'max':>12}")
    print(f"{'load: page -> ready (s)':34}{statistics.median(loads):12.2f}{min(loads):12.2f}"
          f"{max(loads):12.2f}")
    print(f"{'browser (Pyodide) scans/s':34}{med:12.0f}{min(rates):12.0f}{max(rates):12.0f}")
    print(f"{'CPython scans/s (same Session)':34}{native:12.0f}")
    print(f"{'ratio CPython / browser':34}{native / med:12.2f}")
    print(f"{'virtual time / wall time, browser':34}{med * 0.02:12.0f}x")
    print(f"{'longest block of the page (ms)':34}{statistics.median(GAPS):12.0f}{min(GAPS):12.0f}"
          f"{max(GAPS):12.0f}   goal 100")
    print(f"{'Stop answered in (ms)':34}{statistics.median(STOPS):12.0f}{min(STOPS):12.0f}"
          f"{max(STOPS):12.0f}   goal 200")


if __name__ == "__main__":
    main()
