"""The operator panel: users and rights, buttons, acknowledgement and recipes through the
Panel API and over HTTP, and the page itself in headless Chromium (playwright)."""

from __future__ import annotations

import json
import re
import shutil
import socket
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

import plclab
from plclab.errors import PlcError
from plclab.process import Alarm, AlarmServer, Recipe
from plclab.scada.panel import Panel, make_server
from plclab.sim import Simulation

TANK = """PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM
PROGRAM Mix
VAR Orange, Water, Sugar, Flavoring : REAL; END_VAR
END_PROGRAM"""


def make_panel(speed: float = 5.0) -> Panel:
    plc = plclab.loads(TANK)
    sim = Simulation(plc, "tank", plant_params={"level0": 0.6}, wall_clock=False)
    alarms = AlarmServer([Alarm("FULL", "the level is above LS1", tag="LS1",
                                alarm_class="error"),
                          Alarm("HIGH", "level above 0.55 m", tag="LEVEL", kind="H",
                                limit=0.55)])
    return Panel(sim, alarms, Recipe.juice(), speed=speed)


def test_rights_of_viewer_operator_and_engineer():
    p = make_panel()
    p.advance(3)
    assert [(a["id"], a["state"]) for a in p.state()["alarms"]] == [("FULL", "I"),
                                                                     ("HIGH", "I")]
    with pytest.raises(PlcError, match="user viewer may not acknowledge alarms; log in as "
                                       "operator or engineer") as e:
        p.acknowledge("FULL")
    assert e.value.code == "PLC6050"
    p.login("operator")
    assert p.acknowledge() is True  # every pending alarm: only FULL needs it
    assert p.state()["log"][-1]["state"] == "IA" and p.state()["log"][-1]["user"] == "operator"
    with pytest.raises(PlcError, match="may not download recipe records; log in as engineer"):
        p.load_recipe("orange_juice")
    p.login("engineer")
    p.load_recipe("orange_juice")
    assert p.sim.plc["Mix.Orange"] == 95.0 and p.state()["record"] == "orange_juice"
    with pytest.raises(PlcError, match="no user"):
        p.login("root")


def test_panel_inputs_only():
    p = make_panel()
    p.login("operator")
    p.set("VALVE", 30)
    assert p.sim.plant.read("VALVE") == 30.0
    with pytest.raises(PlcError, match="not a panel input"):
        p.press("PUMP")
    with pytest.raises(PlcError, match="not a panel input"):
        p.press("VALVE")  # a REAL: set it


def test_a_pressed_button_is_released_after_a_moment():
    plc = plclab.loads("""PROGRAM Main VAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL;
        M AT %QX0.0 : BOOL; END_VAR M := (START OR M) AND STOP; END_PROGRAM""")
    p = Panel(Simulation(plc, "conveyor", wall_clock=False))
    p.login("operator")
    p.press("START")
    assert p.sim.plant.read("START") is True
    p.advance(10)
    assert plc["M"] is True
    p.advance(40)
    assert p.sim.plant.read("START") is False and plc["M"] is True
    p.press("STOP")  # normally closed: pressing opens it
    assert p.sim.plant.read("STOP") is False
    p.advance(40)
    assert plc["M"] is False and p.sim.plant.read("STOP") is True


@pytest.fixture
def served():
    panel = make_panel(speed=5.0)
    server = make_server(panel, port=0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    panel.start()
    yield panel, f"http://127.0.0.1:{server.server_address[1]}"
    panel.stop()
    server.shutdown()
    server.server_close()


def _token(url: str) -> str:
    """The secret the panel's page sends with every action."""
    base = url.split("/", 3)[:3]
    with urllib.request.urlopen("/".join(base) + "/", timeout=5) as r:
        return re.search(r'"X-Plclab-Token": "([^"]+)"', r.read().decode()).group(1)


def _post(url: str, body: dict, headers: dict | None = None) -> tuple[int, dict]:
    h = {"Content-Type": "application/json", "X-Plclab-Token": _token(url), **(headers or {})}
    req = urllib.request.Request(url, json.dumps(body).encode(), h)
    try:
        with urllib.request.urlopen(req, timeout=5) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read())


def test_the_json_api(served):
    panel, url = served
    with urllib.request.urlopen(url + "/state", timeout=5) as r:
        st = json.loads(r.read())
    assert st["plant"] == "tank" and st["user"] == "viewer"
    assert _post(url + "/ack", {})[0] == 403
    assert _post(url + "/login", {"user": "operator"}) == (200, {"ok": True})
    assert _post(url + "/ack", {"id": "FULL"}) == (200, {"ok": True})
    code, body = _post(url + "/recipe", {"record": "orange_juice"})
    assert code == 403 and body["code"] == "PLC6050"
    assert _post(url + "/nope", {})[0] == 404
    with pytest.raises(PlcError, match="only this machine"):
        make_server(panel, host="0.0.0.0")


CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"


