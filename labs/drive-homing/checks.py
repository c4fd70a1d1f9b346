"""Python checks of the drives lab: READY lights, and only while every axis is in position."""

from __future__ import annotations

WORK = {"BELT_POS": 250.0, "PISTON_POS": 100.0, "PUMP_POS": 40.0}


def ready_only_in_position(trace, tolerance=2.0):
    """READY_LAMP is TRUE at some time, and whenever it is, every axis is within
    ``tolerance`` mm of its work position."""
    import numpy as np

    ready = trace["READY_LAMP"].astype(bool)
    if not ready.any():
        return False, "READY never lights", None, ["READY_LAMP"]
    ok = np.ones_like(ready)
    for name, x in WORK.items():
        ok &= np.abs(trace[name].astype(float) - x) <= float(tolerance)
    bad = np.nonzero(ready & ~ok)[0]
    if len(bad):
        t = float(trace.time[bad[0]])
        return (False, f"READY lights at t = {t:.2f} s with an axis out of position", t,
                ["READY_LAMP", *WORK])
    return True, "READY lights only with every axis in its work position"
