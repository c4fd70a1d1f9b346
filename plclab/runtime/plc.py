"""The virtual PLC: process image, tasks, scan cycle, virtual clock, forcing, restarts.

>>> import plclab
>>> plc = plclab.loads('''
... PROGRAM Tank
... VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
... M := ((NOT LS1) OR M) AND (NOT LS2);
... END_PROGRAM''')
>>> plc.scan(); plc["M"]
True
>>> plc["LS2"] = True; plc.scan(); plc["%QX0.0"]
False
"""

from __future__ import annotations

import math
import re
import sys
from dataclasses import dataclass
from typing import Any

from ..compile.codegen import Compiled
from ..compile.real32 import single_cell
from ..errors import Location, PlcError, PlcRuntimeFault
from ..lang.check.symbols import instance_label
from . import natives, scan_gen
from .plc_limits import (
    DEFAULT_IMAGE,
    MAX_CYCLE_NS,
    MAX_IMAGE,
    MAX_SCANS,
    MIN_CYCLE_NS,
    auto_image_size,
    check_address,
    check_cycle_ns,
    check_image_size,
    check_memory_byte,
    fmt_ns,
    parse_task_intervals,
    to_ns,
)
from .plc_scan import ScanCycle
from .plc_vars import Var, VariableAccess, convert_in, format_typed
from .plc_watch import ForcedTable, ForcingAndWatch, TriggerHooks
from .rt import HELPERS, AssertFailure, Budget, Fault, fb_exit_all

# the trigger points of TIA Portal's watch tables (001 lines 3985-4030, Table 14)
TRIGGERS = ("scan_start", "scan_end", "stop")


class Context:
    """What running code sees of the PLC: the clock (sampled once per scan) and the cycle."""

    __slots__ = ("now", "now_ns", "cycle_ms", "cycle_ns", "first_scan", "scan_count")

    def __init__(self, cycle_ns: int) -> None:
        self.now = 0  # TIME (ms) of the current scan
        self.now_ns = 0
        self.cycle_ns = cycle_ns
        self.cycle_ms = cycle_ns / 1e6
        self.first_scan = True
        self.scan_count = 0

    def advance_ns(self, ns: int) -> None:
        """Move the clock (used by ADVANCE_TIME in TEST blocks)."""
        if ns < 0:
            raise Fault("PLC2010", "ADVANCE_TIME needs a positive duration")
        self.now_ns += ns
        self.now = self.now_ns // 1_000_000


@dataclass
class Task:
    name: str
    interval_ns: int
    priority: int
    programs: list[str]  # instance names


_IMAGE_USE = re.compile(r"\b_[IQ]\b")  # generated code touching the input or output image


