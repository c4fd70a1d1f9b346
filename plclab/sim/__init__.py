"""Simulation: a virtual PLC joined to a physics plant through I/O modules, on one clock.

Layer ``sim`` (``docs/adr/0013-layers-and-lazy-cli.md``): above the PLC core, ``io`` and
``trace``; below the viewers, the grader and the CLI, which it never imports.

>>> import plclab
>>> from plclab.sim import Simulation, run
>>> tr = run('''PROGRAM Main
... VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
... M := ((NOT LS1) OR M) AND (NOT LS2);
... END_PROGRAM''', plant="tank", duration="1min")
>>> tr.switchings("PUMP"), round(tr.value_at("LEVEL", 60.0), 2)
(1, 0.41)

The pieces: :class:`Simulation` (the loop, see :mod:`plclab.sim.simulation` for the exact
order), :class:`Wiring` and :func:`default_wiring` (which plant signal reaches which PLC
address through which I/O module), :class:`Scenario` (operator actions and faults at times,
when to stop), :func:`run` (all of it in one call) and the :class:`~plclab.trace.Trace` every
run produces. Error codes: :data:`plclab.sim.errors.CODES` (PLC4001-PLC4021).
"""

from __future__ import annotations

from .durations import format_duration, parse_ns, parse_seconds
from .runner import load_plc, run
from .scenario import Action, Scenario, load_scenario
from .simulation import Simulation
from .wiring import MODULES, WireRow, Wiring, load_wiring
from .wirings import default_wiring

__all__ = [
    "MODULES",
    "Action",
    "Scenario",
    "Simulation",
    "WireRow",
    "Wiring",
    "default_wiring",
    "format_duration",
    "load_plc",
    "load_scenario",
    "load_wiring",
    "parse_ns",
    "parse_seconds",
    "run",
]
