"""Issue 32: every picture after a failed check opens on the first failing scenario at the
moment of its first failure, with what the criterion checks drawn on its signal.

The description of a criterion's limits is checked on made-up parameters (including ones it
must not mistake for limits) and on the labs' own criteria; the pictures are read back: the
PNG's pixels (the failure's red line where the failure is, the band's fill, the window's
tint), the rerun files (one per scenario, the failing one first, lanes named by the
student's variable and address, the limit lines)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from plclab.grade.criteria import comparisons, criterion_limits, describe_limits, limits_of
from plclab.grade.lab import load_lab


def _kinds(lims):
    return [(x.kind, x.signal, x.value, x.hi) for x in lims]


# ---------------------------------------------------------------------------- the description


def test_comparisons_put_the_signal_left_and_read_bands_and_addresses():
    assert comparisons("LEVEL >= 1.75") == [("LEVEL", ">=", 1.75)]
    assert comparisons("1.75 <= LEVEL") == [("LEVEL", ">=", 1.75)]  # flipped
    assert comparisons("47 <= TEMP <= 53") == [("TEMP", ">=", 47.0), ("TEMP", "<=", 53.0)]
    assert comparisons("abs(TEMP - 50) <= 2") == [("TEMP", ">=", 48.0), ("TEMP", "<=", 52.0)]
    assert comparisons("%QX0.0 and %IW64 > -3") == [("%IW64", ">", -3.0)]
    assert comparisons("PUMP and not LS2") == []  # no number: no limit
    assert comparisons("t > 30") == []  # time is a window, not a level of a signal
    assert comparisons("LEVEL > OTHER") == []  # two signals: no constant to draw


def test_each_check_kind_describes_its_limits():
    assert _kinds(limits_of("always_after", {"condition": "47 <= TEMP <= 53", "after": 360.0})) \
        == [("rule", "", None, None), ("band", "TEMP", 47.0, 53.0), ("window", "", None, None)]
    win = limits_of("always_after", {"condition": "47 <= TEMP <= 53", "after": 360.0})[-1]
    assert (win.t0, win.t1) == (360.0, None)
    assert _kinds(limits_of("in_band", {"signal": "TEMP", "lo": 200.0, "hi": 220.0})) == \
        [("band", "TEMP", 200.0, 220.0)]
    st = limits_of("settles", {"signal": "TEMP", "target": 50.0, "band": 0.5, "within": 600.0,
                               "to": 720.0})
    assert _kinds(st)[:2] == [("target", "TEMP", 50.0, None), ("band", "TEMP", 49.5, 50.5)]
    assert (st[2].kind, st[2].t0, st[2].t1) == ("window", 600.0, 720.0)
    sw = limits_of("max_switchings", {"signal": "PUMP", "max": 8})
    assert _kinds(sw) == [("count", "PUMP", 8.0, None)] and "8 switchings" in sw[0].label
    ev = limits_of("event_count", {"event": "cold_extrusion", "max": 0})
    assert ev[0].kind == "count" and ev[0].label == "at most 0 cold extrusion events"
    wi = limits_of("within", {"trigger": "not LS1", "response": "PUMP", "time": 1.0})
    assert wi[-1].kind == "time" and wi[-1].value == 1.0 and wi[-1].signal == "PUMP"
    own = limits_of("", {"pulses": 60, "tol": 2.0, "count": 2, "strict": True, "from": 3.0})
    assert own[0].label == "pulses = 60, tol = 2, count = 2"  # no bool, no window in it
    assert own[-1].kind == "window" and own[-1].t0 == 3.0
    # a condition with no number draws no line, but still says what it checks
    assert [x.kind for x in limits_of("never", {"condition": "PUMP and LS2"})] == ["rule"]


def test_the_labs_criteria_are_described_from_their_definitions():
    thermo = {c.name: c for c in load_lab("relay-thermostat").criteria}
    holds = criterion_limits(thermo["holds 50 °C ± 2 °C"])
    band = next(x for x in holds if x.kind == "band")
    assert (band.signal, band.value, band.hi) == ("TEMP", 47.0, 53.0)
    washer = {c.name: c for c in load_lab("washing-machine").criteria}
    cool = [x for x in criterion_limits(washer["cools before draining"]) if x.kind == "level"]
    assert [(x.signal, x.value) for x in cool] == [("TEMP", 41.0)]
    press = {c.name: c for c in load_lab("press-safety").criteria}
    doses = describe_limits(criterion_limits(press["makes doses"]))
    assert "pulses = 60" in doses and "count = 2" in doses
    band = criterion_limits(press["temperature in its band"])[0]
    assert (band.value, band.hi) == (200.0, 220.0)
    tank = {c.name: c for c in load_lab("tank-two-position").criteria}
    assert "LEVEL never >= 1.75 m" in describe_limits(criterion_limits(tank["no overflow"]),
                                                     {"LEVEL": "m"})


def test_every_criterion_of_every_lab_can_be_described():
    """Held-back labs use the same check kinds: none may make the description fail."""
    from plclab.grade.lab import list_labs

    for lab_id in list_labs():
        lab = load_lab(lab_id)
        for c in lab.criteria:
            for lim in criterion_limits(c):
                assert lim.kind in ("level", "band", "target", "window", "count", "time",
                                    "rate", "rule"), (lab_id, c.name, lim)
                assert lim.label.strip()


# ---------------------------------------------------------------------------- the first failure


def _test(scenario, criterion, t_fail, passed=False, detail="x"):
    return SimpleNamespace(scenario=scenario, criterion=criterion, t_fail=t_fail,
                           passed=passed, detail=detail)


def test_the_first_failure_is_the_first_failing_scenario_in_the_labs_order():
    from plclab.grade.commands import first_failure

    lab = load_lab("press-safety")
    order = [s.name for s in lab.scenarios]
    a, b = order[0], order[2]
    traces = {a: None, b: None}
    tests = [_test(b, "stops for the light curtain", 2.25),
             _test(a, "makes doses", None),  # failed over the whole run
             _test(a, "the piston moves", 1.0, passed=True),
             _test(a, "returns to the top", 5.0, detail="not run: requires ..."),
             _test(a, "no crash", 7.0)]
    got = first_failure(lab, tests, traces)
    assert (got.scenario, got.criterion) == (a, "no crash")  # a moment beats "over the run"
    assert first_failure(lab, tests[:1], traces).scenario == b
    assert first_failure(lab, [tests[2], tests[3]], traces) is None  # passed or not run
    assert first_failure(lab, tests, {b: None}).scenario == b  # only scenarios drawn


# ---------------------------------------------------------------------------- the pictures


def _pixels(path):
    from PIL import Image

    img = Image.open(path).convert("RGB")
    return img, img.load()


def _red(c) -> bool:
    """Red, or red thinned towards white by anti-aliasing (not orange, not pink fills)."""
    return c[0] - c[1] > 45 and abs(c[1] - c[2]) < 30


def _red_columns(img, px, min_count=40):
    """x of the columns with at least ``min_count`` red pixels (a vertical line, dashed or
    not)."""
    w, h = img.size
    return [x for x in range(w) if sum(_red(px[x, y]) for y in range(h)) >= min_count]


def test_png_of_a_failed_check_marks_the_failure_and_draws_the_band(tmp_path):
    """A trace whose TEMP leaves a 47..53 band at 30 s: the diagram has the red failure line
    at 30 s, the band's fill and edges and the window's tint; without the criterion none."""
    import numpy as np

    from plclab.grade.feedback import criterion_picture, timing_png
    from plclab.trace import Trace
    from plclab.viz.failure_diagram import BAND_RGB, SPAN_RGB

    t = np.arange(0.0, 60.0, 0.1)
    temp = np.where(t < 30, 50 + np.sin(t), 56.0)
    trace = Trace(t, {"TEMP": temp, "HEATER": np.sin(t) > 0}, {"TEMP": "float",
                                                               "HEATER": "bool"},
                  meta={"t_end": 60.0, "units": {"TEMP": "degC"}})
    crit = SimpleNamespace(check="always_after", function=None,
                           params={"condition": "47 <= TEMP <= 53", "after": 10.0})
    path = tmp_path / "f.png"
    timing_png(trace, ["TEMP", "HEATER"], path, 0.0, 60.0, [(30.0, "holds fails")],
               "warm-up: holds", None, drawing=criterion_picture(trace, crit,
                                                                 ["TEMP", "HEATER"]))
    img, px = _pixels(path)
    colours = {c for _, c in img.getcolors(1 << 20)}
    band = tuple(int(255 * c) for c in BAND_RGB)
    span = tuple(int(255 * c) for c in SPAN_RGB)
    assert any(all(abs(c[i] - band[i]) < 4 for i in range(3)) for c in colours)
    assert any(all(abs(c[i] - span[i]) < 4 for i in range(3)) for c in colours)
    reds = _red_columns(img, px)
    assert reds, "no failure line"
    # where 30 s lies: between the axis' ends, which are 0 s and 60 s
    w = img.size[0]
    assert 0.35 * w < sum(reds) / len(reds) < 0.75 * w
    plain = tmp_path / "g.png"
    timing_png(trace, ["TEMP", "HEATER"], plain, 0.0, 60.0, [], "t", None)
    img2, _ = _pixels(plain)
    assert not any(all(abs(c[i] - band[i]) < 4 for i in range(3))
                   for _, c in img2.getcolors(1 << 20))


def test_input_rows_are_blue_and_output_rows_green():
    from plclab.viz.failure_diagram import INPUT_RGB, OUTPUT_RGB, bool_rgb

    assert bool_rgb("START %IX0.0") == INPUT_RGB
    assert bool_rgb("PUMP %QX0.0") == OUTPUT_RGB
    assert bool_rgb("PUMP") == OUTPUT_RGB and bool_rgb("X%IX") == OUTPUT_RGB


def test_labels_of_close_limits_never_overlap():
    from plclab.viz.failure_diagram import spread

    ys = [10.0, 11.0, 50.0, 12.0]
    got = spread(ys, 5.0)
    order = sorted(got)
    assert all(b - a >= 5.0 - 1e-9 for a, b in zip(order, order[1:], strict=False))
    assert got[2] == 50.0  # a label with room stays where its line is
    assert [ys.index(y) for y in sorted(ys)] == [got.index(y) for y in sorted(got)]


def test_signal_labels_name_both_sides_of_a_wire_but_not_analog_values():
    import numpy as np

    from plclab.trace import Trace
    from plclab.viz.layout import signal_labels

    t = np.arange(3.0)
    tr = Trace(t, {"PUMP": np.array([0, 1, 0], bool), "%QX0.0": np.array([0, 1, 0], bool),
                   "TEMP": np.array([1.0, 2, 3]), "%IW64": np.array([1, 2, 3])},
               {"PUMP": "bool", "%QX0.0": "bool", "TEMP": "float", "%IW64": "int"},
               meta={"t_end": 3.0, "io": [
                   {"column": "%QX0.0", "plant_column": "PUMP", "direction": "out"},
                   {"column": "%IW64", "plant_column": "TEMP", "direction": "in"}]})
    io = [("PUMP", "%QX0.0", "BOOL"), ("TEMP_RAW", "%IW64", "INT")]
    got = signal_labels(io, tr)
    assert got["%QX0.0"] == got["PUMP"] == "PUMP %QX0.0"
    assert got["%IW64"] == "TEMP_RAW %IW64" and "TEMP" not in got  # degC is not counts


def test_lab_check_png_draws_the_first_failure_and_says_so(tmp_path, capsys):
    from plclab.cli import main

    lab = load_lab("tank-two-position")
    png = tmp_path / "t.png"
    assert main(["lab", "check", "tank-two-position",
                 str(lab.path / "mistakes" / "follows_ls1.st"), "--png", str(png)]) == 0
    out = capsys.readouterr().out
    line = next(ln for ln in out.splitlines() if ln.startswith("timing diagram:"))
    first = next(s.name for s in lab.scenarios if s.visible)
    assert f"scenario '{first}'" in line and "criterion '" in line and "failed at t =" in line
    img, px = _pixels(png)

    assert _red_columns(img, px), "the failure's line"
    assert "add --out DIR (or --png" not in out


# ---------------------------------------------------------------------------- rerun


rr = pytest.importorskip("rerun")


def test_lab_rrd_is_one_file_per_scenario_the_failure_first(tmp_path):
    from rerun.chunk import RrdReader

    from plclab.grade.criteria import criterion_limits as cl
    from plclab.grade.engine import grade_sources, read_submission
    from plclab.viz.from_trace import write_lab_rrd
    from plclab.viz.recording import read_entity_paths

    lab = load_lab("tank-two-position")
    src, _ = read_submission(str(lab.path / "mistakes" / "follows_ls2.st"))
    res = grade_sources(lab, src, student="", scenarios=["normal", "low-demand"],
                        keep_traces=True)
    failing = [s for s in ("normal", "low-demand") if any(
        t.scenario == s and not t.passed for t in res.tests)]
    assert failing, "the mistake fails somewhere"
    text = write_lab_rrd(lab, res, tmp_path / "run.rrd", "follows_ls2.st",
                         limits={c.name: cl(c) for c in lab.criteria})
    lines = text.splitlines()
    assert f"scenario '{failing[0]}'" in lines[0] and "FAILED" in lines[0]
    files = sorted(tmp_path.glob("*.rrd"))
    assert len(files) == 2
    stores = RrdReader(tmp_path / "run.rrd").recordings()
    assert [s.recording_id for s in stores] == [f"tank-two-position/{failing[0]}/follows_ls2.st"]
    paths = read_entity_paths(tmp_path / "run.rrd")
    assert "/digital/03_PUMP" in paths
    assert any(p.startswith("/plots/m/limits/") for p in paths)


def test_rerun_plot_has_the_failed_criterions_limit_and_the_failure_selected(tmp_path):
    import numpy as np
    import rerun.blueprint as rrb

    from plclab.trace import Trace
    from plclab.viz.from_trace import recording
    from plclab.viz.layout import RunInfo, Verdict
    from plclab.viz.view import blueprint, plot_title

    t = np.arange(0.0, 60.0, 0.1)
    trace = Trace(t, {"TEMP": 45 + t / 5}, {"TEMP": "float"},
                  meta={"t_end": 60.0, "units": {"TEMP": "degC"}, "signals": ["TEMP"]})
    lims = limits_of("never", {"condition": "TEMP >= 53"})
    info = RunInfo(lab="x", scenario="warm", verdicts=[
        Verdict("never overheats", False, 40.0, "TEMP >= 53", ["TEMP"], lims)])
    rec = recording(trace, info=info, fps=1.0)
    plot = rec.layout.plots[0]
    assert [lim.value for lim in plot.limits] == [53.0]
    assert "53" in plot_title(plot)
    assert rec.focus == 40.0
    assert "checks: never: TEMP >= 53; TEMP never >= 53 degC" in rec.summary
    bp = blueprint(rec)
    sel = bp.time_panel.time_selection
    assert sel is not None and "40" in repr(sel).replace("_", "")  # around 40 s
    passed = RunInfo(lab="x", scenario="warm", verdicts=[
        Verdict("never overheats", True, None, "", ["TEMP"], lims)])
    rec2 = recording(trace, info=passed, fps=1.0)
    assert rec2.layout.plots[0].limits == [] and rec2.focus is None
    assert isinstance(bp, rrb.Blueprint)


# ---------------------------------------------------------------------------- plant drawings


class _Plant:
    def __init__(self, geo):
        self.geo = geo

    def geometry(self):
        return self.geo


def _plant_trace(cols, kinds, info):
    import numpy as np

    from plclab.trace import Trace

    t = np.arange(0.0, 10.0, 0.5)
    return Trace(t, {k: np.asarray(v) for k, v in cols.items()}, kinds,
                 meta={"t_end": 10.0, "signal_info": info,
                       "units": {k: d.get("unit", "") for k, d in info.items()}})


def test_a_round_drum_holds_its_water_level():
    from plclab.viz.plant_view import picture

    level = [0.0] * 4 + [10.0] * 16  # half of 0..20 l from t = 2 s
    tr = _plant_trace({"LEVEL": level}, {"LEVEL": "float"},
                      {"LEVEL": {"type": "real", "kind": "sensor", "unit": "l",
                                 "range": [0.0, 20.0]}})
    geo = {"shapes": [{"type": "rect", "name": "cabinet", "x": 0.0, "y": 0.0, "w": 0.6,
                       "h": 0.85},
                      {"type": "circle", "name": "drum", "x": 0.3, "y": 0.45, "r": 0.25}]}
    pic = picture(tr, _Plant(geo))
    empty = [s for s in pic.frame(0) if s.name == "water"]
    half = [s for s in pic.frame(10) if s.name == "water"]
    assert not empty and half
    top = max(s.y + s.h for s in half)
    assert abs(top - 0.45) < 1e-6  # half full: up to the drum's centre
    assert all(0.05 - 1e-9 <= s.x and s.x + s.w <= 0.55 + 1e-9 for s in half)  # inside
    label = next(s for s in pic.frame(10) if s.name == "level_value")
    assert label.label == "LEVEL 10.0 l" and label.x < 0.0  # outside the cabinet


def test_fans_turn_while_they_run_and_a_curtain_shows_a_hand():
    from plclab.viz.plant_view import HOT, ON, picture

    on = [False] * 6 + [True] * 14
    clear = [True] * 10 + [False] * 4 + [True] * 6
    tr = _plant_trace({"FAN1": on, "LIGHT_CURTAIN": clear, "HAND_L": on},
                      {"FAN1": "bool", "LIGHT_CURTAIN": "bool", "HAND_L": "bool"},
                      {"FAN1": {"type": "bool", "kind": "actuator"},
                       "LIGHT_CURTAIN": {"type": "bool", "kind": "panel"},
                       "HAND_L": {"type": "bool", "kind": "panel"}})
    geo = {"shapes": [{"type": "rect", "name": "building", "x": 0.0, "y": 0.0, "w": 30.0,
                       "h": 6.0},
                      {"type": "circle", "name": "FAN1", "x": 5.0, "y": 4.5, "r": 0.6}]}
    pic = picture(tr, _Plant(geo))

    def blades(i):
        return [s.points[1] for s in pic.frame(i) if s.name == "FAN1/blades"]

    assert blades(2) == blades(5)  # stopped: the blades stand still
    assert blades(8) != blades(12)  # running: they turn
    state = {s.label for i in (2, 12) for s in pic.frame(i) if s.name == "FAN1/state"}
    assert state == {"FAN1 off", "FAN1 ON"}
    beams_clear = [s for s in pic.frame(2) if s.name == "LIGHT_CURTAIN/beams"]
    beams_cut = [s for s in pic.frame(11) if s.name == "LIGHT_CURTAIN/beams"]
    assert {s.color for s in beams_clear} == {ON} and {s.color for s in beams_cut} == {HOT}
    assert len(beams_cut) < len(beams_clear)
    hands = {s.label for i in (2, 12) for s in pic.frame(i) if s.name == "HAND_L"}
    assert hands == {"HAND_L released", "HAND_L pressed"}
    assert not any(s.name == "FAN1" and s.kind == "dot" for s in pic.frame(12))  # no lamp


def test_the_plant_view_shows_the_failure_with_every_shape_logged_there(tmp_path):
    from plclab.viz.from_trace import recording
    from plclab.viz.layout import RunInfo, Verdict
    from plclab.viz.recording import blueprint

    tr = sim_tank()
    info = RunInfo(lab="x", scenario="s", verdicts=[Verdict("c", False, 20.25, "d")])
    rec = recording(tr, info=info, fps=1.0)
    assert 20.25 in [round(t, 6) for t in rec.frame_times]
    from test_viz_rerun_layout import blueprint_views

    views = blueprint_views(blueprint(rec))
    plant = next(v for v in views if v.origin == "/plant")
    assert plant.name == "plant at the first failure, t = 20.25 s"
    # every moving shape is logged at that moment, so a view of that moment shows them all
    from plclab.viz.recording import RrdWriter

    sent = []
    w = RrdWriter(rec, tmp_path / "a.rrd")
    w._shape_columns = lambda entity, items: sent.extend(
        entity for t, _ in items if abs(t - 20.25) < 1e-9)
    w.send(rec)
    w.close()
    names = {s.name for s in rec.picture.frame(int(rec.frame_rows[
        [round(t, 6) for t in rec.frame_times].index(20.25)]))}
    assert {f"/plant/{n}" for n in names} <= set(sent)


def sim_tank():
    import plclab.sim as sim

    prog = ("PROGRAM P VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; "
            "END_VAR M := ((NOT LS1) OR M) AND (NOT LS2); END_PROGRAM")
    return sim.run(prog, plant="tank", duration="40s")


def test_fast_switching_lanes_are_also_drawn_edge_by_edge():
    from plclab.viz.layout import FAST_CHANGES, Lane, edge_plot
    from plclab.viz.series import Series

    n = 2 * FAST_CHANGES
    t = [0.1 * k for k in range(n)]
    fast = Lane("PUMP", Series("%QX0.0", t, [k % 2 == 1 for k in range(n)], "bool"), "out",
                "%QX0.0")
    slow = Lane("LS2", Series("%IX0.1", t, [k > n // 2 for k in range(n)], "bool"), "in",
                "%IX0.1")
    assert edge_plot([slow]) is None  # one switching: the lane shows it
    p = edge_plot([slow, fast])
    assert [ln.label for ln in p.lines] == [f"PUMP %QX0.0 ({n - 1} switchings)"]
    assert p.lines[0].step and p.lines[0].color == fast.color
    vals = list(p.lines[0].series.values)
    assert sorted(set(vals)) == [0.0, 1.0] and sum(vals) == n // 2  # every edge kept


def test_lab_check_out_names_the_first_failures_picture(tmp_path, capsys):
    from plclab.cli import main

    lab = load_lab("tank-two-position")
    out = tmp_path / "fb"
    assert main(["lab", "check", "tank-two-position",
                 str(lab.path / "mistakes" / "follows_ls1.st"), "--out", str(out)]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines()
                if ln.startswith("first failure: "))
    first = next(s.name for s in lab.scenarios if s.visible)
    assert f"scenario '{first}'" in line
    path = line.split(": ", 1)[1].split(" (")[0]
    assert path.endswith(".png") and (out / path.rsplit("/", 1)[1]).is_file()
    img, px = _pixels(path)
    assert _red_columns(img, px)


def test_a_failure_judged_at_the_end_is_drawn_over_the_whole_run():
    import argparse

    from plclab.grade.commands import student_picture
    from plclab.grade.feedback import judged_at_end

    assert judged_at_end(40.0, 40.0) and not judged_at_end(39.0, 40.0)
    lab = load_lab("bottle-reject")
    res = SimpleNamespace(traces={"run": SimpleNamespace(t_end=40.0)}, tests=[])
    lab.student_watch = []
    for t_fail, want in ((40.0, "0s..40.000s"), (None, "0s..40.000s")):
        ns = argparse.Namespace(signals="X", window=None)
        student_picture(lab, res, "run", ns, _test("run", "counts good bottles", t_fail))
        assert ns.window == want
    ns = argparse.Namespace(signals="X", window=None)
    student_picture(lab, res, "run", ns, _test("run", "counts good bottles", 20.0))
    a, _, b = ns.window.partition("..")
    assert float(a.rstrip("s")) > 0.0 and float(b.rstrip("s")) < 40.0  # around 20 s


def test_a_spawned_viewer_gets_its_cursor_at_the_failure_in_the_right_recording():
    """ADR 0050: only a live viewer can be told where the cursor stands; ``place_cursor``
    waits for the recording to arrive, picks it by its id and pauses there."""
    from types import SimpleNamespace as NS

    from plclab.viz.recording import place_cursor

    calls, polls = [], []

    class Viewer:
        def __init__(self, arrived_after):
            self.arrived_after = arrived_after

        def get_state(self):
            polls.append(1)
            recs = [NS(store_id="Recording:a:lab/other/f.st")]
            if len(polls) > self.arrived_after:
                recs.append(NS(store_id="Recording:b:lab/cold/f.st"))
            return NS(recordings=recs)

        def set_time(self, timeline, **kw):
            calls.append((timeline, kw))

    viewer = Viewer(arrived_after=2)
    assert place_cursor(12.5, "lab/cold/f.st", connect=lambda url: viewer, pause=0.0)
    assert calls == [("sim_time", {"duration": 12.5, "play_state": "paused",
                                   "recording": "Recording:b:lab/cold/f.st"})]
    assert len(polls) == 3, "it waited for the recording"

    def refused(url):
        raise ConnectionError(url)

    calls.clear()
    assert not place_cursor(3.0, "x", connect=refused, tries=3, pause=0.0) and calls == []
    polls.clear()
    never = Viewer(arrived_after=99)
    assert not place_cursor(3.0, "lab/cold/f.st", connect=lambda url: never, tries=4,
                            pause=0.0) and calls == []


def test_a_labs_own_check_with_a_signal_and_a_set_point_draws_its_band():
    """heater-pid's own checks name TEMP, a target and a band: the band is drawn on TEMP;
    without a signal (or without a target) the numbers stay words."""
    got = _kinds(limits_of("", {"signal": "TEMP", "target": 60.0, "band": 0.5, "after": 720.0}))
    assert ("band", "TEMP", 59.5, 60.5) in got
    assert ("target", "TEMP", 60.0, None) in _kinds(limits_of("", {"signal": "TEMP",
                                                                   "target": 60.0}))
    assert ("level", "TEMP", 45.0, None) in _kinds(limits_of("", {"signal": "TEMP",
                                                                  "level": 45.0}))
    assert [k for k, *_ in _kinds(limits_of("", {"target": 60.0, "band": 0.5}))] == ["count"]
    assert [k for k, *_ in _kinds(limits_of("", {"signal": "TEMP", "band": 0.5}))] == ["count"]


def test_the_failure_is_crossed_on_the_signal_its_limits_are_drawn_on():
    """heater-pid: the criterion reads SP, TEMP and POWER, its band is on TEMP: the cross goes
    on TEMP's line at the failure (not on SP, the first signal it reads)."""
    import numpy as np

    from plclab.trace import Trace
    from plclab.viz.from_trace import recording
    from plclab.viz.layout import RunInfo, Verdict

    t = np.arange(0.0, 100.0, 0.5)
    trace = Trace(t, {"SP": np.where(t < 50, 50.0, 60.0), "TEMP": 50.0 + 0.01 * np.sin(t)},
                  {"SP": "float", "TEMP": "float"},
                  meta={"t_end": 100.0, "units": {"SP": "%", "TEMP": "degC"},
                        "signals": ["SP", "TEMP"]})
    lims = limits_of("", {"signal": "TEMP", "target": 60.0, "band": 0.5})
    info = RunInfo(lab="x", scenario="step", verdicts=[
        Verdict("follows the step", False, 80.0, "left the band", ["SP", "TEMP"], lims)])
    rec = recording(trace, info=info, fps=1.0)
    [cross] = [m for m in rec.markers if m.kind == "fails" and m.plot is not None]
    plot = next(p for p in rec.layout.plots if p.key == cross.plot)
    assert [ln.series.name for ln in plot.lines] == ["TEMP"] and abs(cross.value - 50.0) < 0.1
    no_limits = RunInfo(lab="x", scenario="step", verdicts=[
        Verdict("follows the step", False, 80.0, "left the band", ["SP", "TEMP"], [])])
    [first] = [m for m in recording(trace, info=no_limits, fps=1.0).markers
               if m.kind == "fails" and m.plot is not None]
    assert first.value == 60.0, "without limits: its first signal, SP"
