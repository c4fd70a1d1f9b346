"""rerun recordings of a run (rerun-sdk 0.41, the optional [viz] extra).

Layout of a recording:

* ``/analog/<signal>``: analog values as lines (setpoints and alarm limits as dashed companions
  under ``/analog/<signal>/limits/<name>``);
* ``/digital/<signal>``: BOOLs stacked like a logic analyzer, drawn step-after;
* ``/markers/<signal>``: points where something happened to the signal (chatter, fault);
* ``/events``: a text log (faults and chatter as warnings);
* ``/scan/duration_us``: the wall-clock time each scan took;
* ``/plant``: a 2D picture of the plant where it has geometry (bottles, tank fill, fans);
* time lines ``sim_time`` (seconds) and ``scan`` (scan number) to scrub to any scan.

Everything is logged column-wise with ``rr.send_columns``, so a whole run is written at once.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .series import Series


@dataclass
class Event:
    time: float
    kind: str
    source: str
    message: str
    level: str = "INFO"  # INFO | WARN | ERROR


@dataclass
class Recording:
    """What goes into one .rrd file (built from a Trace by :mod:`plclab.viz.trace_adapter`)."""

    analog: list[Series] = field(default_factory=list)
    digital: list[Series] = field(default_factory=list)
    events: list[Event] = field(default_factory=list)
    limits: dict[str, list[tuple[str, float]]] = field(default_factory=dict)
    scan_times: Sequence[float] = ()
    scan_durations_us: Sequence[float] = ()
    geometry: dict[str, Any] = field(default_factory=dict)
    frames: Callable[[float], list[dict]] | None = None  # time -> dynamic shapes
    frame_times: Sequence[float] = ()
    title: str = "plclab"


_PALETTE = [(31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40), (148, 103, 189),
            (140, 86, 75), (227, 119, 194), (127, 127, 127), (188, 189, 34), (23, 190, 207)]


def _entity(name: str) -> str:
    return "".join(c if c.isalnum() or c in "_-" else "_" for c in name)


class RrdWriter:
    """A rerun stream for one run: the layout is fixed by the first :class:`Recording`, then
    :meth:`send` logs rows (all of them, or only the new ones when streaming live)."""

    def __init__(self, rec: Recording, path: str | Path | None = "run.rrd",
                 spawn: bool = False, blueprint: bool = True) -> None:
        import rerun as rr

        self.rr = rr
        self.path = None if spawn else path
        self.stream = rr.RecordingStream(f"plclab-{_entity(rec.title)}")
        if spawn:
            self.stream.spawn()
        elif path is not None:
            self.stream.save(str(path))
        if blueprint:
            self._blueprint(rec)
        n = len(rec.digital)
        # stacked: each digital signal on its own 0..1 lane, like a logic analyzer
        self.lanes = {s.name: 1.5 * (n - 1 - k) for k, s in enumerate(rec.digital)}
        self.rows = 0  # rows already sent
        self.events = 0  # events already sent
        self.marked: set[str] = set()
        self._styles(rec)
        if rec.geometry:
            _log_geometry(self.stream, Recording(geometry=rec.geometry))

    def _blueprint(self, rec: Recording) -> None:
        import rerun.blueprint as rrb

        views = []
        if rec.analog:
            views.append(rrb.TimeSeriesView(origin="/analog", name="analog signals"))
        if rec.digital:
            views.append(rrb.TimeSeriesView(origin="/digital", name="digital I/O"))
        if rec.geometry:
            views.append(rrb.Spatial2DView(origin="/plant", name="plant"))
        views.append(rrb.TextLogView(origin="/events", name="events"))
        if len(rec.scan_durations_us):
            views.append(rrb.TimeSeriesView(origin="/scan", name="scan duration"))
        self.stream.send_blueprint(rrb.Blueprint(rrb.Vertical(*views)))

    def _styles(self, rec: Recording) -> None:
        rr = self.rr

        def style(entity, name, color, step):
            self.stream.log(entity, rr.SeriesLines(
                names=name, colors=[color],
                interpolation_mode="StepAfter" if step else "Linear"), static=True)

        for k, s in enumerate(rec.analog):
            style(f"/analog/{_entity(s.name)}", s.name, _PALETTE[k % len(_PALETTE)],
                  s.kind != "real")
            for lname, _ in rec.limits.get(s.name, []):
                style(f"/analog/{_entity(s.name)}/limits/{_entity(lname)}", lname,
                      (150, 150, 150), False)
        for k, s in enumerate(rec.digital):
            style(f"/digital/{_entity(s.name)}", s.name, _PALETTE[k % len(_PALETTE)], True)
        if len(rec.scan_durations_us):
            style("/scan/duration_us", "scan duration [us]", (100, 100, 100), False)

    def _columns(self, entity: str, times, values, first_index: int, offset: float = 0.0):
        import numpy as np

        rr = self.rr
        t = np.asarray(times, dtype=np.float64)
        v = np.asarray([float(x) for x in values], dtype=np.float64) + offset
        idx = np.arange(first_index, first_index + len(t), dtype=np.int64)
        rr.send_columns(entity, indexes=[rr.TimeColumn("sim_time", duration=t),
                                         rr.TimeColumn("scan", sequence=idx)],
                        columns=rr.Scalars.columns(scalars=v), recording=self.stream)

    def send(self, rec: Recording) -> None:
        """Log the rows of ``rec`` from row ``self.rows`` on, and its new events and frames."""
        start = self.rows
        for s in rec.analog:
            self._columns(f"/analog/{_entity(s.name)}", s.times[start:], s.values[start:],
                          start)
            for lname, value in rec.limits.get(s.name, []):
                if len(s.times) > start:
                    ends = [s.times[start], s.times[-1]]
                    self._columns(f"/analog/{_entity(s.name)}/limits/{_entity(lname)}", ends,
                                  [value, value], start)
        for s in rec.digital:
            self._columns(f"/digital/{_entity(s.name)}", s.times[start:], s.values[start:],
                          start, offset=self.lanes.get(s.name, 0.0))
        if len(rec.scan_durations_us):
            self._columns("/scan/duration_us", list(rec.scan_times)[start:],
                          list(rec.scan_durations_us)[start:], start)
        self.rows = max([len(s.times) for s in rec.analog + rec.digital] + [start])
        self._events(rec.events[self.events:])
        self.events = len(rec.events)
        if rec.geometry and rec.frames is not None:
            _log_frames(self.stream, rec)

    def _events(self, events: list[Event]) -> None:
        rr = self.rr
        levels = {"INFO": rr.TextLogLevel.INFO, "WARN": rr.TextLogLevel.WARN,
                  "ERROR": rr.TextLogLevel.ERROR}
        for ev in sorted(events, key=lambda e: e.time):
            self.stream.set_time("sim_time", duration=ev.time)
            self.stream.log("/events", rr.TextLog(f"[{ev.kind}] {ev.source}: {ev.message}",
                                                  level=levels.get(ev.level,
                                                                   rr.TextLogLevel.INFO)))
            if ev.level != "INFO":
                name = _entity(ev.source)
                if name not in self.marked:
                    self.marked.add(name)
                    self.stream.log(f"/markers/{name}", rr.SeriesPoints(
                        markers="cross", colors=[(214, 39, 40)]), static=True)
                self.stream.log(f"/markers/{name}",
                                rr.Scalars(self.lanes.get(ev.source, 0.0) + 1.2))

    def close(self) -> Path | None:
        if self.path is not None:
            self.stream.flush()
            self.stream.disconnect()
            return Path(self.path)
        return None


def write_rrd(rec: Recording, path: str | Path | None = "run.rrd", spawn: bool = False,
              blueprint: bool = True) -> Path | None:
    """Write ``rec`` to ``path`` (headless), or open a viewer with ``spawn=True``."""
    w = RrdWriter(rec, path, spawn, blueprint)
    w.send(rec)
    return w.close()


def _log_geometry(stream, rec: Recording) -> None:
    """The plant's static shapes."""
    import rerun as rr

    for shp in rec.geometry.get("shapes", []):
        _log_shape(stream, f"/plant/static/{_entity(shp.get('name', 'shape'))}", shp, rr,
                   static=True)


