"""The checks of conditions over time and of switching: ``never``, ``always``, ``always_after``,
``eventually``, ``implies``, ``within``; ``max_switchings``, ``no_chatter``, ``min_dwell``,
``max_on``, ``blink_frequency``. Registered in :data:`.criteria_base.CHECKS` when imported.
"""


from __future__ import annotations

import math
from typing import Any

from .criteria_base import (
    Param,
    Verdict,
    changes_in,
    check,
    condition_names,
    fmt_t,
    in_window,
    intervals_of,
    lazy_numpy,
    mask,
    span_text,
    values_at,
    window,
)

# ---------------------------------------------------------------------------- conditions

CONDITION = Param("condition", "condition", True, help="a condition, e.g. \"LEVEL >= 1.95\"")


@check("never", CONDITION)
def never(tr: Any, p: dict[str, Any]) -> Verdict:
    """The condition never holds in the window (``LEVEL >= 1.95``: no overflow)."""
    a, b = window(tr, p)
    text = p["condition"]
    names = condition_names(text)
    m = mask(tr, text) & in_window(tr, a, b)
    idx = lazy_numpy().nonzero(m)[0]
    if len(idx) == 0:
        return Verdict(True, f"`{text}` never held {span_text(a, b)}", None, names)
    t = float(tr.time[idx[0]])
    return Verdict(False, f"`{text}` at t = {fmt_t(t)} ({values_at(tr, names, t)})", t, names)


def _always(tr: Any, p: dict[str, Any], a: float, b: float) -> Verdict:
    text = p["condition"]
    names = condition_names(text)
    m = ~mask(tr, text) & in_window(tr, a, b)
    idx = lazy_numpy().nonzero(m)[0]
    if len(idx) == 0:
        return Verdict(True, f"`{text}` held {span_text(a, b)}", None, names)
    t = float(tr.time[idx[0]])
    return Verdict(False, f"`{text}` did not hold at t = {fmt_t(t)} "
                   f"({values_at(tr, names, t)})", t, names)


@check("always", CONDITION)
def always(tr: Any, p: dict[str, Any]) -> Verdict:
    """The condition holds at every row of the window."""
    a, b = window(tr, p)
    return _always(tr, p, a, b)


@check("always_after", CONDITION, Param("after", "time", True,
                                    help="start-up time after which the condition must hold"))
def always_after(tr: Any, p: dict[str, Any]) -> Verdict:
    """After the start-up time ``after`` the condition holds (a band: ``47 <= TEMP <= 53``)."""
    a, b = window(tr, p)
    return _always(tr, p, max(a, float(p["after"])), b)


@check("eventually", CONDITION)
def eventually(tr: Any, p: dict[str, Any]) -> Verdict:
    """The condition holds at least once in the window."""
    a, b = window(tr, p)
    text = p["condition"]
    names = condition_names(text)
    m = mask(tr, text) & in_window(tr, a, b)
    idx = lazy_numpy().nonzero(m)[0]
    if len(idx):
        t = float(tr.time[idx[0]])
        return Verdict(True, f"`{text}` at t = {fmt_t(t)}", None, names, t)
    return Verdict(False, f"`{text}` never held {span_text(a, b)}", None, names)


@check("implies", Param("if", "condition", True), Param("then", "condition", True))
def implies(tr: Any, p: dict[str, Any]) -> Verdict:
    """Whenever ``if`` holds, ``then`` holds too ("the press moves down only with both hands
    on": if = "DOWN", then = "HAND_L and HAND_R")."""
    a, b = window(tr, p)
    names = sorted(set(condition_names(p["if"]) + condition_names(p["then"])))
    m = mask(tr, p["if"]) & ~mask(tr, p["then"]) & in_window(tr, a, b)
    idx = lazy_numpy().nonzero(m)[0]
    if len(idx) == 0:
        return Verdict(True, f"`{p['then']}` whenever `{p['if']}`", None, names)
    t = float(tr.time[idx[0]])
    return Verdict(False, f"`{p['if']}` without `{p['then']}` at t = {fmt_t(t)} "
                   f"({values_at(tr, names, t)})", t, names)


