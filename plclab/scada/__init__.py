"""SCADA and commissioning around the PLC: watch tables, alarms, archives, recipes, a panel.

Layer ``scada`` (``docs/adr/0025-scada-alarms-trigger-points.md``): above ``sim``; it reads the
runtime (trigger points, modify, force) and the Trace. The simulation never imports it: an
alarm server or a watch table joins a run as a hook (``sim.add_hook(...)``), so the PLC and the
simulator stay free of SCADA concepts and a run without hooks costs nothing extra.

>>> from plclab.scada import Alarm, AlarmServer, WatchRow, WatchTable
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
