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


def write_rrd(rec: Recording, path: str | Path | None = "run.rrd", spawn: bool = False,
              blueprint: bool = True) -> Path | None:
    """Write ``rec`` to ``path`` (headless), or open a viewer with ``spawn=True``."""
    import numpy as np
    import rerun as rr
    import rerun.blueprint as rrb

    stream = rr.RecordingStream(f"plclab-{_entity(rec.title)}")
    if spawn:
        stream.spawn()
    elif path is not None:
        stream.save(str(path))
    if blueprint:
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
        stream.send_blueprint(rrb.Blueprint(rrb.Vertical(*views)))

    def send(entity: str, s: Series, step: bool, color, offset: float = 0.0) -> None:
        t = np.asarray(s.times, dtype=np.float64)
        v = np.asarray([float(x) for x in s.values], dtype=np.float64) + offset
        stream.log(entity, rr.SeriesLines(
            names=s.name, colors=[color],
            interpolation_mode="StepAfter" if step else "Linear"), static=True)
        idx = np.arange(len(t), dtype=np.int64)
        rr.send_columns(entity, indexes=[rr.TimeColumn("sim_time", duration=t),
                                         rr.TimeColumn("scan", sequence=idx)],
                        columns=rr.Scalars.columns(scalars=v), recording=stream)

    for k, s in enumerate(rec.analog):
        color = _PALETTE[k % len(_PALETTE)]
        send(f"/analog/{_entity(s.name)}", s, s.kind != "real", color)
        for lname, value in rec.limits.get(s.name, []):
            lim = Series(lname, [s.times[0], s.times[-1]], [value, value], "real")
            send(f"/analog/{_entity(s.name)}/limits/{_entity(lname)}", lim, False,
                 (150, 150, 150))
    n = len(rec.digital)
    for k, s in enumerate(rec.digital):
        # stacked: each digital signal on its own 0..1 lane, like a logic analyzer
        send(f"/digital/{_entity(s.name)}", s, True, _PALETTE[k % len(_PALETTE)],
             offset=1.5 * (n - 1 - k))
    if len(rec.scan_durations_us):
        d = Series("scan duration [us]", list(rec.scan_times), list(rec.scan_durations_us))
        send("/scan/duration_us", d, False, (100, 100, 100))
    levels = {"INFO": rr.TextLogLevel.INFO, "WARN": rr.TextLogLevel.WARN,
              "ERROR": rr.TextLogLevel.ERROR}
    lanes = {s.name: 1.5 * (n - 1 - k) for k, s in enumerate(rec.digital)}
    for ev in sorted(rec.events, key=lambda e: e.time):
        stream.set_time("sim_time", duration=ev.time)
        stream.log("/events", rr.TextLog(f"[{ev.kind}] {ev.source}: {ev.message}",
                                         level=levels.get(ev.level, rr.TextLogLevel.INFO)))
        if ev.level != "INFO":
            y = lanes.get(ev.source, 0.0) + 1.2
            stream.log(f"/markers/{_entity(ev.source)}", rr.Scalars(y))
    for name in {_entity(ev.source) for ev in rec.events if ev.level != "INFO"}:
        stream.log(f"/markers/{name}", rr.SeriesPoints(markers="cross", colors=[(214, 39, 40)]),
                   static=True)
    if rec.geometry:
        _log_geometry(stream, rec)
    if path is not None and not spawn:
        stream.flush()
        stream.disconnect()
        return Path(path)
    return None


def _log_geometry(stream, rec: Recording) -> None:
    import rerun as rr

    statics = rec.geometry.get("shapes", [])
    for shp in statics:
        _log_shape(stream, f"/plant/static/{_entity(shp.get('name', 'shape'))}", shp, rr,
                   static=True)
    if rec.frames is None:
        return
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
