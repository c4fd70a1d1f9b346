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


def steady_output(trace, signal="POWER", max_std=3.0, start=0.0, end=None):
    """In a steady stretch (``start`` .. ``end`` seconds) the output's standard deviation is
    at most ``max_std`` (its unit). A controller that holds the temperature only through a
    huge proportional gain passes the measurement noise to the element, amplified; a PI
    controller holds it with a calm output."""
    import numpy as np

    t = trace.time
    b = trace.t_end if end is None else float(end)
    sel = (t >= float(start)) & (t < b)
    x = trace[signal].astype(float)[sel]
    if len(x) < 2:
        return False, f"no samples of {signal} between {start:g} s and {b:g} s"
    std = float(np.std(x))
    msg = (f"{signal} varied by {std:.2f} (standard deviation) between {start:g} s and {b:g} s "
           f"around a mean of {float(np.mean(x)):.1f} (at most {max_std:g} allowed)")
    if std <= float(max_std):
        return True, msg
    return False, msg, float(start), [signal, "TEMP"]
