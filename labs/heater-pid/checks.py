"""Python checks of the heater-pid lab.

The criteria library has no check for an analog output that bangs between its limits; this one
counts the jumps from one limit to the other.
"""

from __future__ import annotations


def no_saturation_chatter(trace, signal="POWER", lo=1.0, hi=99.0, max_flips=4, window=60.0):
    """The output never goes from one limit (``<= lo``) to the other (``>= hi``) and back more
    than ``max_flips`` times within ``window`` seconds. Values in between are ignored, so a
    controller that saturates for a while during a big step passes, and one that behaves like
    an on/off switch around the set point fails."""
    import numpy as np

    x = trace[signal].astype(float)
    t = trace.time
    state = np.where(x <= float(lo), -1, np.where(x >= float(hi), 1, 0))
    flips = []
    last = 0
    for i in np.nonzero(state)[0]:
        s = int(state[i])
        if last and s != last:
            flips.append(float(t[i]))
        last = s
    k = int(max_flips)
    for j in range(len(flips) - k):
        if flips[j + k] - flips[j] <= float(window):
            return (False, f"{signal} jumped between {lo:g} and {hi:g} {k + 1} times between "
                    f"{flips[j]:.1f} s and {flips[j + k]:.1f} s ({len(flips)} jumps in all)",
                    flips[j], [signal])
    return True, f"{signal} jumped between its limits {len(flips)} time(s)"
