"""The faults generated code raises, the watchdog's budget and the bound checks.

Run-time faults raise :class:`Fault`; the PLC turns them into located
:class:`~plclab.errors.PlcRuntimeFault` using the generated code's line map. A failed ``ASSERT``
of a TEST block raises :class:`AssertFailure`.
"""

from __future__ import annotations

from typing import Any


def helpers_of(namespace: dict[str, Any]) -> dict[str, Any]:
    """The helpers a module of the runtime gives generated code: its private callables
    (``_idiv``, ``_RefAttr``), by name. :data:`plclab.runtime.rt.HELPERS` joins them."""
    return {name: obj for name, obj in namespace.items()
            if name.startswith("_") and not name.startswith("__") and callable(obj)}


class Fault(Exception):
    """A PLC runtime fault raised by generated code: code, message, location index."""

    def __init__(self, code: str, message: str, where: int | None = None) -> None:
        super().__init__(message)
        self.code = code
        self.message = message
        self.where = where


class AssertFailure(Exception):
    """A failed ASSERT of a TEST block: the message and the location index."""

    def __init__(self, message: str, where: int) -> None:
        super().__init__(message)
        self.message = message
        self.where = where


class Budget:
    """The watchdog: loop iterations left in this scan (deterministic, unlike wall time)."""

    __slots__ = ("left", "limit")

    def __init__(self, limit: int = 1_000_000) -> None:
        self.limit = limit
        self.left = limit


def _oob(i: int, lo: int, hi: int, where: int):
    """An array index outside its bounds (PLC2002)."""
    raise Fault("PLC2002", f"array index {i} is outside the bounds {lo}..{hi}", where)


def _subr(x: int, lo: int, hi: int, where: int) -> int:
    if lo <= x <= hi:
        return x
    raise Fault("PLC2004", f"value {x} is outside the subrange {lo}..{hi}", where)


def _mux(k: int, n: int, where: int):
    raise Fault("PLC2002", f"MUX selector K = {k} is outside 0..{n - 1}", where)


out_of_bounds = _oob  # the name the other helper modules import (ARRAY[*] indexing)
