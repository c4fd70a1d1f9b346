"""Python checks of the modbus-operator lab.

The station's writes (holding register 0 = %MW0, the command; register 1 = %MW2, the set point)
are scenario actions, recorded in the trace as ``scenario`` events whose message is
``var %MW0 := 1``. The program clears the command in the scan that reads it, so the trace of
%MW0 itself shows only commands that were *not* acknowledged; the checks take the writes from
the events and compare the plant and the status word with what the station asked for.
"""

from __future__ import annotations

import re

CMD, SP, STATUS, OUT = "%MW0", "%MW2", "%MW20", "%QX0.0"
_WRITE = re.compile(r"var\s+(%MW\d+)\s*:=\s*(-?\d+)")
SP_LO, SP_HI = 300, 1700


def writes(trace, address):
    """``[(t, value)]`` of the station's writes to ``address``, in time order."""
    out = []
    for e in trace.events_of("scenario"):
        m = _WRITE.search(e.message or "")
        if m and m.group(1).upper() == address:
            out.append((float(e.time), int(m.group(2))))
    return sorted(out)


def running_periods(trace):
    """``[(start, stop)]`` from the START (1) and STOP (2) commands; other values are ignored."""
    periods, start = [], None
    for t, v in writes(trace, CMD):
        if v == 1 and start is None:
            start = t
        elif v == 2 and start is not None:
            periods.append((start, t))
            start = None
    if start is not None:
        periods.append((start, float(trace.t_end)))
    return periods


def _value(trace, name, t):
    return float(trace.value_at(name, min(t, trace.t_end - 1e-9)))


def acknowledged(trace, within=0.1):
    """Every nonzero value of CMD (%MW0) goes back to 0 within ``within`` seconds."""
    x = trace[CMD].astype(float) != 0
    tt = trace.time
    start = None
    for i in range(len(x)):
        if x[i] and start is None:
            start = float(tt[i])
        elif not x[i]:
            start = None
        if start is not None and float(tt[i]) - start > float(within):
            return (False, f"CMD (%MW0) still holds {int(trace[CMD][i])} at t = {tt[i]:.2f} s, "
                    f"{float(tt[i]) - start:.2f} s after it was written", start, [CMD])
    n = len(writes(trace, CMD))
    return True, f"all {n} command(s) were acknowledged", None, [CMD]


def starts(trace, within=1.0):
    """The pump runs within ``within`` s of the first START command."""
    periods = running_periods(trace)
    if not periods:
        return False, "the scenario sent no START", None, [OUT]
    t0 = periods[0][0]
    on = trace[OUT].astype(bool)
    tt = trace.time
    idx = [i for i in range(len(tt)) if t0 <= tt[i] <= t0 + float(within) and on[i]]
    if idx:
        return True, f"the pump started {float(tt[idx[0]]) - t0:.2f} s after START", None, [OUT]
    return (False, f"START at t = {t0:.2f} s, but the pump was still off {float(within):g} s "
            "later", t0 + float(within), [OUT, "LEVEL"])


def _target_at(sp_writes, t, default=1000):
    target = default
    for ts, v in sp_writes:
        if ts > t:
            break
        if SP_LO <= v <= SP_HI:
            target = v
    return target


def follows(trace, band=0.15, settle=60.0):
    """While running, once ``settle`` s have passed since the start or the last set-point
    change, the level stays within ``band`` m of the accepted set point."""
    import numpy as np

    sp = writes(trace, SP)
    level = trace["LEVEL"]
    tt = trace.time
    checked = 0.0
    for a, b in running_periods(trace):
        edges = [a] + [t for t, _ in sp if a < t < b] + [b]
        for s0, s1 in zip(edges[:-1], edges[1:], strict=True):
            lo = s0 + float(settle)
            if lo >= s1:
                continue
            target = _target_at(sp, s0 + 1e-6) / 1000.0
            sel = (tt >= lo) & (tt < s1)
            bad = np.nonzero(sel & (np.abs(level - target) > float(band)))[0]
            if len(bad):
                t = float(tt[bad[0]])
                return (False, f"at t = {t:.1f} s the level is {float(level[bad[0]]):.2f} m, the "
                        f"set point {target:.2f} m", t, ["LEVEL", OUT, SP])
            checked += s1 - lo
    if checked <= 0:
        return False, "the level was never checked: no long enough running period", None, []
    return True, f"the level stayed near the set point ({checked:.0f} s checked)", None, [
        "LEVEL", OUT]


def stops(trace, within=0.1):
    """After each STOP the pump is off from ``within`` s on until the next START."""
    import numpy as np

    cmds = writes(trace, CMD)
    on = trace[OUT].astype(bool)
    tt = trace.time
    n = 0
    for k, (t, v) in enumerate(cmds):
        if v != 2:
            continue
        nxt = next((ts for ts, vv in cmds[k + 1:] if vv == 1), float(trace.t_end) + 1.0)
        bad = np.nonzero((tt >= t + float(within)) & (tt < nxt) & on)[0]
        if len(bad):
            tb = float(tt[bad[0]])
            return (False, f"STOP at t = {t:.2f} s, but the pump runs at t = {tb:.2f} s", tb,
                    [OUT, CMD])
        n += 1
    if not n:
        return False, "the scenario sent no STOP", None, [OUT]
    return True, f"the pump stopped after {n} STOP command(s)", None, [OUT]


