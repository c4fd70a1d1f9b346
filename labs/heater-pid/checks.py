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


def _why(trace, err, t_from, target, band, signal="TEMP", after=0.0, sp="SP"):
    """What the error ``err`` (signal - target over a window starting at ``t_from``) shows:
    a swing around the set point, a steady error (held at an old set point, held far away, a
    proportional offset), a decaying overshoot or a slow creep."""
    import numpy as np

    t = trace.time
    mean = float(np.mean(err))
    half = len(err) // 2
    drift = float(np.mean(err[half:]) - np.mean(err[:half]))
    crossings = int(np.count_nonzero(np.diff(np.sign(err)) != 0))
    p2p = float(np.max(err) - np.min(err))
    held = target + mean
    before = (t >= float(after)) & (t < float(t_from))
    peak = float(np.max(trace[signal].astype(float)[before])) if np.any(before) else target
    old = []
    if sp and sp in trace:
        spv = trace[sp].astype(float)
        old = sorted({round(float(v), 3) for v in spv[t < float(t_from)]} - {round(target, 3)})
    if crossings >= 1 and p2p > band:
        return (f"it swings around the set point ({float(np.min(err)):+.2f} to "
                f"{float(np.max(err)):+.2f} °C): too much gain, too short an integral time or "
                f"too long a sampling period")
    if p2p <= band and any(abs(held - o) <= band for o in old):
        o = next(o for o in old if abs(held - o) <= band)
        return (f"it stays at {held:.1f} °C, the set point before the change ({o:g} °C): the "
                f"controller does not follow SP")
    if p2p <= band and abs(mean) > 4.0:
        return (f"it is held steadily at {held:.1f} °C, {mean:+.1f} °C from the set point: the "
                f"loop works but holds the wrong value: does the controller get SP as its set "
                f"point, and is TEMP_RAW scaled right (0..27648 counts = -20..120 °C)?")
    if p2p <= band and mean < 0:
        return (f"it stays {-mean:.2f} °C below the set point: a steady-state error (a "
                f"proportional action alone needs an error to give power; the integral action "
                f"removes it)")
    if p2p <= band:
        return f"it stays {mean:.2f} °C above the set point"
    if abs(drift) > 0.5 * band and np.sign(drift) == -np.sign(mean):
        if mean > 0 and peak > target + 2.0 * band:
            return (f"it is still coming down from an overshoot (peak {peak:.1f} °C): the "
                    f"integral grew too much on the way (windup) or acts too strongly")
        return (f"it is still creeping towards the set point ({mean:+.2f} °C on average): the "
                f"loop is too slow")
    return f"it is {mean:+.2f} °C from the set point on average and moves by {p2p:.2f} °C"


def settles_diagnosed(trace, signal="TEMP", target=50.0, band=0.5, after=0.0, within=600.0,
                      to=None, sp="SP"):
    """From ``after + within`` seconds to ``to`` (the end) the signal stays within
    ``target +- band``. On failure the message names what the trace shows (:func:`_why`)
    rather than one guess for all."""
    import numpy as np

    t = trace.time
    a = float(after) + float(within)
    b = trace.t_end if to is None else float(to)
    sel = (t >= a) & (t <= b)
    x = trace[signal].astype(float)[sel]
    if len(x) < 2:
        return False, f"no samples of {signal} between {a:g} s and {b:g} s", a, [signal]
    target, band = float(target), float(band)
    err = x - target
    bad = np.nonzero(np.abs(err) > band)[0]
    span = f"between {a:.0f} s and {b:.0f} s"
    if len(bad) == 0:
        return True, (f"{signal} stayed within {target - band:g}..{target + band:g} {span} "
                      f"(largest error {float(np.max(np.abs(err))):.2f})")
    t_fail = float(t[sel][bad[0]])
    why = _why(trace, err, a, target, band, signal, after, sp)
    return (False, f"{signal} left {target - band:g}..{target + band:g} at t = {t_fail:.0f} s "
            f"{span}: {why}", t_fail, [signal])


