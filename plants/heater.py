"""Water heater (boiler): a tank of water with a heating element, a steam coil, fill and drain.

The boiler of the textbook's HMI chapter (fill valve, drain valve, electric element, level and
temperature limits) and the steam-valve temperature loop of its PID section.

Physics
-------
Volume: ``dV/dt = q_fill - q_drain - q_demand`` with ``q_drain`` by Torricelli through the drain
valve and ``q_demand`` a hot-water demand profile. Energy, with ``m = rho V`` and ``c`` the
specific heat of water::

    m c dT/dt = P_el + P_steam + rho c q_fill (T_in - T) - UA (T - T_amb)

``P_el = p_max * u`` where ``u = 1`` while ``HEATER`` is on and ``POWER/100`` otherwise (so
either a relay or a thyristor controller can drive the element); the element only heats the
water while it is submerged (level above ``element_height``), otherwise the event
``dry_heating`` is raised and no heat reaches the water. ``P_steam = steam_power *
STEAM_VALVE/100``. Over one step the right-hand side is linear in ``T`` and is integrated exactly
(exponential update), so any step size is stable. Water cannot exceed 100 degC: the excess energy
evaporates water (event ``boiling``).

Analytic steady state with no flow: ``T_ss = T_amb + P / UA`` (see
:meth:`Heater.steady_state_temperature`), reached with time constant ``rho V c / UA``.

Temperature sensor
------------------
``TEMP_RTD_OHM`` is a Pt100 (IEC 60751, Callendar-Van Dusen):
``R = R0 (1 + A T + B T^2)`` for ``T >= 0`` and ``R = R0 (1 + A T + B T^2 + C (T - 100) T^3)``
below 0 degC, with ``R0 = 100``, ``A = 3.9083e-3``, ``B = -5.775e-7``, ``C = -4.183e-12``.
``TEMP`` is the true water temperature (for recording and for simple labs).
"""

from __future__ import annotations

import math
from typing import Any

from .base import Plant, PlantError, ProfileSpec, StepProfile, bool_signal, real_signal

__all__ = ["Heater", "pt100_ohm"]

RHO = 1000.0  # kg/m3
C_WATER = 4186.0  # J/(kg K)
H_EVAP = 2.257e6  # J/kg
PT_R0 = 100.0
PT_A = 3.9083e-3
PT_B = -5.775e-7
PT_C = -4.183e-12
OPEN_CIRCUIT_OHM = 1.0e6


def pt100_ohm(t: float) -> float:
    """Resistance of a Pt100 at ``t`` degC (IEC 60751).

    Examples
    --------
    >>> round(pt100_ohm(0.0), 3), round(pt100_ohm(100.0), 3)
    (100.0, 138.505)
    """
    r = 1.0 + PT_A * t + PT_B * t * t
    if t < 0.0:
        r += PT_C * (t - 100.0) * t * t * t
    return PT_R0 * r


