"""Python checks of the scan-timing lab.

The program's own measurement of the reaction time (REACTION_MS, %MW4) is compared with the
plant's clock: the time from the START button's rising edge to the contactor's auxiliary
contact RUN closing, both read from the plant signals in the trace.
"""

from __future__ import annotations


def _rises(trace, name):
    import numpy as np

    x = trace[name].astype(bool)
    idx = np.nonzero(x[1:] & ~x[:-1])[0] + 1
    return [float(trace.time[i]) for i in idx]


def reaction(trace, tol_ms=15, settle=0.2):
    """After each start of the motor, REACTION_MS equals RUN's rise minus START's rise (ms),
    within ``tol_ms``; read ``settle`` s after RUN closed."""
    starts = _rises(trace, "START")
    runs = _rises(trace, "RUN")
    signals = ["START", "RUN", "%MW4"]
    checked = 0
    for t_run in runs:
        before = [t for t in starts if t <= t_run]
        if not before:
            continue
        true_ms = (t_run - before[-1]) * 1000.0
        t_read = min(t_run + float(settle), trace.t_end - 1e-9)
        got = float(trace.value_at("%MW4", t_read))
        checked += 1
        if abs(got - true_ms) > float(tol_ms):
            return (False, f"the start at t = {before[-1]:.3f} s took {true_ms:.0f} ms to RUN, "
                    f"but REACTION_MS reads {got:.0f} ms", t_run, signals)
    if not checked:
        return False, "the motor never started, so no reaction time was measured", None, signals
    return True, f"{checked} reaction time(s) measured within {tol_ms} ms", None, signals
