"""The failure diagram: no row is dropped silently (the failed criterion's own signals are
always drawn, the others left out are named on the picture); the one-Axes drawing gives a PNG
with one band per signal."""

from __future__ import annotations

from plclab.grade.feedback import diagram_names, timing_png
from plclab.grade.lab import load_lab


class _AnyTrace:
    """A trace that has every signal under its own name."""

    io: list = []

    def __contains__(self, name: str) -> bool:
        return True

    def resolve(self, name: str) -> str:
        return name


def test_the_failed_criterions_signal_is_drawn_and_the_rows_left_out_are_named():
    from plclab.viz.failure_model import describe
    from plclab.viz.series import Series

    lab = load_lab("ventilation-fans")
    crit = next(c for c in lab.criteria if c.name == "fault lamp flashes at 5 Hz")
    names = diagram_names(_AnyTrace(), lab, crit)
    assert names[:len(lab.diagram_signals)] == list(lab.diagram_signals)  # none dropped
    assert "FAULT_LAMP" in names
    rows = [Series(n, [0.0, 1.0], [False, True], "bool") for n in names]
    cap = names.index("FAULT_LAMP")  # a cap that would cut the lamp off if taken in order
    assert cap >= 2
    d = describe(rows, 0.0, 1.0, keep=["FAULT_LAMP"], max_rows=cap)
    drawn = [r.name for r in d.rows]
    assert len(drawn) == cap and "FAULT_LAMP" in drawn
    assert drawn == [n for n in names if n in drawn]  # in the lab's order
    left = [n for n in names if n not in drawn]
    assert d.left_out.startswith(f"{len(left)} more signals not drawn: ")
    assert all(n in d.left_out for n in left)
    assert ("left_out", d.left_out) in d.items()  # on the picture, both renderers
    assert describe(rows, 0.0, 1.0).left_out == ""  # no cap reached: no line


def test_a_failure_diagram_is_a_png_of_the_signals(tmp_path):
    import numpy as np

    from plclab.trace import Trace

    t = np.arange(0, 60, 0.01)
    trace = Trace(t, {"LEVEL": np.sin(t / 5) + 1.0, "PUMP": np.sin(t) > 0},
                  {"LEVEL": "float", "PUMP": "bool"})
    path = tmp_path / "f.png"
    fig_path = tmp_path / "g.png"
    timing_png(trace, ["LEVEL", "PUMP"], path, 10.0, 30.0, [(20.0, "no overflow fails")],
               "normal: no overflow", None, {"LEVEL": [(1.75, "limit")]})
    timing_png(trace, ["LEVEL"], fig_path, 10.0, 30.0, [], "one row", None, None)
    assert path.read_bytes().startswith(b"\x89PNG")
    from PIL import Image

    tall, short = Image.open(path).size, Image.open(fig_path).size
    assert tall[0] == short[0] and tall[1] > short[1]  # one band per signal


def _rows():
    from plclab.viz.series import Series

    ts = [0.0, 5.0, 10.0, 15.0, 20.0]
    return [Series("LEVEL", ts, [0.2, 0.8, 1.4, 1.8, 1.9], "real", "m"),
            Series("STEP", ts, [0, 1, 2, 2, 3], "int"),
            Series("PUMP", ts, [True, True, False, True, False], "bool")]


def test_the_pillow_diagram_has_the_matplotlib_diagrams_size():
    """The feedback's PNG (Pillow) keeps the geometry of the matplotlib drawing at 72 dpi."""
    import io

    from PIL import Image

    from plclab.viz.timing import failure_png, timing_diagram

    kw = {"title": "normal: no overflow", "markers": [(12.0, "no overflow fails")],
          "thresholds": {"LEVEL": [(1.75, "limit")]}}
    png = failure_png(_rows(), None, 0.0, 20.0, **kw)
    fig = timing_diagram(_rows(), None, 0.0, 20.0, width=9.0, fixed_layout=True, **kw)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=72)
    assert png.startswith(b"\x89PNG")
    assert Image.open(io.BytesIO(png)).size == Image.open(buf).size


