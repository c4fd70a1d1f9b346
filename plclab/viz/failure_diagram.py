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

PAD = 0.15
"""Empty fraction of a row's band above and below its drawing."""


def band_scale(s: Series, limits: Sequence[tuple[float, str]]) -> tuple[float, float]:
    """The value range an analog row shows: its values and its thresholds."""
    vals = [float(v) for v in s.values] + [float(v) for v, _ in limits]
    if not vals:
        return 0.0, 1.0
    lo, hi = min(vals), max(vals)
    if hi - lo < 1e-12:
        lo, hi = lo - 0.5, hi + 0.5
    return lo, hi


class Frame(NamedTuple):
    """Where the one Axes of a failure diagram sits, in inches and figure fractions; shared
    by the matplotlib figure and the Pillow PNG (:mod:`plclab.viz.failure_png`)."""

    h_in: float   # the figure's height (inches)
    left: float   # the Axes' left edge (fraction of the width), room for the row names
    right_in: float  # room right of the Axes (inches), for threshold values
    frac: float   # the Axes' height (fraction of the figure's height); its bottom is 0.45 in


def frame(series: Sequence[Series], heights: Sequence[float], width: float, title: str,
          thresholds: Mapping[str, Sequence[tuple[float, str]]] | None,
          labels: Sequence[tuple[float, str, int]]) -> Frame:
    """The geometry of a failure diagram: arguments as :func:`failure_figure`."""
    h_in = 0.5 + sum(heights)
    label_chars = max((len(s.name) + (len(s.unit) + 3 if s.unit else 0) for s in series),
                      default=4)
    levels = max((lv for _, _, lv in labels), default=-1) + 1
    top_in = 0.3 + (0.2 if title else 0) + 0.16 * levels
    right_in = 0.75 if thresholds else 0.25
    left = min(0.45, (0.15 + 0.065 * label_chars + 0.3) / width)
    return Frame(h_in, left, right_in, max(0.2, 1 - (top_in + 0.45) / h_in))


def failure_figure(series: Sequence[Series], lo: float, hi: float, heights: Sequence[float],
                   title: str = "", markers: Sequence[tuple[float, str]] = (),
                   width: float = 9.0,
                   thresholds: Mapping[str, Sequence[tuple[float, str]]] | None = None,
                   labels: Sequence[tuple[float, str, int]] = ()) -> Any:
    """A figure (outside pyplot's registry) of ``series`` (already windowed to [lo, hi]),
    one band of height ``heights[i]`` (inches) per row, top to bottom. ``labels`` are the
    markers' labels placed by :func:`plclab.viz.timing.marker_labels` (time, text, row)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    h_in, left, right_in, frac = frame(series, heights, width, title, thresholds, labels)
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
    top = total
    for s, h in zip(series, heights, strict=True):
        base = top - h
        y0, y1 = base + PAD * h, top - PAD * h
        limits = list((thresholds or {}).get(s.name, ()))
        ax.text(-0.01, (y0 + y1) / 2, s.name + (f" [{s.unit}]" if s.unit else ""),
                transform=yaxis, ha="right", va="center", fontsize=8)
        _row(ax, s, lo, hi, y0, y1, limits, yaxis)
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
    return fig


def _row(ax: Any, s: Series, lo: float, hi: float, y0: float, y1: float,
         limits: list[tuple[float, str]], yaxis: Any) -> None:
    """One signal drawn between heights y0 and y1 of the shared Axes."""
    times = list(s.times)
    if s.kind == "bool":
        ys = [y1 if v else y0 for v in s.values]
        if times:
            times, ys = times + [hi], ys + ys[-1:]
            ax.step(times, ys, where="post", color="tab:green", lw=1.2)
            ax.fill_between(times, ys, y0, step="post", alpha=0.15, color="tab:green",
                            lw=0)
    elif s.kind == "real":
        vlo, vhi = band_scale(s, limits)
        k = (y1 - y0) / (vhi - vlo)
        ax.plot(times, [y0 + (float(v) - vlo) * k for v in s.values], color="tab:blue",
                lw=1.0)
        for edge, y in ((vlo, y0), (vhi, y1)):
            ax.text(-0.003, y, f"{edge:.4g}", transform=yaxis, ha="right", va="center",
                    fontsize=6, color="0.4")
        for value, label in limits:
            y = y0 + (value - vlo) * k
            ax.axhline(y, color="tab:orange", lw=0.9, ls=":")
            ax.text(1.005, y, f"{label} {value:g}", transform=yaxis, fontsize=7,
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
