"""An operator panel in the browser: the plant's signals and alarms, buttons, acknowledgement.

:class:`Panel` runs a :class:`~plclab.sim.Simulation` paced to the wall clock (``speed`` times
real time) in a background thread and answers a small JSON API; :func:`serve` puts it behind
the standard library's HTTP server on the loopback interface, with one HTML page that polls
``/state`` and posts the operator's actions. The simulation is stepped and acted on under one
lock, so the browser never sees half a scan.

Users and rights are a teaching example of WinCC's user administration
(``001_c648febd3bbd6efb.txt``, lines 6300-6420), not security: anybody on this machine can
pick any user. A **viewer** only watches, an **operator** presses buttons and acknowledges
alarms, an **engineer** may also download recipe records. A refused action is PlcError
PLC6050.

API (JSON): ``GET /state``; ``POST /login {user}``, ``/press {signal}``, ``/set {signal,
value}``, ``/ack {id}`` (no id: every pending alarm), ``/recipe {record}``.
"""

from __future__ import annotations

import json
import math
import secrets
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

from plclab.errors import PlcError
from plclab.scada.http_limits import BoundedHTTPServer, DeadlineMixin

USERS: dict[str, frozenset[str]] = {
    "viewer": frozenset(),
    "operator": frozenset({"operate", "ack"}),
    "engineer": frozenset({"operate", "ack", "recipe"}),
}
"""The panel's users and their rights (a teaching example, not security)."""

RIGHT_TEXT = {"operate": "press buttons and set values", "ack": "acknowledge alarms",
              "recipe": "download recipe records"}
LOG_LINES = 30
PRESS_S = 0.3  # how long a pressed button stays pressed (virtual time)


class Panel:
    """The state and the actions of an operator panel around a running simulation.

    Parameters
    ----------
    sim : plclab.sim.Simulation
        A fresh simulation (the panel adds ``alarms`` as a hook).
    alarms : AlarmServer, optional
    recipe : Recipe, optional
    speed : float
        Virtual seconds per wall-clock second.
    """

    def __init__(self, sim: Any, alarms: Any = None, recipe: Any = None,
                 speed: float = 1.0) -> None:
        if not speed > 0:
            raise PlcError("PLC6050", f"speed={speed!r}: give a positive factor (1 = real time)")
        self.sim = sim
        self.alarms = sim.add_hook(alarms) if alarms is not None else None
        self.recipe = recipe
        self.active_record = ""
        self.speed = float(speed)
        self.user = "viewer"
        self.lock = threading.Lock()
        self._releases: list[tuple[float, str, bool]] = []
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self.message = ""

    # ------------------------------------------------------------------ running
    def start(self) -> None:
        """Run the simulation in a background thread, paced to the wall clock."""
        if self._thread is not None:
            return
        self._thread = threading.Thread(target=self._run, name="plclab-panel", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5)
            self._thread = None

    def _run(self) -> None:
        sim = self.sim
        wall0 = time.monotonic()
        t0 = sim.time
        while not self._stop.is_set():
            target = t0 + (time.monotonic() - wall0) * self.speed
            n = int((target - sim.time) / sim.scan)
            if n > 0:
                self.advance(min(n, 2000))
            self._stop.wait(0.02)

    def advance(self, scans: int) -> None:
        """Step the simulation (under the lock), releasing pressed buttons on time."""
        with self.lock:
            for _ in range(scans):
                due = [r for r in self._releases if r[0] <= self.sim.time + 1e-9]
                for r in due:
                    self.sim.plant.write(r[1], r[2])
                    self._releases.remove(r)
                self.sim.step(1)

    # ------------------------------------------------------------------ users
    def login(self, user: str) -> None:
        if user not in USERS:
            raise PlcError("PLC6050", f"no user {user!r}; the panel knows "
                           f"{', '.join(USERS)}")
        self.user = user

    def _need(self, right: str) -> None:
        if right not in USERS[self.user]:
            who = [u for u, r in USERS.items() if right in r]
            raise PlcError("PLC6050", f"user {self.user} may not {RIGHT_TEXT[right]}; log in as "
                           f"{' or '.join(who)}")

    # ------------------------------------------------------------------ actions
    def press(self, signal: str) -> None:
        """Press a panel push button for a moment (a normally closed one opens)."""
        self._need("operate")
        sig = self._panel_signal(signal, "bool")
        rest = bool(sig.default)
        with self.lock:
            self.sim.plant.write(sig.name, not rest)
            self._releases.append((self.sim.time + PRESS_S, sig.name, rest))

    def set(self, signal: str, value: Any) -> None:
        """Set a panel input (a switch or a REAL such as a valve opening)."""
        self._need("operate")
        sig = self._panel_signal(signal)
        with self.lock:
            try:
                if sig.type == "bool":
                    if not isinstance(value, bool):
                        raise TypeError
                    v: Any = value
                else:
                    if isinstance(value, bool) or not isinstance(value, int | float | str):
                        raise TypeError
                    v = float(value)
                    if not math.isfinite(v):
                        raise ValueError
            except (TypeError, ValueError, OverflowError):
                shown = repr(value)[:40]
                raise PlcError("PLC6051", f"{sig.name}: {shown} is not a value for it ("
                               f"{'TRUE or FALSE' if sig.type == 'bool' else 'a finite number'})"
                               ) from None
            self.sim.plant.write(sig.name, v)

    def acknowledge(self, alarm_id: str | None = None) -> bool:
        self._need("ack")
        if self.alarms is None:
            raise PlcError("PLC6050", "this panel has no alarms; start it with --alarms FILE")
        with self.lock:
            return self.alarms.acknowledge(alarm_id, t=self.sim.time, user=self.user)

    def load_recipe(self, record: str) -> None:
        self._need("recipe")
        if self.recipe is None:
            raise PlcError("PLC6050", "this panel has no recipe; start it with --recipe FILE")
        with self.lock:
            self.recipe.load_into(self.sim.plc, record)
            self.active_record = record

    def _panel_signal(self, name: str, type_: str | None = None) -> Any:
        sig = self.sim.plant.signals.get(name)
        if sig is None or sig.kind != "panel" or (type_ and sig.type != type_):
            buttons = [n for n, s in self.sim.plant.signals.items() if s.kind == "panel"]
            raise PlcError("PLC6050", f"{name!r} is not a panel input of "
                           f"'{self.sim.plant.name}' ({', '.join(buttons) or 'none'})")
        return sig

    # ------------------------------------------------------------------ state
    def state(self) -> dict[str, Any]:
        """What the page shows, as JSON-ready data."""
        with self.lock:
            sim = self.sim
            plant = sim.plant
            signals = []
            for name, s in plant.signals.items():
                v = plant.read(name)
                signals.append({"name": name, "kind": s.kind, "type": s.type, "unit": s.unit,
                                "value": bool(v) if s.type == "bool" else round(float(v), 4)})
            alarms, log = [], []
            if self.alarms is not None:
                classes = self.alarms.classes
                for a, st in self.alarms.pending():
                    alarms.append({"id": a.id, "text": a.text, "class": a.alarm_class,
                                   "state": st, "color": classes[a.alarm_class].color,
                                   "ack": classes[a.alarm_class].ack})
                for e in self.alarms.log[-LOG_LINES:]:
                    log.append({"t": round(e.time, 3), "id": e.id, "state": e.state,
                                "class": e.alarm_class, "text": e.text, "user": e.user})
            return {
                "t": round(sim.time, 3), "plant": plant.name,
                "title": getattr(plant, "title", plant.name), "plc": sim.plc.state,
                "signals": signals, "alarms": alarms, "log": log,
                "user": self.user, "users": list(USERS), "rights": sorted(USERS[self.user]),
                "records": list(self.recipe.records) if self.recipe is not None else [],
                "record": self.active_record, "message": self.message,
            }


