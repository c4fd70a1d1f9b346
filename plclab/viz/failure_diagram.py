"""The failure diagram drawn with matplotlib (SVG, and PNG where asked): a thin renderer of a
:class:`plclab.viz.failure_model.FailureDiagram`, which decides what the picture holds (ADR 0069).

Every signal is a band of ONE matplotlib Axes (building an Axes per signal is most of a small
figure's cost): the names are text beside the bands, an analog row shows its range as two small
numbers, and only the time axis has ticks. Square waves for BOOLs, labelled bus segments for
small integers, lines for analog values, thresholds dotted with their value, failure markers
dashed across all rows with labels that never overlap. :mod:`plclab.viz.failure_png` draws the
same description with Pillow.
"""

from __future__ import annotations

from typing import Any

from .failure_model import (  # noqa: F401 - the names this module had before ADR 0069
    BAND_RGB,
    INPUT_RGB,
    OUTPUT_RGB,
    PAD,
    SPAN_RGB,
    Drawing,
    FailureDiagram,
    Row,
    band_scale,
    bool_rgb,
    criterion_drawing,
    spread,
)


def failure_figure(d: FailureDiagram) -> Any:
    """A figure (outside pyplot's registry) of the description ``d``: one band per row, top
    to bottom, the failure lines and their labels, the limits, bands and windows checked,
    the title and the lines under it. Draws ``d`` and nothing else."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    lo, hi, width = d.lo, d.hi, d.width
    h_in, left, right_in, frac = d.frame()
    fig = Figure(figsize=(width, h_in))
    FigureCanvasAgg(fig)
    ax = fig.add_axes((left, 0.45 / h_in, 1 - right_in / width - left, frac))
    ax.xaxis.set_major_locator(MaxNLocator(nbins=8))
    ax.set_yticks([])
    for side in ("top", "right", "left"):
        ax.spines[side].set_visible(False)
    ax.tick_params(labelsize=7)
    total = float(sum(r.height for r in d.rows))
    yaxis = ax.get_yaxis_transform()  # x in axes fraction, y in data
    for a, b, _text in d.spans:
        a, b = max(lo, a if a is not None else lo), min(hi, b if b is not None else hi)
        if b > a:
            ax.axvspan(a, b, color=SPAN_RGB, lw=0, zorder=0)
    top = total
    for r in d.rows:
        h = r.height
        base = top - h
        y0, y1 = base + PAD * h, top - PAD * h
        ax.text(-0.01, (y0 + y1) / 2, r.caption, transform=yaxis, ha="right", va="center",
                fontsize=8)
        _row(ax, r, lo, hi, y0, y1, yaxis)
        ax.axhline(base, color="0.85", lw=0.6)
        top = base
    for t in d.markers:
        ax.axvline(t, color="tab:red", lw=0.8, ls="--")
    for t, label, level in d.labels:
        ax.annotate(label, (t, 1.02 + 0.17 * level / (frac * h_in)),  # 0.17 in a row
                    xycoords=("data", "axes fraction"), fontsize=7, color="tab:red",
                    annotation_clip=False)
    ax.set_xlim(lo, hi)
    ax.set_ylim(0, total or 1.0)
    ax.set_xlabel(d.xlabel, fontsize=8)
    if d.title:
        fig.suptitle(d.title, fontsize=10, y=1 - d.TITLE_Y / h_in, va="top")
    for k, (kind, text) in enumerate(d.header()):
        fig.text(0.5, 1 - d.header_y(k) / h_in, text, fontsize=8,
                 color="black" if kind == "caption" else "tab:orange" if kind == "note"
                 else "0.3", ha="center", va="top")
    return fig


def _row(ax: Any, r: Row, lo: float, hi: float, y0: float, y1: float, yaxis: Any) -> None:
    """One row drawn between heights y0 and y1 of the shared Axes."""
    s = r.series
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
        vlo, vhi = r.value_range
        k = (y1 - y0) / (vhi - vlo)
        for a, b, label in r.bands:
            ax.fill_between([lo, hi], y0 + (a - vlo) * k, y0 + (b - vlo) * k,
                            color=BAND_RGB, lw=0)
            for v in (a, b):
                ax.axhline(y0 + (v - vlo) * k, color="tab:orange", lw=0.9, ls="--")
            ax.text(1.005, y0 + ((a + b) / 2 - vlo) * k, label, transform=yaxis, fontsize=7,
                    color="tab:orange", va="center")
        ax.plot(times, [y0 + (float(v) - vlo) * k for v in s.values], color="tab:blue",
                lw=1.0)
        for text, y in zip(r.range_texts(), (y0, y1), strict=True):
            ax.text(-0.003, y, text, transform=yaxis, ha="right", va="center",
                    fontsize=6, color="0.4")
        gap = 0.13  # a 7-point label in the rows' inches
        at = spread([y0 + (value - vlo) * k for value, _ in r.limits], gap)
        for (value, _label), text, ty in zip(r.limits, r.limit_texts(), at, strict=True):
            y = y0 + (value - vlo) * k
            ax.axhline(y, color="tab:orange", lw=0.9, ls=":")
            ax.text(1.005, ty, text, transform=yaxis, fontsize=7, color="tab:orange",
                    va="center")
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


