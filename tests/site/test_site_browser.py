"""The built site in a real browser: Debian's Chromium driven by Playwright, the site served on
loopback. Screenshots go to the folder ``site-screenshots`` of the test's temporary directory
(printed at the end of the run)."""

import re
import shutil
from pathlib import Path
from urllib.parse import urljoin, urlparse

import pytest

CHROMIUM = "/usr/bin/chromium"

PATIENCE_MS = 600_000
"""How long a wait for something the page will do (Pyodide loaded, a run ended, the search
index built) may take before it is a failure: reached only when the page is broken, so it is
generous. On a loaded 2-core machine (three suites at once, load 17) loading Pyodide and
building the Russian search index each took minutes. A test's own measure of speed (the page
not frozen, the clock's pace) compares with what the same page does under the same load."""


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


@pytest.fixture(autouse=True)
def close_pages(browser):
    """Every page a test opened is closed after it: a playground left running or a search
    index still building would take the machine from the tests that follow."""
    yield
    for context in browser.contexts:
        context.close()


def new_page(browser, **options):
    """A page whose waits (navigation, clicks, selectors) last up to PATIENCE_MS."""
    page = browser.new_page(**options)
    page.set_default_timeout(PATIENCE_MS)
    page.set_default_navigation_timeout(PATIENCE_MS)
    return page


@pytest.fixture(scope="module")
def shots(tmp_path_factory):
    d = tmp_path_factory.mktemp("site-screenshots")
    yield d
    print(f"\nsite screenshots: {d}")


def open_page(browser, url, width=1280):
    """A page at ``url`` (``width`` px wide) and the console errors and failed requests it
    produced."""
    page = new_page(browser, viewport={"width": width, "height": 900})
    errors: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    # a request the page's own navigation cancelled (a favicon still loading when a try-it
    # link opens the playground) is net::ERR_ABORTED, not a fault; a missing file is a 404
    page.on("requestfailed", lambda r: errors.append(f"failed: {r.url} ({r.failure})")
            if r.failure != "net::ERR_ABORTED" else None)
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
    page = new_page(browser)
    errors: list[str] = []
    page.on("console", lambda m: errors.append(f"{page.url}: {m.text}")
            if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"{page.url}: {e}"))
    langs = set()
    for rel in paths:
        if rel.startswith(("playground/", "ru/playground/")):
            continue  # loads Python: its own test below
        url = urljoin(base, rel[: -len("index.html")])
        resp = page.goto(url)
        assert resp.status == 200, url
        lang = page.get_attribute("html", "lang")  # each edition's pages speak its language
        assert lang == ("ru" if rel.startswith("ru/") else "en"), url
        langs.add(lang)
        for href in page.eval_on_selector_all("a[href]", "els => els.map(e => e.href)"):
            u = urlparse(href)
            if u.netloc == urlparse(base).netloc:
                seen_links.add(u._replace(fragment="", query="").geturl())
        for src in page.eval_on_selector_all("img[src]", "els => els.map(e => e.src)"):
            seen_links.add(src)
    page.close()
    assert errors == [] and langs == {"en", "ru"}
    broken = []
    for link in sorted(seen_links):
        target = out / urlparse(link).path.lstrip("/")
        if not (target.is_file() or (target / "index.html").is_file()):
            broken.append(link)
    assert broken == []


def search(page, query):
    """Put ``query`` into the site's search and return the result list's text.

    The whole query is one value with one ``keyup``: the search (mkdocs-material) asks its
    web worker for the value on a keyup and again when the index is ready, so the first list
    shown is the answer to the whole query, however long the index takes to build (the
    Russian one, with its stemmer, takes minutes on a loaded machine). Typing it key by key
    made each prefix a query of its own, answered in turn."""
    page.click("label.md-search__icon, .md-search__input")
    page.fill("input.md-search__input", query)
    page.press("input.md-search__input", "End")
    page.wait_for_selector(".md-search-result__item")
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


def wait_state(page, state):
    page.wait_for_function(
        f"['{state}', 'failed'].includes(document.getElementById('pg-status')?.dataset.state)")
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


