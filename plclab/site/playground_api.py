"""The playground's Python side: it runs in the browser under Pyodide (and in CPython for tests).

It imports only the standard library, the PLC core and the pure-Python plants ``tank`` and
``motor`` (the same classes the simulator uses, so the page follows the same simulation rules).
Every function returns plain data (dicts, lists, numbers) that the page turns into JavaScript
objects; a user's mistake is returned as diagnostics, never raised.

>>> s = Session(TANK_EXAMPLE, "st", "tank")
>>> s.ok, s.mapped["PUMP"]
(True, '%QX0.0')
>>> rows = s.advance(60.0)
>>> any(r["PUMP"] for r in rows) and not all(r["PUMP"] for r in rows)
True
"""

from __future__ import annotations

from typing import Any

from plclab.errors import Diagnostic, PlcError

LANGUAGE_SUFFIX = {"st": ".st", "il": ".il", "ld": ".ld"}

# The boolean rows of the default wirings (plclab/sim/wirings/tank.toml and motor.toml): the
# playground wires the PLC's addresses to the plant's signals directly (no input filter, no relay
# delay), or by name when the program declares a variable called like the signal.
WIRING: dict[str, list[tuple[str, str, str]]] = {
    "tank": [("%IX0.0", "LS1", "in"), ("%IX0.1", "LS2", "in"), ("%QX0.0", "PUMP", "out")],
    "motor": [("%IX0.0", "START", "in"), ("%IX0.1", "STOP", "in"), ("%IX0.2", "OL_RESET", "in"),
              ("%IX0.3", "RUN", "in"), ("%IX0.4", "OVERLOAD", "in"), ("%QX0.0", "K1", "out")],
}
# What the timing diagram draws for each plant (plant signals; analog ones are scaled).
DIAGRAM: dict[str, list[str]] = {
    "tank": ["LEVEL", "LS1", "LS2", "PUMP"],
    "motor": ["START", "STOP", "K1", "RUN", "OVERLOAD", "SPEED"],
}
# The plants' parameters in the playground: a tank of 0.1 m2 (half the first lab's, so the pump
# stops within the first minute) and the motor with its defaults.
PLANT_PARAMS: dict[str, dict[str, Any]] = {"tank": {"area": 0.1}, "motor": {}}
NO_PLANT = "none"
"""The plant choice of a program that drives no plant: it runs alone, seen in the watch panel."""
WATCH_LIMIT = 200
"""At most this many variables in the watch panel (a program with more shows the first ones)."""
VALUE_WIDTH = 120
"""A value longer than this (a big array) is cut, with an ellipsis."""

TANK_EXAMPLE = """\
(* Two-position level control: the pump starts below LS1 and runs until LS2. *)
PROGRAM TankLevel
VAR
    LS1  AT %IX0.0 : BOOL;   (* low level switch: TRUE at or above it *)
    LS2  AT %IX0.1 : BOOL;   (* high level switch *)
    PUMP AT %QX0.0 : BOOL;   (* pump contactor *)
END_VAR
PUMP := ((NOT LS1) OR PUMP) AND (NOT LS2);
END_PROGRAM
"""


def make_plant(name: str, params: dict[str, Any] | None = None) -> Any:
    """A fresh ``tank`` or ``motor`` plant with ``params`` (default: the playground's)."""
    kw = PLANT_PARAMS.get(name, {}) if params is None else params
    if name == "tank":
        from plants.tank import Tank

        return Tank(**kw)
    if name == "motor":
        from plants.motor import Motor

        return Motor(**kw)
    raise PlcError("PLC3044", f"the playground has no plant {name!r}; choose tank or motor")


def set_language(lang: str) -> None:
    """The page's language (``en``, ``ru``): plclab's messages in the worker speak it (the
    worker calls this once, from the ``lang`` of the page; ADR 0071)."""
    from plclab.i18n import set_language as choose

    choose(lang)


def diagnostic_dict(d: Diagnostic) -> dict[str, Any]:
    """A diagnostic as the page shows it: code, message (in the page's language: the
    problem catalogue's), severity, line and column."""
    from plclab.i18n import message

    loc = d.location
    return {"code": d.code, "message": message(d.code, d.message), "severity": d.severity,
            "line": loc.line if loc else 0, "col": loc.col if loc else 0}


def check(text: str, language: str = "st") -> list[dict[str, Any]]:
    """Every diagnostic of a program (errors first), as dicts."""
    from plclab.project import check_sources

    filename = "playground" + LANGUAGE_SUFFIX.get(language, ".st")
    _, diags = check_sources([(text, filename)])
    return [diagnostic_dict(d) for d in diags]


def _error_dicts(e: PlcError) -> list[dict[str, Any]]:
    diags = list(getattr(e, "diagnostics", None) or [])
    if not diags:
        diags = [Diagnostic(e.code, e.message, e.location)]
    return [diagnostic_dict(d) for d in diags]


