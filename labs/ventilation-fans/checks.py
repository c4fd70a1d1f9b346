"""Python checks of the ventilation-fans lab (``python = "checks:two_fans_run"``).

The criteria library has no check for "exactly k of n units run"; this one counts the healthy
running fans row by row.
"""

from __future__ import annotations


def two_fans_run(trace, start=0.0, end=None, settle=2.0):
    """With no fan or one fan faulted, exactly two healthy fans run: main power on, the fan's
    contactor on and its motor protection not tripped. Rows less than ``settle`` seconds after a
    fault contact changed are not judged (the program may take that long to react)."""
    import numpy as np

    t = trace.time
    end = trace.t_end if end is None else min(float(end), trace.t_end)
    faults = [trace[f"FAULT{i}"].astype(bool) for i in (1, 2, 3)]
    power = trace["MAIN_POWER"].astype(bool)
    running = [trace[f"FAN{i}"].astype(bool) & ~faults[i - 1] & power for i in (1, 2, 3)]
    n_faults = sum(f.astype(int) for f in faults)
    n_running = sum(r.astype(int) for r in running)
    changed = np.zeros(len(t), dtype=bool)
    for f in faults:
        changed[1:] |= f[1:] != f[:-1]
    last = np.where(changed, t, -np.inf)
    last = np.maximum.accumulate(last) if len(last) else last
    judged = (t >= float(start)) & (t < end) & (n_faults <= 1) & (t - last >= float(settle))
    bad = np.nonzero(judged & (n_running != 2))[0]
    if len(bad) == 0:
        return True, f"two healthy fans ran from {float(start):g} s to {end:g} s (one fault or none)"
    i = int(bad[0])
    names = [f"FAN{k}" for k in (1, 2, 3) if running[k - 1][i]]
    what = ", ".join(names) if names else "no fan"
    return (False, f"{int(n_running[i])} fan(s) running at t = {t[i]:.2f} s ({what}) with "
            f"{int(n_faults[i])} fault(s)", float(t[i]))


def lamps_show_state(trace):
    """RUN_LAMP follows the main power output, FANn_LAMP is lit exactly while fan n is switched on
    (its contactor output and the main power on) and not faulted. Compared on the PLC's side, in
    the same scan: the lamps are outputs of the same program."""
    import numpy as np

    t = trace.time
    power = trace["%QX0.0"].astype(bool)
    rows = [("RUN_LAMP", trace["%QX0.4"].astype(bool), power, "the main power is on")]
    for k, (fan, fault, lamp) in enumerate(
            (("%QX0.1", "%IX0.3", "%QX0.6"), ("%QX0.2", "%IX0.4", "%QX0.7"),
             ("%QX0.3", "%IX0.5", "%QX1.0")), 1):
        want = trace[fan].astype(bool) & power & ~trace[fault].astype(bool)
        rows.append((f"FAN{k}_LAMP", trace[lamp].astype(bool), want, f"fan {k} runs"))
    first = None
    for name, lamp, want, what in rows:
        bad = np.nonzero(lamp != want)[0]
        if len(bad) and (first is None or bad[0] < first[0]):
            i = int(bad[0])
            state = "lit" if lamp[i] else "dark"
            truth = what if want[i] else f"not ({what})"
            first = (i, f"{name} is {state} at t = {t[i]:.2f} s, but {truth}", name)
    if first is None:
        return True, "the lamps showed the main power and the running fans"
    i, msg, name = first
    return False, msg, float(t[i]), [name]
