"""From a :class:`~plclab.trace.Trace` to pictures and files: the glue behind
``plclab sim --rrd/--vcd/--wavedrom/--png`` and ``plclab view``.

For example::

    from plclab.viz import to_rerun
    to_rerun(trace, path="run.rrd")
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from ..errors import PlcError
from .chatter import output_stats
from .layout import Layout, RunInfo, plan, slug
from .recording import Event, Marker, Recording, write_rrd
from .series import Series
from .trace_series import plant_limits, plant_marks, plant_of, series  # noqa: F401 - public here too


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


CHATTER = (6, 5.0)
"""Chatter: at least 6 switchings within 5 s (a motor started twice or a reject pulse train
is not chatter; a pump on a bare level switch is)."""


def chatter_episodes(trace, min_toggles: int = CHATTER[0],
                     window: float = CHATTER[1]) -> list[tuple[str, float, float, int]]:
    """(output, start, end, switchings) of each chatter episode of a digital output
    (actuators, %Q columns; not lamps or transistor outputs, which blink on purpose)."""
    out = []
    info = trace.meta.get("signal_info", {})
    quiet = set()  # lamps and transistor outputs may blink: that is not relay chatter
    for r in trace.io:
        kind = (r.get("params") or {}).get("kind")
        if kind == "transistor" or info.get(r.get("plant_column"), {}).get("kind") == "lamp":
            quiet |= {r.get("column"), r.get("plant_column")}
    outs = [n for n in trace.columns if trace.kind(n) == "bool" and n not in quiet and (
        n.startswith("%Q") or info.get(n, {}).get("kind") == "actuator")]
    for name in outs:
        st = output_stats(Series(name, trace.time, trace.columns[name], "bool"),
                          min_toggles=min_toggles, window=window)
        out += [(name, a, b, n) for a, b, n in st.episodes]
    return out


def chatter_events(trace, min_toggles: int = CHATTER[0],
                   window: float = CHATTER[1]) -> list[Event]:
    """A warning event at each chatter episode of a digital output (actuators, %Q columns)."""
    return [Event(a, "chatter", name, f"{n} switchings in {b - a:.2f} s", "WARN")
            for name, a, b, n in chatter_episodes(trace, min_toggles, window)]


WARN_KINDS = {"overflow", "dry_run", "plc_fault", "io_fault", "fault_injected",
              "bottle_toppled", "chatter", "spill", "crash", "moved_without_two_hands",
              "curtain_violation", "alarm"}
"""Trace event kinds shown as warnings (plc_fault as an error)."""
MAX_INFO = 12
"""An informational event kind that happens more often than this is counted, not listed."""


def recording(trace, names: list[str] | None = None, t0: float | None = None,
              t1: float | None = None, fps: float = 10.0, info: RunInfo | None = None,
              scan: bool = False) -> Recording:
    """Build a :class:`Recording`: plots per unit, lanes in the lab's order, markers, the
    summary and events, the plant picture; ``scan`` adds the wall-clock scan durations."""
    if info is None:
        info = RunInfo(lab=str(trace.meta.get("plant", "")))
    start = t0 if t0 is not None else (float(trace.time[0]) if len(trace.time) else 0.0)
    end = t1 if t1 is not None else trace.t_end
    plant = plant_of(trace)
    lay = plan(trace, info, names, t0, t1, plant_marks(trace, plant))
    _criterion_lines(trace, lay)
    rec = Recording(layout=lay)
    first = first_failed(info.verdicts)
    if first is not None and first.time is not None:  # the moment every view shows
        rec.focus = first.time
    if first is not None:  # its lane above the I/O lanes, its line in every plot
        rec.failed, rec.checks = first, _checks_text(first.limits, trace, lay)
        faults = [e.time for e in trace.events if e.kind == "plc_fault" and start <= e.time]
        if first.time is None and faults:  # failed over the run: the PLC stopped here
            rec.focus = min(faults)

    def inside(t: float) -> bool:
        return start - 1e-9 <= t <= end + 1e-9

    evs = [e for e in trace.events if inside(e.time)]
    counts: dict[tuple[str, str], int] = {}
    for e in evs:
        counts[(e.kind, e.source)] = counts.get((e.kind, e.source), 0) + 1
    kinds: dict[str, int] = {}
    for e in evs:
        kinds[e.kind] = kinds.get(e.kind, 0) + 1
    for e in evs:
        level = "ERROR" if e.kind == "plc_fault" else "WARN" if e.kind in WARN_KINDS else "INFO"
        ev = Event(e.time, e.kind, _label(lay, e.source), e.message, level)
        if level == "INFO" and (e.kind == "relay" or kinds[e.kind] > MAX_INFO):
            rec.details.append(ev)
        else:
            rec.events.append(ev)
        if level != "INFO":
            what = e.kind.replace("_", " ")
            rec.markers += _markers(lay, e.source, what, e.time, None,
                                    text="" if lay.lane_of(e.source) is None else None)
    chat = []
    wired = {r.get("plant_column") for r in trace.io if r.get("direction") == "out"}
    for name, a, b, n in chatter_episodes(trace):
        if name in wired or not (inside(a) or inside(b)):  # once, by its PLC output
            continue
        e = Event(max(a, start), "chatter", name, f"{n} switchings in {b - a:.2f} s", "WARN")
        chat.append(e)
        rec.events.append(Event(e.time, "chatter", _label(lay, name), e.message, "WARN"))
        rec.markers += _markers(lay, name, "chatter", e.time, min(b, end))
    for v in info.verdicts:
        t = v.time if v.time is not None else end
        if not v.passed and _not_run(v):
            rec.events.append(Event(t, "verdict", "", f"not run {v.name}: {v.detail}", "INFO"))
        elif not v.passed:
            rec.events.append(Event(t, "verdict", "", f"FAILED {v.name}: {v.detail}", "ERROR"))
            if v.time is not None and inside(v.time):
                # on the signal its limits are drawn on (TEMP's band), else its first signal
                lim_sigs = [lim.signal for lim in v.limits if getattr(lim, "signal", "")]
                sig = next((s for s in [*lim_sigs, *v.signals]
                            if lay.lane_of(s) or lay.plot_of(s)), "")
                rec.markers += _markers(lay, sig, "fails", v.time, None, f"FAILED {v.name}")
        else:
            rec.events.append(Event(t, "verdict", "", f"passed {v.name}", "INFO"))
    rec.summary = _summary(lay, rec, chat, counts, trace)
    pic = None
    if plant is not None:
        key = None
        if lay.plots and lay.plots[0].lines:
            ln = lay.plots[0].lines[0]
            key = (ln.series.name, ln.label, lay.plots[0].unit, ln.step)
        from .plant_view import picture

        pic = picture(trace, plant, key)
    if pic is not None and len(trace.time):
        import numpy as np

        n = max(1, int((end - start) * fps))
        times = np.array([start + k / fps for k in range(n + 1)])
        if rec.focus is not None and start <= rec.focus <= end:  # a frame at the failure
            times = np.unique(np.append(times, rec.focus))
        rows = np.clip(np.searchsorted(trace.time, times + 1e-9, "right") - 1, 0,
                       len(trace.time) - 1)
        rec.picture, rec.frame_times, rec.frame_rows = pic, list(times), list(rows)
    wall = trace.wall.get("scan_s") if scan else None
    if wall is not None:
        keep = [k for k, t in enumerate(trace.time) if inside(float(t))]
        rec.scan_times = [float(trace.time[k]) for k in keep]
        rec.scan_durations_us = [float(wall[k]) * 1e6 for k in keep]
    return rec


def _criterion_lines(trace, lay: Layout) -> None:
    """The levels, set points and band edges of the failed criteria as dashed lines in the
    plot of their signal (beside the plant's switch heights), and the set points and bands
    of the criteria that passed (what the signal is held to); the plot's range widened to
    show them."""
    from .layout import LIMIT_COLORS, Limit

    for v in sorted(lay.info.verdicts, key=lambda v: v.passed):  # failures first
        if _not_run(v):
            continue
        for lim in v.limits:
            kinds = ("target", "band") if v.passed else ("level", "target", "band")
            if lim.kind not in kinds or lim.value is None:
                continue  # a passed criterion's band or set point is context, not its levels
            try:
                col = trace.resolve(lim.signal) if lim.signal in trace else lim.signal
            except PlcError:
                continue
            hit = lay.plot_of(col) or lay.plot_of(lim.signal)
            if hit is None:
                continue
            plot = hit[0]
            num = f"{lim.value:g}"  # the value is written after the label: not twice
            text = lim.label[:-len(num)].rstrip() if lim.label.endswith(num) else lim.label
            values = [(text or lim.kind, float(lim.value))]
            if lim.kind == "band" and lim.hi is not None:
                values = [(f"{lim.label} low", float(lim.value)),
                          (f"{lim.label} high", float(lim.hi))]
            for label, value in values:
                if any(abs(x.value - value) < 1e-9 for x in plot.limits):
                    continue
                color = LIMIT_COLORS[len(plot.limits) % len(LIMIT_COLORS)]
                plot.limits.append(Limit(f"{v.name}: {label}", value, color))
            from .layout import span_of

            lo, hi = plot.y_range or span_of(plot)
            vals = [x.value for x in plot.limits]
            lo, hi = min([lo, *vals]), max([hi, *vals])
            plot.y_range = (lo, hi + 0.05 * (hi - lo) if hi > lo else hi + 1.0)


def _label(lay: Layout, source: str) -> str:
    """An event source as the lab names it (``%QX0.0`` -> ``PUMP (%QX0.0)``)."""
    lane = lay.lane_of(source)
    if lane is not None and lane.label != source:
        return f"{lane.label} ({source})"
    return source


def _markers(lay: Layout, source: str, what: str, t: float, t_end: float | None,
             text: str | None = None) -> list[Marker]:
    """A cross in the plot of ``source`` (else in the first plot, on its first line) and a
    red segment under its lane, if it has one."""
    lane = lay.lane_of(source) if source else None
    name = lane.label if lane is not None else source
    label = f"{name} {what}".strip() if text is None else (text or what)
    out: list[Marker] = []
    from .recording import lane_entity

    if lane is not None:
        k = lay.lanes.index(lane)
        span = t_end if t_end is not None else t
        out.append(Marker(t, label, what, end=max(span, t + _min_width(lane)),
                          lane=lane_entity(k, lane.label)))
    hit = lay.plot_of(source) if source else None
    if hit is None and lay.plots and lay.plots[0].lines:
        hit = lay.plots[0], lay.plots[0].lines[0]
    if hit is not None:
        plot, line = hit
        out.append(Marker(t, label, what, plot=plot.key, value=_value_at(line.series, t)))
    return out


def _min_width(lane) -> float:
    """A marker segment is at least 1 % of the lane's time span wide, so it can be seen."""
    ts = lane.series.times
    return 0.01 * (float(ts[-1]) - float(ts[0])) if len(ts) > 1 else 0.0


def _value_at(s: Series, t: float) -> float:
    import bisect

    i = max(0, bisect.bisect_right(list(s.times), t) - 1) if len(s.times) else 0
    return float(s.values[i]) if len(s.values) else 0.0


def _summary(lay: Layout, rec: Recording, chat: list[Event], counts, trace) -> str:
    """Markdown, most important first: faults, failed criteria, chatter, warnings, passed
    criteria, relay operations."""
    info = lay.info
    lines = [f"**{info.title()}**", ""]
    errors = [e for e in rec.events if e.level == "ERROR" and e.kind != "verdict"]
    failed = [v for v in info.verdicts if not v.passed and not _not_run(v)]
    warns = [e for e in rec.events if e.level == "WARN" and e.kind != "chatter"]
    for e in errors:
        lines.append(f"- **FAULT at {_t(e.time)}**: {e.message}")
    for v in failed:
        when = f"at {_t(v.time)}" if v.time is not None else "over the run"
        lines.append(f"- **FAILED {when}: {v.name}**: {v.detail}")
        checks = _checks_text(v.limits, trace, lay)
        if checks:
            lines.append(f"  - checks: {checks}")
    for e in chat:
        lines.append(f"- **CHATTER at {_t(e.time)}**: {_label(lay, e.source)}, {e.message}")
    for e in warns[:8]:
        lines.append(f"- **WARNING at {_t(e.time)}**: {e.source}: {e.message}")
    if len(warns) > 8:
        lines.append(f"- {len(warns) - 8} more warnings in the events view")
    passed = [v for v in info.verdicts if v.passed]
    if passed:
        lines.append(f"- passed: {', '.join(v.name for v in passed)}")
    skipped = [v for v in info.verdicts if not v.passed and _not_run(v)]
    if skipped:
        lines.append(f"- not run (they need another criterion first): "
                     f"{', '.join(v.name for v in skipped)}")
    relays = [(src, n) for (kind, src), n in counts.items() if kind == "relay"]
    if relays:
        lines.append("- relay operations: " + ", ".join(
            f"{_label(lay, src)} {n}" for src, n in relays))
    others = [(k, n) for (k, _src), n in counts.items() if k not in WARN_KINDS | {"relay"}
              and n > MAX_INFO]
    if others:
        lines.append("- " + ", ".join(f"{n} × {k}" for k, n in others))
    if len(lines) == 2:
        lines.append("- nothing went wrong")
    return "\n".join(lines)


def _not_run(v) -> bool:
    """A criterion that was not evaluated (it requires another one), not a failure."""
    return v.detail.startswith(("not earned", "not run"))


def first_failed(verdicts):
    """The failed verdict every picture opens on: a moment of failure before a failure over
    the whole run, the earliest first, criteria that did not run left out."""
    failed = [v for v in verdicts if not v.passed and not _not_run(v)]
    if not failed:
        return None
    return min(failed, key=lambda v: (v.time is None, v.time or 0.0))


def _checks_text(limits, trace, lay: Layout | None = None) -> str:
    """What a criterion checks, in words with units (the same description the diagrams
    draw); with ``lay``, an address the criterion names (``%MW0``, also inside a rule,
    ``%MW4 + %MW0 == 6``) is named as the lab's I/O table and the view name it (``GOOD``)."""
    parts = []
    units = trace.meta.get("units", {}) or {}
    names: dict[str, str] = {}
    if lay is not None:
        names = {addr: name for name, addr, _ in lay.info.io if addr.startswith("%")}
    for lim in limits:
        try:
            col = trace.resolve(lim.signal) if lim.signal and lim.signal in trace else ""
        except PlcError:
            col = ""
        if lay is not None and lim.signal.startswith("%") and lim.signal not in names:
            shown = _shown_name(lay, col) or _shown_name(lay, lim.signal)
            if shown:
                names[lim.signal] = shown
        who = f"{lim.signal} " if lim.signal and lim.kind not in ("window", "time") else ""
        parts.append(f"{who}{lim.text(units.get(col, ''))}")
    text = "; ".join(dict.fromkeys(parts))
    return re.sub(r"%[A-Za-z]+\d+(?:\.\d+)?", lambda m: names.get(m.group(0), m.group(0)), text)


def _shown_name(lay: Layout, key: str) -> str:
    """The name a lane or plot line shows for a signal or column, '' when none does."""
    if not key:
        return ""
    lane = lay.lane_of(key)
    if lane is not None:
        return lane.label
    hit = lay.plot_of(key)
    return hit[1].label if hit is not None else ""


def _t(t: float | None) -> str:
    if t is None:
        return ""
    return f"{t:.2f} s" if t < 60 else f"{int(t // 60)} min {t % 60:.1f} s"


def lab_recordings(lab, result, student_file: str = "", fps: float = 10.0,
                   scan: bool = False, names: list[str] | None = None,
                   limits: Any = None) -> list[Recording]:
    """One recording per scenario of a graded run, named by lab, scenario, file and score,
    each with its own layout and time span; scenarios with a failed criterion first, in
    the lab's order (the first is the one every picture opens on). ``limits`` maps a
    criterion to what it checks (drawn on its signals), or is ``f(criterion, trace)`` for
    limits that depend on the run (a counter's plant count)."""
    from .layout import run_info

    recs = []  # each its own layout: a signal flat in this scenario tells nothing here
    for name, trace in result.traces.items():
        lims = limits
        if callable(limits):
            lims = {c.name: limits(c.name, trace) for c in lab.criteria}
        info = run_info(lab, result, name, student_file, lims)
        recs.append(recording(trace, names, fps=fps, info=info, scan=scan))
    recs.sort(key=lambda r: first_failed(r.layout.info.verdicts) is None)
    return recs


def write_lab_rrd(lab, result, path: str | Path, student_file: str = "", ns: Any = None,
                  limits: Any = None) -> str:
    """``plclab lab check --rrd F``: one recording file per scenario, so that the viewer
    cannot open another scenario first: ``F`` holds the first failing scenario (else the
    first), ``F-2-<scenario>.rrd``... the others, failures first; returns the lines to
    print (each file with its scenario and score)."""
    try:
        import rerun  # noqa: F401
    except ImportError:
        raise PlcError("PLC3005", "rerun recordings need the viz extra: pip install "
                       "'plclab[viz]'") from None
    sig = getattr(ns, "signals", None)
    if sig and sig == getattr(ns, "_default_signals", None):
        sig = None  # the lab's diagram list is for the diagram: the timeline shows all I/O
    names = [s.strip() for s in sig.split(",") if s.strip()] if sig else None
    recs = lab_recordings(lab, result, student_file, scan=bool(getattr(ns, "scan_times", False)),
                          names=names, limits=limits)
    from .recording import write_rrd

    path = Path(path)
    lines = []
    for k, rec in enumerate(recs):
        info = rec.layout.info
        where = path if k == 0 else path.with_name(
            f"{path.stem}-{k + 1}-{slug(info.scenario)}{path.suffix or '.rrd'}")
        write_rrd(rec, where)
        first = first_failed(info.verdicts)
        score = f"{info.score:g}/{info.max_score:g}" if info.score is not None else ""
        what = (f"FAILED {first.name}" + (f" at t = {first.time:.2f} s"
                                           if first.time is not None else "")
                if first is not None else "passed")
        lines.append(f"timeline: {where} (scenario '{info.scenario}', {score}, {what})")
    return "\n".join(lines)


def to_rerun(trace, path: str | Path | None = "run.rrd", spawn: bool = False,
             names: list[str] | None = None,
             window: tuple[float | None, float | None] = (None, None), fps: float = 10.0,
             info: RunInfo | None = None, scan: bool = False, cursor: float | None = None):
    """Write a trace as a rerun recording (``spawn=True`` opens the viewer instead); ``fps``
    is the frame rate of the plant animation (the signals keep every scan); ``info`` names
    the run and carries the lab's I/O table and verdicts; ``scan`` adds scan durations;
    ``cursor`` is where a spawned viewer's time cursor stands (default: the first failure)."""
    try:
        import rerun  # noqa: F401
    except ImportError:
        raise PlcError("PLC3005", "rerun recordings need the viz extra: pip install "
                       "'plclab[viz]'") from None
    rec = recording(trace, names, *window, fps=fps, info=info, scan=scan)
    return write_rrd(rec, None if spawn else path, spawn=spawn, cursor=cursor)


def export(trace, *, rrd: str | None = None, vcd: str | None = None,
           wavedrom: str | None = None, png: str | None = None, csv: str | None = None,
           signals: list[str] | None = None, window: str | None = None,
           spawn: bool = False, scan: bool = False, info: RunInfo | None = None,
           labels: dict[str, str] | None = None, cursor: float | None = None) -> list[str]:
    """Write every requested file; returns lines saying what was written where. ``labels``
    names columns for the timing diagram (``%QX0.0`` -> ``PUMP %QX0.0``; default: the
    wiring's signal names, :func:`plclab.viz.layout.signal_labels`)."""
    t0, t1 = parse_window(window)
    done = []
    if spawn:
        from .display import require_display

        require_display()
    ss = series(trace, signals, t0, t1) if (vcd or wavedrom or png or csv) else []
    if rrd or spawn:
        to_rerun(trace, rrd, spawn=spawn, names=signals, window=(t0, t1), info=info, scan=scan,
                 cursor=cursor)
        done.append("rerun viewer opened" if spawn else f"timeline: {rrd}")
    if vcd:
        from .exports import write_vcd

        write_vcd(ss, vcd)
        done.append(f"VCD: {vcd}")
    if wavedrom:
        from .exports import write_wavedrom

        write_wavedrom(ss, wavedrom, tick=trace.period, t0=t0, t1=t1)
        done.append(f"WaveDrom: {wavedrom}")
    if png:  # the failure diagram's description and renderers (ADR 0069), every row kept
        from .failure_trace import trace_diagram, write_diagram

        markers = [(e.time, e.kind) for e in chatter_events(trace)]
        write_diagram(trace_diagram(trace, signals, t0, t1, markers,
                                    str(trace.meta.get("title", "")), labels,
                                    max_rows=None), png)
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
    p.add_argument("--scan-times", action="store_true",
                   help="also record how long each scan took (wall clock) in the rerun timeline")


def run_exports(trace, ns: Any) -> list[str]:
    sig = [s.strip() for s in ns.signals.split(",") if s.strip()] if getattr(
        ns, "signals", None) else None
    return export(trace, rrd=getattr(ns, "rrd", None), vcd=getattr(ns, "vcd", None),
                  wavedrom=getattr(ns, "wavedrom", None), png=getattr(ns, "png", None),
                  signals=sig, window=getattr(ns, "window", None),
                  spawn=getattr(ns, "spawn", False), scan=getattr(ns, "scan_times", False),
                  labels=getattr(ns, "labels", None), cursor=getattr(ns, "cursor", None))