def test_the_page_in_headless_chromium(served, tmp_path):
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="the browser test needs playwright (pip install "
                                          "playwright)")
    if not Path(CHROMIUM).exists():
        pytest.skip("no chromium at /usr/bin/chromium (apt-get install chromium)")
    panel, url = served
    with sync_api.sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, headless=True,
                                     args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1200, "height": 800})
        page.set_default_timeout(300_000)  # waits end when the page answers; a loaded
        page.set_default_navigation_timeout(300_000)  # machine must not fail them
        page.goto(url)
        page.wait_for_selector("#alarm-FULL")
        assert page.inner_text("#title").startswith("Hydro-accumulator tank")
        assert page.is_disabled("#ack-FULL")  # a viewer may not acknowledge
        page.select_option("#user", "operator")
        page.wait_for_function("!document.querySelector('#ack-FULL').disabled")
        page.click("#ack-FULL")
        page.wait_for_function(
            "document.querySelector('#alarm-FULL td:nth-child(2)').textContent === 'IA'")
        page.click("#recipe-orange_juice")
        page.wait_for_function("document.querySelector('#message').textContent.includes("
                               "'may not download recipe records')")
        page.select_option("#user", "engineer")
        page.wait_for_function("document.querySelector('#user').value === 'engineer'")
        page.click("#recipe-orange_nectar")
        page.wait_for_selector("text=load orange_nectar (active)")
        assert panel.sim.plc["Mix.Orange"] == 70.0
        log = page.inner_text("#log-body")
        assert "operator" in log and "IA" in log
        shot = tmp_path / "panel.png"
        page.screenshot(path=str(shot), full_page=True)
        browser.close()
    assert shot.stat().st_size > 10_000
    import os

    keep = os.environ.get("PLCLAB_KEEP_SCREENSHOT")
    if keep:  # to look at the picture: PLCLAB_KEEP_SCREENSHOT=/tmp/panel.png
        shutil.copyfile(shot, keep)


def test_the_notebook_panel_acts_through_the_same_rights():
    pytest.importorskip("ipywidgets", reason="the notebook panel needs ipywidgets")
    from plclab.scada.widgets import notebook_panel

    p = make_panel()
    nb = notebook_panel(p)
    nb.run(1.0)
    assert "FULL" in nb.alarms.value and ">I<" in nb.alarms.value
    assert nb.ack.disabled  # a viewer
    nb.records["orange_juice"].click()
    assert "may not download recipe records" in nb.message.value
    nb.user.value = "operator"
    assert not nb.ack.disabled
    nb.ack.click()
    assert ">IA<" in nb.alarms.value and "operator" in nb.alarms.value
    nb.user.value = "engineer"
    nb.records["orange_nectar"].click()
    assert p.sim.plc["Mix.Orange"] == 70.0 and nb.message.value == ""
    assert "t = 1.0 s" in nb.signals.value


def _raw(url: str, request: bytes, timeout: float = 10.0) -> bytes:
    """Send raw bytes to the panel's port and return what it answers (b"" on close)."""
    port = int(url.rsplit(":", 1)[1])
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(request)
        out = b""
        while True:
            try:
                chunk = s.recv(65536)
            except (TimeoutError, OSError):
                break
            if not chunk:
                break
            out += chunk
        return out


def test_cross_site_and_rebinding_requests_are_refused(served):
    panel, url = served
    port = url.rsplit(":", 1)[1]
    # another web page in the student's browser: no token, a foreign Origin
    evil = {"Origin": "http://evil.example"}
    assert _post(url + "/login", {"user": "operator"}, evil)[0] == 403
    req = urllib.request.Request(url + "/login", b'{"user": "operator"}',
                                 {"Content-Type": "application/json"})
    with pytest.raises(urllib.error.HTTPError) as e:
        urllib.request.urlopen(req, timeout=5)
    assert e.value.code == 403
    assert panel.user == "viewer"
    # DNS rebinding: the right address under a foreign name
    got = _raw(url, f"GET /state HTTP/1.1\r\nHost: evil.example:{port}\r\n"
                    "Connection: close\r\n\r\n".encode())
    assert got.startswith(b"HTTP/1.0 403") and b'"plant"' not in got
    # the panel's own page still works
    assert _post(url + "/login", {"user": "operator"}) == (200, {"ok": True})


@pytest.mark.parametrize("value", [1e400, "inf", "NaN", "1e999", True, [1], None])
def test_set_points_must_be_finite_numbers(served, value):
    panel, url = served
    assert _post(url + "/login", {"user": "engineer"})[0] == 200
    sig = next(s["name"] for s in panel.state()["signals"]
               if s["kind"] == "panel" and s["type"] != "bool")
    assert _post(url + "/set", {"signal": sig, "value": 0.5}) == (200, {"ok": True})
    body = json.dumps({"signal": sig, "value": value}) if value != 1e400 else \
        '{"signal": "' + sig + '", "value": 1e400}'
    req = urllib.request.Request(url + "/set", body.encode(), {
        "Content-Type": "application/json", "X-Plclab-Token": _token(url)})
    with pytest.raises(urllib.error.HTTPError) as e:
        urllib.request.urlopen(req, timeout=5)
    assert e.value.code == 400


