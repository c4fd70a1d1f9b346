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
