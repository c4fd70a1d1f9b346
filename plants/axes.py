"""Three simple axes for the drives lab: a conveyor belt, a press piston and a dosing pump.

Each axis is driven by a reversing contactor pair (``<AXIS>_FWD``, ``<AXIS>_REV``) and moves at
its rated speed while one of them is on (both on: the interlock of the contactors stops it).
An encoder reports the position ``<AXIS>_POS`` in millimetres, a home switch ``<AXIS>_HOME``
closes near position 0, and the drive's fault contact ``<AXIS>_FAULT`` opens a trip.

Signals
-------
Per axis ``BELT``, ``PISTON``, ``PUMP``: actuators ``_FWD``, ``_REV``; sensors ``_POS`` (mm),
``_HOME`` (``True`` while ``0 <= pos <= home_width``), ``_FAULT`` (``True`` = drive tripped).
Panel: ``START`` and ``RESET`` (NO buttons). Lamps: ``READY_LAMP``, ``ALARM_LAMP``.

Physics
-------
``dpos/dt = v``; the speed follows the command (``+speed``, ``-speed`` or 0) with the rate
limit ``accel`` (mm/s²), so a position integrator with a speed and an acceleration limit. The
travel is limited by hard stops at ``-end_margin`` and ``travel``: an axis driven into a stop
stalls there (event ``end_stop``). A tripped drive coasts to a halt at the same rate.

Faults: ``<axis>_trip`` (the drive trips: its fault contact closes and it does not move),
``<axis>_home_dead`` (the home switch is broken: it never closes, the axis runs into its
stop). Events: ``end_stop``, ``both_directions`` (FWD and REV on together), ``moved_tripped``
(a tripped drive still commanded for more than a second).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .base import Plant, PlantError, bool_signal, real_signal

__all__ = ["Axes", "AXES"]

AXES = ("BELT", "PISTON", "PUMP")
"""The axes, in the order of the lab's drive array."""


@dataclass
class _Axis:
    """The state of one axis."""

    name: str
    speed: float
    travel: float
    start: float
    pos: float = 0.0
    v: float = 0.0
    at_stop: bool = False
    both: bool = False
    tripped_cmd: float = 0.0
    tripped_flag: bool = False