# ---------------------------------------------------------------------- HTTP


def page() -> str:
    """The panel's HTML page."""
    from .panel_page import PAGE

    return PAGE


MAX_BODY = 10_000
"""Bytes a POST body may have (a panel action is a small JSON object)."""
MAX_NUMBER_DIGITS = 30
"""Digits a JSON number may have."""
REQUEST_TIMEOUT = 5.0
"""Seconds a connection may take to send its request (a short body does not hold a thread)."""
TOKEN_HEADER = "X-Plclab-Token"
MAX_CONNECTIONS = 32
"""Connections served at once; a further one is closed at once (no thread per attacker)."""


def _loads(body: bytes) -> dict[str, Any]:
    """The JSON object of a request body: ValueError for anything else, for NaN and
    infinities, numbers of more than MAX_NUMBER_DIGITS digits and nesting that deep."""
    def number(text: str) -> Any:
        if len(text) > MAX_NUMBER_DIGITS:
            raise ValueError("number too long")
        return float(text) if any(c in text for c in ".eE") else int(text)

    def constant(text: str) -> Any:
        raise ValueError(f"{text} is not a number here")

    try:
        data = json.loads(body or b"{}", parse_int=number, parse_float=number,
                          parse_constant=constant)
    except RecursionError:
        raise ValueError("nested too deeply") from None
    if not isinstance(data, dict):
        raise ValueError("not an object")
    return data


