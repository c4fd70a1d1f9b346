"""What a timeline shows by default, decided from a Trace and (optionally) its lab.

Pure Python (no rerun): :func:`plan` picks one plot per physical unit (level in m with the switch
heights as labelled limits, valve and pump speed in %, ...), one digital lane per program input
and output in the lab's order and named by its I/O table (not by address), and the student's
watched variables. :mod:`plclab.viz.recording` turns a :class:`Layout` into rerun entities and a
blueprint; tests read the layout and the recording back.

>>> info = RunInfo(lab="tank-two-position", scenario="normal", student_file="tank.st",
...                score=20, max_score=26)
>>> info.title()
'tank-two-position · normal · tank.st · 20/26'
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from .series import Series

LINE_COLORS = [(31, 119, 180), (44, 160, 44), (148, 103, 189), (140, 86, 75), (127, 127, 127),
               (23, 190, 207)]
"""Colours of the measured lines of one plot (each plot starts again at blue)."""
LIMIT_COLORS = [(255, 127, 14), (214, 39, 40), (188, 189, 34), (227, 119, 194), (23, 190, 207)]
"""Colours of limit lines: never one of the first line colours."""
LANE_COLORS = {"in": (31, 119, 180), "out": (44, 160, 44), "var": (148, 103, 189)}
"""ON colour of a digital lane: program input, program output, watched variable."""
MAX_PLOTS = 4
"""At most this many analog plots by default (the lab's own signals first)."""
HIDDEN_UNITS = {"mA", "Ohm"}
"""Transmitter signals shown only when the lab is about them (in its diagram or criteria)."""


@dataclass
class Verdict:
    """One criterion's result in one scenario."""

    name: str
    passed: bool
    time: float | None = None
    detail: str = ""
    signals: list[str] = field(default_factory=list)
    limits: list[Any] = field(default_factory=list)  # what it checks (criteria.Limit)


@dataclass
class RunInfo:
    """What names a recording and what the lab says about the run (all optional)."""

    lab: str = ""
    scenario: str = ""
    student_file: str = ""
    score: float | None = None
    max_score: float | None = None
    io: list[tuple[str, str, str]] = field(default_factory=list)  # (name, address, type)
    watch: list[str] = field(default_factory=list)
    focus: list[str] = field(default_factory=list)  # signals the lab is about
    keep: list[str] = field(default_factory=list)  # shown even when flat in this run
    verdicts: list[Verdict] = field(default_factory=list)

    def title(self) -> str:
        """``lab · scenario · file · score``: the recording's name in the viewer."""
        parts = [p for p in (self.lab, self.scenario, self.student_file) if p]
        if self.score is not None:
            parts.append(f"{self.score:g}/{self.max_score:g}" if self.max_score is not None
                         else f"{self.score:g}")
        return " · ".join(parts) or "plclab run"

    def application_id(self) -> str:
        """One per lab and scenario: the viewer keeps one blueprint per application, so each
        scenario opens with its own layout and time span, not another scenario's."""
        return " ".join(p for p in ("plclab", self.lab, self.scenario) if p)

    def recording_id(self) -> str:
        """Stable per lab, scenario and file, so a re-run replaces its recording in the viewer."""
        raw = "/".join(p for p in (self.lab, self.scenario, self.student_file) if p) or "run"
        return re.sub(r"[^A-Za-z0-9._/-]+", "-", raw)


@dataclass
class Line:
    """One measured curve of a plot."""

    label: str
    series: Series
    color: tuple[int, int, int]
    step: bool = False


@dataclass
class Limit:
    """A constant drawn dashed across a plot (switch heights, alarm limits)."""

    label: str
    value: float
    color: tuple[int, int, int]


@dataclass
class Plot:
    """One time-series view: the signals of one unit."""

    key: str  # entity name under /plots
    unit: str
    lines: list[Line] = field(default_factory=list)
    limits: list[Limit] = field(default_factory=list)
    y_range: tuple[float, float] | None = None

    @property
    def title(self) -> str:
        names = ", ".join(ln.label for ln in self.lines)
        if self.unit == "every edge":
            return f"every edge of the fast-switching signals: {names}"
        if self.unit == "watched":
            return f"watched: {names}"
        return f"{names} [{self.unit}]" if self.unit else names


@dataclass
class Lane:
    """One digital lane: a BOOL the program reads or writes, named as the lab names it."""

    label: str
    series: Series
    direction: str  # in | out | var
    address: str = ""

    @property
    def color(self) -> tuple[int, int, int]:
        return LANE_COLORS.get(self.direction, LANE_COLORS["var"])


@dataclass
class Layout:
    plots: list[Plot] = field(default_factory=list)
    lanes: list[Lane] = field(default_factory=list)
    info: RunInfo = field(default_factory=RunInfo)

    def plot_of(self, label: str) -> tuple[Plot, Line] | None:
        """The plot and line drawing ``label`` (a signal or column name)."""
        for p in self.plots:
            for ln in p.lines:
                if label in (ln.label, ln.series.name):
                    return p, ln
        return None

    def lane_of(self, label: str) -> Lane | None:
        for lane in self.lanes:
            if label in (lane.label, lane.series.name, lane.address):
                return lane
        return None


def slug(text: str) -> str:
    """An entity-path-safe name (``%`` becomes ``percent``)."""
    text = text.replace("%", "percent")
    return re.sub(r"[^A-Za-z0-9_-]+", "_", text).strip("_") or "x"


def _resolve(trace: Any, name: str) -> str | None:
    try:
        return trace.resolve(name) if name in trace else None
    except Exception:  # noqa: BLE001 - a name the trace does not know
        return None


def _is_bool(trace: Any, col: str) -> bool:
    return trace.kind(col) == "bool"


def _io_rows(trace: Any, info: RunInfo) -> list[tuple[str, str, str]]:
    """(label, column, direction) of every program input/output, in the lab's order."""
    rows: list[tuple[str, str, str]] = []
    if info.io:
        for name, address, _type in info.io:
            col = _resolve(trace, address) or _resolve(trace, name)
            if col is None:
                continue
            a = address.upper()
            direction = "in" if a.startswith("%I") else "out" if a.startswith("%Q") else "var"
            rows.append((name, col, direction))
        return rows
    for r in trace.io:
        col = r.get("column")
        if col in trace.columns:
            rows.append((r.get("plant_column") or col, col,
                         "in" if r.get("direction") == "in" else "out"))
    return rows


def plan(trace: Any, info: RunInfo | None = None, names: list[str] | None = None,
         t0: float | None = None, t1: float | None = None,
         limits: dict[str, list[tuple[str, float]]] | None = None) -> Layout:
    """The default view of a run: plots per unit, lanes in the lab's order, watched variables.

    ``names`` restricts the view to these signals (in this order); ``limits`` maps a signal to
    (label, value) pairs drawn as dashed lines."""
    info = info or RunInfo()
    units = trace.meta.get("units", {}) or {}
    focus_order = [c for c in (_resolve(trace, n) for n in info.focus) if c]
    focus = set(focus_order)
    keep = focus | {c for c in (_resolve(trace, n) for n in info.keep) if c}
    wanted = None
    if names is not None:
        wanted = [c for c in (_resolve(trace, n) for n in names) if c]
        wire = {r.get("plant_column"): r.get("column") for r in trace.io
                if r.get("column") in trace.columns and r.get("plant_column") in trace.columns
                and _is_bool(trace, r["plant_column"])}  # a value is not its ADC counts
        wanted += [wire[c] for c in wanted if c in wire and wire[c] not in wanted]

    def win(s: Series) -> Series:
        return s.window(t0, t1) if (t0 is not None or t1 is not None) else s

    def series(col: str, kind: str, unit: str = "") -> Series:
        return win(Series(col, trace.time, trace.columns[col], kind, unit))

    io = _io_rows(trace, info)
    io_cols = {c for _, c, _ in io}
    lanes: list[Lane] = []
    analog: list[tuple[str, str, str, bool]] = []  # (label, column, unit, step)
    for label, col, direction in io:
        if wanted is not None and col not in wanted:
            continue
        if _is_bool(trace, col):
            lanes.append(Lane(label, series(col, "bool"), direction, col))
        elif col.upper().startswith(("%I", "%Q")):
            if col in focus or wanted is not None:  # raw ADC counts: only when asked for
                analog.append((label, col, "counts", False))
        else:
            analog.append((label, col, "", True))
    for w in info.watch:
        col = _resolve(trace, w)
        if col is None or col in io_cols or (wanted is not None and col not in wanted):
            continue
        if _is_bool(trace, col):
            lanes.append(Lane(w, series(col, "bool"), "var", col))
        else:
            analog.append((w, col, "watched", trace.kind(col) != "float"))
    from .sfc_lane import step_columns  # a lane per SFC step (ADR 0023)

    for label, col in step_columns(trace):  # always: a chart's steps are the story of its run
        if not any(ln.series.name == col for ln in lanes):
            lanes.append(Lane(label, series(col, "bool"), "var", col))
    labels = {a[0] for a in analog}
    for sig in trace.signals:
        col = _resolve(trace, sig)
        if col is None or _is_bool(trace, col) or col in io_cols:
            continue
        if wanted is not None and col not in wanted:
            continue
        unit = units.get(col, "")
        if wanted is None and unit in HIDDEN_UNITS and col not in focus:
            continue
        if wanted is None and col not in keep and _constant(trace.columns[col]):
            continue  # a flat line tells nothing
        if sig in labels:  # an I/O row already has this name: the plant side in its unit wins
            analog = [a for a in analog if a[0] != sig]
        analog.append((sig, col, unit, False))
    if wanted is not None:  # explicit names keep their order and may add plant booleans
        wired = {r.get("plant_column") for r in trace.io if r.get("column") in io_cols}
        for col in wanted:
            if col in wired:  # its wire's PLC side is a lane already
                continue
            if _is_bool(trace, col) and not any(ln.series.name == col for ln in lanes):
                lanes.append(Lane(col, series(col, "bool"), "var", col))
        order: dict[str, int] = {}
        for k, c in enumerate(wanted):
            order.setdefault(c, k)
            w = wire.get(c)
            if w is not None:
                order.setdefault(w, k)
        lanes.sort(key=lambda ln: order.get(ln.series.name, len(order)))
        analog.sort(key=lambda a: order.get(a[1], len(order)))
    plots = _group(analog, focus_order, series, limits or {}, wanted is None)
    edges = edge_plot(lanes)
    if edges is not None:
        if wanted is None:  # within the cap on plots: the edges take the last place
            plots = plots[:MAX_PLOTS - 1]
        plots.append(edges)
    return Layout(plots, lanes, info)


FAST_CHANGES = 40
"""A lane that changes more often than this in the view is also drawn as a square wave in
the ``edges`` plot: a state lane merges states narrower than a pixel into one grey bar
("363 states"), a line shows every edge."""


def edge_plot(lanes: list[Lane]) -> Plot | None:
    """The fast-switching lanes as square waves stacked in one plot (each on its own
    level, named by the student's variable and address, in its lane's colour)."""
    fast = [ln for ln in lanes if _changes(ln.series) > FAST_CHANGES]
    if not fast:
        return None
    p = Plot("edges", "every edge")
    for k, ln in enumerate(reversed(fast)):  # the first lane on top
        base = 1.5 * k
        vals = [base + (1.0 if v else 0.0) for v in ln.series.values]
        name = f"{ln.label} {ln.address}".strip() if ln.address.startswith("%") and \
            ln.address != ln.label else ln.label
        s = Series(ln.series.name, ln.series.times, vals, "real", "")
        p.lines.append(Line(f"{name} ({_changes(ln.series)} switchings)", s, ln.color,
                            step=True))
    p.lines.reverse()
    p.y_range = (-0.25, 1.5 * len(fast) - 0.25)
    return p


def _changes(s: Series) -> int:
    v = list(s.values)
    return sum(1 for a, b in zip(v, v[1:], strict=False) if bool(a) != bool(b))


def varying(trace: Any) -> set[str]:
    """The analog plant signals that change during the run."""
    return {s for s in trace.signals if s in trace.columns and not _is_bool(trace, s)
            and not _constant(trace.columns[s])}


def _constant(values: Any) -> bool:
    if not len(values):
        return True
    first = values[0]
    return all(v == first for v in values) if not hasattr(values, "min") else \
        bool(values.min() == values.max())


def _group(analog, focus: list[str], series, limits, cap: bool) -> list[Plot]:
    """Plots per unit; a watched variable joins the plot whose values it shares most (a
    setpoint beside its temperature), else its own; the lab's signals first, in its order."""
    plots: dict[str, Plot] = {}

    def add(key: str, unit: str, label: str, s: Series, step: bool) -> None:
        p = plots.setdefault(key, Plot(key, unit))
        p.lines.append(Line(label, s, LINE_COLORS[len(p.lines) % len(LINE_COLORS)], step))
        for k, (lname, value) in enumerate(limits.get(s.name, [])):
            p.limits.append(Limit(lname, float(value), LIMIT_COLORS[k % len(LIMIT_COLORS)]))

    watched = []
    for label, col, unit, step in analog:
        s = series(col, "int" if step else "real", unit)
        if unit == "watched":
            watched.append((label, s, step))
        else:
            add(slug(unit or "value"), unit, label, s, step)
    for label, s, step in watched:
        best, score = None, 0.05
        for p in plots.values():
            o = _overlap(_span(s), span_of(p))
            if o > score:
                best, score = p, o
        if best is not None:
            add(best.key, best.unit, label, s, step)
        else:
            add("watched", "watched", label, s, step)
    rank = {c: k for k, c in enumerate(focus)}
    ordered = sorted(plots.values(), key=lambda p: min(
        [rank.get(ln.series.name, len(rank)) for ln in p.lines]))
    if cap:
        ordered = ordered[:MAX_PLOTS]
    for p in ordered:
        if p.limits:
            lo = min([0.0] + [lim.value for lim in p.limits] + [span_of(p)[0]])
            hi = max([lim.value for lim in p.limits] + [span_of(p)[1]])
            p.y_range = (lo, hi + 0.08 * (hi - lo) if hi > lo else hi + 1.0)
    return ordered


def _span(s: Series) -> tuple[float, float]:
    vals = [float(v) for v in s.values if v == v]
    return (min(vals), max(vals)) if vals else (0.0, 0.0)


def span_of(p: Plot) -> tuple[float, float]:
    spans = [_span(ln.series) for ln in p.lines]
    return min(a for a, _ in spans), max(b for _, b in spans)


def _overlap(a: tuple[float, float], b: tuple[float, float]) -> float:
    """Shared length over joint length of two value ranges (1 = the same range)."""
    inter = min(a[1], b[1]) - max(a[0], b[0])
    union = max(a[1], b[1]) - min(a[0], b[0])
    if union <= 0:
        return 1.0 if inter >= 0 else 0.0
    return max(inter, 0.0) / union


def run_info(lab: Any = None, result: Any = None, scenario: str = "",
             student_file: str = "", limits: Any = None) -> RunInfo:
    """A :class:`RunInfo` from a :class:`~plclab.grade.lab.Lab` and a grading result
    (duck-typed, so this module does not import the grader); ``limits`` maps a criterion's
    name to what it checks (``plclab.grade.criteria.criterion_limits``), drawn on its
    signals."""
    info = RunInfo(scenario=scenario, student_file=student_file)
    if lab is not None:
        info.lab = lab.id
        info.io = [(r.name, r.address, r.type) for r in lab.io]
        spec = None
        try:
            spec = lab.scenario(scenario) if scenario else None
        except Exception:  # noqa: BLE001 - unknown scenario: lab-wide watch only
            spec = None
        info.watch = [w for w in lab.all_watch(spec) if not w.startswith("%")] \
            if hasattr(lab, "all_watch") else list(getattr(lab, "watch", []))
        focus = list(lab.diagram_signals)
        crits = {c.name: c for c in lab.criteria}
        for c in crits.values():
            focus += [s for s in c.relevant_signals() if s not in focus]
        info.focus = focus
    if result is not None:
        tests = [t for t in result.tests if not scenario or t.scenario == scenario]
        info.score = sum(t.score for t in tests)
        info.max_score = sum(t.max_score for t in tests)
        crits = {c.name: c for c in lab.criteria} if lab is not None else {}
        for t in tests:
            sigs = crits[t.criterion].relevant_signals() if t.criterion in crits else []
            info.verdicts.append(Verdict(t.criterion, bool(t.passed), t.t_fail,
                                         t.detail or t.message, list(sigs),
                                         list((limits or {}).get(t.criterion, ()))))
    return info


def signal_labels(io: Any, trace: Any) -> dict[str, str]:
    """Each trace column of a program input or output named as a logic analyser names it:
    the student's variable and its address (``PUMP %QX0.0``), for the PLC side (``%QX0.0``)
    and the plant side of the wiring (``PUMP``, ``LS1``) alike. ``io`` is the lab's I/O
    table (rows with ``name`` and ``address``, or (name, address, type) tuples); None: the
    wiring's signal names. The names the student's program declares at the addresses
    (``trace.meta["located"]``, recorded by the simulation) come first."""
    names: dict[str, str] = {}
    for r in io or ():
        name, address = (r[0], r[1]) if isinstance(r, tuple) else (r.name, r.address)
        if address:
            names[str(address).upper()] = f"{name} {address}"
    meta = getattr(trace, "meta", None) or {}
    for address, var in (meta.get("located") or {}).items():  # the student's own names
        names[str(address).upper()] = f"{var} {address}"
    if io is None:  # no I/O table: the wiring's signal names
        for r in getattr(trace, "io", None) or ():
            col, sig = str(r.get("column") or ""), r.get("signal")
            if sig and col.startswith("%"):
                names.setdefault(col.upper(), f"{sig} {col}")
    out: dict[str, str] = {}
    for col in trace.columns if hasattr(trace, "columns") else ():
        if col.upper() in names:
            out[col] = names[col.upper()]
    for r in getattr(trace, "io", None) or ():
        col, plant = str(r.get("column") or ""), r.get("plant_column")
        if plant and col.upper() in names and plant in trace.columns and \
                trace.kind(plant) == "bool":  # an analog plant value is not the ADC's counts
            out.setdefault(plant, names[col.upper()])
    return out

