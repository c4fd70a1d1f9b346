"""What a check checks, as limits: set points, bands and windows read from a criterion's own
parameters, for the pictures of a failure and the criteria tables.
"""


from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from plclab.errors import PlcError
from plclab.i18n import tr

from .criteria_base import condition, condition_names, fmt_t, fmt_v

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
            out.append(Limit("band", name, _verbed(verb, tr("{lo:num}..{hi:num}", lo=lo, hi=hi)),
                             lo, hi))
            ops = [(o, v) for o, v in ops if v not in (lo, hi)]
        for o, v in ops:
            if any(lim.value == v and lim.signal == name for lim in out):
                continue
            out.append(Limit("level", name, _verbed(verb, tr("{op} {v:num}", op=o, v=v)), v))
    return out


def _verbed(verb: str, what: str) -> str:
    """``never >= 1.75``: a comparison with the check's verb, in the language in use."""
    worded = {"never": tr("never {what}", what=what), "stay": tr("stay {what}", what=what),
              "reach": tr("reach {what}", what=what), "then": tr("then {what}", what=what)}
    return worded.get(verb, what)


def _window(p: Mapping[str, Any]) -> Limit | None:
    a = p.get("after") if p.get("after") is not None else p.get("from")
    if a is not None and p.get("from") is not None:
        a = max(float(a), float(p["from"]))
    b = p.get("to")
    if a is None and b is None:
        return None
    span = " ".join(w for w in (tr("from {t:time}", t=fmt_t(float(a))) if a is not None else "",
                                tr("to {t:time}", t=fmt_t(float(b))) if b is not None else "")
                    if w)
    return Limit("window", "", tr("checked {span}", span=span), t0=None if a is None else float(a),
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
        rule = {"never": tr("never: {condition}", condition=p.get("condition")),
                "eventually": tr("at least once: {condition}", condition=p.get("condition"))}
        out.append(Limit("rule", "", rule.get(check_name) or
                         tr("always: {condition}", condition=p.get("condition"))))
        out += _condition_limits(check_name, str(p.get("condition", "")))
    elif check_name == "implies":
        out.append(Limit("rule", "", tr("whenever {cond}: {then}", cond=p.get("if"),
                                        then=p.get("then"))))
        out += _condition_limits("implies", str(p.get("then", "")))
        out += [lim for lim in _condition_limits("", str(p.get("if", "")))
                if not any(o.signal == lim.signal and o.value == lim.value for o in out)]
    elif check_name in ("within", "alarm_within"):
        out += _condition_limits("", str(p.get("trigger", "")))
        if check_name == "within":
            out += _condition_limits("", str(p.get("response", "")))
        what = tr("alarm {alarm}", alarm=p.get("alarm")) if check_name == "alarm_within" \
            else f"{p.get('response')}"
        names = condition_names(str(p.get("response"))) if check_name == "within" else []
        out.append(Limit("time", names[0] if names else "",
                         tr("{what} within {s:num} s of {trigger}", what=what,
                            s=float(p["time"]), trigger=p.get("trigger")), float(p["time"])))
    elif check_name == "ack_before_restart":
        names = condition_names(str(p.get("restart", "")))
        out.append(Limit("time", names[0] if names else "",
                         tr("{restart} off {s:num} s after alarm {alarm} until acknowledged",
                            restart=p.get("restart"), s=float(p.get("time") or 1.0),
                            alarm=p.get("alarm")), float(p.get("time") or 1.0)))
    elif check_name == "in_band":
        lo, hi = _num(p, "lo"), _num(p, "hi")
        frac = _num(p, "min_fraction")
        label = tr("band {lo:num}..{hi:num}", lo=lo, hi=hi)
        if frac is not None and frac < 1:
            label += " " + tr("({pct:num} % of the time)", pct=frac * 100)
        out.append(Limit("band", sig, label, lo, hi))
    elif check_name == "settles":
        target, band = float(p["target"]), float(p["band"])
        out.append(Limit("target", sig, tr("set point {v:num}", v=target), target))
        out.append(Limit("band", sig, tr("{v:num} ± {band:num}", v=target, band=band),
                         target - band, target + band))
        step = float(p.get("after") or 0.0)
        if p.get("from") is not None:
            step = max(step, float(p["from"]))
        ok = step + float(p["within"])
        to = _num(p, "to")
        out.append(Limit("window", sig, tr("in the band from {t:time}", t=fmt_t(ok)), t0=ok,
                         t1=to))
        return out
    elif check_name == "value":
        at = tr("at the end") if p.get("at") is None else \
            tr("at {t:time}", t=fmt_t(float(p["at"])))
        for key, word in (("equals", "="), ("min", ">="), ("max", "<=")):
            v = _num(p, key)
            if v is not None:
                out.append(Limit("level", sig, tr("{op} {v:num} {at}", op=word, v=v, at=at), v,
                                 t0=None if p.get("at") is None else float(p["at"])))
    elif check_name == "max_switchings":
        if p.get("max") is not None:
            out.append(Limit("count", sig, tr("at most {n} switchings", n=int(p["max"])),
                             float(p["max"])))
        else:
            out.append(Limit("rate", sig, tr("at most {n:num} switchings per hour",
                                             n=float(p["per_hour"])), float(p["per_hour"])))
    elif check_name == "no_chatter":
        k, w = int(p.get("min_toggles") or 4), float(p.get("window") or 1.0)
        out.append(Limit("count", sig, tr("fewer than {n} switchings in {s:num} s", n=k, s=w),
                         float(k)))
    elif check_name == "min_dwell":
        for key in ("on", "off"):
            if p.get(key) is not None:
                out.append(Limit("time", sig, tr("{state} at least {s:num} s", state=key.upper(),
                                                 s=float(p[key])), float(p[key])))
    elif check_name == "max_on":
        out.append(Limit("time", sig, tr("ON at most {s:num} s", s=float(p["max"])),
                         float(p["max"])))
    elif check_name == "blink_frequency":
        tol = float(p.get("tol") if p.get("tol") is not None else 0.1)
        out.append(Limit("rate", sig, tr("flashes at {hz:num} Hz ± {pct:num} %",
                                         hz=float(p["hz"]), pct=tol * 100), float(p["hz"])))
    elif check_name in ("event_count", "counter", "event_data"):
        what = str(p.get("event", "")).replace("_", " ")
        if check_name == "counter":
            out.append(Limit("count", sig, tr("= number of {what} events", what=what)))
        elif check_name == "event_data":
            out.append(Limit("band", "", tr("{field} of each {what} within {lo:num}..{hi:num}",
                                            field=p.get("field"), what=what,
                                            lo=fmt_v(_num(p, "lo")), hi=fmt_v(_num(p, "hi"))),
                             _num(p, "lo"), _num(p, "hi")))
        else:
            parts = [word for k, word in (
                ("equals", tr("exactly {n}", n=p.get("equals"))),
                ("min", tr("at least {n}", n=p.get("min"))),
                ("max", tr("at most {n}", n=p.get("max")))) if p.get(k) is not None]
            out.append(Limit("count", "", tr("{counts} {what} events",
                                             counts=tr(" and ").join(parts), what=what),
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
                out.append(Limit("band", sig, tr("{v:num} ± {band:num}", v=target, band=band),
                                 target - band, target + band))
            else:
                out.append(Limit("target", sig, tr("set point {v:num}", v=target), target))
        elif sig and "level" in num:
            out.append(Limit("level", sig, tr("level {v:num}", v=float(num["level"])),
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
