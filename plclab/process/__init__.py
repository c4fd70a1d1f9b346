"""Process data around a running PLC: watch tables, alarms, archives, recipes.

Layer ``process`` (``docs/adr/0061-one-place-per-concept-no-circles.md``): above the runtime and
the Trace, below ``sim``, the grader and the operator panel, which all use it. It reads the
runtime (trigger points, modify, force, addresses) and writes Trace events; it never imports the
simulator: an alarm server or a watch table joins a run as a hook (``sim.add_hook(...)``), so a
run without hooks costs nothing extra. The panel and its commands stay in :mod:`plclab.scada`.

>>> from plclab.process import Alarm, AlarmServer, WatchRow, WatchTable
>>> AlarmServer([Alarm("HOT", "too hot", tag="T", kind="H", limit=90.0)]).alarms[0].high
True
"""

from __future__ import annotations

from .alarms import Alarm, AlarmClass, AlarmServer, LogEntry, alarm_log
from .archive import ArchiveRow, archive, write_csv, write_parquet
from .recipes import Element, Recipe
from .watch import Sample, WatchRow, WatchTable, format_value

__all__ = [
    "Alarm",
    "AlarmClass",
    "AlarmServer",
    "ArchiveRow",
    "Element",
    "LogEntry",
    "Recipe",
    "Sample",
    "WatchRow",
    "WatchTable",
    "alarm_log",
    "archive",
    "format_value",
    "write_csv",
    "write_parquet",
]
