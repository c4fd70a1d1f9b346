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

from plclab.process import *  # noqa: F403 - the process layer's names, re-exported
from plclab.process import __all__  # noqa: F401
