"""Python checks of the bottle-reject lab.

``event_count`` can say that no fallen bottle was pushed off, but its diagram would point at
the end of the run. When the cylinder did fire at a fallen bottle, the cause is in the push
itself: this check points at the first push, so the diagram shows how long the valve was open
and whether the cylinder ever reached its stroke.
"""

from __future__ import annotations

SIGNALS = ["X1", "X2", "%QX0.1", "CYL_EXTENDED", "CONVEYOR"]


def pushes_off(trace, min=1):
    """At least ``min`` fallen bottles were swept off the belt (``bottle_rejected`` events with
    ``fallen`` TRUE); on failure, the time of the first push at a fallen bottle."""
    import numpy as np

    swept = [e for e in trace.events_of("bottle_rejected") if e.data.get("fallen")]
    if len(swept) >= int(min):
        return True, f"{len(swept)} fallen bottle(s) pushed off", None, SIGNALS
    aimed = (trace["REJECT"].astype(bool) & trace["X2"].astype(bool)
             & ~trace["X1"].astype(bool))
    valve = trace["%QX0.1"].astype(bool)
    rises = np.nonzero(valve[1:] & ~valve[:-1])[0] + 1
    first = next((int(i) for i in rises if aimed[int(i):int(i) + 50].any()), None)
    if first is None:
        return (False, f"{len(swept)} fallen bottle(s) pushed off, {int(min)} expected",
                trace.t_end, SIGNALS)
    t0 = float(trace.time[first])
    off = np.nonzero(~valve[first:])[0]
    length = float(trace.time[first + int(off[0])]) - t0 if len(off) else trace.t_end - t0
    return (False, f"the first push at a fallen bottle, at t = {t0:.2f} s, lasted "
            f"{length * 1000:.0f} ms, and no fallen bottle was swept off in the whole run",
            t0 + 0.4, SIGNALS)
