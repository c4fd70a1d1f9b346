"""Python checks of the washing-machine lab: how long the heater was on, and whether the
programme ended (tub empty, every output off)."""

from __future__ import annotations


def heating_time(trace, seconds=600.0, tolerance=2.0, signal="HEATER"):
    """The heater was on for ``seconds`` in all (± ``tolerance``)."""
    import numpy as np

    t = trace.time
    on = trace[signal].astype(bool)
    dt = np.diff(t, append=trace.t_end)
    total = float(np.sum(dt[on]))
    ok = abs(total - float(seconds)) <= float(tolerance)
    msg = f"{signal} was on for {total:.1f} s in all ({float(seconds):g} s expected)"
    if ok:
        return True, msg
    first = np.nonzero(on)[0]
    return False, msg, float(t[first[0]]) if len(first) else None, [signal]


def finished(trace, settle=5.0):
    """During the last ``settle`` seconds the tub is empty and every output is off, and the
    machine did run (the fill valve was opened)."""
    import numpy as np

    t = trace.time
    if not trace["FILL_VALVE"].astype(bool).any():
        return False, "the fill valve never opened: the programme did not start", None, ["START"]
    tail = t >= trace.t_end - float(settle)
    outputs = ["FILL_VALVE", "DRAIN_VALVE", "HEATER", "MOTOR"]
    on = [o for o in outputs if trace[o].astype(bool)[tail].any()]
    empty = bool(np.all(trace["EMPTY"].astype(bool)[tail]))
    if on or not empty:
        what = ", ".join(on + ([] if empty else ["the tub is not empty"]))
        return False, f"at the end: {what}", float(trace.t_end - settle), ["EMPTY"] + outputs
    return True, "the programme ended: the tub is empty and every output is off"
