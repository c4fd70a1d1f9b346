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

import datetime as _dt
import math
import re
import sys
from dataclasses import dataclass
from dataclasses import replace as _replace
from typing import Any

from ..compile.codegen import Compiled, kind_name
from ..compile.real32 import single_cell
from ..durations import parse_duration
from ..errors import Location, PlcError, PlcRuntimeFault
from ..lang import types as T
from ..lang.addresses import LOCATED_RE, SIZE_BYTES, canonical
from ..lang.check.symbols import instance_label
from ..lang.limits import MAX_INTERVAL_NS, MIN_INTERVAL_NS
from ..names import split_outside_brackets
from . import natives
from .rt import HELPERS, AssertFailure, Budget, Fault, fb_exit_all, format_value

# the trigger points of TIA Portal's watch tables (001 lines 3985-4030, Table 14)
TRIGGERS = ("scan_start", "scan_end", "stop")

_PATH_RE = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[[^\]]*\])*)")


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


@dataclass
class Var:
    """A resolved variable path: how to read and write it and what type it has."""

    path: str
    type: T.Type
    get: Any
    set: Any
    address: str | None = None


def to_ns(value: Any) -> int:
    """Accept 0.01 (seconds), '10ms', '1min', 'T#10ms' or a timedelta and return nanoseconds
    (:func:`plclab.durations.parse_duration`)."""
    ns = None if isinstance(value, float) and not math.isfinite(value) else \
        parse_duration(value)
    if ns is not None:
        return ns
    if isinstance(value, float):
        raise PlcError("PLC3002", f"{value!r} is not a duration; give a finite number of "
                       "seconds or e.g. '10ms'")
    if isinstance(value, str):
        raise PlcError("PLC3002", f"'{value}' is not a duration; write e.g. 10ms, 1.5s or "
                       "T#1m30s")
    raise PlcError("PLC3002", f"{value!r} is not a duration")


# Bounds of the run-time API (documented in docs and in problems.py PLC3010-PLC3012).
MIN_CYCLE_NS = MIN_INTERVAL_NS  # 0.1 ms: the fastest task a PLC of the course runs
MAX_CYCLE_NS = MAX_INTERVAL_NS  # one day
MAX_SCANS = 100_000_000  # scans per run()/scan() call
MAX_IMAGE = 65_536  # bytes of each process image area (%I, %Q, %M)
_IMAGE_USE = re.compile(r"\b_[IQ]\b")  # generated code touching the input or output image
_ADDR_RE = LOCATED_RE  # the one parser of direct addresses (plclab.lang.addresses)
_SIZE_BYTES = SIZE_BYTES


def check_cycle_ns(ns: int, what: str, location: Location | None = None) -> int:
    """``ns`` when it is a usable cycle time or task interval; else PlcError PLC3011."""
    if not MIN_CYCLE_NS <= ns <= MAX_CYCLE_NS:
        raise PlcError("PLC3011", f"{what} is {_fmt_ns(ns)}; it must lie between 0.1 ms and "
                       "1 day (e.g. 10ms)", location)
    return ns


MAX_SHOWN = 1000  # elements of an array that format_typed writes out


_SHOWN_SECTIONS = ("VAR_INPUT", "VAR_OUTPUT", "VAR")  # a block instance's state, shown
MAX_DEPTH = 4  # block instances inside block instances that format_typed writes out


def format_typed(v: Any, ty: Any, members: Any = None, depth: int = 0) -> str:
    """``v`` as an IEC literal of its declared type: arrays as ``[1, 2]`` (flat, as an array
    initializer; the first :data:`MAX_SHOWN` elements), structures as ``(X := 1, S := 'a')``,
    block instances as a structure of their inputs, outputs and variables (``(IN := TRUE,
    PT := T#1s, Q := FALSE, ET := T#0ms)``; VAR_IN_OUT and VAR_TEMP are not state), every
    element formatted by its own type (``T#1s``, ``'a$N'``), never a Python repr.
    ``members(pou)``: a block's variables with the inherited ones (the symbol table's)."""
    r = T.resolve(ty) if ty is not None else None
    if isinstance(r, T.ArrayType) and isinstance(v, list):
        shown = [format_typed(e, r.elem, members, depth) for e in v[:MAX_SHOWN]]
        if len(v) > MAX_SHOWN:
            shown.append(f"... {len(v) - MAX_SHOWN} more")
        return "[" + ", ".join(shown) + "]"
    if isinstance(r, T.StructType) and hasattr(type(v), "__slots__"):
        return "(" + ", ".join(
            f"{getattr(d, 'spelling', None) or n} := "
            f"{format_typed(getattr(v, n.upper(), None), d.ty, members, depth)}"
            for n, d in r.fields.items()) + ")"
    if isinstance(r, T.FBType) and r.pou is not None and hasattr(type(v), "__slots__") and \
            depth < MAX_DEPTH:
        decls = members(r.pou).values() if members is not None else r.pou.decls
        return "(" + ", ".join(
            f"{d.spelling or d.name} := "
            f"{format_typed(getattr(v, d.name.upper()), d.ty, members, depth + 1)}"
            for d in decls if d.section in _SHOWN_SECTIONS and not d.constant and
            d.ty is not None and hasattr(v, d.name.upper())) + ")"
    return format_value(v, kind_name(ty))


