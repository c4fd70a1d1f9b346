"""The Trace: one columnar record of a simulation run (see :mod:`plclab.trace.trace`).

>>> from plclab.trace import Trace, Event, load   # doctest: +SKIP

NumPy is imported when a trace is built or loaded, not when this package is imported.
"""

from __future__ import annotations

from .events import Event
from .trace import Trace, load

__all__ = ["Event", "Trace", "load"]