def test_the_language_switch_goes_to_the_same_page_of_the_other_edition(site, browser):
    """English -> Russian -> English by the header's switch, on a chapter, a quiz, a lab, a
    code's page and the playground: each time the same page in the other language, and every
    link of a Russian page but the switch's stays in the Russian edition."""
    out, base, _ = site
    for path in ("course/12-control/", "course/12-control/quiz/", "labs/tank-two-position/",
                 "problems/PLC0113/", "playground/"):
        page, errors = open_page(browser, urljoin(base, path))
        assert page.get_attribute("html", "lang") == "en"
        for lang, url in (("ru", urljoin(base, "ru/" + path)), ("en", urljoin(base, path))):
            page.hover(".md-header__option .md-select")
            page.click(f"a.plclab-edition[hreflang={lang}]")
            page.wait_for_url(url)  # only the click changes the address
            page.wait_for_load_state("load")
            assert page.get_attribute("html", "lang") == lang
            title = page.inner_text("h1")
            assert bool(re.search("[А-Яа-яЁё]", title)) is (lang == "ru") or \
                path.startswith("problems/") and lang == "en", (url, title)
            if lang == "ru":
                hrefs = page.eval_on_selector_all(
                    "a[href]:not(.plclab-edition)", "els => els.map(e => e.href)")
                here = [h for h in hrefs if urlparse(h).netloc == urlparse(base).netloc]
                assert here and all(h.startswith(urljoin(base, "ru/")) for h in here), \
                    [h for h in here if not h.startswith(urljoin(base, "ru/"))]
        page.close()
        assert errors == [] or path == "playground/", errors  # the playground is left loading


@pytest.mark.parametrize("query,chapter", [
    ("гистерезис", "Двухпозиционное регулирование и ПИД"),
    ("гистерезиса", "Двухпозиционное регулирование и ПИД"),  # another case: stemming
    ("сторожевой", "Рабочий цикл ПЛК"),
])
def test_russian_search_finds_a_russian_word_on_its_chapter(site, browser, query, chapter):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "ru/"))
    found = search(page, query)
    assert chapter in found, found
    links = page.eval_on_selector_all(".md-search-result__link", "els => els.map(e => e.href)")
    assert links and all(h.startswith(urljoin(base, "ru/")) for h in links), links
    assert errors == []


def test_russian_playground_runs_the_tank_for_60_s_and_speaks_russian(site, browser, shots):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "ru/playground/"))
    wait_state(page, "ready")
    assert page.inner_text("#pg-status").startswith("Готово: Python и plclab загружены за ")
    assert page.inner_text("#pg-run60") == "Пуск на 60 с"
    assert page.evaluate("window.plclabPlayground.lang") == "ru"
    page.click("#pg-run60")
    wait_state(page, "ran")
    status = page.inner_text("#pg-status")
    assert re.fullmatch(r"Выполнено 60 с виртуального времени \(циклов: 3000\) за \d+ мс\.",
                        status), status
    summary = page.inner_text("#pg-summary")
    assert summary.startswith("t = 60,0 с, циклов: 3000; PUMP переключался раз: "), summary
    assert summary.endswith("сейчас ВЫКЛ.")
    assert int(page.get_attribute("#pg-summary", "data-switchings")) >= 2
    assert page.inner_text("#pg-clock") == "t = 60,00 с"
    page.screenshot(path=str(shots / "ru-playground-run.png"), full_page=True)
    assert errors == []


RU_ERRORS = {  # a syntax error, an undeclared name, a type mismatch
    "PLC0010": "PROGRAM P\nVAR x : INT; END_VAR\nx := 1 +;\nEND_PROGRAM\n",
    "PLC0100": "PROGRAM P\nVAR x : INT; END_VAR\nx := y + 1;\nEND_PROGRAM\n",
    "PLC0118": "PROGRAM P\nVAR x : INT; b : BOOL; END_VAR\nx := b;\nEND_PROGRAM\n",
}


