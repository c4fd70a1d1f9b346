"""The checks of analog values, plant events and alarms: ``settles``, ``in_band``, ``value``;
``event_count``, ``counter``, ``event_data``; ``alarm_within``, ``ack_before_restart``.
Registered in :data:`.criteria_base.CHECKS` when imported.
"""


from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from plclab.errors import PlcError

from .criteria_base import (
    Param,
    Verdict,
    check,
    condition_names,
    fmt_t,
    fmt_v,
    in_window,
    lazy_numpy,
    mask,
    span_text,
    unit_of,
    window,
)

# ---------------------------------------------------------------------------- analog


@check("settles", Param("signal", "signal", True), Param("target", "number", True),
       Param("band", "number", True, help="half-width of the band around the target"),
       Param("within", "time", True, help="allowed settling time after `after`"),
       Param("after", "time", default=0.0, help="time of the step (default 0)"))
def settles(tr: Any, p: dict[str, Any]) -> Verdict:
    """After a step at ``after`` the signal is within ``target +- band`` from ``after +
    within`` to the end of the window (+-1 C within 5 min)."""
    np = lazy_numpy()
    a, b = window(tr, p)
    name = p["signal"]
    target, band = float(p["target"]), float(p["band"])
    step = max(a, float(p.get("after") or 0.0))
    t_ok = step + float(p["within"])
    unit = unit_of(tr, name)
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
    unit = unit_of(tr, name)
    msg = (f"{name} was within {p['lo']:g}..{p['hi']:g} {unit} for {frac * 100:.1f} % of the "
           f"time {span_text(a, b)} (at least {want * 100:g} % expected)")
    if frac + 1e-9 >= want:
        return Verdict(True, msg, None, [name], frac)
    np = lazy_numpy()
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
    unit = unit_of(tr, name)
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


def trace_events(tr: Any, kind: str, where: Mapping[str, Any] | None, a: float, b: float,
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
    evs = trace_events(tr, p["event"], p.get("where"), a, b, p.get("source"))
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
        return Verdict(False, f"only {n} {what} (at least {lo} expected) {span_text(a, b)}; {when}",
                       due, [], n)
    return Verdict(True, f"{n} {what}", None, [], n)


def _missing_due(tr: Any, p: Mapping[str, Any], times: list[float], a: float, b: float
                 ) -> tuple[float, str]:
    """When the first missing event of a minimum count was due, and the words for it: by the
    window's end when the criterion gives one (``to``); at the pace of the events that came
    when they came at a steady pace (at least two, the next one due before the window's end);
    otherwise the failure points at the window's end and the message says that the moment
    cannot be told."""
    np = lazy_numpy()
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


def plant_count(tr: Any, p: dict[str, Any], a: float, b: float) -> int:
    """The events a ``counter`` criterion compares its PLC counter with, in ``[a, b]``: its
    ``event`` (with ``where`` and ``source``) plus its optional second ``events`` table."""
    n = len(trace_events(tr, p["event"], p.get("where"), a, b, p.get("source")))
    extra = p.get("events")
    if extra:
        n += len(trace_events(tr, str(extra.get("event")), extra.get("where"), a, b))
    return n


@check("counter", Param("signal", "signal", True, help="the PLC counter, e.g. \"%MW0\""),
       _EVENT, _WHERE, Param("events", "table", help="a second {event, where} to add"),
       Param("tolerance", "int", default=0), Param("source", "str"))
def counter(tr: Any, p: dict[str, Any]) -> Verdict:
    """A counter of the program (a watched variable or %M address) equals, at the end of the
    window, the number of matching events (good bottles counted = bottles that passed)."""
    a, b = window(tr, p)
    name = p["signal"]
    n = plant_count(tr, p, a, b)
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
    evs = [e for e in trace_events(tr, p["event"], p.get("where"), a, b, p.get("source"))
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
        return Verdict(False, f"only {len(evs)} {what} with {p['field']} {span_text(a, b)} (at least "
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
    np = lazy_numpy()
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
        return Verdict(ok, f"`{p['trigger']}` never happened {span_text(a, b)}" +
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
    np = lazy_numpy()
    a, b = window(tr, p)
    grace = float(p.get("time", 1.0))
    names = condition_names(p["restart"])
    came = [float(e.time) for e in _alarm_events(tr, p["alarm"], ("I",)) if a <= e.time <= b]
    acks = [float(e.time) for e in _alarm_events(tr, p["alarm"], ("IA", "IOA"))]
    if not came:
        ok = p.get("need_alarm") is False
        return Verdict(ok, f"alarm {p['alarm']} never came {span_text(a, b)}", None if ok else a,
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
