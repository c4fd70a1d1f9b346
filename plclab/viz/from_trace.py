"""From a :class:`~plclab.trace.Trace` to pictures and files: the glue behind
``plclab sim --rrd/--vcd/--wavedrom/--png`` and ``plclab view``.

For example::

    from plclab.viz import to_rerun
    to_rerun(trace, path="run.rrd")
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from ..errors import PlcError
from .chatter import output_stats
from .recording import Event, Recording, write_rrd
from .series import Series


def series(trace, names: list[str] | None = None, t0: float | None = None,
           t1: float | None = None) -> list[Series]:
    """The named columns of a trace as step series (default: plant signals, then wired I/O)."""
    if names is None:
        names = list(trace.signals) + [r["column"] for r in trace.io
                                       if r.get("column") in trace.columns]
    units = trace.meta.get("units", {})
    out = []
    for name in names:
        try:
            col = trace.resolve(name)
        except PlcError:
            raise
        kind = trace.kind(col)
        kind = {"float": "real"}.get(kind, kind)
        s = Series(col, trace.time, trace.columns[col], kind, units.get(col, ""))
        out.append(s.window(t0, t1) if (t0 is not None or t1 is not None) else s)
    return out


def parse_window(text: str | None) -> tuple[float | None, float | None]:
    """``"0s..20s"``, ``"5..10"``, ``"1min.."`` -> (t0, t1) in seconds."""
    if not text:
        return None, None
    from ..sim.durations import parse_seconds

    if ".." not in text:
        raise PlcError("PLC3002", f"--window {text}: write START..END, e.g. 0s..20s")
    a, _, b = text.partition("..")
    t0 = parse_seconds(a) if a.strip() else None
    t1 = parse_seconds(b) if b.strip() else None
    if t0 is not None and t1 is not None and t1 <= t0:
        raise PlcError("PLC3002", f"--window {text}: the end must come after the start")
    return t0, t1


def chatter_events(trace, min_toggles: int = 4, window: float = 10.0) -> list[Event]:
    """A warning event at each chatter episode of a digital output (actuators, %Q columns)."""
    evs = []
    info = trace.meta.get("signal_info", {})
    outs = [n for n in trace.columns if trace.kind(n) == "bool" and (
        n.startswith("%Q") or info.get(n, {}).get("kind") == "actuator")]
    for name in outs:
        st = output_stats(Series(name, trace.time, trace.columns[name], "bool"),
                          min_toggles=min_toggles, window=window)
        for a, b, n in st.episodes:
            evs.append(Event(a, "chatter", name, f"{n} switchings in {b - a:.2f} s", "WARN"))
    return evs


def recording(trace, names: list[str] | None = None, t0: float | None = None,
              t1: float | None = None, fps: float = 10.0) -> Recording:
    """Build a :class:`Recording`: analog and digital lanes, limits, events, plant picture."""
    ss = series(trace, names, t0, t1)
    analog = [s for s in ss if s.kind == "real"]
    digital = [s for s in ss if s.kind != "real"]
    warn_kinds = {"overflow", "dry_run", "plc_fault", "io_fault", "fault_injected",
                  "bottle_toppled", "chatter", "spill", "crash", "moved_without_two_hands",
                  "curtain_violation"}
    events = [Event(e.time, e.kind, e.source, e.message,
                    "ERROR" if e.kind == "plc_fault" else "WARN" if e.kind in warn_kinds
                    else "INFO") for e in trace.events
              if (t0 is None or e.time >= t0) and (t1 is None or e.time <= t1)]
    events += [e for e in chatter_events(trace)
               if (t0 is None or e.time >= t0) and (t1 is None or e.time <= t1)]
    geometry, frames = _plant_picture(trace)
    start = t0 if t0 is not None else (float(trace.time[0]) if len(trace.time) else 0.0)
    end = t1 if t1 is not None else trace.t_end
    n = max(1, int((end - start) * fps))
    frame_times = [start + k / fps for k in range(n + 1)] if geometry else []
    wall = trace.wall.get("scan_s")
    scan_us = [] if wall is None else [float(x) * 1e6 for x in wall]
    return Recording(analog=analog, digital=digital, events=events,
                     limits=_limits(trace), scan_times=list(trace.time) if scan_us else [],
                     scan_durations_us=scan_us, geometry=geometry, frames=frames,
                     frame_times=frame_times, title=str(trace.meta.get("plant", "run")))


def _limits(trace) -> dict[str, list[tuple[str, float]]]:
    """Setpoints and switch heights worth drawing beside analog signals."""
    out: dict[str, list[tuple[str, float]]] = {}
    params = trace.meta.get("plant_params", {}) or {}
    plant = _plant(trace)
    if plant is not None and "LEVEL" in trace.columns:
        for attr, label in (("ls1_height", "LS1"), ("ls2_height", "LS2"), ("height", "rim")):
            v = params.get(attr, getattr(plant, attr, None))
            if isinstance(v, int | float):
                out.setdefault("LEVEL", []).append((label, float(v)))
    return out


def _plant(trace):
    name = trace.meta.get("plant")
    if not name:
        return None
    try:
        import plants

        return plants.get_plant(name, **(trace.meta.get("plant_params") or {}))
    except Exception:  # noqa: BLE001 - a picture is optional
        return None


def _plant_picture(trace):
    plant = _plant(trace)
    if plant is None:
        return {}, None
    try:
        geometry = plant.geometry() or {}
    except Exception:  # noqa: BLE001
        return {}, None
    if not geometry:
        return {}, None
    marks = [s for s in geometry.get("shapes", []) if s.get("type") in ("mark", "circle")
             and s.get("name") in trace.columns]
    fill = geometry.get("fill")
    bottles = sorted({c.split(".")[0] for c in trace.columns if c.startswith("bottle")
                      and c.endswith(".x")})
    bw = float(getattr(plant, "bottle_width", 0.06))
    bh = float(getattr(plant, "bottle_height", 0.25))

    def frames(t: float) -> list[dict]:
        shapes: list[dict] = []
        if fill and fill.get("signal") in trace.columns:
            h = float(trace.value_at(fill["signal"], t))
            shapes.append({"type": "rect", "name": "fill", "x": fill["x"], "y": fill["y"],
                           "w": fill["w"], "h": max(h, 0.0), "color": (40, 110, 220)})
        for m in marks:
            on = bool(trace.value_at(m["name"], t))
            shapes.append({"type": "mark", "name": m["name"] + "_state", "x": m["x"],
                           "y": m["y"], "color": (40, 180, 60) if on else (160, 160, 160)})
        for b in bottles:
            x = float(trace.value_at(f"{b}.x", t))
            if math.isnan(x):
                shapes.append({"type": "clear", "name": b})
                continue
            y = float(trace.value_at(f"{b}.y", t))
            a = float(trace.value_at(f"{b}.angle", t)) if f"{b}.angle" in trace.columns else 0
            shapes.append({"type": "rect", "name": b, "x": x - bw / 2, "y": y - bh / 2,
                           "w": bw, "h": bh, "angle": a or 1e-9, "color": (30, 140, 90)})
        return shapes

    geometry = {"shapes": [s for s in geometry.get("shapes", []) if s.get("type") != "circle"]
                + [{"type": "mark", "name": s["name"], "x": s["x"], "y": s["y"]}
                   for s in geometry.get("shapes", []) if s.get("type") == "circle"]}
    return geometry, frames


def to_rerun(trace, path: str | Path | None = "run.rrd", spawn: bool = False,
             names: list[str] | None = None,
             window: tuple[float | None, float | None] = (None, None), fps: float = 10.0):
    """Write a trace as a rerun recording (``spawn=True`` opens the viewer instead); ``fps``
    is the frame rate of the plant animation (the signals keep every scan)."""
    try:
        import rerun  # noqa: F401
    except ImportError:
        raise PlcError("PLC3005", "rerun recordings need the viz extra: pip install "
                       "'plclab[viz]'") from None
    return write_rrd(recording(trace, names, *window, fps=fps), None if spawn else path,
                     spawn=spawn)


def export(trace, *, rrd: str | None = None, vcd: str | None = None,
           wavedrom: str | None = None, png: str | None = None, csv: str | None = None,
           signals: list[str] | None = None, window: str | None = None,
           spawn: bool = False) -> list[str]:
    """Write every requested file; returns lines saying what was written where."""
    t0, t1 = parse_window(window)
    done = []
    ss = series(trace, signals, t0, t1) if (vcd or wavedrom or png or csv) else []
    if rrd or spawn:
        to_rerun(trace, rrd, spawn=spawn, names=signals, window=(t0, t1))
        done.append("rerun viewer opened" if spawn else f"timeline: {rrd}")
    if vcd:
        from .exports import write_vcd

        write_vcd(ss, vcd)
        done.append(f"VCD: {vcd}")
    if wavedrom:
        from .exports import write_wavedrom

        write_wavedrom(ss, wavedrom, tick=trace.period, t0=t0, t1=t1)
        done.append(f"WaveDrom: {wavedrom}")
    if png:
        from .timing import timing_diagram

        markers = [(e.time, e.kind) for e in chatter_events(trace)]
        timing_diagram(ss[:12], png, t0=t0, t1=t1, markers=markers,
                       title=str(trace.meta.get("title", "")))
        done.append(f"timing diagram: {png}")
    if csv:
        from .exports import to_csv

        to_csv(ss, csv)
        done.append(f"CSV: {csv}")
    return done


def add_export_args(p: Any) -> None:
    """The export flags shared by ``plclab sim``, ``plclab view`` and ``plclab lab check``."""
    p.add_argument("--rrd", help="write a rerun recording (.rrd)")
    p.add_argument("--spawn", action="store_true", help="open the rerun viewer live")
    p.add_argument("--vcd", help="write a VCD file (GTKWave)")
    p.add_argument("--wavedrom", help="write WaveDrom WaveJSON")
    p.add_argument("--png", help="write a timing diagram (.png or .svg)")
    p.add_argument("--signals", help="signals for the exports, comma separated")
    p.add_argument("--window", help="time window for the exports, e.g. 0s..20s")


def run_exports(trace, ns: Any) -> list[str]:
    sig = [s.strip() for s in ns.signals.split(",") if s.strip()] if getattr(
        ns, "signals", None) else None
    return export(trace, rrd=getattr(ns, "rrd", None), vcd=getattr(ns, "vcd", None),
                  wavedrom=getattr(ns, "wavedrom", None), png=getattr(ns, "png", None),
                  signals=sig, window=getattr(ns, "window", None),
                  spawn=getattr(ns, "spawn", False))
