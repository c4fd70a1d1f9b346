"""Python's cyclic garbage collector paused while a program is compiled (issue 19).

Parsing, checking and code generation allocate millions of small objects that all stay alive
until the compile ends; the collector keeps walking them (30-40 % of a large compile, see
``benchmarks/run.py``) and frees nothing. Reference counting still frees what is dropped; the
cycles left over are collected at the next collection after the pause (ADR 0024).
"""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["gc_paused"]


@contextmanager
def gc_paused() -> Iterator[None]:
    """Disable the cyclic collector inside the block (nests; restores the previous state).

    >>> with gc_paused():
    ...     gc.isenabled()
    False
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()