@check("within", Param("trigger", "condition", True, help="the cause, e.g. \"FAULT2\""),
       Param("response", "condition", True, help="the effect, e.g. \"FAN1\""),
       Param("time", "time", True, help="the allowed response time, e.g. \"2s\""),
       Param("need_trigger", "bool", default=True,
             help="fail when the trigger never happens (default true)"))
def within(tr: Any, p: dict[str, Any]) -> Verdict:
    """Each time ``trigger`` becomes true, ``response`` holds within ``time`` ("FAN1 on within
    2 s of a fault on FAN2"). With ``need_trigger = false`` a trigger that never happens
    passes."""
    np = lazy_numpy()
    a, b = window(tr, p)
    limit = float(p["time"])
    names = sorted(set(condition_names(p["trigger"]) + condition_names(p["response"])))
    trig = mask(tr, p["trigger"])
    resp = mask(tr, p["response"])
    t = tr.time
    prev = np.concatenate(([False], trig[:-1]))
    edges = np.nonzero(trig & ~prev & in_window(tr, a, b))[0]
    if len(edges) == 0:
        if p.get("need_trigger") is False:
            return Verdict(True, f"`{p['trigger']}` never happened {span_text(a, b)}", None, names)
        return Verdict(False, f"`{p['trigger']}` never happened {span_text(a, b)}, so the response "
                       "could not be checked", a, names)
    worst = 0.0
    for i in edges:
        te = float(t[i])
        if te + limit > tr.t_end + 1e-9:
            continue  # not enough time left to judge
        j1 = int(np.searchsorted(t, te + limit + 1e-9, "right"))
        hit = np.nonzero(resp[i:j1])[0]
        if len(hit) == 0:
            tf = te + limit
            return Verdict(False, f"`{p['trigger']}` at t = {fmt_t(te)}, but `{p['response']}` "
                           f"did not follow within {limit:g} s ({values_at(tr, names, tf)} at "
                           f"{fmt_t(tf)})", tf, names)
        worst = max(worst, float(t[i + int(hit[0])]) - te)
    return Verdict(True, f"`{p['response']}` followed `{p['trigger']}` within {worst:.2f} s "
                   f"(allowed {limit:g} s)", None, names, worst)


# ---------------------------------------------------------------------------- switching


@check("max_switchings", Param("signal", "signal", True),
       Param("max", "int", help="largest number of changes in the window"),
       Param("per_hour", "number", help="largest rate, changes per hour"))
def max_switchings(tr: Any, p: dict[str, Any]) -> Verdict:
    """The signal changes at most ``max`` times in the window (or ``per_hour``)."""
    a, b = window(tr, p)
    name = p["signal"]
    _, ts = changes_in(tr, name, a, b)
    n = len(ts)
    if p.get("max") is not None:
        limit = int(p["max"])
        what = f"at most {limit} allowed"
    else:
        rate = float(p["per_hour"])
        limit = max(1, int(math.floor(rate * (b - a) / 3600.0 + 1e-9)))
        what = f"at most {rate:g} per hour allowed, {limit} in this window"
    span = max(b - a, 1e-9)
    per_min = n / span * 60.0
    if n <= limit:
        return Verdict(True, f"{name} switched {n} times {span_text(a, b)} ({what})", None, [name],
                       n)
    tf = float(ts[limit])
    return Verdict(False, f"{name} switched {n} times {span_text(a, b)} ({per_min:.1f} per "
                   f"minute; {what})", tf, [name], n)


@check("no_chatter", Param("signal", "signal", True),
       Param("min_toggles", "int", default=4, help="changes that count as chatter (4)"),
       Param("window", "time", default=1.0, help="within this time (1 s)"))
