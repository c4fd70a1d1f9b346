"""Wiring tables: TOML and Python forms, defaults, and every validation error (PLC4001-4008)."""

from __future__ import annotations

from pathlib import Path

import pytest

import plclab
from plclab.errors import PlcError
from plclab.sim import Simulation, Wiring, default_wiring, load_scenario, load_wiring, run
from plclab.sim.wirings import DEFAULTS, FOLDER

LABS = Path(__file__).resolve().parents[2] / "labs"

TANK = """PROGRAM Main
VAR
  LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; lvl AT %IW64 : INT;
  level_real AT %ID8 : REAL; counts : INT; run : BOOL; sp : REAL; t1 : TON;
  pos AT %QW64 : INT; coil AT %QX0.1 : BOOL;
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
run := M;
END_PROGRAM"""


def plc():
    return plclab.loads(TANK)


def bind(rows, plant="tank"):
    return Simulation(plc(), plant, rows)


def error_of(rows, plant="tank") -> PlcError:
    with pytest.raises(PlcError) as e:
        bind(rows, plant)
    return e.value


def test_python_rows_and_toml_are_the_same_table(tmp_path):
    rows = [
        {"plc": "%IX0.0", "signal": "LS1", "module": "di", "bounce_ms": 2, "filter_ms": 3},
        {"plc": "%IW64", "signal": "LEVEL", "module": "ai", "lo": 0, "hi": 2,
         "signal_range": "4-20mA", "convention": "s7", "noise": 0.002, "seed": 1},
        {"plc": "%QX0.0", "signal": "PUMP", "module": "do", "kind": "relay",
         "description": "pump contactor"},
    ]
    w = Wiring.from_rows(rows, plant="tank")
    f = tmp_path / "w.toml"
    f.write_text(w.to_toml())
    back = load_wiring(f)
    assert back.to_rows() == w.to_rows()
    assert back.plant == "tank" and back.source == str(f)
    assert w[0].params == {"bounce_ms": 2.0, "filter_ms": 3.0}
    assert w[2].description == "pump contactor"
    # [[wiring]] tables are the same
    g = tmp_path / "tables.toml"
    g.write_text('plant = "tank"\n[[wiring]]\nplc = "%ix0.0"\nsignal = "LS1"\nmodule = "di"\n'
                 'bounce_ms = 2\nfilter_ms = "3ms"\n')
    assert load_wiring(g).to_rows()[0] == w.to_rows()[0]  # %ix0.0 -> %IX0.0, "3ms" -> 3.0


@pytest.mark.parametrize("plant", sorted(DEFAULTS))
def test_default_wiring_matches_its_toml_and_binds(plant):
    w = default_wiring(plant)
    toml = load_wiring(FOLDER / f"{plant}.toml")
    assert toml.to_rows() == w.to_rows()
    assert toml.plant == plant
    assert all(r.description for r in w)
    sim = Simulation(plclab.loads("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM"), plant)
    assert len(sim.transfer.channels) == len(w)


def test_the_wiring_tables_and_the_labs_scenario_files_load():
    trivial = "PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM"
    scenarios = sorted(LABS.glob("*/*_scenario.toml"))  # beside the lab they belong to
    assert len(scenarios) >= 3
    for f in scenarios:
        tr = run(trivial, scenario=f, duration="2s")
        assert tr.meta["plant"] == load_scenario(f).plant
    tables = sorted(FOLDER.glob("*.toml"))
    assert {f.stem for f in tables} > set(DEFAULTS)  # a default for each plant, and variants
    for f in tables:
        w = load_wiring(f)
        Simulation(plclab.loads(trivial), w.plant, w)


def test_default_wiring_unknown_plant():
    with pytest.raises(PlcError) as e:
        default_wiring("tnak")
    assert e.value.code == "PLC4020" and "tank" in e.value.message


# --------------------------------------------------------------------------- file errors
def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(PlcError) as e:
        load_wiring(tmp_path / "nope.toml")
    assert e.value.code == "PLC4001" and "no such wiring file" in e.value.message
    bad = tmp_path / "bad.toml"
    bad.write_text('plant = "tank"\nwiring = [\n  { plc = "%IX0.0", signal = LS1 },\n]\n')
    with pytest.raises(PlcError) as e:
        load_wiring(bad)
    assert e.value.code == "PLC4001"
    assert e.value.location.line == 3 and str(bad) in str(e.value)
    with pytest.raises(PlcError) as e:
        Wiring.load(tmp_path)
    assert e.value.code == "PLC4001"
    nowiring = tmp_path / "empty.toml"
    nowiring.write_text('plant = "tank"\n')
    with pytest.raises(PlcError) as e:
        load_wiring(nowiring)
    assert e.value.code == "PLC4005" and "wiring" in e.value.message
    extra = tmp_path / "extra.toml"
    extra.write_text('plant = "tank"\nwirring = []\n')
    with pytest.raises(PlcError) as e:
        load_wiring(extra)
    assert e.value.code == "PLC4005" and "wiring" in e.value.message


