"""Scenarios: scripted operator actions and faults at given times, and when to stop.

An action happens at the first scan at or after its time ``at`` (seconds from the start of the
simulation), before the inputs of that scan are read. Actions with the same time happen in the
order they are written.

=============  ===============================================  ===============================
verb           what happens                                      more keys
=============  ===============================================  ===============================
press          a push button is pressed, then released           ``for`` (default 200 ms)
set            a panel input (button, switch, valve, the         ``value``
               environment) or an unwired actuator takes a value
ramp           a REAL panel input moves linearly to a value      ``to``, ``over``
var            a PLC variable is written (``SP := 55.0``)        ``value``
force/unforce  a PLC variable or address is forced / released    ``value`` (force)
fault/clear    a plant fault is injected / cleared               ``params`` (table), ``for``
io_fault       an I/O module fault (wire_break, stuck_1,          ``plc`` (the wiring row), ``value``
               welded...) / ``io_clear`` clears it
=============  ===============================================  ===============================

``press`` works for normally closed buttons too: pressing ``STOP`` (NC, TRUE at rest) makes it
FALSE for the time given. In TOML::

    description = "start the pump station, fail fan 2 after a minute"
    duration = "10min"          # or: until = "LEVEL > 1.9" (stops earlier when it holds)

    [[action]]
    at = "1s"
    press = "START"
    for = "200ms"

    [[action]]
    at = "60s"
    fault = "fan2_fail"

    [[action]]
    at = "300s"
    set = "VALVE"
    value = 30

    [[action]]
    at = "300s"
    var = "Main.SP"
    value = 55.0

A scenario file may also name the ``plant`` (checked), ``plant_params`` (a table),
``wiring`` (a path relative to the scenario file), ``scan``, ``dt``, ``seed`` and ``watch``.
The same in Python::

    sc = (Scenario(duration="10min")
          .press("START", at="1s", hold="200ms")
          .fault("fan2_fail", at="60s")
          .set("VALVE", 30, at="300s")
          .var("Main.SP", 55.0, at="300s"))

``until`` is a condition (see :mod:`plclab.trace.expr`) or a Python callable taking the
:class:`~plclab.sim.Simulation`; the run stops after the first scan at which it holds.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from plclab.errors import Diagnostic, Location, PlcError

from ._toml import read_toml, row_reporter, row_spans
from .durations import format_duration, parse_ns
from .errors import did_you_mean, raise_all, sim_error

VERBS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    # verb: (required keys, optional keys) besides at, description
    "press": ((), ("for", "duration")),
    "set": (("value",), ()),
    "ramp": (("to", "over"), ()),
    "var": (("value",), ()),
    "force": (("value",), ()),
    "unforce": ((), ()),
    "fault": ((), ("params", "for", "duration")),
    "clear": ((), ()),
    "io_fault": (("plc",), ("value",)),
    "io_clear": ((), ()),
}
"""Scenario verbs with their required and optional keys."""

TOP_KEYS = ("description", "plant", "plant_params", "wiring", "duration", "until", "scan", "dt",
            "seed", "watch", "action")


@dataclass
class Action:
    """One scripted action (see the module docstring for the verbs).

    ``target`` is the signal, PLC variable, fault name or (for ``io_fault``) the fault name;
    ``plc`` is the wiring row of an ``io_fault``; ``hold_ns`` is ``for``/``over``.
    """

    at_ns: int
    verb: str
    target: str
    value: Any = None
    hold_ns: int | None = None
    params: dict[str, Any] = field(default_factory=dict)
    plc: str | None = None
    description: str = ""
    location: Location | None = None
    index: int = 0

    @property
    def at(self) -> float:
        """Time in seconds."""
        return self.at_ns / 1e9

    def text(self) -> str:
        """What the action does, in words."""
        v = self.verb
        if self.description:
            return self.description
        if v == "press":
            return f"press {self.target} for {format_duration((self.hold_ns or 0) / 1e9)}"
        if v in ("set", "var", "force"):
            return f"{v} {self.target} := {_lit(self.value)}"
        if v == "ramp":
            return (f"ramp {self.target} to {_lit(self.value)} over "
                    f"{format_duration((self.hold_ns or 0) / 1e9)}")
        if v == "fault":
            p = ", ".join(f"{k}={_lit(x)}" for k, x in self.params.items())
            return f"fault {self.target}" + (f" ({p})" if p else "")
        if v == "io_fault":
            return f"I/O fault {self.target} on {self.plc}"
        return f"{v} {self.target}"


def _lit(v: Any) -> str:
    if isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    return str(v)


class Scenario:
    """Actions at times, a duration and an optional stop condition (see the module docstring).

    Parameters
    ----------
    actions : iterable of Action or dict, optional
        Dicts use the TOML keys (``{"at": "1s", "press": "START", "for": "200ms"}``).
    duration : duration, optional
        How long :meth:`Simulation.run` runs when not told otherwise.
    until : str or callable, optional
        Stop after the first scan at which this holds.
    description : str
    plant, plant_params, wiring, scan, dt, seed, watch : optional
        Settings used by :func:`plclab.sim.run` and ``plclab sim`` unless given there.
    """

    def __init__(self, actions: Iterable[Action | Mapping[str, Any]] = (),
                 duration: Any = None, until: str | Callable[[Any], bool] | None = None,
                 description: str = "", plant: str | None = None,
                 plant_params: Mapping[str, Any] | None = None, wiring: Any = None,
                 scan: Any = None, dt: Any = None, seed: int | None = None,
                 watch: Iterable[str] | None = None, source: str | None = None) -> None:
        self.actions: list[Action] = []
        self.duration_ns = None if duration is None else parse_ns(duration, "duration",
                                                                  allow_zero=False)
        self.until = until
        if isinstance(until, str):
            from plclab.trace.expr import parse_condition

            parse_condition(until)
        elif until is not None and not callable(until):
            raise sim_error("PLC4013", f"until must be a condition such as 'LEVEL > 1.9' or a "
                            f"function of the simulation, not {until!r}", source)
        self.description = description
        self.plant = plant
        self.plant_params = dict(plant_params or {})
        self.wiring = wiring
        self.scan = scan
        self.dt = dt
        self.seed = seed
        self.watch = list(watch or [])
        self.source = source
        diags: list[Diagnostic] = []
        for i, a in enumerate(actions):
            act = a if isinstance(a, Action) else _action_from(a, i, source, None, None, diags)
            if act is not None:
                self.actions.append(act)
        raise_all(diags)

    @property
    def duration(self) -> float | None:
        """The duration in seconds (None when not set)."""
        return None if self.duration_ns is None else self.duration_ns / 1e9

    def __repr__(self) -> str:
        src = f" from {self.source}" if self.source else ""
        return f"<Scenario {len(self.actions)} actions{src}>"

    # ------------------------------------------------------------------ Python API
    def _add(self, verb: str, target: str, at: Any, **kw: Any) -> Scenario:
        data = {"at": at, verb: target}
        data.update({k: v for k, v in kw.items() if v is not None})
        diags: list[Diagnostic] = []
        act = _action_from(data, len(self.actions), None, None, None, diags)
        raise_all(diags)
        assert act is not None
        self.actions.append(act)
        return self

    def press(self, signal: str, at: Any, hold: Any = "200ms", description: str = ""
              ) -> Scenario:
        """Press a push button at ``at`` for ``hold`` (NC buttons read FALSE while pressed)."""
        return self._add("press", signal, at, **{"for": hold, "description": description or None})

    def set(self, signal: str, value: Any, at: Any, description: str = "") -> Scenario:
        """Set a panel input (or an actuator no wiring row drives) to ``value``."""
        return self._add("set", signal, at, value=value, description=description or None)

    def ramp(self, signal: str, to: float, at: Any, over: Any, description: str = ""
             ) -> Scenario:
        """Move a REAL panel input linearly from its present value to ``to`` over ``over``."""
        return self._add("ramp", signal, at, to=to, over=over, description=description or None)

    def var(self, path: str, value: Any, at: Any, description: str = "") -> Scenario:
        """Write a PLC variable (``value`` may be an IEC literal string such as ``'T#5s'``)."""
        return self._add("var", path, at, value=value, description=description or None)

    def force(self, path: str, value: Any, at: Any) -> Scenario:
        """Force a PLC variable or address (it keeps ``value`` whatever the program does)."""
        return self._add("force", path, at, value=value)

    def unforce(self, path: str, at: Any) -> Scenario:
        """Release a forced variable or address."""
        return self._add("unforce", path, at)

    def fault(self, name: str, at: Any, hold: Any = None, **params: Any) -> Scenario:
        """Inject a plant fault at ``at`` (cleared again after ``hold`` when given)."""
        return self._add("fault", name, at, params=params or None, **{"for": hold})

    def clear(self, name: str, at: Any) -> Scenario:
        """Clear a plant fault."""
        return self._add("clear", name, at)

    def io_fault(self, plc: str, fault: str, at: Any, value: float | None = None) -> Scenario:
        """Inject an I/O module fault on the wiring row of ``plc`` (address, variable or
        signal): di ``open``/``stuck_1``, do ``welded``/``open_coil``, ai ``wire_break``/
        ``short``/``stuck``, ao ``open``/``stuck``."""
        return self._add("io_fault", fault, at, plc=plc, value=value)

    def io_clear(self, plc: str, at: Any) -> Scenario:
        """Clear the I/O fault of a wiring row."""
        return self._add("io_clear", plc, at)

    def stop_when(self, until: str | Callable[[Any], bool]) -> Scenario:
        """Set the stop condition."""
        if isinstance(until, str):
            from plclab.trace.expr import parse_condition

            parse_condition(until)
        self.until = until
        return self

    # ------------------------------------------------------------------ files
    @classmethod
    def load(cls, path: str | os.PathLike) -> Scenario:
        """Read a TOML scenario file."""
        data, text, filename = read_toml(path, "scenario")
        return cls.from_data(data, filename, text)

    @classmethod
    def from_data(cls, data: Mapping[str, Any], filename: str | None = None,
                  text: str | None = None) -> Scenario:
        """Build from parsed TOML (see the module docstring for the keys)."""
        for k in data:
            if k not in TOP_KEYS:
                raise sim_error("PLC4010", f"unknown key '{k}' in the scenario file."
                                f"{did_you_mean(k, TOP_KEYS)} Keys: {', '.join(TOP_KEYS)}; "
                                "actions are [[action]] tables", filename)
        raw = data.get("action", [])
        if not isinstance(raw, list):
            raise sim_error("PLC4010", "'action' must be an array of tables ([[action]])",
                            filename)
        spans = row_spans(text, "action") if text is not None else []
        if len(spans) != len(raw):
            spans = []
        diags: list[Diagnostic] = []
        actions = []
        for i, a in enumerate(raw):
            act = _action_from(a, i, filename, text, spans[i] if spans else None, diags)
            if act is not None:
                actions.append(act)
        raise_all(diags)
        wiring = data.get("wiring")
        if isinstance(wiring, str) and filename and not os.path.isabs(wiring):
            wiring = os.path.join(os.path.dirname(os.path.abspath(filename)), wiring)
        pp = data.get("plant_params", {})
        if not isinstance(pp, Mapping):
            raise sim_error("PLC4010", "plant_params must be a table, e.g. plant_params = "
                            "{ area = 2.0 }", filename)
        watch = data.get("watch", [])
        if isinstance(watch, str):
            watch = [w.strip() for w in watch.split(",") if w.strip()]
        seed = data.get("seed")
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int)):
            raise sim_error("PLC4010", "seed must be a whole number", filename)
        for key in ("duration", "scan", "dt"):
            if key in data:
                try:
                    ns = parse_ns(data[key], key, allow_zero=False)
                    if key == "scan":
                        from plclab.runtime.plc import check_cycle_ns

                        check_cycle_ns(ns, "scan")
                except PlcError as e:
                    raise sim_error("PLC4012", e.message, filename,
                                    *(_top_line(text, key) if text else (0, 0))) from None
        until = data.get("until")
        if until is not None and not isinstance(until, str):
            raise sim_error("PLC4013", "until must be a condition string such as "
                            "\"LEVEL > 1.9\"", filename)
        if isinstance(until, str):
            from plclab.trace.expr import parse_condition

            try:
                parse_condition(until)
            except PlcError as e:
                raise sim_error("PLC4013", e.message, filename,
                                *(_top_line(text, "until") if text else (0, 0))) from None
        return cls(actions, data.get("duration"), until, str(data.get("description", "")),
                   data.get("plant"), pp, wiring, data.get("scan"), data.get("dt"), seed,
                   watch, filename)


def _top_line(text: str, key: str) -> tuple[int, int]:
    for i, ln in enumerate(text.splitlines(), 1):
        if ln.lstrip().startswith(key) and "=" in ln:
            return i, ln.index(key) + 1
    return 0, 0


def _action_from(raw: Any, index: int, file: str | None, text: str | None,
                 span: tuple[int, int] | None, diags: list[Diagnostic]) -> Action | None:
    loc, bad = row_reporter('action', index, file, text, span, diags)

    if not isinstance(raw, Mapping):
        bad("PLC4010", None, f"an action is a table such as {{ at = \"1s\", press = \"START\" }}, "
            f"not {raw!r}")
        return None
    verbs = [k for k in raw if k in VERBS]
    if len(verbs) != 1:
        if not verbs:
            others = [k for k in raw if k not in ("at", "description")]
            hint = did_you_mean(others[0], VERBS) if others else ""
            bad("PLC4010", None, f"no verb.{hint} An action needs exactly one of "
                f"{', '.join(VERBS)}")
        else:
            bad("PLC4010", verbs[1], f"two verbs ({verbs[0]} and {verbs[1]}); write one action "
                "per table")
        return None
    verb = verbs[0]
    required, optional = VERBS[verb]
    n0 = len(diags)
    if "at" not in raw:
        bad("PLC4010", None, "'at' is missing: when does it happen? e.g. at = \"1s\"")
    for k in required:
        if k not in raw:
            bad("PLC4010", None, f"'{verb}' needs '{k}'" + (
                " (the value to write)" if k == "value" else ""))
    allowed = set(required) | set(optional) | {"at", "description", verb}
    for k in raw:
        if k not in allowed:
            extra = ", ".join(sorted(set(required) | set(optional))) or "nothing else"
            bad("PLC4010", k, f"'{verb}' does not take '{k}'.{did_you_mean(k, allowed)} It takes: "
                f"{extra} (plus at, description)")
    if len(diags) > n0:
        return None
    target = raw[verb]
    if not isinstance(target, str) or not target.strip():
        bad("PLC4010", verb, f"{verb} names a signal, variable or fault: a non-empty string")
        return None
    try:
        at_ns = parse_ns(raw["at"], f"action {index}: at")
    except PlcError as e:
        bad("PLC4012", "at", e.message.split(": ", 1)[-1])
        return None
    hold = None
    for k in ("for", "duration", "over"):
        if k in raw:
            try:
                hold = parse_ns(raw[k], f"action {index}: {k}", allow_zero=(k != "over"))
            except PlcError as e:
                bad("PLC4012", k, e.message.split(": ", 1)[-1])
                return None
    if verb == "press" and hold is None:
        hold = 200_000_000
    value = raw.get("value", raw.get("to"))
    if verb in ("set", "var", "force", "ramp") and not isinstance(value, bool | int | float | str):
        bad("PLC4015", "value" if verb != "ramp" else "to", f"{value!r} is not a value; write a "
            "number, true/false or an IEC literal string such as \"T#5s\"")
        return None
    if verb == "ramp" and (isinstance(value, bool) or not isinstance(value, int | float)):
        bad("PLC4015", "to", f"ramp needs a number to go to, not {value!r}")
        return None
    params = raw.get("params", {})
    if not isinstance(params, Mapping):
        bad("PLC4010", "params", "params must be a table, e.g. params = { area = 2e-4 }")
        return None
    plc = raw.get("plc")
    if verb == "io_fault" and (not isinstance(plc, str) or not plc.strip()):
        bad("PLC4010", "plc", "io_fault needs plc = the wiring row's address, variable or "
            "signal, e.g. plc = \"%IW64\"")
        return None
    if verb == "io_fault" and "value" in raw and (isinstance(value, bool) or
                                                  not isinstance(value, int | float)):
        bad("PLC4015", "value", "the stuck value of an I/O fault is a number in engineering units")
        return None
    desc = raw.get("description", "")
    return Action(at_ns, verb, target.strip(), value, hold, dict(params),
                  plc.strip() if isinstance(plc, str) else None, str(desc), loc(), index)


def as_scenario(scenario: Any) -> Scenario:
    """Accept None, a Scenario, a path to a TOML file, a dict or a list of actions."""
    if scenario is None:
        return Scenario()
    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, str | os.PathLike):
        return Scenario.load(scenario)
    if isinstance(scenario, Mapping):
        return Scenario.from_data(scenario)
    return Scenario(scenario)


def load_scenario(path: str | os.PathLike) -> Scenario:
    """Read a TOML scenario file (same as :meth:`Scenario.load`)."""
    return Scenario.load(path)
