"""Induction motor on a contactor with a start/stop push-button station (textbook Fig. 113).

Wiring modelled
---------------
* ``START`` is a normally open push button: ``True`` while pressed.
* ``STOP`` is a normally closed push button: it reads ``True`` while **not** pressed (the
  contact is closed), ``False`` while pressed or when a wire is broken. The scenario presses it
  by writing ``False``. This is why the classic rung is ``K1 := (START OR K1) AND STOP``.
* ``K1`` is the contactor coil, written by the PLC. The main contacts follow the coil after a
  pick-up / drop-out delay. ``RUN`` is the auxiliary (mirror) contact of the main contacts, so a
  welded contactor keeps ``RUN`` at ``True`` after the coil has been switched off.
* ``OVERLOAD`` is the signalling contact (97-98) of a thermal overload relay: ``True`` = tripped.
  With ``overload_breaks_coil=True`` (the default) its 95-96 contact is wired in series with the
  coil, so a trip drops the contactor whatever the PLC writes. The relay stays tripped until
  ``OL_RESET`` is pressed (or ``auto_reset=True``) and it has cooled down.
* ``HEARTBEAT`` is a panel lamp the PLC may drive (the scan-timing lab blinks it from a slow
  task); the plant only shows it.

Physics
-------
While energised the speed runs up linearly to the loaded speed in ``spin_up_time`` (the
torque-speed curve is steep near synchronism, so the approach is quick); it coasts down
exponentially with ``coast_tau`` otherwise and stops within a few tens of ms when jammed. The
line current is the locked-rotor value ``I_lr`` up to 75 % of the loaded speed ``n_run`` and then
falls linearly to the running value: ``I = I_run + (I_lr - I_run) * clip(4 (1 - n/n_run), 0, 1)``.
The overload relay integrates ``d(theta)/dt = ((I/I_set)^2 - theta) / ol_tau`` and trips when
``theta >= ol_trip_ratio^2`` (an I^2 t characteristic: a locked rotor at 6 x I_set trips in
about 11 s from cold and about 3 s from running at rated load, with the defaults).

Events: ``motor_started``, ``motor_stopped`` (main contacts), ``overload_trip``,
``overload_reset``.
"""

from __future__ import annotations

from typing import Any

from .base import Plant, PlantError, bool_signal, real_signal

__all__ = ["Motor"]


