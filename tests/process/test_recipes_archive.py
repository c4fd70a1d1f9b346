"""Recipes (the juice example: load, save, limits, files, scheduled in a simulation) and tag
logging archives (cycle, on change, CSV, Parquet)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

import plclab
from plclab.errors import PlcError
from plclab.process import Recipe, archive, write_csv, write_parquet
from plclab.trace import Trace

MIX = """PROGRAM Mix
VAR Orange, Water, Sugar, Flavoring : REAL; Total : REAL; END_VAR
Total := Orange + Water;
END_PROGRAM"""


def test_the_juice_records_load_into_the_plc_and_the_program_uses_them():
    plc = plclab.loads(MIX)
    mix = Recipe.juice()
    for rec, total in [("orange_drink", 100.0), ("orange_nectar", 100.0)]:
        mix.load_into(plc, rec)
        plc.scan()
        assert plc["Mix.Total"] == total
    assert plc["Mix.Flavoring"] == pytest.approx(0.4)


def test_save_from_the_plc_makes_a_record_and_round_trips_through_toml(tmp_path):
    plc = plclab.loads(MIX)
    mix = Recipe.juice()
    mix.load_into(plc, "orange_juice")
    plc["Mix.Sugar"] = 2.0
    mix.save_from(plc, "sweet_juice")
    path = tmp_path / "mix.toml"
    mix.save(path)
    back = Recipe.load(path)
    assert back.records == mix.records and back.elements == mix.elements
    assert back.record("sweet_juice")["sugar"] == 2.0


@pytest.mark.parametrize("values, fragment", [
    ({"orange": 120, "water": 5, "sugar": 0.5, "flavoring": 0.1}, "orange = 120 l is outside 0..100"),
    ({"orange": 90, "water": 5, "sugar": 0.5}, "flavoring is missing"),
    ({"orange": 90, "water": 5, "sugar": 0.5, "flavoring": 0.1, "salt": 1}, "salt is not"),
    ({"orange": 90, "water": "a lot", "sugar": 0.5, "flavoring": 0.1}, "not a number"),
])
def test_records_are_checked_against_the_limits_before_anything_is_written(values, fragment):
    plc = plclab.loads(MIX)
    with pytest.raises(PlcError, match=fragment) as e:
        Recipe.juice().load_into(plc, values)
    assert e.value.code == "PLC6040"
    assert plc["Mix.Orange"] == 0.0  # all or nothing


def test_a_value_saved_from_the_plc_outside_the_limits_is_refused():
    plc = plclab.loads(MIX)
    plc["Mix.Sugar"] = 9.0
    with pytest.raises(PlcError, match="sugar = 9 kg is outside 0..5"):
        Recipe.juice().save_from(plc, "too_sweet")


def test_unknown_record_and_variable():
    plc = plclab.loads(MIX)
    with pytest.raises(PlcError) as e:
        Recipe.juice().load_into(plc, "grapefruit")
    assert e.value.code == "PLC6041"
    with pytest.raises(PlcError) as e:
        Recipe.juice("Juice").load_into(plc, "orange_juice")
    assert e.value.code == "PLC6041"


def test_a_scheduled_record_is_loaded_during_a_simulation_and_logged():
    from plclab.sim import Simulation

    plc = plclab.loads("""PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM
PROGRAM Mix
VAR Orange, Water, Sugar, Flavoring : REAL; END_VAR
END_PROGRAM""")
    sim = Simulation(plc, "tank", watch=["Mix.Orange"])
    sim.add_hook(Recipe.juice().schedule(1.0, "orange_drink").schedule(2.0, "orange_nectar"))
    tr = sim.run("3s")
    assert tr.value_at("Mix.Orange", 0.5) == 0.0
    assert tr.value_at("Mix.Orange", 1.5) == 90.0
    assert tr.value_at("Mix.Orange", 2.5) == 70.0
    assert [e.data["record"] for e in tr.events_of("recipe")] == ["orange_drink", "orange_nectar"]


def _trace():
    t = np.arange(8) * 0.25
    return Trace(t, {"T": np.array([20.0, 20.02, 20.5, 20.5, 21.0, 21.0, 21.0, 22.0]),
                     "ON": np.array([0, 0, 1, 1, 1, 0, 0, 0], bool)}, meta={"t_end": 2.0})


@pytest.mark.parametrize("mode, cycle, deadband, expected_t", [
    ("cycle", 0.5, 0.0, [0.0, 0.5, 1.0, 1.5]),
    ("cycle", "1s", 0.0, [0.0, 1.0]),
    ("on_change", 1.0, 0.0, [0.0, 0.25, 0.5, 1.0, 1.75]),
    ("on_change", 1.0, 0.1, [0.0, 0.5, 1.0, 1.75]),
])
def test_cycle_and_on_change_logging(mode, cycle, deadband, expected_t):
    rows = archive(_trace(), ["T"], mode=mode, cycle=cycle, deadband=deadband)
    assert [r.time for r in rows] == expected_t


def test_csv_and_parquet(tmp_path):
    rows = archive(_trace(), ["T", "ON"], mode="on_change")
    assert [(r.time, r.value) for r in rows if r.tag == "ON"] == [(0.0, False), (0.5, True),
                                                                   (1.25, False)]
    with open(write_csv(rows, tmp_path / "a.csv"), newline="") as f:
        got = list(csv.reader(f))
    assert got[0] == ["time_s", "tag", "value"] and len(got) == len(rows) + 1
    pq = pytest.importorskip("pyarrow.parquet", reason="Parquet archives need pyarrow")
    table = pq.read_table(write_parquet(rows, tmp_path / "a.parquet"))
    assert table.num_rows == len(rows) and table.column("tag").to_pylist()[0] == "T"


@pytest.mark.parametrize("kw, fragment", [
    ({"mode": "hourly"}, "mode"), ({"cycle": 0}, "positive"), ({"cycle": "soon"}, "duration"),
    ({"deadband": -1}, "deadband"),
])
def test_bad_archive_settings(kw, fragment):
    with pytest.raises(PlcError, match=fragment) as e:
        archive(_trace(), ["T"], **kw)
    assert e.value.code == "PLC6030"


def test_an_unknown_tag():
    with pytest.raises(PlcError) as e:
        archive(_trace(), ["NOPE"])
    assert e.value.code == "PLC6030"
