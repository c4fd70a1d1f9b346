"""The student's failure diagram drawn cheaply: every signal in ONE matplotlib Axes.

:func:`plclab.viz.timing.timing_diagram` stacks one Axes per signal. Building an Axes and its
tick objects is most of a small figure's cost, and the grader draws a diagram for every failed
criterion of every failing submission, so ``timing_diagram(..., fixed_layout=True)`` (the
feedback's call) uses :func:`failure_figure` instead: the rows are bands of one Axes, the
names are text beside them, an analog row shows its range as two small numbers, and only the
time axis has ticks. The picture reads the same: square waves for BOOLs, labelled bus
segments for small integers, lines for analog values, thresholds dotted with their value,
failure markers dashed across all rows with labels that never overlap.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

from .series import Series

SPAN_RGB = (0.93, 0.95, 0.98)
"""Background of the time window a criterion checks."""
BAND_RGB = (1.0, 0.93, 0.85)
"""Fill of a value band a criterion checks (orange, light)."""
PAD = 0.15
"""Empty fraction of a row's band above and below its drawing."""


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


INPUT_RGB = (31, 119, 180)
OUTPUT_RGB = (44, 160, 44)
"""A program input is blue, an output green, in every picture (as in the rerun lanes,
:data:`plclab.viz.layout.LANE_COLORS`)."""


def bool_rgb(name: str) -> tuple[int, int, int]:
    """The colour of a BOOL row by the address in its name (``START %IX0.0`` blue);
    outputs and rows without an address green."""
    import re

    return INPUT_RGB if re.search(r"(^|\s)%I", name) else OUTPUT_RGB


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


class Frame(NamedTuple):
    """Where the one Axes of a failure diagram sits, in inches and figure fractions; shared
    by the matplotlib figure and the Pillow PNG (:mod:`plclab.viz.failure_png`)."""

    h_in: float   # the figure's height (inches)
    left: float   # the Axes' left edge (fraction of the width), room for the row names
    right_in: float  # room right of the Axes (inches), for threshold values
    frac: float   # the Axes' height (fraction of the figure's height); its bottom is 0.45 in


def frame(series: Sequence[Series], heights: Sequence[float], width: float, title: str,
          thresholds: Mapping[str, Sequence[tuple[float, str]]] | None,
          labels: Sequence[tuple[float, str, int]], note: str = "",
          bands: Mapping[str, Sequence[tuple[float, float, str]]] | None = None) -> Frame:
    """The geometry of a failure diagram: arguments as :func:`failure_figure`."""
    h_in = 0.5 + sum(heights)
    label_chars = max((len(s.name) + (len(s.unit) + 3 if s.unit else 0) for s in series),
                      default=4)
    levels = max((lv for _, _, lv in labels), default=-1) + 1
    top_in = 0.3 + (0.2 if title else 0) + (0.18 if note else 0) + 0.16 * levels
    texts = [f"{lab} {v:g}" for lim in (thresholds or {}).values() for v, lab in lim]
    texts += [lab for bs in (bands or {}).values() for _, _, lab in bs]
    right_in = min(1.8, 0.25 + 0.062 * max(map(len, texts))) if texts else 0.25
    left = min(0.45, (0.15 + 0.065 * label_chars + 0.3) / width)
    return Frame(h_in, left, right_in, max(0.2, 1 - (top_in + 0.45) / h_in))


