"""Plastic press: heated container, hydraulic piston with encoder dosing, safety inputs (Fig. 100).

The textbook's real-time example: the computer must keep the plastic temperature in a narrow
band **and** at the same time move the piston, counting encoder pulses to dose the plastic.
Here the piston moves vertically; ``DOWN`` extrudes, ``UP`` retracts (and refills).

Signals
-------
* ``DOWN``/``UP`` are the two solenoids of the hydraulic valve; both or neither: the piston stops.
* ``TOP``/``BOTTOM`` are end switches, ``True`` within ``end_switch_margin`` mm of the end.
  The mechanical stops are at 0 and ``stroke`` mm; hitting one while still driven is a ``crash``.
* ``ENCODER_PULSE`` is a square wave, ``pulses_per_mm`` periods per mm of travel, derived from
  the position (``frac(position * pulses_per_mm) >= 0.5``), so the number of rising edges equals
  the pulses travelled. A PLC counts them exactly only if it samples every half period at least
  once: with the defaults (25 mm/s, 1 pulse/mm) a half period lasts 20 ms. Step the plant at
  ``max_dt`` (2 ms) or finer for a faithful pulse train.
* ``POSITION`` (mm, 0 = top) and ``TEMP`` (degC) are the true values.
* Safety, all panel inputs set by the scenario: ``HAND_L``/``HAND_R`` two-hand buttons (NO),
  ``LIGHT_CURTAIN`` (``True`` = clear, ``False`` = something in the field), ``E_STOP`` (NC,
  ``True`` while not pressed). With ``estop_hardwired=True`` a pressed E-stop de-energises both
  solenoids in hardware, whatever the PLC writes.

Physics
-------
Piston speed follows the valve command with a first-order lag ``valve_tau``: ``+v_down`` mm/s
for ``DOWN``, ``-v_up`` for ``UP``. The dosed volume is ``piston_area * travel down``. Heat:
``C dT/dt = P * HEATER - UA (T - T_amb)`` integrated exactly per step.

Events: ``moved_without_two_hands`` (the DOWN solenoid drives the piston down while not both
hands are on their buttons), ``curtain_violation`` (moving while the curtain is broken); both
only after the condition lasted longer than ``reaction_time`` (50 ms), so a PLC that reacts
within a few scans is not blamed for the valve's lag; ``crash`` (driven into a mechanical
stop), ``cold_extrusion`` (extruding below ``t_melt``), ``overheat`` (above ``t_degrade``),
``valve_conflict`` (both solenoids on).
"""

from __future__ import annotations

import math
from typing import Any

from .base import Plant, PlantError, bool_signal, real_signal

__all__ = ["Press"]


