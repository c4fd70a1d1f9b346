"""rerun recordings of a run (rerun-sdk 0.41, the optional [viz] extra).

Layout of a recording (see :mod:`plclab.viz.layout` for what is chosen, ADR 0014 for why):

* ``/plots/<unit>/<signal>``: one time-series view per unit (``/plots/m/LEVEL``); limits as
  labelled dashed lines under ``/plots/<unit>/limits/<name>``; chatter, faults and failed
  criteria as red crosses under ``/plots/<unit>/markers/<what>``;
* ``/digital/<NN>_<name>``: one state lane per program input/output in the lab's order (ON/off),
  ``/digital/<NN>_<name>_<what>`` a red segment where that signal chattered or failed;
* ``/digital/00_first_failure``: the lane above them all, after a failure: what the first
  failed criterion checks over the span it looks at (teal, "checks ...") and a red mark at
  the failure; ``/plots/<unit>/failed_at`` a red vertical line at that moment in every plot;
* ``/summary``: Markdown, most important first (faults, failed criteria with their time,
  chatter, passed criteria, relay operation counts);
* ``/events``: the timed warnings and verdicts; ``/details/relays`` every relay operation
  (not in the default view);
* ``/plant``: the plant picture (:mod:`plclab.viz.plant_view`);
* ``/scan/duration_us``: wall-clock time of each scan, only when asked for;
* time lines ``sim_time`` (seconds) and ``scan`` (scan number).

Signals are logged column-wise with ``rr.send_columns``, so a whole run is written at once.
The default view (the blueprint) and the geometry of the failure's marks: :mod:`plclab.viz.view`.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import PlcError
from .layout import Layout, slug
from .plant_view import Picture, Shape
from .view import CHECKED, FAILED_LANE, blueprint, failure_line, failure_states, failure_time

MARK = (230, 40, 40)
OFF_LANE = (45, 45, 45)
MARK_COLORS = {"fails": (230, 40, 40), "chatter": (255, 140, 0), "plc fault": (200, 0, 200),
               "fault injected": (120, 120, 255)}
"""One colour per marker kind (red: a failed criterion); other warnings are yellow."""
WARN_MARK = (230, 200, 0)
DASHES = 48
"""A limit line is drawn as this many dashes across the run."""


@dataclass
class Event:
    time: float
    kind: str
    source: str
    message: str
    level: str = "INFO"  # INFO | WARN | ERROR


@dataclass
class Marker:
    """Something that happened to a signal, drawn in the plot or lane that shows it."""

    time: float
    label: str  # e.g. "PUMP chatter"
    kind: str = "mark"  # chatter | fault | fails ...: names the marker's lane
    end: float | None = None
    plot: str | None = None  # plot key
    value: float | None = None  # height of the cross in that plot
    lane: str | None = None  # lane entity under /digital


@dataclass
class Recording:
    """What goes into one recording (built from a Trace by :func:`plclab.viz.from_trace.recording`)."""

    layout: Layout = field(default_factory=Layout)
    events: list[Event] = field(default_factory=list)
    details: list[Event] = field(default_factory=list)
    markers: list[Marker] = field(default_factory=list)
    summary: str = ""
    scan_times: Sequence[float] = ()
    scan_durations_us: Sequence[float] = ()
    picture: Picture | None = None
    frame_rows: Sequence[int] = ()
    frame_times: Sequence[float] = ()
    view_span: tuple[float, float] | None = None  # time range at open (default: the run's)
    focus: float | None = None  # the moment of the first failure: the time selection at open
    failed: Any = None  # the first failed criterion (a layout.Verdict): its lane and line
    checks: str = ""  # what that criterion checks, in words with units

    @property
    def title(self) -> str:
        return self.layout.info.title()

    def span(self) -> tuple[float, float]:
        """First and last time of the signals: what the plots show at open."""
        ts = [s.times for s in [ln.series for p in self.layout.plots for ln in p.lines]
              + [lane.series for lane in self.layout.lanes] if len(s.times)]
        if not ts:
            return 0.0, 1.0
        return float(min(t[0] for t in ts)), float(max(t[-1] for t in ts))



def mark_color(kind: str) -> tuple[int, int, int]:
    """The colour of a marker kind: red for a failed criterion, one colour per other kind."""
    return MARK_COLORS.get(kind, WARN_MARK)


def _limit_entity(p: Any, lim: Any) -> str:
    """Highest limit first, as they lie in the plot (``/plots/m/limits/1_rim``)."""
    order = sorted(p.limits, key=lambda x: -x.value).index(lim) + 1
    return f"/plots/{p.key}/limits/{order}_{slug(lim.label)}"


def lane_entity(k: int, label: str) -> str:
    """Lanes sort by entity path in the viewer: the number keeps the lab's order. (The
    viewer shows a path's escapes, ``01\\ PUMP``, so the name and address of the student's
    variable are in the lane's state labels instead: :func:`lane_name`.)"""
    return f"/digital/{k + 1:02d}_{slug(label)}"