@pytest.mark.parametrize("code", list(RU_ERRORS))
def test_russian_playground_shows_a_compile_error_in_russian_with_its_code(site, browser, code):
    """The worker's diagnostics come from the Russian problem catalogue: the message the page
    shows is the one plclab gives with --lang ru, with its code and line."""
    from plclab.site import playground_api
    from plclab.site.build import speaking

    program = RU_ERRORS[code]
    with speaking("ru"):
        want = playground_api.check(program)
    assert want and want[0]["code"] == code, want  # the program makes the mistake named
    english = playground_api.check(program)[0]["message"]
    assert want[0]["message"] != english and re.search("[а-я]", want[0]["message"])
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "ru/playground/"))
    wait_state(page, "ready")
    page.fill("#pg-code", program)
    page.click("#pg-compile")
    wait_state(page, "error")
    assert page.inner_text("#pg-status").startswith("Программа не компилируется")
    first = page.locator("#pg-diagnostics li").first
    assert first.get_attribute("data-code") == code
    assert first.get_attribute("data-line") == str(want[0]["line"])
    text = first.inner_text()
    assert text.startswith(f"строка {want[0]['line']}") and f"ошибка {code}: " in text, text
    assert " ".join(want[0]["message"].replace("`", "").split()) in " ".join(text.split())
    assert first.locator("a").get_attribute("href") == f"../problems/{code}/"  # ru/problems
    assert errors == []


def test_russian_lab_page_opens_the_russian_playground_and_checks_in_russian(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "ru/labs/tank-two-position/"))
    page.click("a.try-it")
    page.wait_for_url(re.compile(re.escape(urljoin(base, "ru/playground/")) + "#"))
    wait_state(page, "ready")
    assert page.input_value("#pg-lab") == "tank-two-position"
    assert page.inner_text("#pg-lab option:checked").startswith("Бак:")
    page.click("#pg-check")
    wait_state(page, "checked")
    assert re.search(r"\d+ из \d+ баллов в открытых сценариях", page.inner_text("#pg-status"))
    head = page.locator("#pg-results tr").first.inner_text()
    assert "критерий" in head and "сценарий" in head
    assert "насос включается ниже LS1" in page.inner_text("#pg-results")
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
    benchmarks/site_bench.py. Here the page is measured against the scan itself, so that a
    loaded machine, which slows both, cannot fail it: a loop on the page's thread would
    freeze the page for a whole scan, and a Stop that waited for the scan's end would take
    the rest of one."""
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.fill("#pg-code", LONG_LOOP)
    page.click("#pg-run60")
    page.wait_for_function("window.plclabPlayground.state.scans > 2")
    heartbeat(page)
    scan_ms = page.evaluate("""async () => {  // the mean time of three scans, as the page sees it
        const s = window.plclabPlayground.state, k = s.scans, t = performance.now();
        while (s.scans < k + 3) await new Promise((r) => setTimeout(r, 5));
        return (performance.now() - t) / (s.scans - k); }""")
    gap = page.evaluate("window.__gap")
    stopped_in = page.evaluate("""async () => {  // Stop just after a scan began
        const s = window.plclabPlayground.state, k = s.scans;
        while (s.scans === k) await new Promise((r) => setTimeout(r, 5));
        const t = performance.now();
        await window.plclabPlayground.stop(); return performance.now() - t; }""")
    assert page.get_attribute("#pg-status", "data-state") == "stopped"
    assert gap < max(1000, scan_ms / 2), (gap, scan_ms)
    assert stopped_in < max(2000, scan_ms / 2), (stopped_in, scan_ms)
    assert "Stopped at t = " in page.inner_text("#pg-status")
    assert page.is_disabled("#pg-stop")
    page.wait_for_function("!document.getElementById('pg-run60').disabled")
    assert errors == []


def test_step_pause_and_live_at_the_clocks_pace(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.click("#pg-compile")
    wait_state(page, "compiled")
    for n in (1, 2):
        # After the first step the state already reads "stepped": wait for the scan count,
        # which only the worker's answer to this click moves, then for the state.
        page.click("#pg-step")
        page.wait_for_function(f"window.plclabPlayground.state.scans >= {n}")
        wait_state(page, "stepped")
        assert page.evaluate("window.plclabPlayground.state.scans") == n
    page.click("#pg-live")
    page.wait_for_function("window.plclabPlayground.state.t > 0.5")
    t0 = page.evaluate("[window.plclabPlayground.state.t, performance.now()]")
    page.wait_for_timeout(1000)  # then until the run has moved on: a loaded machine is slower
    page.wait_for_function(f"window.plclabPlayground.state.t > {t0[0]} + 0.5")
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
    page.wait_for_function("document.querySelector(\"#pg-watch tr[data-path='Avg.m']\") !== null")
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


# ------------------------------------------------------------------ accessibility (issue 39)

PAGES = {"home": "", "chapter": "course/10-timers-counters/", "lab": "labs/tank-two-position/",
         "playground": "playground/",
         "ru-home": "ru/", "ru-chapter": "ru/course/10-timers-counters/",
         "ru-quiz": "ru/course/10-timers-counters/quiz/", "ru-lab": "ru/labs/tank-two-position/",
         "ru-playground": "ru/playground/"}
WIDTHS = (1280, 390)
WCAG_AA = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]


@pytest.fixture(scope="module")
def axe():
    from plclab.errors import PlcError
    from plclab.site.bundle import axe_script

    try:
        return axe_script().read_text("utf-8")
    except PlcError as e:
        pytest.skip(f"axe-core could not be installed from npm here: {e.message}")


def axe_violations(page, axe_js):
    """axe-core's WCAG 2.1 A/AA violations of the page as it is now: [(rule, target, why)]."""
    if not page.evaluate("typeof window.axe !== 'undefined'"):
        page.add_script_tag(content=axe_js)
    found = page.evaluate("""async (tags) => {
        const r = await axe.run(document, {runOnly: {type: 'tag', values: tags}});
        return r.violations.flatMap(v => v.nodes.map(n =>
            [v.id, n.target.join(' '), n.failureSummary]));}""", WCAG_AA)
    return [tuple(v) for v in found]


