"""Python checks of the bottle-packing lab.

The criteria library counts plant events, but a box of bottles is a pattern over time: the
standing bottles seen at the photo-eye X1 (rising edges of the plant's own X1 signal) between
two box changes (rising edges of the BOX_FULL lamp, %QX0.2). These checks read both edges.
"""

from __future__ import annotations

LAMP = "%QX0.2"
BELT = "%QX0.0"
# the PLC sees a bottle one filter time and up to two scans after the plant does
SEEN = 0.06


def _rises(trace, name):
    import numpy as np

    x = trace[name].astype(bool)
    idx = np.nonzero(x[1:] & ~x[:-1])[0] + 1
    return [float(trace.time[i]) for i in idx]


def _intervals(trace, name):
    """(start, end, completed) of every ON interval of ``name``."""
    import numpy as np

    x = trace[name].astype(bool)
    tt = trace.time
    out = []
    start = float(tt[0]) if len(x) and x[0] else None
    for i in np.nonzero(x[1:] != x[:-1])[0] + 1:
        if x[i]:
            start = float(tt[i])
        elif start is not None:
            out.append((start, float(tt[i]), True))
            start = None
    if start is not None:
        out.append((start, float(trace.t_end), False))
    return out


def _count_before(times, t):
    return sum(1 for s in times if s <= t)


def boxes_of(trace, size=6, boxes=2):
    """Every box change (rising edge of BOX_FULL) comes after exactly ``size`` more standing
    bottles, no box is skipped, and at least ``boxes`` boxes are filled."""
    size = int(size)
    bottles = _rises(trace, "X1")
    changes = _rises(trace, LAMP)
    signals = ["X1", LAMP, "%MW0"]
    for k, t in enumerate(changes, start=1):
        n = _count_before(bottles, t) - (k - 1) * size
        if n != size:
            return (False, f"box {k} was closed at t = {t:.2f} s after {n} bottle(s), not "
                    f"{size}", t, signals)
    n_open = len(bottles) - len(changes) * size
    if n_open >= size:
        late = bottles[len(changes) * size + size - 1]
        return (False, f"{size} bottles went past X1 by t = {late:.2f} s but BOX_FULL did not "
                f"light", late + 0.5, signals)
    if len(changes) < int(boxes):
        ended = [e for _, e, done in _intervals(trace, LAMP) if done]
        if ended and not any(t > ended[-1] for t in _rises(trace, BELT)) \
                and not trace[BELT].astype(bool)[-1]:
            return (False, f"only {len(changes)} box change(s) in the run, {boxes} expected: "
                    f"the belt never ran again after the box change that ended at "
                    f"t = {ended[-1]:.2f} s", ended[-1] + 0.5, [LAMP, BELT, "X1"])
        return (False, f"only {len(changes)} box change(s) in the run, {boxes} expected "
                f"({len(bottles)} standing bottles were seen)", trace.t_end, signals)
    return True, f"{len(changes)} boxes of {size} ({len(bottles)} standing bottles)", None, signals


def box_change(trace, hold=3.0, tol=0.3):
    """The belt output is off while BOX_FULL is lit, and each box change lasts ``hold`` s."""
    import numpy as np

    lamp = trace[LAMP].astype(bool)
    belt = trace[BELT].astype(bool)
    both = np.nonzero(lamp & belt)[0]
    signals = [LAMP, BELT, "BELT_SPEED"]
    if len(both):
        t = float(trace.time[both[0]])
        return False, f"the belt runs during the box change at t = {t:.2f} s", t, signals
    for s, e, done in _intervals(trace, LAMP):
        if done and abs((e - s) - float(hold)) > float(tol):
            return (False, f"the box change at t = {s:.2f} s lasted {e - s:.2f} s, not "
                    f"{float(hold):g} s", s, signals)
    return True, f"the belt stood still for every box change of {float(hold):g} s", None, signals


def in_box(trace, size=6):
    """IN_BOX (%MW0) at the end equals the standing bottles since the last box change."""
    bottles = _rises(trace, "X1")
    changes = _rises(trace, LAMP)
    expect = len(bottles) - len(changes) * int(size)
    got = int(trace.value_at("%MW0", trace.t_end - 1e-9))
    if got == expect:
        return True, f"%MW0 = {got}, the bottles in the open box", None, ["%MW0", "X1"]
    return (False, f"%MW0 = {got} at the end, but {expect} bottle(s) went into the open box",
            trace.t_end, ["%MW0", "X1", LAMP])


def boxes_counted(trace):
    """BOXES (%MW2) at the end equals the number of box changes."""
    n = len(_rises(trace, LAMP))
    got = int(trace.value_at("%MW2", trace.t_end - 1e-9))
    if got == n:
        return True, f"%MW2 = {got} boxes", None, ["%MW2", LAMP]
    return (False, f"%MW2 = {got} at the end, but BOX_FULL lit {n} time(s)", trace.t_end,
            ["%MW2", LAMP])