def lane_name(lane: Any) -> str:
    """What a lane says in its bars: the student's variable and its address, as a logic
    analyser names a channel (``PUMP %QX0.0``)."""
    addr = lane.address if lane.address.startswith("%") and lane.address != lane.label else ""
    return f"{lane.label} {addr}".strip()



class RrdWriter:
    """A rerun stream for one run: the layout is fixed by the first :class:`Recording`, then
    :meth:`send` logs rows (all of them, or only the new ones when streaming live)."""

    def __init__(self, rec: Recording, path: str | Path | None = "run.rrd",
                 spawn: bool = False, send_blueprint: bool = True, stream: Any = None) -> None:
        import rerun as rr

        self.rr = rr
        self.path = None if (spawn or stream is not None) else path
        info = rec.layout.info
        if stream is not None:  # a stream someone else shows (the notebook viewer)
            self.stream = stream
        else:
            self.stream = rr.RecordingStream(info.application_id(),
                                             recording_id=info.recording_id())
        if stream is None and spawn:
            self.stream.spawn()
        elif stream is None and path is not None:
            folder = Path(path).resolve().parent
            if not folder.is_dir():  # rerun's own error is a RuntimeError with a traceback
                raise PlcError("PLC3014", f"cannot write {path}: the folder {folder} does not "
                               "exist; create it or give a path in an existing folder")
            self.stream.save(str(path))
        self.stream.send_recording_name(info.title())
        self._failure_drawn = False
        props = {k: v for k, v in (("lab", info.lab), ("scenario", info.scenario),
                                   ("file", info.student_file)) if v}
        if info.score is not None:
            props["score"] = f"{info.score:g}/{info.max_score:g}"
        if props:
            self.stream.send_property("plclab", rr.AnyValues(**props))
        if send_blueprint:
            self.stream.send_blueprint(blueprint(rec))
        self.rows = 0  # rows already sent
        self._last: dict[str, bool] = {}  # last state sent per lane
        self._sent: set[str] = set()  # events and markers already sent
        self._shown: set[str] = set()  # plant entities drawn so far
        self._drawn: dict[str, Any] = {}  # what each plant entity shows now
        self.lane_paths = {lane.label: lane_entity(k, lane.label)
                           for k, lane in enumerate(rec.layout.lanes)}
        self._styles(rec)
        self._static_plant(rec)

    # ------------------------------------------------------------------ set-up
    def _styles(self, rec: Recording) -> None:
        rr, st = self.rr, self.stream
        for p in rec.layout.plots:
            for ln in p.lines:
                # MinMax: squeezed into a pixel, a square wave keeps both levels (every edge,
                # not an average of 0.5), a chattering level its whole swing
                st.log(f"/plots/{p.key}/{slug(ln.label)}", rr.SeriesLines(
                    names=ln.label, colors=[ln.color], widths=[2.0],
                    interpolation_mode="StepAfter" if ln.step else "Linear",
                    aggregation_policy="MinMax"), static=True)
            for lim in p.limits:
                st.log(_limit_entity(p, lim), rr.SeriesLines(
                    names=f"{lim.label} {lim.value:g} {p.unit}".rstrip(), colors=[lim.color],
                    widths=[1.5]), static=True)
        for lane in rec.layout.lanes:
            name = lane_name(lane)
            st.log(self.lane_paths[lane.label], rr.StateConfiguration(
                values=["1", "0"], labels=[f"{name} ON", f"{name} off"],
                colors=[lane.color, OFF_LANE]), static=True)
        if len(rec.scan_durations_us):
            st.log("/scan/duration_us", rr.SeriesLines(names="scan duration [us]",
                                                       colors=[(120, 120, 120)]), static=True)

    def _static_plant(self, rec: Recording) -> None:
        if rec.picture is None:
            return
        for shp in rec.picture.static:
            self._shapes(f"/plant/static/{slug(shp.name)}", [shp], static=True)

    # ------------------------------------------------------------------ rows
    def _columns(self, entity: str, times, values, first_index: int) -> None:
        import numpy as np

        rr = self.rr
        t = np.asarray(times, dtype=np.float64)
        v = np.asarray(values, dtype=np.float64)
        idx = np.arange(first_index, first_index + len(t), dtype=np.int64)
        rr.send_columns(entity, indexes=[rr.TimeColumn("sim_time", duration=t),
                                         rr.TimeColumn("scan", sequence=idx)],
                        columns=rr.Scalars.columns(scalars=v), recording=self.stream)

    def _states(self, entity: str, times, values) -> None:
        """Only the changes of a BOOL (and its first value): a lane of 24,000 scans with three
        switchings is four rows."""
        import numpy as np

        rr = self.rr
        v = np.asarray(values).astype(bool)
        if not len(v):
            return
        prev = self._last.get(entity)
        before = np.r_[[not v[0]] if prev is None else [prev], v[:-1]]
        keep = np.flatnonzero(v != before)
        self._last[entity] = bool(v[-1])
        if not len(keep):
            return
        t = np.asarray(times, dtype=np.float64)[keep]
        rr.send_columns(entity, indexes=[rr.TimeColumn("sim_time", duration=t)],
                        columns=rr.StateChange.columns(state=["1" if x else "0" for x in v[keep]]),
                        recording=self.stream)

    def _dashes(self, entity: str, value: float, a: float, b: float) -> None:
        """A dashed horizontal line from a to b: dashes separated by NaN gaps."""
        if b <= a:
            return
        p = (b - a) / DASHES
        ts, vs = [], []
        for k in range(DASHES):
            s = a + k * p
            ts += [s, s + 0.6 * p, s + 0.6 * p + 1e-9]
            vs += [value, value, float("nan")]
        rr = self.rr
        rr.send_columns(entity, indexes=[rr.TimeColumn("sim_time", duration=ts)],
                        columns=rr.Scalars.columns(scalars=vs), recording=self.stream)

    def send(self, rec: Recording) -> None:
        """Log the rows of ``rec`` from row ``self.rows`` on, and its new events and frames."""
        start = self.rows
        n = start
        for p in rec.layout.plots:
            for ln in p.lines:
                s = ln.series
                self._columns(f"/plots/{p.key}/{slug(ln.label)}", s.times[start:],
                              [float(x) for x in s.values[start:]], start)
                n = max(n, len(s.times))
            ends = [ln.series.times for ln in p.lines if len(ln.series.times) > start]
            if ends:
                a, b = float(ends[0][start]), float(ends[0][-1])
                for lim in p.limits:
                    self._dashes(_limit_entity(p, lim), lim.value, a, b)
        for lane in rec.layout.lanes:
            s = lane.series
            self._states(self.lane_paths[lane.label], s.times[start:], s.values[start:])
            n = max(n, len(s.times))
        if len(rec.scan_durations_us):
            self._columns("/scan/duration_us", list(rec.scan_times)[start:],
                          list(rec.scan_durations_us)[start:], start)
        self.rows = n
        self._events(rec)
        self._first_failure(rec)
        self._plant_frames(rec)

    def _first_failure(self, rec: Recording) -> None:
        """The lane above the I/O lanes (the span the failed criterion checks, the failure
        in red) and a red vertical line at the failure in every plot."""
        if rec.failed is None or self._failure_drawn:
            return
        self._failure_drawn = True
        rr, st, v = self.rr, self.stream, rec.failed
        t = failure_time(rec)
        when = f" at {v.time:.2f} s" if v.time is not None else " over the run"
        if v.time is None and t is not None:
            when += f" (PLC fault at {t:.2f} s)"
        checks = f"checks {rec.checks} ({v.name})" if rec.checks else f"checked by {v.name}"
        st.log(FAILED_LANE, rr.StateConfiguration(
            values=["w", "f", "0"], labels=[checks, f"FAILED {v.name}{when}", ""],
            colors=[CHECKED, MARK, (0, 0, 0, 0)], visible=[True, True, False]), static=True)
        times, states = failure_states(rec)
        rr.send_columns(FAILED_LANE, indexes=[rr.TimeColumn("sim_time", duration=times)],
                        columns=rr.StateChange.columns(state=states), recording=st)
        if t is None:
            return
        for p in rec.layout.plots:
            if not p.lines:
                continue
            entity = f"/plots/{p.key}/failed_at"
            # MinMax: the two points share a pixel column, averaged they would be a dot
            st.log(entity, rr.SeriesLines(names=f"FAILED {v.name}{when}", colors=[MARK],
                                          widths=[1.5], aggregation_policy="MinMax"),
                   static=True)
            ts, vs = failure_line(p, t)
            rr.send_columns(entity, indexes=[rr.TimeColumn("sim_time", duration=ts)],
                            columns=rr.Scalars.columns(scalars=vs), recording=st)

    def _events(self, rec: Recording) -> None:
        rr, st = self.rr, self.stream
        levels = {"INFO": rr.TextLogLevel.INFO, "WARN": rr.TextLogLevel.WARN,
                  "ERROR": rr.TextLogLevel.ERROR}
        # one send_columns per entity, not one log per event (a chattering relay has
        # hundreds of operations in /details): the same rows on sim_time (ADR 0033)
        evs = sorted(self._new(rec.events), key=lambda e: e.time)
        if evs:
            self._texts("/events", [ev.time for ev in evs],
                        [f"{ev.source}: {ev.message}" if ev.source else ev.message
                         for ev in evs],
                        [str(levels.get(ev.level, rr.TextLogLevel.INFO)) for ev in evs])
        details: dict[str, list[Event]] = {}
        for ev in self._new(rec.details):
            details.setdefault(f"/details/{slug(ev.kind)}", []).append(ev)
        for entity, group in details.items():
            self._texts(entity, [ev.time for ev in group],
                        [f"{ev.source}: {ev.message}" for ev in group])
        for m in self._new(rec.markers):
            self._marker(m)
        if rec.summary:
            st.log("/summary", rr.TextDocument(rec.summary, media_type="text/markdown"),
                   static=True)

    def _texts(self, entity: str, times: list[float], texts: list[str],
               levels: list[str] | None = None) -> None:
        """Rows of a ``TextLog`` (with their levels, if given) at their times."""
        rr = self.rr
        kw: dict[str, Any] = {"text": texts}
        if levels is not None:
            kw["level"] = levels
        rr.send_columns(entity, indexes=[rr.TimeColumn("sim_time", duration=times)],
                        columns=rr.TextLog.columns(**kw), recording=self.stream)

    def _new(self, items: list[Any]) -> list[Any]:
        """The items not sent yet (a live run sends a growing recording chunk by chunk)."""
        out = []
        for it in items:
            key = repr(it)
            if key not in self._sent:
                self._sent.add(key)
                out.append(it)
        return out

    def _marker(self, m: Marker) -> None:
        rr, st = self.rr, self.stream
        if m.plot is not None and m.value is not None:
            path = f"/plots/{m.plot}/markers/{slug(m.label)}"
            st.log(path, rr.SeriesPoints(markers="cross", colors=[mark_color(m.kind)],
                                         marker_sizes=[8.0], names=m.label), static=True)
            st.set_time("sim_time", duration=m.time)
            st.log(path, rr.Scalars(m.value))
        if m.lane is not None:
            path = f"{m.lane}_{slug(m.kind)}"  # a sibling: sorts right under its lane
            st.log(path, rr.StateConfiguration(values=["1", "0"], labels=[m.label, ""],
                                               colors=[mark_color(m.kind), (0, 0, 0, 0)],
                                               visible=[True, False]), static=True)
            st.set_time("sim_time", duration=m.time)
            st.log(path, rr.StateChange(state="1"))
            st.set_time("sim_time", duration=m.end if m.end is not None else m.time)
            st.log(path, rr.StateChange(state="0"))

    def _plant_frames(self, rec: Recording) -> None:
        """The plant's moving shapes at each frame time, an entity logged only when what it
        shows changed, and sent column-wise: one ``send_columns`` per entity (and kind) for
        all its frames, instead of one ``log`` per entity and frame (most of a recording's
        cost when it was logged row by row, ADR 0033)."""
        pic = rec.picture
        if pic is None:
            return
        shown, last = self._shown, self._drawn
        rows: dict[tuple[str, str], list[tuple[float, list[Shape]]]] = {}
        clears: dict[str, list[float]] = {}
        for t, i in zip(rec.frame_times, rec.frame_rows, strict=True):
            groups: dict[str, list[Shape]] = {}
            for shp in pic.frame(int(i)):
                groups.setdefault(shp.name, []).append(shp)
            for name, shapes in groups.items():
                key = tuple((s.kind, s.color, round(s.x, 4), round(s.y, 4), round(s.w, 4),
                             round(s.h, 4), round(s.angle, 3), s.label) for s in shapes)
                # every shape at the failure's moment: the plant view shows that moment
                if last.get(name) != key or (rec.focus is not None and t == rec.focus):
                    rows.setdefault((name, shapes[0].kind), []).append((float(t), shapes))
                    last[name] = key
            for name in shown - set(groups):
                if last.get(name) != "":
                    clears.setdefault(name, []).append(float(t))
                    last[name] = ""
            shown |= set(groups)
        for (name, _kind), items in rows.items():
            self._shape_columns(f"/plant/{name}", items)
        import numpy as np

        rr = self.rr
        for name, ts in clears.items():
            rr.send_columns(f"/plant/{name}", indexes=[rr.TimeColumn(
                "sim_time", duration=np.asarray(ts, dtype=np.float64))],
                            columns=rr.Clear.columns(is_recursive=[False] * len(ts)),
                            recording=self.stream)

    def _shape_columns(self, entity: str, items: list[tuple[float, list[Shape]]]) -> None:
        """Rows of shapes of one kind (``(time, shapes)``), as :meth:`_shapes` would log each
        of them, in one ``send_columns``."""
        import numpy as np

        rr = self.rr
        kind = items[0][1][0].kind
        times = [t for t, _ in items]
        lengths: list[int] = []
        if kind in ("box", "outline"):
            strips: list[Any] = []
            radii: list[float] = []
            colors: list[Any] = []
            for _, shapes in items:
                n0 = len(strips)
                for s in shapes:
                    if kind == "box":
                        for strip, r in _box_slices(s):
                            strips.append(strip)
                            radii.append(1.2 * r)
                            colors.append(s.color)
                    else:
                        strips.append([(x, -y) for x, y in s.points])
                        radii.append(float(rr.Radius.ui_points(2.0)))
                        colors.append(s.color)
                lengths.append(len(strips) - n0)
            if kind == "box":  # equal strips of two points: one (N, 2, 2) array converts fast
                strips = np.asarray(strips, dtype=np.float32).reshape(-1, 2, 2)
            cols = list(rr.LineStrips2D.columns(strips=strips, radii=radii, colors=colors)
                        .partition(lengths))
        elif kind in ("dot", "text"):
            pos: list[tuple[float, float]] = []
            radii, colors, labels = [], [], []
            for _, shapes in items:
                for s in shapes:
                    pos.append((s.x, -s.y))
                    radii.append(s.r if kind == "dot" else 1e-6)
                    colors.append(s.color)
                    labels.append(s.label)
                lengths.append(len(shapes))
            cols = list(rr.Points2D.columns(positions=pos, radii=radii, colors=colors,
                                            labels=labels).partition(lengths))
            cols += list(rr.Points2D.columns(show_labels=[True] * len(items)))
        else:
            return
        rr.send_columns(entity, indexes=[rr.TimeColumn(
            "sim_time", duration=np.asarray(times, dtype=np.float64))],
                        columns=cols, recording=self.stream)

    def _shapes(self, entity: str, shapes: list[Shape], static: bool = False) -> None:
        rr, st = self.rr, self.stream
        kind = shapes[0].kind
        if kind == "box":
            strips, radii, colors = [], [], []
            for s in shapes:
                for strip, r in _box_slices(s):
                    strips.append(strip)
                    radii.append(1.2 * r)  # overlap: no seams between the slices
                    colors.append(s.color)
            st.log(entity, rr.LineStrips2D(strips, radii=radii, colors=colors), static=static)
        elif kind == "outline":
            st.log(entity, rr.LineStrips2D([[(x, -y) for x, y in s.points] for s in shapes],
                                           colors=[s.color for s in shapes],
                                           radii=rr.Radius.ui_points(2.0)), static=static)
        elif kind in ("dot", "text"):
            st.log(entity, rr.Points2D([(s.x, -s.y) for s in shapes],
                                       radii=[s.r if kind == "dot" else 1e-6 for s in shapes],
                                       colors=[s.color for s in shapes],
                                       labels=[s.label for s in shapes], show_labels=True),
                   static=static)

    def close(self) -> Path | None:
        if self.path is not None:
            self.stream.flush()
            self.stream.disconnect()
            return Path(self.path)
        return None


