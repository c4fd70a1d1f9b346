"""Python checks of the pump-station lab.

The criteria library has no check for "B starts only after A has run for a time (or a switch
closed)" nor for "at least N seconds between the starts of several outputs"; these two read
the rising edges of the pump contactors in the trace.
"""

from __future__ import annotations


def _rises(trace, name):
    import numpy as np

    x = trace[name].astype(bool)
    idx = np.nonzero(x[1:] & ~x[:-1])[0] + 1
    return [float(trace.time[i]) for i in idx]


def _on_since(trace, name, t):
    """The start of the ON interval of ``name`` that holds at ``t`` (None if it is off)."""
    import numpy as np

    x = trace[name].astype(bool)
    tt = trace.time
    i = int(np.searchsorted(tt, t, "right")) - 1
    if i < 0 or not x[i]:
        return None
    off = np.nonzero(~x[: i + 1])[0]
    j = int(off[-1]) + 1 if len(off) else 0
    return float(tt[j])


def stage(trace, first="NS1", second="NS2", switch="PWY", delay=120.0, tol=2.0, lookback=10.0):
    """The pump ``second`` is added in stage: it starts only when ``first`` has run for
    ``delay`` seconds or the level switch ``switch`` closed (in the last ``lookback`` s), and it
    does run once ``first`` has run ``delay + tol`` seconds."""
    import numpy as np

    delay, tol = float(delay), float(tol)
    sw = trace[switch].astype(bool)
    tt = trace.time
    for t in _rises(trace, second):
        lo = int(np.searchsorted(tt, t - float(lookback), "left"))
        hi = int(np.searchsorted(tt, t, "right"))
        if sw[lo:hi].any():
            continue
        since = _on_since(trace, first, t)
        if since is None:
            return (False, f"{second} started at t = {t:.1f} s although {first} was off and "
                    f"{switch} was not reached", t, [first, second, switch])
        if t - since < delay - tol:
            return (False, f"{second} started at t = {t:.1f} s, only {t - since:.1f} s after "
                    f"{first} (the stage time is {delay:g} s and {switch} was not reached)", t,
                    [first, second, switch])
    x1 = trace[first].astype(bool)
    x2 = trace[second].astype(bool)
    for t in _rises(trace, first) + ([float(tt[0])] if len(x1) and x1[0] else []):
        due = t + delay + tol
        if due > trace.t_end:
            continue
        k = int(np.searchsorted(tt, due, "right")) - 1
        s = _on_since(trace, first, due)
        if s is not None and abs(s - t) < 1e-9 and not x2[k]:
            return (False, f"{first} has run since t = {t:.1f} s, but {second} was still off at "
                    f"t = {due:.1f} s (it should join after {delay:g} s)", due,
                    [first, second, switch])
    n = len(_rises(trace, second))
    return True, f"{second} joined {first} in stage ({n} start(s))"


def start_gap(trace, signals=("NS1", "NS2", "NS3"), gap=5.0, tol=0.2):
    """Never two pump starts within ``gap`` seconds of each other (inrush current)."""
    starts = sorted((t, s) for s in signals for t in _rises(trace, s))
    for (t0, s0), (t1, s1) in zip(starts, starts[1:], strict=False):
        if t1 - t0 < float(gap) - float(tol):
            return (False, f"{s0} started at t = {t0:.1f} s and {s1} only {t1 - t0:.1f} s later "
                    f"(at least {float(gap):g} s apart)", t1, [s0, s1])
    return True, f"{len(starts)} pump start(s), each at least {float(gap):g} s after the last"


def latched(trace, pumps=("NS1", "NS2", "NS3"), low="NY", tol=2.0):
    """Every pump, once started, runs until the water falls below the low level: each time a
    pump goes off, ``low`` went FALSE at most ``tol`` seconds before (or the pump stops with
    the low level at most ``tol`` later). A pump that follows a level switch stops while the
    water is still above the low level and fails."""
    import numpy as np

    t = trace.time
    ny = trace[low].astype(bool)
    for name in pumps:
        x = trace[name].astype(bool)
        for i in np.nonzero(~x[1:] & x[:-1])[0] + 1:
            ts = float(t[i])
            a = int(np.searchsorted(t, ts - float(tol), "left"))
            b = int(np.searchsorted(t, ts + float(tol), "right"))
            if ny[a:b].all():
                return (False, f"{name} stopped at t = {ts:.1f} s while the water was still above "
                        f"the low level {low}: a pump must stay on until {low}", ts,
                        [name, low, "LEVEL"])
    return True, f"{', '.join(pumps)} ran each time until the low level {low}"
