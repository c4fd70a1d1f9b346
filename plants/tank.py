"""Hydro-accumulator tank: a pump fills it, consumers draw from it (textbook Fig. 31).

The classic first lab: keep the level between the low switch LS1 and the high switch LS2 with
two-position control, ``M := ((NOT LS1) OR M) AND (NOT LS2);``.

Physics
-------
The liquid volume ``V`` (m3) in a tank of constant cross-section ``A`` obeys

``dV/dt = q_pump - q_outlet - q_demand - q_leak``

* ``q_pump = pump_flow * PUMP_SPEED/100`` while ``PUMP`` is on, reached with a first-order lag
  ``pump_tau``;
* ``q_outlet = cd * outlet_area * VALVE/100 * sqrt(2 g h)`` (Torricelli, ``h = V/A``);
* ``q_demand`` is the consumer demand profile (m3/s), drawn as long as there is water;
* ``q_leak = cd * leak_area * sqrt(2 g h)`` while the ``leak`` fault is active.

Integration is explicit Euler on the volume; the outflows of a step are limited to the water
actually present, and water above the rim is lost as overflow, so the books always balance:
``volume_in - volume_out - volume_overflow == volume - volume0`` (see :meth:`Tank.snapshot`).

``FAULT_LAMP`` is a panel lamp the PLC lights for a measurement fault (wire-break lab); the plant
only shows it.

Events: ``overflow`` (the level reaches the rim), ``dry_run`` (the outlet or the consumers draw
from an empty tank).
"""

from __future__ import annotations

import math
from typing import Any

from .base import Plant, PlantError, ProfileSpec, StepProfile, bool_signal, real_signal

__all__ = ["Tank"]

_sqrt = math.sqrt


