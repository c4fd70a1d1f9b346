"""`plclab check`, `plclab test` and `plclab run` take .il, .ld and .xml files like .st files."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from plclab.cli import main

EXAMPLES = Path(__file__).parent.parent.parent / "examples"


@pytest.mark.parametrize("name", ["tank.il", "motor.ld", "bottle.ld", "motor.xml",
                                  "bottle.xml", "tank_fbd.xml", "project.xml"])
def test_check_accepts_every_language(name, capsys):
    # --no-lint: motor.xml and project.xml are language demos without I/O (PLC0214)
    assert main(["check", "--no-lint", str(EXAMPLES / name)]) == 0
    assert capsys.readouterr().out.strip().endswith("0 error(s), 0 warning(s)")


@pytest.mark.parametrize("name", ["tank.il", "motor.ld", "bottle.ld"])
def test_test_runs_test_blocks_of_il_and_ld_files(name, capsys):
    assert main(["test", str(EXAMPLES / name)]) == 0
    assert capsys.readouterr().out.strip().splitlines()[-1].endswith("passed, 0 failed")


def test_test_with_xml_program_and_st_tests(tmp_path, capsys):
    tests = tmp_path / "t.st"
    tests.write_text("TEST 'xml motor latches'\n  Motor.START := TRUE; Motor();\n"
                     "  Motor.START := FALSE; Motor();\n  ASSERT_TRUE(Motor.MOTOR);\nEND_TEST\n")
    assert main(["test", str(EXAMPLES / "motor.xml"), str(tests)]) == 0
    assert capsys.readouterr().out.strip().splitlines()[-1] == "1 passed, 0 failed"


@pytest.mark.parametrize("name,args,expect", [
    ("tank.il", ["--set", "TankLevel.LS1=FALSE", "--print", "TankLevel.M"], "TankLevel.M = TRUE"),
    ("motor.ld", ["--set", "Motor.START=TRUE", "--print", "Motor.MOTOR"], "Motor.MOTOR = TRUE"),
    ("bottle.xml", ["--set", "Bottle.X2=TRUE", "--print", "Bottle.CYL"], "Bottle.CYL = TRUE"),
])
def test_run_accepts_il_ld_xml(name, args, expect, capsys):
    assert main(["run", str(EXAMPLES / name), "--cycles", "3", *args]) == 0
    assert capsys.readouterr().out.strip() == expect


def test_errors_in_il_and_ld_files_are_messages(tmp_path, capsys):
    il = tmp_path / "bad.il"
    il.write_text("PROGRAM P\nVAR a : BOOL; END_VAR\n  LD a\n  ANDD a\n  ST a\nEND_PROGRAM\n")
    ld = tmp_path / "bad.ld"
    ld.write_text("PROGRAM P\nVAR a : BOOL; END_VAR\n|   a        a |\n|---[ ]  ----( )|\n"
                  "END_PROGRAM\n")
    xml = tmp_path / "bad.xml"
    xml.write_text("<project xmlns='http://www.plcopen.org/xml/tc6_0201'><types>")
    assert main(["check", str(il), str(ld), str(xml)]) == 1
    out = capsys.readouterr().out
    assert f"{il}:4:3: error PLC0141" in out
    assert f"{ld}:4:8: error PLC0160" in out
    assert f"{xml}:1:" in out and "PLC0180" in out
    assert main(["run", str(il), "--cycles", "1"]) == 1
    err = capsys.readouterr().err
    assert "PLC0141" in err and "Traceback" not in err


def test_unknown_extension_is_explained(tmp_path, capsys):
    f = tmp_path / "prog.sfc"
    f.write_text("x")
    assert main(["check", str(f)]) == 1
    assert ".il, .ld" in capsys.readouterr().err


def test_subprocess_round_trip(tmp_path):
    target = tmp_path / "motor.ld"
    shutil.copy(EXAMPLES / "motor.ld", target)
    r = subprocess.run([sys.executable, "-m", "plclab", "run", str(target), "--cycles", "2",
                        "--set", "Motor.START=TRUE", "--print", "Motor.MOTOR"],
                       capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip() == "Motor.MOTOR = TRUE"
