"""IEEE single precision (REAL): the one rounding the compiler and the generated code share.

The compiler folds REAL constants with it; :mod:`plclab.runtime.rt` hands the same function to
generated code as ``_f32``. It lives here, below the runtime, so that the compiler does not import
the runtime (``docs/adr/0013-layers-and-lazy-cli.md``).
"""

from __future__ import annotations

import math
import struct

__all__ = ["f32"]

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
