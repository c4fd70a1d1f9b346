"""The library of checks a lab's criteria are built from.

Each check is a function of a :class:`~plclab.trace.Trace` and its parameters that returns a
:class:`Verdict`: passed or not, a message a student can act on, the time of the failure (the
feedback draws the timing diagram around it) and the signals worth drawing.

A criterion in ``lab.toml`` names a check and gives its parameters::

    [[criterion]]
    name = "no overflow"
    scenario = "normal"
    check = "never"
    condition = "LEVEL >= 1.95"
    points = 2
    message = "the tank overflows: stop the pump at LS2"

Conditions are the small expressions of :mod:`plclab.trace.expr` (plant signals, PLC
addresses, watched variables, ``t``; ``and or not``, comparisons, ``abs min max``). Times are
seconds or durations (``"2s"``, ``"5min"``); ``from``/``to`` limit a check to a window.

>>> import numpy as np
>>> from plclab.trace import Trace
>>> tr = Trace(np.arange(6.0), {"L": np.array([0.0, 1, 2, 3, 2, 1])}, meta={"t_end": 6.0})
>>> run_check("never", tr, {"condition": "L >= 3"}).t_fail
3.0
>>> run_check("max_switchings", tr, {"signal": "L", "max": 10}).passed
True
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from plclab.errors import PlcError

# ---------------------------------------------------------------------------- results


@dataclass
class Verdict:
    """The outcome of one check on one trace.

    Attributes
    ----------
    passed : bool
    message : str
        What happened, in words ("LEVEL >= 1.95 at t = 83.20 s (LEVEL = 1.951)").
    t_fail : float or None
        When it went wrong (None when it passed or no single moment is to blame).
    signals : list of str
        The signals the check looked at (for the timing diagram).
    value : Any
        The measured quantity (a count, a frequency...), for reports.
    """

    passed: bool
    message: str
    t_fail: float | None = None
    signals: list[str] = field(default_factory=list)
    value: Any = None


@dataclass(frozen=True)
class Param:
    """A parameter of a check: its key in lab.toml, its kind and whether it is required.

    Kinds: ``condition``, ``signal``, ``time`` (s or a duration), ``number``, ``int``,
    ``bool``, ``str``, ``table``.
    """

    key: str
    kind: str
    required: bool = False
    default: Any = None
    help: str = ""


@dataclass
class Check:
    """A registered check."""

    name: str
    fn: Callable[[Any, dict[str, Any]], Verdict]
    params: dict[str, Param]
    doc: str


CHECKS: dict[str, Check] = {}
"""Every check by name (``never``, ``within``, ...)."""

_WINDOW = (Param("from", "time", help="start of the window (default: the start)"),
           Param("to", "time", help="end of the window (default: the end)"))


def check(name: str, *params: Param, window: bool = True):
    """Register a check function ``fn(trace, params) -> Verdict``."""

    def deco(fn: Callable[[Any, dict[str, Any]], Verdict]):
        ps = {p.key: p for p in params + (_WINDOW if window else ())}
        CHECKS[name] = Check(name, fn, ps, (fn.__doc__ or "").strip())
        return fn

    return deco


# ---------------------------------------------------------------------------- helpers


def fmt_t(t: float | None) -> str:
    """``12.30 s`` (or ``2 min 5.0 s`` above 100 s)."""
    if t is None:
        return "?"
    if t >= 100:
        m, s = divmod(t, 60.0)
        return f"{int(m)} min {s:.1f} s"
    return f"{t:.2f} s"


def fmt_v(v: Any, unit: str = "") -> str:
    """TRUE/FALSE for BOOLs, 4 significant digits for REALs."""
    if isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    if isinstance(v, float):
        if math.isnan(v):
            return "NaN"
        s = f"{v:.4g}"
    else:
        s = str(v)
    return f"{s} {unit}".rstrip()


def _np():
    import numpy as np

    return np


def _unit(tr: Any, name: str) -> str:
    try:
        return tr.meta.get("units", {}).get(tr.resolve(name), "")
    except PlcError:
        return ""


def values_at(tr: Any, names: list[str], t: float) -> str:
    """``LEVEL = 1.951 m, PUMP = TRUE`` at time ``t``."""
    out = []
    for n in names:
        try:
            v = tr.value_at(n, t)
        except PlcError:
            continue
        if tr.kind(n) == "bool":
            v = bool(v)
        out.append(f"{n} = {fmt_v(v, _unit(tr, n))}")
    return ", ".join(out)


_COND_CACHE: dict[str, Any] = {}


def condition(text: str) -> Any:
    """The parsed condition (cached)."""
    c = _COND_CACHE.get(text)
    if c is None:
        from plclab.trace.expr import parse_condition

        c = _COND_CACHE[text] = parse_condition(text)
    return c


def condition_names(text: str) -> list[str]:
    """The signal names a condition reads (sorted; ``t`` left out)."""
    return sorted(n for n in condition(text).names if n not in ("t", "time"))


def mask(tr: Any, text: str) -> Any:
    """One boolean per row: where the condition holds."""
    np = _np()
    m = condition(text).vector(tr.__getitem__, tr.time)
    m = np.asarray(m, dtype=bool)
    if m.shape != tr.time.shape:
        m = np.broadcast_to(m, tr.time.shape).copy()
    return m


def window(tr: Any, p: Mapping[str, Any]) -> tuple[float, float]:
    """``(from, to)`` of the check, clipped to the trace."""
    t0 = p.get("from")
    t1 = p.get("to")
    start = float(tr.time[0]) if len(tr) else 0.0
    a = start if t0 is None else max(float(t0), start)
    b = tr.t_end if t1 is None else min(float(t1), tr.t_end)
    return a, b


def in_window(tr: Any, a: float, b: float) -> Any:
    """Rows whose time lies in [a, b)."""
    t = tr.time
    return (t >= a - 1e-9) & (t < b - 1e-9) if b < tr.t_end else (t >= a - 1e-9)


def _span(a: float, b: float) -> str:
    return f"between {fmt_t(a)} and {fmt_t(b)}"


def _changes(tr: Any, name: str, a: float, b: float) -> tuple[Any, Any]:
    """(row indices, times) of the value changes in (a, b]."""
    np = _np()
    x = tr[name]
    idx = np.nonzero(x[1:] != x[:-1])[0] + 1
    t = tr.time[idx]
    m = (t > a + 1e-9) & (t <= b + 1e-9)
    return idx[m], t[m]


def _intervals(tr: Any, name: str, a: float, b: float, on: bool = True
               ) -> list[tuple[float, float, bool]]:
    """ON (or OFF) intervals of a BOOL column clipped to [a, b]: (start, end, completed)."""
    np = _np()
    x = tr[name].astype(bool)
    t = tr.time
    sel = np.nonzero(in_window(tr, a, b))[0]
    if len(sel) == 0:
        return []
    out = []
    start = None
    for i in sel:
        v = bool(x[i]) == on
        if v and start is None:
            start = (float(t[i]), i == sel[0])
        elif not v and start is not None:
            out.append((start[0], float(t[i]), not start[1]))
            start = None
    if start is not None:
        out.append((start[0], b, False))
    return out


# ---------------------------------------------------------------------------- conditions

_COND = Param("condition", "condition", True, help="a condition, e.g. \"LEVEL >= 1.95\"")


@check("never", _COND)
def never(tr: Any, p: dict[str, Any]) -> Verdict:
    """The condition never holds in the window (``LEVEL >= 1.95``: no overflow)."""
    a, b = window(tr, p)
    text = p["condition"]
    names = condition_names(text)
    m = mask(tr, text) & in_window(tr, a, b)
    idx = _np().nonzero(m)[0]
    if len(idx) == 0:
        return Verdict(True, f"`{text}` never held {_span(a, b)}", None, names)
    t = float(tr.time[idx[0]])
    return Verdict(False, f"`{text}` at t = {fmt_t(t)} ({values_at(tr, names, t)})", t, names)


def _always(tr: Any, p: dict[str, Any], a: float, b: float) -> Verdict:
    text = p["condition"]
    names = condition_names(text)
    m = ~mask(tr, text) & in_window(tr, a, b)
    idx = _np().nonzero(m)[0]
    if len(idx) == 0:
        return Verdict(True, f"`{text}` held {_span(a, b)}", None, names)
    t = float(tr.time[idx[0]])
    return Verdict(False, f"`{text}` did not hold at t = {fmt_t(t)} "
                   f"({values_at(tr, names, t)})", t, names)


@check("always", _COND)
def always(tr: Any, p: dict[str, Any]) -> Verdict:
    """The condition holds at every row of the window."""
    a, b = window(tr, p)
    return _always(tr, p, a, b)


@check("always_after", _COND, Param("after", "time", True,
                                    help="start-up time after which the condition must hold"))
def always_after(tr: Any, p: dict[str, Any]) -> Verdict:
    """After the start-up time ``after`` the condition holds (a band: ``47 <= TEMP <= 53``)."""
    a, b = window(tr, p)
    return _always(tr, p, max(a, float(p["after"])), b)


@check("eventually", _COND)
def eventually(tr: Any, p: dict[str, Any]) -> Verdict:
    """The condition holds at least once in the window."""
    a, b = window(tr, p)
    text = p["condition"]
    names = condition_names(text)
    m = mask(tr, text) & in_window(tr, a, b)
    idx = _np().nonzero(m)[0]
    if len(idx):
        t = float(tr.time[idx[0]])
        return Verdict(True, f"`{text}` at t = {fmt_t(t)}", None, names, t)
    return Verdict(False, f"`{text}` never held {_span(a, b)}", None, names)


@check("implies", Param("if", "condition", True), Param("then", "condition", True))
def implies(tr: Any, p: dict[str, Any]) -> Verdict:
    """Whenever ``if`` holds, ``then`` holds too ("the press moves down only with both hands
    on": if = "DOWN", then = "HAND_L and HAND_R")."""
    a, b = window(tr, p)
    names = sorted(set(condition_names(p["if"]) + condition_names(p["then"])))
    m = mask(tr, p["if"]) & ~mask(tr, p["then"]) & in_window(tr, a, b)
    idx = _np().nonzero(m)[0]
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
    np = _np()
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
            return Verdict(True, f"`{p['trigger']}` never happened {_span(a, b)}", None, names)
        return Verdict(False, f"`{p['trigger']}` never happened {_span(a, b)}, so the response "
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
    _, ts = _changes(tr, name, a, b)
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
        return Verdict(True, f"{name} switched {n} times {_span(a, b)} ({what})", None, [name],
                       n)
    tf = float(ts[limit])
    return Verdict(False, f"{name} switched {n} times {_span(a, b)} ({per_min:.1f} per "
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
        for s, e, done in _intervals(tr, name, a, b, state):
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
    for s, e, _ in _intervals(tr, name, a, b, True):
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
    np = _np()
    a, b = window(tr, p)
    name = p["signal"]
    hz = float(p["hz"])
    tol = float(p.get("tol") if p.get("tol") is not None else 0.1)
    idx, ts = _changes(tr, name, a, b)
    x = tr[name]
    rises = ts[x[idx].astype(bool)] if len(idx) else ts
    if len(rises) < 3:
        sel = in_window(tr, a, b)
        on = float(np.mean(x[sel].astype(float))) if sel.any() else 0.0
        state = "TRUE" if on > 0.5 else "FALSE"
        return Verdict(False, f"{name} does not flash {_span(a, b)}: it stays {state} "
                       f"(expected {hz:g} Hz)", a, [name], 0.0)
    f = (len(rises) - 1) / float(rises[-1] - rises[0])
    if abs(f - hz) <= tol * hz + 1e-9:
        return Verdict(True, f"{name} flashes at {f:.2f} Hz (expected {hz:g} Hz +- "
                       f"{tol * 100:g} %)", None, [name], f)
    return Verdict(False, f"{name} flashes at {f:.2f} Hz, expected {hz:g} Hz +- "
                   f"{tol * 100:g} %", float(rises[0]), [name], f)


# ---------------------------------------------------------------------------- analog


@check("settles", Param("signal", "signal", True), Param("target", "number", True),
       Param("band", "number", True, help="half-width of the band around the target"),
       Param("within", "time", True, help="allowed settling time after `after`"),
       Param("after", "time", default=0.0, help="time of the step (default 0)"))
def settles(tr: Any, p: dict[str, Any]) -> Verdict:
    """After a step at ``after`` the signal is within ``target +- band`` from ``after +
    within`` to the end of the window (+-1 C within 5 min)."""
    np = _np()
    a, b = window(tr, p)
    name = p["signal"]
    target, band = float(p["target"]), float(p["band"])
    step = max(a, float(p.get("after") or 0.0))
    t_ok = step + float(p["within"])
    unit = _unit(tr, name)
    x = tr[name].astype(float)
    sel = in_window(tr, t_ok, b)
    bad = np.nonzero(sel & (np.abs(x - target) > band))[0]
    st = None
    try:
        st = tr.settling_time(name, t0=step, t1=b, final=target, band=band)
    except PlcError:
        pass
    took = "it never settled" if st is None else f"it settled after {st:.1f} s"
    if len(bad) == 0:
        return Verdict(True, f"{name} within {target:g} +- {band:g} {unit} from {fmt_t(t_ok)} "
                       f"({took})", None, [name], st)
    tf = float(tr.time[bad[0]])
    return Verdict(False, f"{name} = {fmt_v(float(x[bad[0]]), unit)} at {fmt_t(tf)}: it should"
                   f" stay within {target:g} +- {band:g} {unit} from {fmt_t(t_ok)} on ({took})",
                   tf, [name], st)


@check("in_band", Param("signal", "signal", True), Param("lo", "number", True),
       Param("hi", "number", True),
       Param("min_fraction", "number", default=1.0, help="share of the window (0..1)"))
def in_band(tr: Any, p: dict[str, Any]) -> Verdict:
    """The signal is within ``lo .. hi`` for at least ``min_fraction`` of the window."""
    a, b = window(tr, p)
    name = p["signal"]
    frac = tr.time_in_band(name, float(p["lo"]), float(p["hi"]), a, b, fraction=True)
    want = float(p.get("min_fraction") if p.get("min_fraction") is not None else 1.0)
    unit = _unit(tr, name)
    msg = (f"{name} was within {p['lo']:g}..{p['hi']:g} {unit} for {frac * 100:.1f} % of the "
           f"time {_span(a, b)} (at least {want * 100:g} % expected)")
    if frac + 1e-9 >= want:
        return Verdict(True, msg, None, [name], frac)
    np = _np()
    x = tr[name].astype(float)
    bad = np.nonzero(in_window(tr, a, b) & ((x < p["lo"]) | (x > p["hi"])))[0]
    tf = float(tr.time[bad[0]]) if len(bad) else a
    return Verdict(False, msg, tf, [name], frac)


@check("value", Param("signal", "signal", True),
       Param("at", "time", help="when (default: the end of the run)"),
       Param("equals", "number"), Param("min", "number"), Param("max", "number"),
       Param("tolerance", "number", default=0.0), window=False)
def value(tr: Any, p: dict[str, Any]) -> Verdict:
    """The value of a signal or variable at a time (default: the end) equals / lies within."""
    name = p["signal"]
    t = tr.t_end if p.get("at") is None else min(float(p["at"]), tr.t_end)
    v = tr.value_at(name, t - 1e-9)
    if tr.kind(name) == "bool":
        v = bool(v)
    unit = _unit(tr, name)
    problems = []
    tol = float(p.get("tolerance") or 0.0)
    if p.get("equals") is not None and abs(float(v) - float(p["equals"])) > tol:
        problems.append(f"expected {fmt_v(p['equals'], unit)}")
    if p.get("min") is not None and float(v) < float(p["min"]):
        problems.append(f"expected at least {fmt_v(p['min'], unit)}")
    if p.get("max") is not None and float(v) > float(p["max"]):
        problems.append(f"expected at most {fmt_v(p['max'], unit)}")
    msg = f"{name} = {fmt_v(v, unit)} at {fmt_t(t)}"
    if problems:
        return Verdict(False, f"{msg}; {', '.join(problems)}", t, [name], v)
    return Verdict(True, msg, None, [name], v)


# ---------------------------------------------------------------------------- events


def _events(tr: Any, kind: str, where: Mapping[str, Any] | None, a: float, b: float,
            source: str | None = None) -> list[Any]:
    out = []
    for e in tr.events_of(kind, source, a, b):
        data = e.data or {}
        if where and any(data.get(k) != v for k, v in where.items()):
            continue
        out.append(e)
    return out


def _what(kind: str, where: Mapping[str, Any] | None) -> str:
    if not where:
        return f"'{kind}' events"
    cond = ", ".join(f"{k} = {fmt_v(v)}" for k, v in where.items())
    return f"'{kind}' events with {cond}"


_EVENT = Param("event", "str", True, help="event kind, e.g. \"bottle_rejected\"")
_WHERE = Param("where", "table", help="match the event's data, e.g. { fallen = false }")


@check("event_count", _EVENT, _WHERE, Param("min", "int"), Param("max", "int"),
       Param("equals", "int"), Param("source", "str"))
def event_count(tr: Any, p: dict[str, Any]) -> Verdict:
    """The number of plant (or simulation) events of a kind, optionally matching data: ``min``,
    ``max`` or ``equals`` ("no standing bottle rejected": bottle_rejected where fallen = false,
    max = 0)."""
    a, b = window(tr, p)
    evs = _events(tr, p["event"], p.get("where"), a, b, p.get("source"))
    n = len(evs)
    what = _what(p["event"], p.get("where"))
    hi = p.get("max") if p.get("equals") is None else p["equals"]
    lo = p.get("min") if p.get("equals") is None else p["equals"]
    if hi is not None and n > int(hi):
        e = evs[int(hi)]
        return Verdict(False, f"{n} {what} (at most {hi} expected); the first extra one at "
                       f"{fmt_t(e.time)}: {e.message}", float(e.time), [], n)
    if lo is not None and n < int(lo):
        due, when = _missing_due(tr, p, [float(e.time) for e in evs], a, b)
        return Verdict(False, f"only {n} {what} (at least {lo} expected) {_span(a, b)}; {when}",
                       due, [], n)
    return Verdict(True, f"{n} {what}", None, [], n)


def _missing_due(tr: Any, p: Mapping[str, Any], times: list[float], a: float, b: float
                 ) -> tuple[float, str]:
    """When the first missing event of a minimum count was due, and the words for it: by the
    window's end when the criterion gives one (``to``); at the pace of the events that came
    when they came at a steady pace (at least two, the next one due before the window's end);
    otherwise the failure points at the window's end and the message says that the moment
    cannot be told."""
    np = _np()
    if p.get("to") is not None and b < tr.t_end - 1e-9:
        return b, f"the missing one was due by {fmt_t(b)}, the end of the checked window"
    if len(times) >= 2:
        gaps = np.diff(np.asarray(sorted(times)))
        pace = float(np.median(gaps))
        steady = pace > 0 and float(np.max(np.abs(gaps - pace))) <= 0.25 * pace
        due = max(times) + pace
        if steady and due < b - 1e-9:
            return due, (f"at the pace of the ones that came (one every {pace:.3g} s) the next "
                         f"was due at about {fmt_t(due)} and never came")
    return b, (f"when the missing one was due cannot be told from this run, so the failure "
               f"points at the end of the checked window ({fmt_t(b)})")


@check("counter", Param("signal", "signal", True, help="the PLC counter, e.g. \"%MW0\""),
       _EVENT, _WHERE, Param("events", "table", help="a second {event, where} to add"),
       Param("tolerance", "int", default=0), Param("source", "str"))
def counter(tr: Any, p: dict[str, Any]) -> Verdict:
    """A counter of the program (a watched variable or %M address) equals, at the end of the
    window, the number of matching events (good bottles counted = bottles that passed)."""
    a, b = window(tr, p)
    name = p["signal"]
    n = len(_events(tr, p["event"], p.get("where"), a, b, p.get("source")))
    extra = p.get("events")
    if extra:
        n += len(_events(tr, str(extra.get("event")), extra.get("where"), a, b))
    v = tr.value_at(name, b - 1e-9)
    tol = int(p.get("tolerance") or 0)
    if abs(int(v) - n) <= tol:
        return Verdict(True, f"{name} = {v}, the plant counted {n}", None, [name], v)
    return Verdict(False, f"{name} = {v} at {fmt_t(b)}, but the plant counted {n} "
                   f"({_what(p['event'], p.get('where'))})", b, [name], v)


@check("event_data", _EVENT, _WHERE, Param("field", "str", True,
                                         help="the data field, e.g. \"fill\""),
       Param("lo", "number", help="smallest allowed value"),
       Param("hi", "number", help="largest allowed value"),
       Param("min", "int", default=1, help="at least this many matching events (default 1)"),
       Param("source", "str"))
def event_data(tr: Any, p: dict[str, Any]) -> Verdict:
    """Every event of a kind (matching ``where``) carries a ``field`` between ``lo`` and
    ``hi``, and there are at least ``min`` of them ("every bottle that left the belt holds
    0.45 l ± 0.02 l", the recipe's volume)."""
    a, b = window(tr, p)
    evs = [e for e in _events(tr, p["event"], p.get("where"), a, b, p.get("source"))
           if isinstance(e.data.get(p["field"]), int | float)]
    what = _what(p["event"], p.get("where"))
    lo = -math.inf if p.get("lo") is None else float(p["lo"])
    hi = math.inf if p.get("hi") is None else float(p["hi"])
    for e in evs:
        v = float(e.data[p["field"]])
        if not lo <= v <= hi:
            return Verdict(False, f"{p['field']} = {fmt_v(v)} at {fmt_t(e.time)} ({e.message}); "
                           f"expected {fmt_v(lo)}..{fmt_v(hi)}", float(e.time), [], v)
    need = int(p.get("min", 1))
    if len(evs) < need:
        return Verdict(False, f"only {len(evs)} {what} with {p['field']} {_span(a, b)} (at least "
                       f"{need} expected)", b, [], len(evs))
    return Verdict(True, f"{len(evs)} {what}: {p['field']} within {fmt_v(lo)}..{fmt_v(hi)}",
                   None, [], len(evs))


# ---------------------------------------------------------------------------- alarms
# The alarm log of plclab.scada (``alarm`` events: source = alarm id, data state = I, IO, IA,
# IAO, IOA; ADR 0025). A lab with ``alarms = "alarms.toml"`` records it in every trace.

_ALARM = Param("alarm", "str", True, help="the alarm id, e.g. \"NO_WATER\"")


def _alarm_events(tr: Any, alarm: str, states: tuple[str, ...]) -> list[Any]:
    evs = tr.events_of("alarm", alarm)
    if not evs and alarm not in {a.get("id") for a in tr.meta.get("alarms", [])}:
        known = ", ".join(a.get("id", "") for a in tr.meta.get("alarms", [])) or "none"
        raise PlcError("PLC6021", f"no alarm {alarm!r} in this run's alarm configuration "
                       f"(alarms: {known})")
    return [e for e in evs if e.data.get("state") in states]


@check("alarm_within", _ALARM, Param("trigger", "condition", True,
                                     help="the cause, e.g. \"LEVEL < 0.3\""),
       Param("time", "time", True, help="the allowed delay, e.g. \"2s\""),
       Param("need_trigger", "bool", default=True,
             help="fail when the trigger never happens (default true)"))
def alarm_within(tr: Any, p: dict[str, Any]) -> Verdict:
    """Each time ``trigger`` becomes true, the alarm is raised (incoming) within ``time``,
    or is still pending from an earlier occurrence of the same cause ("alarm raised within
    2 s"). An alarm that was already pending *without* the cause (raised before the trigger
    ever held, or stuck on) does not answer the trigger: a program that never clears its
    alarm, or raises it at start, would otherwise pass every trigger after the first."""
    np = _np()
    a, b = window(tr, p)
    limit = float(p["time"])
    names = condition_names(p["trigger"])
    came = [float(e.time) for e in _alarm_events(tr, p["alarm"], ("I",))]
    gone = [float(e.time) for e in _alarm_events(tr, p["alarm"], ("IO", "IAO"))]
    trig = mask(tr, p["trigger"])
    prev = np.concatenate(([False], trig[:-1]))
    rising = trig & ~prev
    edges = np.nonzero(rising & in_window(tr, a, b))[0]
    if len(edges) == 0:
        ok = p.get("need_trigger") is False
        return Verdict(ok, f"`{p['trigger']}` never happened {_span(a, b)}" +
                       ("" if ok else ", so the alarm could not be checked"),
                       None if ok else a, names)
    all_edges = [float(x) for x in tr.time[np.nonzero(rising)[0]]]

    def answers_cause(c: float) -> bool:
        """The alarm that came at ``c`` answered the cause: the trigger held then, or had
        become true at most ``time`` before."""
        k = min(int(np.searchsorted(tr.time, c - 1e-9)), len(trig) - 1)
        return bool(trig[k]) or any(e - 1e-9 <= c <= e + limit + 1e-9 for e in all_edges)

    worst = 0.0
    for i in edges:
        te = float(tr.time[i])
        if te + limit > tr.t_end + 1e-9:
            continue
        pending = [c for c in came if c < te - 1e-9 and not any(c < g <= te for g in gone)]
        active = any(answers_cause(c) for c in pending)
        hits = [c for c in came if te - 1e-9 <= c <= te + limit + 1e-9]
        if not active and not hits:
            why = (f": it was already pending since {fmt_t(pending[0])}, before the cause "
                   f"(an alarm that is never cleared, or raised without its cause, does not "
                   f"answer it)") if pending else ""
            return Verdict(False, f"`{p['trigger']}` at t = {fmt_t(te)}, but alarm "
                           f"{p['alarm']} was not raised within {limit:g} s{why}", te + limit,
                           names)
        worst = max(worst, 0.0 if active else hits[0] - te)
    return Verdict(True, f"alarm {p['alarm']} came within {worst:.2f} s of `{p['trigger']}` "
                   f"(allowed {limit:g} s)", None, names, worst)


@check("ack_before_restart", _ALARM, Param("restart", "condition", True,
                                           help="what must wait for the acknowledgement, "
                                                "e.g. \"HEATER\""),
       Param("time", "time", default=1.0, help="time allowed to switch it off after the alarm "
                                              "came (default 1 s)"),
       Param("need_alarm", "bool", default=True,
             help="fail when the alarm never comes (default true)"))
def ack_before_restart(tr: Any, p: dict[str, Any]) -> Verdict:
    """After the alarm comes, ``restart`` is off (from ``time`` later) until the operator
    acknowledges the alarm ("the burner runs again only after the acknowledgement")."""
    np = _np()
    a, b = window(tr, p)
    grace = float(p.get("time", 1.0))
    names = condition_names(p["restart"])
    came = [float(e.time) for e in _alarm_events(tr, p["alarm"], ("I",)) if a <= e.time <= b]
    acks = [float(e.time) for e in _alarm_events(tr, p["alarm"], ("IA", "IOA"))]
    if not came:
        ok = p.get("need_alarm") is False
        return Verdict(ok, f"alarm {p['alarm']} never came {_span(a, b)}", None if ok else a,
                       names)
    on = mask(tr, p["restart"])
    t = tr.time
    for c in came:
        ack = next((x for x in acks if x >= c - 1e-9), None)
        end = ack if ack is not None else tr.t_end
        bad = np.nonzero(on & (t > c + grace + 1e-9) & (t < end - 1e-9))[0]
        if len(bad):
            tf = float(t[bad[0]])
            when = "before it was acknowledged" if ack is None else \
                f"before the acknowledgement at {fmt_t(ack)}"
            return Verdict(False, f"alarm {p['alarm']} came at {fmt_t(c)} and `{p['restart']}` "
                           f"was on at {fmt_t(tf)}, {when}", tf, names)
    return Verdict(True, f"`{p['restart']}` waited for the acknowledgement of alarm "
                   f"{p['alarm']} ({len(came)} time(s))", None, names, len(came))


# ---------------------------------------------------------------------------- running


def run_check(name: str, tr: Any, params: Mapping[str, Any]) -> Verdict:
    """Run a registered check with already converted parameters."""
    return CHECKS[name].fn(tr, dict(params))


def signals_of(name: str, params: Mapping[str, Any]) -> list[str]:
    """The signal names a check's parameters mention (conditions and signals)."""
    chk = CHECKS.get(name)
    out: list[str] = []
    if chk is None:
        return out
    for key, prm in chk.params.items():
        v = params.get(key)
        if v is None:
            continue
        if prm.kind == "condition":
            out.extend(n for n in condition_names(str(v)) if n not in out)
        elif prm.kind == "signal" and v not in out:
            out.append(str(v))
    return out


def describe() -> str:
    """A Markdown list of every check and its parameters (for docs and ``--help``)."""
    lines = []
    for c in CHECKS.values():
        ps = ", ".join(f"`{k}`" + ("" if prm.required else "?") for k, prm in c.params.items())
        lines.append(f"- `{c.name}` ({ps}): {c.doc.splitlines()[0] if c.doc else ''}")
    return "\n".join(lines)


# ---------------------------------------------------------------------------- what a check checks
# One description of a criterion's limits, taken from its own parameters, feeds every picture
# (the --png and --out diagrams, the rerun plots, the notebooks): set points and bands as lines
# on their signal, windows as spans of time, counts and times as notes beside the signal.


@dataclass
class Limit:
    """One thing a criterion checks, to be drawn on its signal.

    Attributes
    ----------
    kind : str
        ``level`` (a value the signal is compared with), ``band`` (``value .. hi``),
        ``target`` (a set point), ``window`` (the time span ``t0 .. t1`` the check looks
        at), ``rule`` (the condition itself, in words), ``count`` (a number of switchings, events or pulses), ``time`` (a response,
        dwell or on time), ``rate`` (a frequency).
    signal : str
        The signal as the criterion names it (``TEMP``, ``%QX0.0``); empty for events.
    label : str
        Short words for the picture (``never >= 1.75``, ``at most 8 switchings``).
    """

    kind: str
    signal: str
    label: str
    value: float | None = None
    hi: float | None = None
    t0: float | None = None
    t1: float | None = None

    def text(self, unit: str = "") -> str:
        """The label with the unit where it has a value: ``never >= 1.75 m``."""
        if unit and self.kind in ("level", "band", "target") and self.value is not None:
            return f"{self.label} {unit}"
        return self.label


_OPS = {"Gt": ">", "GtE": ">=", "Lt": "<", "LtE": "<=", "Eq": "=", "NotEq": "<>"}
_FLIP = {">": "<", ">=": "<=", "<": ">", "<=": ">=", "=": "=", "<>": "<>"}
_VERB = {"never": "never", "always": "stay", "always_after": "stay", "eventually": "reach",
         "implies": "then", "within": "", "alarm_within": "", "ack_before_restart": ""}


def _number(node: Any) -> float | None:
    import ast

    if isinstance(node, ast.Constant) and type(node.value) in (int, float):
        return float(node.value)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        v = _number(node.operand)
        return None if v is None else -v
    return None


def comparisons(text: str) -> list[tuple[str, str, float]]:
    """``(signal, op, value)`` of every comparison of a signal with a number in a condition,
    the signal on the left (``47 <= TEMP <= 53`` -> TEMP >= 47, TEMP <= 53;
    ``abs(TEMP - 50) <= 2`` -> TEMP >= 48, TEMP <= 52)."""
    import ast

    def _path(node: Any) -> str | None:  # a signal as the condition names it
        if not isinstance(node, ast.Name | ast.Attribute | ast.Subscript):
            return None
        text = ast.unparse(node)
        return "%" + text[5:].replace("_dot_", ".") if text.startswith("_pct_") else text

    out: list[tuple[str, str, float]] = []
    try:
        tree = condition(text).tree
    except PlcError:
        return out
    for node in ast.walk(tree):
        if not isinstance(node, ast.Compare):
            continue
        items = [node.left, *node.comparators]
        for k, op in enumerate(node.ops):
            sym = _OPS.get(type(op).__name__)
            a, b = items[k], items[k + 1]
            if sym is None:
                continue
            va, vb = _number(a), _number(b)
            if vb is not None and va is None:
                sig, val, o = a, vb, sym
            elif va is not None and vb is None:
                sig, val, o = b, va, _FLIP[sym]
            else:
                continue
            name = _path(sig)
            if name is not None and name not in ("t", "time"):
                out.append((name, o, val))
            elif (isinstance(sig, ast.Call) and getattr(sig.func, "id", "") == "abs"
                  and isinstance(sig.args[0], ast.BinOp) and isinstance(sig.args[0].op, ast.Sub)
                  and o in ("<", "<=")):
                inner, c = sig.args[0], _number(sig.args[0].right)
                name = _path(inner.left)
                if name is not None and c is not None:
                    out += [(name, ">=", c - val), (name, "<=", c + val)]
    return out


def _condition_limits(check_name: str, text: str) -> list[Limit]:
    """Levels and bands from the comparisons of a condition, worded for the check."""
    verb = _VERB.get(check_name, "")
    found = comparisons(text)
    out: list[Limit] = []
    by_sig: dict[str, list[tuple[str, float]]] = {}
    for name, op, val in found:
        by_sig.setdefault(name, []).append((op, val))
    for name, ops in by_sig.items():
        lows = [v for o, v in ops if o in (">", ">=")]
        highs = [v for o, v in ops if o in ("<", "<=")]
        if check_name in ("always", "always_after") and lows and highs and max(lows) < min(highs):
            lo, hi = max(lows), min(highs)
            out.append(Limit("band", name, f"{verb} {lo:g}..{hi:g}".strip(), lo, hi))
            ops = [(o, v) for o, v in ops if v not in (lo, hi)]
        for o, v in ops:
            if any(lim.value == v and lim.signal == name for lim in out):
                continue
            out.append(Limit("level", name, f"{verb} {o} {v:g}".strip(), v))
    return out


def _window(p: Mapping[str, Any]) -> Limit | None:
    a = p.get("after") if p.get("after") is not None else p.get("from")
    if a is not None and p.get("from") is not None:
        a = max(float(a), float(p["from"]))
    b = p.get("to")
    if a is None and b is None:
        return None
    span = " ".join(w for w in (f"from {fmt_t(float(a))}" if a is not None else "",
                                f"to {fmt_t(float(b))}" if b is not None else "") if w)
    return Limit("window", "", f"checked {span}", t0=None if a is None else float(a),
                 t1=None if b is None else float(b))


def _num(p: Mapping[str, Any], key: str) -> float | None:
    v = p.get(key)
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else None


def limits_of(check_name: str, params: Mapping[str, Any]) -> list[Limit]:
    """What a check with these parameters checks, for the pictures: levels, bands, set points,
    windows, counts and times, from the parameters alone (no trace needed).

    >>> [(x.kind, x.signal, x.label) for x in limits_of("never", {"condition": "LEVEL >= 1.75"})]
    [('rule', '', 'never: LEVEL >= 1.75'), ('level', 'LEVEL', 'never >= 1.75')]
    >>> [(x.kind, x.value, x.hi) for x in limits_of("in_band", {"signal": "T", "lo": 200, "hi": 220})]
    [('band', 200.0, 220.0)]
    """
    p = dict(params)
    out: list[Limit] = []
    sig = str(p.get("signal") or "")
    if check_name in ("never", "always", "always_after", "eventually"):
        word = {"never": "never", "eventually": "at least once"}.get(check_name, "always")
        out.append(Limit("rule", "", f"{word}: {p.get('condition')}"))
        out += _condition_limits(check_name, str(p.get("condition", "")))
    elif check_name == "implies":
        out.append(Limit("rule", "", f"whenever {p.get('if')}: {p.get('then')}"))
        out += _condition_limits("implies", str(p.get("then", "")))
        out += [lim for lim in _condition_limits("", str(p.get("if", "")))
                if not any(o.signal == lim.signal and o.value == lim.value for o in out)]
    elif check_name in ("within", "alarm_within"):
        out += _condition_limits("", str(p.get("trigger", "")))
        if check_name == "within":
            out += _condition_limits("", str(p.get("response", "")))
        what = f"alarm {p.get('alarm')}" if check_name == "alarm_within" else \
            f"{p.get('response')}"
        names = condition_names(str(p.get("response"))) if check_name == "within" else []
        out.append(Limit("time", names[0] if names else "", f"{what} within "
                         f"{float(p['time']):g} s of {p.get('trigger')}", float(p["time"])))
    elif check_name == "ack_before_restart":
        names = condition_names(str(p.get("restart", "")))
        out.append(Limit("time", names[0] if names else "", f"{p.get('restart')} off "
                         f"{float(p.get('time') or 1.0):g} s after alarm {p.get('alarm')} "
                         "until acknowledged", float(p.get("time") or 1.0)))
    elif check_name == "in_band":
        lo, hi = _num(p, "lo"), _num(p, "hi")
        frac = _num(p, "min_fraction")
        extra = f" ({frac * 100:g} % of the time)" if frac is not None and frac < 1 else ""
        out.append(Limit("band", sig, f"band {lo:g}..{hi:g}{extra}", lo, hi))
    elif check_name == "settles":
        target, band = float(p["target"]), float(p["band"])
        out.append(Limit("target", sig, f"set point {target:g}", target))
        out.append(Limit("band", sig, f"{target:g} ± {band:g}", target - band, target + band))
        step = float(p.get("after") or 0.0)
        if p.get("from") is not None:
            step = max(step, float(p["from"]))
        ok = step + float(p["within"])
        to = _num(p, "to")
        out.append(Limit("window", sig, f"in the band from {fmt_t(ok)}", t0=ok, t1=to))
        return out
    elif check_name == "value":
        at = "at the end" if p.get("at") is None else f"at {fmt_t(float(p['at']))}"
        for key, word in (("equals", "="), ("min", ">="), ("max", "<=")):
            v = _num(p, key)
            if v is not None:
                out.append(Limit("level", sig, f"{word} {v:g} {at}", v,
                                 t0=None if p.get("at") is None else float(p["at"])))
    elif check_name == "max_switchings":
        if p.get("max") is not None:
            out.append(Limit("count", sig, f"at most {int(p['max'])} switchings",
                             float(p["max"])))
        else:
            out.append(Limit("rate", sig, f"at most {float(p['per_hour']):g} switchings per "
                             "hour", float(p["per_hour"])))
    elif check_name == "no_chatter":
        k, w = int(p.get("min_toggles") or 4), float(p.get("window") or 1.0)
        out.append(Limit("count", sig, f"fewer than {k} switchings in {w:g} s", float(k)))
    elif check_name == "min_dwell":
        for key in ("on", "off"):
            if p.get(key) is not None:
                out.append(Limit("time", sig, f"{key.upper()} at least {float(p[key]):g} s",
                                 float(p[key])))
    elif check_name == "max_on":
        out.append(Limit("time", sig, f"ON at most {float(p['max']):g} s", float(p["max"])))
    elif check_name == "blink_frequency":
        tol = float(p.get("tol") if p.get("tol") is not None else 0.1)
        out.append(Limit("rate", sig, f"flashes at {float(p['hz']):g} Hz ± {tol * 100:g} %",
                         float(p["hz"])))
    elif check_name in ("event_count", "counter", "event_data"):
        what = str(p.get("event", "")).replace("_", " ")
        if check_name == "counter":
            out.append(Limit("count", sig, f"= number of {what} events"))
        elif check_name == "event_data":
            out.append(Limit("band", "", f"{p.get('field')} of each {what} within "
                             f"{fmt_v(_num(p, 'lo'))}..{fmt_v(_num(p, 'hi'))}",
                             _num(p, "lo"), _num(p, "hi")))
        else:
            parts = [f"{w} {int(p[k])}" for k, w in (("equals", "exactly"), ("min", "at least"),
                                                     ("max", "at most")) if p.get(k) is not None]
            out.append(Limit("count", "", f"{' and '.join(parts)} {what} events",
                             _num(p, "equals") if p.get("equals") is not None
                             else _num(p, "max") if p.get("max") is not None else _num(p, "min")))
    else:  # a lab's own Python check: its numeric parameters, as they are named
        nums = [(k, v) for k, v in p.items() if isinstance(v, int | float)
                and not isinstance(v, bool) and k not in ("from", "to")]
        sig = p.get("signal") if isinstance(p.get("signal"), str) else ""
        num = dict(nums)
        if sig and "target" in num:  # a set point on its signal (heater-pid's own checks)
            target = float(num["target"])
            if "band" in num:  # "60 ± 0.5" says the set point too: one label, not two
                band = float(num["band"])
                out.append(Limit("band", sig, f"{target:g} ± {band:g}", target - band,
                                 target + band))
            else:
                out.append(Limit("target", sig, f"set point {target:g}", target))
        elif sig and "level" in num:
            out.append(Limit("level", sig, f"level {float(num['level']):g}",
                             float(num["level"])))
        if nums:
            out.append(Limit("count", "", ", ".join(f"{k} = {v:g}" for k, v in nums)))
    win = _window(p) if check_name not in ("value",) else None
    if win is not None:
        out.append(win)
    return out


def criterion_limits(crit: Any) -> list[Limit]:
    """:func:`limits_of` of a lab's criterion (a built-in check or a lab's own function)."""
    name = crit.check if getattr(crit, "function", None) is None else ""
    return limits_of(name, crit.params)


def describe_limits(limits: list[Limit], units: Mapping[str, str] | None = None) -> str:
    """One line for text (feedback, the rerun summary): ``LEVEL never >= 1.75 m; checked
    from 6 min``."""
    parts = []
    for lim in limits:
        unit = (units or {}).get(lim.signal, "")
        who = f"{lim.signal} " if lim.signal and lim.kind not in ("window", "time") else ""
        parts.append(f"{who}{lim.text(unit)}")
    return "; ".join(parts)
