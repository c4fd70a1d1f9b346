"""Python checks of the drives lab.

The library has no check for "after each START", "between a fault and the next RESET and START"
or "8 s after the move began": these find those moments in the trace itself (the plant's START,
RESET and fault signals), so they hold for any timing of a scenario.
"""

from __future__ import annotations

WORK = {"BELT_POS": 250.0, "PISTON_POS": 100.0, "PUMP_POS": 40.0}
AXES = ("BELT", "PISTON", "PUMP")
MOTION = [f"{a}_{d}" for a in AXES for d in ("FWD", "REV")]


def _rises(x):
    import numpy as np

    x = np.asarray(x).astype(bool)
    return np.nonzero(x[1:] & ~x[:-1])[0] + 1


def _any(trace, names):
    import numpy as np

    out = np.zeros(len(trace.time), dtype=bool)
    for n in names:
        out |= trace[n].astype(bool)
    return out


def _all_home(trace):
    import numpy as np

    out = np.ones(len(trace.time), dtype=bool)
    for a in AXES:
        out &= trace[f"{a}_HOME"].astype(bool)
    return out


def ready_only_in_position(trace, tolerance=2.0):
    """READY_LAMP is TRUE at some time, and whenever it is, every axis is within
    ``tolerance`` mm of its work position and ALARM_LAMP is dark."""
    import numpy as np

    t = trace.time
    ready = trace["READY_LAMP"].astype(bool)
    if not ready.any():
        return False, "READY never lights", None, ["READY_LAMP"]
    alarm = trace["ALARM_LAMP"].astype(bool) & ready
    if alarm.any():
        i = int(np.nonzero(alarm)[0][0])
        return (False, f"READY and ALARM are lit together at t = {t[i]:.2f} s: an alarm ends "
                "READY", float(t[i]), ["READY_LAMP", "ALARM_LAMP"])
    for name, x in WORK.items():
        off = ready & (np.abs(trace[name].astype(float) - x) > float(tolerance))
        if off.any():
            i = int(np.nonzero(off)[0][0])
            axis = name.split("_")[0].lower()
            return (False, f"READY lights at t = {t[i]:.2f} s while the {axis} stands at "
                    f"{float(trace[name][i]):.1f} mm, not at its work position {x:g} mm",
                    float(t[i]), ["READY_LAMP", *WORK])
    return True, "READY lights only with every axis in its work position"


def moves_after_all_home(trace, backoff=5.0):
    """After each START press, no axis moves more than ``backoff`` mm away from home (its
    lowest position since the press) before all three home switches are closed together."""
    import numpy as np

    t = trace.time
    presses = list(_rises(trace["START"]))
    home = _all_home(trace)
    ends = presses[1:] + [len(t)]
    for i0, i1 in zip(presses, ends, strict=True):
        seg = slice(i0, i1)
        h = np.nonzero(home[seg])[0]
        stop = i0 + int(h[0]) if len(h) else i1
        first = None
        for a in AXES:
            pos = trace[f"{a}_POS"].astype(float)[i0:stop]
            if not len(pos):
                continue
            away = pos - np.minimum.accumulate(pos)
            bad = np.nonzero(away > float(backoff))[0]
            if len(bad) and (first is None or i0 + int(bad[0]) < first[0]):
                first = (i0 + int(bad[0]), a)
        if first is not None:
            k, a = first
            return (False, f"the {a.lower()} moves away from home at t = {t[k]:.2f} s, "
                    "before every drive is home", float(t[k]),
                    ["START", f"{a}_POS", "BELT_HOME", "PISTON_HOME", "PUMP_HOME"])
    return True, f"{len(presses)} START press(es): the moves begin once every drive is home"


