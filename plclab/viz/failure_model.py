"""One description of a failure diagram, drawn by one renderer per output format (ADR 0069).

:func:`describe` decides *what* a failure picture holds: its title and caption (the
criterion's own words), the rows (named by the student's variable and its address,
``PUMP %QX0.0``, inputs and outputs told apart), each analog row's value range, limit lines
and bands with their labels, the time windows a criterion checks, the failure lines and their
labels placed so that they never overlap, the note of what is checked that is not a line
(counts, times), a line saying which rows were left out when there are too many, and the
fixed texts (the time axis) in the reader's language. :mod:`plclab.viz.failure_png` (Pillow,
the feedback's PNGs) and :mod:`plclab.viz.failure_diagram` (matplotlib, SVG) only draw a
:class:`FailureDiagram`; :meth:`FailureDiagram.items` lists every text a renderer must show,
so a test can hold both renderers to the same content.

>>> from plclab.viz.series import Series
>>> d = describe([Series("PUMP %QX0.0", [0.0, 2.0], [False, True], "bool"),
...               Series("LEVEL", [0.0, 4.0], [0.5, 1.9], "real", "m")], 0.0, 4.0,
...              title="normal: no overflow (FAILED)", markers=[(3.0, "no overflow fails")],
...              thresholds={"LEVEL": [(1.75, "never >=")]})
>>> [r.caption for r in d.rows], d.rows[1].limit_texts()
(['PUMP %QX0.0', 'LEVEL [m]'], ['never >= 1.75'])
>>> [text for kind, text in d.items() if kind in ("marker", "axis")]
['no overflow fails', 'time [s]']
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from .series import Series

SPAN_RGB = (0.93, 0.95, 0.98)
"""Background of the time window a criterion checks."""
BAND_RGB = (1.0, 0.93, 0.85)
"""Fill of a value band a criterion checks (orange, light)."""
PAD = 0.15
"""Empty fraction of a row's band above and below its drawing."""
INPUT_RGB = (31, 119, 180)
OUTPUT_RGB = (44, 160, 44)
"""A program input is blue, an output green, in every picture (as in the rerun lanes,
:data:`plclab.viz.layout.LANE_COLORS`)."""
MAX_ROWS = 14
"""Rows a failure diagram draws at most; the rest are named on the picture (never silently
dropped), and the rows of the failed criterion are always among those drawn."""
ANALOG_VALUES = 12
"""An integer series with more distinct values than this is analog (ADC counts): a line."""


def bool_rgb(name: str) -> tuple[int, int, int]:
    """The colour of a BOOL row by the address in its name (``START %IX0.0`` blue);
    outputs and rows without an address green."""
    return INPUT_RGB if re.search(r"(^|\s)%I", name) else OUTPUT_RGB


def band_scale(s: Series, limits: Sequence[tuple[float, str]],
               bands: Sequence[tuple[float, float, str]] = ()) -> tuple[float, float]:
    """The value range an analog row shows: its values, its thresholds and its bands."""
    vals = [float(v) for v in s.values if v == v] + [float(v) for v, _ in limits]
    vals += [float(x) for a, b, _ in bands for x in (a, b)]
    if not vals:
        return 0.0, 1.0
    lo, hi = min(vals), max(vals)
    if hi - lo < 1e-12:
        lo, hi = lo - 0.5, hi + 0.5
    return lo, hi


def spread(ys: Sequence[float], gap: float) -> list[float]:
    """Label heights moved apart so that no two are closer than ``gap`` (the order kept,
    each group centred on where its labels belong): labels of close lines never overlap."""
    groups: list[list[int]] = []  # runs of labels that touch, bottom to top

    def bounds(g: list[int]) -> tuple[float, float]:
        centre = sum(ys[j] for j in g) / len(g)
        half = gap * (len(g) - 1) / 2
        return centre - half, centre + half

    for i in sorted(range(len(ys)), key=lambda i: ys[i]):
        groups.append([i])
        while len(groups) > 1 and bounds(groups[-1])[0] - bounds(groups[-2])[1] < gap - 1e-12:
            groups[-2:] = [groups[-2] + groups[-1]]
    out = [float(y) for y in ys]
    for g in groups:
        low = bounds(g)[0]
        for k, j in enumerate(sorted(g, key=lambda j: ys[j])):
            out[j] = low + gap * k
    return out


