"""One failure-diagram description, two renderers (ADR 0069): the description is built once and
both renderers show each of its items (the Pillow PNG read back region by region, the matplotlib
figure's text artists); a renderer that drops an item is caught; the fixed texts follow the
reader's language."""

from __future__ import annotations

import io

import numpy as np
import pytest

from plclab.viz.failure_model import FailureDiagram, describe, missing, rename
from plclab.viz.series import Series

pytest.importorskip("PIL")
pytest.importorskip("matplotlib")


def _description() -> FailureDiagram:
    """A description with an item of every kind: title, caption, note, rows left out, a BOOL
    lane, a bus, an analog plot with a limit and a band, a window, two failure lines."""
    t = np.arange(0.0, 20.0, 0.1)
    rows = [Series("PUMP %QX0.0", t, (t % 6) < 3, "bool"),
            Series("START %IX0.0", t, (t % 9) < 1, "bool"),
            Series("STEP %MW2", t, (t // 5).astype(int), "int"),
            Series("LEVEL", t, 1.0 + 0.8 * np.sin(t / 3), "real", "m"),
            Series("SPARE %QX0.7", t, t > 30, "bool")]
    return describe(rows, 0.0, 20.0, title="normal: no overflow (FAILED)",
                    markers=[(12.0, "no overflow fails"), (16.0, "PLC fault")],
                    thresholds={"LEVEL": [(1.75, "never >=")]},
                    bands={"LEVEL": [(0.4, 0.6, "stay 0.4..0.6 m")]},
                    spans=[(5.0, None, "checked from 5 s")],
                    note="checks: at most 3 switchings", caption="the tank overflows",
                    keep=["LEVEL"], max_rows=4)


def _png_texts(d: FailureDiagram) -> tuple[list[tuple[str, tuple]], object]:
    from PIL import Image

    from plclab.viz.failure_png import failure_png

    drawn: list = []
    data = failure_png(d, drawn=drawn)
    return drawn, Image.open(io.BytesIO(data)).convert("RGB")


def _mpl_texts(d: FailureDiagram) -> list[str]:
    from matplotlib.text import Text

    from plclab.viz.failure_diagram import failure_figure

    fig = failure_figure(d)
    fig.canvas.draw()
    return [a.get_text() for a in fig.findobj(Text) if a.get_visible() and a.get_text()]


def test_the_description_holds_every_item_once():
    d = _description()
    kinds = [k for k, _ in d.items()]
    for kind in ("title", "caption", "note", "left_out", "row", "range", "limit", "band",
                 "marker", "axis"):
        assert kind in kinds, kind
    assert [r.name for r in d.rows] == ["PUMP %QX0.0", "START %IX0.0", "STEP %MW2", "LEVEL"]
    assert "SPARE %QX0.7" in d.left_out  # named, not dropped silently
    assert ("row", "LEVEL [m]") in d.items() and ("limit", "never >= 1.75") in d.items()


def test_both_renderers_draw_every_item_of_the_description():
    d = _description()
    drawn, img = _png_texts(d)
    assert missing(d, [t for t, _ in drawn]) == []
    assert missing(d, _mpl_texts(d)) == []
    # the PNG's regions: ink inside the box of each text drawn, nothing outside the picture
    w, h = img.size
    px = np.asarray(img)
    for text, (x0, y0, x1, y1) in drawn:
        assert 0 <= x0 < x1 <= w and 0 <= y0 < y1 <= h, text
        assert px[y0:y1, x0:x1].min() < 200, text
    # the failure lines: red columns where the description puts them
    red = (px[:, :, 0] > 170) & (px[:, :, 1] < 120) & (px[:, :, 2] < 120)
    h_in, left, right_in, frac = d.frame()
    ax_l, ax_r = left * w, (1 - right_in / d.width) * w
    for t in d.markers:
        x = int(round(ax_l + (t - d.lo) / (d.hi - d.lo) * (ax_r - ax_l)))
        assert red[:, max(0, x - 2):x + 3].sum() > 0.3 * frac * h, t


def test_a_change_of_content_is_made_in_the_description_only():
    d = _description()
    d.rows[3].limits.append((0.25, "plant counted"))
    d.labels.append((3.0, "a new line", 0))
    drawn, _ = _png_texts(d)
    for texts in ([t for t, _ in drawn], _mpl_texts(d)):
        assert "plant counted 0.25" in texts and "a new line" in texts


@pytest.mark.parametrize("renderer", ["png", "matplotlib"])
def test_a_renderer_that_drops_an_item_is_caught(renderer, monkeypatch):
    """Each item in turn left out by the renderer: the check names exactly that item."""
    from matplotlib.text import Text

    from plclab.viz import failure_png as fp
    from plclab.viz.failure_diagram import failure_figure

    d = _description()
    items = d.items()
    assert len(items) >= 15
    draw_text = fp._Canvas.text
    for k, (kind, text) in enumerate(items):
        if sum(1 for _, t in items if t == text) > 1:
            continue  # the same text twice: dropping one is the count's business below
        if renderer == "png":
            def skipping(self, xy, s, *a, _skip=text, **kw):
                if s != _skip:
                    draw_text(self, xy, s, *a, **kw)
            monkeypatch.setattr(fp._Canvas, "text", skipping)
            drawn: list = []
            fp.failure_png(d, drawn=drawn)
            texts = [t for t, _ in drawn]
            monkeypatch.setattr(fp._Canvas, "text", draw_text)
        else:
            fig = failure_figure(d)
            for a in fig.findobj(Text):
                if a.get_text() == text:
                    a.set_visible(False)
            texts = [a.get_text() for a in fig.findobj(Text) if a.get_visible()]
        assert missing(d, texts) == [(kind, text)], (k, kind, text)
    # an item shown once where the description has it twice is caught too
    assert missing(d, [t for _, t in items] + ["extra"]) == []
    assert missing(d, [t for _, t in items][1:]) == [items[0]]


def test_lanes_and_notes_use_the_students_names():
    assert rename("checks: %MW0 = 90; %MW02 stays; GOOD %MW0 once",
                  {"%MW0": "GOOD %MW0"}) == "checks: GOOD %MW0 = 90; %MW02 stays; GOOD %MW0 once"
    assert rename("X1 and X10 and X1.Q", {"X1": "X1 %IX0.2"}) == "X1 %IX0.2 and X10 and X1.Q"


def test_a_russian_picture_has_russian_fixed_texts():
    from plclab.i18n import set_language

    set_language("ru")
    try:
        d = describe([Series("PUMP %QX0.0", [0.0, 1.0], [False, True], "bool")] * 3, 0.0, 2.0,
                     title="t", markers=[(1.0, "x")], keep=[], max_rows=2)
        drawn, _ = _png_texts(d)
        texts = [t for t, _ in drawn]
        mpl = _mpl_texts(d)
    finally:
        set_language(None)
    assert d.xlabel == "время [с]" and "время [с]" in texts and "время [с]" in mpl
    assert d.left_out.startswith("не показано сигналов: 1") and d.left_out in texts
    assert "time [s]" not in texts + mpl


def test_lab_check_png_in_russian_names_the_criterion_in_russian(tmp_path, capsys):
    """``plclab --lang ru lab check ... --png``: the title (the lab's Russian criterion name,
    "НЕ ВЫПОЛНЕН") and the caption (the criterion's Russian message) read back from the PNG."""
    from PIL import Image

    from plclab.cli import main
    from plclab.grade.lab import load_lab
    from plclab.i18n_labs import lab_texts

    lab = load_lab("tank-two-position")
    png = tmp_path / "t.png"
    assert main(["--lang", "ru", "lab", "check", "tank-two-position",
                 str(lab.path / "mistakes" / "follows_ls1.st"), "--png", str(png)]) == 0
    capsys.readouterr()
    info = Image.open(png).text
    title, caption = info["Title"], info.get("Description", "")
    assert title.endswith("(НЕ ВЫПОЛНЕН)")
    names = lab_texts(lab, "ru")["criteria"]
    failed = next(n for n, c in names.items() if f": {c['name']} (" in title)
    assert caption.split("\n")[0] == names[failed]["message"]
    assert not any(w in title + caption for w in ("FAILED", "fails", "checks:"))


@pytest.mark.parametrize("n_rows", [1, 4, 14])
def test_the_title_and_the_lines_under_it_never_overlap(n_rows):
    """A tall picture (a washer with 13 rows) put its title over the caption once: the texts
    above the plot, read back from the PNG, are apart from each other and from the plot's
    marker labels."""
    rows = [Series(f"S{k} %IX0.{k % 8}", [0.0, 1.0], [False, True], "bool")
            for k in range(n_rows)]
    d = describe(rows, 0.0, 2.0, title="door-opened: starts only on START (FAILED)",
                 markers=[(1.0, "starts only on START fails")],
                 caption="the machine starts when it must not", note="checks: x")
    drawn, _ = _png_texts(d)
    box = dict(drawn)
    top = [box[d.title], box[d.caption], box[d.note], box["starts only on START fails"]]
    for a, b in zip(top[:-1], top[1:], strict=True):
        assert a[3] + 2 <= b[1], (a, b)  # each ends 2 px above the next one's top


def test_a_labs_own_check_is_worded_by_its_message_not_its_python_parameters():
    """heater-pid's "reaches 50 °C" noted "checks: target = 50, band = 0.5, after = 0, within =
    600": the band is drawn, the caption says the rest; a built-in count stays in the note."""
    from plclab.grade.criteria_limits import limits_of
    from plclab.viz.failure_model import criterion_drawing

    own = criterion_drawing(limits_of("", {"signal": "TEMP", "target": 50.0, "band": 0.5,
                                           "after": 0.0, "within": 600.0}),
                            lambda s: s, {"TEMP": "degC"}, lambda r: True)
    assert own.bands == {"TEMP": [(49.5, 50.5, "50 ± 0.5 degC")]}
    assert "target =" not in own.note and "within =" not in own.note
    built_in = criterion_drawing(limits_of("event_count", {"event": "bottle_passed", "max": 3}),
                                 lambda s: s)
    assert built_in.note == "checks: at most 3 bottle passed events"


def test_a_long_note_is_wrapped_inside_the_picture():
    """drive-homing's note (a condition over six drives, each named with its address) ran off
    both sides of the picture: every line above the plot now fits the picture's width."""
    words = " or ".join(f"DRIVE_{k}_FWD %QX0.{k}" for k in range(8))
    d = describe([Series("A %IX0.0", [0.0, 1.0], [False, True], "bool")], 0.0, 2.0,
                 title="drive-trip: a fault stops every drive (FAILED)",
                 note=f"checks: not ({words}) within 0.1 s", caption="every drive must stop")
    notes = [t for k, t in d.header() if k == "note"]
    assert len(notes) >= 2 and " ".join(notes) == d.note
    drawn, img = _png_texts(d)
    for text, (x0, _, x1, _) in drawn:
        assert 0 <= x0 and x1 <= img.size[0], text
    assert missing(d, _mpl_texts(d)) == [] and missing(d, [t for t, _ in drawn]) == []
