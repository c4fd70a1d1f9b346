"""The Modbus address map, map files, plant layout and scaling (no network, no pymodbus)."""

from __future__ import annotations

import csv
import json
import subprocess
import sys

import pytest

import plclab
from plclab.errors import PlcError
from plclab.modbus import addressing as A
from plclab.modbus import plantmap as PM
from plclab.modbus.remote_io import counts_from_program, parse_io_url

PROG = """
VAR_GLOBAL g AT %MD4 : REAL; END_VAR
PROGRAM Main
VAR
    sp AT %MW0 : INT; out AT %QW0 : INT; lamp AT %QX0.0 : BOOL;
    ls AT %IX1.2 : BOOL; b AT %IB3 : BYTE; x AT %MX7.2 : BOOL; ain AT %IW10 : INT;
    far AT %MW2000 : INT; plain : INT;
END_VAR
out := sp * 2; lamp := sp > 10;
END_PROGRAM
"""


@pytest.fixture(scope="module")
def plc():
    # a 4 KiB image: %MW2000 is a valid address that lies beyond the Modbus map (1024 bytes)
    return plclab.loads(PROG, image_size=4096)


def test_bits_follow_the_openplc_convention():
    assert A.locate("%QX0.0") == A.Entry("coil", 0, None, 1, "read")
    assert A.locate("%QX1.2").number == 10
    assert A.locate("%QX1023.7").number == 8191
    assert A.locate("%IX0.1") == A.Entry("discrete_input", 1, None, 1, "read")
    assert A.locate("%QX0.3", allow_coil_writes=True).access == "read/force"


def test_words_are_byte_addressed_like_s7():
    # input register n = %IW(2n)
    assert A.locate("%IW0").number == 0
    assert A.locate("%IW2").number == 1
    assert A.locate("%IW10").number == 5
    assert A.locate("%MW0") == A.Entry("holding_register", 0, None, 1, "read/write")
    assert A.locate("%QW2").number == A.HR_OUTPUT_BASE + 1
    assert A.locate("%MD4") == A.Entry("holding_register", 2, None, 2, "read/write")
    assert A.locate("%ML8").words == 4
    # bytes and bits inside registers: even bytes are the high byte
    assert A.locate("%IB3") == A.Entry("input_register", 1, 0, 1, "read")
    assert A.locate("%IB2").bit == 8
    assert A.locate("%MX0.0").bit == 8 and A.locate("%MX1.7").bit == 7
    assert A.locate("%MW1022").number == 511
    assert A.locate("%MW1023") is None and A.locate("%IX1024.0") is None


def test_input_window():
    assert A.input_window("%IX1.2") == A.Entry("coil", A.COIL_INPUT_BASE + 10, None, 1,
                                               "read/write")
    assert A.input_window("%IW4").number == A.HR_INPUT_BASE + 2
    assert A.input_window("%QX0.0") is None


@pytest.mark.parametrize("bad", ["%QX0.8", "%ZW0", "QW0", "%MW2.1", ""])
def test_bad_addresses(bad):
    with pytest.raises(ValueError):
        A.parse_address(bad)


def test_iec_flat_bit_numbers():
    # IEC 61131-3 ed.3 Table 16: %QX75 and %Q75 are output bit 75 (byte 9, bit 3)
    assert A.parse_address("%QX75") == A.parse_address("%Q75") == ("Q", "X", 9, 3)
    assert A.parse_address("%QX0") == ("Q", "X", 0, 0)