def test_the_pillow_diagram_draws_the_failure_mark_the_limit_and_the_rows(tmp_path):
    """Red for the failure's dashed line, orange for the limit, the rows' colours."""
    from PIL import Image

    from plclab.viz import failure_png as fp
    from plclab.viz.timing import failure_png

    path = tmp_path / "f.png"
    failure_png(_rows(), path, 0.0, 20.0, title="t", markers=[(12.0, "fails")],
                thresholds={"LEVEL": [(1.75, "limit")]})
    def tints(p):  # the colours drawn, lightened towards white as a thin line is
        img = Image.open(p).convert("RGB")
        return {c for _, c in img.getcolors(1 << 16)}

    def has(colours, ref) -> bool:  # a pixel on the way from white to ref
        k = max(range(3), key=lambda i: 255 - ref[i])
        for c in colours:
            alpha = (255 - c[k]) / (255 - ref[k])
            if alpha > 0.4 and all(abs(255 - alpha * (255 - r) - x) < 20
                                   for x, r in zip(c, ref, strict=True)):
                return True
        return False

    colours = tints(path)
    for ref in (fp.RED, fp.ORANGE, fp.BLUE, fp.GREEN, fp.PURPLE):
        assert has(colours, ref), ref
    no_limit = tmp_path / "g.png"
    failure_png(_rows(), no_limit, 0.0, 20.0, title="t")
    assert not has(tints(no_limit), fp.ORANGE)


def test_time_ticks_are_matplotlibs():
    from matplotlib.ticker import MaxNLocator

    from plclab.viz.failure_png import nice_ticks, tick_labels

    for lo, hi in [(106.3, 166.3), (6.5, 26.5), (0.0, 240.0), (0.0, 180.0), (1.234, 3.4),
                   (0.0, 3600.0), (226.5, 256.5)]:
        want = [t for t in MaxNLocator(nbins=8).tick_values(lo, hi) if lo <= t <= hi]
        assert nice_ticks(lo, hi) == [round(t, 9) for t in want] or \
            all(abs(a - b) < 1e-9 for a, b in zip(nice_ticks(lo, hi), want, strict=True))
    assert tick_labels([7.5, 10.0, 12.5]) == ["7.5", "10.0", "12.5"]
    assert tick_labels([112.0, 120.0]) == ["112", "120"]


def test_a_failure_label_at_the_right_edge_stays_inside_the_picture(tmp_path):
    """A failure near the end of the window ("move timeout fails" in drive-homing
    move_every_scan) gets its label left of the line, not cut at the picture's edge."""
    from PIL import Image

    from plclab.viz import failure_png as fp
    from plclab.viz.timing import failure_png

    label = "move timeout fails"
    cv = fp._Canvas(9.0, 4.0)
    f = fp.font(7 * fp.SCALE)
    overflowing = 0
    for k in range(0, 101):
        x = k / 100 * cv.w
        x0, _, x1, _ = fp.label_box(cv, x, 40.0, label)
        assert 0 <= x0 and x1 <= cv.w - fp.LABEL_MARGIN, (x, x0, x1)
        # the check can fail: left of the line, the label would pass the edge here
        overflowing += cv.draw.textbbox((x, 40.0), label, font=f, anchor="ls")[2] > cv.w
    assert overflowing >= 5
    x0, _, x1, _ = fp.label_box(cv, 0.2 * cv.w, 40.0, label)
    assert x0 >= 0.2 * cv.w  # room to the right: the label stays right of its line
    for k in range(0, 101):  # bounded by the plot's right edge
        x0, _, x1, _ = fp.label_box(cv, k / 100 * 0.9 * cv.w, 40.0, label, right=0.9 * cv.w)
        assert 0 <= x0 and x1 <= 0.9 * cv.w

    def red_columns(p):  # the columns that hold a red (text or line) pixel
        img = Image.open(p).convert("RGB")
        w, h = img.size
        px = img.load()
        return w, {x for x in range(w) for y in range(h)
                   if px[x, y][0] > 170 and px[x, y][1] < 140 and px[x, y][2] < 140}

    path = tmp_path / "edge.png"
    failure_png(_rows(), path, 0.0, 20.0, title="move-timeout: move timeout",
                markers=[(19.9, label)])
    w, cols = red_columns(path)
    assert cols and max(cols) < w - 1  # nothing red on the picture's last column
    line = max(cols)  # the dashed line: the label ends left of it, not past the plot
    assert min(cols) < line - 40  # the label's text, left of the dashed line