def parse_task_intervals(mapping: Any) -> dict[int, int]:
    """``{"10ms": "20ms"}`` as nanoseconds, each side checked like a cycle time (PLC3011)."""
    if not mapping:
        return {}
    if not hasattr(mapping, "items"):
        raise PlcError("PLC3011", f"task_intervals={mapping!r}: give a table from the "
                       "configured interval to the one to run, e.g. {'10ms': '20ms'}")
    return {check_cycle_ns(to_ns(k), "a task interval"): check_cycle_ns(to_ns(v), "a task "
            "interval") for k, v in mapping.items()}


def _fmt_ns(ns: int) -> str:
    if ns <= 0 or ns % 1_000_000:
        return f"{ns} ns"
    if ns % 1_000_000_000 == 0:
        return f"{ns // 1_000_000_000} s"
    return f"{ns // 1_000_000} ms"


def check_address(addr: str, image_size: int, location: Location | None = None,
                  what: str = "") -> tuple[str, str, int, int | None]:
    """Split ``%QX1.2``/``%IW4`` into (area, size, byte, bit), checking that it lies inside a
    process image of ``image_size`` bytes: PlcError PLC3001 (not an address) or PLC3010."""
    m = _ADDR_RE.fullmatch(canonical(addr))
    if not m:
        raise PlcError("PLC3001", f"{what}{addr} is not a direct address (e.g. %IX0.0, %QW2, "
                       "%MD4)", location)
    area, size, byte = m.group(1), m.group(2) or "X", int(m.group(3))
    bit = int(m.group(4)) if m.group(4) is not None else None
    if size == "X" and bit is None:
        raise PlcError("PLC3001", f"{what}{addr}: a bit address needs byte.bit, e.g. "
                       f"%{area}X{byte}.0", location)
    if size != "X" and bit is not None:
        raise PlcError("PLC3001", f"{what}{addr}: only bit addresses (X) have a .bit part",
                       location)
    if bit is not None and bit > 7:
        raise PlcError("PLC3010", f"{what}{addr}: a byte has bits 0..7, not {bit}", location)
    n = _SIZE_BYTES[size]
    if byte + n > image_size:
        last = image_size - n
        raise PlcError("PLC3010", f"{what}{addr} is beyond the process image ({image_size} "
                       f"bytes: %{area}{size}0{'.0' if size == 'X' else ''}..%{area}{size}{last}"
                       f"{'.7' if size == 'X' else ''}); use a lower address or a larger "
                       "image_size", location)
    return area, size, byte, bit


DEFAULT_IMAGE = 1024  # bytes of each process image area unless the program needs more


