"""Ventilation of a livestock building with three fans, any two of which must run (Fig. 118-119).

The control task of the textbook: with the cycle on (``START``/``STOP``, main switch ``MS``),
run FAN2 and FAN3; if one of them faults, start the standby FAN1; if two fans fault, switch the
main power off; show fan states on lamps and blink the fault lamp at 5 Hz when more than one fan
is faulted.

Signals
-------
``MS`` (main switch), ``START`` (NO button), ``STOP`` (NC button, ``True`` while not pressed)
are panel inputs. ``MAIN_POWER`` is the main contactor: no fan turns unless it is on. ``FAN1``
..``FAN3`` are the fan contactors. ``FAULT1``..``FAULT3`` are the fans' fault contacts:
``True`` = fan faulted (motor protection tripped); a faulted fan does not turn. Lamps
(``RUN_LAMP``, ``FAULT_LAMP``, ``FAN1_LAMP``..``FAN3_LAMP``) are written by the PLC and only
recorded. ``CURRENT1..3`` are the fan motor currents, ``TEMP_IN``/``TEMP_OUT`` the inside and
outside air temperatures.

Physics
-------
One lumped heat capacity ``C`` (air and building)::

    C dT/dt = Q_animals + Q_sun(t) - (UA + rho cp (q_inf + sum(s_i q_fan))) (T - T_out(t))

``T_out`` follows a daily sine (minimum at 03:00, maximum at 15:00) around a mean that the seed
shifts per day (``weather_sigma``); the sun is a half-sine from 06:00 to 18:00 scaled by a seeded
daily cloud factor. Environment values are refreshed once per simulated second. Fan speed
fractions ``s_i`` follow first-order lags (``fan_tau_up``/``fan_tau_down``); the current is
``I = I_run * (0.3 + 0.7 s) + I_run * (start_ratio - 1) * (1 - s)`` while powered.

Events: ``overheat`` when the inside temperature reaches ``t_alarm`` (again after it fell 1 K
below), ``fans_stopped`` when the air exchange is lost while the animals are inside.
"""

from __future__ import annotations

import math
import random
from typing import Any

from .base import Plant, PlantError, bool_signal, real_signal

__all__ = ["Ventilation"]

DAY = 86400.0
RHO_CP_AIR = 1.2 * 1005.0  # J/(m3 K)