class Press(Plant):
    """Plastic press with heated container, hydraulic piston, encoder and safety inputs.

    Parameters
    ----------
    stroke : float
        Piston stroke between the mechanical stops, mm.
    position0 : float
        Position after reset, mm (0 = top).
    v_down, v_up : float
        Piston speeds, mm/s.
    valve_tau : float
        Time constant of the piston speed after a valve change, s.
    pulses_per_mm : float
        Encoder pulses per mm of travel.
    end_switch_margin : float
        End switches close this far before the mechanical stops, mm.
    piston_area : float
        Piston area, cm2 (dosed volume in cm3 = area * travel in cm).
    heater_power : float
        Heater power, W.
    heat_capacity : float
        Heat capacity of the container and plastic, J/K.
    ua : float
        Heat-loss coefficient, W/K.
    t_amb : float
        Ambient temperature, degC.
    t0 : float or None
        Plastic temperature after reset, degC (default ``t_amb``).
    t_melt, t_degrade : float
        Lowest temperature for extrusion and the temperature where the plastic degrades, degC.
    estop_hardwired : bool
        A pressed E_STOP cuts the solenoids in hardware.
    reaction_time : float
        Allowance before a safety violation is reported: the piston may move on for this long
        after a hand left its button or the curtain was broken (the PLC needs a scan or two and
        the valve needs to close), s.
    max_dt : float
        Largest integration step, s.
    """

    name = "press"
    title = "Plastic press: heater, hydraulic piston with encoder, two-hand and light curtain"
    EVENTS = {
        "moved_without_two_hands": "the piston was driven down without both hands on the buttons",
        "curtain_violation": "the piston moved while the light curtain was broken",
        "crash": "the piston was driven into a mechanical end stop",
        "cold_extrusion": "extruding below the melt temperature",
        "overheat": "the plastic was heated above the degradation temperature",
        "valve_conflict": "DOWN and UP were both on",
    }
    FAULTS = {
        "encoder_fail": "the encoder output freezes: no more pulses",
        "heater_fail": "the heater is burnt out",
        "down_valve_stuck": "the DOWN solenoid valve sticks open: the piston keeps going down",
        "bottom_switch_fail": "the BOTTOM end switch always reads FALSE",
    }

    def __init__(
        self,
        *,
        stroke: float = 200.0,
        position0: float = 0.0,
        v_down: float = 25.0,
        v_up: float = 50.0,
        valve_tau: float = 0.03,
        pulses_per_mm: float = 1.0,
        end_switch_margin: float = 2.0,
        piston_area: float = 20.0,
        heater_power: float = 1500.0,
        heat_capacity: float = 3000.0,
        ua: float = 4.0,
        t_amb: float = 20.0,
        t0: float | None = None,
        t_melt: float = 180.0,
        t_degrade: float = 260.0,
        estop_hardwired: bool = True,
        reaction_time: float = 0.05,
        max_dt: float = 0.002,
    ) -> None:
        if stroke <= 2 * end_switch_margin or v_down <= 0 or v_up <= 0 or pulses_per_mm <= 0:
            raise PlantError("press: need stroke > 2*end_switch_margin and positive speeds")
        if not 0.0 <= position0 <= stroke:
            raise PlantError("press: position0 must be within 0..stroke")
        self.stroke = float(stroke)
        self.position0 = float(position0)
        self.v_down = float(v_down)
        self.v_up = float(v_up)
        self.valve_tau = float(valve_tau)
        self.pulses_per_mm = float(pulses_per_mm)
        self.end_switch_margin = float(end_switch_margin)
        self.piston_area = float(piston_area)
        self.heater_power = float(heater_power)
        self.heat_capacity = float(heat_capacity)
        self.ua = float(ua)
        self.t_amb = float(t_amb)
        self.t0 = self.t_amb if t0 is None else float(t0)
        self.t_melt = float(t_melt)
        self.t_degrade = float(t_degrade)
        self.estop_hardwired = bool(estop_hardwired)
        self.reaction_time = float(reaction_time)
        self.max_dt = float(max_dt)
        super().__init__(
            [
                bool_signal("HAND_L", "panel", "left two-hand button, NO: TRUE while pressed"),
                bool_signal("HAND_R", "panel", "right two-hand button, NO: TRUE while pressed"),
                bool_signal(
                    "LIGHT_CURTAIN", "panel", "light curtain, TRUE = field clear", initial=True
                ),
                bool_signal(
                    "E_STOP", "panel", "emergency stop, NC: TRUE while NOT pressed", initial=True
                ),
                bool_signal("DOWN", "actuator", "valve solenoid: piston down (extrude)"),
                bool_signal("UP", "actuator", "valve solenoid: piston up (retract)"),
                bool_signal("HEATER", "actuator", "container heater"),
                bool_signal("TOP", "sensor", "top end switch"),
                bool_signal("BOTTOM", "sensor", "bottom end switch"),
                bool_signal("ENCODER_PULSE", "sensor", "encoder pulse train"),
                real_signal("POSITION", "sensor", "mm", 0, self.stroke, "piston position, 0 = top"),
                real_signal("TEMP", "sensor", "degC", 0, 400, "plastic temperature"),
            ]
        )

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self.position = self.position0
        self.velocity = 0.0
        self.temp = self.t0
        self.travel_down = 0.0
        self.strokes = 0
        self._stroke_start: float | None = None
        self._pulse_frozen: bool | None = None
        self._ev = {
            "hands": False,
            "curtain": False,
            "crash": False,
            "cold": False,
            "hot": False,
            "conflict": False,
        }
        self.crashes = 0
        self.violations = 0
        self._hands_t = 0.0
        self._curtain_t = 0.0

    def _faults_changed(self) -> None:
        f = self._faults
        self._heater_ok = "heater_fail" not in f
        self._down_stuck = "down_valve_stuck" in f
        self._bottom_fail = "bottom_switch_fail" in f
        if "encoder_fail" not in f:
            self._pulse_frozen = None

    def _on_inject(self, fault: str, params: dict[str, Any]) -> None:
        if fault == "encoder_fail":
            self._pulse_frozen = bool(self._io["ENCODER_PULSE"])

    def _advance(self, h: float) -> None:
        io = self._io
        ev = self._ev
        powered = io["E_STOP"] or not self.estop_hardwired
        down = (io["DOWN"] or self._down_stuck) and powered
        up = io["UP"] and powered
        if down and up:
            target = 0.0
            if not ev["conflict"]:
                ev["conflict"] = True
                self._emit("valve_conflict", "DOWN and UP are both on: the piston is blocked")
        else:
            ev["conflict"] = False
            target = self.v_down if down else -self.v_up if up else 0.0
        v = self.velocity
        if v != target:
            tau = self.valve_tau
            v += (target - v) * (h / tau if h < tau else 1.0)
            if -1e-6 < v - target < 1e-6:
                v = target
        pos = self.position + v * h
        if pos >= self.stroke or pos <= 0.0:
            end = self.stroke if pos >= self.stroke else 0.0
            if v != 0.0 and not ev["crash"]:
                ev["crash"] = True
                self.crashes += 1
                where = "bottom" if end else "top"
                self._emit(
                    "crash",
                    f"the piston was driven into the {where} stop at {abs(v):.1f} mm/s",
                    speed=abs(v),
                    position=end,
                )
            pos = end
            v = 0.0
        elif ev["crash"] and self.end_switch_margin < pos < self.stroke - self.end_switch_margin:
            ev["crash"] = False
        if v > 0.0:
            self.travel_down += pos - self.position
            if self._stroke_start is None:
                self._stroke_start = self.position
        elif self._stroke_start is not None and v <= 0.0:
            self.strokes += 1
            self._stroke_start = None
        self.position = pos
        self.velocity = v
        # safety supervision: a violation lasting longer than the reaction allowance
        moving = v > 0.5 or v < -0.5
        both = io["HAND_L"] and io["HAND_R"]
        grace = self.reaction_time
        if down and v > 0.5 and not both:
            self._hands_t += h
            if self._hands_t > grace and not ev["hands"]:
                ev["hands"] = True
                self.violations += 1
                self._emit(
                    "moved_without_two_hands",
                    "the piston moves down while not both hands are on their buttons",
                )
        else:
            self._hands_t = 0.0
            ev["hands"] = False
        # as for the two hands: only while a valve is commanded, so the valve's own lag after
        # a PLC that stopped at once is not blamed on the PLC
        commanded = down or io["UP"]
        if moving and commanded and not io["LIGHT_CURTAIN"]:
            self._curtain_t += h
            if self._curtain_t > grace and not ev["curtain"]:
                ev["curtain"] = True
                self.violations += 1
                self._emit(
                    "curtain_violation", "the piston moves while the light curtain is broken"
                )
        else:
            self._curtain_t = 0.0
            ev["curtain"] = False
        # temperature
        p = self.heater_power if io["HEATER"] and self._heater_ok else 0.0
        t_eq = self.t_amb + p / self.ua
        self.temp = t_eq + (self.temp - t_eq) * math.exp(-self.ua * h / self.heat_capacity)
        t = self.temp
        if v > 0.5 and t < self.t_melt:
            if not ev["cold"]:
                ev["cold"] = True
                self._emit(
                    "cold_extrusion", f"extruding at {t:.0f} degC, below {self.t_melt} degC", temp=t
                )
        elif ev["cold"] and v <= 0.0:
            ev["cold"] = False
        if t >= self.t_degrade:
            if not ev["hot"]:
                ev["hot"] = True
                self._emit("overheat", f"the plastic degrades above {self.t_degrade} degC", temp=t)
        elif ev["hot"] and t < self.t_degrade - 5.0:
            ev["hot"] = False

    def _outputs(self) -> None:
        io = self._io
        pos = self.position
        io["POSITION"] = pos
        io["TOP"] = pos <= self.end_switch_margin
        io["BOTTOM"] = pos >= self.stroke - self.end_switch_margin and not self._bottom_fail
        if self._pulse_frozen is None:
            phase = pos * self.pulses_per_mm
            io["ENCODER_PULSE"] = phase - math.floor(phase) >= 0.5
        else:
            io["ENCODER_PULSE"] = self._pulse_frozen
        io["TEMP"] = self.temp

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Encoder count, dosed volume, speed and counters."""
        return {
            "velocity": self.velocity,
            "encoder_count": float(math.floor(self.position * self.pulses_per_mm + 0.5)),
            "travel_down": self.travel_down,
            "dosed_volume": self.travel_down * 0.1 * self.piston_area,
            "strokes": float(self.strokes),
            "crashes": float(self.crashes),
            "violations": float(self.violations),
        }

    def geometry(self) -> dict[str, Any]:
        s = self.stroke / 1000.0
        return {
            "shapes": [
                {"type": "rect", "name": "cylinder", "x": -0.05, "y": -s, "w": 0.1, "h": s},
                {"type": "mark", "name": "TOP", "x": 0.06, "y": -self.end_switch_margin / 1000},
                {
                    "type": "mark",
                    "name": "BOTTOM",
                    "x": 0.06,
                    "y": -(self.stroke - self.end_switch_margin) / 1000,
                },
            ],
            "piston": {"signal": "POSITION", "scale": -0.001},
        }
