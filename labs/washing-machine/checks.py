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
    drained = on & trace["DRAIN_VALVE"].astype(bool)
    if drained.any():  # the usual cause: a stored action that no later step resets
        k = int(np.nonzero(drained)[0][0])
        return (False, f"{msg}; it is still on at t = {float(t[k]):.1f} s while the water is "
                "drained", float(t[k]), [signal, "DRAIN_VALVE"])
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


def starts_only_on_start(trace, grace=2.0, window=1.0):
    """The machine (fill valve, heater or drum) starts only right after a START press made
    while the machine may start: STOP released, the door closed and the selector on exactly
    one programme. A start is a rising edge of "running" after ``grace`` s of standstill; it
    must follow such a press by at most ``window`` s. Covers a START refused (door open, STOP
    held, selector off) and a chart that carries on by itself after an abort."""
    import numpy as np

    t = trace.time
    sig = {n: trace[n].astype(bool) for n in ("FILL_VALVE", "HEATER", "MOTOR", "START", "STOP",
                                              "DOOR", "COTTON", "SILK")}
    running = sig["FILL_VALVE"] | sig["HEATER"] | sig["MOTOR"]
    ready = sig["STOP"] & sig["DOOR"] & (sig["COTTON"] ^ sig["SILK"])
    signals = ["START", "STOP", "DOOR", "COTTON", "SILK", "FILL_VALVE", "HEATER", "MOTOR"]
    on_idx = np.nonzero(running)[0]
    starts = np.nonzero(running & ~np.concatenate(([False], running[:-1])))[0]
    for i in starts:  # a machine running from the first scan started too
        now = float(t[i])
        before = on_idx[on_idx < i]
        if len(before) and now - float(t[before[-1]]) <= grace:
            continue  # a step change inside the programme, not a start
        near = (t >= now - window) & (t <= now)
        pressed = near & sig["START"]
        if (pressed & ready).any():
            continue
        if pressed.any():
            k = np.nonzero(pressed)[0][-1]
            why = [w for w, bad in (("the door open", not sig["DOOR"][k]),
                                    ("STOP pressed", not sig["STOP"][k]),
                                    ("the selector on no programme",
                                     not (sig["COTTON"][k] ^ sig["SILK"][k]))) if bad]
            return (False, f"the machine starts at t = {now:.1f} s on a START pressed with "
                    f"{' and '.join(why)}", now, signals)
        return (False, f"the machine starts by itself at t = {now:.1f} s: no START was pressed",
                now, signals)
    return True, "the machine starts only on START, with the door closed, STOP released and a programme selected"
