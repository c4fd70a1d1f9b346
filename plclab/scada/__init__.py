"""SCADA around a simulated plant: the operator panel, its page, the notebook widget, ``plclab panel``.

Layer ``scada`` (``docs/adr/0025-scada-alarms-trigger-points.md``): above ``sim``; the panel runs
a Simulation in real time behind a small HTTP server. The process data it shows (watch tables,
alarms, archives, recipes) live one layer down in :mod:`plclab.process`, where the simulator and
the grader use them too; this package re-exports those names, so ``from plclab.scada import
Recipe`` (the course, the labs' READMEs) keeps working.

>>> from plclab.scada import Alarm, AlarmServer, WatchRow, WatchTable
>>> AlarmServer([Alarm("HOT", "too hot", tag="T", kind="H", limit=90.0)]).alarms[0].high
True
"""

from __future__ import annotations

from plclab.process.alarms import Alarm, AlarmClass, AlarmServer, LogEntry, alarm_log
from plclab.process.archive import ArchiveRow, archive, write_csv, write_parquet
from plclab.process.recipes import Element, Recipe
from plclab.process.watch import Sample, WatchRow, WatchTable, format_value

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
