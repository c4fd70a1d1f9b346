"""The Trace: one columnar record of a simulation run (see :mod:`plclab.trace.trace`).

Layer ``trace`` (``docs/adr/0013-layers-and-lazy-cli.md``): written by the simulator, read by
the viewers and the grader; it imports only :mod:`plclab.errors` (and NumPy, lazily).

>>> from plclab.trace import Trace, Event, load
>>> Trace.__module__, load.__module__
('plclab.trace.trace', 'plclab.trace.trace')

NumPy is imported when a trace is built or loaded, not when this package is imported.
"""

from __future__ import annotations

from .events import Event
from .trace import Trace, load

__all__ = ["Event", "Trace", "load"]
