"""Python checks of the water-boiler lab.

The criteria library checks a band with ``always``, but a fill valve switched at one point in
the middle of the band keeps the level in it too. This check looks at the level at every
moment the valve changes: it must open only low in the band and close only high in it.
"""

from __future__ import annotations


def switch_points(trace, signal="FILL_VALVE", level="LEVEL", open_below=0.53,
                  close_above=0.67, min_cycles=1, start=0.0):
    """Every time ``signal`` opens (FALSE -> TRUE) the ``level`` is at most ``open_below``,
    every time it closes the level is at least ``close_above``, from ``start`` seconds on; and
    the valve completes at least ``min_cycles`` open-close cycles (a valve that never moves
    proves nothing). Returns ``(passed, message, t_fail, signals)``."""
    import numpy as np

    t = trace.time
    v = trace[signal].astype(bool)
    x = trace[level].astype(float)
    idx = np.nonzero(v[1:] != v[:-1])[0] + 1
    idx = idx[t[idx] >= float(start)]
    sigs = [level, signal]
    opens = closes = 0
    for i in idx:
        lv, ti = float(x[i]), float(t[i])
        if v[i]:
            opens += 1
            if lv > float(open_below):
                return (False, f"{signal} opened at t = {ti:.1f} s with the level at {lv:.3f} m "
                        f"(it should open only below {open_below:g} m)", ti, sigs)
        else:
            closes += 1
            if lv < float(close_above):
                return (False, f"{signal} closed at t = {ti:.1f} s with the level at {lv:.3f} m "
                        f"(it should close only above {close_above:g} m)", ti, sigs)
    cycles = min(opens, closes)
    if cycles < int(min_cycles):
        return (False, f"{signal} opened {opens} and closed {closes} time(s) from {start:g} s "
                f"on: at least {int(min_cycles)} full cycle(s) expected", float(start), sigs)
    return True, (f"{signal} opened {opens} time(s), always at or below {open_below:g} m, and "
                  f"closed {closes} time(s), always at or above {close_above:g} m")