def auto_image_size(need: int) -> int:
    """The process image for a program whose located variables end at byte ``need``: 1024
    bytes, or the next multiple of 1024 (at most MAX_IMAGE; the checker refuses more).

    >>> auto_image_size(0), auto_image_size(1024), auto_image_size(1033), auto_image_size(65536)
    (1024, 1024, 2048, 65536)
    """
    return min(MAX_IMAGE, max(DEFAULT_IMAGE, -(-need // 1024) * 1024))


def _check_image_size(size: Any) -> int:
    if isinstance(size, bool) or not isinstance(size, int) or not 8 <= size <= MAX_IMAGE:
        raise PlcError("PLC3012", f"image_size={size!r}: the process image is a whole number of "
                       f"bytes from 8 to {MAX_IMAGE} (default: sized from the program's addresses, at least "
                       "1024)")
    return size


def _check_memory_byte(byte: Any, image_size: int, what: str) -> int | None:
    if byte is None:
        return None
    if isinstance(byte, bool) or not isinstance(byte, int) or not 0 <= byte < image_size:
        raise PlcError("PLC3012", f"{what}={byte!r}: give a byte number of %M from 0 to "
                       f"{image_size - 1}, or None")
    return byte


def _check_count(n: Any, what: str) -> int:
    """A number of scans: a whole number from 0 to MAX_SCANS, else PlcError PLC3011."""
    if isinstance(n, bool) or not isinstance(n, int):
        raise PlcError("PLC3011", f"{what}={n!r}: give a whole number of scans")
    if not 0 <= n <= MAX_SCANS:
        raise PlcError("PLC3011", f"{what}={n}: one call runs 0 to {MAX_SCANS:,} scans; split a "
                       "longer run into several calls")
    return n


class Plc:
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
        self.image_size = _check_image_size(image_size)
        if need is not None and need[0] > image_size:
            raise PlcError("PLC0127", f"{need[1]} lies beyond the process image of {image_size} "
                           f"bytes; use a smaller address, a larger image (Plc(..., "
                           f"image_size={need[0]}), --image-size {need[0]}), or leave the "
                           "size out: it is then sized from the program", need[2])
        # S7-style system and clock memory bytes (001 lines 2494-2540), off unless asked for
        self.system_memory_byte = _check_memory_byte(system_memory_byte, image_size,
                                                     "system_memory_byte")
        self.clock_memory_byte = _check_memory_byte(clock_memory_byte, image_size,
                                                    "clock_memory_byte")
        self.inputs = bytearray(image_size)  # the physical input terminals
        self.outputs = bytearray(image_size)  # the physical output terminals
        self.forced: dict[str, Any] = {}
        # trigger points of a watch table (ADR 0025): callbacks and one-shot modifications
        self.triggers: dict[str, list[Any]] = {t: _Hooks(self._rewatch) for t in TRIGGERS}
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
                _fmt_ns(t.interval_ns) for t in self.tasks) + f") share a base period of only "
                f"{_fmt_ns(self._tick_ns)}; make them multiples of 0.1 ms or more")
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
        self._one = self._one_scan() if self._single is not None else None

    # -- the scan cycle -----------------------------------------------------------------------
    @property
    def time(self) -> float:
        """Virtual time in seconds."""
        return self.ctx.now_ns / 1e9

    @property
    def scan_count(self) -> int:
        return self.ctx.scan_count

    def scan(self, n: int = 1) -> None:
        """Run ``n`` scan cycles: freeze inputs, run due tasks, write outputs, advance clock."""
        if n.__class__ is not int or not 0 <= n <= MAX_SCANS:
            _check_count(n, "scan: n")
        if (self.state != "RUN" or self.forced or self._single is None or n < 1
                or self._system_bytes or self._hooked):
            for _ in range(n):
                self._scan_once()
            return
        if n == 1:
            self._one()
            return
        self._fast_scans(n)

    def _one_scan(self):
        """``_fast_scans(1)`` with what it needs bound once (made by ``_bind``): the fixed
        cost of a ``scan()`` call (ADR 0034). The same steps and end state, a fault included
        (no output copy, no clock step, the scan counted); without a process image in the
        program the order of the image copies cannot be seen."""
        plc, ctx, budget, tick = self, self.ctx, self.budget, self._tick_ns
        img_in, inputs, img_out, outputs = self.image_in, self.inputs, self.image_out, self.outputs
        sync_in, sync_out, bodies = self._sync_in, self._sync_out, self._single

        def one() -> None:
            budget.left = budget.limit
            img_in[:] = inputs
            try:
                if sync_in is not None:
                    sync_in()
                for body in bodies:
                    body()
                if sync_out is not None:
                    sync_out()
                outputs[:] = img_out
                t = ctx.now_ns + tick
                ctx.now_ns = t
                ctx.now = t // 1_000_000
            except BaseException as exc:  # noqa: BLE001
                plc._to_stop(exc)
            ctx.first_scan = False
            ctx.scan_count += 1

        return one

    def _fast_scans(self, n: int) -> None:
        """The common case (RUN, nothing forced, one cyclic task, no system bytes): the steps
        of :meth:`_scan_once` with everything in locals. A program that uses no process image
        (no located variable, no direct address) cannot see the image copies, so they are made
        once after the ``n`` scans, with the same end state (ADR 0024); nothing reads the scan
        count or the first-scan flag during these scans, so they are set once at the end."""
        ctx, budget, limit = self.ctx, self.budget, self.budget.limit
        img_in, inputs, img_out, outputs = self.image_in, self.inputs, self.image_out, self.outputs
        bodies, tick = self._single, self._tick_ns
        k = 0
        try:
            if self._images:
                sync_in, sync_out = self._sync_in, self._sync_out
                for k in range(n):  # noqa: B007 - k counts the scans done if one faults
                    budget.left = limit
                    img_in[:] = inputs
                    if sync_in is not None:
                        sync_in()
                    for body in bodies:
                        body()
                    if sync_out is not None:
                        sync_out()
                    outputs[:] = img_out
                    t = ctx.now_ns + tick
                    ctx.now_ns = t
                    ctx.now = t // 1_000_000
            elif len(bodies) == 1:
                body = bodies[0]
                for k in range(n):  # noqa: B007
                    budget.left = limit
                    body()
                    t = ctx.now_ns + tick
                    ctx.now_ns = t
                    ctx.now = t // 1_000_000
                img_in[:] = inputs
                outputs[:] = img_out
            else:
                for k in range(n):  # noqa: B007
                    budget.left = limit
                    for body in bodies:
                        body()
                    t = ctx.now_ns + tick
                    ctx.now_ns = t
                    ctx.now = t // 1_000_000
                img_in[:] = inputs
                outputs[:] = img_out
        except BaseException as exc:  # noqa: BLE001
            ctx.scan_count += k
            if not self._images:
                img_in[:] = inputs
            self._to_stop(exc)
        ctx.first_scan = False
        ctx.scan_count += n

    def scanner(self):
        """A function that runs one scan, as ``scan()`` does, at less cost per call: what it
        needs is bound once (the simulation calls it every cycle). While the PLC is not in
        the common case (STOP, forced values, several tasks, system bytes, or after a
        restart, or with a watch table's trigger points or a pending modify) it simply calls
        :meth:`scan`."""
        plc = self
        bodies = self._single
        if bodies is None or len(bodies) != 1:
            return self.scan
        body = bodies[0]
        ctx, budget, tick = self.ctx, self.budget, self._tick_ns
        img_in, inputs, img_out, outputs = self.image_in, self.inputs, self.image_out, self.outputs
        sync_in, sync_out = self._sync_in, self._sync_out

        def ready() -> bool:
            """True while ``unchecked`` may stand for ``scan_one``."""
            return not (plc._single is not bodies or plc.state != "RUN" or plc.forced
                        or plc._system_bytes or plc._hooked)

        def scan_one() -> None:
            if (plc._single is not bodies or plc.state != "RUN" or plc.forced
                    or plc._system_bytes or plc._hooked):  # trigger points: scan()
                plc.scan()
                return
            budget.left = budget.limit  # from here on as unchecked() (a call less)
            img_in[:] = inputs
            try:
                if sync_in is not None:
                    sync_in()
                body()
                if sync_out is not None:
                    sync_out()
            except BaseException as exc:  # noqa: BLE001
                plc._to_stop(exc)
            outputs[:] = img_out
            t = ctx.now_ns + tick
            ctx.now_ns = t
            ctx.now = t // 1_000_000
            ctx.first_scan = False
            ctx.scan_count += 1

        def unchecked() -> None:
            budget.left = budget.limit
            img_in[:] = inputs
            try:
                if sync_in is not None:
                    sync_in()
                body()
                if sync_out is not None:
                    sync_out()
            except BaseException as exc:  # noqa: BLE001
                plc._to_stop(exc)
            outputs[:] = img_out
            t = ctx.now_ns + tick
            ctx.now_ns = t
            ctx.now = t // 1_000_000
            ctx.first_scan = False
            ctx.scan_count += 1

        # for a caller that knows what can change between its scans (the simulation's fused
        # loop, ADR 0032): while ready() holds and nothing but the scans themselves runs,
        # only a fault (state STOP) can end the common case, so the caller may check ready()
        # once, call unchecked() and go back to scan_one after the state changed
        scan_one.ready = ready  # type: ignore[attr-defined]
        scan_one.unchecked = unchecked  # type: ignore[attr-defined]
        return scan_one

    def _scan_once(self) -> None:
        ctx = self.ctx
        if self.state != "RUN":
            self._stop_scan()
            ctx.now_ns += self._tick_ns
            ctx.now = ctx.now_ns // 1_000_000
            return
        watched = self._hooked
        self.budget.left = self.budget.limit
        self.image_in[:] = self.inputs
        if self._system_bytes:
            self._update_system_memory()
        if self.forced:
            self._apply_forced_inputs()
        if watched and self.modified["scan_start"]:
            self._apply_inputs(self._take("scan_start"))
        try:
            if self._sync_in is not None:
                self._sync_in()
            if watched:
                self._fire("scan_start")
            if self._single is not None:
                for body in self._single:
                    body()
            else:
                now = ctx.now_ns
                for interval, bodies in self._task_bodies:
                    if now % interval == 0:
                        for body in bodies:
                            body()
            if self._sync_out is not None:
                self._sync_out()
        except BaseException as exc:  # noqa: BLE001 - every fault becomes a PlcRuntimeFault
            self._to_stop(exc)
        if watched and self.modified["scan_end"]:
            self._apply_outputs(self._take("scan_end"))
        held = None
        if self.forced:
            held = bytes(self.image_out)
            self._apply_forced_outputs()
        if watched:
            self._fire("scan_end")
        self.outputs[:] = self.image_out
        if held is not None:
            self._unforce_image(held)
        ctx.first_scan = False
        ctx.scan_count += 1
        ns = ctx.now_ns + self._tick_ns
        ctx.now_ns = ns
        ctx.now = ns // 1_000_000

    @property
    def _system_bytes(self) -> bool:
        return self.system_memory_byte is not None or self.clock_memory_byte is not None

    # clock memory bits 0..7: 10, 5, 2.5, 2, 1.25, 1, 0.625, 0.5 Hz (periods in ms)
    CLOCK_PERIODS_MS = (100, 200, 400, 500, 800, 1000, 1600, 2000)

    def _update_system_memory(self) -> None:
        """S7 system memory byte: bit 0 FirstScan, bit 1 DiagStatusUpdate (FALSE here),
        bit 2 AlwaysTRUE, bit 3 AlwaysFALSE. Clock memory byte: square waves, 50 % duty,
        TRUE in the second half of each period."""
        if self.system_memory_byte is not None:
            self.memory[self.system_memory_byte] = (1 if self.ctx.first_scan else 0) | 0b100
        if self.clock_memory_byte is not None:
            now = self.ctx.now
            v = 0
            for bit, period in enumerate(self.CLOCK_PERIODS_MS):
                if now % period >= period // 2:
                    v |= 1 << bit
            self.memory[self.clock_memory_byte] = v

    def run(self, seconds: float | str | None = None, cycles: int | None = None) -> None:
        """Run for a duration of virtual time (``plc.run(seconds=5)``) or a number of scans."""
        if cycles is None:
            if seconds is None:
                raise PlcError("PLC3002", "run() needs seconds= or cycles=")
            ns = to_ns(seconds)
            if ns < 0:
                raise PlcError("PLC3011", f"run(seconds={seconds!r}): virtual time only moves "
                               "forward; give a duration >= 0")
            cycles = -(-ns // self._tick_ns)
            if cycles > MAX_SCANS:
                raise PlcError("PLC3011", f"run(seconds={seconds!r}) is {cycles:,} scans of "
                               f"{_fmt_ns(self._tick_ns)}; one call runs at most {MAX_SCANS:,}: "
                               "split the run into several calls")
        _check_count(cycles, "run: cycles")
        self.scan(cycles)  # the fast scan loop when it applies (same state, ADR 0024)

    def advance(self, duration: Any) -> None:
        """Run scans for ``duration`` of virtual time (``plc.advance('T#2s')``)."""
        self.run(seconds=duration)

    def stop(self) -> None:
        """Go to STOP: programs do not run and all outputs are switched off."""
        was = self.state
        self.state = "STOP"
        if was == "RUN":
            self._fire("stop")

    def start(self) -> None:
        """Back to RUN after STOP (a fault must be cleared with a restart)."""
        if self.fault is not None:
            raise PlcError("PLC3004", "the PLC stopped on a fault; call cold_restart() or "
                           "warm_restart() after fixing the program", self.fault.location)
        self.state = "RUN"
        self.outputs_enabled_in_stop = False  # going to RUN blocks the option (001 l. 4073)

    def _guard(self, fn):
        try:
            return fn()
        except PlcError:
            raise
        except BaseException as exc:  # noqa: BLE001
            raise self._translate(exc) from None

    def _to_stop(self, exc: BaseException) -> None:
        """A fault ends the scan like a real CPU going to STOP: outputs off, the cycle
        completes (the clock moves on), then the fault is raised to the caller."""
        fault = self._translate(exc)
        self.state = "STOP"
        self.fault = fault
        self.image_out[:] = bytes(self.image_size)
        self.outputs[:] = self.image_out
        ctx = self.ctx
        ctx.first_scan = False
        ctx.scan_count += 1
        ctx.now_ns += self._tick_ns
        ctx.now = ctx.now_ns // 1_000_000
        self._fire("stop")
        raise fault from None

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

    # -- variables ----------------------------------------------------------------------------
    def var(self, path: str) -> Var:
        """Resolve ``"Main.t1.ET"``, ``"LS1"``, ``"arr[3]"`` or ``"%QX0.0"``."""
        key = path.strip().upper()
        v = self._var_cache.get(key)
        if v is None:
            v = self._resolve(path.strip())
            self._var_cache[key] = v
        return v

    def __getitem__(self, path: str) -> Any:
        return self.var(path).get()

    def __setitem__(self, path: str, value: Any) -> None:
        v = self.var(path)
        v.set(convert_in(value, v.type, path))

    def get(self, path: str, iec: bool = False) -> Any:
        v = self.var(path)
        val = v.get()
        return format_typed(val, v.type, self.project.symbols.members) if iec else val

    def format(self, path: str) -> str:
        """The value as an IEC literal (``T#1s``, ``TRUE``, ``7.8``)."""
        return self.get(path, iec=True)

    def _access_var(self, path: str, access: Any) -> Var:
        """An access path (VAR_ACCESS) is the variable it names; READ_ONLY refuses writes."""
        v = self._resolve(access.target)
        if not access.read_only:
            return Var(path, v.type, v.get, v.set, v.address)

        def refuse(_value: Any) -> None:
            raise PlcError("PLC3013", f"{access.spelling} is a READ_ONLY access path; write {access.target} itself, or declare the access "
                           "path READ_WRITE")

        return Var(path, v.type, v.get, refuse, v.address)

    def _resolve(self, path: str) -> Var:
        if path.startswith("%"):
            return self._address_var(path)
        parts = _split_path(path)
        if not parts:
            raise PlcError("PLC3001", f"'{path}' is not a variable path")
        head, idx = parts[0]
        head_u = head.upper()
        progs = {n.upper(): pou for n, pou, _ in self.project.programs}

        def program(name: str):
            attr = name.replace(".", "__")  # RESA.MAIN: a resource's instance (ADR 0037)
            return lambda: getattr(self.ns["_P"], attr)

        res_globals = self.project.symbols.resource_globals
        if len(parts) > 1 and not idx and (head_u in res_globals or any(
                n.startswith(head_u + ".") for n in progs)):
            # RESA.MAIN.x (a program of resource RESA) or RESA.g (a global of RESA)
            second = parts[1][0].upper()
            key = f"{head_u}.{second}"
            if key in progs and (len(parts) > 2 or parts[1][1]):
                if parts[1][1]:
                    raise PlcError("PLC3001", f"{parts[1][0]} is a program, not an array")
                pou = progs[key]
                return self._walk(path, program(key), T.FBType(pou.name, pou), parts[2:],
                                  head_u)
            if second in res_globals.get(head_u, {}):
                return self._walk(path, lambda: self.ns[f"_RG_{head_u}"],
                                  _GlobalsType(self.project, head_u), parts[1:], head_u)

        access = self.project.symbols.access_paths.get(head_u)
        if access is not None and len(parts) == 1 and not idx:  # VAR_ACCESS of the configuration
            return self._access_var(path, access)
        # 1. a program instance name 2. a global 3. a variable of exactly one program
        if head_u in progs and (len(parts) > 1 or idx):
            if idx:
                raise PlcError("PLC3001", f"{head} is a program, not an array")
            pou = progs[head_u]
            own = self.project.symbols.program_access.get(pou.name, {})
            if len(parts) == 2 and not parts[1][1] and parts[1][0].upper() in own:
                # Inst.ax: the program's own VAR_ACCESS (ed.2/ed.3 program_access_decls)
                ap = own[parts[1][0].upper()]
                return self._access_var(path, _replace(
                    ap, target=f"{head}.{ap.target}"))
            return self._walk(path, program(head_u), T.FBType(pou.name, pou), parts[1:])
        if head_u in self.project.globals:
            return self._walk(path, lambda: self.ns["_G"], _GlobalsType(self.project), parts)
        owners = self.project.symbols.programs_declaring(head_u)
        if len(owners) == 1:
            n, pou = owners[0]
            return self._walk(path, program(n.upper()), T.FBType(pou.name, pou), parts)
        if len(owners) > 1:
            raise PlcError("PLC3001", f"{head} exists in several programs ("
                           + ", ".join(n for n, _ in owners) + f"); write e.g. "
                           f"{owners[0][0]}.{head}")
        from ..suggest import suggest

        symbols = self.project.symbols
        cands = [name for _, pou, _ in symbols.programs() for name in symbols.members(pou)]
        cands += list(self.project.globals) + [n for n, _, _ in self.project.programs]
        close = suggest(head_u, cands)
        hint = f"; did you mean {close[0]}?" if close else ""
        raise PlcError("PLC3001", f"no variable named {path}{hint}")

    def _walk(self, path: str, get_obj, ty: T.Type, parts, resource: str | None = None) -> Var:
        """Build getter/setter closures walking members and indices from a root object;
        ``resource``: the resource of the program instance walked (ADR 0037)."""
        steps: list[tuple[str, Any]] = []
        cur = ty
        address = None
        for name, idx in parts:
            cur = T.resolve(cur)
            nu = name.upper()
            if isinstance(cur, _GlobalsType):
                d = cur.globals().get(nu)
                address = d.address if d is not None else None
            elif isinstance(cur, T.FBType) and cur.pou is not None:
                d = self.project.symbols.members(cur.pou).get(nu)
                if d is not None and d.section == "VAR_TEMP":
                    d = None
                if d is not None and d.section == "VAR_EXTERNAL":
                    rest = [(name, idx)] + parts[parts.index((name, idx)) + 1:]
                    if resource and nu not in self.project.globals and nu in \
                            self.project.symbols.resource_globals.get(resource, {}):
                        return self._walk(path, lambda: self.ns[f"_RG_{resource}"],
                                          _GlobalsType(self.project, resource), rest)
                    return self._walk(path, lambda: self.ns["_G"], _GlobalsType(self.project),
                                      rest)
                address = d.address if d is not None else None
            elif isinstance(cur, T.StructType):
                d = cur.fields.get(nu)
            else:
                d = None
            if d is None:
                raise PlcError("PLC3001", f"{path}: {cur} has no member {name}")
            steps.append(("attr", nu))
            cur = d.ty
            for ixs in idx:
                at = T.resolve(cur)
                if not isinstance(at, T.ArrayType) or len(ixs) != len(at.dims):
                    raise PlcError("PLC3001", f"{path}: wrong index for {at}")
                flat, stride = 0, 1
                for i, (lo, hi) in reversed(list(zip(ixs, at.dims, strict=True))):
                    if not lo <= i <= hi:
                        raise PlcError("PLC3001", f"{path}: index {i} is outside {lo}..{hi}")
                    flat += (i - lo) * stride
                    stride *= hi - lo + 1
                steps.append(("item", flat))
                cur = at.elem
        final_t = cur

        def walk_to_parent():
            o = get_obj()
            for kind, key in steps[:-1]:
                o = getattr(o, key) if kind == "attr" else o[key]
            return o

        last_kind, last_key = steps[-1]
        if last_kind == "attr":
            def getter():
                return getattr(walk_to_parent(), last_key)

            def setter(v):
                setattr(walk_to_parent(), last_key, v)
                if address:  # a located variable is its bytes of the image (ADR 0056)
                    self._write_address(address, v, final_t, physical=True)
        else:
            def getter():
                return walk_to_parent()[last_key]

            def setter(v):
                walk_to_parent()[last_key] = v
        return Var(path, final_t, getter, setter, address)

    def _address_var(self, addr: str) -> Var:
        a = addr.upper()
        area, size, byte, bit = check_address(a, self.image_size)
        n = _SIZE_BYTES[size]
        ty = {"X": T.BOOL, "B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}[size]
        # reading %I gives the input terminals, %Q the output terminals, %M the memory
        buf = {"I": lambda: self.inputs, "Q": lambda: self.outputs, "M": lambda: self.memory}[area]

        def getter():
            b = buf()
            if size == "X":
                return bool(b[byte] >> int(bit) & 1)
            return int.from_bytes(b[byte:byte + n], "big")

        def setter(v):
            if area == "Q":
                self._write_bytes(self.image_out, size, byte, bit, v)
            self._write_bytes(buf(), size, byte, bit, v)

        return Var(addr, ty, getter, setter, a)

    @staticmethod
    def _write_bytes(b: bytearray, size: str, byte: int, bit, v) -> None:
        if size == "X":
            if v:
                b[byte] |= 1 << int(bit)
            else:
                b[byte] &= 0xFF ^ (1 << int(bit))
        else:
            n = {"B": 1, "W": 2, "D": 4, "L": 8}[size]
            b[byte:byte + n] = (int(v) & ((1 << (8 * n)) - 1)).to_bytes(n, "big")

    def _write_address(self, address: str, value: Any, ty: T.Type, physical: bool) -> None:
        import struct as _struct

        m = _ADDR_RE.fullmatch(address)
        if not m:
            return
        size = m.group(2) or "X"
        byte, bit = int(m.group(3)), m.group(4)
        # %I: the terminals (physical) or the frozen input image; %Q: the output image, which
        # the terminals follow at scan end; %M: the memory (ADR 0056)
        tgt = {"I": self.inputs if physical else self.image_in, "Q": self.image_out,
               "M": self.memory}[m.group(1)]
        t = T.base_of(ty)
        if t.kind == "real":
            fmt = ">f" if size == "D" else ">d"
            _struct.pack_into(fmt, tgt, byte, float(value))
        else:
            self._write_bytes(tgt, size, byte, bit, value)

    # -- forcing ------------------------------------------------------------------------------
    def force(self, path: str, value: Any) -> None:
        """Force a variable or address: it keeps ``value`` whatever the program or input does."""
        v = self.var(path)
        self.forced[path.upper()] = (v, convert_in(value, v.type, path))

    def unforce(self, path: str | None = None) -> None:
        if path is None:
            self.forced.clear()
        else:
            self.forced.pop(path.upper(), None)

    def _apply_forced_inputs(self) -> None:
        self._apply_inputs(self.forced.items())

    def _apply_inputs(self, items: Any) -> None:
        """Write values into the input image (or the variables) before the program reads them."""
        for key, (v, val) in items:
            if key.startswith("%I"):
                self._write_bytes(self.image_in, *self._addr_parts(key), val)
            elif key.startswith("%M"):
                self._write_bytes(self.memory, *self._addr_parts(key), val)
            elif v.address and v.address.startswith("%I"):
                self._write_address(v.address, val, v.type, physical=False)
            elif not key.startswith("%"):
                v.set(val)

    def _apply_forced_outputs(self) -> None:
        self._apply_outputs(self.forced.items())

    def _apply_outputs(self, items: Any) -> None:
        """Write values into the variables and the output image after the program ran."""
        for key, (v, val) in items:
            if key.startswith("%Q"):
                self._write_bytes(self.image_out, *self._addr_parts(key), val)
            elif key.startswith("%M"):
                self._write_bytes(self.memory, *self._addr_parts(key), val)
            elif not key.startswith("%") and not (v.address and v.address.startswith("%I")):
                v.set(val)
                if v.address and v.address.startswith("%Q"):
                    area_size = self._addr_parts(v.address)
                    self._write_bytes(self.image_out, *area_size, val)

    def _unforce_image(self, held: bytes) -> None:
        """A forced output *address* acts on the terminal, not on the output image the program
        and its located variables see (as S7's force of a peripheral output): after the
        terminals are written, its bits of the image go back to what the program wrote (ADR
        0056; the image is loaded into located variables at the next scan start)."""
        for key in self.forced:
            if key.startswith("%Q"):
                size, byte, bit = self._addr_parts(key)
                if size == "X":
                    mask = 1 << int(bit)
                    self.image_out[byte] = (self.image_out[byte] & ~mask & 0xFF) | \
                        (held[byte] & mask)
                else:
                    n = _SIZE_BYTES[size]
                    self.image_out[byte:byte + n] = held[byte:byte + n]

    @staticmethod
    def _addr_parts(addr: str):
        m = _ADDR_RE.fullmatch(addr.upper())
        assert m
        return m.group(2) or "X", int(m.group(3)), m.group(4)

    # -- trigger points, modify, outputs in STOP (ADR 0025; 001 lines 3890-4080) ----------------
    def modify(self, path: str, value: Any, at: str = "scan_start") -> None:
        """Write ``value`` to a variable or address ONCE at a trigger point (``"scan_start"``,
        after the inputs are read: best for inputs; ``"scan_end"``, before the outputs are
        written: best for outputs), unlike :meth:`force`, which holds it every scan."""
        if at not in ("scan_start", "scan_end"):
            raise PlcError("PLC6001", f"modify at {at!r}: a value is modified at 'scan_start' "
                           "or 'scan_end'")
        v = self.var(path)
        self.modified[at][path.upper()] = (v, convert_in(value, v.type, path))
        self._hooked = True

    def enable_outputs_in_stop(self, enable: bool = True) -> None:
        """TIA Portal's *Enable peripheral outputs*: in STOP, modified outputs reach the
        terminals (to test the wiring). Only in STOP, only with nothing forced; RUN clears it."""
        if enable and self.state == "RUN":
            raise PlcError("PLC6002", "outputs can be enabled only in STOP; call plc.stop() "
                           "first")
        if enable and self.forced:
            raise PlcError("PLC6002", "outputs cannot be enabled in STOP while values are "
                           f"forced ({', '.join(self.forced)}); call plc.unforce() first")
        self.outputs_enabled_in_stop = bool(enable)
        if enable:
            self.image_out[:] = bytes(self.image_size)

    @property
    def _watched(self) -> bool:
        return self._hooked

    def _rewatch(self) -> None:
        """Recompute ``_hooked`` after a trigger list or a pending modification changed."""
        self._hooked = any(self._watch_parts)

    def _take(self, at: str) -> list[tuple[str, Any]]:
        items = list(self.modified[at].items())
        self.modified[at].clear()
        self._rewatch()
        return items

    def _fire(self, at: str) -> None:
        for fn in tuple(self.triggers[at]):
            fn(self, at)

    def _stop_scan(self) -> None:
        """A scan in STOP: the program does not run; outputs are off unless enabled, when
        modified outputs reach the terminals. Watch tables still sample."""
        if self.outputs_enabled_in_stop:
            self._apply_outputs(self._take("scan_end") + self._take("scan_start"))
            self.outputs[:] = self.image_out
        else:
            self.outputs[:] = bytes(self.image_size)
        if self.triggers["scan_start"] or self.triggers["scan_end"]:
            self.image_in[:] = self.inputs
            self._fire("scan_start")
            self._fire("scan_end")

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


class _Hooks(list):
    """The callbacks of one trigger point (``plc.triggers[at]``): a list that calls
    ``changed()`` after every change, so the PLC keeps one flag instead of testing every
    trigger point on each ``scan()`` call (ADR 0034)."""

    __slots__ = ("_changed",)

    def __init__(self, changed: Any) -> None:
        super().__init__()
        self._changed = changed

    def __iadd__(self, other: Any) -> _Hooks:
        super().__iadd__(other)
        self._changed()
        return self


def _notifying(name: str) -> Any:
    method = getattr(list, name)

    def changed(self: _Hooks, *args: Any) -> Any:
        out = method(self, *args)
        self._changed()
        return out

    changed.__name__ = name
    return changed


for _name in ("append", "extend", "insert", "remove", "pop", "clear", "__setitem__",
              "__delitem__"):
    setattr(_Hooks, _name, _notifying(_name))
del _name


class _GlobalsType(T.Type):
    kind = "globals"
    name = "globals"

    def __init__(self, project, resource: str | None = None) -> None:
        self.project = project
        self.resource = resource  # the globals of this resource (ADR 0037)

    def globals(self) -> dict:
        if self.resource is not None:
            return self.project.symbols.resource_globals.get(self.resource, {})
        return self.project.globals


def _split_path(path: str) -> list[tuple[str, list[list[int]]]]:
    out = []
    for seg in _split_dots(path):
        m = _PATH_RE.fullmatch(seg.strip())
        if not m:
            raise PlcError("PLC3001", f"'{path}' is not a variable path (e.g. Main.t1.Q, "
                           "arr[2], %QX0.0)")
        idx = []
        for grp in re.findall(r"\[([^\]]*)\]", m.group(2)):
            try:
                idx.append([int(x) for x in grp.split(",")])
            except ValueError:
                raise PlcError("PLC3001", f"'{path}': indices must be integers") from None
        out.append((m.group(1), idx))
    return out


def _split_dots(path: str) -> list[str]:
    return split_outside_brackets(path, ".")


def convert_in(value: Any, ty: T.Type, path: str = "") -> Any:
    """Convert a Python value or an IEC literal string to the run-time form of ``ty``."""
    t = T.resolve(ty)
    if isinstance(value, str) and not isinstance(t, T.StringType):
        from .literals import parse_literal

        return parse_literal(value, t, path)
    if t is T.BOOL:
        if isinstance(value, bool | int):
            return bool(value)
    elif isinstance(t, T.EnumType):
        if isinstance(value, int):
            return value
    elif t.kind in ("int", "bits"):
        if isinstance(value, bool):
            return int(value)
        if isinstance(value, int):
            lo, hi = (t.lo, t.hi) if isinstance(t, T.Elementary | T.Subrange) else (None, None)
            if lo is not None and not lo <= value <= hi:
                raise PlcError("PLC3002", f"{path}: {value} does not fit {t} ({lo}..{hi})")
            return value
    elif t.kind == "real":
        if isinstance(value, int | float) and not isinstance(value, bool):
            from ..compile.real32 import f32

            return f32(float(value)) if t is T.REAL else float(value)
    elif t.kind == "time":
        if isinstance(value, _dt.timedelta):
            ns = round(value.total_seconds() * 1e9)
            return ns if t is T.LTIME else ns // 1_000_000
        if isinstance(value, int) and not isinstance(value, bool):
            return value
    elif isinstance(t, T.StringType):
        if isinstance(value, str):
            return value[: t.length]
    elif t.kind in ("date", "tod", "dt") and isinstance(value, int):
        return value
    elif t is T.ANY:
        return value
    raise PlcError("PLC3002", f"{path}: cannot store {value!r} in a {t} variable")


def _gcd_all(values: list[int]) -> int:
    g = 0
    for v in values:
        g = math.gcd(g, v)
    return g or 10_000_000


del sys
