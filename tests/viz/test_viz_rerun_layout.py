"""The default rerun view reads without a click: structure read back from the recording
(rerun's own reader) and from the blueprint sent, for a tank lab run and a conveyor run."""

import pytest

import plclab.sim as sim
from plclab.viz.recording import lane_entity

rr = pytest.importorskip("rerun")

TANK = """PROGRAM P VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2); END_PROGRAM"""
CHATTER = TANK.replace("((NOT LS1) OR M) AND (NOT LS2)", "NOT LS1")


@pytest.fixture(scope="module")
def tank_lab():
    from plclab.grade.lab import load_lab

    return load_lab("tank-two-position")


@pytest.fixture(scope="module")
def graded(tank_lab):
    """The chattering mistake, graded in two visible scenarios."""
    from plclab.grade.engine import grade_sources

    res = grade_sources(tank_lab, [(CHATTER, "follows_ls1.st")], student="",
                        scenarios=["normal", "low-demand"], keep_traces=True)
    return res


@pytest.fixture(scope="module")
def recs(tank_lab, graded):
    from plclab.viz.from_trace import lab_recordings

    return lab_recordings(tank_lab, graded, "follows_ls1.st", fps=2.0)


def _columns(path, recording_id, entity, component):
    """Values of one component of one entity in one recording of an .rrd file."""
    from rerun.chunk import RrdReader

    reader = RrdReader(path)
    store = next(s for s in reader.recordings() if s.recording_id == recording_id)
    out = []
    for chunk in reader.stream(store=store):
        if str(chunk.entity_path) != entity:
            continue
        batch = chunk.to_record_batch()
        for name in batch.schema.names:
            if name.endswith(component):
                out += batch.column(name).to_pylist()
    return out


def test_lanes_are_the_io_table_in_order_named_not_by_address(recs, tank_lab):
    lay = recs[0].layout
    assert [ln.label for ln in lay.lanes] == [r.name for r in tank_lab.io if r.type == "BOOL"]
    assert [ln.address for ln in lay.lanes] == ["%IX0.0", "%IX0.1", "%QX0.0"]
    assert not any(ln.label.startswith("%") for ln in lay.lanes)  # no address duplicates


def test_plots_per_unit_with_labelled_distinct_limits(recs):
    lay = recs[0].layout
    units = [p.unit for p in lay.plots]
    assert units[0] == "m" and len(units) == len(set(units))
    level = lay.plots[0]
    assert [ln.label for ln in level.lines] == ["LEVEL"]
    assert [lim.label for lim in level.limits] == ["LS1", "LS2", "rim"]
    assert [lim.value for lim in level.limits] == pytest.approx([0.5, 1.5, 2.0])
    colors = [lim.color for lim in level.limits] + [level.lines[0].color]
    assert len(set(colors)) == len(colors)
    assert "mA" not in units  # the transmitter current: the lab is not about it


def test_recording_reads_back_with_names_lanes_limits_and_markers(recs, tmp_path):
    from rerun.chunk import RrdReader

    from plclab.viz.recording import read_entity_paths, write_many

    path = write_many(recs, tmp_path / "run.rrd")
    ids = {s.recording_id for s in RrdReader(path).recordings()}
    assert ids == {"tank-two-position/normal/follows_ls1.st",
                   "tank-two-position/low-demand/follows_ls1.st"}  # every scenario, selectable
    rid = "tank-two-position/normal/follows_ls1.st"
    paths = read_entity_paths(path, rid)
    assert {"/digital/01_LS1", "/digital/02_LS2", "/digital/03_PUMP"} <= paths
    assert "/digital/03_PUMP_chatter" in paths  # the chatter in the lane it concerns
    # the lane says the student's variable and its address, as a logic analyser does
    labels = _columns(path, rid, "/digital/03_PUMP", "StateConfiguration:labels")
    assert "PUMP %QX0.0 ON" in str(labels) and "PUMP %QX0.0 off" in str(labels)
    assert "/plots/edges/markers/PUMP_chatter" in paths  # ... and on its every-edge wave
    names = _columns(path, rid, "/plots/m/limits/2_LS2", "SeriesLines:names")
    assert names and "LS2 1.5 m" in str(names)
    dashes = _columns(path, rid, "/plots/m/limits/2_LS2", "Scalars:scalars")
    flat = [v for row in dashes for v in (row or [])]
    assert any(v != v for v in flat) and 1.5 in flat  # dashed: NaN gaps between dashes
    states = [v for row in _columns(path, rid, "/digital/03_PUMP", "StateChange:state")
              for v in (row or [])]
    assert set(states) == {"0", "1"} and len(states) > 50  # chattering: many changes
    title = _columns(path, rid, "/__properties", "RecordingInfo:name")
    assert "tank-two-position · normal · follows_ls1.st · " in str(title)
    assert "/scan/duration_us" not in paths  # only on request


