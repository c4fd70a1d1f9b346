"""The default view of a rerun recording: its blueprint (what goes where and how high, the time
span shown, the panels open) and the marks of the first failure (the span its criterion
checks, the failure line across a plot). The recording itself, whose ``Recording`` every
function here takes: :mod:`plclab.viz.recording` (which imports this module, not back).
"""

from __future__ import annotations

from typing import Any

SCREEN_PX = 930.0
"""Height of the left column on a 1000-pixel screen: lanes get their height, plots the rest."""
LANE_PX = 34.0
"""Height of one state lane in the viewer."""
MIN_PLOT_PX = 200.0
"""A plot is never squashed below this height, whatever the number of lanes."""
MIN_LANES_PX = 170.0
"""The lanes' pane is at least this high (it scrolls when the lanes need more)."""
CHECKED = (0, 120, 130)
"""The span the first failed criterion looks at, in the lane above the I/O lanes."""
END_MARGIN = 0.02
"""After a failure the view reaches this share of the run past its end (a counter checked at
the end is marked at the last moment)."""
FAILED_LANE = "/digital/00_first_failure"
"""Sorts above every I/O lane (``01_...``): visible without scrolling the lanes' pane."""


def checked_span(rec: Any) -> tuple[float, float]:
    """The span the first failed criterion looks at: its window (``settles`` from the
    step plus its time), the allowed time before a timed failure (``within 5.5 s``, ``ON at
    most 300 s``), else the whole run."""
    a, b = rec.span()
    v = rec.failed
    for lim in v.limits:
        if lim.kind == "window" and (lim.t0 is not None or lim.t1 is not None):
            lo = a if lim.t0 is None else max(a, float(lim.t0))
            hi = b if lim.t1 is None else min(b, float(lim.t1))
            if hi > lo:
                return lo, hi
    if v.time is not None:
        for lim in v.limits:
            if lim.kind == "time" and lim.value is not None and lim.value > 0:
                return max(a, v.time - float(lim.value)), v.time
    return a, b


def view_span(rec: Any) -> tuple[float, float]:
    """The time span the plots and lanes show at open: the run's, after a failure reaching
    ``END_MARGIN`` past its end, and as far before its start when the failure is in its
    first ``END_MARGIN`` (a failure at t = 0.02 s is not hidden under the axis)."""
    a, b = rec.view_span or rec.span()
    if rec.failed is None:
        return a, b
    m = END_MARGIN * (b - a)
    t = failure_time(rec)
    return (a - m if t is not None and t < a + m else a), b + m


def failure_time(rec: Any) -> float | None:
    """Where the first failure is marked: its criterion's time, else (a failure over the
    run) the moment every view shows, the first PLC fault (``rec.focus``), else None."""
    return rec.failed.time if rec.failed.time is not None else rec.focus


def failure_states(rec: Any) -> tuple[list[float], list[str]]:
    """The changes of the first-failure lane: ``w`` over the checked span, ``f`` (1 % of the
    run wide) at the failure, ``0`` elsewhere."""
    a, b = rec.span()
    w0, w1 = checked_span(rec)
    t = failure_time(rec)
    width = max(0.01 * (b - a), 1e-3)
    cuts = sorted({w0, w1, *(() if t is None else (t, t + width))})

    def at(x: float) -> str:
        if t is not None and t <= x < t + width:
            return "f"
        return "w" if w0 <= x < w1 else "0"

    times, states = [], []
    for x in cuts:
        st = at(x)
        if not states or states[-1] != st:
            times.append(x)
            states.append(st)
    return times, states


def failure_line(p: Any, t: float) -> tuple[list[float], list[float]]:
    """A vertical line at ``t`` across plot ``p`` (its range, limits included): two points one
    nanosecond apart, then a gap."""
    from .layout import span_of

    lo, hi = p.y_range or span_of(p)
    vals = [lim.value for lim in p.limits]
    lo, hi = min([lo, *vals]), max([hi, *vals])
    if hi <= lo:
        lo, hi = lo - 0.5, hi + 0.5
    return [t, t + 1e-9, t + 2e-9], [lo, hi, float("nan")]