def test_errors_point_at_the_row_line_and_key(tmp_path):
    f = tmp_path / "w.toml"
    f.write_text(
        'plant = "tank"\n'
        'wiring = [\n'
        '  { plc = "%IX0.0", signal = "LS1", module = "di" },\n'
        '  # a comment { with a brace\n'
        '  { plc = "%IX0.1", signal = "LS2", module = "di", filtr_ms = 3 },\n'
        '  { plc = "%QX0.0", signal = "PUMP", module = "do", kind = "reed" },\n'
        ']\n')
    with pytest.raises(PlcError) as e:
        load_wiring(f)
    err = e.value
    assert len(err.diagnostics) == 2  # every bad row is reported
    d1, d2 = err.diagnostics
    assert d1.code == "PLC4005" and (d1.location.line, d1.location.col) == (5, 52)
    assert "filter_ms" in d1.message and "wiring row 1" in d1.message  # did you mean
    assert d2.code == "PLC4006" and d2.location.line == 6 and "'transistor'" in d2.message
    assert f"{f}:5:52: error PLC4005" in str(err)


def test_signal_errors_from_a_file_name_the_line(tmp_path):
    f = tmp_path / "w.toml"
    f.write_text('[[wiring]]\nplc = "%IX0.0"\nsignal = "LS1"\nmodule = "di"\n\n'
                 '[[wiring]]\nplc = "%IX0.1"\nsignal = "LS3"\nmodule = "di"\n')
    e = error_of(load_wiring(f))
    assert e.code == "PLC4002" and e.location.line == 8 and "'LS1'" in e.message


# --------------------------------------------------------------------------- row errors
def test_unknown_signal():
    e = error_of([{"plc": "%IX0.0", "signal": "LS3", "module": "di"}])
    assert e.code == "PLC4002"
    assert "Did you mean" in e.message and "LS1" in e.message and "LEVEL" in e.message


@pytest.mark.parametrize("row, words", [
    ({"plc": "%QX0.0", "signal": "LS1", "module": "do"}, "sensor"),  # sensor as output
    ({"plc": "%QX0.1", "signal": "LS2", "module": "direct"}, "sensor"),
    ({"plc": "%IX0.0", "signal": "PUMP", "module": "di"}, "actuator"),  # actuator as input
    ({"plc": "%IX0.0", "signal": "PUMP", "module": "direct"}, "actuator"),
    ({"plc": "%QW64", "signal": "VALVE", "module": "direct"}, "panel"),  # PLC driving a panel
    ({"plc": "%QW64", "signal": "VALVE", "module": "ao"}, "panel"),
])
def test_wrong_direction(row, words):
    e = error_of([row])
    assert e.code == "PLC4003" and words in e.message


@pytest.mark.parametrize("row, words", [
    ({"plc": "%IX0.9", "signal": "LS1", "module": "di"}, "bit 0..7"),
    ({"plc": "%QX0.0", "signal": "LS1", "module": "di"}, "output address"),
    ({"plc": "%IX0.0", "signal": "PUMP", "module": "do"}, "input address"),
    ({"plc": "%IW64", "signal": "LS1", "module": "di"}, "bit address"),
    ({"plc": "%IX0.0", "signal": "LEVEL", "module": "ai"}, "word"),
    ({"plc": "%IB64", "signal": "LEVEL", "module": "ai"}, "word"),
    ({"plc": "%MX0.0", "signal": "LS1", "module": "direct"}, "memory"),
    ({"plc": "%IW2000", "signal": "LEVEL", "module": "ai"}, "beyond the process image"),
    ({"plc": "%IX0", "signal": "LS1", "module": "di"}, "byte.bit"),
    ({"plc": "%ID8", "signal": "LEVEL", "module": "ai"}, "REAL"),  # a REAL is declared there
    ({"plc": "%FOO", "signal": "LS1", "module": "di"}, "not a PLC address"),
    ({"plc": "Main.nosuch", "signal": "LS1", "module": "di"}, "no member nosuch"),
    ({"plc": "nosuch", "signal": "LS1", "module": "di"}, "no variable"),
    ({"plc": "Main.sp", "signal": "LS1", "module": "di"}, "BOOL variable"),
    ({"plc": "Main.run", "signal": "LEVEL", "module": "ai"}, "INT variable"),
    ({"plc": "Main.t1", "signal": "LEVEL", "module": "direct"}, "REAL or integer"),
    ({"plc": "Main.M", "signal": "LS1", "module": "di"}, "located at %QX0.0"),
])
def test_bad_addresses_and_variables(row, words):
    e = error_of([row])
    assert e.code == "PLC4004", e
    assert words in e.message