def _log_frames(stream, rec: Recording) -> None:
    """The plant's moving parts at each frame time."""
    import rerun as rr

    for t in rec.frame_times:
        stream.set_time("sim_time", duration=float(t))
        for shp in rec.frames(t):
            _log_shape(stream, f"/plant/dynamic/{_entity(shp.get('name', 'shape'))}", shp, rr)


def _log_shape(stream, entity: str, shp: dict, rr, static: bool = False) -> None:
    kind = shp.get("type")
    color = shp.get("color", (90, 90, 90))
    if kind == "rect":
        if shp.get("angle"):
            cx, cy = shp["x"] + shp["w"] / 2, shp["y"] + shp["h"] / 2
            pts = _rotated_rect(cx, cy, shp["w"], shp["h"], shp["angle"])
            stream.log(entity, rr.LineStrips2D([pts], colors=[color]), static=static)
        else:
            stream.log(entity, rr.Boxes2D(mins=[(shp["x"], -shp["y"] - shp["h"])],
                                          sizes=[(shp["w"], shp["h"])], colors=[color],
                                          labels=[shp.get("label", "")]), static=static)
    elif kind == "line":
        stream.log(entity, rr.LineStrips2D([[(shp["x0"], -shp["y0"]), (shp["x1"], -shp["y1"])]],
                                           colors=[color]), static=static)
    elif kind == "mark":
        stream.log(entity, rr.Points2D([(shp["x"], -shp["y"])], labels=[shp.get("name", "")],
                                       colors=[color], radii=[0.01]), static=static)
    elif kind == "clear":
        stream.log(entity, rr.Clear(recursive=True))


def _rotated_rect(cx: float, cy: float, w: float, h: float, angle: float) -> list:
    c, s = math.cos(angle), math.sin(angle)
    pts = []
    for dx, dy in ((-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2),
                   (-w / 2, -h / 2)):
        x, y = cx + dx * c - dy * s, cy + dx * s + dy * c
        pts.append((x, -y))  # screen y grows downwards in 2D views
    return pts


def read_entity_paths(path: str | Path) -> set[str]:
    """Entity paths stored in an .rrd file (rerun's own reader; for tests and checks)."""
    from rerun.chunk import RrdReader

    paths: set[str] = set()
    for chunk in RrdReader(path).stream():
        ep = getattr(chunk, "entity_path", None)
        if ep is not None:
            paths.add(str(ep))
    return paths
