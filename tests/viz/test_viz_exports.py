"""Timing diagrams, VCD, WaveDrom, CSV and chatter statistics on series with known answers."""

import json
import xml.etree.ElementTree as ET

import pytest

import plclab
from plclab.viz.chatter import bounce_stats, chatter_episodes, output_stats, report
from plclab.viz.exports import render_wavedrom_svg, to_csv, wavejson, write_vcd
from plclab.viz.series import Series

pytest.importorskip("matplotlib")


def ton_run():
    plc = plclab.loads("""PROGRAM P VAR t : TON; inp : BOOL; st : INT; et : TIME; END_VAR
    t(IN := inp, PT := T#300ms); et := t.ET;
    IF t.Q THEN st := 2; ELSIF inp THEN st := 1; ELSE st := 0; END_IF END_PROGRAM""")
    cols = {"T": [], "IN": [], "Q": [], "ET": [], "ST": []}
    for k in range(100):
        plc["inp"] = 10 <= k < 60 or 70 <= k < 80
        plc.scan()
        cols["T"].append(round(k * 0.01, 6))
        cols["IN"].append(plc["inp"])
        cols["Q"].append(plc["t.Q"])
        cols["ET"].append(plc["et"] / 1000)
        cols["ST"].append(plc["st"])
    t = cols["T"]
    return [Series("IN", t, cols["IN"], "bool"), Series("Q", t, cols["Q"], "bool"),
            Series("ET", t, cols["ET"], "real", "s"),
            Series("state", t, cols["ST"], "enum", labels={0: "IDLE", 1: "TIMING", 2: "DONE"})]


def test_vcd_parsed_back_equals_every_change(tmp_path):
    vcdvcd = pytest.importorskip("vcdvcd")
    pytest.importorskip("vcd")
    series = ton_run()
    path = write_vcd(series, tmp_path / "ton.vcd")
    v = vcdvcd.VCDVCD(str(path))
    for s in series:
        tv = v[f"plclab.{s.name}"].tv
        expected = s.changes()
        assert len(tv) == len(expected)
        for (ts, raw), (t, val) in zip(tv, expected, strict=True):
            assert ts == round(t * 1000)
            if s.kind == "bool":
                assert raw == ("1" if val else "0")
            elif s.kind == "real":
                assert float(raw) == pytest.approx(val)
            else:
                assert int(raw, 2) == val


def test_wavedrom_json_and_svg(tmp_path):
    pytest.importorskip("wavedrom")
    series = ton_run()
    w = wavejson(series, tick=0.01)
    q = next(s for s in w["signal"] if s["name"] == "Q")
    assert q["wave"] == "0" + "." * 39 + "1" + "." * 19 + "0" + "." * 39
    st = next(s for s in w["signal"] if s["name"] == "state")
    assert st["data"] == ["IDLE", "TIMING", "DONE", "IDLE", "TIMING", "IDLE"]
    json.dumps(w)
    svg = render_wavedrom_svg(w, tmp_path / "w.svg")
    root = ET.parse(svg).getroot()
    assert root.tag.endswith("svg")
    assert "TIMING" in svg.read_text()


def test_wavedrom_coarsens_long_windows():
    s = Series("X", [i * 0.001 for i in range(10000)], [i % 2 == 0 for i in range(10000)], "bool")
    w = wavejson([s], tick=0.001, max_ticks=100)
    assert len(w["signal"][0]["wave"]) == 100


def test_timing_diagram_png_and_svg_labels(tmp_path):
    from plclab.viz.timing import timing_diagram

    series = ton_run()
    timing_diagram(series, tmp_path / "t.png", title="TON")
    assert (tmp_path / "t.png").read_bytes()[:4] == b"\x89PNG"
    timing_diagram(series, tmp_path / "t.svg", t0=0.05, t1=0.9, markers=[(0.4, "Q rises")])
    text = (tmp_path / "t.svg").read_text()
    for label in ("IN", "Q", "ET [s]", "state", "TIMING", "DONE", "Q rises"):
        assert f">{label}<" in text, label


def test_scan_cycle_reaction_between_one_and_two_scans(tmp_path):
    from plclab.viz.timing import scan_cycle_diagram

    for at in (0.5, 3.0, 9.5, 13.0):
        _, reaction = scan_cycle_diagram(tmp_path / "s.png", cycle_ms=10.0, input_at_ms=at)
        assert 10.0 <= reaction <= 20.0


def test_csv_union_of_times():
    a = Series("A", [0.0, 0.5], [False, True], "bool")
    b = Series("B", [0.0, 0.25, 1.0], [1.0, 2.0, 3.0], "real")
    lines = to_csv([a, b]).strip().splitlines()
    assert lines == ["time_s,A,B", "0.000000,0,1.0", "0.250000,0,2.0", "0.500000,1,2.0",
                     "1.000000,1,3.0"]


def test_output_stats_known_answers():
    # relay on 0-2 s, off 2-2.1, on 2.1-2.15, off 2.15-2.2, on 2.2-10: 4 switchings
    s = Series("K1", [0, 2.0, 2.1, 2.15, 2.2, 10], [1, 0, 1, 0, 1, 1], "bool")
    st = output_stats(s, duration=60.0)
    assert st.switchings == 4 and st.operations == 2
    assert st.per_minute == pytest.approx(4.0)
    assert st.min_on == pytest.approx(0.05) and st.min_off == pytest.approx(0.05)
    assert st.episodes == [(2.0, 2.2, 4)] and st.chatters
    quiet = output_stats(Series("K2", [0, 10, 40], [0, 1, 0], "bool"), duration=60)
    assert not quiet.chatters and quiet.min_on == 30 and quiet.min_off is None
    assert "K1: 4 switchings" in report([s], 60.0)


def test_chatter_episodes_merge_and_separate():
    times = [1.0, 1.1, 1.2, 1.3, 1.4, 5.0, 9.0, 9.05, 9.1, 9.15]
    assert chatter_episodes(times, 4, 1.0) == [(1.0, 1.4, 5), (9.0, 9.15, 4)]
    assert chatter_episodes(times, 6, 1.0) == []


def test_bounce_stats():
    raw = Series("S1.raw", [0, 1.000, 1.001, 1.002, 1.003, 1.004, 3.0],
                 [0, 1, 0, 1, 0, 1, 1], "bool")
    plc = Series("S1", [0, 1.007], [0, 1], "bool")
    phys = Series("S1.phys", [0, 1.0], [0, 1], "bool")
    b = bounce_stats("S1", raw, plc, phys)
    assert (b.physical_edges, b.raw_edges, b.plc_edges) == (1, 5, 1)
    assert b.bursts == [(1.0, 1.004, 5)]
    assert "the PLC saw 1 edge" in b.line()