def blueprint(rec: Any) -> Any:
    """The default view: plots and lanes on the left, plant, summary and events on the right."""
    import rerun.blueprint as rrb
    import rerun.blueprint.archetypes as rrba
    import rerun.blueprint.components as rrbc

    lay = rec.layout
    span = view_span(rec)
    whole = rrb.TimeAxis(view_range=rrb.TimeRange(
        start=rrb.TimeRangeBoundary.absolute(seconds=span[0]),
        end=rrb.TimeRangeBoundary.absolute(seconds=span[1])))  # linked axes ignore view_range
    left: list[Any] = []
    shares: list[float] = []
    marks = len({m.lane + m.kind for m in rec.markers if m.lane})  # a marker lane each
    marks += rec.failed is not None  # the first failure's lane
    has_lanes = bool(lay.lanes) or rec.failed is not None
    lanes_px = LANE_PX * (len(lay.lanes) + marks) + 56.0 if has_lanes else 0.0
    plot_px = max(MIN_PLOT_PX, (SCREEN_PX - lanes_px) / max(len(lay.plots), 1))
    if lay.plots and has_lanes:  # plots keep their 200 px; the lanes scroll in the rest
        # (a pane of one or two lanes, heater-pid's first-failure lane alone, keeps its size:
        # the rest of the column goes to the plots, not to black)
        lanes_px = max(min(MIN_LANES_PX, lanes_px),
                       min(lanes_px, SCREEN_PX - plot_px * len(lay.plots)))
    for p in lay.plots:
        kw: dict[str, Any] = {}
        if p.y_range is not None:
            kw["axis_y"] = rrb.ScalarAxis(range=p.y_range)
        # no legend over the data: the lines and the dashed limits are named in the title
        left.append(rrb.TimeSeriesView(origin=f"/plots/{p.key}", name=plot_title(p),
                                       plot_legend=rrb.PlotLegend(visible=False),
                                       axis_x=whole, **kw))
        shares.append(plot_px)
    if has_lanes:
        left.append(rrb.StateTimelineView(origin="/digital", name="digital I/O, in the lab's "
                                          "order (ON = coloured)", time_view=whole))
        shares.append(lanes_px)
    if len(rec.scan_durations_us):
        left.append(rrb.TimeSeriesView(origin="/scan", name="scan duration [us]",
                                       axis_x=whole))
        shares.append(140.0)
    right: list[Any] = []
    rshares: list[float] = []
    if rec.picture is not None:
        x0, y0, x1, y1 = rec.picture.bounds
        kw = {}
        name = "plant"
        if rec.focus is not None:  # the plant at the failure, wherever the cursor is
            at = rrb.TimeRangeBoundary.absolute(seconds=rec.focus)
            kw["time_ranges"] = rrb.VisibleTimeRange("sim_time", start=at, end=at)
            name = f"plant at the first failure, t = {rec.focus:.2f} s"
            if rec.failed is not None and rec.failed.time is None:  # failed over the run
                name = f"plant when the PLC stopped, t = {rec.focus:.2f} s"
        right.append(rrb.Spatial2DView(origin="/plant", name=name, visual_bounds=(
            rrb.VisualBounds2D(x_range=(x0, x1), y_range=(-y1, -y0))), **kw))
        rshares.append(3.0)
    right.append(rrb.TextDocumentView(origin="/summary", name="summary: most important first"))
    rshares.append(2.0)
    # the warnings and failures only (the steps of the scenario are INFO): a failure at the
    # end of a long run is not fifty rows down; the entity path column says nothing here
    right.append(rrb.TextLogView(
        origin="/events", name="warnings and failures (all events: the view's level filter)",
        rows=rrba.TextLogRows(filter_by_log_level=["WARN", "ERROR"]),
        columns=rrba.TextLogColumns(text_log_columns=[
            rrbc.TextLogColumn(kind=k, visible=k != "EntityPath")
            for k in ("EntityPath", "LogLevel", "Body")])))
    rshares.append(1.5)
    cols: list[Any] = []
    if left:
        cols.append(rrb.Vertical(*left, row_shares=shares))
    cols.append(rrb.Vertical(*right, row_shares=rshares))
    return rrb.Blueprint(
        rrb.Horizontal(*cols, column_shares=[3, 2] if left else None),
        rrb.BlueprintPanel(state="collapsed"), rrb.SelectionPanel(state="collapsed"),
        rrb.TimePanel(state="collapsed", timeline="sim_time", play_state="paused",
                      **_selection(rec)))


def _selection(rec: Any) -> dict[str, Any]:
    """At open, after a failure: the moments before and just after the first failure
    selected on the time line (rerun 0.41's blueprint has no initial time cursor: a playing
    loop over the selection would start from the cursor at 0, so the plant view shows the
    failure's moment by its own visible time range instead)."""
    if rec.focus is None:
        return {}
    import rerun.blueprint as rrb

    a, b = rec.span()
    w = max((b - a) * 0.02, 1.0)
    return {"time_selection": rrb.components.AbsoluteTimeRange(
        min=_ns(max(a, rec.focus - w)), max=_ns(min(b, rec.focus + w / 2)))}


def _ns(seconds: float) -> int:
    return int(round(seconds * 1e9))


def plot_title(p: Any) -> str:
    """A plot's title names its lines and its dashed limits (the legend is hidden, so that
    it covers no data): ``LEVEL [m] · dashed: LS1 0.5, LS2 1.5, rim 2``."""
    if not p.limits:
        return p.title
    lims = ", ".join(f"{lim.label} {lim.value:g}" for lim in
                     sorted(p.limits, key=lambda x: x.value))
    return f"{p.title} · dashed: {lims}"
