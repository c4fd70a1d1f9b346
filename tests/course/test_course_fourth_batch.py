"""Chapters 7, 11, 13, 15 and 16: the new figure kinds (``render`` and ``lab``) draw what the
text says, the numbers the text quotes from lab runs are what those runs give, and the terminal
output chapter 16 prints is what ``plclab run`` prints."""

import re

import numpy as np
import pytest

from plclab.cli import main
from plclab.course.figures import draw
from plclab.course.lab_figures import lab_run
from plclab.course.model import find_chapter
from plclab.errors import PlcError
from plclab.process.alarms import alarm_log


def _spec(chapter, name):
    return next(s for s in chapter.figure_specs if s["file"] == name)


def _lab_trace(chapter_no: int, figure: str):
    ch = find_chapter(chapter_no)
    spec = _spec(ch, figure)
    wanted = [n for n in spec.get("signals", []) if "." in n]
    return lab_run(ch.folder / "examples" / spec["program"], spec["lab"], spec["scenario"], wanted)


def test_render_figures_draw_the_chart_and_the_network(tmp_path):
    sfc = find_chapter(11)
    path, note = draw(sfc, _spec(sfc, "washer_chart.svg"), tmp_path)
    svg = path.read_text(encoding="utf-8")
    for step in ("Start", "Fill", "Boiling", "Warming", "Cooling", "Drain", "Abort"):
        assert f">{step}<" in svg
    assert "render of washer.st" in note
    fbd = find_chapter(7)
    svg = draw(fbd, _spec(fbd, "boxes_fbd.svg"), tmp_path)[0].read_text(encoding="utf-8")
    assert svg.count(">MOVE<") == 2 and ">R_TRIG<" in svg and ">GE<" in svg


def test_a_lab_figure_needs_a_known_scenario(tmp_path):
    ch = find_chapter(15)
    spec = dict(_spec(ch, "boiler_alarms.svg"), scenario="no-such-scenario")
    with pytest.raises(PlcError) as e:
        draw(ch, spec, tmp_path)
    assert "tap-open" in str(e.value)


def test_the_washer_boils_ten_minutes_on_cotton_as_chapter_11_says():
    tr = _lab_trace(11, "washer_cotton.svg")
    t = np.asarray(tr.time)
    boiling = np.asarray(tr["Washer.Boiling.X"], dtype=bool)
    assert (t[boiling].max() - t[boiling].min()) == pytest.approx(600.0, abs=0.5)
    assert not np.asarray(tr["Washer.Warming.X"], dtype=bool).any()
    assert np.asarray(tr["Washer.Start.X"], dtype=bool)[-1]
    temp = np.asarray(tr["TEMP"])
    assert 70.0 < temp[boiling].max() < 80.0  # "about 75 °C"
    assert "Boiling for exactly ten minutes" in find_chapter(11).text


def test_the_boiler_alarm_log_is_what_chapter_15_tells():
    log = alarm_log(_lab_trace(15, "boiler_alarms.svg"))
    states = [(e.id, e.state, e.time) for e in log]
    assert [s[:2] for s in states] == [("NO_WATER", "I"), ("NO_WATER", "IO"),
                                       ("NO_WATER", "IOA")]
    assert states[0][2] == pytest.approx(74, abs=1)
    assert states[1][2] == pytest.approx(133, abs=1)
    assert states[2][2] == pytest.approx(200, abs=0.2)
    text = find_chapter(15).text
    assert "at about 74 s" in text and "at about 133 s" in text and "at 200 s" in text


def test_the_forced_valve_runs_as_chapter_16_tells():
    tr = _lab_trace(16, "forced_valve.svg")
    t = np.asarray(tr.time)
    assert not np.asarray(tr["Boiler.FILL_VALVE"], dtype=bool).any()
    terminal = np.asarray(tr["FILL_VALVE"], dtype=bool)
    assert t[terminal].min() == pytest.approx(20.0, abs=0.2)
    high = np.asarray(tr["LEVEL_MAX"], dtype=bool)
    assert t[high].min() == pytest.approx(34, abs=1)
    assert [(e.id, e.state) for e in alarm_log(tr)] == [("LEVEL_HIGH", "I")]


def test_chapter_16_terminal_output_is_what_plclab_run_prints(capsys, monkeypatch):
    ch = find_chapter(16)
    blocks = re.findall(r"```console\n\$ (plclab [^\n]+)\n(.*?)```", ch.text, re.S)
    assert len(blocks) == 2
    monkeypatch.chdir(ch.folder / "examples")
    for command, expected in blocks:
        assert main(command.split()[1:]) == 0
        assert capsys.readouterr().out == expected


def test_a_render_figure_of_an_st_program_is_refused(tmp_path):
    ch = find_chapter(13)
    with pytest.raises(PlcError) as e:
        draw(ch, {"file": "x.svg", "kind": "render", "source": "station.st"}, tmp_path)
    assert "FBD, LD or SFC" in str(e.value)


def test_the_fbd_tank_runs_like_the_ladder_tank_as_chapter_7_says():
    from plclab.sim import run

    traces = []
    for number, figure in ((6, "tank_run.svg"), (7, "tank_run.svg")):
        ch = find_chapter(number)
        spec = _spec(ch, figure)
        traces.append(run([str(ch.folder / "examples" / spec["program"])], plant=spec["plant"],
                          duration=spec["duration"], plant_params=spec.get("plant_params")))
    ladder, fbd = traces
    for name in ("LS1", "LS2", "PUMP"):
        assert np.array_equal(np.asarray(ladder[name]), np.asarray(fbd[name]))
    assert "switch for switch" in find_chapter(7).text
