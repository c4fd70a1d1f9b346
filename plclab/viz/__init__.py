"""Visual timelines: rerun recordings, timing diagrams, VCD/WaveDrom/CSV, chatter analysis.

Layer ``viz`` (``docs/adr/0013-layers-and-lazy-cli.md``): reads a Trace; may use the simulator's
duration parsing, never the grader, the Modbus server or the CLI.

Heavy libraries (rerun, matplotlib, pyvcd, wavedrom) are imported only when used.
"""

from __future__ import annotations

__all__ = ["export", "timing_diagram", "to_rerun"]


def to_rerun(trace, path="run.rrd", spawn=False, **kw):
    """Write a Trace as a rerun recording; see :func:`plclab.viz.from_trace.to_rerun`."""
    from .from_trace import to_rerun as _to_rerun

    return _to_rerun(trace, path, spawn=spawn, **kw)


def timing_diagram(*args, **kw):
    from .timing import timing_diagram as _td

    return _td(*args, **kw)


def export(trace, **kw):
    from .from_trace import export as _export

    return _export(trace, **kw)
