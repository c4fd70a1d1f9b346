"""Washing machine for the SFC lab (textbook Fig. 32).

The SFC of the textbook: Start -> Fill -> Boiling (COTTON, 10 min) or Warming (SILK, 5 min)
-> Cooling (until the water is at most 40 degC) -> Stop.

Signals
-------
Panel: ``START`` (NO button), ``STOP`` (NC button, ``True`` while not pressed), and the mode
selector with two contacts ``COTTON`` and ``SILK`` (a three-position selector: cotton, off,
silk; the scenario should not set both), and the door switch ``DOOR`` (NC: ``True`` while the
door is closed). Actuators: ``FILL_VALVE``, ``DRAIN_VALVE``,
``HEATER``, ``MOTOR`` (drum). Sensors: ``LEVEL`` (litres), ``LEVEL_SW`` (pressure switch,
``True`` at or above ``level_full``), ``EMPTY`` (``True`` at or below ``level_empty``),
``TEMP`` (degC), ``DRUM_SPEED`` (rpm).

Physics
-------
``dV/dt = q_fill - q_drain`` (litres); water above ``capacity`` overflows. Energy::

    m c dT/dt = P * HEATER + rho c q_fill (T_in - T) - UA (T - T_amb)

integrated exactly per step; the heater only heats while covered (``element_level``), and
water cannot exceed 100 degC (the excess boils off). Cooling is by losses and, faster, by
exchanging water: drain and fill at the same time. The fill valve delivers what the drain pump
removes (both 0.5 l/s by default, ADR 0046), so exchanging water keeps the drum full: the water
cools as ``T_in + (T0 - T_in) exp(-q t / V)`` (losses aside), about 16 s per time constant
with 8 l, and an exchange that goes on after 40 degC wastes water instead of emptying the tub.
The drum speed follows ``MOTOR`` with a first-order lag.

Events: ``overflow``, ``dry_heating``, ``boiling``, ``drum_dry`` (drum turning with no water
for more than 10 s), ``door_open_running`` (the drum motor or the heater still on a second
after the door was opened).
"""

from __future__ import annotations

import math
from typing import Any

from .base import Plant, PlantError, bool_signal, real_signal

__all__ = ["Washer"]

C_WATER = 4186.0  # J/(kg K), 1 litre = 1 kg


