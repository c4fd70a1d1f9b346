"""Logic-analyzer style timing diagrams (matplotlib; PNG or SVG).

BOOLs are drawn as square waves, integers/enumerations/SFC steps as bus segments labelled with
their values, REALs (analog values, timer ET) as lines. SVG output keeps text as text, so labels
can be searched and tested.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from .failure_model import ANALOG_VALUES, marker_labels, rows_of  # noqa: F401 - public here too
from .failure_model import as_analog as _as_analog  # noqa: F401
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
                   note: str = "", caption: str = "", keep: Sequence[str] = ()):
    """Draw ``series`` stacked over a shared time axis; save to ``path`` (.png/.svg) if given.

    ``markers`` are (time, label) pairs drawn as vertical lines (e.g. "chatter", "fault");
    their labels are merged and stacked so that they never overlap. ``thresholds`` maps a
    series name to (value, label) pairs drawn as dotted horizontal lines (a limit, a switch
    level). Integer series with many values (ADC counts) are drawn as lines, like REALs.
    ``fixed_layout`` draws the failure diagram of :func:`plclab.viz.failure_model.describe`
    (every row in one Axes, ``bands``, ``spans``, ``note``, ``caption``, at most
    :data:`~plclab.viz.failure_model.MAX_ROWS` rows with ``keep`` always in and the rest named)
    instead of one Axes per row and ``tight_layout``: the feedback diagrams drawn for every
    failure. Returns the matplotlib figure.
    """
    plt = _mpl()
    if fixed_layout:  # the feedback's diagram: one Axes, a fraction of the cost
        from .failure_diagram import failure_figure
        from .failure_model import describe

        fig = failure_figure(describe(series, t0, t1, title, markers, width, thresholds, bands,
                                      spans, note, caption, keep))
        if path is not None:
            fig.savefig(str(path), dpi=dpi)
        return fig
    from plclab.i18n import tr

    series, heights, lo, hi = rows_of(series, t0, t1)
    rows = len(series)
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
    axes[-1, 0].set_xlabel(tr("time [s]"))
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    if path is not None:
        fig.savefig(str(path), dpi=dpi)
        plt.close(fig)
    return fig


def failure_png(series: Sequence[Series], path: str | Path | None, t0: float | None = None,
                t1: float | None = None, title: str = "",
                markers: Sequence[tuple[float, str]] = (), width: float = 9.0,
                thresholds: Mapping[str, Sequence[tuple[float, str]]] | None = None,
                bands: Mapping[str, Sequence[tuple[float, float, str]]] | None = None,
                spans: Sequence[tuple[float | None, float | None, str]] = (),
                note: str = "", caption: str = "", keep: Sequence[str] = ()) -> bytes:
    """``timing_diagram(..., fixed_layout=True)`` saved at 72 dpi, drawn with Pillow instead
    of matplotlib (:mod:`plclab.viz.failure_png`, a tenth of the cost) from the same
    description (:func:`plclab.viz.failure_model.describe`): the feedback's failure
    diagrams. Writes ``path`` when given; returns the PNG's bytes."""
    from .failure_model import describe
    from .failure_png import failure_png as draw

    return draw(describe(series, t0, t1, title, markers, width, thresholds, bands, spans, note,
                         caption, keep), path)


def _draw(ax, s: Series, lo: float, hi: float) -> None:
    ax.set_ylabel(s.name + (f" [{s.unit}]" if s.unit else ""), rotation=0, ha="right",
                  va="center", fontsize=8)
    ax.tick_params(labelsize=7)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    times = list(s.times) + [hi]
    if s.kind == "bool":
        from .failure_model import bool_rgb

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