def test_plant_frames_read_back_as_drawn(recs, tmp_path):
    """The plant's moving shapes (sent column-wise) read back frame by frame: the level
    written beside the water at every frame where it changed."""
    from plclab.viz.recording import write_rrd

    rec = recs[0]
    want: list[str] = []
    last = None
    for i in rec.frame_rows:  # a frame is logged where the text or its place changed
        shp = next(s for s in rec.picture.frame(int(i)) if s.name == "level_value")
        key = (shp.label, round(shp.x, 4), round(shp.y, 4))
        if key != last:
            want.append(shp.label)
            last = key
    path = write_rrd(rec, tmp_path / "one.rrd")
    rid = rec.layout.info.recording_id()
    got = [v for row in _columns(path, rid, "/plant/level_value", "Points2D:labels")
           for v in (row or [])]
    assert len(want) > 10 and got == want
    pumps = _columns(path, rid, "/plant/PUMP", "Points2D:labels")
    assert {"PUMP ON", "PUMP off"} <= {v for row in pumps for v in (row or [])}


def test_summary_puts_failures_first_and_counts_relays(recs):
    text = recs[0].summary
    lines = [ln for ln in text.splitlines() if ln.startswith("- ")]
    assert lines[0].startswith("- **FAILED")
    assert any("CHATTER" in ln for ln in lines)
    assert "relay operations: PUMP (%QX0.0)" in text
    assert not any(e.kind == "relay" for e in recs[0].events)  # one by one only in details
    assert any(e.kind == "relay" for e in recs[0].details)
    verdicts = [e for e in recs[0].events if e.kind == "verdict"]
    assert verdicts and all(e.time >= 0 for e in verdicts)


def blueprint_views(bp) -> list:
    """Every view of a rerun blueprint, depth first through its containers."""
    import rerun.blueprint as rrb

    views = []

    def walk(node):
        for c in getattr(node, "contents", []) or []:
            walk(c)
        if isinstance(node, rrb.View):
            views.append(node)

    walk(bp.root_container)
    return views


def test_blueprint_shows_the_whole_run_paused(recs):

    from plclab.viz.recording import blueprint

    bp = blueprint(recs[0])
    views = blueprint_views(bp)
    kinds = [type(v).__name__ for v in views]
    assert kinds.count("TimeSeriesView") == len(recs[0].layout.plots)
    assert {"StateTimelineView", "Spatial2DView", "TextDocumentView", "TextLogView"} <= set(kinds)
    assert bp.time_panel is not None and "paused" in repr(bp.time_panel.play_state).lower()
    a, b = recs[0].span()
    assert a == 0.0 and b > 200.0


def test_conveyor_bottles_upright_and_fallen_and_counters(tmp_path):
    pytest.importorskip("pymunk")
    from plclab.viz.from_trace import recording
    from plclab.viz.recording import read_entity_paths, write_rrd

    prog = """PROGRAM B VAR C AT %QX0.0 : BOOL; END_VAR C := TRUE; END_PROGRAM"""
    tr = sim.run(prog, plant="conveyor", duration="25s",
                 plant_params={"topple_rate": 0.5, "feed_limit": 6})
    rec = recording(tr, fps=2.0)
    shapes = [s for i in rec.frame_rows for s in rec.picture.frame(int(i))]
    kinds = {s.name for s in shapes}
    assert {"bottles/upright", "bottles/fallen", "counters"} <= kinds
    x0, y0, x1, y1 = rec.picture.bounds
    bottles = [s for s in shapes if s.name.startswith("bottles/")]
    assert all(x0 <= s.x and s.x + s.w <= x1 for s in bottles if s.x > -0.5)  # in frame
    paths = read_entity_paths(write_rrd(rec, tmp_path / "c.rrd"))
    assert {"/plant/bottles/upright", "/plant/bottles/fallen", "/plant/counters"} <= paths


