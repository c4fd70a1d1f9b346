"""Bottle conveyor with fallen-bottle rejection and a filling station (textbook Fig. 115-117).

A 2-D side view simulated with pymunk (rigid bodies, friction, toppling). ``x`` runs along the
belt from the feeder to the end, ``y`` is up, the belt surface is ``y = 0``.

Stations along the belt (defaults)::

    x = 0.15  feeder: releases a bottle each ``feed_pitch`` m of belt travel (spot clear)
    x = 1.20  photo-eyes X1 (neck height, 0.20 m) and X2 (body height, 0.04 m)
    x = 1.25  reject cylinder (REJECT) with end switches CYL_EXTENDED / CYL_RETRACTED
    x = 2.20  filling nozzle (FILL_VALVE), FILL_LEVEL; bottle-in-position eye FILL_EYE just before
    x = 3.00  end of the belt: bottles drop into the bin and are counted

Signals
-------
``CONVEYOR`` runs the belt motor; the belt speed ramps to ``belt_speed`` and back to zero with
the acceleration limits ``belt_accel`` / ``belt_decel`` (a rate-limited drive; set a large
``belt_decel`` to model an abrupt stop). ``BELT_SPEED`` reports it. ``START``/``STOP`` (NO/NC)
are the operator buttons of the textbook's ladder program. ``BOX_LAMP`` is a panel lamp the PLC
lights while a box is changed (packing lab); the plant only shows it.

``X1``/``X2`` are ``True`` while something breaks the beam. The beams cross the belt, so in
the side view each is a point ``(x_eye, height)``; a bottle breaks a beam when that point lies
inside its rotated rectangle. A standing bottle breaks both; a fallen bottle only X2 -- the
textbook's rule "X2 and not X1 -> reject".

The reject cylinder pushes across the belt, which the side view does not show. It is modelled
as a kinematic pusher: the rod position ``e`` runs 0..1 in ``extend_time`` / ``retract_time``;
while ``e >= 0.5`` (the plate has reached mid-belt) every bottle overlapping the plate's
``plate_width`` window along x is swept off the line into the reject bin (removed from the
simulation and counted as rejected, split into fallen and standing).

The filling nozzle fills the bottle under it with ``fill_flow`` l/s if the bottle stands upright
and its centre is within ``nozzle_tolerance`` of the nozzle; otherwise the liquid is spilled.
A full bottle overflows (spill). ``FILL_EYE`` sees a bottle whose leading edge passed
``x_fill + fill_eye_offset`` (stop the belt on it and the bottle comes to rest under the nozzle
with the default ramps). ``FILL_LEVEL`` is the fill of the bottle under the nozzle in %.

Bottles
-------
Boxes ``bottle_width`` x ``bottle_height`` of ``bottle_mass``. The default ramps (1 m/s2) move
a standing bottle without tipping it; an abrupt start or stop at the default 0.4 m/s (set
``belt_accel``/``belt_decel`` large) tips it over (at 0.3 m/s and below it only slides: the
rotation it picks up while the friction brakes it is too small to pass the tipping point). Some
bottles are released already lying (probability ``topple_rate``), some get knocked over on the
way (probability ``knock_rate``, at a seeded place at least 0.5 m before the eyes, so that the
bottle lies flat when it reaches them). A bottle counts as *fallen* when it is tilted more than
60 degrees.

At the end of the belt a bottle is classified: ``good`` (standing and at least 95 % full),
``unfilled_passed`` (standing, not full) or ``fallen_passed``. Bottles occupy one of
``max_bottles`` slots, recorded as ``bottleN.id/x/y/angle`` in :meth:`Conveyor.snapshot`
(NaN when the slot is free).

Events: ``bottle_released``, ``bottle_toppled``, ``bottle_rejected``, ``bottle_binned``,
``spill``.

This module is the line (belt, eyes, cylinder, nozzle, feeder); a bottle and the reading of its
pose are in :mod:`plants.conveyor_bottle`, the snapshot's layout and the geometry a viewer draws
in :mod:`plants.conveyor_record`.
"""

from __future__ import annotations

import math
from typing import Any

from .base import Plant, PlantError, bool_signal, real_signal
from .conveyor_bottle import (
    COS_FALLEN,
    COS_UPRIGHT,
    Bottle,
    PoseReader,
    find_pose_getters,
    pose_getters,
)
from .conveyor_record import SnapshotLayout, line_geometry

