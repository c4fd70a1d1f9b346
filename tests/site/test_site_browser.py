"""The built site in a real browser: Debian's Chromium driven by Playwright, the site served on
loopback. Screenshots go to the folder ``site-screenshots`` of the test's temporary directory
(printed at the end of the run)."""

import re
import shutil
from pathlib import Path
from urllib.parse import urljoin, urlparse

import pytest

CHROMIUM = "/usr/bin/chromium"


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    if not Path(CHROMIUM).exists():
        pytest.skip(f"no Chromium at {CHROMIUM} (apt-get install chromium)")
    if shutil.which("node") is None and shutil.which("npm") is None:
        pytest.skip("node/npm are not installed: the playground's Pyodide cannot be fetched")
    pytest.importorskip("mkdocs")
    pytest.importorskip("material")
    pytest.importorskip("playwright")
    from plclab.errors import PlcError
    from plclab.site.build import build
    from plclab.site.serve import serve_in_thread

    out = tmp_path_factory.mktemp("site") / "site"
    try:
        rep = build(out)
    except PlcError as e:
        if e.code != "PLC3042":
            raise
        pytest.skip(f"Pyodide could not be installed from npm here: {e.message}")
    server, base = serve_in_thread(out)
    yield out, base, rep
    server.shutdown()
    server.server_close()


@pytest.fixture(scope="module")
def browser(site):
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        yield b
        b.close()


@pytest.fixture(scope="module")
def shots(tmp_path_factory):
    d = tmp_path_factory.mktemp("site-screenshots")
    yield d
    print(f"\nsite screenshots: {d}")


def open_page(browser, url):
    """A page at ``url`` and the console errors and failed requests it produced."""
    page = browser.new_page(viewport={"width": 1280, "height": 900})
    errors: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("requestfailed", lambda r: errors.append(f"failed: {r.url}"))
    page.on("response", lambda r: errors.append(f"{r.status}: {r.url}") if r.status >= 400
            else None)
    page.goto(url)
    page.wait_for_load_state("load")
    return page, errors


def all_pages(out: Path) -> list[str]:
    return sorted(p.relative_to(out).as_posix() for p in out.rglob("index.html"))


def test_every_page_loads_without_console_errors_and_no_internal_link_is_broken(site, browser):
    out, base, rep = site
    assert rep.warnings == []
    paths = all_pages(out)
    assert len(paths) > 150  # chapters, labs, one page per code, plants, ADRs
    seen_links: set[str] = set()
    page = browser.new_page()
    errors: list[str] = []
    page.on("console", lambda m: errors.append(f"{page.url}: {m.text}")
            if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"{page.url}: {e}"))
    for rel in paths:
        if rel.startswith("playground/"):
            continue  # loads Python: its own test below
        url = urljoin(base, rel[: -len("index.html")])
        resp = page.goto(url)
        assert resp.status == 200, url
        for href in page.eval_on_selector_all("a[href]", "els => els.map(e => e.href)"):
            u = urlparse(href)
            if u.netloc == urlparse(base).netloc:
                seen_links.add(u._replace(fragment="", query="").geturl())
        for src in page.eval_on_selector_all("img[src]", "els => els.map(e => e.src)"):
            seen_links.add(src)
    page.close()
    assert errors == []
    broken = []
    for link in sorted(seen_links):
        target = out / urlparse(link).path.lstrip("/")
        if not (target.is_file() or (target / "index.html").is_file()):
            broken.append(link)
    assert broken == []


def search(page, query):
    """Type ``query`` into the site's search and return the result list's text."""
    page.click("label.md-search__icon, .md-search__input", timeout=5000)
    for _ in range(15):  # the search index loads in a web worker: type again until it answers
        page.fill("input.md-search__input", "")
        page.type("input.md-search__input", query)
        try:
            page.wait_for_selector(".md-search-result__item", timeout=2000)
            break
        except Exception:  # noqa: BLE001 - playwright's TimeoutError: not ready yet
            continue
    return page.inner_text(".md-search-result__list")


def test_search_finds_ton(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, base)
    assert re.search(r"\bTON\b", search(page, "TON"))
    assert errors == []