def _box_slices(s: Shape, n: int = 6) -> list[tuple[list[tuple[float, float]], float]]:
    """A filled rotated rectangle as ``n`` thick segments along its long side (rerun's boxes
    are outlines only, and a thick line has round caps: thin slices keep the corners nearly
    square), in screen coordinates (y down). Returns (strip, radius) pairs."""
    import math

    cx, cy = s.x + s.w / 2, s.y + s.h / 2
    c, sn = math.cos(s.angle), math.sin(s.angle)
    long_, short = (s.h, s.w) if s.h >= s.w else (s.w, s.h)
    t = short / n
    half = max(long_ - t, 0.0) / 2  # the caps add t/2 at each end
    out = []
    for k in range(n):
        off = -short / 2 + t * (k + 0.5)
        if s.h >= s.w:  # long axis along the box's y
            ax, ay, ox, oy = -sn * half, c * half, c * off, sn * off
        else:
            ax, ay, ox, oy = c * half, sn * half, -sn * off, c * off
        x, y = cx + ox, cy + oy
        out.append(([(x - ax, -(y - ay)), (x + ax, -(y + ay))], t / 2))
    return out


def write_rrd(rec: Recording, path: str | Path | None = "run.rrd", spawn: bool = False,
              send_blueprint: bool = True, cursor: float | None = None) -> Path | None:
    """Write ``rec`` to ``path`` (headless), or open a viewer with ``spawn=True``: its time
    cursor then stands at ``cursor`` (default: the recording's first failure, if any)."""
    w = RrdWriter(rec, path, spawn, send_blueprint)
    w.send(rec)
    out = w.close()
    if spawn:
        info = rec.layout.info
        fails = [v.time for v in info.verdicts if not v.passed and v.time is not None]
        t = cursor if cursor is not None else (min(fails) if fails else None)
        if t is not None:
            place_cursor(t, info.recording_id())
    return out


