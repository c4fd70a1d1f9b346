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

import math
from collections.abc import Callable, Iterable
from typing import Any

from plclab.errors import PlcError

from .channels import Transfer, bind
from .durations import format_duration, parse_ns
from .errors import sim_error
from .scenario import Scenario, as_scenario
from .sim_actions import ScenarioActions
from .sim_loop import RunLoop
from .sim_record import Recording
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


class Simulation(Recording, ScenarioActions, RunLoop):
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

    def __repr__(self) -> str:
        return (f"<Simulation {self.plant.name} t={self.time:g}s scan={format_duration(self.scan)}"
                f" {len(self.wiring)} wiring rows>")
