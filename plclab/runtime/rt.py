"""The namespace every compiled program starts from: :data:`HELPERS`, the names generated code
may call besides its own.

Kept small and fast: generated code inlines what it can and calls these for the rest. Each
helper lives in the module of its concept, and each of those modules gives generated code its
private callables (:func:`~plclab.runtime.rt_faults.helpers_of`), so a new helper is written
in one place:

- :mod:`~plclab.runtime.rt_faults`: :class:`Fault`, :class:`AssertFailure`, the watchdog's
  :class:`Budget`, bound and subrange checks;
- :mod:`~plclab.runtime.rt_arith`: integer division, REAL conversions, IEEE 754 math, shifts, BCD;
- :mod:`~plclab.runtime.rt_strings`: string functions and conversions, values as IEC literals;
- :mod:`~plclab.runtime.rt_objects`: ``ARRAY[*]`` arguments, interfaces, references, copies;
- :mod:`~plclab.runtime.rt_flow`: FOR loops and the watchdog, large CASE, ASSERT.

Run-time faults raise :class:`Fault`; the PLC turns them into located
:class:`~plclab.errors.PlcRuntimeFault` using the generated code's line map.
"""

from __future__ import annotations

import math
import struct
from types import ModuleType
from typing import Any

from . import rt_arith, rt_faults, rt_flow, rt_objects, rt_strings
from .rt_arith import nan_at_infinity
from .rt_faults import AssertFailure, Budget, Fault, helpers_of
from .rt_objects import fb_exit_all
from .rt_strings import fmt_duration, fmt_real, format_value

__all__ = ["HELPERS", "AssertFailure", "Budget", "Fault", "fb_exit_all", "fmt_duration",
           "fmt_real", "format_value", "nan_at_infinity"]

MODULES: tuple[ModuleType, ...] = (rt_faults, rt_arith, rt_strings, rt_objects, rt_flow)


def namespace(modules: tuple[ModuleType, ...] = MODULES) -> dict[str, Any]:
    """The helpers of *modules*, joined; a name two modules give different objects is an error
    (generated code would call whichever came last)."""
    out: dict[str, Any] = {}
    for module in modules:
        for name, obj in helpers_of(vars(module)).items():
            if out.get(name, obj) is not obj:
                raise ValueError(f"two runtime helpers are called {name}: rename one "
                                 f"(the second in {module.__name__})")
            out[name] = obj
    return out


HELPERS: dict[str, Any] = namespace()
HELPERS.update({
    "_math": math,
    "_unpack_from": struct.unpack_from, "_pack_into": struct.pack_into,  # located variables
})