class Ventilation(Plant):
    """Livestock-building thermal model with three fans (FAN1 is the standby).

    Parameters
    ----------
    heat_capacity : float
        Heat capacity of the air and building, J/K.
    ua : float
        Heat-loss coefficient of the envelope, W/K.
    infiltration : float
        Natural air exchange, m3/s.
    fan_flow : float
        Air flow of one fan at full speed, m3/s.
    heat_animals : float
        Sensible heat of the animals, W.
    solar_peak : float
        Solar gain at noon on a clear day, W.
    t_out_mean, t_out_amp : float
        Daily mean and amplitude of the outside temperature, degC / K.
    weather_sigma : float
        Standard deviation of the seeded day-to-day shift of the mean, K.
    start_hour : float
        Time of day at reset, h.
    t0 : float or None
        Inside temperature at reset, degC (default: outside temperature + 5 K).
    fan_current : float
        Running current of a fan motor, A.
    start_ratio : float
        Starting current as a multiple of the running current.
    fan_tau_up, fan_tau_down : float
        Spin-up and coast-down time constants, s.
    t_alarm : float
        Inside temperature of the ``overheat`` event, degC.
    max_dt : float
        Largest integration step, s.
    """

    name = "ventilation"
    title = "Livestock building ventilation: three fans, two must run"
    EVENTS = {
        "overheat": "the inside temperature reached t_alarm",
        "fans_stopped": "all fans stopped: no forced air exchange",
    }
    FAULTS = {
        "fan1_fail": "fan 1 motor protection trips: FAULT1 TRUE, the fan stops",
        "fan2_fail": "fan 2 motor protection trips: FAULT2 TRUE, the fan stops",
        "fan3_fail": "fan 3 motor protection trips: FAULT3 TRUE, the fan stops",
    }

    def __init__(
        self,
        *,
        heat_capacity: float = 2.0e7,
        ua: float = 1500.0,
        infiltration: float = 0.5,
        fan_flow: float = 5.0,
        heat_animals: float = 60000.0,
        solar_peak: float = 40000.0,
        t_out_mean: float = 15.0,
        t_out_amp: float = 7.0,
        weather_sigma: float = 2.0,
        start_hour: float = 6.0,
        t0: float | None = None,
        fan_current: float = 2.5,
        start_ratio: float = 5.0,
        fan_tau_up: float = 3.0,
        fan_tau_down: float = 10.0,
        t_alarm: float = 32.0,
        max_dt: float = 0.5,
    ) -> None:
        if heat_capacity <= 0 or ua < 0 or fan_flow < 0 or fan_tau_up <= 0 or fan_tau_down <= 0:
            raise PlantError("ventilation: heat_capacity, time constants must be > 0")
        self.heat_capacity = float(heat_capacity)
        self.ua = float(ua)
        self.infiltration = float(infiltration)
        self.fan_flow = float(fan_flow)
        self.heat_animals = float(heat_animals)
        self.solar_peak = float(solar_peak)
        self.t_out_mean = float(t_out_mean)
        self.t_out_amp = float(t_out_amp)
        self.weather_sigma = float(weather_sigma)
        self.start_hour = float(start_hour)
        self.t0 = t0
        self.fan_current = float(fan_current)
        self.start_ratio = float(start_ratio)
        self.fan_tau_up = float(fan_tau_up)
        self.fan_tau_down = float(fan_tau_down)
        self.t_alarm = float(t_alarm)
        self.max_dt = float(max_dt)
        i_max = self.fan_current * self.start_ratio * 1.05
        sigs = [
            bool_signal("MS", "panel", "main switch, TRUE = on (off after reset)"),
            bool_signal("START", "panel", "start button, NO: TRUE while pressed"),
            bool_signal("STOP", "panel", "stop button, NC: TRUE while NOT pressed", initial=True),
            bool_signal("MAIN_POWER", "actuator", "main power contactor of the fan circuit"),
            bool_signal("FAN1", "actuator", "fan 1 contactor (standby fan)"),
            bool_signal("FAN2", "actuator", "fan 2 contactor"),
            bool_signal("FAN3", "actuator", "fan 3 contactor"),
            bool_signal("RUN_LAMP", "lamp", "cycle running / main power lamp"),
            bool_signal("FAULT_LAMP", "lamp", "fault lamp (FIND): steady 1 fault, 5 Hz 2+ faults"),
            bool_signal("FAN1_LAMP", "lamp", "fan 1 running lamp"),
            bool_signal("FAN2_LAMP", "lamp", "fan 2 running lamp"),
            bool_signal("FAN3_LAMP", "lamp", "fan 3 running lamp"),
            bool_signal("FAULT1", "sensor", "fan 1 fault contact, TRUE = faulted"),
            bool_signal("FAULT2", "sensor", "fan 2 fault contact, TRUE = faulted"),
            bool_signal("FAULT3", "sensor", "fan 3 fault contact, TRUE = faulted"),
            real_signal("CURRENT1", "sensor", "A", 0, i_max, "fan 1 motor current"),
            real_signal("CURRENT2", "sensor", "A", 0, i_max, "fan 2 motor current"),
            real_signal("CURRENT3", "sensor", "A", 0, i_max, "fan 3 motor current"),
            real_signal("TEMP_IN", "sensor", "degC", -30, 60, "inside air temperature"),
            real_signal("TEMP_OUT", "sensor", "degC", -30, 50, "outside air temperature"),
        ]
        super().__init__(sigs)

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self._day = -1
        self._day_shift = 0.0
        self._cloud = 1.0
        self._env_next = 0.0
        self._env(0.0)
        self.temp = self.t_out + 5.0 if self.t0 is None else float(self.t0)
        self.s1 = self.s2 = self.s3 = 0.0
        self.airflow = self.infiltration
        self._hot = False
        self._stopped_flag = False
        self.energy_sun = 0.0
        self.fan_seconds = [0.0, 0.0, 0.0]

    def _faults_changed(self) -> None:
        f = self._faults
        self._ok1 = "fan1_fail" not in f
        self._ok2 = "fan2_fail" not in f
        self._ok3 = "fan3_fail" not in f

    def _env(self, t: float) -> None:
        """Refresh the outside temperature and solar gain for time ``t``."""
        hour = (self.start_hour + t / 3600.0) % 24.0
        day = int((self.start_hour * 3600.0 + t) // DAY)
        if day != self._day:
            self._day = day
            r = _day_rng(self.seed, day)
            self._day_shift = r.gauss(0.0, 1.0) * self.weather_sigma
            self._cloud = 0.3 + 0.7 * r.random()
        self.t_out = (
            self.t_out_mean
            + self._day_shift
            + self.t_out_amp * math.sin(2.0 * math.pi * (hour - 9.0) / 24.0)
        )
        sun = math.sin(math.pi * (hour - 6.0) / 12.0) if 6.0 < hour < 18.0 else 0.0
        self.q_sun = self.solar_peak * self._cloud * sun
        self._env_next = t + 1.0

    def _advance(self, h: float) -> None:
        t = self.time
        if t >= self._env_next:
            self._env(t)
        io = self._io
        power = io["MAIN_POWER"]
        # fans (skip the arithmetic once a fan has settled)
        s = self.s1
        target = 1.0 if power and io["FAN1"] and self._ok1 else 0.0
        if s != target:
            self.s1 = _lag(s, target, h, self.fan_tau_up if target else self.fan_tau_down)
        s = self.s2
        target = 1.0 if power and io["FAN2"] and self._ok2 else 0.0
        if s != target:
            self.s2 = _lag(s, target, h, self.fan_tau_up if target else self.fan_tau_down)
        s = self.s3
        target = 1.0 if power and io["FAN3"] and self._ok3 else 0.0
        if s != target:
            self.s3 = _lag(s, target, h, self.fan_tau_up if target else self.fan_tau_down)
        q = self.infiltration + self.fan_flow * (self.s1 + self.s2 + self.s3)
        self.airflow = q
        g = self.ua + RHO_CP_AIR * q
        tin = self.temp
        tin += (self.heat_animals + self.q_sun - g * (tin - self.t_out)) * h / self.heat_capacity
        self.temp = tin
        if tin >= self.t_alarm:
            if not self._hot:
                self._hot = True
                self._emit(
                    "overheat", f"the inside temperature reached {self.t_alarm:.1f} degC", temp=tin
                )
        elif self._hot and tin < self.t_alarm - 1.0:
            self._hot = False

    def _outputs(self) -> None:
        io = self._io
        power = io["MAIN_POWER"]
        ir = self.fan_current
        k = ir * (self.start_ratio - 1.0)
        on1 = power and io["FAN1"] and self._ok1
        on2 = power and io["FAN2"] and self._ok2
        on3 = power and io["FAN3"] and self._ok3
        s1, s2, s3 = self.s1, self.s2, self.s3
        io["CURRENT1"] = ir * (0.3 + 0.7 * s1) + k * (1.0 - s1) if on1 else 0.0
        io["CURRENT2"] = ir * (0.3 + 0.7 * s2) + k * (1.0 - s2) if on2 else 0.0
        io["CURRENT3"] = ir * (0.3 + 0.7 * s3) + k * (1.0 - s3) if on3 else 0.0
        io["FAULT1"] = not self._ok1
        io["FAULT2"] = not self._ok2
        io["FAULT3"] = not self._ok3
        io["TEMP_IN"] = self.temp
        io["TEMP_OUT"] = self.t_out
        stopped = s1 + s2 + s3 < 0.05
        if stopped and not self._stopped_flag and self.time > 0.0:
            self._emit("fans_stopped", "all fans stopped: no forced air exchange")
        self._stopped_flag = stopped

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Fan speeds (0..1), air flow, heat flows and fan running seconds."""
        g = self.ua + RHO_CP_AIR * self.airflow
        return {
            "fan1_speed": self.s1,
            "fan2_speed": self.s2,
            "fan3_speed": self.s3,
            "airflow": self.airflow,
            "q_sun": self.q_sun,
            "q_animals": self.heat_animals,
            "q_removed": g * (self.temp - self.t_out),
            "hour": (self.start_hour + self.time / 3600.0) % 24.0,
        }

    def geometry(self) -> dict[str, Any]:
        return {
            "shapes": [
                {"type": "rect", "name": "building", "x": 0.0, "y": 0.0, "w": 30.0, "h": 6.0},
                {"type": "circle", "name": "FAN1", "x": 5.0, "y": 4.5, "r": 0.6},
                {"type": "circle", "name": "FAN2", "x": 15.0, "y": 4.5, "r": 0.6},
                {"type": "circle", "name": "FAN3", "x": 25.0, "y": 4.5, "r": 0.6},
            ]
        }


def _lag(s: float, target: float, h: float, tau: float) -> float:
    s += (target - s) * (h / tau if h < tau else 1.0)
    if -1e-6 < s - target < 1e-6:
        return target
    return s


def _day_rng(seed: int, day: int) -> random.Random:
    """Weather of one day: depends on the seed and the day only, not on the step sizes."""
    return random.Random(seed * 1_000_003 + day)
