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

from collections.abc import Mapping
from typing import Any

from . import criteria_conditions, criteria_values  # noqa: F401  (importing registers their checks)
from .criteria_base import CHECKS, Check, Param, Verdict, check, condition, condition_names
from .criteria_limits import Limit, comparisons, criterion_limits, describe_limits, limits_of

__all__ = [  # the checks live in criteria_conditions and criteria_values, the registry in
    # criteria_base, the limits in criteria_limits; this is the library's one front door
    "CHECKS", "Check", "Limit", "Param", "Verdict", "check", "comparisons", "condition",
    "condition_names", "criterion_limits", "describe", "describe_limits", "limits_of",
    "run_check", "signals_of",
]

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
