"""Values as the program declares them, for the pictures and feedback lines.

A trace records an address column (``%MW0``, ``%QW2``, ``%MD4``) as the bytes of the process
image read as an integer: a watched ``%MW22`` is a WORD (``65535``), a wired ``%QW`` is read
signed. A student who declared ``LEVEL_MM AT %MW22 : INT`` expects ``-1``, one who declared
``X AT %MD4 : REAL`` expects ``1.5``, not the float's bits. :func:`declared_view` gives the
trace whose address columns hold the values of the declared type; grading keeps the raw trace
(the labs' criteria and scenarios are written on it), only what is shown uses this view.

>>> import numpy as np
>>> from plclab.trace import Trace
>>> tr = Trace([0.0, 1.0], {"%MW0": np.array([65535, 7]), "%MB1": np.array([200, 1])})
>>> v = declared_view(tr, {"%MW0": "INT", "%MB1": "SINT"})
>>> v.columns["%MW0"].tolist(), v.columns["%MB1"].tolist()
([-1, 7], [-56, 1])
>>> declared_view(tr, {"%MW0": "WORD"}) is tr   # nothing to change: the same trace
True
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..lang.addresses import SIZE_BYTES, parse_located

__all__ = ["declared_view"]

# integer types: (bits, signed); the reals by their size
_INTS = {"SINT": (8, True), "INT": (16, True), "DINT": (32, True), "LINT": (64, True),
         "USINT": (8, False), "UINT": (16, False), "UDINT": (32, False), "ULINT": (64, False),
         "BYTE": (8, False), "WORD": (16, False), "DWORD": (32, False), "LWORD": (64, False)}
_REALS = {"REAL": 32, "LREAL": 64}


def _typed(col: Any, size: str, ty: str) -> Any:
    """The raw integers of one address column as values of ``ty`` (None: no change)."""
    import numpy as np

    bits = 8 * SIZE_BYTES[size]
    if ty in _INTS:
        tbits, signed = _INTS[ty]
        if tbits != bits:
            return None
        if bits == 64:  # an int64 column: as read
            return None
        raw = col.astype(np.int64) & ((1 << bits) - 1)  # the bytes, however they were read
        if signed:
            raw = np.where(raw >= 1 << (bits - 1), raw - (1 << bits), raw)
        return raw
    if ty in _REALS and _REALS[ty] == bits:
        u = col.astype(np.int64)
        if bits == 32:
            return (u & 0xFFFFFFFF).astype(np.uint32).view(np.float32).astype(np.float64)
        return u.view(np.float64)
    return None


def declared_view(trace: Any, types: Mapping[str, str]) -> Any:
    """The trace with each integer address column (``%MW0``) read as the type declared at
    its address (``types``: ``{address: elementary type name}``, e.g. from
    :func:`plclab.grade.feedback.declared_types`); the same
    trace when no column changes. Bit addresses, variables and plant signals stay."""
    from .trace import Trace

    wanted = {k.upper(): v.upper() for k, v in types.items()}
    cols = dict(trace.columns)
    kinds = dict(trace.kinds)
    changed = False
    for name, col in trace.columns.items():
        loc = parse_located(name)  # a byte or word address: %MW0, %ID4 (not a bit)
        ty = wanted.get(name.upper())
        if loc is None or loc.size == "X" or loc.bit is not None or ty is None \
                or trace.kinds.get(name) != "int":
            continue
        new = _typed(col, loc.size, ty)
        if new is None or (new.dtype == col.dtype and (new == col).all()):
            continue
        cols[name] = new
        kinds[name] = "float" if ty in _REALS else "int"
        changed = True
    if not changed:
        return trace
    out = Trace(trace.time, cols, kinds, trace.meta, trace.events, trace.wall, trace.edges)
    out.meta["declared"] = dict(wanted)
    return out