def no_chatter(tr: Any, p: dict[str, Any]) -> Verdict:
    """The signal never toggles ``min_toggles`` times within ``window`` seconds."""
    a, b = window(tr, p)
    name = p["signal"]
    k = int(p.get("min_toggles") or 4)
    w = float(p.get("window") or 1.0)
    eps = tr.chatter_episodes(name, k, w, a, b)
    if not eps:
        return Verdict(True, f"{name} did not chatter", None, [name], 0)
    s, e, n = eps[0]
    total = sum(x[2] for x in eps)
    return Verdict(False, f"{name} chatters: {n} switchings between {fmt_t(s)} and {fmt_t(e)}"
                   f" ({len(eps)} episode{'s' if len(eps) > 1 else ''}, {total} switchings in "
                   "all)", s, [name], total)


@check("min_dwell", Param("signal", "signal", True),
       Param("on", "time", help="shortest allowed ON time"),
       Param("off", "time", help="shortest allowed OFF time"))
def min_dwell(tr: Any, p: dict[str, Any]) -> Verdict:
    """Every completed ON (OFF) interval lasts at least ``on`` (``off``) seconds."""
    a, b = window(tr, p)
    name = p["signal"]
    for state, key in ((True, "on"), (False, "off")):
        lim = p.get(key)
        if lim is None:
            continue
        for s, e, done in intervals_of(tr, name, a, b, state):
            if done and e - s < float(lim) - 1e-9:
                return Verdict(False, f"{name} was {key.upper()} for only {e - s:.2f} s at "
                               f"{fmt_t(s)} (at least {float(lim):g} s expected)", s, [name],
                               e - s)
    return Verdict(True, f"{name} kept its minimum on/off times", None, [name])


@check("max_on", Param("signal", "signal", True),
       Param("max", "time", True, help="longest allowed ON time"))
def max_on(tr: Any, p: dict[str, Any]) -> Verdict:
    """No ON interval of the signal lasts longer than ``max`` (a cylinder held too long)."""
    a, b = window(tr, p)
    name = p["signal"]
    lim = float(p["max"])
    longest = 0.0
    for s, e, _ in intervals_of(tr, name, a, b, True):
        longest = max(longest, e - s)
        if e - s > lim + 1e-9:
            return Verdict(False, f"{name} stayed on for {e - s:.2f} s from {fmt_t(s)} "
                           f"(at most {lim:g} s allowed)", s + lim, [name], e - s)
    return Verdict(True, f"{name} stayed on at most {longest:.2f} s (allowed {lim:g} s)", None,
                   [name], longest)


@check("blink_frequency", Param("signal", "signal", True),
       Param("hz", "number", True, help="expected frequency"),
       Param("tol", "number", default=0.1, help="relative tolerance (0.1 = 10 %)"))
def blink_frequency(tr: Any, p: dict[str, Any]) -> Verdict:
    """The signal flashes at ``hz`` +- ``tol`` in the window (a 5 Hz fault lamp)."""
    np = lazy_numpy()
    a, b = window(tr, p)
    name = p["signal"]
    hz = float(p["hz"])
    tol = float(p.get("tol") if p.get("tol") is not None else 0.1)
    idx, ts = changes_in(tr, name, a, b)
    x = tr[name]
    rises = ts[x[idx].astype(bool)] if len(idx) else ts
    if len(rises) < 3:
        sel = in_window(tr, a, b)
        on = float(np.mean(x[sel].astype(float))) if sel.any() else 0.0
        state = "TRUE" if on > 0.5 else "FALSE"
        return Verdict(False, f"{name} does not flash {span_text(a, b)}: it stays {state} "
                       f"(expected {hz:g} Hz)", a, [name], 0.0)
    f = (len(rises) - 1) / float(rises[-1] - rises[0])
    if abs(f - hz) <= tol * hz + 1e-9:
        return Verdict(True, f"{name} flashes at {f:.2f} Hz (expected {hz:g} Hz +- "
                       f"{tol * 100:g} %)", None, [name], f)
    return Verdict(False, f"{name} flashes at {f:.2f} Hz, expected {hz:g} Hz +- "
                   f"{tol * 100:g} %", float(rises[0]), [name], f)