class Session:
    """A compiled program wired to a plant, advanced in virtual time by the page.

    ``ok`` is False when the program does not compile; ``diagnostics`` then says why.
    ``mapped`` tells which PLC variable or address each plant signal is wired to.
    """

    def __init__(self, text: str, language: str = "st", plant: str = "tank",
                 scan_ms: float = 20.0) -> None:
        from plclab.project import loads

        self.plant_name = plant
        self.scan_s = scan_ms / 1000.0
        self.diagnostics: list[dict[str, Any]] = []
        self.mapped: dict[str, str] = {}
        self.trend: list[str] = []
        self.rows: list[tuple[str, str, str]] = []
        self.plant = make_plant(plant) if plant != NO_PLANT else None
        self.plc: Any = None
        self.time = 0.0
        self.scans = 0
        self._owed = 0.0  # scans asked for and not yet run (advance's slices)
        self.forced: dict[str, Any] = {}
        try:
            self.plc = loads(text, "playground" + LANGUAGE_SUFFIX.get(language, ".st"),
                             cycle_time=f"{scan_ms:g}ms")
        except PlcError as e:
            self.diagnostics = _error_dicts(e)
            return
        self.diagnostics = [diagnostic_dict(d) for d in
                            getattr(self.plc, "diagnostics", None) or []]
        if self.plant is None:
            return
        for address, signal, direction in WIRING[plant]:
            path = address  # the process image always exists; a variable AT it reads it
            try:
                if self.plc.var(signal).address is None:
                    path = signal  # an unlocated variable called like the signal
            except PlcError:
                pass
            self.mapped[signal] = path
            self.rows.append((path, signal, direction))
        used = self._outputs_used(text)
        if not used:
            outs = ", ".join(f"{s} ({a})" for a, s, d in WIRING[plant] if d == "out")
            self.diagnostics.append(diagnostic_dict(Diagnostic(
                "PLC3044", f"no variable drives the {plant}'s outputs: declare {outs} "
                "(by name or AT its address)", None, "warning")))

    def _outputs_used(self, text: str) -> bool:
        """Does the program write one of the plant's outputs (by its address or its name)?"""
        upper = text.upper()
        return any(d == "out" and (p.upper() in upper) for p, _, d in self.rows)

    @property
    def ok(self) -> bool:
        return self.plc is not None

    def set_input(self, signal: str, value: Any) -> None:
        """Hold a plant signal at a value (a push button pressed from the page), until
        :meth:`release`."""
        self.forced[signal] = value

    def release(self, signal: str) -> None:
        self.forced.pop(signal, None)

    def sample(self) -> dict[str, Any]:
        """The diagram's signals now (BOOLs as bools, analog values as floats), with ``t``."""
        row: dict[str, Any] = {"t": round(self.time, 6)}
        for name in DIAGRAM.get(self.plant_name, []):
            v = self.plant.read(name)
            row[name] = v if isinstance(v, bool) else float(v)
        for path in self.trend:
            if self.plc is not None:
                v = self.plc[path]
                row[path] = v if isinstance(v, bool) else float(v)
        return row

    def scan_once(self) -> None:
        """One scan: plant signals into the inputs, the program, outputs into the plant,
        then the plant moves on by one scan time."""
        if self.plant is None:
            self.plc.scan()
            self.time += self.scan_s
            self.scans += 1
            return
        for signal, value in self.forced.items():
            self.plant.write(signal, value)
        for path, signal, direction in self.rows:
            if direction == "in":
                self.plc[path] = bool(self.plant.read(signal))
        self.plc.scan()
        for path, signal, direction in self.rows:
            if direction == "out":
                self.plant.write(signal, bool(self.plc[path]))
        self.plant.step(self.scan_s)
        self.time += self.scan_s
        self.scans += 1

    def advance(self, seconds: float, every: float | None = None) -> list[dict[str, Any]]:
        """Run scans for ``seconds`` of virtual time; return a sample each ``every`` s
        (default: each scan), on the session's own clock: a run advanced in slices (the page's
        worker) samples at the same moments as one call. Slices of any length, which the
        worker sizes by the wall clock, add up to the same number of scans as one call: the
        part of a scan a slice leaves over is carried to the next, so the machine's speed never
        changes a run. A run-time fault stops the session and becomes a diagnostic."""
        if self.plc is None:
            return []
        wanted = seconds / self.scan_s + self._owed
        n = max(0, round(wanted))
        self._owed = wanted - n
        return self._scans(n, every)

    def step(self) -> None:
        """Exactly one scan (the page's Step), whatever part of a scan a run left over."""
        if self.plc is not None:
            self._scans(1, None)

    def _scans(self, n: int, every: float | None) -> list[dict[str, Any]]:
        """``n`` scans, sampled each ``every`` s of the session's clock (default: each scan);
        a run-time fault stops the session and becomes a diagnostic."""
        out: list[dict[str, Any]] = []
        step = max(1, round((every or self.scan_s) / self.scan_s))
        for _ in range(n):
            try:
                self.scan_once()
            except PlcError as e:
                self.diagnostics += _error_dicts(e)
                self.plc = None
                break
            if self.scans % step == 0:
                out.append(self.sample())
        return out


    # -- the watch panel ----------------------------------------------------------------------
    def watch(self) -> list[dict[str, Any]]:
        """Every variable of the program (at most WATCH_LIMIT) with its type, its value as an
        IEC literal, whether it is forced, and whether the trend can draw it (BOOL or number)."""
        if self.plc is None:
            return []
        from plclab.lang import types as T

        out = []
        for path in self.plc.variables()[:WATCH_LIMIT]:
            try:
                v = self.plc.var(path)
                text = self.plc.format(path)
            except PlcError:
                continue
            ty = T.resolve(v.type)
            if len(text) > VALUE_WIDTH:
                text = text[:VALUE_WIDTH - 1] + "\u2026"
            out.append({"path": path, "type": str(ty), "value": text,
                        "forced": path.upper() in self.plc.forced,
                        "trendable": getattr(ty, "kind", "") in ("bool", "int", "real", "bits")})
        return out

    def _value(self, path: str, text: str) -> Any:
        from plclab.runtime.literals import parse_literal

        return parse_literal(text, self.plc.var(path).type, path)

    def write(self, path: str, text: str) -> list[dict[str, Any]]:
        """Write an IEC literal to a variable now (the watch panel shows it at once) and again
        once at the start of the next scan, after the inputs are read (modify: so a plant
        input keeps it for that scan); returns the diagnostics of a bad value (none when it
        was accepted)."""
        def act() -> None:
            value = self._value(path, text)
            self.plc[path] = value
            self.plc.modify(path, value)
        return self._guarded(act)

    def force(self, path: str, text: str) -> list[dict[str, Any]]:
        """Force a variable to an IEC literal every scan, until :meth:`unforce`."""
        return self._guarded(lambda: self.plc.force(path, self._value(path, text)))

    def unforce(self, path: str) -> None:
        if self.plc is not None:
            self.plc.unforce(path)

    def set_trend(self, paths: list[str]) -> None:
        """The variables the timing diagram draws besides the plant's signals."""
        self.trend = [str(p) for p in paths][:8]

    def _guarded(self, act: Any) -> list[dict[str, Any]]:
        if self.plc is None:
            return []
        try:
            act()
        except PlcError as e:
            return _error_dicts(e)
        return []


