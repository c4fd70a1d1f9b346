"""The registry of blocks implemented in Python: block name -> implementation.

This is the trust boundary between a program and Python (``docs/adr/0003-native-blocks.md``).
Only plclab's own library files (``stdlib.st``, ``ctrllib.st``, parsed with ``library=True``)
may bind a FUNCTION_BLOCK to Python, with a ``{native 'NAME'}`` pragma; ``NAME`` is looked up
here, in a table written in this file, and nothing is ever imported by a name taken from
source text. In a user file the pragma is an error (PLC0131).

>>> sorted(names())[:3]
['AI_SCALE', 'AO_SCALE', 'BLINKER']
>>> resolve("TON").__name__
'TON'
"""

from __future__ import annotations

from functools import cache

from ..errors import PlcError
from ..lang.builtins import BLOCKS

# the blocks are listed once, in the standard library's specification (plclab.lang.builtins)
STANDARD_BLOCKS = tuple(b.name for b in BLOCKS.values() if b.library == "stdlib.st")
CONTROL_BLOCKS = tuple(b.name for b in BLOCKS.values() if b.library == "ctrllib.st")
SFC_BLOCKS = ("SFC_TIMER",)  # sfclib.st: a step's elapsed time (ADR 0016, addendum 2026-11)


@cache
def _table() -> dict[str, type]:
    from . import ctrlfb, stdfb

    table = {name: getattr(stdfb, name) for name in STANDARD_BLOCKS}
    table.update({name: getattr(ctrlfb, name) for name in CONTROL_BLOCKS})
    table.update({name: getattr(stdfb, name) for name in SFC_BLOCKS})
    return table


def names() -> frozenset[str]:
    """The names a library ``{native 'NAME'}`` pragma may use."""
    return frozenset(STANDARD_BLOCKS + CONTROL_BLOCKS + SFC_BLOCKS)


def resolve(name: str) -> type:
    """The Python class registered for a library block (PLC0130 if there is none)."""
    impl = _table().get(name)
    if impl is None:
        raise PlcError("PLC0130", f"no native implementation is registered for {name!r}; "
                       "native blocks are listed in plclab/runtime/natives.py")
    return impl