class Tank(Plant):
    """Hydro-accumulator with pump, outlet valve, consumer demand and level instruments.

    Parameters
    ----------
    area : float
        Cross-section of the tank, m2.
    height : float
        Height of the rim above the bottom, m (also the 20 mA point of the transmitter).
    level0 : float
        Level after reset, m.
    pump_flow : float
        Pump flow at 100 % speed, m3/s.
    pump_tau : float
        Time constant of the pump flow after switching, s (0: instant).
    outlet_area : float
        Open area of the outlet valve at 100 %, m2.
    cd : float
        Discharge coefficient of the outlet (and of a leak).
    valve : float
        Initial outlet valve opening, % (the scenario changes it through ``VALVE``).
    demand : float, list of (time_s, m3/s) or callable, optional
        Consumer demand drawn from the tank in addition to the outlet.
    ls1_height, ls2_height : float
        Heights of the low and high level switches, m.
    g : float
        Gravity, m/s2.
    max_dt : float
        Largest integration step, s.

    Examples
    --------
    >>> tank = Tank()
    >>> tank.write("PUMP", True)
    >>> for _ in range(1000):
    ...     tank.step(0.1)
    >>> round(tank.read("LEVEL"), 2) > 0.2
    True
    """

    name = "tank"
    title = "Hydro-accumulator tank with pump, outlet and level switches"
    EVENTS = {
        "overflow": "the level reached the rim; the excess is lost (volume_overflow)",
        "dry_run": "the outlet or the consumers drew from an empty tank",
    }
    FAULTS = {
        "leak": "a hole in the tank wall drains extra water (param area, m2, default 2e-4)",
        "ls1_stuck_off": "low level switch LS1 always reads FALSE",
        "ls2_stuck_off": "high level switch LS2 always reads FALSE",
        "pump_fail": "the pump motor turns but delivers nothing",
        "transmitter_open": "the 4-20 mA loop is broken: LEVEL_MA reads 0 mA",
        "transmitter_fail": "the transmitter detects its own failure and drives the loop to a "
        "NAMUR NE43 failure current (param ma, default 3.4 mA; 21.5 for an upscale failure)",
    }

    def __init__(
        self,
        *,
        area: float = 1.0,
        height: float = 2.0,
        level0: float = 0.2,
        pump_flow: float = 0.005,
        pump_tau: float = 0.5,
        outlet_area: float = 0.001,
        cd: float = 0.62,
        valve: float = 100.0,
        demand: ProfileSpec = None,
        ls1_height: float = 0.5,
        ls2_height: float = 1.5,
        g: float = 9.81,
        max_dt: float = 0.1,
    ) -> None:
        if area <= 0 or height <= 0 or pump_flow < 0 or outlet_area < 0 or max_dt <= 0:
            raise PlantError("tank: area, height, max_dt must be > 0; flows and areas >= 0")
        if not 0.0 <= ls1_height < ls2_height <= height:
            raise PlantError(
                f"tank: need 0 <= ls1_height < ls2_height <= height, got {ls1_height}, "
                f"{ls2_height}, {height}"
            )
        if not 0.0 <= level0 <= height:
            raise PlantError(f"tank: level0 must be within 0..height ({height} m), got {level0}")
        self.area = float(area)
        self.height = float(height)
        self.level0 = float(level0)
        self.pump_flow = float(pump_flow)
        self.pump_tau = float(pump_tau)
        self.outlet_area = float(outlet_area)
        self.cd = float(cd)
        self.ls1_height = float(ls1_height)
        self.ls2_height = float(ls2_height)
        self.g = float(g)
        self.max_dt = float(max_dt)
        self.demand = StepProfile(demand, "tank demand")
        self._vmax = self.area * self.height
        self._inv_area = 1.0 / self.area
        self._k_out = self.cd * self.outlet_area * math.sqrt(2.0 * self.g) * 0.01  # per % open
        qmax = self.pump_flow
        super().__init__(
            [
                bool_signal("PUMP", "actuator", "pump motor contactor, TRUE = run"),
                real_signal(
                    "PUMP_SPEED", "actuator", "%", 0, 100, "pump speed (frequency drive)", 100.0
                ),
                real_signal(
                    "VALVE", "panel", "%", 0, 100, "outlet valve opening (the consumer)", valve
                ),
                bool_signal("LS1", "sensor", "low level switch, TRUE when liquid at/above it"),
                bool_signal("LS2", "sensor", "high level switch, TRUE when liquid at/above it"),
                real_signal("LEVEL", "sensor", "m", 0, self.height, "liquid level"),
                real_signal(
                    "LEVEL_MA", "sensor", "mA", 0, 20, "level transmitter 4-20 mA over 0..height"
                ),
                real_signal("FLOW_IN", "sensor", "m3/s", 0, qmax, "pump delivery"),
                bool_signal("FAULT_LAMP", "lamp", "measurement fault lamp on the panel"),
            ]
        )

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self.volume = self.level0 * self.area
        self.volume0 = self.volume
        self.q_pump = 0.0
        self.q_out = 0.0
        self.volume_in = 0.0
        self.volume_out = 0.0
        self.volume_overflow = 0.0
        self.volume_demand = 0.0
        self.volume_leak = 0.0
        self._overflowing = False
        self._dry = False
        self.demand.reset()
        self._no_demand = self.demand.is_zero  # asked every step otherwise (issue 19)

    def _faults_changed(self) -> None:
        f = self._faults
        self._pump_failed = "pump_fail" in f
        self._ls1_off = "ls1_stuck_off" in f
        self._ls2_off = "ls2_stuck_off" in f
        self._tx_open = "transmitter_open" in f
        fail = f.get("transmitter_fail")
        self._tx_fail_ma = None if fail is None else float(fail.get("ma", 3.4))
        leak = f.get("leak")
        self._k_leak = (
            0.0
            if leak is None
            else self.cd * float(leak.get("area", 2e-4)) * math.sqrt(2.0 * self.g)
        )

    def _advance(self, h: float) -> None:
        io = self._io
        # pump with first-order flow lag
        target = (
            self.pump_flow * io["PUMP_SPEED"] * 0.01
            if io["PUMP"] and not self._pump_failed
            else 0.0
        )
        q = self.q_pump
        if q != target:
            tau = self.pump_tau
            if tau <= 0.0:
                q = target
            else:
                q += (target - q) * (1.0 - math.exp(-h / tau))
                if -1e-9 * self.pump_flow < q - target < 1e-9 * self.pump_flow:
                    q = target
            self.q_pump = q
        v = self.volume
        vin = q * h
        # outflows from the head at the start of the step
        sq = _sqrt(v * self._inv_area) if v > 0.0 else 0.0
        q_valve = self._k_out * io["VALVE"] * sq
        q_dem = 0.0 if self._no_demand else self.demand(self.time)
        q_leak = self._k_leak * sq
        want = (q_valve + q_dem + q_leak) * h
        avail = v + vin
        if want > avail:
            scale = avail / want
            if not self._dry:
                self._dry = True
                self._emit(
                    "dry_run",
                    "the tank ran empty while water was being drawn from it",
                    level=0.0,
                )
        else:
            scale = 1.0
            if self._dry and v > 0.01 * self.area:
                self._dry = False
        out = want * scale
        self.q_out = out / h
        self.volume_out += out
        if q_dem:
            self.volume_demand += q_dem * h * scale
        if q_leak:
            self.volume_leak += q_leak * h * scale
        self.volume_in += vin
        v = avail - out
        if v > self._vmax:
            self.volume_overflow += v - self._vmax
            v = self._vmax
            if not self._overflowing:
                self._overflowing = True
                self._emit(
                    "overflow", "the tank overflowed: water runs over the rim", level=self.height
                )
        else:
            if v < 0.0:
                v = 0.0
            if self._overflowing and v < self._vmax - 0.01 * self.area:
                self._overflowing = False
        self.volume = v

    def _outputs(self) -> None:
        io = self._io
        lvl = self.volume * self._inv_area
        io["LEVEL"] = lvl
        io["LS1"] = lvl >= self.ls1_height and not self._ls1_off
        io["LS2"] = lvl >= self.ls2_height and not self._ls2_off
        if self._tx_open:
            io["LEVEL_MA"] = 0.0
        elif self._tx_fail_ma is not None:
            io["LEVEL_MA"] = self._tx_fail_ma
        else:
            io["LEVEL_MA"] = 4.0 + 16.0 * lvl / self.height
        io["FLOW_IN"] = self.q_pump

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Volumes for a mass balance, flows and the level.

        ``volume_in - volume_out - volume_overflow == volume - volume0`` holds to rounding.
        ``volume_out`` includes the demand and the leak (also given separately).
        """
        return {
            "volume": self.volume,
            "volume0": self.volume0,
            "volume_in": self.volume_in,
            "volume_out": self.volume_out,
            "volume_overflow": self.volume_overflow,
            "volume_demand": self.volume_demand,
            "volume_leak": self.volume_leak,
            "q_pump": self.q_pump,
            "q_out": self.q_out,
        }

    def geometry(self) -> dict[str, Any]:
        w = math.sqrt(self.area)
        return {
            "shapes": [
                {"type": "rect", "name": "tank", "x": 0.0, "y": 0.0, "w": w, "h": self.height},
                {"type": "mark", "name": "LS1", "x": w, "y": self.ls1_height},
                {"type": "mark", "name": "LS2", "x": w, "y": self.ls2_height},
            ],
            "fill": {"signal": "LEVEL", "x": 0.0, "y": 0.0, "w": w},
        }