def analyse(text: str, language: str = "st") -> dict[str, Any]:
    """What a program needs to be shown: the plant its variables fit (``tank`` or ``motor``
    by the signals' names, ``tank`` for a program that only writes ``%QX0.0``; ``none`` when it
    drives neither) and how many TEST blocks it has.

    >>> analyse(TANK_EXAMPLE)
    {'plant': 'tank', 'tests': 0, 'ok': True}
    >>> analyse("PROGRAM P VAR x : INT; END_VAR x := x + 1; END_PROGRAM")["plant"]
    'none'
    """
    from plclab.project import loads

    try:
        plc = loads(text, "playground" + LANGUAGE_SUFFIX.get(language, ".st"))
    except PlcError:
        return {"plant": NO_PLANT, "tests": text.upper().count("END_TEST"), "ok": False}
    names: set[str] = set()
    addresses: set[str] = set()
    for path in plc.variables():
        names.add(path.rsplit(".", 1)[-1].upper())
        try:
            address = plc.var(path).address
        except PlcError:
            continue
        if address:
            addresses.add(address.upper())
    tests = len(getattr(plc.compiled, "tests", []) or [])
    score = {plant: sum(sig in names for _, sig, _ in rows) for plant, rows in WIRING.items()}
    best = max(score, key=lambda k: score[k])
    if score[best] == 0:
        best = "tank" if "%QX0.0" in addresses else NO_PLANT
    return {"plant": best, "tests": tests, "ok": True}


def run_tests(text: str, language: str = "st") -> dict[str, Any]:
    """The TEST blocks of a program, run as ``plclab test -v`` runs them: one line a test and
    the summary line ``N passed, M failed``; a program that does not compile gives its
    diagnostics instead."""
    from plclab.project import compile_sources
    from plclab.testing import run_compiled_tests

    filename = "playground" + LANGUAGE_SUFFIX.get(language, ".st")
    try:
        compiled = compile_sources([(text, filename)])
    except PlcError as e:
        return {"lines": [], "summary": "", "passed": 0, "failed": 0,
                "diagnostics": _error_dicts(e)}
    results = run_compiled_tests(compiled)
    passed = sum(r.passed for r in results)
    lines = [str(r) for r in results] or ["no TEST blocks found"]
    return {"lines": lines, "summary": f"{passed} passed, {len(results) - passed} failed",
            "passed": passed, "failed": len(results) - passed,
            "diagnostics": [diagnostic_dict(d) for d in getattr(compiled, "diagnostics", [])]}


def session(text: str, language: str, plant: str, scan_ms: float = 20.0) -> Session:
    """The page's entry point (keyword-free, easy to call from JavaScript)."""
    return Session(text, language, plant, scan_ms)