@pytest.mark.parametrize("query", ["seal-in", "two-hand", "4-20 mA"])
def test_search_finds_hyphenated_terms(site, browser, query):
    """A hyphen inside a word is part of the term, not lunr's "exclude" operator."""
    out, base, _ = site
    page, errors = open_page(browser, base)
    found = search(page, query)
    assert found.strip() and "No matching" not in found, found
    assert query.split("-")[0].split()[0].lower() in found.lower()
    assert errors == []


def test_home_chapter_and_lab_pages(site, browser, shots):
    out, base, _ = site
    page, errors = open_page(browser, base)
    assert "plclab" in page.title()
    page.screenshot(path=str(shots / "home.png"))
    page, errors2 = open_page(browser, urljoin(base, "course/10-timers-counters/"))
    assert page.locator("img[src$='ton.svg']").count() == 1
    assert page.locator("a.try-it").count() > 3
    page.screenshot(path=str(shots / "chapter.png"))
    page, errors3 = open_page(browser, urljoin(base, "labs/tank-two-position/"))
    table = page.locator("xpath=//h2[@id='io-table']/following::table[1]")
    assert table.count() == 1 and "%IX0.0" in table.inner_text()
    assert "LS1" in table.inner_text() and "PUMP" in table.inner_text()
    assert page.locator("xpath=//th[normalize-space()='Address']").count() == 1  # once
    page.screenshot(path=str(shots / "lab.png"))
    assert errors == errors2 == errors3 == []


def wait_state(page, state, timeout=120000):
    page.wait_for_function(
        f"['{state}', 'failed'].includes(document.getElementById('pg-status')?.dataset.state)",
        timeout=timeout)
    assert page.get_attribute("#pg-status", "data-state") == state, page.inner_text("#pg-status")


def test_playground_runs_the_tank_for_60_s_and_shows_the_pump_switching(site, browser, shots):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    assert "TankLevel" in page.input_value("#pg-code")
    page.click("#pg-run60")
    wait_state(page, "ran")
    summary = page.inner_text("#pg-summary")
    assert "t = 60.0 s, 3000 scans" in summary
    assert int(page.get_attribute("#pg-summary", "data-switchings")) >= 2
    assert "now OFF" in summary  # switched on at the start, off at LS2
    page.screenshot(path=str(shots / "playground.png"), full_page=True)
    assert errors == []


def test_playground_shows_a_syntax_error_at_its_line(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.fill("#pg-code", "PROGRAM P\nVAR x : INT; END_VAR\nx := 1 +;\nEND_PROGRAM\n")
    page.click("#pg-compile")
    wait_state(page, "error")
    first = page.locator("#pg-diagnostics li").first
    assert first.get_attribute("data-code") == "PLC0010"
    assert first.get_attribute("data-line") == "3"
    assert first.inner_text().startswith("line 3")
    assert page.locator("#pg-gutter .pg-bad").inner_text() == "3"
    assert errors == []


def test_try_it_link_and_check_against_the_lab(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "labs/tank-two-position/"))
    page.click("a.try-it")
    wait_state(page, "ready")
    assert "your code here" in page.input_value("#pg-code")  # the starter
    assert page.input_value("#pg-lab") == "tank-two-position"
    page.click("#pg-check")
    wait_state(page, "checked")
    assert "0 of" in page.inner_text("#pg-status")  # the starter does nothing yet
    solution = ("PROGRAM TankLevel\nVAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL;\n"
                "PUMP AT %QX0.0 : BOOL; END_VAR\nPUMP := ((NOT LS1) OR PUMP) AND NOT LS2;\n"
                "END_PROGRAM\n")
    page.fill("#pg-code", solution)
    page.click("#pg-check")
    wait_state(page, "checked")
    m = re.search(r"(\d+) of (\d+) points", page.inner_text("#pg-status"))
    assert m and m.group(1) == m.group(2) and int(m.group(2)) > 0
    assert page.locator("#pg-results tr.pg-pass").count() > 5
    assert errors == []


