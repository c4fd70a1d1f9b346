"""The Simulation: a PLC and a plant in lockstep on one virtual clock.

The clock is the PLC's: time ``t_k = k * scan`` (seconds since the simulation started) is the
time the PLC samples at the start of scan ``k``. Nothing reads the wall clock, except that the
duration of each ``plc.scan()`` call is measured and kept apart in the trace
(``trace.wall``).

One scan ``k`` (``Simulation.step``) does, in this order:

1. **scenario**: actions due at ``t <= t_k`` happen (buttons, set points, faults);
2. **inputs**: the plant's signals at ``t_k`` go through the input modules (bounce, filter, ADC)
   onto the PLC's input terminals (``plc.inputs``) or input variables;
3. **scan**: ``plc.scan()`` copies the terminals into the input image, runs the program with
   the clock at ``t_k`` and writes the output terminals (``plc.outputs``);
4. **record**: the trace row for ``t_k`` (plant signals at ``t_k``, the PLC side of every wired
   I/O, watched variables); the stop condition ``until`` is checked;
5. **plant**: the plant advances from ``t_k`` to ``t_{k+1}`` in ``substeps`` steps of ``dt``
   (``dt = min(scan, plant.max_dt)`` rounded down to a whole number of sub-steps per scan),
   with the actuators as the previous scan left them;
6. **outputs**: at ``t_{k+1}``, the end of the scan cycle, the outputs of scan ``k`` go
   through the output modules (transistor, relay delays, DAC) to the plant's actuators.

A real PLC writes its outputs at the end of the cycle, one scan after it read its inputs; step 6
models that. So a change in the plant during ``(t_{k-1}, t_k]`` is read at ``t_k`` and acts on
the plant from ``t_{k+1}``: **a reaction takes between 1 and 2 scans** (the textbook's rule),
plus the delays of the modules (input filter, relay). In the trace, row ``k`` shows the PLC's
decision (``%QX0.0``) in the same row as the input that caused it and the actuator (``PUMP``)
one row later.

Determinism: the plant is reset with ``seed``; every module's random generator is seeded from
``seed`` and the row (its own ``seed`` or its position); the same seed, program, wiring and
scenario give identical traces on every machine.
"""

from __future__ import annotations

import gc
import math
import time as _time
from collections.abc import Callable, Iterable
from typing import Any

from plclab.errors import PlcError, PlcRuntimeFault

from .channels import Transfer, bind
from .durations import format_duration, parse_ns
from .errors import did_you_mean, sim_error
from .scenario import IO_FAULTS, Action, Scenario, as_scenario
from .wiring import Wiring
from .wirings import as_wiring


def _gcd_all(values: Iterable[int]) -> int:
    g = 0
    for v in values:
        g = math.gcd(g, v)
    return g


def plc_tick_ns(plc: Any) -> int:
    """The PLC's base tick: the period of its cyclic task(s) (their gcd), ns."""
    return plc.tick_ns


def make_plant(plant: Any, params: dict[str, Any] | None = None) -> Any:
    """A plant from a registry name (with parameters) or a plant object as it is."""
    if isinstance(plant, str):
        from plants import PlantError, get_plant

        try:
            return get_plant(plant, **(params or {}))
        except PlantError as e:
            raise sim_error("PLC4020", str(e)) from None
        except TypeError as e:  # a parameter of the wrong type
            raise sim_error("PLC4020", f"plant {plant!r}: {e}") from None
    if params:
        raise sim_error("PLC4020", "plant_params only apply when the plant is given by name")
    if not hasattr(plant, "signals") or not hasattr(plant, "step"):
        raise sim_error("PLC4020", f"{plant!r} is not a plant; give a name such as 'tank' or a "
                        "plants.Plant object")
    return plant


