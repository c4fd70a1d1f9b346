"""Python checks of the pedestrian-crossing lab: the order and the times of the car lights,
and the clearance time between the cars' yellow and the pedestrians' green."""

from __future__ import annotations

# the car signal's phases (red, yellow, green) and the phase that must follow each
PHASES = {(0, 0, 1): "green", (0, 1, 0): "yellow", (1, 0, 0): "red", (1, 1, 0): "red-yellow"}
NEXT = {"green": "yellow", "yellow": "red", "red": "red-yellow", "red-yellow": "green"}


def _phases(trace):
    """[(phase, start, end)] of the car signal; unknown lamp patterns are named by their lamps."""
    import numpy as np

    t = trace.time
    r, y, g = (trace[s].astype(bool) for s in ("CAR_RED", "CAR_YELLOW", "CAR_GREEN"))
    code = r.astype(int) * 4 + y.astype(int) * 2 + g.astype(int)
    cuts = np.nonzero(np.diff(code))[0] + 1
    starts = np.concatenate(([0], cuts))
    out = []
    for k, i in enumerate(starts):
        end = float(t[starts[k + 1]]) if k + 1 < len(starts) else float(trace.t_end)
        key = (int(r[i]), int(y[i]), int(g[i]))
        lit = [n for n, on in zip(("red", "yellow", "green"), key, strict=True) if on]
        name = PHASES.get(key) or ("+".join(lit) if lit else "dark")
        out.append((name, float(t[i]), end))
    return out


def car_sequence(trace, yellow=3.0, red_yellow=1.5, tolerance=0.2, startup=1.0):
    """After ``startup`` s the car signal runs green -> yellow -> red -> red-yellow -> green,
    yellow lasts ``yellow`` s and red-yellow ``red_yellow`` s (± ``tolerance``)."""
    signals = ["CAR_RED", "CAR_YELLOW", "CAR_GREEN"]
    phases = [p for p in _phases(trace) if p[2] > startup]
    for k, (name, a, b) in enumerate(phases):
        if a > startup and name not in NEXT:
            return False, f"the car signal shows {name} at t = {a:.2f} s", a, signals
        done = k + 1 < len(phases)
        want = {"yellow": yellow, "red-yellow": red_yellow}.get(name)
        if want is not None and done and abs((b - a) - want) > tolerance:
            return (False, f"{name} lasts {b - a:.2f} s at t = {a:.2f} s ({want:g} s expected)",
                    a, signals)
        if done and a > startup:
            nxt = phases[k + 1][0]
            if nxt != NEXT[name]:
                return (False, f"the car signal goes from {name} to {nxt} at t = {b:.2f} s "
                        f"({NEXT[name]} expected)", b, signals)
    return True, "the car signal runs green, yellow, red, red-yellow, green with the right times"


def clearance(trace, seconds=2.0, tolerance=0.1):
    """Every pedestrian green starts at least ``seconds`` after the cars' yellow went out."""
    import numpy as np

    t = trace.time
    yel = trace["CAR_YELLOW"].astype(bool)
    ped = trace["PED_GREEN"].astype(bool)
    rises = np.nonzero(ped[1:] & ~ped[:-1])[0] + 1
    for i in rises:
        before = np.nonzero(yel[:i])[0]
        if len(before) == 0:
            continue
        gap = float(t[i] - t[before[-1] + 1]) if before[-1] + 1 < len(t) else 0.0
        if gap < float(seconds) - float(tolerance):
            return (False, f"pedestrian green at t = {t[i]:.2f} s only {gap:.2f} s after the "
                    f"cars' yellow ({float(seconds):g} s of all-red expected)", float(t[i]),
                    ["CAR_YELLOW", "CAR_RED", "PED_GREEN"])
    return True, f"pedestrians get green at least {float(seconds):g} s after the cars' yellow"