class Plc(ScanCycle, VariableAccess, ForcingAndWatch):
    """A virtual PLC running a compiled project.

    Parameters
    ----------
    compiled : Compiled
        The output of :func:`plclab.compile_files`.
    cycle_time : str | float
        The default cyclic task's period (``"10ms"``, ``0.01``), 0.1 ms to 1 day.
    watchdog : int
        Loop iterations allowed per scan before a scan-overrun fault (deterministic).
    image_size : int | None
        Bytes of each process image area (%I, %Q, %M), 8 to 65536. By default (None) the
        image is sized from the program's addresses: 1024 bytes, or the next multiple of 1024
        that holds its highest located variable (``AT %MW2000``: 3072); the checker refuses
        addresses beyond 65535 (PLC0127). A smaller explicit size than the program needs is
        PLC0127.
    task_intervals : mapping, optional
        Run the tasks configured at one interval at another, ``{"10ms": "20ms"}``: the same
        program on a controller whose tasks are scheduled differently (a lab checks that a
        program measures its periods instead of assuming them). Keys that no task has are
        ignored; the default cyclic task counts as configured at ``cycle_time``.
    """

    def __init__(self, compiled: Compiled, cycle_time: Any = "10ms",
                 watchdog: int = 2_000_000, image_size: int | None = None,
                 system_memory_byte: int | None = None,
                 clock_memory_byte: int | None = None,
                 task_intervals: Any = None) -> None:
        self.compiled = compiled
        self.project = compiled.project
        self.cycle_ns = check_cycle_ns(to_ns(cycle_time), "the cycle time")
        if isinstance(watchdog, bool) or not isinstance(watchdog, int) or watchdog < 1:
            raise PlcError("PLC3012", f"watchdog={watchdog!r}: give the loop iterations allowed "
                           "per scan as a positive whole number (default 2000000)")
        self.watchdog = watchdog
        need = getattr(self.project, "image_needed", None)
        if image_size is None:  # sized from the program (ADR 0053)
            image_size = auto_image_size(need[0] if need is not None else 0)
        self.image_size = check_image_size(image_size)
        if need is not None and need[0] > image_size:
            raise PlcError("PLC0127", f"{need[1]} lies beyond the process image of {image_size} "
                           f"bytes; use a smaller address, a larger image (Plc(..., "
                           f"image_size={need[0]}), --image-size {need[0]}), or leave the "
                           "size out: it is then sized from the program", need[2])
        # S7-style system and clock memory bytes (001 lines 2494-2540), off unless asked for
        self.system_memory_byte = check_memory_byte(system_memory_byte, image_size,
                                                     "system_memory_byte")
        self.clock_memory_byte = check_memory_byte(clock_memory_byte, image_size,
                                                    "clock_memory_byte")
        self.inputs = bytearray(image_size)  # the physical input terminals
        self.outputs = bytearray(image_size)  # the physical output terminals
        self._live = [False]  # the generated scan's flag: the common case holds (ADR 0058)
        self.forced: dict[str, Any] = ForcedTable(self._reselect)
        # trigger points of a watch table (ADR 0025): callbacks and one-shot modifications
        self.triggers: dict[str, list[Any]] = {t: TriggerHooks(self._rewatch) for t in TRIGGERS}
        self.modified: dict[str, dict[str, Any]] = {t: {} for t in TRIGGERS}
        self.outputs_enabled_in_stop = False
        # the same list and dict objects; _hooked is any() of them, kept up to date by the
        # trigger lists, modify() and _take(), so a scan() call tests one flag (ADR 0034)
        self._watch_parts = (*self.triggers.values(), *self.modified.values())
        self._hooked = False
        self.state = "RUN"
        self.fault: PlcRuntimeFault | None = None
        self._natives = {k: natives.resolve(v) for k, v in compiled.natives.items()}
        self._var_cache: dict[str, Var] = {}
        self.tasks = self._make_tasks(parse_task_intervals(task_intervals))
        self._tick_ns = _gcd_all([t.interval_ns for t in self.tasks] or [self.cycle_ns])
        if self._tick_ns < MIN_CYCLE_NS:
            raise PlcError("PLC3011", "the task intervals (" + ", ".join(
                fmt_ns(t.interval_ns) for t in self.tasks) + f") share a base period of only "
                f"{fmt_ns(self._tick_ns)}; make them multiples of 0.1 ms or more")
        self.cold_restart()

    # -- set-up -------------------------------------------------------------------------------
    def _make_tasks(self, retime: dict[int, int]) -> list[Task]:
        tasks: dict[str, Task] = {}
        for td in self.project.tasks:
            iv = self.cycle_ns
            if td.interval is not None:
                v = getattr(td.interval, "value", None)
                if isinstance(v, int):
                    iv = v  # ns, range-checked by the checker (PLC0129)
            prio = getattr(td.priority, "value", 0) if td.priority is not None else 0
            name = f"{td.resource}.{td.name}" if td.resource else td.name  # ADR 0037
            tasks[name] = Task(name, retime.get(iv, iv), int(prio or 0), [])
        default = Task("__default__", retime.get(self.cycle_ns, self.cycle_ns), 0, [])
        for inst, _, task in self.project.programs:
            (tasks[task] if task in tasks else default).programs.append(inst)
        out = sorted(tasks.values(), key=lambda t: t.priority)
        if default.programs or not out:
            out.append(default)
        return out

    def _new_namespace(self) -> dict[str, Any]:
        ns: dict[str, Any] = dict(HELPERS)
        ns.update(self._natives)
        self.ctx = Context(self.cycle_ns)
        self.budget = Budget(self.watchdog)
        self.image_in = bytearray(self.image_size)
        self.image_out = bytearray(self.image_size)
        self.memory = bytearray(self.image_size)
        cell, f32_cell = single_cell()  # this PLC's own REAL rounding cell (ADR 0024)
        ns.update(_CTX=self.ctx, _B=self.budget, _I=self.image_in, _Q=self.image_out,
                  _M=self.memory, _F32=cell, _f32=f32_cell, __name__="plclab_program",
                  _INIT_RETAINS=not getattr(self, "_warm", False))  # FB_init (ADR 0021)
        for code in self.compiled.code:  # the module in pieces (plclab.compile.pycompile)
            exec(code, ns)
        ns["_G"] = ns["_Globals"]()
        ns["_P"] = ns["_Programs"]()
        if any(True for _ in self.compiled.located):  # %Q and %M start as their variables
            ns["_sync_init"]()
        return ns

    def cold_restart(self) -> None:
        """All variables back to their initial values, clock to zero (a cold restart)."""
        old = getattr(self, "ns", None)
        if old is not None and "_P" in old:  # the old instances go: FB_exit (ADR 0021)
            self._guard(lambda: fb_exit_all([old["_G"], *(
                old[f"_RG_{r}"] for r in self.project.symbols.resource_globals), old["_P"]]))
        self.ns = self._guard(self._new_namespace)
        self._bind()
        self.state = "RUN"
        self.fault = None

    def warm_restart(self) -> None:
        """Restart keeping RETAIN variables (as after a power cycle with a battery)."""
        keep = {}
        for path, var in self._retain_vars():
            keep[path] = var.get()
        now_ns = self.ctx.now_ns
        mem = bytes(self.memory)
        self._warm = True  # FB_init sees bInitRetains = FALSE
        try:
            self.cold_restart()
        finally:
            self._warm = False
        self.ctx.now_ns = now_ns
        self.ctx.now = now_ns // 1_000_000
        self.memory[:] = mem
        for path, val in keep.items():
            self._var_cache.pop(path.upper(), None)
            self.var(path).set(val)

    def _retain_vars(self):
        for d in self.project.globals.values():
            if d.retain:
                yield d.name, self.var(d.name)
        for r, gs in self.project.symbols.resource_globals.items():  # ADR 0037
            for d in gs.values():
                if d.retain:
                    yield f"{r}.{d.name}", self.var(f"{r}.{d.name}")
        symbols = self.project.symbols
        for inst, pou, _ in symbols.programs():
            for d in symbols.members(pou).values():
                if d.retain and d.section != "VAR_EXTERNAL":
                    yield f"{inst}.{d.name}", self.var(f"{inst}.{d.name}")

    def _bind(self) -> None:
        ns = self.ns
        self._var_cache.clear()
        located = any(True for _ in self.compiled.located)
        self._sync_in = ns["_sync_in"] if located else None
        self._sync_out = ns["_sync_out"] if located else None
        # whether the program reads or writes a process image (fast scans, ADR 0024)
        self._images = located or _IMAGE_USE.search(self.compiled.source) is not None
        progs = ns["_P"]
        self._task_bodies = [
            (t.interval_ns, [getattr(progs, n.upper().replace(".", "__"))._body
                             for n in t.programs])
            for t in self.tasks
        ]
        # one task running at the base tick: no need to check which tasks are due
        self._single = (self._task_bodies[0][1] if len(self._task_bodies) == 1 and
                        self._task_bodies[0][0] == self._tick_ns else None)
        # the scan of this PLC as one generated function (ADR 0058); the old one, if a
        # caller still holds it, hands its calls to the general scan()
        self._live[0] = False
        self.scan, self._unchecked, self._live = scan_gen.build(self, ScanCycle.scan)
        self._reselect()

    @property
    def tick_ns(self) -> int:
        """The base period of the scan loop (the gcd of the task intervals), in ns."""
        return self._tick_ns

    def _translate(self, exc: BaseException) -> PlcError:
        if isinstance(exc, KeyboardInterrupt):
            raise exc
        if isinstance(exc, PlcError):
            return exc
        loc = self._location_of(exc)
        if isinstance(exc, Fault):
            if exc.where:
                loc = self.compiled.locations[exc.where] or loc
            return PlcRuntimeFault(exc.code, exc.message, loc)
        if isinstance(exc, AssertFailure):
            return PlcRuntimeFault("PLC2010", exc.message,
                                   self.compiled.locations[exc.where] or loc)
        if isinstance(exc, ZeroDivisionError):
            return PlcRuntimeFault("PLC2001", "division by zero; check the divisor before "
                                   "dividing", loc)
        if isinstance(exc, RecursionError):
            return PlcRuntimeFault("PLC2007", "calls are nested too deeply", loc)
        if isinstance(exc, OverflowError):
            return PlcRuntimeFault("PLC2008", f"numeric overflow ({exc})", loc)
        if isinstance(exc, MemoryError):
            return PlcRuntimeFault("PLC2009", "out of memory", loc)
        return PlcRuntimeFault("PLC9999", f"internal error ({type(exc).__name__}: {exc}); "
                               "please report it with your program", loc)

    def _location_of(self, exc: BaseException) -> Location | None:
        tb = exc.__traceback__
        loc = None
        while tb is not None:
            if tb.tb_frame.f_code.co_filename == self.compiled.filename:
                loc = self.compiled.location_of_line(tb.tb_lineno) or loc
            tb = tb.tb_next
        return loc

    # -- listing ------------------------------------------------------------------------------
    def variables(self) -> list[str]:
        """Every top-level variable path (program variables and globals)."""
        out = [d.spelling or d.name for d in self.project.globals.values()]
        symbols = self.project.symbols
        out += [f"{r}.{d.spelling or d.name}" for r, gs in symbols.resource_globals.items()
                for d in gs.values()]
        for inst, pou, _ in symbols.programs():
            label = instance_label(inst, pou)
            out += [f"{label}.{d.spelling or d.name}" for d in symbols.members(pou).values()
                    if d.section != "VAR_TEMP" and not d.name.startswith("__")]
        return out


def _gcd_all(values: list[int]) -> int:
    g = 0
    for v in values:
        g = math.gcd(g, v)
    return g or 10_000_000


# the names other modules import from here (the parts live in plc_limits, plc_vars, plc_scan,
# plc_watch)
__all__ = ["DEFAULT_IMAGE", "MAX_CYCLE_NS", "MAX_IMAGE", "MAX_SCANS", "MIN_CYCLE_NS", "TRIGGERS",
           "Context", "Plc", "Task", "Var", "auto_image_size", "check_address", "check_cycle_ns",
           "convert_in", "format_typed", "parse_task_intervals", "to_ns"]

del sys
