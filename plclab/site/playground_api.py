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

# The boolean rows of the labs' wirings (labs/wiring/tank.toml, labs/wiring/motor.toml): the
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


def diagnostic_dict(d: Diagnostic) -> dict[str, Any]:
    """A diagnostic as the page shows it: code, message, severity, line and column."""
    loc = d.location
    return {"code": d.code, "message": d.message, "severity": d.severity,
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
        self.plant = make_plant(plant)
        self.plc: Any = None
        self.time = 0.0
        self.scans = 0
        self.forced: dict[str, Any] = {}
        try:
            self.plc = loads(text, "playground" + LANGUAGE_SUFFIX.get(language, ".st"),
                             cycle_time=f"{scan_ms:g}ms")
        except PlcError as e:
            self.diagnostics = _error_dicts(e)
            return
        self.diagnostics = [diagnostic_dict(d) for d in
                            getattr(self.plc, "diagnostics", None) or []]
        self.rows: list[tuple[str, str, str]] = []
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
        for name in DIAGRAM[self.plant_name]:
            v = self.plant.read(name)
            row[name] = v if isinstance(v, bool) else float(v)
        return row

    def scan_once(self) -> None:
        """One scan: plant signals into the inputs, the program, outputs into the plant,
        then the plant moves on by one scan time."""
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
        (default: each scan). A run-time fault stops the session and becomes a diagnostic."""
        if self.plc is None:
            return []
        out: list[dict[str, Any]] = []
        n = max(1, round(seconds / self.scan_s))
        step = max(1, round((every or self.scan_s) / self.scan_s))
        for i in range(n):
            try:
                self.scan_once()
            except PlcError as e:
                self.diagnostics += _error_dicts(e)
                self.plc = None
                break
            if (i + 1) % step == 0:
                out.append(self.sample())
        return out


def session(text: str, language: str, plant: str, scan_ms: float = 20.0) -> Session:
    """The page's entry point (keyword-free, easy to call from JavaScript)."""
    return Session(text, language, plant, scan_ms)