def test_motor_lab_checked_in_the_page(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.select_option("#pg-lab", "motor-start-stop")
    assert page.input_value("#pg-plant") == "motor"
    assert page.locator("#pg-buttons button").all_inner_texts() == ["START", "STOP", "OL_RESET"]
    page.select_option("#pg-lang", "st")
    page.fill("#pg-code", "PROGRAM Motor\nVAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL;\n"
              "OVERLOAD AT %IX0.4 : BOOL; K1 AT %QX0.0 : BOOL; END_VAR\n"
              "K1 := (START OR K1) AND STOP AND NOT OVERLOAD;\nEND_PROGRAM\n")
    page.click("#pg-check")
    wait_state(page, "checked")
    m = re.search(r"(\d+) of (\d+) points", page.inner_text("#pg-status"))
    assert m and m.group(1) == m.group(2) and int(m.group(2)) > 0
    assert errors == []


def test_course_code_is_highlighted_as_iec_text_not_smalltalk(site):
    """Every course page's code is coloured by plclab's IEC lexers: ``(* ... *)`` is a comment
    and nothing is an error token (Pygments' Smalltalk lexer, which owns the name "st", marks
    ``:`` as an error and colours comments as code)."""
    out, _, _ = site
    pages = sorted((out / "course").rglob("index.html"))
    assert pages
    comments = 0
    for page in pages:
        html = page.read_text("utf-8")
        assert 'class="err"' not in html, page
        comments += html.count('<span class="cm">(*')
    assert comments >= 20


def test_serve_reuses_a_site_built_from_the_same_sources(site):
    """``plclab site serve`` does not build again what is up to date, and the build left
    gzip copies of the playground's large assets."""
    from plclab.site.build import build

    out, _, rep = site
    assert not rep.reused and rep.compressed > 0
    again = build(out, reuse=True)
    assert again.reused and again.pages > 0
    wasm = next(out.rglob("*.wasm"))
    assert wasm.with_name(wasm.name + ".gz").stat().st_size < wasm.stat().st_size / 2


LONG_LOOP = ("PROGRAM Busy\nVAR i : DINT; x : DINT; END_VAR\n"
             "FOR i := 1 TO 200000 DO x := x + 1; END_FOR;\nEND_PROGRAM\n")


def heartbeat(page):
    """Start a timer in the page that records the longest gap between its ticks (ms): the
    main thread is blocked for about that long at worst."""
    page.evaluate("""() => { window.__gap = 0; let last = performance.now();
        window.__beat = setInterval(() => { const n = performance.now();
            window.__gap = Math.max(window.__gap, n - last); last = n; }, 10); }""")


def test_a_long_legal_loop_never_freezes_the_page_and_stop_answers(site, browser):
    """The program runs in a worker: a 200,000-iteration loop per scan keeps the page's own
    thread free, and Stop ends the run at once, even inside one long scan (the worker is
    replaced). The figures the issue asks for (100 ms, 200 ms) are measured by
    benchmarks/site_bench.py; this test bounds them loosely (a loaded CI machine)."""
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.fill("#pg-code", LONG_LOOP)
    heartbeat(page)
    page.click("#pg-run60")
    page.wait_for_function("window.plclabPlayground.state.scans > 2", timeout=120000)
    page.wait_for_timeout(1500)
    stopped_in = page.evaluate("""async () => { const t = performance.now();
        await window.plclabPlayground.stop(); return performance.now() - t; }""")
    gap = page.evaluate("window.__gap")
    assert page.get_attribute("#pg-status", "data-state") == "stopped"
    assert stopped_in < 2000 and gap < 1000, (stopped_in, gap)
    assert "Stopped at t = " in page.inner_text("#pg-status")
    assert page.is_disabled("#pg-stop")
    page.wait_for_function("!document.getElementById('pg-run60').disabled", timeout=120000)
    assert errors == []


def test_step_pause_and_live_at_the_clocks_pace(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.click("#pg-compile")
    wait_state(page, "compiled")
    for n in (1, 2):
        page.click("#pg-step")
        wait_state(page, "stepped")
        assert page.evaluate("window.plclabPlayground.state.scans") == n
    page.click("#pg-live")
    page.wait_for_function("window.plclabPlayground.state.t > 0.5", timeout=60000)
    t0 = page.evaluate("[window.plclabPlayground.state.t, performance.now()]")
    page.wait_for_timeout(1500)
    t1 = page.evaluate("[window.plclabPlayground.state.t, performance.now()]")
    virtual, wall = t1[0] - t0[0], (t1[1] - t0[1]) / 1000
    assert 0 < virtual <= wall * 1.0 + 0.6, (virtual, wall)  # 1x: never ahead of the clock
    assert "live at 1x" in page.inner_text("#pg-clock")
    page.click("#pg-pause")
    wait_state(page, "paused")
    held = page.evaluate("window.plclabPlayground.state.t")
    page.wait_for_timeout(600)
    assert page.evaluate("window.plclabPlayground.state.t") - held < 0.25
    page.click("#pg-stop")
    wait_state(page, "stopped")
    assert errors == []


def test_watch_panel_writes_and_forces_a_program_without_a_plant(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.select_option("#pg-plant", "none")
    page.fill("#pg-code", "PROGRAM Count\nVAR n : INT; run : BOOL := TRUE; END_VAR\n"
              "IF run THEN n := n + 1; END_IF;\nEND_PROGRAM\n")
    page.click("#pg-compile")
    wait_state(page, "compiled")
    assert page.locator("#pg-diagnostics li").count() == 0  # no warning about a plant
    row = page.locator("#pg-watch tr[data-path='Count.run']")
    row.locator("input.pg-new").fill("FALSE")
    row.locator("button", has_text="Force").click()
    page.wait_for_function("document.querySelector(\"#pg-watch tr[data-path='Count.run']\")"
                           ".classList.contains('pg-forced')")
    page.click("#pg-step")
    wait_state(page, "stepped")
    assert page.locator("#pg-watch tr[data-path='Count.n'] .pg-value").inner_text() == "0"
    nrow = page.locator("#pg-watch tr[data-path='Count.n']")
    nrow.locator("input.pg-new").fill("41")
    nrow.locator("button", has_text="Write").click()
    page.wait_for_function("document.querySelector(\"#pg-watch tr[data-path='Count.n'] "
                           ".pg-value\").textContent === '41'")
    assert errors == []


def test_try_it_opens_what_the_example_needs_and_share_links_round_trip(site, browser):
    """A try-it link of a program with TEST blocks shows their results as `plclab test` prints
    them; one that drives no plant opens without a plant and shows its variables; the share
    link brings back the program, and a changed hash in an open tab is followed."""
    import base64

    def link(code):
        data = base64.urlsafe_b64encode(code.encode()).decode().rstrip("=")
        return urljoin(base, f"playground/#lang=st&code={data}")

    out, base, _ = site
    tested = ("FUNCTION Twice : INT VAR_INPUT x : INT; END_VAR Twice := 2 * x; END_FUNCTION\n"
              "TEST 'twice three' ASSERT_EQ(Twice(3), 6); END_TEST\n")
    page, errors = open_page(browser, link(tested))
    wait_state(page, "tested")
    assert page.inner_text("#pg-test-output").splitlines() == ["PASS twice three",
                                                              "1 passed, 0 failed"]
    plain = "PROGRAM Avg\nVAR a : REAL := 2.0; b : REAL := 4.0; m : REAL; END_VAR\n" \
            "m := (a + b) / 2.0;\nEND_PROGRAM\n"
    page.evaluate(f"location.hash = {link(plain).split('#')[1]!r}")
    page.wait_for_function("document.querySelector(\"#pg-watch tr[data-path='Avg.m']\") !== null",
                           timeout=60000)
    assert page.input_value("#pg-plant") == "none"
    assert page.locator("#pg-diagnostics li").count() == 0
    assert page.locator("#pg-watch tr[data-path='Avg.m'] .pg-value").inner_text() == "3.0"
    url = page.evaluate("window.plclabPlayground.shareLink()")
    other, errors2 = open_page(browser, url)
    wait_state(other, "ready")
    assert other.input_value("#pg-code") == plain
    assert other.input_value("#pg-plant") == "none"
    assert errors == errors2 == []


def test_motor_buttons_answer_the_keyboard(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.select_option("#pg-plant", "motor")
    page.fill("#pg-code", "PROGRAM Motor\nVAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL;\n"
              "K1 AT %QX0.0 : BOOL; END_VAR\nK1 := (START OR K1) AND STOP;\nEND_PROGRAM\n")
    page.click("#pg-compile")
    wait_state(page, "compiled")
    start = page.locator("#pg-buttons button", has_text="START")
    start.focus()
    page.keyboard.down(" ")
    for _ in range(3):
        page.click("#pg-step")
        wait_state(page, "stepped")
    page.keyboard.up(" ")
    assert page.locator("#pg-watch tr[data-path='Motor.K1'] .pg-value").inner_text() == "TRUE"
    assert errors == []