def holds_diagnosed(trace, signal="TEMP", target=50.0, band=0.2, start=600.0, min_fraction=0.9,
                    sp="SP"):
    """From ``start`` on the signal is within ``target +- band`` for at least ``min_fraction``
    of the time; on failure the message says what it does instead (:func:`_why`)."""
    import numpy as np

    t = trace.time
    sel = t >= float(start)
    x = trace[signal].astype(float)[sel]
    if len(x) < 2:
        return False, f"no samples of {signal} from {start:g} s on", float(start), [signal]
    target, band = float(target), float(band)
    err = x - target
    frac = float(np.mean(np.abs(err) <= band))
    head = (f"{signal} was within {target - band:g}..{target + band:g} for {100 * frac:.0f} % "
            f"of the time from {float(start):.0f} s on (at least {100 * float(min_fraction):.0f} "
            f"% expected)")
    if frac >= float(min_fraction):
        return True, head
    return False, f"{head}: {_why(trace, err, float(start), target, band, signal, 0.0, sp)}", \
        float(start), [signal]


def heats_up(trace, signal="TEMP", level=45.0, to=600.0, power="POWER"):
    """The water reaches ``level`` by ``to`` seconds. On failure the message tells a controller
    that never gives power (direction, or nothing written to the output) from one whose output
    arrives as a tiny fraction (not scaled to counts) and from one that holds a lower
    temperature calmly (a measurement scaled wrongly)."""
    import numpy as np

    t = trace.time
    sel = t <= float(to)
    x = trace[signal].astype(float)[sel]
    p = trace[power].astype(float)[sel]
    if np.any(x >= float(level)):
        i = int(np.argmax(x >= float(level)))
        return True, f"{signal} reached {level:g} °C at {float(t[sel][i]):.0f} s"
    pmax = float(np.max(p)) if len(p) else 0.0
    top = float(np.max(x)) if len(x) else float("nan")
    msg = f"{signal} reached only {top:.1f} °C in {float(to):.0f} s: "
    if pmax <= 0.01:
        msg += ("the element never got any power: a heater is direct acting (the colder the "
                "water, the more power), and the controller's output must be written to "
                "POWER_OUT")
    elif pmax < 5.0:
        msg += (f"the element got at most {pmax:.2f} % of its power: the controller's 0..100 % "
                f"is not scaled to the analog output (27648 counts = 100 %)")
    else:
        tail = p[t[sel] >= float(to) * 0.7]
        msg += (f"the temperature levels off with the element at {float(np.mean(tail)):.0f} % "
                f"on average: the controller is content with a lower temperature; is TEMP_RAW "
                f"scaled right (0..27648 counts = -20..120 °C)?")
    return False, msg, 0.0, [signal, power]


def damped_step(trace, signal="TEMP", at=360.0, max_overshoot=0.4, sp="SP"):
    """After the set point steps at ``at`` seconds (from the value before to the value after,
    read from ``sp``), the signal overshoots the new set point by at most ``max_overshoot``
    of the step: the damping of a step small enough that the output does not saturate (a
    well-damped PI loop, phase margin about 40 degrees or more, overshoots less than 40 %)."""
    import numpy as np

    t = trace.time
    spv = trace[sp].astype(float)
    before = spv[t < float(at)]
    after = spv[t >= float(at)]
    if len(before) == 0 or len(after) == 0:
        return False, f"no set-point step at {float(at):.0f} s", float(at), [sp]
    old, new = float(before[-1]), float(after[-1])
    step = new - old
    if abs(step) < 1e-9:
        return False, f"{sp} did not change at {float(at):.0f} s", float(at), [sp]
    x = trace[signal].astype(float)[t >= float(at)]
    over = float(np.max((x - new) * np.sign(step)))
    share = max(over, 0.0) / abs(step)
    head = (f"after {sp} stepped from {old:g} to {new:g} at {float(at):.0f} s, {signal} "
            f"overshot by {max(over, 0.0):.2f} ({share:.0%} of the step, at most "
            f"{float(max_overshoot):.0%} allowed)")
    if share <= float(max_overshoot):
        return True, head
    k = int(np.argmax((x - new) * np.sign(step)))
    return False, head + ": the loop swings (too much integral action for the gain, or " \
        "the controller is told another sampling period than the one it runs at)", \
        float(t[t >= float(at)][k]), [signal, sp]