class Heater(Plant):
    """Boiler tank with electric element, steam coil, fill/drain valves and instruments.

    Parameters
    ----------
    area : float
        Tank cross-section, m2.
    height : float
        Tank height (overflow), m.
    level0 : float
        Level after reset, m.
    t0 : float or None
        Water temperature after reset, degC (default ``t_amb``).
    t_amb : float
        Ambient temperature, degC.
    t_in : float
        Temperature of the cold fill water, degC.
    p_max : float
        Element power at 100 %, W.
    steam_power : float
        Heat from the steam coil with the valve fully open, W.
    ua : float
        Heat-loss coefficient to ambient, W/K.
    fill_flow : float
        Flow through the open fill valve, m3/s.
    drain_area : float
        Effective area of the open drain valve (Torricelli, Cd included), m2.
    demand : float, list of (time_s, m3/s) or callable, optional
        Hot-water demand drawn from the tank.
    element_height : float
        The element is covered by water above this level, m.
    level_min, level_max : float
        Heights of the min/max level switches, m.
    t_max : float
        Switching temperature of the over-temperature thermostat, degC.
    max_dt : float
        Largest integration step, s.
    """

    name = "heater"
    title = "Water heater (boiler) with element, steam coil, fill/drain and Pt100"
    EVENTS = {
        "dry_heating": "the element is on but not covered by water",
        "boiling": "the water reached 100 degC and boils",
        "overflow": "the boiler overflowed",
    }
    FAULTS = {
        "sensor_open": "Pt100 wire broken: TEMP_RTD_OHM reads 1 MOhm (over range)",
        "sensor_short": "Pt100 shorted: TEMP_RTD_OHM reads 0 Ohm",
        "heater_fail": "the element is burnt out: no heat",
        "valve_stuck": "the steam valve sticks at its present opening (param position, %)",
    }

    def __init__(
        self,
        *,
        area: float = 0.25,
        height: float = 1.0,
        level0: float = 0.6,
        t0: float | None = None,
        t_amb: float = 20.0,
        t_in: float = 10.0,
        p_max: float = 6000.0,
        steam_power: float = 20000.0,
        ua: float = 15.0,
        fill_flow: float = 0.0005,
        drain_area: float = 3.0e-4,
        demand: ProfileSpec = None,
        element_height: float = 0.15,
        level_min: float = 0.3,
        level_max: float = 0.9,
        t_max: float = 95.0,
        max_dt: float = 1.0,
    ) -> None:
        if area <= 0 or height <= 0 or ua <= 0 or max_dt <= 0:
            raise PlantError("heater: area, height, ua and max_dt must be > 0")
        if not 0 <= level_min < level_max <= height or not 0 <= level0 <= height:
            raise PlantError("heater: need 0 <= level_min < level_max <= height, level0 <= height")
        self.area = float(area)
        self.height = float(height)
        self.level0 = float(level0)
        self.t_amb = float(t_amb)
        self.t0 = float(t0) if t0 is not None else self.t_amb
        self.t_in = float(t_in)
        self.p_max = float(p_max)
        self.steam_power = float(steam_power)
        self.ua = float(ua)
        self.fill_flow = float(fill_flow)
        self.drain_area = float(drain_area)
        self.demand = StepProfile(demand, "heater demand")
        self.element_height = float(element_height)
        self.level_min = float(level_min)
        self.level_max = float(level_max)
        self.t_max = float(t_max)
        self.max_dt = float(max_dt)
        self._vmax = self.area * self.height
        self._k_drain = self.drain_area * math.sqrt(2.0 * 9.81)
        super().__init__(
            [
                bool_signal("HEATER", "actuator", "heating element contactor, TRUE = full power"),
                real_signal(
                    "POWER", "actuator", "%", 0, 100, "element power via thyristor (if HEATER off)"
                ),
                real_signal("STEAM_VALVE", "actuator", "%", 0, 100, "steam coil valve opening"),
                bool_signal("FILL_VALVE", "actuator", "cold water fill valve"),
                bool_signal("DRAIN_VALVE", "actuator", "drain valve"),
                real_signal("TEMP", "sensor", "degC", -20, 120, "true water temperature"),
                real_signal(
                    "TEMP_RTD_OHM", "sensor", "Ohm", 0, OPEN_CIRCUIT_OHM, "Pt100 resistance"
                ),
                real_signal("LEVEL", "sensor", "m", 0, self.height, "water level"),
                bool_signal("LEVEL_MIN", "sensor", "min level switch, TRUE when water at/above"),
                bool_signal("LEVEL_MAX", "sensor", "max level switch, TRUE when water at/above"),
                bool_signal("TEMP_MAX", "sensor", "over-temperature thermostat, TRUE when hot"),
            ]
        )

    def steady_state_temperature(self, power: float) -> float:
        """Analytic steady state with no flows: ``T_amb + power / UA`` (capped at 100 degC).

        Parameters
        ----------
        power : float
            Constant heat input, W.
        """
        return min(self.t_amb + power / self.ua, 100.0)

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self.volume = self.level0 * self.area
        self.volume0 = self.volume
        self.temp = self.t0
        self.p_el = 0.0
        self.p_steam = 0.0
        self.volume_in = 0.0
        self.volume_out = 0.0
        self.volume_overflow = 0.0
        self.volume_evaporated = 0.0
        self.energy_in = 0.0
        self._valve_pos: float | None = None
        self._flags = {"overflow": False, "dry": False, "boil": False}
        self.demand.reset()

    def _faults_changed(self) -> None:
        f = self._faults
        self._heater_ok = "heater_fail" not in f
        self._open = "sensor_open" in f
        self._short = "sensor_short" in f
        if "valve_stuck" not in f:
            self._valve_pos = None

    def _on_inject(self, fault: str, params: dict[str, Any]) -> None:
        if fault == "valve_stuck":
            pos = params.get("position")
            self._valve_pos = float(self._io["STEAM_VALVE"] if pos is None else pos)

    def _advance(self, h: float) -> None:
        io = self._io
        v = self.volume
        lvl = v / self.area
        flags = self._flags
        # heat inputs
        u = 1.0 if io["HEATER"] else io["POWER"] * 0.01
        p_el = self.p_max * u if self._heater_ok else 0.0
        if p_el > 0.0 and lvl < self.element_height:
            if not flags["dry"]:
                flags["dry"] = True
                self._emit("dry_heating", "the element is switched on but not covered by water")
            p_el = 0.0
        elif flags["dry"] and (p_el == 0.0 or lvl >= self.element_height):
            flags["dry"] = False
        self.p_el = p_el
        valve = io["STEAM_VALVE"] if self._valve_pos is None else self._valve_pos
        p_st = self.steam_power * valve * 0.01
        self.p_steam = p_st
        # flows
        q_fill = self.fill_flow if io["FILL_VALVE"] else 0.0
        sq = math.sqrt(lvl) if lvl > 0.0 else 0.0
        q_drain = self._k_drain * sq if io["DRAIN_VALVE"] else 0.0
        q_dem = 0.0 if self.demand.is_zero else self.demand(self.time)
        # temperature: exact update of m c dT/dt = P + rho c q_in (T_in - T) - UA (T - T_amb)
        m_c = max(v, 5e-4) * (RHO * C_WATER)
        g_fill = RHO * C_WATER * q_fill
        g = self.ua + g_fill
        t_eq = (p_el + p_st + g_fill * self.t_in + self.ua * self.t_amb) / g
        t = t_eq + (self.temp - t_eq) * math.exp(-g * h / m_c)
        self.energy_in += (p_el + p_st) * h
        # volumes
        vin = q_fill * h
        want = (q_drain + q_dem) * h
        avail = v + vin
        out = want if want <= avail else avail
        v = avail - out
        if t > 100.0:
            evap = (t - 100.0) * m_c / H_EVAP / RHO
            if evap > v:
                evap = v
            v -= evap
            self.volume_evaporated += evap
            t = 100.0
            if not flags["boil"]:
                flags["boil"] = True
                self._emit("boiling", "the water boils: steam escapes")
        elif flags["boil"] and t < 99.0:
            flags["boil"] = False
        if v > self._vmax:
            self.volume_overflow += v - self._vmax
            v = self._vmax
            if not flags["overflow"]:
                flags["overflow"] = True
                self._emit("overflow", "the boiler overflowed")
        elif flags["overflow"] and v < self._vmax * 0.99:
            flags["overflow"] = False
        self.volume_in += vin
        self.volume_out += out
        self.volume = v
        self.temp = t

    def _outputs(self) -> None:
        io = self._io
        t = self.temp
        lvl = self.volume / self.area
        io["TEMP"] = t
        if self._open:
            io["TEMP_RTD_OHM"] = OPEN_CIRCUIT_OHM
        elif self._short:
            io["TEMP_RTD_OHM"] = 0.0
        else:
            io["TEMP_RTD_OHM"] = pt100_ohm(t)
        io["LEVEL"] = lvl
        io["LEVEL_MIN"] = lvl >= self.level_min
        io["LEVEL_MAX"] = lvl >= self.level_max
        io["TEMP_MAX"] = t >= self.t_max

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Volumes, heat flows and the energy put in."""
        return {
            "volume": self.volume,
            "volume_in": self.volume_in,
            "volume_out": self.volume_out,
            "volume_overflow": self.volume_overflow,
            "volume_evaporated": self.volume_evaporated,
            "p_el": self.p_el,
            "p_steam": self.p_steam,
            "p_loss": self.ua * (self.temp - self.t_amb),
            "energy_in": self.energy_in,
        }

    def geometry(self) -> dict[str, Any]:
        w = math.sqrt(self.area)
        return {
            "shapes": [
                {"type": "rect", "name": "boiler", "x": 0.0, "y": 0.0, "w": w, "h": self.height},
                {"type": "mark", "name": "LEVEL_MIN", "x": w, "y": self.level_min},
                {"type": "mark", "name": "LEVEL_MAX", "x": w, "y": self.level_max},
                {
                    "type": "line",
                    "name": "element",
                    "x0": 0.1 * w,
                    "y0": self.element_height,
                    "x1": 0.9 * w,
                    "y1": self.element_height,
                },
            ],
            "fill": {"signal": "LEVEL", "x": 0.0, "y": 0.0, "w": w},
        }
