"""``run()``: program text or files + plant + scenario -> Trace, in one call."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

from .errors import sim_error
from .scenario import as_scenario
from .simulation import Simulation

_TEXT_STARTS = ("PROGRAM", "FUNCTION", "FUNCTION_BLOCK", "TYPE", "VAR_GLOBAL", "CONFIGURATION",
                "(*", "//", "/*", "{")


def _is_text(s: str) -> bool:
    return "\n" in s or s.lstrip().upper().startswith(_TEXT_STARTS) or ";" in s


def load_plc(program: Any, cycle_time: Any = "10ms", image_size: int | None = None) -> Any:
    """A PLC from program text, a path, a list of paths/texts, or a PLC as it is.

    >>> plc = load_plc("PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM", "100ms")
    >>> plc.cycle_ns
    100000000
    """
    from plclab.project import compile_sources, read_sources
    from plclab.runtime.plc import Plc

    if hasattr(program, "scan") and hasattr(program, "inputs"):
        return program
    items: Iterable[Any]
    if isinstance(program, str | os.PathLike):
        items = [program]
    else:
        items = list(program)
    sources: list[tuple[str, str]] = []
    for i, it in enumerate(items):
        if isinstance(it, str) and _is_text(it):
            sources.append((it, f"<program{i + 1 if len(items) > 1 else ''}>.st"))
        elif isinstance(it, str | os.PathLike):
            sources.extend(read_sources([it]))
        else:
            raise sim_error("PLC4020", f"{it!r} is neither program text nor a path")
    if not sources:
        raise sim_error("PLC4020", "no program given")
    return Plc(compile_sources(sources), cycle_time=cycle_time, image_size=image_size)


def run(program: Any, plant: Any = None, duration: Any = None, scenario: Any = None,
        wiring: Any = None, scan: Any = None, seed: int | None = None,
        watch: Iterable[str] = (), plant_params: dict[str, Any] | None = None, dt: Any = None,
        until: Any = None, snapshot: bool | None = None, decimate: int = 1) -> Any:
    """Load a program, build the plant, simulate, return the :class:`~plclab.trace.Trace`.

    Parameters
    ----------
    program : str, path, list of them, or a Plc
        ST source text (anything with a newline or a ``;``), file paths, or a loaded PLC.
    plant : str or Plant, optional
        Default: the scenario's plant, else ``"tank"``.
    duration : duration, optional
        Default: the scenario's duration, else 10 min.
    scenario : Scenario, path, dict or list of actions, optional
    wiring : Wiring, list of rows or path, optional
        Default: the scenario's wiring, else the plant's default.
    scan : duration, optional
        The PLC's cycle time (default: the scenario's, else 10 ms; a program with a
        CONFIGURATION runs at its tasks' intervals). A loaded PLC must already have it.
    seed, watch, plant_params, dt, until, snapshot, decimate
        See :class:`~plclab.sim.Simulation` and :class:`~plclab.sim.Scenario`.
    """
    sc = as_scenario(scenario)
    scan = scan if scan is not None else sc.scan  # None: the PLC's own cycle
    plc = load_plc(program, cycle_time=scan if scan is not None else "10ms")
    plant = plant if plant is not None else (sc.plant or "tank")
    sim = Simulation(plc, plant, wiring, scan, dt, seed,
                     scenario=sc, watch=watch, snapshot=snapshot, decimate=decimate,
                     plant_params=plant_params)
    if duration is None and sc.duration_ns is None:
        duration = "10min"
    return sim.run(duration, until)
