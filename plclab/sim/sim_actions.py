"""Scenario actions of a :class:`~plclab.sim.simulation.Simulation`: compiled once into timed
operations (buttons, set points, ramps, I/O faults), run when due (a mixin, moved out of
simulation.py)."""


from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from plclab.errors import PlcError

from .errors import did_you_mean
from .scenario import Action, Scenario


class ScenarioActions:
    """Scenario actions (a mixin of Simulation)."""

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
        valid = ch.kind.faults  # the module kind's own fault table (plclab.io.modules)
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
