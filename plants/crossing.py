"""A pedestrian crossing with traffic lights for the second SFC lab.

Cars see red, yellow and green; pedestrians see red and green and a request button with a
"signal comes" lamp. A kerb sensor sees pedestrians waiting, a second sensor (a radar over the
zebra) sees pedestrians on the crossing.

Signals
-------
Panel: ``REQUEST`` (the pedestrians' push button, NO) and ``ARRIVE`` (the scenario: a rising
edge brings one pedestrian to the kerb). Lamps: ``CAR_RED``, ``CAR_YELLOW``, ``CAR_GREEN``,
``PED_RED``, ``PED_GREEN``, ``WAIT_LAMP``. Sensors: ``PED_WAITING`` (``True`` while someone
waits at the kerb), ``ON_CROSSING`` (``True`` while someone is on the crossing).

Behaviour
---------
Waiting pedestrians step onto the crossing as soon as ``PED_GREEN`` is on and take
``cross_time`` seconds to cross (whatever the lights do meanwhile); a pedestrian who arrives
during the green crosses at once. Events: ``conflict`` (pedestrian green together with car green
or yellow), ``cars_on_pedestrian`` (car green while someone is on the crossing), ``long_wait``
(a pedestrian waited longer than ``patience``), ``lights_dark`` (no car lamp for a second).
Faults: ``request_stuck`` (the button contact is welded: ``REQUEST`` reads TRUE),
``crossing_sensor_dead`` (``ON_CROSSING`` always reads FALSE).
"""

from __future__ import annotations

from typing import Any

from .base import Plant, PlantError, bool_signal

__all__ = ["Crossing"]


class Crossing(Plant):
    """Pedestrian crossing: car and pedestrian lights, request button, two sensors.

    Parameters
    ----------
    cross_time : float
        Seconds a pedestrian needs to cross.
    patience : float
        A wait longer than this (s) is reported as ``long_wait``.
    max_dt : float
        Largest integration step, s.
    """

    name = "crossing"
    title = "Pedestrian crossing with traffic lights"
    EVENTS = {
        "conflict": "pedestrian green together with car green or yellow",
        "cars_on_pedestrian": "car green while a pedestrian is on the crossing",
        "long_wait": "a pedestrian waited longer than the patience",
        "lights_dark": "no car lamp was lit for a second",
    }
    FAULTS = {
        "request_stuck": "the request button's contact is welded: REQUEST reads TRUE",
        "crossing_sensor_dead": "the crossing sensor is dead: ON_CROSSING reads FALSE",
    }

    def __init__(self, *, cross_time: float = 5.0, patience: float = 60.0,
                 max_dt: float = 0.05) -> None:
        if cross_time <= 0 or patience <= 0 or max_dt <= 0:
            raise PlantError("crossing: need cross_time, patience and max_dt > 0")
        self.cross_time = float(cross_time)
        self.patience = float(patience)
        self.max_dt = float(max_dt)
        super().__init__([
            bool_signal("REQUEST", "panel", "pedestrian request button, NO: TRUE while pressed"),
            bool_signal("ARRIVE", "panel", "scenario: a rising edge brings a pedestrian"),
            bool_signal("CAR_RED", "lamp", "car signal red"),
            bool_signal("CAR_YELLOW", "lamp", "car signal yellow"),
            bool_signal("CAR_GREEN", "lamp", "car signal green"),
            bool_signal("PED_RED", "lamp", "pedestrian signal red"),
            bool_signal("PED_GREEN", "lamp", "pedestrian signal green"),
            bool_signal("WAIT_LAMP", "lamp", "'signal comes' lamp at the button"),
            bool_signal("PED_WAITING", "sensor", "kerb sensor: TRUE while someone waits"),
            bool_signal("ON_CROSSING", "sensor", "crossing sensor: TRUE while someone crosses"),
        ])

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        self.waiting: list[float] = []  # arrival times
        self.crossing: list[float] = []  # times left to cross
        self._arrive_prev = False
        self._dark = 0.0
        self._flags = {"conflict": False, "cars": False, "dark": False}
        self._long_reported: set[float] = set()
        self.crossed = 0.0
        self.wait_total = 0.0
        self.wait_max = 0.0

    def _faults_changed(self) -> None:
        self._stuck = "request_stuck" in self._faults
        self._sensor_dead = "crossing_sensor_dead" in self._faults

    def _advance(self, h: float) -> None:
        io = self._io
        now = self.time
        if io["ARRIVE"] and not self._arrive_prev:
            self.waiting.append(now)
        self._arrive_prev = bool(io["ARRIVE"])
        if io["PED_GREEN"] and self.waiting:
            for t0 in self.waiting:
                w = now - t0
                self.wait_total += w
                self.wait_max = max(self.wait_max, w)
            self.crossing += [self.cross_time] * len(self.waiting)
            self.waiting = []
        for t0 in self.waiting:
            if now - t0 > self.patience and t0 not in self._long_reported:
                self._long_reported.add(t0)
                self._emit("long_wait", f"a pedestrian has waited {self.patience:g} s")
        left = [c - h for c in self.crossing]
        self.crossed += sum(1 for c in left if c <= 0.0)
        self.crossing = [c for c in left if c > 0.0]
        flags = self._flags
        conflict = bool(io["PED_GREEN"] and (io["CAR_GREEN"] or io["CAR_YELLOW"]))
        if conflict and not flags["conflict"]:
            self._emit("conflict", "pedestrians and cars have green at the same time")
        flags["conflict"] = conflict
        cars = bool(io["CAR_GREEN"] and self.crossing)
        if cars and not flags["cars"]:
            self._emit("cars_on_pedestrian", "cars get green while a pedestrian is crossing")
        flags["cars"] = cars
        if io["CAR_RED"] or io["CAR_YELLOW"] or io["CAR_GREEN"]:
            self._dark = 0.0
            flags["dark"] = False
        else:
            self._dark += h
            if self._dark >= 1.0 and not flags["dark"]:
                flags["dark"] = True
                self._emit("lights_dark", "the car signal has been dark for a second")

    def _outputs(self) -> None:
        io = self._io
        io["PED_WAITING"] = bool(self.waiting)
        io["ON_CROSSING"] = bool(self.crossing) and not self._sensor_dead
        if self._stuck:
            io["REQUEST"] = True

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """Pedestrians waiting, crossing and crossed; total and longest wait (s)."""
        return {"waiting": float(len(self.waiting)), "crossing": float(len(self.crossing)),
                "crossed": self.crossed, "wait_total": self.wait_total,
                "wait_max": self.wait_max}

    def geometry(self) -> dict[str, Any]:
        lamps = [("CAR_RED", 0.0, 14.0), ("CAR_YELLOW", 0.0, 11.5), ("CAR_GREEN", 0.0, 9.0),
                 ("PED_RED", 11.0, 14.0), ("PED_GREEN", 11.0, 11.5), ("WAIT_LAMP", 11.0, 9.0)]
        return {"shapes": [
            {"type": "rect", "name": "road", "x": 0.0, "y": 0.0, "w": 20.0, "h": 7.0},
            {"type": "rect", "name": "zebra", "x": 9.0, "y": 0.0, "w": 3.0, "h": 7.0},
            *[{"type": "circle", "name": n, "x": x, "y": y, "r": 0.4} for n, x, y in lamps],
            {"type": "mark", "name": "ON_CROSSING", "x": 10.5, "y": 3.5},
            {"type": "mark", "name": "PED_WAITING", "x": 3.0, "y": -2.0},
        ]}