def test_map_rows_and_files(plc, tmp_path):
    rows, unmapped = A.map_rows(plc)
    by = {r["name"]: r for r in rows}
    assert set(by) == {"g", "Main.sp", "Main.out", "Main.lamp", "Main.ls", "Main.b", "Main.x",
                       "Main.ain"}
    assert unmapped == ["Main.far AT %MW2000"]
    assert by["Main.lamp"]["table"] == "coil" and by["Main.lamp"]["number"] == 0
    assert by["Main.lamp"]["ref"] == 1
    assert by["Main.ls"]["table"] == "discrete_input" and by["Main.ls"]["number"] == 10
    assert by["Main.ls"]["write_table"] == "coil"
    assert by["Main.ls"]["write_number"] == A.COIL_INPUT_BASE + 10
    assert by["Main.ain"]["number"] == 5 and by["Main.ain"]["type"] == "INT"
    assert by["Main.out"]["number"] == 1024 and by["Main.out"]["access"] == "read"
    assert by["g"]["words"] == 2 and by["g"]["type"] == "REAL"
    assert by["Main.x"]["number"] == 3 and by["Main.x"]["bit"] == 2

    ro_rows, _ = A.map_rows(plc, read_only_inputs=True, allow_coil_writes=True)
    ro = {r["name"]: r for r in ro_rows}
    assert ro["Main.ls"]["write_table"] == "" and ro["Main.lamp"]["access"] == "read/force"

    A.write_map(str(tmp_path / "m.csv"), rows)
    with open(tmp_path / "m.csv", encoding="utf-8") as fh:
        got = list(csv.DictReader(fh))
    assert [r["name"] for r in got] == [r["name"] for r in rows]
    assert list(got[0]) == A.MAP_COLUMNS
    A.write_map(str(tmp_path / "m.json"), rows)
    data = json.loads((tmp_path / "m.json").read_text())
    assert data["device_id"] == 1 and data["variables"] == rows
    with pytest.raises(ValueError):
        A.write_map(str(tmp_path / "m.txt"), rows)

    shared = A.overlaps(plc)
    assert shared == ["g (%MD4) and Main.x (%MX7.2) share bits",
                      "Main.out (%QW0) and Main.lamp (%QX0.0) share bits"]
    text = A.format_map(rows, allow_coil_writes=False, read_only_inputs=False,
                        unmapped=unmapped, shared=shared)
    assert "note: g (%MD4) and Main.x (%MX7.2) share bits" in text
    assert "coil n = %QX(n//8).(n%8)" in text and "register n = %IW(2n)" in text
    assert "Main.far AT %MW2000" in text


def test_scaling_round_trip():
    assert A.to_register(0.0, 0, 2) == 0 and A.to_register(2.0, 0, 2) == 27648
    assert A.from_register(A.to_register(1.234, 0, 2), 0, 2) == pytest.approx(1.234, abs=1e-4)
    assert A.to_register(-1e9, 0, 1) == 0x8000  # clipped to -32768
    assert A.from_register(0xFFFF, 0, 27648) == -1


def test_plant_layout_in_signal_order():
    from plants import get_plant

    plant = get_plant("tank")
    lay = PM.plant_layout(plant)
    assert [s.name for s in lay.di] == ["LS1", "LS2"]
    assert [s.name for s in lay.ir] == ["LEVEL", "LEVEL_MA", "FLOW_IN"]
    assert [s.name for s in lay.coils] == ["PUMP", "FAULT_LAMP"]  # the lamp: level-4-20ma lab
    assert [s.name for s in lay.hr] == ["PUMP_SPEED"]
    assert [s.name for s in lay.panel_hr] == ["VALVE"]
    assert lay.counts() == [2, 3, 2, 1, 0, 1]
    assert PM.plc_address("di", 9) == "%IX1.1" and PM.plc_address("ir", 0) == "%IW64"
    assert PM.plc_address("hr", 1) == "%QW66"
    assert "LS1" in PM.format_plant_map(plant)


def test_local_coupling_keeps_uncovered_actuators():
    from plants import get_plant

    tank = get_plant("tank")
    plc = plclab.loads("""PROGRAM T
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; lvl AT %IW64 : INT; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM""")
    c = PM.PlantCoupling(tank, plc)
    for _ in range(3000):  # 30 s
        c.to_plc()
        plc.scan()
        c.from_plc()
        tank.step(0.01)
    assert tank["PUMP"] is True and tank["PUMP_SPEED"] == 100.0  # not written: not covered
    assert plc["lvl"] > 0
    assert abs(plc["lvl"] - A.to_register(tank["LEVEL"], 0, 2)) < 50


def test_io_urls():
    assert parse_io_url("modbus://127.0.0.1:5021") == ("127.0.0.1", 5021, {}, 1)
    assert parse_io_url("modbus://localhost:1502?di=2&hr=0&unit=3") == (
        "localhost", 1502, {"di": 2, "hr": 0}, 3)
    for bad in ("tcp://127.0.0.1:5021", "modbus://127.0.0.1:99999", "modbus://h:1?di=x",
                "modbus://h:1?foo=1", "modbus://h:1?di=100000"):
        with pytest.raises(PlcError) as e:
            parse_io_url(bad)
        assert e.value.code == "PLC9203"


def test_counts_from_program(plc):
    c = counts_from_program(plclab.loads("""PROGRAM T
VAR a AT %IX0.3 : BOOL; q AT %QX2.0 : BOOL; w AT %IW66 : INT; o AT %QW64 : INT;
    lo AT %IW0 : INT; END_VAR
q := a; o := w;
END_PROGRAM"""))
    assert c == {"di": 4, "ir": 2, "coils": 17, "hr": 1}


def test_import_plclab_does_not_import_pymodbus():
    code = ("import sys, plclab, plclab.modbus, plclab.modbus.addressing, "
            "plclab.modbus.plantmap; plclab.loads('PROGRAM P VAR n : INT; END_VAR n := 1; "
            "END_PROGRAM'); print('pymodbus' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "False"