class Axes(Plant):
    """Conveyor belt, press piston and dosing pump on reversing contactors with encoders.

    Parameters
    ----------
    speeds : dict
        Rated speed per axis, mm/s (default BELT 100, PISTON 50, PUMP 20).
    travels : dict
        Upper hard stop per axis, mm (default BELT 1000, PISTON 300, PUMP 100).
    starts : dict
        Position per axis after ``reset()``, mm (default BELT 420, PISTON 130, PUMP 55).
    accel : float
        Acceleration and braking limit, mm/s².
    home_width : float
        The home switch is closed for ``0 <= pos <= home_width``, mm.
    end_margin : float
        The lower hard stop is at ``-end_margin``, mm.
    max_dt : float
        Largest integration step, s.
    """

    name = "axes"
    title = "Three axes: conveyor belt, press piston, dosing pump"
    EVENTS = {
        "end_stop": "an axis was driven into its hard stop",
        "both_directions": "FWD and REV of an axis were on together",
        "moved_tripped": "a tripped drive was still commanded a second after its trip",
    }
    FAULTS = {
        **{f"{a.lower()}_trip": f"the {a.lower()} drive trips (its FAULT contact closes)"
           for a in AXES},
        **{f"{a.lower()}_home_dead": f"the {a.lower()} home switch is broken: it never closes"
           for a in AXES},
    }

    def __init__(
        self,
        *,
        speeds: dict[str, float] | None = None,
        travels: dict[str, float] | None = None,
        starts: dict[str, float] | None = None,
        accel: float = 2000.0,
        home_width: float = 2.0,
        end_margin: float = 10.0,
        max_dt: float = 0.005,
    ) -> None:
        speeds = {"BELT": 100.0, "PISTON": 50.0, "PUMP": 20.0, **(speeds or {})}
        travels = {"BELT": 1000.0, "PISTON": 300.0, "PUMP": 100.0, **(travels or {})}
        starts = {"BELT": 420.0, "PISTON": 130.0, "PUMP": 55.0, **(starts or {})}
        for table in (speeds, travels, starts):
            unknown = set(table) - set(AXES)
            if unknown:
                raise PlantError(f"axes: unknown axis {sorted(unknown)}; axes: {', '.join(AXES)}")
        if accel <= 0 or home_width <= 0 or end_margin <= 0 or max_dt <= 0:
            raise PlantError("axes: need accel, home_width, end_margin and max_dt > 0")
        self.axes = {}
        for a in AXES:
            if speeds[a] <= 0 or not -end_margin <= starts[a] <= travels[a]:
                raise PlantError(f"axes: {a} needs speed > 0 and -end_margin <= start <= travel")
            self.axes[a] = _Axis(a, float(speeds[a]), float(travels[a]), float(starts[a]))
        self.accel = float(accel)
        self.home_width = float(home_width)
        self.end_margin = float(end_margin)
        self.max_dt = float(max_dt)
        signals = [
            bool_signal("START", "panel", "start push button, NO: TRUE while pressed"),
            bool_signal("RESET", "panel", "alarm reset push button, NO: TRUE while pressed"),
            bool_signal("READY_LAMP", "lamp", "every drive homed and in its work position"),
            bool_signal("ALARM_LAMP", "lamp", "a drive fault or a timeout stopped the machine"),
        ]
        for a, ax in self.axes.items():
            what = {"BELT": "conveyor belt", "PISTON": "press piston", "PUMP": "dosing pump"}[a]
            signals += [
                bool_signal(f"{a}_FWD", "actuator", f"{what}: forward contactor"),
                bool_signal(f"{a}_REV", "actuator", f"{what}: reverse contactor (towards home)"),
                real_signal(f"{a}_POS", "sensor", "mm", -self.end_margin, ax.travel,
                            f"{what}: encoder position"),
                bool_signal(f"{a}_HOME", "sensor", f"{what}: home switch, TRUE near 0 mm"),
                bool_signal(f"{a}_FAULT", "sensor", f"{what}: drive fault contact, TRUE = tripped"),
            ]
        super().__init__(signals)

    # ------------------------------------------------------------------ hooks
    def _reset_state(self) -> None:
        for ax in self.axes.values():
            ax.pos, ax.v = ax.start, 0.0
            ax.at_stop = ax.both = ax.tripped_flag = False
            ax.tripped_cmd = 0.0
        self.distance = 0.0

    def _faults_changed(self) -> None:
        f = self._faults
        self._tripped = {a: f"{a.lower()}_trip" in f for a in AXES}
        self._home_dead = {a: f"{a.lower()}_home_dead" in f for a in AXES}

    def _advance(self, h: float) -> None:
        io = self._io
        dv = self.accel * h
        for a, ax in self.axes.items():
            fwd, rev = io[f"{a}_FWD"], io[f"{a}_REV"]
            if fwd and rev and not ax.both:
                self._emit("both_directions", f"{a}_FWD and {a}_REV are on together", axis=a)
            ax.both = bool(fwd and rev)
            tripped = self._tripped[a]
            cmd = 0.0 if tripped or fwd == rev else (ax.speed if fwd else -ax.speed)
            if tripped and (fwd or rev):
                ax.tripped_cmd += h
                if ax.tripped_cmd >= 1.0 and not ax.tripped_flag:
                    ax.tripped_flag = True
                    self._emit("moved_tripped", f"the tripped {a} drive is still commanded",
                               axis=a)
            else:
                ax.tripped_cmd = 0.0
                ax.tripped_flag = False
            v = ax.v
            v = min(cmd, v + dv) if cmd > v else max(cmd, v - dv)
            pos = ax.pos + v * h
            lo, hi = -self.end_margin, ax.travel
            if pos <= lo or pos >= hi:
                pos = lo if pos <= lo else hi
                v = 0.0
                if not ax.at_stop:
                    ax.at_stop = True
                    self._emit("end_stop", f"{a} runs into its hard stop at {pos:g} mm", axis=a)
            elif ax.at_stop and lo + 1.0 < pos < hi - 1.0:
                ax.at_stop = False
            self.distance += abs(pos - ax.pos)
            ax.pos, ax.v = pos, v

    def _outputs(self) -> None:
        io = self._io
        for a, ax in self.axes.items():
            io[f"{a}_POS"] = ax.pos
            io[f"{a}_HOME"] = 0.0 <= ax.pos <= self.home_width and not self._home_dead[a]
            io[f"{a}_FAULT"] = self._tripped[a]

    # ------------------------------------------------------------------ records
    def snapshot(self) -> dict[str, float]:
        """The speed of every axis (mm/s) and the distance travelled by all of them (mm)."""
        out = {f"{a.lower()}_speed": ax.v for a, ax in self.axes.items()}
        out["distance"] = self.distance
        return out

    def geometry(self) -> dict[str, Any]:
        shapes: list[dict[str, Any]] = []
        for i, ax in enumerate(self.axes.values()):
            y = 0.3 * (len(self.axes) - 1 - i)  # the belt on top
            shapes += [
                {"type": "rect", "name": ax.name.lower(), "x": 0.0, "y": y,
                 "w": ax.travel / 1000.0, "h": 0.1},
                {"type": "mark", "name": f"{ax.name}_HOME", "x": 0.0, "y": y + 0.15},
                {"type": "mark", "name": f"{ax.name}_FAULT", "x": 0.5, "y": y + 0.15},
            ]
        return {"shapes": shapes}
