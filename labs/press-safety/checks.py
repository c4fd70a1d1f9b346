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


def _held_since(x, t, seconds):
    """Rows where the boolean ``x`` has been TRUE for more than ``seconds``."""
    import numpy as np

    x = np.asarray(x).astype(bool)
    out = np.zeros(len(x), dtype=bool)
    since = None
    for i, v in enumerate(x):
        if not v:
            since = None
        elif since is None:
            since = t[i]
        if since is not None and t[i] - since > seconds:
            out[i] = True
    return out


def curtain_stops(trace, react=0.05, curtain="LIGHT_CURTAIN", down="%QX0.0", up="%QX0.1"):
    """While the light curtain has been broken for longer than ``react`` seconds (the input
    filter and a scan or two), neither valve output is on: at rest, going down or going up."""
    import numpy as np

    t = trace.time
    broken = ~trace[curtain].astype(bool)
    if not broken.any():
        return False, "the light curtain is never broken in this scenario", None, [curtain]
    late = _held_since(broken, t, float(react))
    valves = trace[down].astype(bool) | trace[up].astype(bool)
    bad = np.nonzero(late & valves)[0]
    if len(bad):
        i = int(bad[0])
        which = "DOWN" if trace[down][i] else "UP"
        where = "at rest" if trace["TOP"][i] else f"at {float(trace['POSITION'][i]):.0f} mm"
        return (False, f"{which} is on at t = {t[i]:.2f} s while the light curtain is broken "
                f"(the piston {where})", float(t[i]), [curtain, "DOWN", "UP", "POSITION"])
    return True, "both valves off whenever the light curtain is broken"


def returns_when_clear(trace, time=0.5, curtain="LIGHT_CURTAIN", top_mm=5.0):
    """Each time the curtain clears with the piston away from the top, ``UP`` is on within
    ``time`` seconds and ``DOWN`` stays off until the piston is back at TOP."""
    import numpy as np

    t = trace.time
    clear = trace[curtain].astype(bool)
    pos = trace["POSITION"].astype(float)
    up = trace["%QX0.1"].astype(bool)
    dn = trace["%QX0.0"].astype(bool)
    top = trace["TOP"].astype(bool)
    n = 0
    for i in _rises(clear):
        if pos[i] <= top_mm:
            continue
        n += 1
        k = int(np.searchsorted(t, t[i] + float(time), "right"))
        if not up[i:k].any():
            return (False, f"the field is clear at t = {t[i]:.2f} s with the piston at "
                    f"{pos[i]:.0f} mm, but UP does not come within {float(time):g} s",
                    float(t[i]), [curtain, "UP", "POSITION"])
        at_top = np.nonzero(top[i:])[0]
        j = i + int(at_top[0]) if len(at_top) else len(t)
        if dn[i:j].any():
            m = i + int(np.nonzero(dn[i:j])[0][0])
            return (False, f"DOWN at t = {t[m]:.2f} s, after the field cleared and before the "
                    "piston was back at the top", float(t[m]), [curtain, "DOWN", "POSITION"])
    if not n:
        return True, "the field never cleared with the piston away from the top"
    return True, f"{n} time(s) the field cleared: the piston went back up"


def estop_no_restart(trace, react=0.05, skew=0.5):
    """After each E-stop: the valves stay off from the press (+``react``) until a two-hand
    command given after the release (a button pressed after it, the other within ``skew``
    seconds); that command only returns the piston: DOWN stays off until both buttons have
    been released and pressed again."""
    import numpy as np

    t = trace.time
    es = trace["E_STOP"].astype(bool)
    lx = trace["%IX0.0"].astype(bool)
    rx = trace["%IX0.1"].astype(bool)
    dn = trace["%QX0.0"].astype(bool)
    valves = dn | trace["%QX0.1"].astype(bool)
    falls = _rises(~es)
    if not len(falls):
        return False, "the E-stop is never pressed in this scenario", None, ["E_STOP"]
    sig = ["E_STOP", "HAND_L", "HAND_R", "DOWN", "UP"]
    for f in falls:
        rel = np.nonzero(es[f:])[0]
        r = f + int(rel[0]) if len(rel) else len(t)
        # the first command after the release: both on, one of them pressed after the release
        both = lx & rx
        cmd = len(t)
        for i in np.nonzero(both[r:])[0] + r:
            li, ri = _rises(lx[r:i + 1]), _rises(rx[r:i + 1])
            if len(li) and len(ri) and abs(float(t[r + li[-1]] - t[r + ri[-1]])) <= skew + 0.03:
                cmd = int(i)
                break
        i0 = int(np.searchsorted(t, t[f] + float(react)))
        bad = np.nonzero(valves[i0:cmd])[0]
        if len(bad):
            k = i0 + int(bad[0])
            when = "while the E-stop is pressed" if k < r else "after the E-stop was released"
            return (False, f"a valve is on at t = {t[k]:.2f} s {when}, without a new two-hand "
                    "command", float(t[k]), sig)
        if cmd < len(t):
            off = np.nonzero(~lx[cmd:] & ~rx[cmd:])[0]
            end = cmd + int(off[0]) if len(off) else len(t)
            bad = np.nonzero(dn[cmd:end])[0]
            if len(bad):
                k = cmd + int(bad[0])
                return (False, f"the command after the E-stop (t = {t[cmd]:.2f} s) also starts "
                        f"a dose at t = {t[k]:.2f} s: it may only bring the piston back up",
                        float(t[k]), sig)
    return True, "after each E-stop nothing moved until a new two-hand command returned the piston"