class Washer(Plant):
    """Washing machine: fill, heat, wash, drain.

    Parameters
    ----------
    capacity : float
        Tub volume before overflow, l.
    fill_flow, drain_flow : float
        Flows of the open fill and drain valves, l/s (the drain pump is linear in the level
        below 2 litres). Equal by default, so that exchanging water (both open) keeps the level.
    level_full, level_empty : float
        Switching points of LEVEL_SW and EMPTY, l.
    heater_power : float
        Heater power, W.
    element_level : float
        The heater is covered above this volume, l.
    ua : float
        Heat-loss coefficient, W/K.
    t_amb, t_in : float
        Ambient and cold-water temperatures, degC.
    drum_speed : float
        Wash speed of the drum, rpm.
    drum_tau : float
        Drum spin-up/down time constant, s.
    max_dt : float
        Largest integration step, s.
    """

    name = "washer"
    title = "Washing machine for the SFC lab"
    EVENTS = {
        "overflow": "water ran over the tub",
        "dry_heating": "the heater is on but not covered by water",
        "boiling": "the water boils",
        "drum_dry": "the drum turned without water for more than 10 s",
        "door_open_running": "the drum motor or the heater stayed on with the door open",
    }
    FAULTS = {
        "heater_fail": "the heater is burnt out",
        "drain_blocked": "the drain is blocked: no water leaves",
        "fill_valve_stuck": "the fill valve sticks (param open: bool, default TRUE = stuck open)",
        "level_switch_stuck_off": "LEVEL_SW always reads FALSE",
    }

    def __init__(
        self,
        *,
        capacity: float = 30.0,
        fill_flow: float = 0.5,
        drain_flow: float = 0.5,
        level_full: float = 12.0,
        level_empty: float = 0.5,
        heater_power: float = 2500.0,
        element_level: float = 3.0,
        ua: float = 20.0,
        t_amb: float = 20.0,
        t_in: float = 15.0,
        drum_speed: float = 50.0,
        drum_tau: float = 1.5,
        max_dt: float = 0.5,
    ) -> None:
        if not 0 < level_empty < level_full <= capacity:
            raise PlantError("washer: need 0 < level_empty < level_full <= capacity")
        if fill_flow < 0 or drain_flow <= 0 or ua <= 0:
            raise PlantError("washer: need fill_flow >= 0, drain_flow > 0, ua > 0")
        self.capacity = float(capacity)
        self.fill_flow = float(fill_flow)
        self.drain_flow = float(drain_flow)
        self.level_full = float(level_full)
        self.level_empty = float(level_empty)
        self.heater_power = float(heater_power)
        self.element_level = float(element_level)
        self.ua = float(ua)
        self.t_amb = float(t_amb)
        self.t_in = float(t_in)
        self.drum_speed = float(drum_speed)
        self.drum_tau = float(drum_tau)
        self.max_dt = float(max_dt)
        super().__init__(
            [
                bool_signal("START", "panel", "start button, NO: TRUE while pressed"),
                bool_signal(
                    "STOP", "panel", "stop button, NC: TRUE while NOT pressed", initial=True
                ),
                bool_signal(
                    "COTTON", "panel", "mode selector contact COTTON (boil 10 min)", initial=True
                ),
                bool_signal("SILK", "panel", "mode selector contact SILK (warm 5 min)"),
                bool_signal(
                    "DOOR", "panel", "door switch, NC: TRUE while the door is closed", initial=True
                ),
                bool_signal("FILL_VALVE", "actuator", "cold water inlet valve"),
                bool_signal("DRAIN_VALVE", "actuator", "drain valve / pump"),
                bool_signal("HEATER", "actuator", "heating element"),
                bool_signal("MOTOR", "actuator", "drum motor"),
                real_signal("LEVEL", "sensor", "l", 0, self.capacity, "water in the tub"),
                bool_signal("LEVEL_SW", "sensor", "level pressure switch, TRUE when full"),
                bool_signal("EMPTY", "sensor", "TRUE when the tub is empty"),
                real_signal("TEMP", "sensor", "degC", 0, 100, "water temperature"),
                real_signal("DRUM_SPEED", "sensor", "rpm", 0, self.drum_speed, "drum speed"),
            ]
        )

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self.volume = 0.0
        self.temp = self.t_amb
        self.drum = 0.0
        self.volume_in = 0.0
        self.volume_out = 0.0
        self.volume_overflow = 0.0
        self.energy_in = 0.0
        self._dry_drum = 0.0
        self._door_run = 0.0
        self._flags = {"overflow": False, "dry": False, "boil": False, "drum": False,
                       "door": False}

    def _faults_changed(self) -> None:
        f = self._faults
        self._heater_ok = "heater_fail" not in f
        self._drain_blocked = "drain_blocked" in f
        stuck = f.get("fill_valve_stuck")
        self._fill_stuck: bool | None = None if stuck is None else bool(stuck.get("open", True))
        self._sw_off = "level_switch_stuck_off" in f

    def _advance(self, h: float) -> None:
        io = self._io
        flags = self._flags
        v = self.volume
        fill = io["FILL_VALVE"] if self._fill_stuck is None else self._fill_stuck
        q_in = self.fill_flow if fill else 0.0
        q_out = 0.0
        if io["DRAIN_VALVE"] and not self._drain_blocked:
            q_out = self.drain_flow * (1.0 if v >= 2.0 else v / 2.0)
        p = self.heater_power if io["HEATER"] and self._heater_ok else 0.0
        if p > 0.0 and v < self.element_level:
            if not flags["dry"]:
                flags["dry"] = True
                self._emit("dry_heating", "the heater is on but not covered by water")
            p = 0.0
        elif flags["dry"] and (p == 0.0 or v >= self.element_level):
            flags["dry"] = False
        m_c = max(v, 0.05) * C_WATER
        g_fill = C_WATER * q_in
        g = self.ua + g_fill
        t_eq = (p + g_fill * self.t_in + self.ua * self.t_amb) / g
        t = t_eq + (self.temp - t_eq) * math.exp(-g * h / m_c)
        self.energy_in += p * h
        vin = q_in * h
        vout = q_out * h
        avail = v + vin
        if vout > avail:
            vout = avail
        v = avail - vout
        if t > 100.0:
            boil = (t - 100.0) * m_c / 2.257e6
            v = max(v - boil, 0.0)
            t = 100.0
            if not flags["boil"]:
                flags["boil"] = True
                self._emit("boiling", "the water boils")
        elif flags["boil"] and t < 99.0:
            flags["boil"] = False
        if v > self.capacity:
            self.volume_overflow += v - self.capacity
            v = self.capacity
            if not flags["overflow"]:
                flags["overflow"] = True
                self._emit("overflow", "water runs out of the machine onto the floor")
        elif flags["overflow"] and v < self.capacity - 0.5:
            flags["overflow"] = False
        self.volume_in += vin
        self.volume_out += vout
        self.volume = v
        self.temp = t
        if (io["HEATER"] or io["MOTOR"]) and not io["DOOR"]:
            self._door_run += h  # a second of grace: the PLC and its relays react in a scan
            if self._door_run >= 1.0 and not flags["door"]:
                flags["door"] = True
                self._emit("door_open_running", "the drum motor or the heater is still on a "
                           "second after the door was opened")
        else:
            self._door_run = 0.0
            flags["door"] = False
        # drum
        target = self.drum_speed if io["MOTOR"] else 0.0
        d = self.drum
        if d != target:
            d += (target - d) * (h / self.drum_tau if h < self.drum_tau else 1.0)
            if -1e-3 < d - target < 1e-3:
                d = target
            self.drum = d
        if d > 1.0 and v < self.level_empty:
            self._dry_drum += h
            if self._dry_drum >= 10.0 and not flags["drum"]:
                flags["drum"] = True
                self._emit("drum_dry", "the drum turns without water")
        else:
            self._dry_drum = 0.0
            flags["drum"] = False

    def _outputs(self) -> None:
        io = self._io
        v = self.volume
        io["LEVEL"] = v
        io["LEVEL_SW"] = v >= self.level_full and not self._sw_off
        io["EMPTY"] = v <= self.level_empty
        io["TEMP"] = self.temp
        io["DRUM_SPEED"] = self.drum

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Volumes in litres and the heater energy in joules."""
        return {
            "volume_in": self.volume_in,
            "volume_out": self.volume_out,
            "volume_overflow": self.volume_overflow,
            "energy_in": self.energy_in,
        }

    def geometry(self) -> dict[str, Any]:
        return {
            "shapes": [
                {"type": "rect", "name": "cabinet", "x": 0.0, "y": 0.0, "w": 0.6, "h": 0.85},
                {"type": "circle", "name": "drum", "x": 0.3, "y": 0.45, "r": 0.25},
            ]
        }