def open_at(browser, url, width):
    return open_page(browser, url, width)


def test_axe_catches_what_it_must(site, browser, axe):
    """The check can fail: a page with low-contrast text, a link told apart by colour alone and
    an unlabelled input has violations of those rules."""
    out, base, _ = site
    page, _ = open_page(browser, base)
    page.evaluate("""() => { const p = document.createElement('p');
        p.innerHTML = '<span style="color:#aaa;background:#fff">faint</span> text with ' +
          '<a href="#" style="color:#333;text-decoration:none">a link</a> and <input>';
        p.style.color = '#000'; document.querySelector('.md-content').prepend(p); }""")
    rules = {v[0] for v in axe_violations(page, axe)}
    assert {"color-contrast", "label"} <= rules, rules


@pytest.mark.parametrize("width", WIDTHS)
@pytest.mark.parametrize("name", list(PAGES))
def test_axe_finds_no_wcag_aa_violation(site, browser, axe, shots, name, width):
    """Home, a chapter, a lab and the playground at a desktop's and a phone's width: 0
    violations of WCAG 2.1 A/AA (contrast, names, focusable scrolling regions...); a
    screenshot of each goes to the screenshots folder."""
    out, base, _ = site
    page, errors = open_at(browser, urljoin(base, PAGES[name]), width)
    assert page.get_attribute("html", "lang") == ("ru" if name.startswith("ru-") else "en")
    if name.endswith("playground"):
        wait_state(page, "ready")
    assert axe_violations(page, axe) == []
    page.screenshot(path=str(shots / f"{name}-{width}.png"),
                    full_page=not name.endswith(("chapter", "quiz")))
    assert errors == []


def test_axe_finds_no_violation_in_a_playground_at_work(site, browser, axe):
    """The playground with what a run adds: diagnostics, the watch panel, a tooltip, the
    completion list and TEST output."""
    out, base, _ = site
    page, errors = open_at(browser, urljoin(base, "playground/"), 390)
    wait_state(page, "ready")
    page.select_option("#pg-plant", "none")
    page.fill("#pg-code", "PROGRAM Count\nVAR n : INT; unused : INT; t : TON; END_VAR\n"
              "n := n + 1;\nt(IN := TRUE, PT := T#1s);\nEND_PROGRAM\n"
              "TEST 'one' Count(); ASSERT_EQ(Count.n, 1); END_TEST\n")
    page.click("#pg-tests")
    wait_state(page, "tested")
    page.click("#pg-step")
    wait_state(page, "stepped")
    assert page.locator("#pg-watch tr").count() > 2
    caret_before(page, "\nEND_PROGRAM")
    page.keyboard.type("\nt.")
    page.wait_for_selector("#pg-complete li")
    assert axe_violations(page, axe) == []
    assert errors == []