@pytest.mark.parametrize("row, code, words", [
    ({"plc": "%IX0.0", "signal": "LS1", "module": "dii"}, "PLC4005", "Did you mean 'di'"),
    ({"plc": "%IX0.0", "signal": "LS1", "module": "di", "filter": 3}, "PLC4005", "filter_ms"),
    ({"plc": "%IX0.0", "signal": "LS1", "module": "di", "kind": "relay"}, "PLC4005",
     "belongs to module do"),
    ({"signal": "LS1", "module": "di"}, "PLC4005", "'plc' is missing"),
    ({"plc": "%IX0.0", "module": "di"}, "PLC4005", "'signal' is missing"),
    ({"plc": "%IX0.0", "signal": "LS1", "module": "di", "filter_ms": -1}, "PLC4006", "positive"),
    ({"plc": "%IX0.0", "signal": "LS1", "module": "di", "filter_ms": "fast"}, "PLC4006",
     "not a duration"),
    ({"plc": "%IX0.0", "signal": "LS1", "module": "di", "invert": "yes"}, "PLC4006",
     "true or false"),
    ({"plc": "%IW64", "signal": "LEVEL", "module": "ai", "signal_range": "4-21mA"}, "PLC4006",
     "4-20mA"),
    ({"plc": "%IW64", "signal": "LEVEL", "module": "ai", "bits": 2.5}, "PLC4006",
     "whole number"),
    ({"plc": "%IW64", "signal": "LEVEL", "module": "ai", "convention": "x"}, "PLC4006", "'s7'"),
    ({"plc": "%IW64", "signal": "LEVEL", "module": "ai", "lo": 1, "hi": 1}, "PLC4006", "empty"),
    ({"plc": "%IW64", "signal": "LEVEL", "module": "ai", "bits": 99}, "PLC4006", "bits"),
    ({"plc": "%IW64", "signal": "LS1", "module": "ai"}, "PLC4006", "use di"),
    ({"plc": "%QW64", "signal": "PUMP_SPEED", "module": "do"}, "PLC4006", "module ao"),
    ({"plc": "%IX0.0", "signal": "LEVEL", "module": "di"}, "PLC4006", "threshold"),
    ({"plc": "%IX0.0", "signal": "LS1", "module": "di", "threshold": 1.0}, "PLC4006", "REAL"),
    ({"plc": "%IW64", "signal": "LEVEL", "module": "direct", "invert": True}, "PLC4006",
     "BOOL"),
    ({"plc": "%IX0.0", "signal": "LS1", "module": "di", "bounces": [3, 1]}, "PLC4006", "lo"),
])
def test_bad_modules_and_parameters(row, code, words):
    e = error_of([row])
    assert e.code == code, e
    assert words in e.message


def test_wired_twice():
    e = error_of([{"plc": "%IX0.0", "signal": "LS1", "module": "di"},
                  {"plc": "%IX0.0", "signal": "LS2", "module": "di"}])
    assert e.code == "PLC4007" and "wiring row 0" in e.message
    e = error_of([{"plc": "%IW64", "signal": "LEVEL", "module": "ai"},
                  {"plc": "%IB65", "signal": "LEVEL_MA", "module": "direct"}])
    assert e.code == "PLC4007" and "overlaps" in e.message
    e = error_of([{"plc": "%QX0.0", "signal": "PUMP", "module": "do"},
                  {"plc": "%QX0.1", "signal": "PUMP", "module": "do"}])
    assert e.code == "PLC4007" and "only one output" in e.message
    e = error_of([{"plc": "Main.counts", "signal": "LEVEL", "module": "ai"},
                  {"plc": "main.COUNTS", "signal": "LEVEL_MA", "module": "ai"}])
    assert e.code == "PLC4007"
    # one output may drive... nothing twice, but one input signal may be read twice
    bind([{"plc": "%IW64", "signal": "LEVEL", "module": "ai"},
          {"plc": "Main.sp", "signal": "LEVEL", "module": "direct"}])


def test_wiring_for_another_plant():
    w = default_wiring("motor")
    e = error_of(w, "tank")
    assert e.code == "PLC4008" and "motor" in e.message


def test_all_row_errors_are_reported_together():
    e = error_of([{"plc": "%IX0.0", "signal": "LS9", "module": "di"},
                  {"plc": "%IX0.1", "signal": "LS2", "module": "di"},
                  {"plc": "%QX0.0", "signal": "LS1", "module": "do"}])
    assert [d.code for d in e.diagnostics] == ["PLC4002", "PLC4003"]
    assert "wiring row 2" in e.diagnostics[1].message


def test_not_a_list():
    with pytest.raises(PlcError) as e:
        Wiring.from_rows({"plc": "%IX0.0"})
    assert e.value.code == "PLC4005"
    with pytest.raises(PlcError) as e:
        Wiring.from_rows([42])
    assert e.value.code == "PLC4005"


def test_unwired_located_inputs_are_noted():
    sim = Simulation(plc(), "tank", [{"plc": "%IX0.0", "signal": "LS1", "module": "di"}])
    notes = " ".join(sim.warnings)
    assert "Main.LS2 AT %IX0.1 is not wired" in notes
    assert "Main.M AT %QX0.0 is not wired: it drives nothing" in notes
    assert "%IX0.0" not in notes
