"""``plclab sim`` and ``plclab plants``: summaries, files, and errors without tracebacks."""

from __future__ import annotations

import subprocess
import sys

import pytest

from plclab.cli import main
from plclab.trace import Trace

TANK = """PROGRAM TankLevel
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; spare AT %IX0.7 : BOOL;
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2) AND NOT spare;
END_PROGRAM
"""


@pytest.fixture
def prog(tmp_path):
    f = tmp_path / "tank.st"
    f.write_text(TANK)
    return f


def test_sim_prints_a_summary_and_writes_files(prog, tmp_path, capsys):
    npz = tmp_path / "out.npz"
    csvf = tmp_path / "out.csv"
    rc = main(["sim", "tank", str(prog), "--duration", "15min", "--watch", "M",
               "--trace", str(npz), "--csv", str(csvf)])
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert "tank: 15min simulated" in out and "90000 scans of 10ms" in out
    assert "wiring: default for tank (4 rows)" in out
    assert "relay" in out and "first at 0.020 s" in out
    assert "LEVEL" in out and "final values" in out
    assert "TankLevel.spare AT %IX0.7 is not wired" in err
    tr = Trace.load(npz)
    assert tr.t_end == 900.0 and "M" in tr.names
    assert csvf.read_text().splitlines()[0].startswith("time,PUMP,")


def test_sim_with_scenario_wiring_and_options(prog, tmp_path, capsys):
    sc = tmp_path / "sc.toml"
    sc.write_text('duration = "2min"\n[[action]]\nat = "30s"\nfault = "leak"\n'
                  '[[action]]\nat = "60s"\nset = "VALVE"\nvalue = 20\n')
    rc = main(["sim", "tank", str(prog), "--scenario", str(sc), "--seed", "7", "--scan",
               "T#20ms", "--param", "area=2.0", "--events", "--until", "t > 90",
               "--decimate", "5", "--wiring", "plclab/sim/wirings/tank_vfd.toml"])
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert "seed 7" in out and "scans of 20ms" in out and "until 't > 90'" in out
    assert "fault_injected" in out and "set VALVE := 20" in out
    assert "tank_vfd.toml (5 rows)" in out


@pytest.mark.parametrize("args, code", [
    (["sim", "tnak", "PROG"], "PLC4020"),
    (["sim", "tank", "PROG", "--duration", "ten minutes"], "PLC4012"),
    (["sim", "tank", "PROG", "--wiring", "nope.toml"], "PLC4001"),
    (["sim", "tank", "PROG", "--watch", "nosuch"], "PLC4020"),
    (["sim", "tank", "PROG", "--until", "LEVEL >"], "PLC4013"),
    (["sim", "tank", "PROG", "--param", "area"], "PLC4020"),
    (["sim", "tank", "missing.st"], "PLC3003"),
    (["plants", "tnak"], "PLC4020"),
])
def test_errors_are_messages(prog, capsys, args, code):
    args = [str(prog) if a == "PROG" else a for a in args]
    assert main(args) == 1
    err = capsys.readouterr().err
    assert code in err and "Traceback" not in err


def test_plants_lists_every_plant_and_details_one(capsys):
    assert main(["plants"]) == 0
    out = capsys.readouterr().out
    for name in ("motor", "tank", "sump", "heater", "conveyor", "ventilation", "press", "washer",
                 "axes", "crossing"):
        assert f"{name} — " in out
    assert "LEVEL          sensor    real  m      0..2" in out
    assert main(["plants", "tank"]) == 0
    out = capsys.readouterr().out
    assert "faults:" in out and "ls1_stuck_off" in out and "default wiring" in out
    assert "%IW64      LEVEL          ai" in out


def test_help_lists_the_commands():
    r = subprocess.run([sys.executable, "-m", "plclab", "--help"], capture_output=True,
                       text=True, check=True)
    assert "sim" in r.stdout and "plants" in r.stdout


def test_sim_hands_the_trace_to_viz(prog, tmp_path, capsys):
    pytest.importorskip("vcd")
    out = tmp_path / "run.vcd"
    rc = main(["sim", "tank", str(prog), "--duration", "1min", "--vcd", str(out),
               "--signals", "LS1,PUMP,%QX0.0", "--window", "0s..30s"])
    assert rc == 0, capsys.readouterr().err
    assert out.exists() and "$var" in out.read_text()