def test_the_playground_fits_a_360_px_screen_and_every_control_is_on_it(site, browser):
    out, base, _ = site
    page, errors = open_at(browser, urljoin(base, "playground/"), 360)
    wait_state(page, "ready")
    page.select_option("#pg-lab", "motor-start-stop")  # the longest lab title, motor buttons
    page.click("#pg-compile")
    wait_state(page, "compiled")
    sizes = page.evaluate("[document.documentElement.scrollWidth, "
                          "document.documentElement.clientWidth]")
    assert sizes[0] <= sizes[1] <= 360, sizes
    outside = page.evaluate("""() => [...document.querySelectorAll(
        '#pg button, #pg select, #pg textarea, #pg input')].filter(e => {
          const r = e.getBoundingClientRect();
          return r.width === 0 || r.left < 0 || r.right > document.documentElement.clientWidth;
        }).map(e => e.id || e.textContent)""")
    assert outside == []
    assert errors == []


def test_every_playground_control_is_reached_by_tab_shows_focus_and_answers_the_keys(
        site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.select_option("#pg-plant", "motor")
    wanted = page.evaluate("""() => [...document.querySelectorAll(
        '#pg button, #pg select, #pg textarea, #pg input')].filter(e => !e.disabled)
        .map(e => e.id || e.textContent)""")
    assert {"pg-lang", "pg-code", "pg-compile", "pg-run60", "pg-share", "START"} <= set(wanted)
    page.focus("#pg-lang")
    page.keyboard.press("Shift+Tab")  # then Tab: the keyboard, not a script, brings the focus
    page.keyboard.press("Tab")
    reached, unseen_focus = [], []
    for _ in range(len(wanted) + 5):
        info = page.evaluate("""() => { const e = document.activeElement, s = getComputedStyle(e);
            return [e.id || e.textContent, s.outlineStyle !== 'none' && parseFloat(s.outlineWidth) >= 2
                    || s.boxShadow !== 'none']; }""")
        if info[0] in wanted and info[0] not in reached:
            reached.append(info[0])
            if not info[1]:
                unseen_focus.append(info[0])
        page.keyboard.press("Tab")
    assert reached == wanted  # every control, in the page's order
    assert unseen_focus == []
    page.focus("#pg-compile")
    page.keyboard.press("Enter")
    wait_state(page, "compiled")
    page.focus("#pg-step")
    page.keyboard.press(" ")
    wait_state(page, "stepped")
    assert errors == []


# ------------------------------------------------------------------ the editor (issues 36, 39)

def caret_before(page, text):
    """Focus the editor with the caret just before the first ``text``."""
    page.focus("#pg-code")
    page.evaluate("""s => { const t = document.getElementById('pg-code');
        const at = t.value.indexOf(s); t.setSelectionRange(at, at); }""", text)


def coloured(pieces):
    """(class, text) pieces as a reader sees them: neighbours of one class joined (the course's
    formatter writes one span for them), then whitespace left out."""
    merged = []
    for c, t in pieces:
        if merged and merged[-1][0] == c:
            merged[-1][1] += t
        else:
            merged.append([c, t])
    return [p for p in merged if p[1].strip() and p[0] not in ("w", "")]


def layer_pieces(page):
    """The editor's coloured layer as (class, text) pieces (the marks' classes left out)."""
    return page.evaluate("""() => [...document.querySelectorAll('#pg-layer > span')]
        .map(s => [s.className.split(' ').filter(c => !c.startsWith('pg-'))[0] || '',
                   s.textContent])""")


def test_the_editor_colours_an_example_as_its_chapter_does(site, browser):
    """The first ST, IL and LD examples of the course: the playground's layer has the same
    coloured pieces as the chapter's code block (the same Pygments lexers, in the worker)."""
    out, base, _ = site
    checked = set()
    page, errors = None, []
    for chapter in ("05-iec-61131-3", "08-instruction-list", "06-ladder"):
        ch, errs = open_page(browser, urljoin(base, f"course/{chapter}/"))
        errors += errs
        links = ch.locator("a.try-it")
        for k in range(links.count()):
            href = links.nth(k).get_attribute("href")
            lang = re.search(r"lang=(\w+)", href).group(1)
            if lang in checked or "expect=" in href:
                continue
            block = links.nth(k).locator("xpath=preceding::div[contains(@class,'highlight')][1]")
            course = coloured(block.evaluate("""b => [...b.querySelectorAll('code span')]
                .map(s => [s.className, s.textContent])"""))
            page, e2 = open_page(browser, urljoin(ch.url, href))
            errors += e2
            page.wait_for_function("document.querySelector('#pg-layer .k') !== null")
            ours = coloured(layer_pieces(page))
            assert len(ours) > 10 and ours == course, (chapter, lang)
            checked.add(lang)
            break
    assert checked == {"st", "il", "ld"}
    assert errors == []


def test_diagnostics_are_underlined_in_place_with_a_linked_code_and_a_hover(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.fill("#pg-code", "PROGRAM P\nVAR x : INT; END_VAR\nx := speed + 1;\nEND_PROGRAM\n")
    mark = page.locator("#pg-layer .pg-mark-error")
    mark.wait_for()
    assert mark.inner_text() == "speed"
    assert page.locator("#pg-gutter .pg-bad").inner_text() == "3"
    code = page.locator("#pg-diagnostics li").first.get_attribute("data-code")
    box = mark.bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    tip = page.locator("#pg-tip")
    tip.wait_for(state="visible")
    assert code in tip.inner_text() and "speed" in tip.inner_text()
    href = tip.locator("a").first.get_attribute("href")
    assert href.endswith(f"/problems/{code}/")
    page.mouse.move(box["x"] + 4, box["y"] + box["height"] + 4)  # onto the tooltip
    tip.locator("a").first.click()
    page.wait_for_url(f"**/problems/{code}/")
    assert code in page.inner_text("h1")
    assert errors == []


def test_hover_and_the_info_line_show_declarations_and_standard_signatures(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.fill("#pg-code", "PROGRAM P\nVAR\n    delay : TON;\n    n : INT;\nEND_VAR\n"
              "delay(IN := TRUE, PT := T#1s);\nn := LIMIT(0, n + 1, 5);\nEND_PROGRAM\n")
    # the keyboard: the caret on `delay` (line 6), then on LIMIT (line 7)
    caret_before(page, "lay(")
    page.keyboard.press("ArrowRight")
    page.wait_for_function("document.getElementById('pg-info').textContent.includes('TON')")
    assert "delay : TON" in page.inner_text("#pg-info")
    caret_before(page, "IMIT(")
    page.keyboard.press("ArrowRight")
    page.wait_for_function("document.getElementById('pg-info').textContent.includes('LIMIT')")
    # the mouse: hover over `n` on line 7
    piece = page.locator("#pg-layer span", has_text=re.compile(r"^n$")).nth(1)
    box = piece.bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.wait_for_function("!document.getElementById('pg-tip').hidden")
    assert "n : INT" in page.inner_text("#pg-tip")
    assert errors == []


def test_completion_of_names_blocks_and_members_by_keyboard(site, browser):
    out, base, _ = site
    page, errors = open_page(browser, urljoin(base, "playground/"))
    wait_state(page, "ready")
    page.fill("#pg-code", "PROGRAM P\nVAR\n    delay : TON;\n    level : REAL;\nEND_VAR\n"
              "END_PROGRAM\n")
    caret_before(page, "\nEND_PROGRAM")
    page.keyboard.type("\nlev")
    page.keyboard.press("Control+Space")
    page.wait_for_selector("#pg-complete li")
    assert page.locator("#pg-complete li").first.get_attribute("data-label") == "level"
    page.keyboard.press("Enter")
    assert "\nlevel" in page.input_value("#pg-code")
    page.keyboard.type(" := 1.0;\ndelay.")
    page.wait_for_selector("#pg-complete li")
    labels = page.eval_on_selector_all("#pg-complete li", "els => els.map(e => e.dataset.label)")
    assert {"Q", "ET", "IN", "PT"} <= set(labels) and "level" not in labels
    page.keyboard.press("ArrowDown")
    chosen = page.locator("#pg-complete li[aria-selected='true']").get_attribute("data-label")
    assert page.get_attribute("#pg-code", "aria-activedescendant")
    page.keyboard.press("Tab")
    assert f"delay.{chosen}" in page.input_value("#pg-code")
    assert page.is_hidden("#pg-complete")
    page.keyboard.type(";\nCT")
    page.keyboard.press("Control+Space")
    page.wait_for_selector("#pg-complete li")
    labels = page.eval_on_selector_all("#pg-complete li", "els => els.map(e => e.dataset.label)")
    assert {"CTU", "CTD", "CTUD"} <= set(labels)
    page.keyboard.press("Escape")
    assert page.is_hidden("#pg-complete")
    assert errors == []


# ------------------------------------------------------------------ every try-it example

# Examples whose warning is a known gap elsewhere, each with why; the test fails when the
# example no longer gives it (then remove the entry).
KNOWN_WARNINGS = {
    # the linter counts a variable read only by a TEST as unused (plclab/lang's PLC0200)
    ("09-structured-text", "PLC0200"): "Motor1 is read by the TEST only",
}


def try_links(browser, base, out):
    """Every try-it link of the course and the labs: (page, href)."""
    found = []
    page = new_page(browser)
    for html_file in sorted((out / "course").glob("*/index.html")) + \
            sorted((out / "labs").glob("*/index.html")):
        rel = html_file.relative_to(out).as_posix()[: -len("index.html")]
        page.goto(urljoin(base, rel))
        for href in page.eval_on_selector_all("a.try-it", "els => els.map(e => e.href)"):
            found.append((rel, href))
    page.close()
    return found


def test_every_try_it_example_shows_its_plant_watch_or_tests_without_an_unasked_warning(
        site, browser):
    """Each course and lab example opens with its plant (and no PLC3044), its variables in the
    watch panel, or its TEST results; the only diagnostics are the mistake it makes on purpose
    (``expect=``, with the errors that follow from it)."""
    out, base, _ = site
    links = try_links(browser, base, out)
    assert len(links) > 60
    page = new_page(browser, viewport={"width": 1280, "height": 900})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.add_init_script("window.__shown = []; window.addEventListener('pg-example', "
                         "e => window.__shown.push(e.detail));")
    page.goto(links[0][1])
    page.wait_for_function("window.__shown.length === 1")
    problems, known_seen = [], set()
    for n, (where, href) in enumerate(links):
        if n:
            page.evaluate("h => { location.hash = h; }", href.split("#", 1)[1])
            page.wait_for_function(f"window.__shown.length === {n + 1}")
        d = page.evaluate("window.__shown[window.__shown.length - 1]")
        expect = set(d["expect"])
        codes = set(d["codes"])
        slug = where.strip("/").split("/")[-1]
        known = {c for c in codes if (slug, c) in KNOWN_WARNINGS}
        known_seen |= {(slug, c) for c in known}
        if expect:
            if not expect <= codes:
                problems.append((where, href[-60:], "the deliberate mistake is not shown",
                                 sorted(codes)))
            continue
        if codes - known:
            problems.append((where, d["shown"], "diagnostics it did not ask for",
                             sorted(codes)))
        elif d["shown"] == "plant" and d["rows"] < 1:
            problems.append((where, "plant", "no diagram row"))
        elif d["shown"] == "watch" and d["watch"] < 1:
            problems.append((where, "watch", "an empty watch panel"))
        elif d["shown"] == "tests" and not re.search(r"\d+ passed, 0 failed", d["tests"]):
            problems.append((where, "tests", d["tests"][-200:]))
        elif d["shown"] not in ("plant", "watch", "tests"):
            problems.append((where, d["shown"], d["status"]))
    assert problems == [], problems
    assert known_seen == set(KNOWN_WARNINGS)
    assert errors == []
