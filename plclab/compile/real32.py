"""IEEE single precision (REAL): the one rounding the compiler and the generated code share.

The compiler folds REAL constants with it; :mod:`plclab.runtime.rt` hands the same function to
generated code as ``_f32``. It lives here, below the runtime, so that the compiler does not import
the runtime (``docs/adr/0013-layers-and-lazy-cli.md``).
"""

from __future__ import annotations

import math
import struct
from array import array
from collections.abc import Callable

__all__ = ["f32", "single_cell"]

_F32 = struct.Struct("<f")


def f32(x):
    """Round to IEEE single precision (REAL); out of range gives +-inf like the FPU.

    >>> f32(0.1)
    0.10000000149011612
    """
    try:
        return _F32.unpack(_F32.pack(x))[0]
    except OverflowError:
        return math.copysign(math.inf, x)


def single_cell() -> tuple[array, Callable]:
    """A float32 cell and an ``f32`` that rounds through it, for one PLC's generated code.

    Storing a Python float into an ``array('f')`` casts it to single precision like ``f32``
    (round to nearest, +-inf beyond the range); reading it back widens exactly. That is the
    cheapest rounding Python has: generated code stores REAL values as ``_F32[0] = x`` then
    reads ``_F32[0]``, with no call (``docs/adr/0024-generated-code-fast-paths.md``). Each PLC
    gets its own cell, so PLCs scanned in different threads never share one.

    >>> cell, r = single_cell()
    >>> r(0.1) == f32(0.1), r(1e39), r(-1e39)
    (True, inf, -inf)
    """
    cell = array("f", [0.0])

    def f32_cell(x, _cell=cell):
        try:
            _cell[0] = x
        except OverflowError:  # an integer beyond the double range: as f32 does
            return f32(x)
        return _cell[0]

    return cell, f32_cell