def test_tank_picture_is_filled_and_coloured():
    from plclab.viz.from_trace import recording
    from plclab.viz.plant_view import OFF, ON

    tr = sim.run(TANK, plant="tank", duration="60s")
    rec = recording(tr, fps=1.0)
    frames = [rec.picture.frame(int(i)) for i in rec.frame_rows]
    water = [s for f in frames for s in f if s.name == "water"]
    assert water and all(s.kind == "box" for s in water)  # filled, not an outline
    assert max(s.h for s in water) > min(s.h for s in water)  # it moves with the level
    pump = {s.color for f in frames for s in f if s.name == "PUMP"}
    assert pump == {ON, OFF}
    labels = [s.label for s in frames[-1] if s.kind in ("dot", "text") and s.label]
    assert any(lb.startswith("LEVEL ") and lb.endswith(" m") for lb in labels)  # key value
    spots = [(round(s.x, 3), round(s.y, 3)) for s in frames[-1] if s.label]
    assert len(spots) == len(set(spots))  # no two labels at one place


def test_notebook_viewer_missing_is_a_plc_error(monkeypatch):
    import sys

    from plclab.errors import PlcError
    from plclab.viz import notebook

    monkeypatch.setitem(sys.modules, "rerun_notebook", None)  # as if not installed
    assert not notebook.available()
    with pytest.raises(PlcError) as e:
        notebook.show(sim.run(TANK, plant="tank", duration="5s"))
    assert e.value.code == "PLC4031"


def test_scenarios_failing_first_each_with_its_own_layout_and_application(recs):
    assert not all(v.passed for v in recs[0].layout.info.verdicts)
    lanes = [[ln.label for ln in r.layout.lanes] for r in recs]
    assert all(ln == lanes[0] for ln in lanes)  # the lab's I/O table in every scenario
    apps = {r.layout.info.application_id() for r in recs}
    assert len(apps) == len(recs)  # the viewer keeps a blueprint per application
    spans = {r.span() for r in recs}
    assert all(a == 0.0 for a, _ in spans)


def test_first_failure_lane_and_line_read_back(tank_lab, graded, tmp_path):
    """The first failed criterion: a lane above the I/O lanes (what it checks, teal, then
    red at the failure) and a red vertical line at the failure time in every plot."""
    from plclab.grade.criteria import criterion_limits
    from plclab.viz.from_trace import lab_recordings
    from plclab.viz.recording import FAILED_LANE, write_rrd

    rec = lab_recordings(tank_lab, graded, "follows_ls1.st", fps=2.0, limits={
        c.name: criterion_limits(c) for c in tank_lab.criteria})[0]  # as lab check --rrd
    v = rec.failed
    assert v is not None and not v.passed and v.time is not None
    assert v.time == min(x.time for x in rec.layout.info.verdicts
                         if not x.passed and x.time is not None)  # the first failure
    path = write_rrd(rec, tmp_path / "first.rrd")
    rid = rec.layout.info.recording_id()
    labels = str(_columns(path, rid, FAILED_LANE, "StateConfiguration:labels"))
    assert f"FAILED {v.name} at {v.time:.2f} s" in labels
    assert "checks PUMP fewer than 4 switchings in 20 s" in labels  # the criterion's words
    states = [x for row in _columns(path, rid, FAILED_LANE, "StateChange:state")
              for x in (row or [])]
    assert states[:2] == ["w", "f"]  # the checked span, then the failure
    assert FAILED_LANE < min(lane_entity(k, ln.label)  # sorts above every lane
                             for k, ln in enumerate(rec.layout.lanes))
    for p in rec.layout.plots:
        vals = [x for row in _columns(path, rid, f"/plots/{p.key}/failed_at", "Scalars:scalars")
                for x in (row or [])]
        lo, hi = min(x for x in vals if x == x), max(x for x in vals if x == x)
        assert hi > lo  # a vertical line, not a dot
        assert all(lo <= lim.value <= hi for lim in p.limits)  # across the limits too


def test_checked_span_is_the_window_the_time_or_the_run():
    """What the first-failure lane spans: a settling window, the allowed time before a
    timed failure, the whole run for a count; and the failure's mark inside it."""
    from plclab.grade.criteria_limits import Limit as CLimit
    from plclab.viz.layout import Lane, Layout, Verdict
    from plclab.viz.recording import Recording
    from plclab.viz.series import Series
    from plclab.viz.view import checked_span, failure_states

    lane = Lane("PUMP", Series("PUMP", [0.0, 100.0], [0, 1], "bool", ""), "out", "%QX0.0")
    rec = Recording(layout=Layout(lanes=[lane]))
    rec.failed = Verdict("settles", False, 70.0,
                         limits=[CLimit("window", "T", "in the band from 60 s", t0=60.0)])
    assert checked_span(rec) == (60.0, 100.0)
    times, states = failure_states(rec)
    assert list(zip(times, states, strict=True)) == [(60.0, "w"), (70.0, "f"), (71.0, "w"), (100.0, "0")]
    rec.failed = Verdict("served", False, 45.5,
                         limits=[CLimit("time", "G", "G within 5.5 s of R", 5.5)])
    assert checked_span(rec) == (40.0, 45.5)
    assert failure_states(rec)[1] == ["w", "f", "0"]
    rec.failed = Verdict("no chatter", False, 18.5,
                         limits=[CLimit("count", "PUMP", "fewer than 4 switchings", 4.0)])
    assert checked_span(rec) == (0.0, 100.0)
    rec.failed = Verdict("over the run", False, None, limits=[])
    assert failure_states(rec) == ([0.0, 100.0], ["w", "0"])  # no mark without a time
    rec.focus = 1.22  # ... unless the PLC stopped (a watchdog fault): marked there
    times, states = failure_states(rec)
    assert times == pytest.approx([0.0, 1.22, 2.22, 100.0]) and states == ["w", "f", "w", "0"]


