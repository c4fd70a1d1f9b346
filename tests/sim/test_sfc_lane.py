"""The SFC lane of a simulated run (plclab/sim/sfc_lane.py): the step flags recorded as
columns, transition firings as ``sfc_step`` events, "why did it not advance" at the end, and
how timing diagrams, the rerun layout and the lab feedback show them."""

from __future__ import annotations

from pathlib import Path

import pytest

from plclab.sim import Scenario, run

ROOT = Path(__file__).parent.parent.parent
WASHER = (ROOT / "labs" / "washing-machine" / "solution" / "washer.st").read_text("utf-8")
PARAMS = {"level_full": 8.0, "heater_power": 4000.0}


@pytest.fixture(scope="module")
def silk():
    sc = Scenario().set("COTTON", False, at=0).set("SILK", True, at=0).press("START", at="2s")
    return run(WASHER, "washer", "7min", scan="100ms", scenario=sc, plant_params=PARAMS)


def test_every_step_is_a_column_and_the_firings_are_events(silk):
    chart = silk.meta["sfc"][0]
    assert chart["instance"] == "Washer"
    assert list(chart["columns"]) == ["Start", "Fill", "Boiling", "Warming", "Cooling",
                                      "Drain", "Abort"]
    assert all(c in silk.columns for c in chart["columns"].values())
    steps = [(round(e.time, 1), e.message) for e in silk.events_of("sfc_step")]
    assert [m for _, m in steps] == ["Start -> Fill", "Fill -> Warming", "Warming -> Cooling",
                                     "Cooling -> Drain", "Drain -> Start"]
    fill, warming = steps[1][0], steps[2][0]
    assert warming - fill == pytest.approx(300.0, abs=0.15), "Warming lasts 5 min"
    assert silk.time_in_band("Washer.Warming.X", 1, 1) == pytest.approx(300.0, abs=0.15)


def test_the_end_says_where_the_chart_stands(silk):
    (line,) = silk.meta["sfc_end"]
    assert line.startswith("Washer is in step Start (active for T#")
    assert "to Fill when 'START_PB AND STOP_PB AND DOOR AND (COTTON XOR SILK)': FALSE" in line
    assert "START_PB = FALSE" in line


def test_a_stuck_chart_names_its_step_transitions_and_condition_values():
    sc = Scenario().press("START", at="2s").fault("level_switch_stuck_off", at=0)
    tr = run(WASHER, "washer", "2min", scan="100ms", scenario=sc, plant_params=PARAMS)
    (line,) = tr.meta["sfc_end"]
    assert line.startswith("Washer is in step Fill (active for T#1m57s")
    assert "to Boiling when 'LEVEL_SW AND COTTON': FALSE (LEVEL_SW = FALSE, COTTON = TRUE)" \
        in line
    assert "to Abort when 'NOT STOP_PB OR NOT DOOR': FALSE" in line
    assert "to Warming when 'LEVEL_SW AND SILK': FALSE" in line


def test_timing_diagrams_and_the_rerun_layout_show_the_steps(silk):
    from plclab.viz.from_trace import series
    from plclab.viz.layout import plan

    lane = series(silk, ["HEATER"])[-1]
    assert lane.name == "SFC Washer" and lane.kind == "enum"
    assert [lane.label(v) for _, v in lane.changes()] == [
        "Start", "Fill", "Warming", "Cooling", "Drain", "Start"]
    lanes = [ln.label for ln in plan(silk).lanes]
    assert "step Warming" in lanes and "step Abort" in lanes


def test_a_program_without_a_chart_records_no_lane():
    tr = run("PROGRAM P VAR x AT %QX0.0 : BOOL; END_VAR x := TRUE; END_PROGRAM", "washer",
             "1s", scan="100ms")
    assert "sfc" not in tr.meta and not tr.events_of("sfc_step")
