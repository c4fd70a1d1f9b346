"""Logic-analyzer style timing diagrams (matplotlib; PNG or SVG).

BOOLs are drawn as square waves, integers/enumerations/SFC steps as bus segments labelled with
their values, REALs (analog values, timer ET) as lines. SVG output keeps text as text, so labels
can be searched and tested.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from .series import Series


def _mpl():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    matplotlib.rcParams["svg.fonttype"] = "none"
    return plt


def timing_diagram(series: Sequence[Series], path: str | Path | None = None,
                   t0: float | None = None, t1: float | None = None, title: str = "",
                   markers: Sequence[tuple[float, str]] = (), width: float = 10.0,
                   dpi: int = 110,
                   thresholds: Mapping[str, Sequence[tuple[float, str]]] | None = None,
                   fixed_layout: bool = False,
                   bands: Mapping[str, Sequence[tuple[float, float, str]]] | None = None,
                   spans: Sequence[tuple[float | None, float | None, str]] = (),
                   note: str = ""):
    """Draw ``series`` stacked over a shared time axis; save to ``path`` (.png/.svg) if given.

    ``markers`` are (time, label) pairs drawn as vertical lines (e.g. "chatter", "fault");
    their labels are merged and stacked so that they never overlap. ``thresholds`` maps a
    series name to (value, label) pairs drawn as dotted horizontal lines (a limit, a switch
    level). Integer series with many values (ADC counts) are drawn as lines, like REALs.
    ``fixed_layout`` draws every row in one Axes with margins computed from the label lengths
    (:mod:`plclab.viz.failure_diagram`) instead of one Axes per row and ``tight_layout``:
    the feedback diagrams drawn for every failure. Returns the matplotlib figure.
    """
    plt = _mpl()
    series, heights, lo, hi = _rows(series, t0, t1)
    rows = len(series)
    if fixed_layout:  # the feedback's diagram: one Axes, a fraction of the cost
        from .failure_diagram import failure_figure

        fig = failure_figure(series, lo, hi, heights, title, markers, width, thresholds,
                             marker_labels(markers, lo, hi), bands, spans, note)
        if path is not None:
            fig.savefig(str(path), dpi=dpi)
        return fig
    fig, axes = plt.subplots(rows, 1, sharex=True, figsize=(width, 0.5 + sum(heights)),
                             gridspec_kw={"height_ratios": heights}, squeeze=False)
    for ax, s in zip(axes[:, 0], series, strict=True):
        _draw(ax, s, lo, hi)
        for value, label in (thresholds or {}).get(s.name, ()):
            ax.axhline(value, color="tab:orange", lw=0.9, ls=":")
            ax.annotate(f"{label} {value:g}", (1.0, value), xycoords=("axes fraction", "data"),
                        xytext=(2, 0), textcoords="offset points", fontsize=7,
                        color="tab:orange", va="center", annotation_clip=False)
        for t, _label in markers:
            if lo <= t <= hi:
                ax.axvline(t, color="tab:red", lw=0.8, ls="--")
        ax.set_xlim(lo, hi)
    for t, label, level in marker_labels(markers, lo, hi):
        axes[0, 0].annotate(label, (t, 1.02 + 0.28 * level), xycoords=("data", "axes fraction"),
                            fontsize=7, color="tab:red", rotation=0, annotation_clip=False)
    axes[-1, 0].set_xlabel("time [s]")
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    if path is not None:
        fig.savefig(str(path), dpi=dpi)
        plt.close(fig)
    return fig


def _rows(series: Sequence[Series], t0: float | None, t1: float | None
          ) -> tuple[list[Series], list[float], float, float]:
    """The rows of a diagram (windowed, many-valued integers as lines), their heights in
    inches and the time span shown."""
    rows = [_as_analog(s.window(t0, t1)) for s in series]
    heights = [0.6 if s.kind in ("bool",) else 0.7 if s.kind != "real" else 1.6 for s in rows]
    lo = t0 if t0 is not None else min((s.times[0] for s in rows if len(s.times)), default=0)
    hi = t1 if t1 is not None else max((s.times[-1] for s in rows if len(s.times)), default=1)
    return rows, heights, lo, hi


def failure_png(series: Sequence[Series], path: str | Path | None, t0: float | None = None,
                t1: float | None = None, title: str = "",
                markers: Sequence[tuple[float, str]] = (), width: float = 9.0,
                thresholds: Mapping[str, Sequence[tuple[float, str]]] | None = None,
                bands: Mapping[str, Sequence[tuple[float, float, str]]] | None = None,
                spans: Sequence[tuple[float | None, float | None, str]] = (),
                note: str = "") -> bytes:
    """``timing_diagram(..., fixed_layout=True)`` saved at 72 dpi, drawn with Pillow instead
    of matplotlib (:mod:`plclab.viz.failure_png`, a tenth of the cost): the feedback's
    failure diagrams. Writes ``path`` when given; returns the PNG's bytes. ``bands``,
    ``spans`` and ``note`` draw what a criterion checks (:func:`criterion_drawing`)."""
    from .failure_png import failure_png as draw

    rows, heights, lo, hi = _rows(series, t0, t1)
    return draw(rows, path, lo, hi, heights, title, markers, width, thresholds,
                marker_labels(markers, lo, hi), bands, spans, note)


ANALOG_VALUES = 12
"""An integer series with more distinct values than this is analog (ADC counts): a line."""


def _as_analog(s: Series) -> Series:
    """Integers with many values as a line; a digital series reduced to its changes (the
    same picture, a fraction of the points to draw)."""
    if s.kind == "int" and len(set(s.values)) > ANALOG_VALUES:
        return Series(s.name, s.times, s.values, "real", s.unit, s.labels)
    if s.kind != "real" and len(s.times) > 2:
        ch = s.changes()
        return Series(s.name, [t for t, _ in ch], [v for _, v in ch], s.kind, s.unit,
                      s.labels)
    return s


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


def _draw(ax, s: Series, lo: float, hi: float) -> None:
    ax.set_ylabel(s.name + (f" [{s.unit}]" if s.unit else ""), rotation=0, ha="right",
                  va="center", fontsize=8)
    ax.tick_params(labelsize=7)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    times = list(s.times) + [hi]
    if s.kind == "bool":
        from .failure_diagram import bool_rgb

        rgb = tuple(c / 255 for c in bool_rgb(s.name))  # inputs blue, outputs green
        vals = [1.0 if v else 0.0 for v in s.values]
        ax.step(list(s.times), vals, where="post", color=rgb, lw=1.2)
        if len(s.times):
            ax.plot([s.times[-1], hi], [vals[-1]] * 2, color=rgb, lw=1.2)
        ax.fill_between(times[:-1] + [hi], (vals + vals[-1:]) if vals else [], step="post",
                        alpha=0.15, color=rgb)
        ax.set_ylim(-0.2, 1.3)
        ax.set_yticks([])
    elif s.kind == "real":
        ax.plot(list(s.times), [float(v) for v in s.values], color="tab:blue", lw=1.0)
    else:
        ch = s.changes()
        ax.set_ylim(0, 1)
        ax.set_yticks([])
        for k, (t, v) in enumerate(ch):
            t_end = ch[k + 1][0] if k + 1 < len(ch) else hi
            d = min((t_end - t) * 0.08, (hi - lo) * 0.004)
            xs = [t, t + d, t_end - d, t_end, t_end - d, t + d, t]
            ys = [0.5, 0.9, 0.9, 0.5, 0.1, 0.1, 0.5]
            ax.plot(xs, ys, color="tab:purple", lw=1.0)
            if t_end - t > (hi - lo) * 0.02:
                ax.text((t + t_end) / 2, 0.5, s.label(v), ha="center", va="center",
                        fontsize=7)


def scan_cycle_diagram(path: str | Path | None = None, cycle_ms: float = 10.0,
                       input_at_ms: float = 13.0, scans: int = 4):
    """The scan cycle drawn from a real run: input read / program / output write phases of
    consecutive scans, an input that changes between two input reads, and the output that
    follows it. The reaction time lies between one and two scans (001 lines 1510-1535).

    Returns (figure, reaction time in ms).
    """
    import plclab

    plc = plclab.loads("PROGRAM Echo VAR i AT %IX0.0 : BOOL; q AT %QX0.0 : BOOL; END_VAR\n"
                       "q := i;\nEND_PROGRAM", cycle_time=f"{cycle_ms}ms")
    out_at = None
    for k in range(scans):
        t_scan = k * cycle_ms
        if t_scan >= input_at_ms:
            plc["%IX0.0"] = True
        plc.scan()
        # inputs are read at the start of a scan; outputs are on the terminals once the
        # output-write phase at the end of the scan has finished
        if out_at is None and plc["%QX0.0"]:
            out_at = t_scan + cycle_ms
    reaction = (out_at - input_at_ms) if out_at is not None else None
    plt = _mpl()
    fig, ax = plt.subplots(figsize=(9, 2.6))
    phases = [("input read", 0.0, 0.1, "tab:green"), ("program", 0.1, 0.8, "tab:blue"),
              ("output write", 0.8, 1.0, "tab:orange")]
    for k in range(scans):
        for name, a, b, color in phases:
            ax.broken_barh([((k + a) * cycle_ms, (b - a) * cycle_ms)], (2, 1), color=color)
            if k == 0:
                ax.text((a + b) / 2 * cycle_ms, 3.3, name, ha="center", fontsize=7, rotation=20)
        ax.text((k + 0.5) * cycle_ms, 1.5, f"scan {k + 1}", ha="center", fontsize=7)
    ax.step([0, input_at_ms, scans * cycle_ms], [0.2, 0.8, 0.8], where="post", color="k")
    ax.text(input_at_ms, 0.95, "input changes", fontsize=7)
    if out_at is not None:
        ax.step([0, out_at, scans * cycle_ms], [-1.2, -0.6, -0.6], where="post",
                color="tab:red")
        ax.annotate("", xy=(out_at, -0.2), xytext=(input_at_ms, -0.2),
                    arrowprops={"arrowstyle": "<->"})
        ax.text((input_at_ms + out_at) / 2, -0.05, f"reaction {reaction:.1f} ms "
                f"({reaction / cycle_ms:.2f} scans)", ha="center", fontsize=7)
        ax.text(out_at, -0.45, "output follows", fontsize=7)
    ax.set_yticks([])
    ax.set_xlabel("time [ms]")
    ax.set_ylim(-1.5, 4.2)
    ax.set_xlim(0, scans * cycle_ms)
    fig.tight_layout()
    if path is not None:
        fig.savefig(str(path), dpi=110)
        plt.close(fig)
    return fig, reaction