def status_bits(trace, slack=0.05):
    """Bit 0 of STATUS (%MW20) is the running state the commands ask for, bit 1 the pump output;
    a difference is allowed for ``slack`` s after either changes."""
    import numpy as np

    tt = trace.time
    word = trace[STATUS].astype(np.int64)
    pump = trace[OUT].astype(bool)
    run = np.zeros(len(tt), dtype=bool)
    for a, b in running_periods(trace):
        run |= (tt >= a) & (tt < b)
    changes = [t for t, _ in writes(trace, CMD)]
    changes += [float(tt[i]) for i in np.nonzero(pump[1:] != pump[:-1])[0] + 1]
    near = np.zeros(len(tt), dtype=bool)
    for t in changes:
        near |= (tt >= t - 1e-9) & (tt <= t + float(slack))
    for bit, want, what in ((0, run, "running"), (1, pump, "the pump")):
        have = (word >> bit) & 1 == 1
        bad = np.nonzero((have != want) & ~near)[0]
        if len(bad):
            i = int(bad[0])
            return (False, f"at t = {tt[i]:.2f} s STATUS = {int(word[i])}: bit {bit} ({what}) "
                    f"is {int(have[i])}, expected {int(want[i])}", float(tt[i]),
                    [STATUS, OUT])
    return True, "STATUS bits 0 and 1 matched the running state and the pump", None, [STATUS]


def refused(trace, windows=()):
    """In every window the level stays below 1.8 m and bit 2 of STATUS is set."""
    import numpy as np

    tt = trace.time
    word = trace[STATUS].astype(np.int64)
    level = trace["LEVEL"]
    for a, b in windows:
        sel = (tt >= float(a)) & (tt <= float(b))
        high = np.nonzero(sel & (level >= 1.8))[0]
        if len(high):
            t = float(tt[high[0]])
            return (False, f"the level reached {float(level[high[0]]):.2f} m at t = {t:.1f} s: "
                    "the refused set point was used", t, ["LEVEL", SP])
        unset = np.nonzero(sel & (((word >> 2) & 1) == 0))[0]
        if len(unset):
            t = float(tt[unset[0]])
            return (False, f"bit 2 of STATUS is not set at t = {t:.1f} s although the set point "
                    "was refused", t, [STATUS, SP])
    return True, "the bad set points were refused and reported", None, [STATUS]


def refused_level(trace, windows=(), above=0.2):
    """In every window the level stays below the last accepted set point plus ``above`` m (and
    below 1.8 m): the refused set point was not used."""
    import numpy as np

    sp = writes(trace, SP)
    tt = trace.time
    level = trace["LEVEL"]
    for a, b in windows:
        sel = np.nonzero((tt >= float(a)) & (tt <= float(b)))[0]
        for i in sel:
            t = float(tt[i])
            limit = min(_target_at(sp, t) / 1000.0 + float(above), 1.8)
            if float(level[i]) >= limit:
                return (False, f"the level reached {float(level[i]):.2f} m at t = {t:.1f} s, "
                        f"above the last good set point {_target_at(sp, t) / 1000.0:.2f} m: the "
                        "refused set point was used", t, ["LEVEL", SP])
    return True, "the bad set points were not used", None, ["LEVEL", SP]


def refused_bit(trace, windows=()):
    """In every window bit 2 of STATUS is set (the station sees the refusal)."""
    import numpy as np

    tt = trace.time
    word = trace[STATUS].astype(np.int64)
    for a, b in windows:
        sel = (tt >= float(a)) & (tt <= float(b))
        unset = np.nonzero(sel & (((word >> 2) & 1) == 0))[0]
        if len(unset):
            t = float(tt[unset[0]])
            return (False, f"bit 2 of STATUS is not set at t = {t:.1f} s although the set point "
                    "was refused", t, [STATUS, SP])
    return True, "the refusals were reported in bit 2 of STATUS", None, [STATUS]


def switch_points(trace, margin=0.04, settle=0.5):
    """While running, the pump goes on only with the level at least ``margin`` m below the
    accepted set point and off only at least ``margin`` m above it (a two-position control
    that uses its band). Switchings within ``settle`` s of a command or a set-point write are
    not judged (START and STOP switch the pump at any level)."""
    import numpy as np

    sp = writes(trace, SP)
    events = [t for t, _ in writes(trace, CMD)] + [t for t, _ in sp]
    periods = running_periods(trace)
    tt = trace.time
    on = trace[OUT].astype(bool)
    level = trace["LEVEL"]
    for i in np.nonzero(on[1:] != on[:-1])[0] + 1:
        t = float(tt[i])
        if not any(a <= t <= b for a, b in periods):
            continue
        if any(0.0 <= t - e <= float(settle) for e in events):
            continue
        target = _target_at(sp, t) / 1000.0
        h = float(level[i])
        if on[i] and h > target - float(margin):
            return (False, f"the pump started at t = {t:.1f} s with the level at {h:.3f} m, the "
                    f"set point {target:.2f} m: it must start only at the bottom of the band",
                    t, ["LEVEL", OUT])
        if not on[i] and h < target + float(margin):
            return (False, f"the pump stopped at t = {t:.1f} s with the level at {h:.3f} m, the "
                    f"set point {target:.2f} m: it must run on to the top of the band",
                    t, ["LEVEL", OUT])
    return True, "the pump switched at the edges of the band", None, ["LEVEL", OUT]