def make_server(panel: Panel, port: int = 8765, host: str = "127.0.0.1") -> ThreadingHTTPServer:
    """An HTTP server for ``panel`` on the loopback interface (``port=0``: any free port).

    It answers only requests addressed to this machine by name (the Host header: no DNS
    rebinding), takes actions only from its own page (a POST needs the page's secret token
    and, when the browser sends one, this server's Origin: no cross-site requests), bounds
    bodies and the time to send them, and refuses numbers that are not finite (ADR 0041)."""
    if host not in ("127.0.0.1", "localhost", "::1"):
        raise PlcError("PLC6050", f"the panel serves only this machine (127.0.0.1), not {host}")
    token = secrets.token_urlsafe(24)
    html = page().replace("__PLCLAB_TOKEN__", token).encode("utf-8")

    class Handler(DeadlineMixin, BaseHTTPRequestHandler):
        timeout = REQUEST_TIMEOUT  # each read; the whole request: request_deadline

        def request_deadline(self) -> float:
            return REQUEST_TIMEOUT

        def log_message(self, *args: Any) -> None:  # quiet: the terminal shows the alarms
            return

        def _send(self, code: int, body: bytes, kind: str) -> None:
            self.send_response(code)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.send_header("X-Content-Type-Options", "nosniff")
            self.send_header("X-Frame-Options", "DENY")
            self.end_headers()
            self.wfile.write(body)

        def _json(self, code: int, data: Any) -> None:
            self._send(code, json.dumps(data).encode("utf-8"), "application/json")

        def _ours(self) -> bool:
            """The request names this server (Host) and, if it says, comes from its page."""
            port_ = self.server.server_address[1]
            names = {f"{h}:{port_}" for h in ("127.0.0.1", "localhost", "[::1]")}
            if (self.headers.get("Host") or "").strip().lower() not in names:
                self._json(403, {"error": "this panel answers only http://127.0.0.1:"
                                 f"{port_}/ (Host header)"})
                return False
            origin = self.headers.get("Origin")
            if origin is not None and origin.strip().lower() not in {
                    f"http://{n}" for n in names}:
                self._json(403, {"error": "cross-site requests are refused (Origin)"})
                return False
            return True

        def do_GET(self) -> None:  # noqa: N802 - the http.server API
            if not self._ours():
                return
            if self.path in ("/", "/index.html"):
                self._send(200, html, "text/html; charset=utf-8")
            elif self.path == "/state":
                self._json(200, panel.state())
            else:
                self._json(404, {"error": f"no page {self.path}"})

        def do_POST(self) -> None:  # noqa: N802
            if not self._ours():
                return
            if not secrets.compare_digest(self.headers.get(TOKEN_HEADER) or "", token):
                self._json(403, {"error": "actions come only from the panel's own page "
                                 f"({TOKEN_HEADER} missing or wrong): reload the page"})
                return
            length = (self.headers.get("Content-Length") or "0").strip()
            digits = length.isascii() and length.isdigit()  # not '\xb2', not a full-width 5
            if not digits or len(length) > 9 or int(length) > MAX_BODY:
                self._json(413 if digits else 400,
                           {"error": f"a body of 0 to {MAX_BODY} bytes with its "
                            "Content-Length is expected"})
                self.close_connection = True
                return
            try:
                body = self.rfile.read(int(length))
                if len(body) < int(length):  # cut off at the deadline
                    raise OSError("short body")
                self.request_arrived()
                data = _loads(body)
            except (ValueError, UnicodeDecodeError):
                self._json(400, {"error": "send a JSON object of short, finite values"})
                return
            except OSError:  # the body did not arrive in time
                self.close_connection = True
                return
            actions = {
                "/login": lambda: panel.login(str(data.get("user", ""))),
                "/press": lambda: panel.press(str(data.get("signal", ""))),
                "/set": lambda: panel.set(str(data.get("signal", "")), data.get("value")),
                "/ack": lambda: panel.acknowledge(str(data["id"]) if data.get("id") else None),
                "/recipe": lambda: panel.load_recipe(str(data.get("record", ""))),
            }
            if self.path not in actions:
                self._json(404, {"error": f"no action {self.path}"})
                return
            try:
                actions[self.path]()
            except PlcError as e:
                panel.message = f"{e.code}: {e.message}"
                self._json(403 if e.code == "PLC6050" else 400,
                           {"error": e.message, "code": e.code})
                return
            except Exception as e:  # noqa: BLE001 - a bug of ours: an answer, not a dead thread
                self._json(500, {"error": f"the panel failed ({type(e).__name__}); please "
                                 "report it with the request that caused it"})
                return
            panel.message = ""
            self._json(200, {"ok": True})

    server = BoundedHTTPServer((host, port), Handler, max_connections=MAX_CONNECTIONS)
    return server


def serve(panel: Panel, port: int = 8765) -> None:
    """Serve the panel until Ctrl+C."""
    server = make_server(panel, port)
    panel.start()
    print(f"operator panel of '{panel.sim.plant.name}' on http://127.0.0.1:"
          f"{server.server_address[1]}/  (Ctrl+C stops)")
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
        panel.stop()