def place_cursor(t: float, recording_id: str = "", connect: Any = None,
                 url: str = "rerun+http://127.0.0.1:9876/proxy", tries: int = 20,
                 pause: float = 0.5) -> bool:
    """Move the time cursor of a viewer plclab spawned to ``t`` s on ``sim_time``, paused, in
    the recording ``recording_id`` once it has arrived (ADR 0050: a blueprint or a file
    cannot set the cursor; only a live viewer, through ``rerun.experimental.ViewerClient``).
    Best effort: False when no viewer answers in ``tries`` x ``pause`` s."""
    import time

    if connect is None:
        try:
            from rerun.experimental import ViewerClient
        except ImportError:
            return False
        connect = ViewerClient.connect
    for _ in range(tries):
        try:
            client = connect(url)
            state = client.get_state()
            rec = next((r for r in state.recordings
                        if not recording_id or str(r.store_id).endswith(":" + recording_id)),
                       None)
            if rec is not None:
                client.set_time("sim_time", duration=float(t), play_state="paused",
                                recording=rec.store_id)
                return True
        except Exception:  # noqa: BLE001 - the viewer not up yet, or an older one
            pass
        time.sleep(pause)
    return False


def write_many(recs: list[Recording], path: str | Path) -> Path:
    """Several recordings (every scenario of a run) in one file, each selectable in the viewer.

    Each is written on its own, then rerun's own ``rrd merge`` joins them (a concatenation of
    .rrd files is not a valid .rrd since 0.41's footers)."""
    path = Path(path)  # each keeps its own time span and layout (its own application id)
    if len(recs) == 1:
        return write_rrd(recs[0], path) or path
    with tempfile.TemporaryDirectory(prefix="plclab-rrd-", dir=path.parent) as tmp:
        parts = [write_rrd(r, Path(tmp) / f"{k}.rrd") for k, r in enumerate(recs)]
        out = Path(tmp) / "all.rrd"
        cmd = [sys.executable, "-m", "rerun_cli", "rrd", "merge", *map(str, parts), "-o",
               str(out)]
        env = {**os.environ, "RUST_LOG": "error"}
        r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
        if r.returncode != 0 or not out.exists():
            raise PlcError("PLC4030", f"could not join the recordings of {len(recs)} scenarios "
                           f"into {path} (rerun rrd merge: {r.stderr.strip()[-300:]}); write "
                           "one scenario with --scenario NAME")
        os.replace(out, path)
    return path


def read_entity_paths(path: str | Path, recording_id: str | None = None) -> set[str]:
    """Entity paths stored in an .rrd file (rerun's own reader; for tests and checks)."""
    from rerun.chunk import RrdReader

    reader = RrdReader(path)
    stores = reader.recordings()
    store = stores[0] if stores else None
    if recording_id is not None:
        store = next(s for s in stores if s.recording_id == recording_id)
    paths: set[str] = set()
    for chunk in reader.stream(store=store):
        ep = getattr(chunk, "entity_path", None)
        if ep is not None:
            paths.add(str(ep))
    return paths