def test_hostile_bodies_get_an_answer_and_hold_nothing(served):
    panel, url = served
    port = url.rsplit(":", 1)[1]
    token = _token(url)

    def post(body: bytes, length: str) -> bytes:
        return _raw(url, (f"POST /set HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                          f"X-Plclab-Token: {token}\r\nContent-Length: {length}\r\n"
                          "Connection: close\r\n\r\n").encode() + body)

    assert post(b"", "-1").startswith(b"HTTP/1.0 400")
    assert post(b"x" * 100, "99999999").startswith(b"HTTP/1.0 413")
    digits = b'{"signal": "X", "value": ' + b"9" * 400 + b"}"
    assert post(digits, str(len(digits))).startswith(b"HTTP/1.0 400")
    deep = b"[" * 4900 + b"]" * 4900
    assert post(deep, str(len(deep))).startswith(b"HTTP/1.0 400")
    # a body shorter than announced: the connection is dropped after the timeout
    t0 = time.monotonic()
    post(b"{", "50")
    assert time.monotonic() - t0 < 60
    with urllib.request.urlopen(url + "/state", timeout=5) as r:  # still serving
        assert r.status == 200


@pytest.mark.parametrize("length", ["\xb2", "\uff15", "9" * 5000, "+5", "5 5", "0x10"])
def test_odd_content_lengths_get_an_answer(served, length):
    """Digits Python's int() reads but HTTP does not (a superscript two, a full-width five),
    more digits than int() converts: a 400 or 413, never a dead handler."""
    panel, url = served
    port = url.rsplit(":", 1)[1]
    head = (f"POST /login HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
            f"X-Plclab-Token: {_token(url)}\r\nContent-Length: ").encode()
    got = _raw(url, head + length.encode("latin-1", "replace") + b"\r\n\r\n", timeout=10)
    assert got.startswith((b"HTTP/1.0 400", b"HTTP/1.0 413")), got[:40]
    assert panel.user == "viewer"


def _held_open(url: str, drip: bytes, rounds: int = 100) -> bool:
    """Send ``drip`` every 0.1 s after a request line; False once the panel hangs up."""
    port = int(url.rsplit(":", 1)[1])
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
        s.sendall(f"POST /set HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n".encode())
        for _ in range(rounds):
            time.sleep(0.1)
            try:
                s.sendall(drip)
            except OSError:
                return False
        return True


def test_a_trickled_request_loses_its_connection(served, monkeypatch):
    """A per-read socket timeout does not bound a client sending a byte now and then: the
    whole request has REQUEST_TIMEOUT seconds, then the panel hangs up."""
    from plclab.scada import panel as panel_mod

    monkeypatch.setattr(panel_mod, "REQUEST_TIMEOUT", 0.5)
    _, url = served
    assert _held_open(url, b"X-Slow: 1\r\n") is False  # the header, one line at a time
    port = int(url.rsplit(":", 1)[1])
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:  # the body
        s.sendall(f"POST /set HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Plclab-Token: "
                  f"{_token(url)}\r\nContent-Length: 9000\r\n\r\n".encode())
        closed = False
        for _ in range(100):
            time.sleep(0.1)
            try:
                s.sendall(b" ")
            except OSError:
                closed = True
                break
        assert closed
    with urllib.request.urlopen(url + "/state", timeout=5) as r:  # still serving
        assert r.status == 200


def test_connections_beyond_the_limit_are_closed(served, monkeypatch):
    from plclab.scada import panel as panel_mod

    _, url = served
    port = int(url.rsplit(":", 1)[1])
    idle = []
    try:
        for _ in range(panel_mod.MAX_CONNECTIONS):
            idle.append(socket.create_connection(("127.0.0.1", port), timeout=5))
        got = b"x"
        for _ in range(50):  # until the server has taken every idle connection
            got = _raw(url, f"GET /state HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                            "Connection: close\r\n\r\n".encode(), timeout=5)
            if got == b"":
                break
            time.sleep(0.1)
        assert got == b""
    finally:
        for s in idle:
            s.close()
    for _ in range(50):  # the slots come back when the clients hang up
        got = _raw(url, f"GET /state HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                        "Connection: close\r\n\r\n".encode(), timeout=5)
        if got.startswith(b"HTTP/1.0 200"):
            break
        time.sleep(0.1)
    assert got.startswith(b"HTTP/1.0 200")


@pytest.mark.parametrize("path", ["/login", "/press", "/set", "/ack", "/recipe"])
@pytest.mark.parametrize("value", [[1], {"a": 1}, 5, None, True, "\ud800", "x" * 5000])
def test_every_action_answers_any_json_shape(served, path, value):
    """A list, an object, a number or a lone surrogate where a name is expected: a 4xx
    answer with a message (an /ack with a list once killed the handler)."""
    panel, url = served
    assert _post(url + "/login", {"user": "engineer"})[0] == 200
    field = {"/login": "user", "/press": "signal", "/set": "signal", "/ack": "id",
             "/recipe": "record"}[path]
    status, data = _post(url + path, {field: value, "value": value})
    if path == "/ack" and value is None:
        assert status == 200  # no id: every pending alarm
    else:
        assert 400 <= status < 500 and data["error"], (status, data)
