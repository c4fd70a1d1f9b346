"""The real rerun viewer's default view of a lab mistake, shot under Xvfb with no click and
read back from the PNG: the plots are drawn, the first failure is a red vertical line in the
top plot and the first-failure lane is there. Skipped when Xvfb or the viewer cannot start.
The pixel checks are tried on pictures they must reject first."""

import shutil
import time

import pytest

rr = pytest.importorskip("rerun")
Image = pytest.importorskip("PIL.Image")

PLOT = (30, 70, 940, 235)
"""The top plot of the left column in a 1600x1000 shot (plots are at least 200 px high)."""
LEFT = (0, 40, 955, 990)
"""The left column: plots and lanes."""


def _rgb(im, box):
    import numpy as np

    return np.asarray(im.convert("RGB").crop(box), dtype=np.int32)


def drawn_share(im, box) -> float:
    """The share of pixels in ``box`` that are not (nearly) black."""
    a = _rgb(im, box)
    return float((a.max(axis=2) > 70).mean())


def red_vertical_lines(im, box, share: float = 0.6) -> list[int]:
    """Columns (x) of ``box`` that are red over ``share`` of its height: a failure line, not
    a dashed limit (horizontal) nor a cross (a few pixels)."""
    a = _rgb(im, box)
    r, g, b = a[..., 0], a[..., 1], a[..., 2]
    red = (r > 170) & (g < 110) & (b < 110) & (r - a[..., 1:].max(axis=2) > 90)
    return [box[0] + int(x) for x in (red.mean(axis=0) >= share).nonzero()[0]]


def teal_pixels(im, box) -> int:
    """Pixels of the first-failure lane's colour (what the failed criterion checks)."""
    import numpy as np

    from plclab.viz.recording import CHECKED

    a = _rgb(im, box)
    return int((np.abs(a - np.array(CHECKED)).max(axis=2) < 30).sum())


def _picture(lines=(), red_rows=(), teal=False):
    im = Image.new("RGB", (1600, 1000), (13, 13, 13))
    for x in lines:
        for y in range(PLOT[1], PLOT[3]):
            im.putpixel((x, y), (230, 40, 40))
    for y in red_rows:  # a dashed red limit: horizontal
        for x in range(PLOT[0], PLOT[2], 2):
            im.putpixel((x, y), (230, 40, 40))
    if teal:
        for x in range(0, 800):
            for y in range(600, 620):
                im.putpixel((x, y), (0, 120, 130))
    return im


def test_the_pixel_checks_reject_what_is_not_a_drawn_failure():
    from plclab.viz.recording import CHECKED

    black = _picture()
    assert drawn_share(black, PLOT) == 0.0
    assert red_vertical_lines(black, PLOT) == []
    limit = _picture(red_rows=range(100, 104))  # a red limit is not a failure line
    assert red_vertical_lines(limit, PLOT) == []
    assert red_vertical_lines(_picture(lines=[400]), PLOT) == [400]
    assert teal_pixels(black, LEFT) == 0
    assert teal_pixels(_picture(teal=True), LEFT) == 800 * 20
    assert CHECKED == (0, 120, 130)


@pytest.mark.slow
@pytest.mark.rerun
def test_viewer_default_view_of_a_mistake_marks_the_failure(tmp_path, monkeypatch):
    """tank-two-position ``follows_ls1``: the chattering pump, opened as ``rerun F.rrd``
    opens it after ``lab check --rrd F``."""
    if shutil.which("Xvfb") is None:
        pytest.skip("no Xvfb (apt-get install xvfb mesa-vulkan-drivers)")
    from plclab.grade.lab import find_lab
    from plclab.grade.screenshots import display, record, viewer

    program = find_lab("tank-two-position") / "mistakes" / "follows_ls1.st"
    rrd = tmp_path / "run.rrd"
    t_fail, rid = record("tank-two-position", program, rrd)
    assert rid == "tank-two-position/normal/follows_ls1.st"  # the first failing scenario
    monkeypatch.setenv("PLCLAB_XVFB", "1")  # a screen of our own, 1600x1000
    png = tmp_path / "shot.png"
    # where the failure is on the time axis: 18.5 s of a 240 s run (plus 2 % past the end)
    x_expect = PLOT[0] + (t_fail / (240.0 * 1.02)) * (PLOT[2] - PLOT[0])

    def complete(im) -> bool:
        """The view is drawn: the plot, the red failure line where the failure is, the lane of
        what the failed criterion checks."""
        lines = red_vertical_lines(im, PLOT)
        return (drawn_share(im, PLOT) > 0.02 and bool(lines)
                and min(abs(x - x_expect) for x in lines) < 60 and teal_pixels(im, LEFT) > 2000)

    with display() as env, viewer(rrd, env, timeout=150) as (client, state):
        if client is None or state is None:
            pytest.skip("the rerun viewer did not start under Xvfb")
        # a software renderer on a loaded machine draws late: shoot until the view is complete
        # (at once on an idle machine), for at most five minutes
        deadline = time.monotonic() + 300
        while True:
            time.sleep(3.0)
            try:
                client.save_screenshot(str(png))
            except Exception as e:  # noqa: BLE001 - no software renderer on this machine
                pytest.skip(f"the viewer could not draw: {e}")
            with Image.open(png) as shot:
                if complete(shot) or time.monotonic() > deadline:
                    break
    im = Image.open(png)
    assert im.size == (1600, 1000)
    assert drawn_share(im, PLOT) > 0.02  # the plot is drawn, not a black pane
    lines = red_vertical_lines(im, PLOT)
    assert lines, "no red failure line in the top plot"
    assert min(abs(x - x_expect) for x in lines) < 60
    assert teal_pixels(im, LEFT) > 2000  # the lane of what the failed criterion checks


def test_two_screens_started_at_once_get_two_displays():
    """Xvfb picks its own display number (``-displayfd``): shooters started together (two
    graders, two test runs) never race for one display."""
    if shutil.which("Xvfb") is None:
        pytest.skip("no Xvfb (apt-get install xvfb)")
    from plclab.grade.screenshots import start_xvfb

    (a, n), (b, m) = start_xvfb(), start_xvfb()
    try:
        assert n != m
        assert a.poll() is None and b.poll() is None  # both listen
    finally:
        for p in (a, b):
            p.terminate()
            p.wait(10)
