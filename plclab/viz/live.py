"""Live timelines: stream a simulation into the rerun viewer while it runs.

``plclab sim PLANT PROG --spawn`` runs the simulation in chunks and, after each chunk, sends the
new rows, events and plant frames to a viewer it opened (or, headless, to a file). With
``speed`` the chunks are paced to the wall clock (1.0 = real time), so one watches the plant as
it would run; without it the viewer fills as fast as the simulation goes.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from ..errors import PlcError


def run_live(sim: Any, duration: Any = None, until: Any = None, *, spawn: bool = True,
             path: str | Path | None = None, chunks: int = 50, speed: float | None = None,
             names: list[str] | None = None, fps: float = 10.0, scan: bool = False):
    """Run ``sim`` (a :class:`plclab.sim.Simulation`) streaming it to rerun; returns the Trace."""
    try:
        import rerun  # noqa: F401
    except ImportError:
        raise PlcError("PLC3005", "live timelines need the viz extra: pip install "
                       "'plclab[viz]'") from None
    from ..sim.durations import parse_ns
    from .from_trace import recording
    from .recording import RrdWriter

    if duration is None:
        total_ns = sim.scenario.duration_ns
        if total_ns is None:
            raise PlcError("PLC4020", "how long? give a duration, e.g. --duration 10min")
        total_ns -= sim.k * sim.scan_ns
    else:
        total_ns = parse_ns(duration, "duration")
    step_ns = max(sim.scan_ns, total_ns // max(1, chunks), 200_000_000)
    step_ns -= step_ns % sim.scan_ns
    writer = None
    done_ns = 0
    shown_t = 0.0
    wall0 = time.perf_counter()
    trace = None
    while done_ns < total_ns:
        n_ns = min(step_ns, total_ns - done_ns)
        trace = sim.run(n_ns / 1e9, until)
        done_ns += n_ns
        rec = recording(trace, names, fps=fps, scan=scan)
        end = trace.t_end
        new = [k for k, t in enumerate(rec.frame_times) if shown_t <= t < end]
        rec.frame_times = [rec.frame_times[k] for k in new]
        rec.frame_rows = [rec.frame_rows[k] for k in new]
        if writer is None:
            writer = RrdWriter(rec, path, spawn=spawn)
        writer.send(rec)
        shown_t = end
        if speed:
            ahead = end / speed - (time.perf_counter() - wall0)
            if ahead > 0:
                time.sleep(ahead)
        if trace.meta.get("stop_reason"):
            break
    if writer is not None:
        writer.close()
    return trace