class Motor(Plant):
    """Three-phase motor with contactor K1, overload relay and push-button station.

    Parameters
    ----------
    rated_speed : float
        Speed at rated load, rpm.
    sync_speed : float
        Synchronous (no-load) speed, rpm.
    rated_current : float
        Line current at rated load, A.
    no_load_ratio : float
        No-load current as a fraction of the rated current.
    locked_rotor_ratio : float
        Starting (locked-rotor) current as a multiple of the rated current.
    load : float
        Mechanical load as a fraction of rated torque.
    spin_up_time : float
        Run-up time from standstill to loaded speed, s.
    coast_tau : float
        Time constant of the coast-down when de-energised, s.
    pickup_delay, dropout_delay : float
        Contactor delays, s.
    ol_setting : float or None
        Current setting of the overload relay, A (default: ``rated_current``).
    ol_tau : float
        Thermal time constant of the overload relay, s.
    ol_trip_ratio : float
        The relay trips at ``ol_trip_ratio * ol_setting`` sustained current.
    ol_reset_fraction : float
        The relay can be reset once ``theta`` fell below this fraction of the trip level.
    auto_reset : bool
        Reset the relay automatically once it has cooled down.
    overload_breaks_coil : bool
        Hard-wire the relay's NC contact in series with the coil.
    max_dt : float
        Largest integration step, s.
    """

    name = "motor"
    title = "Motor with contactor, thermal overload relay and start/stop station"
    EVENTS = {
        "motor_started": "the main contacts of K1 closed",
        "motor_stopped": "the main contacts of K1 opened",
        "overload_trip": "the thermal overload relay tripped",
        "overload_reset": "the overload relay was reset",
    }
    FAULTS = {
        "overload": "the overload relay trips now (as after a long overcurrent)",
        "contactor_stuck": "main contacts weld: once closed they stay closed, RUN stays TRUE",
        "jam": "the driven machine jams: locked rotor, starting current until the relay trips",
    }

    def __init__(
        self,
        *,
        rated_speed: float = 1450.0,
        sync_speed: float = 1500.0,
        rated_current: float = 10.0,
        no_load_ratio: float = 0.35,
        locked_rotor_ratio: float = 6.0,
        load: float = 1.0,
        spin_up_time: float = 1.5,
        coast_tau: float = 3.0,
        pickup_delay: float = 0.02,
        dropout_delay: float = 0.015,
        ol_setting: float | None = None,
        ol_tau: float = 300.0,
        ol_trip_ratio: float = 1.15,
        ol_reset_fraction: float = 0.7,
        auto_reset: bool = False,
        overload_breaks_coil: bool = True,
        max_dt: float = 0.005,
    ) -> None:
        if not 0 < rated_speed < sync_speed:
            raise PlantError("motor: need 0 < rated_speed < sync_speed")
        if rated_current <= 0 or ol_tau <= 0 or spin_up_time <= 0 or coast_tau <= 0:
            raise PlantError("motor: currents and time constants must be > 0")
        self.rated_speed = float(rated_speed)
        self.sync_speed = float(sync_speed)
        self.rated_current = float(rated_current)
        self.no_load_ratio = float(no_load_ratio)
        self.locked_rotor_ratio = float(locked_rotor_ratio)
        self.load = float(load)
        self.spin_up_time = float(spin_up_time)
        self.coast_tau = float(coast_tau)
        self.pickup_delay = float(pickup_delay)
        self.dropout_delay = float(dropout_delay)
        self.ol_setting = float(ol_setting if ol_setting is not None else rated_current)
        self.ol_tau = float(ol_tau)
        self.ol_trip_ratio = float(ol_trip_ratio)
        self.ol_reset_fraction = float(ol_reset_fraction)
        self.auto_reset = bool(auto_reset)
        self.overload_breaks_coil = bool(overload_breaks_coil)
        self.max_dt = float(max_dt)
        self._theta_trip = self.ol_trip_ratio**2
        i_max = self.rated_current * self.locked_rotor_ratio * 1.05
        super().__init__(
            [
                bool_signal("START", "panel", "start push button, NO: TRUE while pressed"),
                bool_signal(
                    "STOP", "panel", "stop push button, NC: TRUE while NOT pressed", initial=True
                ),
                bool_signal("OL_RESET", "panel", "overload relay reset button, TRUE while pressed"),
                bool_signal("K1", "actuator", "contactor coil, TRUE = energise"),
                bool_signal("RUN", "sensor", "auxiliary contact of K1: TRUE when contacts closed"),
                bool_signal("OVERLOAD", "sensor", "overload relay contact 97-98: TRUE = tripped"),
                real_signal("SPEED", "sensor", "rpm", 0, self.sync_speed, "shaft speed"),
                real_signal("CURRENT", "sensor", "A", 0, i_max, "line current (RMS)"),
                bool_signal("HEARTBEAT", "lamp", "panel lamp driven by the PLC (only shown)"),
            ]
        )

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self.contacts = False
        self.welded = False
        self.speed = 0.0
        self.current = 0.0
        self.theta = 0.0
        self.tripped = False
        self._switch_timer = 0.0
        self.starts = 0
        self.trips = 0

    def _faults_changed(self) -> None:
        self._jam = "jam" in self._faults
        self._stuck = "contactor_stuck" in self._faults

    def _on_inject(self, fault: str, params: dict[str, Any]) -> None:
        if fault == "overload":
            self.theta = max(self.theta, self._theta_trip)
            self._trip("the overload relay tripped (injected fault)")
        elif fault == "contactor_stuck" and self.contacts:
            self.welded = True
        elif fault == "jam":
            self._switch_timer = 0.0

    def _on_clear(self, fault: str) -> None:
        if fault == "contactor_stuck":
            self.welded = False

    def _trip(self, why: str) -> None:
        if not self.tripped:
            self.tripped = True
            self.trips += 1
            self._emit("overload_trip", why, current=self.current, theta=self.theta)

    def _advance(self, h: float) -> None:
        io = self._io
        # overload relay reset
        if self.tripped and (io["OL_RESET"] or self.auto_reset):
            if (
                "overload" not in self._faults
                and self.theta <= self.ol_reset_fraction * self._theta_trip
            ):
                self.tripped = False
                self._emit("overload_reset", "the overload relay was reset", theta=self.theta)
        coil = io["K1"] and not (self.tripped and self.overload_breaks_coil)
        # contactor with pick-up / drop-out delay and welding
        contacts = self.contacts
        if coil != contacts and not (self.welded and contacts):
            self._switch_timer += h
            delay = self.pickup_delay if coil else self.dropout_delay
            if self._switch_timer >= delay:
                self._switch_timer = 0.0
                contacts = self.contacts = coil
                if coil:
                    self.starts += 1
                    if self._stuck:
                        self.welded = True
                    self._emit("motor_started", "contactor K1 closed: motor energised")
                else:
                    self._emit("motor_stopped", "contactor K1 opened: motor de-energised")
        else:
            self._switch_timer = 0.0
        # speed: linear run-up while energised (the torque curve is steep near synchronism),
        # exponential coast-down, quick stop when jammed
        n = self.speed
        n_run = self.sync_speed - (self.sync_speed - self.rated_speed) * self.load
        if n_run < 0.0:
            n_run = 0.0
        if self._jam:
            n -= n * (h / 0.05 if h < 0.05 else 1.0)
            if n < 1e-3:
                n = 0.0
        elif contacts:
            if n < n_run:
                n += n_run * h / self.spin_up_time
                if n > n_run:
                    n = n_run
            elif n > n_run:
                n = n_run
        elif n > 0.0:
            n -= n * (h / self.coast_tau if h < self.coast_tau else 1.0)
            if n < 1e-3:
                n = 0.0
        self.speed = n
        # current: locked-rotor value until 75 % speed, then falling to the running value
        if contacts:
            i_rated = self.rated_current
            i_nl = i_rated * self.no_load_ratio
            i_run = i_nl + (i_rated - i_nl) * self.load
            i_lr = i_rated * self.locked_rotor_ratio
            f = (1.0 - n / n_run) * 4.0 if n_run > 0.0 else 1.0
            cur = i_run + (i_lr - i_run) * (0.0 if f < 0.0 else 1.0 if f > 1.0 else f)
        else:
            cur = 0.0
        self.current = cur
        # thermal image of the overload relay
        r = cur / self.ol_setting
        self.theta += (r * r - self.theta) * h / self.ol_tau
        if self.theta >= self._theta_trip:
            self._trip(f"the overload relay tripped after sustained overcurrent ({cur:.1f} A)")

    def _outputs(self) -> None:
        io = self._io
        io["RUN"] = self.contacts
        io["OVERLOAD"] = self.tripped
        io["SPEED"] = self.speed
        io["CURRENT"] = self.current

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Thermal state of the relay, counters and contactor state."""
        return {
            "theta": self.theta,
            "theta_trip": self._theta_trip,
            "contacts": float(self.contacts),
            "welded": float(self.welded),
            "starts": float(self.starts),
            "trips": float(self.trips),
        }
