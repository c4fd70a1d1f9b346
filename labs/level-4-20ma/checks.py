"""Python checks of the level-4-20ma lab.

The library's ``always``/``never`` take one window; a scenario with two failures of the loop
needs the same condition in several windows.
"""

from __future__ import annotations

LAMP = "%QX0.1"


def _first_bad(trace, name, windows, want):
    """The first time within ``windows`` at which ``name`` is not ``want`` (None: never)."""
    import numpy as np

    x = trace[name].astype(bool)
    tt = trace.time
    for a, b in windows:
        inside = (tt >= float(a)) & (tt <= float(b))
        bad = np.nonzero(inside & (x != bool(want)))[0]
        if len(bad):
            return float(tt[bad[0]])
    return None


def _spans(windows):
    return ", ".join(f"{float(a):g}-{float(b):g} s" for a, b in windows)


def lamp_during(trace, windows=()):
    """The FAULT lamp (%QX0.1) is on throughout every window ``[from, to]`` (seconds)."""
    t = _first_bad(trace, LAMP, windows, True)
    if t is None:
        return True, f"FAULT was on during {_spans(windows)}", None, [LAMP, "%IW64"]
    return False, f"FAULT was off at t = {t:.2f} s while the loop had failed", t, [LAMP, "%IW64"]


def off_during(trace, signal="PUMP", windows=()):
    """``signal`` is off throughout every window ``[from, to]`` (seconds)."""
    t = _first_bad(trace, signal, windows, False)
    if t is None:
        return True, f"{signal} was off during {_spans(windows)}", None, [signal, LAMP]
    return False, f"{signal} was on at t = {t:.2f} s while the loop had failed", t, [signal,
                                                                                      LAMP]


def switch_levels(trace, on_max=0.7, off_min=1.3, settle=1.0):
    """The two-position control switches where the README says: the pump goes on only with the
    level at or below ``on_max`` m and off only at or above ``off_min`` m. Switchings while the
    fault lamp is on, and within ``settle`` s of the lamp changing, are not judged (a failed
    measurement stops the pump at any level, and after the repair the control resumes)."""
    import numpy as np

    t = trace.time
    pump = trace["PUMP"].astype(bool)
    lamp = trace[LAMP].astype(bool)
    level = trace["LEVEL"].astype(float)
    changed = np.zeros(len(t), dtype=bool)
    changed[1:] = lamp[1:] != lamp[:-1]
    last = np.maximum.accumulate(np.where(changed, t, -np.inf)) if len(t) else t
    judged = ~lamp & (t - last >= float(settle))
    for i in np.nonzero(pump[1:] != pump[:-1])[0] + 1:
        if not judged[i]:
            continue
        if pump[i] and level[i] > float(on_max):
            return (False, f"the pump started at t = {t[i]:.1f} s with the level at "
                    f"{level[i]:.2f} m: it must start only below the lower limit",
                    float(t[i]), ["PUMP", "LEVEL"])
        if not pump[i] and level[i] < float(off_min):
            return (False, f"the pump stopped at t = {t[i]:.1f} s with the level at "
                    f"{level[i]:.2f} m: it must run on up to the upper limit",
                    float(t[i]), ["PUMP", "LEVEL"])
    return (True, f"the pump started below {float(on_max):g} m and stopped above "
            f"{float(off_min):g} m", None, ["PUMP", "LEVEL"])