def as_analog(s: Series) -> Series:
    """Integers with many values as a line; a digital series reduced to its changes (the
    same picture, a fraction of the points to draw)."""
    if s.kind == "int" and len(set(s.values)) > ANALOG_VALUES:
        return Series(s.name, s.times, s.values, "real", s.unit, s.labels)
    if s.kind != "real" and len(s.times) > 2:
        ch = s.changes()
        return Series(s.name, [t for t, _ in ch], [v for _, v in ch], s.kind, s.unit,
                      s.labels)
    return s


def rows_of(series: Sequence[Series], t0: float | None, t1: float | None
            ) -> tuple[list[Series], list[float], float, float]:
    """The rows of a diagram (windowed, many-valued integers as lines), their heights in
    inches and the time span shown."""
    rows = [as_analog(s.window(t0, t1)) for s in series]
    heights = [0.6 if s.kind in ("bool",) else 0.7 if s.kind != "real" else 1.6 for s in rows]
    lo = t0 if t0 is not None else min((s.times[0] for s in rows if len(s.times)), default=0)
    hi = t1 if t1 is not None else max((s.times[-1] for s in rows if len(s.times)), default=1)
    return rows, heights, lo, hi


def marker_labels(markers: Sequence[tuple[float, str]], lo: float, hi: float,
                  chars_per_span: float = 110.0) -> list[tuple[float, str, int]]:
    """The labels of ``markers`` in [lo, hi] as (time, text, row): equal labels close together
    are merged ("chatter x3"), and a label that would overlap the one before it on the same
    row goes one row up. A label takes about ``len(text) / chars_per_span`` of the width."""
    span = max(hi - lo, 1e-9)
    inside = sorted((t, lab) for t, lab in markers if lo <= t <= hi)
    merged: list[list] = []  # [time, label, count]
    for t, lab in inside:
        same = next((m for m in reversed(merged) if m[1] == lab), None)
        if same is not None and t - same[0] < 0.05 * span:
            same[2] += 1
            continue
        merged.append([t, lab, 1])
    out: list[tuple[float, str, int]] = []
    row_end: list[float] = []  # per row: where its last label ends
    for t, lab, n in merged:
        text = lab if n == 1 else f"{lab} x{n}"
        width = (len(text) + 1) / chars_per_span * span
        row = next((r for r, end in enumerate(row_end) if t >= end), len(row_end))
        if row == len(row_end):
            row_end.append(0.0)
        row_end[row] = t + width
        out.append((t, text, row))
    return out


# ---------------------------------------------------------------------------- the description


@dataclass
class Row:
    """One lane (a BOOL, a bus of values) or plot (an analog value) of a failure diagram."""

    series: Series  # windowed; its name is what the row is called (``PUMP %QX0.0``)
    height: float  # inches
    limits: list[tuple[float, str]] = field(default_factory=list)  # (value, label): lines
    bands: list[tuple[float, float, str]] = field(default_factory=list)  # (lo, hi, label)

    @property
    def name(self) -> str:
        return self.series.name

    @property
    def kind(self) -> str:
        return self.series.kind

    @property
    def caption(self) -> str:
        """The row's name as drawn beside it, with its unit: ``TEMP [degC]``."""
        s = self.series
        return s.name + (f" [{s.unit}]" if s.unit else "")

    @property
    def value_range(self) -> tuple[float, float]:
        """The value range an analog row shows (its values, limits and bands)."""
        return band_scale(self.series, self.limits, self.bands)

    def limit_texts(self) -> list[str]:
        """The labels of the limit lines as drawn: ``never >= 1.75``."""
        return [f"{label} {value:g}" for value, label in self.limits]

    def range_texts(self) -> list[str]:
        """The lowest and highest value shown, as drawn beside the row: ``32767``, not
        ``3.277e+04``."""
        return [f"{v:.0f}" if 1e4 <= abs(v) < 1e12 else f"{v:.4g}" for v in self.value_range]


class Frame(NamedTuple):
    """Where the one plot area of a failure diagram sits, in inches and figure fractions;
    shared by both renderers."""

    h_in: float   # the figure's height (inches)
    left: float   # the plot's left edge (fraction of the width), room for the row names
    right_in: float  # room right of the plot (inches), for threshold values
    frac: float   # the plot's height (fraction of the figure's height); its bottom is 0.45 in