def failure_figure(series: Sequence[Series], lo: float, hi: float, heights: Sequence[float],
                   title: str = "", markers: Sequence[tuple[float, str]] = (),
                   width: float = 9.0,
                   thresholds: Mapping[str, Sequence[tuple[float, str]]] | None = None,
                   labels: Sequence[tuple[float, str, int]] = (),
                   bands: Mapping[str, Sequence[tuple[float, float, str]]] | None = None,
                   spans: Sequence[tuple[float | None, float | None, str]] = (),
                   note: str = "") -> Any:
    """A figure (outside pyplot's registry) of ``series`` (already windowed to [lo, hi]),
    one band of height ``heights[i]`` (inches) per row, top to bottom. ``labels`` are the
    markers' labels placed by :func:`plclab.viz.timing.marker_labels` (time, text, row).
    ``bands`` maps a row to (lo, hi, label) value bands drawn shaded, ``spans`` are the time
    windows a criterion looks at (shaded across all rows), ``note`` a line under the title
    (what the criterion checks that is not a line: counts, times)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    h_in, left, right_in, frac = frame(series, heights, width, title, thresholds, labels,
                                       note, bands)
    fig = Figure(figsize=(width, h_in))
    FigureCanvasAgg(fig)
    ax = fig.add_axes((left, 0.45 / h_in, 1 - right_in / width - left, frac))
    ax.xaxis.set_major_locator(MaxNLocator(nbins=8))
    ax.set_yticks([])
    for side in ("top", "right", "left"):
        ax.spines[side].set_visible(False)
    ax.tick_params(labelsize=7)
    total = float(sum(heights))
    yaxis = ax.get_yaxis_transform()  # x in axes fraction, y in data
    for a, b, _text in spans:
        a, b = max(lo, a if a is not None else lo), min(hi, b if b is not None else hi)
        if b > a:
            ax.axvspan(a, b, color=SPAN_RGB, lw=0, zorder=0)
    top = total
    for s, h in zip(series, heights, strict=True):
        base = top - h
        y0, y1 = base + PAD * h, top - PAD * h
        limits = list((thresholds or {}).get(s.name, ()))
        ax.text(-0.01, (y0 + y1) / 2, s.name + (f" [{s.unit}]" if s.unit else ""),
                transform=yaxis, ha="right", va="center", fontsize=8)
        _row(ax, s, lo, hi, y0, y1, limits, yaxis, list((bands or {}).get(s.name, ())))
        ax.axhline(base, color="0.85", lw=0.6)
        top = base
    for t, _label in markers:
        if lo <= t <= hi:
            ax.axvline(t, color="tab:red", lw=0.8, ls="--")
    for t, label, level in labels:
        ax.annotate(label, (t, 1.02 + 0.17 * level / (frac * h_in)),  # 0.17 in a row
                    xycoords=("data", "axes fraction"), fontsize=7, color="tab:red",
                    annotation_clip=False)
    ax.set_xlim(lo, hi)
    ax.set_ylim(0, total)
    ax.set_xlabel("time [s]", fontsize=8)
    if title:
        fig.suptitle(title, fontsize=10)
    if note:
        fig.text(0.5, 1 - (0.32 if title else 0.12) / h_in, note, fontsize=8,
                 color="tab:orange", ha="center", va="top")
    return fig


def _row(ax: Any, s: Series, lo: float, hi: float, y0: float, y1: float,
         limits: list[tuple[float, str]], yaxis: Any,
         bands: list[tuple[float, float, str]] | None = None) -> None:
    """One signal drawn between heights y0 and y1 of the shared Axes."""
    times = list(s.times)
    if s.kind == "bool":
        ys = [y1 if v else y0 for v in s.values]
        if times:
            times, ys = times + [hi], ys + ys[-1:]
            rgb = tuple(c / 255 for c in bool_rgb(s.name))
            ax.step(times, ys, where="post", color=rgb, lw=1.2)
            ax.fill_between(times, ys, y0, step="post", alpha=0.15, color=rgb,
                            lw=0)
    elif s.kind == "real":
        vlo, vhi = band_scale(s, limits, bands or ())
        k = (y1 - y0) / (vhi - vlo)
        for a, b, label in bands or ():
            ax.fill_between([lo, hi], y0 + (a - vlo) * k, y0 + (b - vlo) * k,
                            color=BAND_RGB, lw=0)
            for v in (a, b):
                ax.axhline(y0 + (v - vlo) * k, color="tab:orange", lw=0.9, ls="--")
            ax.text(1.005, y0 + ((a + b) / 2 - vlo) * k, label, transform=yaxis, fontsize=7,
                    color="tab:orange", va="center")
        ax.plot(times, [y0 + (float(v) - vlo) * k for v in s.values], color="tab:blue",
                lw=1.0)
        for edge, y in ((vlo, y0), (vhi, y1)):
            ax.text(-0.003, y, f"{edge:.4g}", transform=yaxis, ha="right", va="center",
                    fontsize=6, color="0.4")
        gap = 0.13  # a 7-point label in the rows' inches
        at = spread([y0 + (value - vlo) * k for value, _ in limits], gap)
        for (value, label), ty in zip(limits, at, strict=True):
            y = y0 + (value - vlo) * k
            ax.axhline(y, color="tab:orange", lw=0.9, ls=":")
            ax.text(1.005, ty, f"{label} {value:g}", transform=yaxis, fontsize=7,
                    color="tab:orange", va="center")
    else:
        ch = s.changes()
        mid, d_y = (y0 + y1) / 2, (y1 - y0) / 2
        xs: list[float] = []
        ys: list[float] = []
        for k, (t, v) in enumerate(ch):
            t_end = ch[k + 1][0] if k + 1 < len(ch) else hi
            d = min((t_end - t) * 0.08, (hi - lo) * 0.004)
            xs += [t, t + d, t_end - d, t_end, t_end - d, t + d, t, float("nan")]
            ys += [mid, mid + d_y, mid + d_y, mid, mid - d_y, mid - d_y, mid, float("nan")]
            if t_end - t > (hi - lo) * 0.02:
                ax.text((t + t_end) / 2, mid, s.label(v), ha="center", va="center",
                        fontsize=7)
        ax.plot(xs, ys, color="tab:purple", lw=1.0)


class Drawing(NamedTuple):
    """What a criterion checks, as a diagram draws it (:func:`criterion_drawing`)."""

    thresholds: dict[str, list[tuple[float, str]]]  # row -> (value, label): dashed lines
    bands: dict[str, list[tuple[float, float, str]]]  # row -> (lo, hi, label): shaded
    spans: list[tuple[float | None, float | None, str]]  # the windows checked
    note: str  # the rest in words: counts, times, rates, limits of rows not drawn


def criterion_drawing(limits: Sequence[Any], row_of: Any, units: Mapping[str, str] | None = None,
                      analog: Any = None) -> Drawing:
    """Turn a criterion's limits (:func:`plclab.grade.criteria.limits_of`) into lines, bands,
    spans and a note. ``row_of(signal)`` names the row a signal is drawn in (None: not drawn);
    ``analog(row)`` says whether that row is drawn as a value (lines and bands go there) --
    a limit on a row that is not drawn, or on a BOOL, goes into the note."""
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
        elif lim.kind in ("level", "target") and drawable and lim.value is not None:
            lst = th.setdefault(row, [])
            num = f"{lim.value:g}"
            text = lim.label[:-len(num)].rstrip() if lim.label.endswith(num) else lim.label
            if all(v != lim.value for v, _ in lst):
                lst.append((float(lim.value), text or lim.kind))
        else:
            who = f"{lim.signal} " if lim.signal and lim.kind not in ("time",) else ""
            words.append(f"{who}{lim.text(unit)}")
    note = ("checks: " + "; ".join(dict.fromkeys(words))) if words else ""
    return Drawing(th, bands, spans, note)