def cycle_after(trace):
    """After the last START press every drive is home together, and READY lights after that."""
    import numpy as np

    t = trace.time
    presses = _rises(trace["START"])
    if not len(presses):
        return False, "START is never pressed", None, ["START"]
    i0 = int(presses[-1])
    h = np.nonzero(_all_home(trace)[i0:])[0]
    if not len(h):
        return (False, f"after the START at t = {t[i0]:.2f} s the drives are not all home "
                "together: no new homing", float(t[i0]),
                ["START", "BELT_HOME", "PISTON_HOME", "PUMP_HOME"])
    ih = i0 + int(h[0])
    r = np.nonzero(trace["READY_LAMP"].astype(bool)[ih:])[0]
    if not len(r):
        return (False, f"after the START at t = {t[i0]:.2f} s every drive is home at "
                f"t = {t[ih]:.2f} s, but READY never lights again", float(t[ih]),
                ["START", "READY_LAMP", *WORK])
    return True, (f"START at {t[i0]:.2f} s: home at {t[ih]:.2f} s, READY at "
                  f"{t[ih + int(r[0])]:.2f} s")


def stopped_until(trace, react=0.1):
    """After each drive fault (a FAULT contact closing), every contactor stays off from
    ``react`` seconds on until the first START press that follows a RESET press."""
    import numpy as np

    t = trace.time
    fault = _any(trace, [f"{a}_FAULT" for a in AXES])
    trips = _rises(fault)
    if fault[0]:
        trips = np.concatenate(([0], trips))
    if not len(trips):
        return False, "no drive fault in this scenario", None, []
    moving = _any(trace, MOTION)
    resets = _rises(trace["RESET"])
    starts = _rises(trace["START"])
    for i in trips:
        i0 = int(np.searchsorted(t, t[i] + float(react)))
        r = resets[resets > i]
        end = len(t)
        if len(r):
            s = starts[starts > r[0]]
            end = int(s[0]) if len(s) else len(t)
        bad = np.nonzero(moving[i0:end])[0]
        if len(bad):
            k = i0 + int(bad[0])
            what = [n for n in MOTION if trace[n][k]]
            return (False, f"{', '.join(what)} on at t = {t[k]:.2f} s, after the fault at "
                    f"t = {t[i]:.2f} s and before RESET and a new START", float(t[k]),
                    ["START", "RESET", "ALARM_LAMP", *what])
    return True, "nothing moves between a fault and the next RESET and START"


def move_timeout(trace, axis="PUMP", timeout=8.0, slack=0.35):
    """The move of ``axis`` (its first forward run) is stopped ``timeout`` seconds after it
    began (+- ``slack``): ALARM lights then, not before, and every contactor is off after it."""
    import numpy as np

    t = trace.time
    fwd = trace[f"{axis}_FWD"].astype(bool)
    on = np.nonzero(fwd)[0]
    if not len(on):
        return False, f"the {axis.lower()} never starts its move", None, [f"{axis}_FWD"]
    t0 = float(t[on[0]])
    alarm = trace["ALARM_LAMP"].astype(bool)
    a = np.nonzero(alarm)[0]
    sig = [f"{axis}_POS", f"{axis}_FWD", "ALARM_LAMP"]
    if not len(a) or t[a[0]] > t0 + timeout + slack:
        k = int(np.searchsorted(t, t0 + timeout + slack))
        return (False, f"the {axis.lower()}'s move began at t = {t0:.2f} s and no alarm came "
                f"{timeout:g} s later", float(t[min(k, len(t) - 1)]), sig)
    ta = float(t[a[0]])
    if ta < t0 + timeout - slack:
        return (False, f"the alarm came {ta - t0:.2f} s after the {axis.lower()}'s move began, "
                f"before its {timeout:g} s were over", ta, sig)
    i1 = int(np.searchsorted(t, ta + 0.1))
    moving = _any(trace, MOTION)
    bad = np.nonzero(moving[i1:] | ~alarm[i1:])[0]
    if len(bad):
        k = i1 + int(bad[0])
        return (False, f"after the timeout at t = {ta:.2f} s a drive moves again or the alarm "
                f"goes out at t = {t[k]:.2f} s", float(t[k]), [*sig, *MOTION])
    return True, f"the move began at {t0:.2f} s, the timeout stopped it at {ta:.2f} s"
