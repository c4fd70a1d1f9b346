"""The run loop of a :class:`~plclab.sim.simulation.Simulation`: step, run, the plain loop and the
fused one (:mod:`.fastloop`), events, stop conditions, PLC faults and state changes (a mixin,
moved out of simulation.py)."""


from __future__ import annotations

import gc
import math
import time as _time
from collections.abc import Callable
from typing import Any

from plclab.errors import PlcError, PlcRuntimeFault

from .durations import parse_ns
from .errors import did_you_mean, sim_error


class RunLoop:
    """Stepping and running (a mixin of Simulation)."""

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
