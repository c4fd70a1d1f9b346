"""The scan cycle of :class:`~plclab.runtime.plc.Plc`: ``scan()`` and its fast paths, the prebound
``scanner()``, STOP and RUN, faults (a mixin, moved out of plc.py)."""


from __future__ import annotations

from typing import Any

from ..errors import PlcError
from .plc_limits import (
    MAX_SCANS,
    check_count,
    fmt_ns,
    to_ns,
)


class ScanCycle:
    """The scan cycle (a mixin of Plc)."""

    # -- the scan cycle -----------------------------------------------------------------------
    @property
    def time(self) -> float:
        """Virtual time in seconds."""
        return self.ctx.now_ns / 1e9

    @property
    def scan_count(self) -> int:
        return self.ctx.scan_count

    @property
    def state(self) -> str:
        """``"RUN"`` or ``"STOP"``."""
        return self._state

    @state.setter
    def state(self, value: str) -> None:
        self._state = value
        self._reselect()

    def _reselect(self) -> None:
        """Whether the generated scan may run (RUN, nothing forced, no trigger point or pending
        modification): called where any of these changes (ADR 0058)."""
        live = getattr(self, "_live", None)
        if live is not None:
            live[0] = (getattr(self, "_state", None) == "RUN" and not self.forced
                       and not getattr(self, "_hooked", True))

    def scan(self, n: int = 1) -> None:
        """Run ``n`` scan cycles: freeze inputs, run due tasks, write outputs, advance clock.

        The general path: ``plc.scan`` is the PLC's generated scan (:mod:`.scan_gen`), which
        comes here for ``n`` other than 1 and outside the common case."""
        if n.__class__ is not int or not 0 <= n <= MAX_SCANS:
            check_count(n, "scan: n")
        if not self._live[0] or n < 1:
            for _ in range(n):
                self._scan_once()
            return
        if n == 1:
            self._unchecked()
        elif self._single is not None and not self._system_bytes:
            self._fast_scans(n)
        else:  # several tasks or system bytes: the generated scan n times
            one = self._unchecked
            for _ in range(n):
                one()

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
        """A function that runs one scan, as ``scan()`` does, at less cost per call: the PLC's
        generated scan (:mod:`.scan_gen`, ADR 0058), which the simulation calls every cycle.
        Outside the common case (STOP, forced values, a watch table's trigger points or a
        pending modify) it hands the call to the general :meth:`scan`; after a restart the
        function of the old program does too.

        Its ``ready()`` tells whether the common case holds, and ``unchecked()`` runs the scan
        without looking: for a caller that knows what can change between its scans (the
        simulation's fused loop, ADR 0032), only a fault (state STOP) can end the common case
        while nothing but the scans themselves runs."""
        return self.scan

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
                               f"{fmt_ns(self._tick_ns)}; one call runs at most {MAX_SCANS:,}: "
                               "split the run into several calls")
        check_count(cycles, "run: cycles")
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
