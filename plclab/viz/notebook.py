"""The rerun timeline inline in a notebook, with the same default view as the .rrd files
(rerun-notebook 0.41, offline: its viewer is served from the installed wheel on localhost,
never from a CDN).

In a notebook cell::

    from plclab.viz.notebook import show
    show(trace)                                # a plain run
    show(trace, lab=lab, scenario="normal")   # named and laid out by the lab
    show(result, lab=lab)                      # every scenario of a graded run, with verdicts
"""

from __future__ import annotations

import os
from typing import Any

from ..errors import PlcError

OFFLINE_ASSET = "serve-local"
"""rerun-notebook's default loads its viewer from app.rerun.io; this serves the wheel's copy."""


def available() -> bool:
    """True when rerun and rerun-notebook are installed."""
    try:
        import rerun  # noqa: F401
        import rerun_notebook  # noqa: F401
    except ImportError:
        return False
    return True


def show(run: Any, lab: Any = None, student_file: str = "", height: int = 760,
         fps: float = 5.0, scenario: str = "", limits: Any = None) -> list[Any]:
    """Show a Trace (with its ``lab`` and ``scenario``: the lab's names and order) or a graded
    Result with its ``lab`` (one viewer per scenario, failures first, each with its time
    cursor at its first failure) inline; ``limits`` maps a criterion to what it checks
    (``plclab.grade.criteria.criterion_limits``), drawn on its signals. Returns the viewer
    widgets."""
    os.environ.setdefault("RERUN_NOTEBOOK_ASSET", OFFLINE_ASSET)  # before rerun_notebook loads
    if not available():
        raise PlcError("PLC4031", "the inline rerun viewer needs rerun-notebook: pip install "
                       "'rerun-notebook==0.41.*' (or open the .rrd file with `rerun FILE`)")
    import rerun as rr
    from rerun.notebook import Viewer

    from .from_trace import lab_recordings, recording
    from .layout import run_info
    from .recording import RrdWriter, blueprint

    if hasattr(run, "traces"):
        recs = lab_recordings(lab, run, student_file, fps=fps, limits=limits)
    else:
        info = run_info(lab, None, scenario, student_file) if lab is not None else None
        recs = [recording(run, fps=fps, info=info)]
    viewers = []
    for rec in recs:
        info = rec.layout.info
        stream = rr.RecordingStream(info.application_id(), recording_id=info.recording_id())
        viewer = Viewer(width="auto", height=height, recording=stream,
                        blueprint=blueprint(rec))
        writer = RrdWriter(rec, None, stream=stream, send_blueprint=False)
        writer.send(rec)
        stream.flush()
        viewer.display()
        if rec.focus is not None:  # the notebook's viewer can place the cursor: the failure
            viewer.set_time_ctrl(timeline="sim_time", duration=rec.focus, play=False)
        viewers.append(viewer)
    return viewers
