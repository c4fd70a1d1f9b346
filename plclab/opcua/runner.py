"""The real-time runner: the operator panel's (:class:`plclab.scada.panel.Panel`), reused.

With a plant the server runs a :class:`plclab.sim.Simulation` (I/O modules, scenario faults,
alarms as a hook) paced to the wall clock by the panel's thread; without one,
:class:`BarePlc` gives a bare PLC the same ``step``/``time``/``scan`` face, so the one runner
serves both. Every access to the PLC goes through ``panel.lock``: a client sees whole scans.
"""

from __future__ import annotations

from typing import Any


class BarePlc:
    """A PLC without a plant, stepped like a Simulation (alarms read PLC variables)."""

    plant = None
    transfer = None

    def __init__(self, plc: Any) -> None:
        self.plc = plc
        self.scan = plc.tick_ns / 1e9
        self._alarms: Any = None

    @property
    def time(self) -> float:
        return self.plc.time

    def add_hook(self, alarms: Any) -> Any:
        self._alarms = alarms
        return alarms

    def step(self, n: int = 1) -> None:
        from plclab.errors import PlcRuntimeFault

        for _ in range(n):
            try:
                self.plc.scan()
            except PlcRuntimeFault:
                return  # the PLC is in STOP now; the tags turn BadOutOfService
            if self._alarms is not None:
                self._alarms.evaluate(self.plc.time, lambda tag: self.plc[tag])


def make_runner(sim: Any, alarms: Any = None, speed: float = 1.0) -> Any:
    """A started-later :class:`~plclab.scada.panel.Panel` around ``sim``."""
    from plclab.scada.panel import Panel

    return Panel(sim, alarms, None, speed=speed)