@dataclass
class FailureDiagram:
    """Everything a failure diagram shows, decided once (:func:`describe`)."""

    rows: list[Row]
    lo: float
    hi: float
    title: str = ""
    caption: str = ""  # the criterion's own words under the title (what failed)
    note: str = ""  # what is checked that is not a line: counts, times
    left_out: str = ""  # the rows not drawn, named (never a silent cap)
    markers: list[float] = field(default_factory=list)  # times of the failure lines
    labels: list[tuple[float, str, int]] = field(default_factory=list)  # (t, text, level)
    spans: list[tuple[float | None, float | None, str]] = field(default_factory=list)
    xlabel: str = "time [s]"
    width: float = 9.0  # inches

    def texts_under_title(self) -> list[tuple[str, str]]:
        """The caption, the note and the rows left out, as (kind, whole text)."""
        return [(k, t) for k, t in (("caption", self.caption), ("note", self.note),
                                    ("left_out", self.left_out)) if t]

    def header(self) -> list[tuple[str, str]]:
        """The lines under the title, top to bottom, as (kind, text): each text wrapped to
        the picture's width (an 8-point line holds about 13 characters an inch)."""
        import textwrap

        chars = max(20, int(self.width * 13))
        return [(k, line) for k, t in self.texts_under_title()
                for line in textwrap.wrap(t, chars, break_on_hyphens=False) or [t]]

    def items(self) -> list[tuple[str, str]]:
        """Every text the picture shows, as (kind, text): what both renderers must draw."""
        out: list[tuple[str, str]] = [("title", self.title)] if self.title else []
        out += self.header()
        for r in self.rows:
            out.append(("row", r.caption))
            if r.kind == "real":
                out += [("range", t) for t in r.range_texts()]
                out += [("limit", t) for t in r.limit_texts()]
                out += [("band", label) for _, _, label in r.bands]
        out += [("marker", text) for _, text, _ in self.labels]
        out.append(("axis", self.xlabel))
        return out

    def frame(self) -> Frame:
        """The geometry both renderers use (inches and fractions)."""
        h_in = 0.5 + sum(r.height for r in self.rows)
        label_chars = max((len(r.caption) for r in self.rows), default=4)
        levels = max((lv for _, _, lv in self.labels), default=-1) + 1
        top_in = 0.3 + (0.2 if self.title else 0) + 0.18 * len(self.header()) + 0.16 * levels
        texts = [t for r in self.rows if r.kind == "real" for t in r.limit_texts()]
        texts += [lab for r in self.rows if r.kind == "real" for _, _, lab in r.bands]
        right_in = min(1.8, 0.25 + 0.062 * max(map(len, texts))) if texts else 0.25
        left = min(0.45, (0.15 + 0.065 * label_chars + 0.3) / self.width)
        h_in += 0.18 * len(self.header())
        return Frame(h_in, left, right_in, max(0.2, 1 - (top_in + 0.45) / h_in))

    TITLE_Y = 0.08
    """Inches from the top to the top of the title (fixed: a tall picture keeps its title clear
    of the lines under it)."""

    def header_y(self, k: int) -> float:
        """Inches from the top to the top of header line ``k``."""
        return (0.32 if self.title else 0.12) + 0.18 * k


def describe(series: Sequence[Series], t0: float | None = None, t1: float | None = None,
             title: str = "", markers: Sequence[tuple[float, str]] = (), width: float = 9.0,
             thresholds: Mapping[str, Sequence[tuple[float, str]]] | None = None,
             bands: Mapping[str, Sequence[tuple[float, float, str]]] | None = None,
             spans: Sequence[tuple[float | None, float | None, str]] = (),
             note: str = "", caption: str = "", keep: Sequence[str] = (),
             max_rows: int | None = MAX_ROWS) -> FailureDiagram:
    """The description of a failure diagram of ``series`` over [t0, t1] (None: the data's
    span). ``markers`` are (time, label) failure lines, ``thresholds`` maps a row name to
    (value, label) lines, ``bands`` to (lo, hi, label) shaded bands, ``spans`` the time
    windows checked, ``note`` and ``caption`` lines under the title. With more than
    ``max_rows`` rows the rows named in ``keep`` (the failed criterion's) stay, then the
    first others; a line names the rest (None: every row)."""
    from plclab.i18n import tr

    series = list(series)
    left_out = ""
    if max_rows is not None and len(series) > max_rows:
        must = [i for i, s in enumerate(series) if s.name in set(keep)][:max_rows]
        chosen = set(must) | set([i for i in range(len(series)) if i not in must]
                                 [:max_rows - len(must)])
        dropped = [s.name for i, s in enumerate(series) if i not in chosen]
        series = [s for i, s in enumerate(series) if i in chosen]
        left_out = tr("{n} more signals not drawn: {names}", n=len(dropped),
                      names=", ".join(dropped))
    ss, heights, lo, hi = rows_of(series, t0, t1)
    rows = [Row(s, h, list((thresholds or {}).get(s.name, ())),
                list((bands or {}).get(s.name, ())) if s.kind == "real" else [])
            for s, h in zip(ss, heights, strict=True)]
    return FailureDiagram(rows, lo, hi, title, caption, note, left_out,
                          [t for t, _ in markers if lo <= t <= hi],
                          marker_labels(markers, lo, hi), list(spans), tr("time [s]"), width)


