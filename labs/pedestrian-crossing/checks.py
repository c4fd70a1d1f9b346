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
        if done and b > startup:  # the first green too: it starts before ``startup``
            nxt = phases[k + 1][0]
            if nxt != NEXT[name]:
                return (False, f"the car signal goes from {name} to {nxt} at t = {b:.2f} s "
                        f"({NEXT[name]} expected)", b, signals)
    return True, "the car signal runs green, yellow, red, red-yellow, green with the right times"


def clearance(trace, seconds=2.0, tolerance=0.1, max_seconds=None):
    """Every pedestrian green starts at least ``seconds`` (and, with ``max_seconds``, at most
    that long) after the cars' yellow went out."""
    import numpy as np

    t = trace.time
    yel = trace["CAR_YELLOW"].astype(bool)
    ped = trace["PED_GREEN"].astype(bool)
    signals = ["CAR_YELLOW", "CAR_RED", "PED_GREEN"]
    rises = np.nonzero(ped[1:] & ~ped[:-1])[0] + 1
    for i in rises:
        before = np.nonzero(yel[:i])[0]
        if len(before) == 0:
            continue
        gap = float(t[i] - t[before[-1] + 1]) if before[-1] + 1 < len(t) else 0.0
        if gap < float(seconds) - float(tolerance):
            return (False, f"pedestrian green at t = {t[i]:.2f} s only {gap:.2f} s after the "
                    f"cars' yellow ({float(seconds):g} s of all-red expected)", float(t[i]),
                    signals)
        if max_seconds is not None and gap > float(max_seconds) + float(tolerance):
            return (False, f"the all-red time before the pedestrian green at t = {t[i]:.2f} s "
                    f"lasts {gap:.2f} s ({float(seconds):g} s expected): the pedestrians wait "
                    "for nothing", float(t[i]), signals)
    return True, f"pedestrians get green {float(seconds):g} s after the cars' yellow"


def pedestrians_clear(trace, seconds=3.0, tolerance=0.1, slack=0.25):
    """After every pedestrian green the cars stay red (no red-yellow, no green) for at least
    ``seconds``, so that the pedestrians who started late leave the crossing, and no longer
    than needed: red-yellow comes within ``slack`` s of the moment the ``seconds`` are over
    and the crossing sensor sees nobody."""
    import numpy as np

    t = trace.time
    ped = trace["PED_GREEN"].astype(bool)
    busy = trace["ON_CROSSING"].astype(bool)
    cars_go = trace["CAR_YELLOW"].astype(bool) | trace["CAR_GREEN"].astype(bool)
    signals = ["PED_GREEN", "CAR_RED", "CAR_YELLOW", "CAR_GREEN", "ON_CROSSING"]
    for i in np.nonzero(ped[:-1] & ~ped[1:])[0] + 1:
        free = np.nonzero((t >= t[i] + float(seconds)) & ~busy)[0]
        free = free[free >= i]
        t_free = float(t[free[0]]) if len(free) else None
        nxt = np.nonzero(cars_go[i:])[0]
        if len(nxt) == 0:
            if t_free is not None and trace.t_end > t_free + float(slack):
                return (False, f"the cars stay red after the pedestrians' green ended at "
                        f"t = {t[i]:.2f} s although the crossing is clear from t = {t_free:.2f} s",
                        t_free, signals)
            continue
        go = float(t[i + nxt[0]])
        gap = go - float(t[i])
        if gap < float(seconds) - float(tolerance):
            return (False, f"the cars get red-yellow {gap:.2f} s after the pedestrians' green "
                    f"ended at t = {t[i]:.2f} s ({float(seconds):g} s of red for everyone "
                    "expected)", float(t[i]), signals)
        if t_free is not None and go > t_free + float(slack):
            return (False, f"the cars wait {gap:.2f} s after the pedestrians' green ended at "
                    f"t = {t[i]:.2f} s, although the {float(seconds):g} s were over and the "
                    f"crossing was clear at t = {t_free:.2f} s", t_free, signals)
    return True, (f"the cars wait {float(seconds):g} s after every pedestrian green, longer only "
                  "while someone is on the crossing")


def wait_lamp(trace, react=0.2):
    """WAIT_LAMP lights within ``react`` s of a press made while the pedestrians do not have
    green, stays lit until their green starts, goes out within ``react`` s of it, and never
    lights during their green."""
    import numpy as np

    t = trace.time
    lamp = trace["WAIT_LAMP"].astype(bool)
    ped = trace["PED_GREEN"].astype(bool)
    req = trace["REQUEST"].astype(bool)
    signals = ["REQUEST", "WAIT_LAMP", "PED_GREEN"]
    n = len(t)

    def after(i, dt):
        return int(np.searchsorted(t, t[i] + dt, side="right"))

    for i in np.nonzero(req[1:] & ~req[:-1])[0] + 1:  # each press
        if ped[i] or t[i] + react > trace.t_end:
            continue
        j = after(i, react)
        if not lamp[i:j].any():
            return (False, f"the request at t = {t[i]:.2f} s is not confirmed: WAIT_LAMP stays "
                    f"dark for {react:g} s", float(t[i]), signals)
        k = i + int(np.argmax(lamp[i:j]))  # the lamp is lit: it stays lit until green
        green = np.nonzero(ped[k:])[0]
        end = k + int(green[0]) if len(green) else n
        off = np.nonzero(~lamp[k:end])[0]
        if len(off):
            m = k + int(off[0])
            return (False, f"WAIT_LAMP goes out at t = {t[m]:.2f} s, before the pedestrians "
                    "get green: the request is forgotten or cleared too early", float(t[m]),
                    signals)
    for i in np.nonzero(ped[1:] & ~ped[:-1])[0] + 1:  # each pedestrian green
        stop = np.nonzero(~ped[i:])[0]
        end = i + int(stop[0]) if len(stop) else n
        j = min(after(i, react), end)
        lit = np.nonzero(lamp[j:end])[0]
        if len(lit):
            m = j + int(lit[0])
            return (False, f"WAIT_LAMP is lit at t = {t[m]:.2f} s during the pedestrians' "
                    "green: a press during the green is not a new request", float(t[m]),
                    signals)
    return True, "WAIT_LAMP confirms every request and goes out when the pedestrians get green"
