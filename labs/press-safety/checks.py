"""Python checks of the press-safety lab.

The criteria library has no check for a two-hand control (the second button within a time of
the first, a new press for every stroke) nor for a dose measured as piston travel per stroke;
these read the PLC's inputs and outputs and the piston position in the trace.
"""

from __future__ import annotations


def _rises(x):
    import numpy as np

    x = x.astype(bool)
    return np.nonzero(x[1:] & ~x[:-1])[0] + 1


def two_hand(trace, skew=0.5, tol=0.03, left="%IX0.0", right="%IX0.1", down="%QX0.0"):
    """Every down stroke starts with both hands on their buttons, the second pressed within
    ``skew`` seconds of the first, and each stroke needs a press of its own."""

    t = trace.time
    lx = trace[left].astype(bool)
    rx = trace[right].astype(bool)
    l_up = _rises(lx)
    r_up = _rises(rx)
    last_press = None
    n = 0
    for i in _rises(trace[down]):
        ts = float(t[i])
        if not (lx[i] and rx[i]):
            return (False, f"the press started down at t = {ts:.2f} s without both hands on the "
                    "buttons", ts, ["HAND_L", "HAND_R", "DOWN"])
        li = l_up[l_up <= i]
        ri = r_up[r_up <= i]
        tl = float(t[li[-1]]) if len(li) else float(t[0])
        tr_ = float(t[ri[-1]]) if len(ri) else float(t[0])
        if abs(tl - tr_) > float(skew) + float(tol):
            first, second = ("left", "right") if tl < tr_ else ("right", "left")
            return (False, f"the press started down at t = {ts:.2f} s, but the {second} hand "
                    f"came {abs(tl - tr_):.2f} s after the {first} one (within {float(skew):g} s "
                    "allowed): a taped-down button must not count", ts,
                    ["HAND_L", "HAND_R", "DOWN"])
        press = max(tl, tr_)
        if last_press is not None and abs(press - last_press) < 1e-9:
            return (False, f"a second down stroke at t = {ts:.2f} s without releasing and pressing "
                    "both buttons again", ts, ["HAND_L", "HAND_R", "DOWN"])
        last_press = press
        n += 1
    return True, f"{n} stroke(s), each started by both hands within {float(skew):g} s"


def dose(trace, pulses=60, per_mm=1.0, tol=2.0, count=None, down="DOWN", position="POSITION"):
    """Each down stroke moves the piston by ``pulses / per_mm`` mm (+- ``tol``); with ``count``,
    exactly that many strokes."""
    import numpy as np

    t = trace.time
    d = trace[down].astype(bool)
    pos = trace[position].astype(float)
    want = float(pulses) / float(per_mm)
    starts = _rises(d)
    if d[0]:
        starts = np.concatenate(([0], starts))
    travels = []
    for i in starts:
        off = np.nonzero(~d[i:])[0]
        j = i + int(off[0]) if len(off) else len(d) - 1
        k = int(np.searchsorted(t, t[j] + 0.5, "right"))
        travel = float(pos[i:max(k, j + 1)].max() - pos[i])
        travels.append(travel)
        if abs(travel - want) > float(tol):
            return (False, f"the stroke at t = {t[i]:.2f} s moved the piston {travel:.1f} mm, "
                    f"{want:g} mm (= {int(pulses)} encoder pulses) expected", float(t[i]),
                    ["POSITION", "ENCODER_PULSE", "DOWN"])
    if count is not None and len(travels) != int(count):
        return (False, f"{len(travels)} dose stroke(s), {int(count)} expected",
                float(t[-1]), ["POSITION", "DOWN"])
    shown = ", ".join(f"{x:.1f}" for x in travels)
    return True, f"{len(travels)} stroke(s) of {shown} mm ({want:g} mm expected)"
