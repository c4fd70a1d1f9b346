"""plclab: a virtual PLC lab for learning IEC 61131-3.

This package is the front door of the PLC core (layer ``api``, above lang -> compile ->
runtime; see ``docs/adr/0013-layers-and-lazy-cli.md``): :func:`load` and :func:`loads` read,
check and compile programs into a :class:`~plclab.runtime.plc.Plc`. Importing it imports only
:mod:`plclab.errors`; the rest comes with the first call.

>>> import plclab
>>> plc = plclab.loads('''
... PROGRAM Blink
... VAR t : TON; lamp : BOOL; END_VAR
... t(IN := NOT t.Q, PT := T#500ms);
... IF t.Q THEN lamp := NOT lamp; END_IF
... END_PROGRAM''')
>>> plc.run(seconds=0.6); plc["lamp"]
True
"""

from __future__ import annotations

from .errors import Diagnostic, Location, PlcError, PlcRuntimeFault

__version__ = "0.1.0"

__all__ = ["Diagnostic", "Location", "PlcError", "PlcRuntimeFault", "__version__", "load",
           "loads", "compile_sources", "run_tests"]


def load(*paths, **options):
    """Load source files into a :class:`~plclab.runtime.plc.Plc` (see :mod:`plclab.project`)."""
    from .project import load as _load

    return _load(*paths, **options)


def loads(text: str, filename: str = "<string>.st", **options):
    """Load a program from a string into a :class:`~plclab.runtime.plc.Plc`."""
    from .project import loads as _loads

    return _loads(text, filename, **options)


def compile_sources(sources, filename: str = "<plclab>", dialect: str | None = None, *,
                    cache: bool = True):
    """Parse, check and compile (text, filename) pairs; ``cache=False``: not from the memory
    cache (ADR 0057; see :func:`plclab.project.compile_sources`)."""
    from .project import compile_sources as _c

    return _c(sources, filename, dialect, cache=cache)


def run_tests(*paths):
    """Run every TEST block of the given files; returns a list of results."""
    from .testing import run_test_files

    return run_test_files(list(paths))
