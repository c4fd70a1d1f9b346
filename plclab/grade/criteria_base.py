"""What every check of :mod:`.criteria` is built from: the :class:`Verdict`, the parameter and
check records, the registry :data:`CHECKS` with its ``@check`` decorator, and the helpers that
read a Trace (conditions, windows, switching intervals, units, times and values as text).
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

WINDOW = (Param("from", "time", help="start of the window (default: the start)"),
           Param("to", "time", help="end of the window (default: the end)"))


def check(name: str, *params: Param, window: bool = True):
    """Register a check function ``fn(trace, params) -> Verdict``."""

    def deco(fn: Callable[[Any, dict[str, Any]], Verdict]):
        ps = {p.key: p for p in params + (WINDOW if window else ())}
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


def lazy_numpy():
    import numpy as np

    return np


def unit_of(tr: Any, name: str) -> str:
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
        out.append(f"{n} = {fmt_v(v, unit_of(tr, n))}")
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
    np = lazy_numpy()
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


def span_text(a: float, b: float) -> str:
    return f"between {fmt_t(a)} and {fmt_t(b)}"


def changes_in(tr: Any, name: str, a: float, b: float) -> tuple[Any, Any]:
    """(row indices, times) of the value changes in (a, b]."""
    np = lazy_numpy()
    x = tr[name]
    idx = np.nonzero(x[1:] != x[:-1])[0] + 1
    t = tr.time[idx]
    m = (t > a + 1e-9) & (t <= b + 1e-9)
    return idx[m], t[m]


def intervals_of(tr: Any, name: str, a: float, b: float, on: bool = True
               ) -> list[tuple[float, float, bool]]:
    """ON (or OFF) intervals of a BOOL column clipped to [a, b]: (start, end, completed)."""
    np = lazy_numpy()
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