class Simulation:
    """A PLC joined to a plant through a wiring table, run on the PLC's virtual clock.

    Parameters
    ----------
    plc : plclab.runtime.plc.Plc
        The PLC (``plclab.load(...)`` / ``plclab.loads(...)``). Its clock goes on from where
        it is; its cycle time must equal ``scan``.
    plant : str or plants.Plant
        A plant object or a registry name (``"tank"``; parameters in ``plant_params``). The
        plant is reset with ``seed``: inject faults through the scenario or after building
        the simulation.
    wiring : Wiring, list of rows, path or None
        None: the plant's default wiring (:func:`plclab.sim.default_wiring`).
    scan : duration, optional
        The scan time (``"10ms"``). Default: the PLC's cycle time. A different value is an
        error (load the PLC with ``cycle_time=...``).
    dt : duration, optional
        Plant sub-step; must divide the scan into a whole number of steps. Default
        ``min(scan, plant.max_dt)``, rounded down to divide the scan.
    seed : int, optional
        Seed of the plant and of the I/O modules (default: the scenario's, else 0).
    scenario : Scenario, path, dict or list of actions, optional
    watch : iterable of str
        PLC variables to record every scan (``"Main.M"``, ``"t1.ET"``).
    snapshot : bool, optional
        Also record the plant's ``snapshot()`` extras (can be expensive, e.g. 32 bottles),
        under their own keys (``volume``, ``bottle3.x``; ``snapshot:<key>`` when the name is
        taken). Default (None): only for plants whose picture needs them (the conveyor's
        bottles and counters, ``"bottle"`` in its geometry).
    decimate : int
        Record every n-th scan (events and edges are always complete).
    plant_params : dict, optional
        Parameters of a plant given by name.
    wall_clock : bool
        Measure the wall time of each PLC scan (kept apart from the deterministic data).
    stop_on_fault : bool
        When the program faults (division by zero, watchdog...), the PLC goes to STOP with its
        outputs off and, by default, the plant runs on (as it would) and the trace gets a
        ``plc_fault`` event; with True the run stops and the fault is raised.

    Examples
    --------
    >>> import plclab
    >>> from plclab.sim import Simulation
    >>> plc = plclab.loads('''PROGRAM Main
    ... VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
    ... M := ((NOT LS1) OR M) AND (NOT LS2);
    ... END_PROGRAM''')
    >>> sim = Simulation(plc, "tank")
    >>> tr = sim.run("10s")
    >>> bool(tr["PUMP"][-1]), tr.first_time("PUMP")
    (True, 0.02)
    """

    def __init__(self, plc: Any, plant: Any = "tank", wiring: Any = None, scan: Any = None,
                 dt: Any = None, seed: int | None = None, *, scenario: Any = None,
                 watch: Iterable[str] = (), snapshot: bool | None = None, decimate: int = 1,
                 plant_params: dict[str, Any] | None = None, wall_clock: bool = True,
                 stop_on_fault: bool = False) -> None:
        self.scenario: Scenario = as_scenario(scenario)
        sc = self.scenario
        if isinstance(plant, str) and sc.plant and plant != sc.plant:
            raise sim_error("PLC4008", f"the scenario is for the plant '{sc.plant}', but the "
                            f"simulation runs '{plant}'", sc.source)
        params = plant_params if plant_params is not None else (
            sc.plant_params if isinstance(plant, str) else None)
        self.plant = make_plant(plant, params)
        self.plant_params = dict(params or {})
        if sc.plant and sc.plant != self.plant.name:
            raise sim_error("PLC4008", f"the scenario is for the plant '{sc.plant}', but the "
                            f"simulation runs '{self.plant.name}'", sc.source)
        self.plc = plc
        if not hasattr(plc, "scan") or not hasattr(plc, "inputs"):
            raise sim_error("PLC4020", f"{plc!r} is not a PLC; build one with plclab.load(...) "
                            "or plclab.loads(...)")
        self.seed = int(seed if seed is not None else (sc.seed or 0))
        self.plant.reset(self.seed)
        # -- clock
        tick = plc_tick_ns(plc)
        scan = scan if scan is not None else sc.scan
        if scan is not None:
            want = parse_ns(scan, "scan", allow_zero=False)
            if want != tick:
                raise sim_error(
                    "PLC4020", f"the PLC scans every {format_duration(tick / 1e9)} (its cycle "
                    f"time), but the simulation was asked for {format_duration(want / 1e9)}; "
                    f"load the PLC with cycle_time='{format_duration(want / 1e9)}' or leave "
                    "scan out")
        self.scan_ns = tick
        self.scan = tick / 1e9
        dt = dt if dt is not None else sc.dt
        if dt is None:
            max_dt = float(getattr(self.plant, "max_dt", self.scan))
            n = max(1, math.ceil(self.scan / max_dt - 1e-9))
        else:
            dt_ns = parse_ns(dt, "dt", allow_zero=False)
            n = round(tick / dt_ns)
            if n < 1 or n * dt_ns != tick and abs(n * dt_ns - tick) > 1:
                divs = [d for d in (1, 2, 4, 5, 10, 20, 25, 50, 100) if tick % d == 0][:6]
                ok = ", ".join(format_duration(tick / d / 1e9) for d in divs)
                raise sim_error("PLC4020", f"dt={format_duration(dt_ns / 1e9)} does not divide "
                                f"the {format_duration(self.scan)} scan into whole sub-steps; "
                                f"use e.g. {ok}")
        self.substeps = n
        self.dt = self.scan / n
        self.t0_ns = plc.ctx.now_ns
        self.k = 0
        # -- wiring
        w = wiring if wiring is not None else sc.wiring
        self.wiring: Wiring = as_wiring(w, self.plant.name)
        self.transfer: Transfer = bind(self.wiring, self.plant, plc, self.seed)
        self.transfer.namespace["_E"] = self._relay_event  # type: ignore[attr-defined]
        self.warnings = list(self.transfer.warnings)
        # -- recording
        if isinstance(decimate, bool) or not isinstance(decimate, int) or decimate < 1:
            raise sim_error("PLC4020", f"decimate must be a whole number >= 1, not {decimate!r}")
        self.decimate = decimate
        if snapshot is None:  # the recording draws bottles: keep them in the Trace
            try:
                snapshot = "bottle" in (self.plant.geometry() or {})
            except Exception:  # noqa: BLE001 - a plant without a usable picture
                snapshot = False
        self.snapshot = bool(snapshot)
        self.wall_clock = bool(wall_clock)
        self.stop_on_fault = bool(stop_on_fault)
        self.events: list[Any] = []
        if isinstance(watch, str):
            from plclab.names import split_names

            watch = split_names(watch)
        watch = list(watch)
        watch += [x for x in sc.watch if x not in watch]
        from .sfc_lane import step_paths  # the SFC lane: every step flag (ADR 0023)

        self._sfc_steps = [x for x in step_paths(plc) if x not in watch]
        self._build_recorder(watch + self._sfc_steps)
        # -- scenario
        self._ops: list[tuple[int, int, Callable[[int], None]]] = []
        self._ramps: list[list[Any]] = []
        self._bind_scenario(sc)
        self._op_i = 0
        self._plc_state = plc.state
        self.stop_reason = ""
        self.wall_s = 0.0
        self.hooks: list[Any] = []
        self._fast: tuple[Any, Any] | None = None  # (key, the fused loop): built on first use

    def add_hook(self, hook: Any) -> Any:
        """Join an observer to every scan (e.g. :class:`plclab.scada.AlarmServer`, a watch
        table); returns it. The simulation does not import the observer's package: a hook
        has ``bind(sim)`` (called here, before the first scan: it may add recorder groups),
        ``after_scan(sim, t_ns, recorded)`` (after each PLC scan, before the plant moves;
        ``recorded``: this scan is a trace row) and ``finish(sim) -> (events, meta)`` (its
        events and a ``meta`` entry of the Trace). See ADR 0025."""
        if self.k:
            raise PlcError("PLC6060", "add hooks (alarms, watch tables) before the first scan "
                           "of the simulation, so that their records cover the whole run")
        hook.bind(self)
        self.hooks.append(hook)
        return hook

    # ------------------------------------------------------------------ set-up
    def _build_recorder(self, watch: list[str]) -> None:
        from plclab.trace.recorder import Recorder

        from .channels import type_kind

        rec = Recorder()
        sigs = self.plant.signals
        used = {n.upper() for n in sigs}
        names = list(self.plant.values())
        self._g_plant = rec.add("plant", names,
                                ["bool" if sigs[n].type == "bool" else "float" for n in names])

        def unique(name: str) -> str:
            cand = name if name.upper() not in used else f"plc:{name}"
            i = 2
            base = cand
            while cand.upper() in used:
                cand = f"{base}#{i}"
                i += 1
            used.add(cand.upper())
            return cand

        tr = self.transfer
        for ch in tr.channels:
            ch.name = unique(ch.name)
        self._g_in = rec.add("in", [c.name for c in tr.inputs], [c.plc_kind for c in tr.inputs])
        self._g_out = rec.add("out", [c.name for c in tr.outputs],
                              [c.plc_kind for c in tr.outputs])
        # watched variables
        wired = {_canonical(self.plc, c.row.plc): c.name for c in tr.channels}
        wired.update({c.name.upper(): c.name for c in tr.channels})
        getters, wnames, wkinds = [], [], []
        self.watch: list[str] = []
        for raw in watch:
            name = raw.strip()
            if not name or name.upper() in wired or _canonical(self.plc, name) in wired:
                continue
            try:
                var = self.plc.var(name)
            except PlcError as e:
                raise sim_error("PLC4020", f"watch {name}: {e.message}") from None
            kind, _ = type_kind(var.type)
            if kind == "time":
                kind = "int"
            elif kind == "enum":
                kind = "int"
            if kind not in ("bool", "int", "real"):
                raise sim_error("PLC4020", f"watch {name}: a {var.type} cannot be recorded; "
                                "watch BOOL, integer, REAL or TIME variables (for arrays and "
                                "structures name an element, e.g. arr[1] or s.x)")
            col = unique(name)
            wired[name.upper()] = col
            wired[_canonical(self.plc, name)] = col
            getters.append(var.get)
            wnames.append(col)
            wkinds.append("float" if kind == "real" else kind)
            self.watch.append(name)
        self._watch_get = _tuple_getter(getters)
        self._g_watch = rec.add("watch", wnames, wkinds)
        self._g_snap = None
        self._snap_keys: list[str] | None = None
        self.recorder = rec

    def _bind_scenario(self, sc: Scenario) -> None:
        from plclab.errors import Diagnostic

        from .errors import raise_all

        diags: list[Diagnostic] = []
        seq = 0
        for a in sc.actions:
            try:
                for at_ns, fn in self._compile_action(a):
                    self._ops.append((at_ns, seq, fn))
                    seq += 1
            except PlcError as e:
                where = a.location or (e.location if e.location else None)
                diags.append(Diagnostic(e.code, f"action {a.index} ({a.verb} {a.target}): "
                                        f"{e.message}", where))
        raise_all(diags)
        self._ops.sort(key=lambda op: (op[0], op[1]))

    def _signal(self, name: str) -> Any:
        sigs = self.plant.signals
        sig = sigs.get(name)
        if sig is None:
            raise PlcError("PLC4011", f"plant '{self.plant.name}' has no signal '{name}'."
                           f"{did_you_mean(name, sigs)} Its signals: {', '.join(sigs)}")
        return sig

    def _compile_action(self, a: Action) -> list[tuple[int, Callable[[int], None]]]:
        plant, plc = self.plant, self.plc
        v = a.verb
        text = a.text()
        if v in ("press", "set", "ramp"):
            sig = self._signal(a.target)
            driven = {c.signal.name: c for c in self.transfer.outputs}
            if sig.kind == "sensor":
                raise PlcError("PLC4011", f"{sig.name} is a sensor: the plant computes it. To "
                               "make it misbehave inject a fault (plant faults: "
                               f"{', '.join(plant.faults) or 'none'}) or an io_fault")
            if sig.kind in ("actuator", "lamp") and (v != "set" or sig.name in driven):
                why = (f"the PLC drives it through wiring row {driven[sig.name].row.index}"
                       if sig.name in driven else "only panel inputs can be pressed or ramped")
                raise PlcError("PLC4011", f"{sig.name} is {('an' if sig.kind[0] == 'a' else 'a')}"
                               f" {sig.kind}: {why}")
            if v == "press":
                if sig.type != "bool":
                    raise PlcError("PLC4011", f"{sig.name} is a REAL signal; press works on "
                                   "buttons (BOOL). Use set or ramp")
                rest = bool(sig.default)
                src = sig.name

                def press(t_ns: int, s: str = src, val: bool = not rest) -> None:
                    plant.write(s, val)
                    self._event(t_ns, "scenario", s, text)

                def release(t_ns: int, s: str = src, val: bool = rest) -> None:
                    plant.write(s, val)
                    self._event(t_ns, "scenario", s, f"release {s}")

                return [(a.at_ns, press), (a.at_ns + (a.hold_ns or 0), release)]
            if v == "set":
                value = self._plant_value(sig, a.value)

                def set_(t_ns: int, s: str = sig.name, val: Any = value) -> None:
                    plant.write(s, val)
                    self._event(t_ns, "scenario", s, text)

                return [(a.at_ns, set_)]
            # ramp
            if sig.type != "real":
                raise PlcError("PLC4011", f"{sig.name} is BOOL; ramp needs a REAL signal")
            to = self._plant_value(sig, a.value)
            over = a.hold_ns or 0

            def ramp(t_ns: int, s: str = sig.name) -> None:
                start = float(plant.read(s))
                self._ramps.append([s, t_ns, t_ns + over, start, to])
                self._event(t_ns, "scenario", s, text)

            return [(a.at_ns, ramp)]
        if v in ("var", "force", "unforce"):
            try:
                var = plc.var(a.target)
            except PlcError as e:
                raise PlcError("PLC4011", e.message) from None
            if v == "unforce":
                return [(a.at_ns, lambda t_ns, p=a.target: (plc.unforce(p),
                                                            self._event(t_ns, "scenario", p,
                                                                        text)))]
            from plclab.runtime.plc import convert_in

            try:
                convert_in(a.value, var.type, a.target)
            except PlcError as e:
                raise PlcError("PLC4015", e.message) from None
            if v == "var":
                def write(t_ns: int, p: str = a.target, val: Any = a.value) -> None:
                    plc[p] = val
                    self._event(t_ns, "scenario", p, text)

                return [(a.at_ns, write)]

            def force(t_ns: int, p: str = a.target, val: Any = a.value) -> None:
                plc.force(p, val)
                self._event(t_ns, "scenario", p, text)

            return [(a.at_ns, force)]
        if v in ("fault", "clear"):
            faults = plant.faults
            if a.target not in faults:
                raise PlcError("PLC4014", f"plant '{plant.name}' has no fault '{a.target}'."
                               f"{did_you_mean(a.target, faults)} Faults: "
                               f"{', '.join(faults) or '(none)'}")
            if v == "clear":
                return [(a.at_ns, lambda t_ns, f=a.target: plant.clear(f))]
            params = dict(a.params)

            def inject(t_ns: int, f: str = a.target) -> None:
                try:
                    plant.inject(f, **params)
                except (TypeError, ValueError) as e:
                    raise PlcError("PLC4014", f"fault {f}: {e}") from None

            ops = [(a.at_ns, inject)]
            if a.hold_ns is not None:
                ops.append((a.at_ns + a.hold_ns, lambda t_ns, f=a.target: plant.clear(f)))
            return ops
        # io_fault / io_clear
        target = a.plc if v == "io_fault" else a.target
        assert target is not None
        chans = [c for c in self.transfer.find(target) if c.module is not None]
        if not chans:
            rows = ", ".join(f"{c.row.plc} ({c.signal.name}, {c.row.module})"
                             for c in self.transfer.channels if c.module is not None)
            raise PlcError("PLC4014", f"no wiring row with an I/O module for {target!r}; rows "
                           f"with modules: {rows or '(none)'}")
        ch = chans[0]
        if v == "io_clear":
            def io_clear(t_ns: int) -> None:
                ch.module.clear()
                self.transfer.mark_dirty(ch)
                self._event(t_ns, "io_clear", ch.name, f"I/O fault on {ch.name} cleared")

            return [(a.at_ns, io_clear)]
        valid = IO_FAULTS[ch.row.module]
        if a.target not in valid:
            raise PlcError("PLC4014", f"module {ch.row.module} ({ch.name}) has no fault "
                           f"'{a.target}'.{did_you_mean(a.target, valid)} Faults: "
                           f"{', '.join(valid)}")
        if a.value is not None and a.target != "stuck":
            raise PlcError("PLC4010", f"value only applies to the 'stuck' fault, not {a.target}")

        def io_fault(t_ns: int, f: str = a.target, val: Any = a.value) -> None:
            if val is not None:
                ch.module.inject(f, val)
            else:
                ch.module.inject(f)
            self.transfer.mark_dirty(ch)
            self._event(t_ns, "io_fault", ch.name, f"I/O fault '{f}' on {ch.name} "
                        f"({ch.signal.name}, {ch.row.module})")

        return [(a.at_ns, io_fault)]

    @staticmethod
    def _plant_value(sig: Any, value: Any) -> Any:
        if sig.type == "bool":
            if isinstance(value, bool):
                return value
            if isinstance(value, int) and value in (0, 1):
                return bool(value)
            if isinstance(value, str) and value.strip().upper() in ("TRUE", "FALSE"):
                return value.strip().upper() == "TRUE"
            raise PlcError("PLC4015", f"{sig.name} is BOOL: write true or false, not {value!r}")
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise PlcError("PLC4015", f"{sig.name} is REAL ({sig.unit}): write a number, not "
                           f"{value!r}")
        lo, hi = sig.range
        if not lo <= value <= hi:
            raise PlcError("PLC4015", f"{sig.name} ranges over {lo:g}..{hi:g} {sig.unit}; "
                           f"{value!r} is outside")
        return float(value)

    # ------------------------------------------------------------------ events
    def _event(self, t_ns: int, kind: str, source: str, message: str,
               data: dict[str, Any] | None = None) -> None:
        from plclab.trace.events import Event

        self.events.append(Event(t_ns / 1e9, kind, source, message, data))

    def _relay_event(self, ch: Any, closed: bool) -> None:
        from plclab.trace.events import Event

        m = ch.module
        t = m.switch_times[-1][0] if m.switch_times else 0.0
        state = "closed" if closed else "opened"
        self.events.append(Event(t, "relay", ch.name, f"relay {ch.name} -> {ch.signal.name} "
                                 f"{state} (operation {m.operations})",
                                 {"closed": closed, "operations": m.operations}))

    def _plant_events(self, evs: list[Any]) -> None:
        from plclab.trace.events import Event

        src = self.plant.name
        for e in evs:
            self.events.append(Event(e.time, e.kind, src, e.message, e.data))

    # ------------------------------------------------------------------ running
    @property
    def time(self) -> float:
        """Simulation time, s: the time of the next scan."""
        return self.k * self.scan_ns / 1e9

    def value(self, name: str) -> Any:
        """A plant signal, or a PLC variable or address, now."""
        if name in self.plant.signals:
            return self.plant.read(name)
        return self.plc[name]

    def _until(self, until: Any) -> Callable[[dict[str, Any], float], bool] | None:
        if until is None:
            return None
        if callable(until):
            return lambda v, t: bool(until(self))
        from plclab.trace.expr import parse_condition

        cond = parse_condition(until)
        sigs = self.plant.signals
        plant_names = {n: n for n in cond.names if n in sigs}
        getters = {}
        for n in cond.names:
            if n in plant_names:
                continue
            try:
                getters[n] = self.plc.var(n).get
            except PlcError:
                raise sim_error("PLC4013", f"condition {until!r}: {n!r} is neither a signal of "
                                f"'{self.plant.name}' ({', '.join(sigs)}) nor a PLC variable"
                                f".{did_you_mean(n, sigs)}") from None
        return cond.scalar(plant_names, getters)

    def step(self, n: int = 1) -> None:
        """Run ``n`` scans."""
        self._advance(int(n), None)

    def run(self, duration: Any = None, until: Any = None) -> Any:
        """Run for ``duration`` more (default: what is left of the scenario's duration) or until
        ``until`` (default: the scenario's) holds; return the :class:`~plclab.trace.Trace` of
        the whole simulation so far."""
        sc = self.scenario
        if duration is None:
            if sc.duration_ns is None:
                raise sim_error("PLC4020", "how long? give a duration (e.g. run('10min')) or put "
                                "duration = \"10min\" in the scenario")
            d_ns = max(0, sc.duration_ns - self.k * self.scan_ns)
        else:
            d_ns = parse_ns(duration, "duration")
        n = -(-d_ns // self.scan_ns)
        u = until if until is not None else sc.until
        self._until_label = repr(u) if isinstance(u, str) else "condition"
        self._advance(n, self._until(u))
        return self.trace

    def _advance(self, n: int, until: Callable[[dict[str, Any], float], bool] | None) -> None:
        """Run ``n`` scans: the common ones through the fused loop (:mod:`.fastloop`, ADR
        0032), the others (a scenario action or a ramp, a stop condition, hooks) through
        :meth:`_advance_plain`; both give the same trace."""
        from . import fastloop

        if until is not None or self.hooks or not fastloop.ENABLED or n < 2:
            self._advance_plain(n, until)
            return
        key = fastloop.key(self)
        if self._fast is None or self._fast[0] != key:
            self._fast = (key, fastloop.build(self))
        fast = self._fast[1]
        ops = self._ops
        tick = self.scan_ns
        k_end = self.k + n
        scan: Any = None
        unchecked = ready = None
        perf = _time.perf_counter_ns
        while self.k < k_end:
            i = self._op_i
            next_op = ops[i][0] if i < len(ops) else math.inf
            if self._ramps or next_op <= self.k * tick:
                self._advance_plain(1, None)
                continue
            if scan is None:
                self._check_clock()
                scan = self.plc.scanner()  # one scan, prebound (ADR 0024)
                unchecked = getattr(scan, "unchecked", None)
                ready = getattr(scan, "ready", None)
            w_start = perf()
            paused = gc.isenabled()
            gc.disable()  # no cyclic GC passes over the rows (ADR 0032); young ones at flushes
            try:
                fast(self.k, k_end, next_op,
                     unchecked if unchecked is not None and ready() else scan, scan)
            finally:
                if paused:
                    gc.enable()
                self.wall_s += (perf() - w_start) / 1e9

    def _check_clock(self) -> None:
        if self.plc.ctx.now_ns != self.t0_ns + self.k * self.scan_ns:
            raise sim_error("PLC4020", "the PLC's clock moved outside the simulation (plc.scan() "
                            "or plc.run() between simulation steps?); drive the PLC only through "
                            "the simulation")

    def _advance_plain(self, n: int, until: Callable[[dict[str, Any], float], bool] | None
                       ) -> None:
        """The reference loop: one scan after another, as the module docstring says."""
        plc = self.plc
        tick = self.scan_ns
        self._check_clock()
        plant = self.plant
        values = plant.values
        pstep = plant.step
        drain = plant.drain_events
        tr = self.transfer
        read_in, read_out, apply_out = tr.read_in, tr.read_out, tr.apply_out
        scan = plc.scanner()  # one scan, prebound (ADR 0024)
        rec = self.recorder
        prow = self._g_plant.rows.append
        irow = self._g_in.rows.append
        orow = self._g_out.rows.append
        wrow = self._g_watch.rows.append
        wget = self._watch_get
        has_watch = bool(self._g_watch.names)
        idx = rec.index.append
        wall = rec.wall.append
        measure = self.wall_clock
        perf = _time.perf_counter_ns
        snapshot = self.snapshot
        dec = self.decimate
        h = self.dt
        nsub = self.substeps
        ops = self._ops
        next_op = ops[self._op_i][0] if self._op_i < len(ops) else math.inf
        chunk = 8192
        hooks = self.hooks
        pending = len(self._g_plant.rows)
        k = self.k
        w_start = perf()
        try:
            for _ in range(n):
                t_ns = k * tick
                t = t_ns / 1e9
                # 1. scenario
                if t_ns >= next_op:
                    next_op = self._run_ops(t_ns)
                if self._ramps:
                    self._do_ramps(t_ns)
                # 2. inputs
                v = values()
                ins = read_in(t, v)
                # 3. scan
                w0 = perf() if measure else 0
                try:
                    scan()
                except PlcRuntimeFault as fault:
                    self._plc_fault(t_ns, fault)
                w1 = perf() if measure else 0
                if plc.state != self._plc_state:
                    self._plc_changed(t_ns)
                if hooks:
                    for hk in hooks:
                        hk.after_scan(self, t_ns, k % dec == 0)
                outs = read_out()
                # 4. record
                if k % dec == 0:
                    idx(k)
                    prow(tuple(v.values()))
                    irow(ins)
                    orow(outs)
                    if has_watch:
                        wrow(wget())
                    if snapshot:
                        self._record_snapshot()
                    wall(w1 - w0)
                    pending += 1
                    if pending >= chunk:
                        rec.flush()
                        pending = 0
                stop = until is not None and until(v, t)
                # 5. plant
                if nsub == 1:
                    pstep(h)
                else:
                    for _ in range(nsub):
                        pstep(h)
                k += 1
                t_next = k * tick / 1e9
                plant.time = t_next
                evs = drain()
                if evs:
                    self._plant_events(evs)
                # 6. outputs
                apply_out(t_next, outs)
                if stop:
                    self.k = k
                    self.stop_reason = f"until {self._until_text(until)} at {t:g} s"
                    self._event(t_ns, "until", "scenario", self.stop_reason)
                    break
        finally:
            self.k = k
            self.wall_s += (perf() - w_start) / 1e9

    def _until_text(self, until: Any) -> str:
        return getattr(self, "_until_label", "condition")

    def _run_ops(self, t_ns: int) -> float:
        ops = self._ops
        i = self._op_i
        while i < len(ops) and ops[i][0] <= t_ns:
            self._op_i = i + 1
            ops[i][2](t_ns)
            i += 1
        self._op_i = i
        return ops[i][0] if i < len(ops) else math.inf

    def _do_ramps(self, t_ns: int) -> None:
        keep = []
        for r in self._ramps:
            s, a, b, y0, y1 = r
            if t_ns >= b or b == a:
                self.plant.write(s, y1)
            else:
                self.plant.write(s, y0 + (y1 - y0) * (t_ns - a) / (b - a))
                keep.append(r)
        self._ramps = keep

    def _plc_fault(self, t_ns: int, fault: PlcRuntimeFault) -> None:
        """The program faulted in this scan: the PLC is in STOP. A STOP scan finishes the cycle
        (outputs off, clock one tick on) so that the PLC stays in step with the plant."""
        plc = self.plc
        if plc.ctx.now_ns == self.t0_ns + t_ns:
            plc.scan()
        if self.stop_on_fault:
            self._plc_changed(t_ns)
            raise fault

    def _plc_changed(self, t_ns: int) -> None:
        plc = self.plc
        self._plc_state = plc.state
        if plc.state != "RUN" and plc.fault is not None:
            f = plc.fault
            where = f" at {f.location}" if getattr(f, "location", None) else ""
            self._event(t_ns, "plc_fault", "plc", f"the PLC stopped: {f.code} {f.message}{where};"
                        " outputs are off", {"code": f.code})
        else:
            self._event(t_ns, "plc_state", "plc", f"the PLC is in {plc.state}")

    def _record_snapshot(self) -> None:
        snap = self.plant.snapshot()
        if self._g_snap is None:
            keys = list(snap)
            self._snap_keys = keys
            taken = {n.upper() for g in self.recorder.groups.values() for n in g.names}
            names = [k if k.upper() not in taken else f"snapshot:{k}" for k in keys]
            self._g_snap = self.recorder.add("snapshot", names, ["float"] * len(keys))
            self._g_snap.rows.extend([(math.nan,) * len(keys)] * (len(self.recorder.index) - 1))
        keys = self._snap_keys
        assert keys is not None
        if len(snap) == len(keys) and list(snap) == keys:
            self._g_snap.rows.append(tuple(snap.values()))
        else:
            self._g_snap.rows.append(tuple(snap.get(k, math.nan) for k in keys))

    # ------------------------------------------------------------------ the record
    @property
    def trace(self) -> Any:
        """The :class:`~plclab.trace.Trace` of everything run so far."""
        import numpy as np

        from plclab import __version__
        from plclab.trace import Trace

        rec = self.recorder
        cols, kinds = rec.columns()
        tnum = np.asarray(rec.index, dtype=np.int64) * self.scan_ns
        time = tnum / 1e9
        sigs = self.plant.signals
        io = []
        for c in self.transfer.channels:
            io.append({"plc": c.row.plc, "signal": c.signal.name, "module": c.row.module,
                       "direction": c.direction, "column": c.name, "plant_column": c.signal.name,
                       "params": c.row.params, "description": c.row.description})
        edges, initial, bounce = self._edges()
        extra: list[Any] = []
        hook_meta: dict[str, Any] = {}
        for hk in self.hooks:
            evs, hm = hk.finish(self)
            extra += evs
            hook_meta.update(hm)
        sfc = self._sfc_lane(cols, time)
        events = sorted(self.events + bounce + extra + sfc.pop("events"),
                        key=lambda e: e.time)
        meta = {
            "plant": self.plant.name, "title": getattr(self.plant, "title", ""),
            "plant_params": {k: v for k, v in self.plant_params.items()
                             if isinstance(v, bool | int | float | str)},
            "signals": list(sigs),
            "units": {n: s.unit for n, s in sigs.items()},
            "signal_info": {n: {"kind": s.kind, "type": s.type, "unit": s.unit,
                                "range": list(s.range), "description": s.description}
                            for n, s in sigs.items()},
            "io": io, "watch": list(self.watch), "scan": self.scan, "dt": self.dt,
            "substeps": self.substeps, "seed": self.seed, "decimate": self.decimate,
            "period": self.scan * self.decimate, "t_end": self.time, "scans": self.k,
            "plc_time0": self.t0_ns / 1e9, "stop_reason": self.stop_reason,
            "wiring": self.wiring.source or f"default for {self.plant.name}",
            "scenario": self.scenario.source or "", "description": self.scenario.description,
            "edge_initial": initial, "warnings": list(self.warnings),
            "plclab_version": __version__,
            **hook_meta,
            **sfc,
        }
        wall = {"scan_s": np.asarray(rec.wall, dtype=np.float64) / 1e9, "run_s": self.wall_s}
        return Trace(time, cols, kinds, meta, events, wall, edges)

    def _sfc_lane(self, cols: dict[str, Any], time: Any) -> dict[str, Any]:
        """The charts (``sfc``), why they stand where they are (``sfc_end``) and the
        transition firings (``events``) of the programs with an SFC body; nothing otherwise."""
        if not self._sfc_steps:
            return {"events": []}
        from .sfc_lane import sfc_meta, step_events, why_stuck

        columns = {name.upper(): col for name, col in zip(
            self.watch, self._g_watch.names, strict=True)}
        meta = sfc_meta(self.plc, columns)
        return {"sfc": meta, "sfc_end": why_stuck(self.plc),
                "events": step_events(meta, time, cols)}

    def _edges(self) -> tuple[dict[str, Any], dict[str, bool], list[Any]]:
        import numpy as np

        from plclab.trace.events import Event

        edges: dict[str, Any] = {}
        initial: dict[str, bool] = {}
        bounce: list[Any] = []
        for c in self.transfer.channels:
            m = c.module
            if c.row.module == "di":
                raw = m.raw_transitions
                filt = m.filtered_transitions
                init = bool(m.initial) if m.initial is not None else False
                edges[f"{c.name}.raw"] = (np.array([x[0] for x in raw], dtype=float),
                                          np.array([x[1] for x in raw], dtype=bool))
                edges[f"{c.name}.filtered"] = (np.array([x[0] for x in filt], dtype=float),
                                               np.array([x[1] for x in filt], dtype=bool))
                initial[f"{c.name}.raw"] = initial[f"{c.name}.filtered"] = init
                if m.bounce_ms > 0 and raw:
                    gap = m.bounce_ms / 1000.0 + 1e-9
                    burst = [raw[0]]
                    for e in list(raw[1:]) + [None]:
                        if e is not None and e[0] - burst[-1][0] <= gap:
                            burst.append(e)
                            continue
                        if len(burst) > 1:
                            span = (burst[-1][0] - burst[0][0]) * 1000.0
                            bounce.append(Event(burst[0][0], "bounce", c.name,
                                                f"{c.signal.name} bounced: {len(burst)} edges in "
                                                f"{span:.2f} ms", {"edges": len(burst)}))
                        if e is not None:
                            burst = [e]
            elif c.row.module == "do":
                sw = m.switch_times
                edges[f"{c.name}.contact"] = (np.array([x[0] for x in sw], dtype=float),
                                              np.array([x[1] for x in sw], dtype=bool))
                initial[f"{c.name}.contact"] = False
        return edges, initial, bounce

    def __repr__(self) -> str:
        return (f"<Simulation {self.plant.name} t={self.time:g}s scan={format_duration(self.scan)}"
                f" {len(self.wiring)} wiring rows>")


def _canonical(plc: Any, path: str) -> str:
    """``PROG.VAR`` for a variable given without its program (for comparing paths)."""
    p = path.strip().upper()
    if p.startswith("%"):
        return p
    head = p.split(".")[0].split("[")[0]
    project = plc.project
    if head in {n.upper() for n, _, _ in project.programs} or head in project.globals:
        return p
    owners = [n.upper() for n, _ in project.symbols.programs_declaring(head)]
    return f"{owners[0]}.{p}" if len(owners) == 1 else p


def _tuple_getter(getters: list[Callable[[], Any]]) -> Callable[[], tuple[Any, ...]]:
    if not getters:
        return tuple
    ns = {f"g{i}": g for i, g in enumerate(getters)}
    src = "lambda: (" + "".join(f"g{i}(), " for i in range(len(getters))) + ")"
    return eval(src, ns)  # noqa: S307 - fixed text, no user input