__all__ = ["Conveyor"]

KNOCK_LEAD = 0.5  # m: knocks happen at least this far before the eyes (a fall takes ~0.3 m)


class Conveyor(Plant):
    """Bottle conveyor with photo-eyes X1/X2, reject cylinder and filling station (pymunk).

    Parameters
    ----------
    belt_length : float
        Belt length, m.
    belt_speed : float
        Belt speed while running, m/s.
    belt_accel, belt_decel : float
        Acceleration limits of the belt drive, m/s2.
    bottle_width, bottle_height, bottle_mass : float
        Bottle size, m, and mass, kg.
    bottle_capacity : float
        Bottle volume, l.
    friction : float
        Friction coefficient bottle-belt (pymunk multiplies the two shapes' values; this is the
        product).
    feed_pitch : float or None
        Belt travel between two releases, m: the feeder is geared to the belt like a star
        wheel, so it releases ``belt_speed / feed_pitch`` bottles per second while the belt runs
        and none while it stands (``None``: no feeder, use :meth:`release_bottle`). The first
        bottle is released at once after reset.
    feed_jitter : float
        Seeded random variation of the pitch, as a fraction (0 = regular).
    feed_limit : int or None
        Stop feeding after this many bottles.
    x_feed, x_eye, x_reject, x_fill : float
        Positions of the feeder, the photo-eyes, the reject cylinder and the nozzle, m.
    eye_x1_height, eye_x2_height : float
        Beam heights above the belt, m.
    plate_width : float
        Width of the reject plate along the belt, m.
    extend_time, retract_time : float
        Cylinder stroke times, s.
    fill_flow : float
        Nozzle flow, l/s.
    nozzle_tolerance : float
        Largest offset of the bottle centre from the nozzle that still fills, m.
    fill_eye_offset : float or None
        The bottle-in-position eye is this far past the nozzle, m (negative: before it). The
        default places it so that a belt stopped on the eye with the ``belt_decel`` ramp leaves
        the bottle centred under the nozzle: ``width/2 - belt_speed^2 / (2 belt_decel)``.
    topple_rate : float
        Probability that a bottle is released already lying.
    knock_rate : float
        Probability that a bottle is knocked over on its way to the eyes.
    max_bottles : int
        Number of bottle slots (bottles on the line at once).
    physics_dt : float
        pymunk time step, s.
    max_dt : float
        Largest step after which the sensors are evaluated, s.
    """

    name = "conveyor"
    title = "Bottle conveyor: fallen-bottle reject, filling station (pymunk)"
    EVENTS = {
        "bottle_released": "the feeder put a bottle on the belt",
        "bottle_toppled": "a standing bottle fell over",
        "bottle_rejected": "the cylinder pushed a bottle into the reject bin",
        "bottle_binned": "a bottle left the end of the belt (data: result good/unfilled/fallen)",
        "spill": "the filling valve ran with no bottle under it, or a bottle overflowed",
    }
    FAULTS = {
        "knock": "knocks over the next standing bottle 0.5 m before the eyes (param count, "
        "default 1)",
        "topple_rate": "bottles arrive fallen with probability param rate (default 0.5)",
        "cylinder_stuck": "the reject cylinder does not move",
        "eye_x1_blocked": "dirt on X1: the high beam reads broken (TRUE) all the time",
    }

    def __init__(
        self,
        *,
        belt_length: float = 3.0,
        belt_speed: float = 0.4,
        belt_accel: float = 1.0,
        belt_decel: float = 1.0,
        bottle_width: float = 0.06,
        bottle_height: float = 0.25,
        bottle_mass: float = 0.4,
        bottle_capacity: float = 0.5,
        friction: float = 0.6,
        feed_pitch: float | None = 0.6,
        feed_jitter: float = 0.0,
        feed_limit: int | None = None,
        x_feed: float = 0.15,
        x_eye: float = 1.2,
        x_reject: float = 1.25,
        x_fill: float = 2.2,
        eye_x1_height: float = 0.20,
        eye_x2_height: float = 0.04,
        plate_width: float = 0.12,
        extend_time: float = 0.3,
        retract_time: float = 0.3,
        fill_flow: float = 0.1,
        nozzle_tolerance: float = 0.02,
        fill_eye_offset: float | None = None,
        topple_rate: float = 0.1,
        knock_rate: float = 0.05,
        max_bottles: int = 32,
        physics_dt: float = 0.0025,
        max_dt: float = 0.01,
    ) -> None:
        if not 0 < x_feed < x_eye < x_fill < belt_length:
            raise PlantError("conveyor: need 0 < x_feed < x_eye < x_fill < belt_length")
        if bottle_height <= 0 or bottle_width <= 0 or bottle_mass <= 0 or physics_dt <= 0:
            raise PlantError("conveyor: bottle sizes, mass and physics_dt must be > 0")
        if not (0 < eye_x2_height < eye_x1_height):
            raise PlantError("conveyor: need 0 < eye_x2_height < eye_x1_height")
        self.belt_length = float(belt_length)
        self.belt_speed = float(belt_speed)
        self.belt_accel = float(belt_accel)
        self.belt_decel = float(belt_decel)
        self.bottle_width = float(bottle_width)
        self.bottle_height = float(bottle_height)
        self.bottle_mass = float(bottle_mass)
        self.bottle_capacity = float(bottle_capacity)
        self.friction = float(friction)
        self.feed_pitch = None if feed_pitch is None else float(feed_pitch)
        self.feed_jitter = float(feed_jitter)
        self.feed_limit = feed_limit
        self.x_feed = float(x_feed)
        self.x_eye = float(x_eye)
        self.x_reject = float(x_reject)
        self.x_fill = float(x_fill)
        self.eye_x1_height = float(eye_x1_height)
        self.eye_x2_height = float(eye_x2_height)
        self.plate_width = float(plate_width)
        self.extend_time = float(extend_time)
        self.retract_time = float(retract_time)
        self.fill_flow = float(fill_flow)
        self.nozzle_tolerance = float(nozzle_tolerance)
        if fill_eye_offset is None:
            # stop on the eye with the default ramp and the bottle comes to rest under the nozzle
            fill_eye_offset = bottle_width / 2 - belt_speed**2 / (2 * belt_decel) - 0.002
        self.fill_eye_offset = float(fill_eye_offset)
        self.topple_rate = float(topple_rate)
        self.knock_rate = float(knock_rate)
        self.max_bottles = int(max_bottles)
        self.physics_dt = float(physics_dt)
        self.max_dt = float(max_dt)
        self._hw = self.bottle_width / 2.0
        self._hh = self.bottle_height / 2.0
        self._layout = SnapshotLayout(self.max_bottles)  # the keys of snapshot()
        super().__init__(
            [
                bool_signal("START", "panel", "start button, NO: TRUE while pressed"),
                bool_signal(
                    "STOP", "panel", "stop button, NC: TRUE while NOT pressed", initial=True
                ),
                bool_signal("CONVEYOR", "actuator", "belt motor, TRUE = run"),
                bool_signal("REJECT", "actuator", "reject cylinder valve, TRUE = extend"),
                bool_signal("FILL_VALVE", "actuator", "filling nozzle valve"),
                bool_signal("X1", "sensor", "high photo-eye (neck height), TRUE = beam broken"),
                bool_signal("X2", "sensor", "low photo-eye (body height), TRUE = beam broken"),
                bool_signal("CYL_EXTENDED", "sensor", "cylinder end switch: fully out"),
                bool_signal("CYL_RETRACTED", "sensor", "cylinder end switch: fully in"),
                bool_signal("FILL_EYE", "sensor", "bottle-in-position eye just before the nozzle"),
                real_signal(
                    "FILL_LEVEL", "sensor", "%", 0, 100, "fill of the bottle under the nozzle"
                ),
                real_signal("BELT_SPEED", "sensor", "m/s", 0, self.belt_speed, "belt speed"),
                bool_signal("BOX_LAMP", "lamp", "packing lamp: box full, change the box"),
            ]
        )

    # ------------------------------------------------------------------ set-up
    def _reset_state(self) -> None:
        import pymunk  # lazy: only this plant needs it

        self._pm = pymunk
        find_pose_getters()
        space = pymunk.Space()
        space.gravity = (0.0, -9.81)
        space.iterations = 10
        r = 0.005
        belt = pymunk.Segment(space.static_body, (0.0, -r), (self.belt_length, -r), r)
        belt.friction = 1.0
        wall = pymunk.Segment(space.static_body, (-r, 0.0), (-r, 0.5), r)
        wall.friction = 0.3
        space.add(belt, wall)
        self._space = space
        self._belt = belt
        self._poses = PoseReader(pymunk)  # one read of every body's pose a scan
        self.v_belt = 0.0
        self.cyl = 0.0
        self._bottles: list[Bottle] = []
        self._free = list(range(self.max_bottles - 1, -1, -1))  # pop() gives the lowest
        self._next_id = 0
        self._pitch = self.feed_pitch if self.feed_pitch is not None else math.inf
        self._travel = self.feed_pitch or 0.0  # the first bottle comes at once
        self._spilling = False
        self.counts = {
            "released": 0,
            "good": 0,
            "unfilled_passed": 0,
            "fallen_passed": 0,
            "rejected": 0,
            "fallen_rejected": 0,
            "standing_rejected": 0,
            "toppled": 0,
            "spilled": 0,
            "binned": 0,
            "lost": 0,
        }
        self.spilled_volume = 0.0
        self.filled_volume = 0.0
        self._under: Bottle | None = None

    def _faults_changed(self) -> None:
        f = self._faults
        self._cyl_stuck = "cylinder_stuck" in f
        self._x1_blocked = "eye_x1_blocked" in f
        tr = f.get("topple_rate")
        self._topple = self.topple_rate if tr is None else float(tr.get("rate", 0.5))
        k = f.get("knock")
        self._knocks_left = 0 if k is None else int(k.get("count", 1))

    # ------------------------------------------------------------------ public helpers
    def release_bottle(self, fallen: bool = False, x: float | None = None) -> int:
        """Put a bottle on the belt now (for scenarios and tests); returns its id, -1 if full.

        Parameters
        ----------
        fallen : bool
            Lay it on its side instead of standing it up.
        x : float, optional
            Position along the belt (default: the feeder).
        """
        pm = self._pm
        if not self._free:
            return -1
        slot = self._free.pop()
        w, hgt = self.bottle_width, self.bottle_height
        body = pm.Body(self.bottle_mass, pm.moment_for_box(self.bottle_mass, (w, hgt)))
        xx = self.x_feed if x is None else float(x)
        if fallen:
            body.angle = math.pi / 2 if self.rng.random() < 0.5 else -math.pi / 2
            body.position = (xx, self._hw + 1e-4)
        else:
            body.position = (xx, self._hh + 1e-4)
        body.velocity = (self.v_belt, 0.0)
        shape = pm.Poly.create_box(body, (w, hgt))
        shape.friction = self.friction
        shape.elasticity = 0.0
        self._space.add(body, shape)
        b = Bottle(self._next_id, slot, body, shape, self._hw, self._hh)
        self._next_id += 1
        b.fallen = fallen
        if not fallen and self.rng.random() < self.knock_rate:
            # knocked early enough to be lying flat when it reaches the eyes
            b.knock_x = self.rng.uniform(xx + 0.1, max(xx + 0.1, self.x_eye - KNOCK_LEAD))
        b.sync()
        self._bottles.append(b)
        self._poses.changed += 1
        self.counts["released"] += 1
        self._emit(
            "bottle_released",
            f"bottle {b.id} released{' lying' if fallen else ''}",
            id=b.id,
            slot=slot,
            fallen=fallen,
        )
        return b.id

    @property
    def bottles(self) -> list[dict[str, float]]:
        """The bottles on the line: id, slot, x, y, angle, fill (l), fallen."""
        return [
            {
                "id": b.id,
                "slot": b.slot,
                "x": b.x,
                "y": b.y,
                "angle": b.angle,
                "fill": b.fill,
                "fallen": float(b.fallen),
            }
            for b in self._bottles
        ]

    # ------------------------------------------------------------------ physics
    def _advance(self, h: float) -> None:
        io = self._io
        # belt drive: rate-limited speed, applied every physics step
        target = self.belt_speed if io["CONVEYOR"] else 0.0
        n = max(1, math.ceil(h / self.physics_dt - 1e-9))
        hs = h / n
        space = self._space
        belt = self._belt
        v = self.v_belt
        for _ in range(n):
            if v != target:
                if v < target:
                    v = min(target, v + self.belt_accel * hs)
                else:
                    v = max(target, v - self.belt_decel * hs)
                belt.surface_velocity = (v, 0.0)
            space.step(hs)
            self._travel += v * hs
        self.v_belt = v
        # cylinder
        if not self._cyl_stuck:
            e = self.cyl
            if io["REJECT"]:
                if e < 1.0:
                    e = min(1.0, e + h / self.extend_time)
            elif e > 0.0:
                e = max(0.0, e - h / self.retract_time)
            self.cyl = e
        # bottles
        hw, hh = self._hw, self._hh
        removed: list[Bottle] = []
        sweep = self.cyl >= 0.5
        half_plate = self.plate_width / 2.0
        # loop invariants (nothing in the loop moves the eyes, the plate or the belt's end)
        k_hi = self.x_eye - KNOCK_LEAD
        k_lo = k_hi - 0.2
        x_reject = self.x_reject
        end = self.belt_length
        gone = end + 1.0
        get_pos, get_angle = pose_getters() or (None, None)
        poses = self._poses.read(self._space, self._bottles)
        if poses is not None:  # every pose from one batched read (pymunk.batch)
            fl, idx = poses
            for b, i in zip(self._bottles, idx, strict=True):
                b.x = fl[i]
                b.y = fl[i + 1]
                a = fl[i + 2]
                if a != b.angle:
                    b.angle = a
        for b in self._bottles:
            if poses is not None:
                x = b.x
            elif b.cb is not None:  # b.sync() inline
                cb = b.cb
                v = get_pos(cb)  # type: ignore[misc]
                b.x = x = v.x
                b.y = v.y
                a = get_angle(cb)  # type: ignore[misc]
                if a != b.angle:
                    b.angle = a
            else:
                b.sync()
                x = b.x
            # |cos| >= cos(1 rad) = 0.54 > COS_FALLEN within 1 rad of upright: no cos needed
            if (not b.fallen and not b.passed and not -1.0 <= b.angle <= 1.0
                    and (b.trig() or abs(b.cos) < COS_FALLEN)):
                b.fallen = True
                self.counts["toppled"] += 1
                self._emit(
                    "bottle_toppled",
                    f"bottle {b.id} toppled at x = {x:.2f} m",
                    id=b.id,
                    x=x,
                    knocked=b.knocked,
                )
            if b.knock_x is not None and x >= b.knock_x and not b.fallen:
                self._knock(b)
            if (
                self._knocks_left > 0
                and not b.fallen
                and not b.knocked
                and k_lo <= x <= k_hi
            ):
                self._knock(b)
                self._knocks_left -= 1
                if self._knocks_left == 0 and "knock" in self._faults:
                    self.clear("knock")
            if sweep and abs(x - x_reject) < b.half_x(hw, hh) + half_plate and b.y < 0.5:
                removed.append(b)
                self._reject(b)
                continue
            if not b.passed and x > end:
                b.passed = True
                self._bin(b)
            if b.y < -0.4 or x > gone:
                removed.append(b)
                if not b.passed:
                    self.counts["lost"] += 1
        for b in removed:
            self._remove(b)
        # filling
        self._under = under = self._bottle_under_nozzle()
        if io["FILL_VALVE"]:
            vol = self.fill_flow * h
            spill = 0.0
            if under is not None:
                room = self.bottle_capacity - under.fill
                if vol > room:
                    spill = vol - room
                    under.fill = self.bottle_capacity
                    self.filled_volume += room
                else:
                    under.fill += vol
                    self.filled_volume += vol
            else:
                spill = vol
            if spill > 0.0:
                self.spilled_volume += spill
                if not self._spilling:
                    self._spilling = True
                    self.counts["spilled"] += 1
                    why = "the bottle overflows" if under is not None else "no bottle under it"
                    self._emit(
                        "spill",
                        f"the filling valve is open but {why}",
                        bottle=-1 if under is None else under.id,
                    )
            else:
                self._spilling = False
        else:
            self._spilling = False
        # feeder
        if self._travel >= self._pitch:
            if self.feed_limit is None or self.counts["released"] < self.feed_limit:
                if self._feed_spot_clear() and self._free:
                    self.release_bottle(fallen=self.rng.random() < self._topple)
                    self._travel = 0.0
                    pitch = self.feed_pitch or 0.0
                    if self.feed_jitter:
                        pitch *= 1.0 + self.feed_jitter * (2.0 * self.rng.random() - 1.0)
                    self._pitch = pitch

    def _knock(self, b: Bottle) -> None:
        b.knocked = True
        b.knock_x = None
        direction = 1.0 if self.rng.random() < 0.5 else -1.0
        b.body.apply_impulse_at_local_point((0.12 * direction, 0.0), (0.0, self._hh))

    def _bottle_under_nozzle(self) -> Bottle | None:
        tol = self.nozzle_tolerance
        xf = self.x_fill
        for b in self._bottles:
            if (abs(b.x - xf) <= tol and (b.trig() or abs(b.cos) >= COS_UPRIGHT)
                    and b.y < self.bottle_height):
                return b
        return None

    def _feed_spot_clear(self) -> bool:
        xf = self.x_feed
        need = self._hh + 0.05
        for b in self._bottles:
            if abs(b.x - xf) < need + b.half_x(self._hw, self._hh) and b.y < 0.5:
                return False
        return True

    def _reject(self, b: Bottle) -> None:
        c = self.counts
        c["rejected"] += 1
        c["fallen_rejected" if b.fallen else "standing_rejected"] += 1
        state = "fallen" if b.fallen else "standing"
        self._emit(
            "bottle_rejected",
            f"{state} bottle {b.id} pushed off into the reject bin",
            id=b.id,
            fallen=b.fallen,
            fill=b.fill,
        )

    def _bin(self, b: Bottle) -> None:
        c = self.counts
        c["binned"] += 1
        if b.fallen:
            kind = "fallen_passed"
        elif b.fill >= 0.95 * self.bottle_capacity:
            kind = "good"
        else:
            kind = "unfilled_passed"
        c[kind] += 1
        self._emit(
            "bottle_binned",
            f"bottle {b.id} left the belt ({kind})",
            id=b.id,
            result=kind,
            fill=b.fill,
            fallen=b.fallen,
        )

    def _remove(self, b: Bottle) -> None:
        self._space.remove(b.body, b.shape)
        self._bottles.remove(b)
        self._poses.changed += 1
        self._free.append(b.slot)
        self._free.sort(reverse=True)

    def _outputs(self) -> None:
        io = self._io
        xe = self.x_eye
        y1 = self.eye_x1_height
        y2 = self.eye_x2_height
        reach = self._hh + 0.01
        x1 = x2 = False
        eye_fill = False
        xfe = self.x_fill + self.fill_eye_offset
        yfe = min(0.5 * self.bottle_height, 0.1)
        for b in self._bottles:
            dx = b.x - xe
            if -reach < dx < reach:
                if not x1 and b.contains(xe, y1):
                    x1 = True
                if not x2 and b.contains(xe, y2):
                    x2 = True
            if not eye_fill:
                dx = b.x - xfe
                if -reach < dx < reach and b.contains(xfe, yfe):
                    eye_fill = True
        io["X1"] = x1 or self._x1_blocked
        io["X2"] = x2
        io["FILL_EYE"] = eye_fill
        e = self.cyl
        io["CYL_EXTENDED"] = e >= 0.999
        io["CYL_RETRACTED"] = e <= 0.001
        under = self._under
        io["FILL_LEVEL"] = 0.0 if under is None else 100.0 * under.fill / self.bottle_capacity
        io["BELT_SPEED"] = self.v_belt

    # ------------------------------------------------------------------ records
    def _line(self) -> tuple[float, ...]:
        """The values of :data:`~plants.conveyor_record.LINE_KEYS`, in that order."""
        return (self.spilled_volume, self.filled_volume, self.v_belt, self.cyl,
                float(len(self._bottles)))

    def snapshot(self) -> dict[str, float]:
        """Counters, belt and cylinder state and every slot's bottle id/x/y/angle (NaN = free)."""
        return self._layout.snapshot(self.counts, self._line(), self._bottles)

    def snapshot_row(self) -> list[float]:
        """:meth:`snapshot`'s values in its keys' order, built without a dict: what the
        simulation records every scan (``snapshot_keys()`` gives the keys once)."""
        return self._layout.row(self.counts, self._line(), self._bottles)

    def snapshot_keys(self) -> list[str]:
        """The keys of :meth:`snapshot`, in the order of :meth:`snapshot_row`."""
        return list(self.snapshot())

    def geometry(self) -> dict[str, Any]:
        return line_geometry(self)