def missing(d: FailureDiagram, drawn: Sequence[str]) -> list[tuple[str, str]]:
    """The items of ``d`` (:meth:`FailureDiagram.items`) a renderer did not draw, given the
    texts it drew (each item as often as it occurs)."""
    left = list(drawn)
    out = []
    for kind, text in d.items():
        if text in left:
            left.remove(text)
        else:
            out.append((kind, text))
    return out


# ---------------------------------------------------------------------------- criteria


class Drawing(NamedTuple):
    """What a criterion checks, as a diagram draws it (:func:`criterion_drawing`)."""

    thresholds: dict[str, list[tuple[float, str]]]  # row -> (value, label): dashed lines
    bands: dict[str, list[tuple[float, float, str]]]  # row -> (lo, hi, label): shaded
    spans: list[tuple[float | None, float | None, str]]  # the windows checked
    note: str  # the rest in words: counts, times, rates, limits of rows not drawn


def rename(text: str, names: Mapping[str, str]) -> str:
    """``text`` with each signal of ``names`` written as the rows name it (``%MW0 = 90`` ->
    ``GOOD %MW0 = 90``); a name inside a longer one (``X1`` in ``X10``) or already named
    (``GOOD %MW0``) stays.

    >>> rename("%MW0 = 90, plant counted 6; X1 <> X10", {"%MW0": "GOOD %MW0", "X1": "X1 %IX0.2"})
    'GOOD %MW0 = 90, plant counted 6; X1 %IX0.2 <> X10'
    """
    for old, new in sorted(names.items(), key=lambda kv: -len(kv[0])):
        if old == new or not old:
            continue
        pattern = re.compile(rf"(?<![\w%.]){re.escape(old)}(?![\w.])")
        text = new.join(pattern.sub(lambda _m, new=new: new, part) for part in text.split(new))
    return text


def criterion_drawing(limits: Sequence[Any], row_of: Any, units: Mapping[str, str] | None = None,
                      analog: Any = None) -> Drawing:
    """Turn a criterion's limits (:func:`plclab.grade.criteria.limits_of`) into lines, bands,
    spans and a note. ``row_of(signal)`` names the row a signal is drawn in (None: not drawn);
    ``analog(row)`` says whether that row is drawn as a value (lines and bands go there) --
    a limit on a row that is not drawn, or on a BOOL, goes into the note; the raw parameters
    of a lab's own check (``target = 50, band = 0.5``) do not."""
    from plclab.i18n import tr

    th: dict[str, list[tuple[float, str]]] = {}
    bands: dict[str, list[tuple[float, float, str]]] = {}
    spans: list[tuple[float | None, float | None, str]] = []
    words: list[str] = []
    for lim in limits:
        row = row_of(lim.signal) if lim.signal else None
        unit = (units or {}).get(row or "", "") if row else ""
        drawable = row is not None and (analog is None or analog(row))
        if lim.kind == "window" and (lim.t0 is not None or lim.t1 is not None):
            spans.append((lim.t0, lim.t1, lim.label))
            words.append(lim.label)
        elif lim.kind == "band" and drawable and lim.value is not None and lim.hi is not None:
            bands.setdefault(row, []).append((lim.value, lim.hi, lim.text(unit)))
        elif lim.kind == "count" and not lim.signal and lim.value is None:
            continue  # a lab's own check's parameters by their Python names: the caption
            # (the criterion's message) says what is checked, in the lab's words
        elif lim.kind in ("level", "target") and drawable and lim.value is not None:
            lst = th.setdefault(row, [])
            num = f"{lim.value:g}"
            text = lim.label[:-len(num)].rstrip() if lim.label.endswith(num) else lim.label
            if all(v != lim.value for v, _ in lst):
                lst.append((float(lim.value), text or lim.kind))
        else:
            who = f"{lim.signal} " if lim.signal and lim.kind not in ("time",) else ""
            words.append(f"{who}{lim.text(unit)}")
    note = tr("checks: {what}", what="; ".join(dict.fromkeys(words))) if words else ""
    return Drawing(th, bands, spans, note)
