"""The command line: check, test, run, --version, --help; user errors never print tracebacks."""

import subprocess
import sys

import pytest

from plclab.cli import main

GOOD = "PROGRAM P VAR n : INT; t : TON; END_VAR n := n + 1; t(IN := TRUE, PT := T#1s); END_PROGRAM\n"


@pytest.fixture
def files(tmp_path):
    good = tmp_path / "good.st"
    good.write_text(GOOD)
    bad = tmp_path / "bad.st"
    bad.write_text("PROGRAM P VAR n : INT; END_VAR\nn := m;\nn = 1;\nEND_PROGRAM\n")
    tests = tmp_path / "t.st"
    tests.write_text("TEST 'ok' ASSERT_EQ(1 + 1, 2); END_TEST\n"
                     "TEST 'bad' VAR x : INT := 3; END_VAR ASSERT_EQ(x, 4); END_TEST\n")
    return good, bad, tests


def test_check_exit_codes(files, capsys):
    good, bad, _ = files
    assert main(["check", str(good)]) == 0
    assert main(["check", str(bad)]) == 1
    out = capsys.readouterr().out
    assert f"{bad}:2:6: error PLC0100" in out
    assert "PLC0013" in out and "2 error(s)" in out


def test_test_command_summary_line(files, capsys):
    _, _, tests = files
    assert main(["test", str(tests)]) == 1
    out = capsys.readouterr().out.strip().splitlines()
    assert out[-1] == "1 passed, 1 failed"
    assert any("FAIL bad" in line and "3 <> 4" in line for line in out)


def test_run_prints_iec_literals(files, capsys):
    good, _, _ = files
    assert main(["run", str(good), "--cycles", "20", "--cycle-time", "50ms",
                 "--set", "P.n=100", "--print", "P.n,t.ET,t.Q"]) == 0
    assert capsys.readouterr().out.splitlines() == ["P.n = 120", "t.ET = T#950ms",
                                                    "t.Q = FALSE"]


def test_run_errors_are_messages_not_tracebacks(files, capsys):
    good, bad, _ = files
    assert main(["run", str(bad), "--cycles", "1"]) == 1
    assert main(["run", str(good), "--cycles", "1", "--set", "nosuch=1"]) == 1
    assert main(["run", str(good), "--cycles", "1", "--set", "P.n=TRUE"]) == 1
    err = capsys.readouterr().err
    assert "Traceback" not in err and "PLC3001" in err and "PLC3002" in err


def test_version_and_help():
    r = subprocess.run([sys.executable, "-m", "plclab", "--version"], capture_output=True,
                       text=True)
    assert r.returncode == 0 and r.stdout.startswith("plclab ")
    for cmd in ("check", "test", "run"):
        r = subprocess.run([sys.executable, "-m", "plclab", cmd, "--help"], capture_output=True,
                           text=True)
        assert r.returncode == 0 and "usage: plclab " + cmd in r.stdout