def test_checks_name_addresses_as_the_lab_does():
    """What a failed criterion checks says the lab's names, also inside a rule; an address
    the lab does not name stays as it is, and a longer address is not cut by a shorter."""
    from plclab.grade.criteria_limits import Limit as CLimit
    from plclab.viz.from_trace import _checks_text
    from plclab.viz.layout import Layout, RunInfo

    class Tr:
        meta: dict = {}

        def __contains__(self, name):
            return False

    lay = Layout(info=RunInfo(io=[("TO_GO", "%MW4", "INT"), ("IN_BOX", "%MW0", "INT")]))
    lims = [CLimit("rule", "", "always: %MW4 + %MW0 == 6 and %MW40 < 3"),
            CLimit("count", "%MW0", "= number of bottle events")]
    text = _checks_text(lims, Tr(), lay)
    assert text == ("always: TO_GO + IN_BOX == 6 and %MW40 < 3; "
                    "IN_BOX = number of bottle events")
    assert "%MW4 +" in _checks_text(lims, Tr())  # without a layout: as the criterion says


def test_view_keeps_a_failure_at_either_end_inside():
    """A failure at the first or last moment of the run is not drawn on the plot's edge."""
    from plclab.viz.layout import Lane, Layout, Verdict
    from plclab.viz.recording import Recording
    from plclab.viz.series import Series
    from plclab.viz.view import view_span

    lane = Lane("PUMP", Series("PUMP", [0.0, 100.0], [0, 1], "bool", ""), "out", "%QX0.0")
    rec = Recording(layout=Layout(lanes=[lane]))
    assert view_span(rec) == (0.0, 100.0)  # passed: the run as it is
    rec.failed = Verdict("counts", False, 100.0)
    assert view_span(rec) == (0.0, 102.0)
    rec.failed = Verdict("chatter", False, 0.02)
    assert view_span(rec) == (-2.0, 102.0)


def test_recording_into_a_missing_folder_is_a_plc_error(recs, tmp_path):
    from plclab.errors import PlcError
    from plclab.viz.recording import write_rrd

    with pytest.raises(PlcError) as e:
        write_rrd(recs[0], tmp_path / "no" / "such" / "run.rrd")
    assert e.value.code == "PLC3014" and "does not exist" in str(e.value)
    assert not (tmp_path / "no").exists()


def test_a_lone_failure_lane_leaves_the_column_to_the_plots():
    """heater-pid has no BOOL I/O: its lanes' pane holds the first-failure lane alone and
    keeps that size (not 170 px of black); with many lanes the pane takes what is left."""
    from plclab.viz.layout import Lane, Layout, Line, Plot, Verdict
    from plclab.viz.recording import Recording
    from plclab.viz.series import Series
    from plclab.viz.view import LANE_PX, MIN_LANES_PX, MIN_PLOT_PX, blueprint

    def left_shares(lanes: int) -> list[float]:
        s = Series("T", [0.0, 10.0], [1.0, 2.0], "real", "degC")
        plots = [Plot(k, k, [Line("T", s, (0, 0, 255))]) for k in ("degC", "%")]
        ls = [Lane(f"B{k}", Series(f"B{k}", [0.0, 10.0], [0, 1], "bool", ""), "in", "")
              for k in range(lanes)]
        rec = Recording(layout=Layout(plots=plots, lanes=ls))
        rec.failed = Verdict("heats up", False, 5.0)
        return blueprint(rec).root_container.contents[0].row_shares

    alone = left_shares(0)
    assert alone[-1] == LANE_PX + 56.0 < MIN_LANES_PX  # one lane, its own height
    assert min(alone[:-1]) > 400  # the plots get the rest
    many = left_shares(30)
    assert many[-1] >= MIN_LANES_PX and min(many[:-1]) >= MIN_PLOT_PX
