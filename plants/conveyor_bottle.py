"""A bottle of the conveyor: its pymunk body and shape, its pose, and the geometry of a tilted
box that the photo-eyes, the reject plate and the nozzle ask about.

Reading a pose is the conveyor's hot path (issue 19): a bottle reads its body through pymunk's
own C getters when this pymunk has them (:func:`find_pose_getters`), and the conveyor reads
every bottle at once through pymunk's batch API when it is there (:class:`PoseReader`).
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["COS_FALLEN", "COS_UPRIGHT", "Bottle", "PoseReader", "batch_reader",
           "find_pose_getters", "pose_getters"]

COS_FALLEN = 0.5  # |cos(angle)| below this: fallen (tilted more than 60 degrees)
COS_UPRIGHT = 0.95  # |cos(angle)| above this: upright enough to be filled

# pymunk's C getters of a body's position and angle (what Body.position and Body.angle call),
# found when the first conveyor is built; None when this pymunk does not have them
_POSE: tuple[Any, Any] | None = None


def find_pose_getters() -> None:
    """Look for pymunk's C pose getters once (every conveyor's reset asks; cheap after the
    first)."""
    global _POSE
    if _POSE is not None:
        return
    try:
        from pymunk._chipmunk_cffi import lib
    except ImportError:  # pragma: no cover - another pymunk: use its properties
        return
    get_pos = getattr(lib, "cpBodyGetPosition", None)
    get_angle = getattr(lib, "cpBodyGetAngle", None)
    if get_pos is not None and get_angle is not None:
        _POSE = (get_pos, get_angle)


def pose_getters() -> tuple[Any, Any] | None:
    """(position getter, angle getter) that :func:`find_pose_getters` found, or None."""
    return _POSE


def batch_reader(pymunk: Any) -> tuple[Any, Any, Any] | None:
    """(buffer, fields, get_space_bodies) of pymunk's batch API (pymunk 6.6+), else None."""
    try:
        from pymunk import batch
    except ImportError:  # pragma: no cover - an older pymunk: one call a bottle
        return None
    fields = batch.BodyFields.BODY_ID | batch.BodyFields.POSITION | batch.BodyFields.ANGLE
    return batch.Buffer(), fields, batch.get_space_bodies


class PoseReader:
    """Every bottle's pose from one call of pymunk's batch API instead of two C calls a bottle;
    ``batch`` is None without that API, and then :meth:`read` gives None."""

    def __init__(self, pymunk: Any) -> None:
        self.batch = batch_reader(pymunk)
        self.changed = 0  # the conveyor counts releases and removals here (the index below)
        self._key: tuple[list[int], int] | None = None
        self._idx: list[int] = []

    def read(self, space: Any, bottles: list[Bottle]) -> tuple[list[float], list[int]] | None:
        """(x, y, angle of every body of *space* in its order, where each of *bottles* starts)."""
        batch = self.batch
        if batch is None:
            return None
        buf, fields, get = batch
        buf.clear()
        get(space, fields, buf)
        ids = memoryview(buf.int_buf()).cast("Q").tolist()
        key = (ids, self.changed)
        if key != self._key:  # a body came or went: where each bottle is now
            self._key = key
            where = {bid: 3 * j for j, bid in enumerate(ids)}
            self._idx = [where[b.body.id] for b in bottles]
        return memoryview(buf.float_buf()).cast("d").tolist(), self._idx


class Bottle:
    """A bottle on the belt: id, slot, body, shape, half sizes, fill (l) and its state; ``x``,
    ``y`` and ``angle`` are its pose at the last read, ``cos`` and ``sin`` of ``ta``."""

    __slots__ = ("angle", "body", "cb", "cos", "fallen", "fill", "hh", "hw", "id", "knock_x",
                 "knocked", "passed", "shape", "sin", "slot", "ta", "x", "y")

    def __init__(self, bid: int, slot: int, body: Any, shape: Any, hw: float, hh: float) -> None:
        self.id = bid
        self.hw = hw
        self.hh = hh
        self.slot = slot
        self.body = body
        self.cb = getattr(body, "_body", None) if _POSE is not None else None
        self.shape = shape
        self.fill = 0.0
        self.fallen = False
        self.knock_x: float | None = None
        self.knocked = False
        self.passed = False
        self.x = self.y = self.angle = 0.0
        self.ta = 0.0  # the angle of cos and sin (worked out when first needed: trig)
        self.cos = 1.0
        self.sin = 0.0

    def sync(self) -> None:
        cb = self.cb
        if cb is not None:  # pymunk's own getters without its properties (issue 19)
            v = _POSE[0](cb)
            self.x = v.x
            self.y = v.y
            a = _POSE[1](cb)
        else:
            body = self.body
            self.x, self.y = body.position
            a = body.angle
        if a != self.angle:
            self.angle = a

    def trig(self) -> None:
        """Bring ``cos`` and ``sin`` up to the angle (only bottles near a sensor, a plate or
        the feeder need them, and a tilt test only beyond 1 rad: issue 19)."""
        a = self.angle
        if a != self.ta:
            self.ta = a
            self.cos = math.cos(a)
            self.sin = math.sin(a)

    def contains(self, px: float, py: float) -> bool:
        """Is the point inside the bottle's rotated rectangle (a beam broken)?"""
        self.trig()
        dx = px - self.x
        dy = py - self.y
        c = self.cos
        s = self.sin
        lx = dx * c + dy * s
        ly = -dx * s + dy * c
        hw = self.hw
        hh = self.hh
        return -hw <= lx <= hw and -hh <= ly <= hh

    def half_x(self, hw: float, hh: float) -> float:
        """Half extent of the bottle along the belt."""
        self.trig()
        return hw * abs(self.cos) + hh * abs(self.sin)
