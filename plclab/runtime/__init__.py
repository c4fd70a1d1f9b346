"""The runtime: the PLC that runs compiled programs, scan after scan, on a virtual clock.

The top layer of the PLC core (``docs/adr/0013-layers-and-lazy-cli.md``): it imports
:mod:`plclab.compile`, :mod:`plclab.lang`, the pure-Python conversions of
:mod:`plclab.io.scaling` and the standard library, never the simulator, the viewers, the grader,
the Modbus server or the CLI. :class:`Plc` (:mod:`~plclab.runtime.plc`) holds the process image,
tasks, forcing, retain and the watchdog; :mod:`~plclab.runtime.rt` is the namespace generated code
runs in (its helpers in ``rt_faults``, ``rt_arith``, ``rt_strings``, ``rt_objects`` and
``rt_flow``, one module per concept); :mod:`~plclab.runtime.stdfb` and
:mod:`~plclab.runtime.ctrlfb` are the native standard and control function blocks that
:mod:`~plclab.runtime.natives` registers.

Importing this package is cheap: :class:`Plc` is imported on first use.
"""

from __future__ import annotations

from typing import Any

__all__ = ["Plc", "ctrlfb", "natives", "plc", "rt", "stdfb"]


def __getattr__(name: str) -> Any:
    if name == "Plc":
        from .plc import Plc

        return Plc
    raise AttributeError(f"module 'plclab.runtime' has no attribute {name!r}")
