"""The command line around plclab.scada: plclab run --watch, plclab sim --watch-table/--alarms,
plclab panel's arguments; errors are PlcErrors with codes, not tracebacks."""

from __future__ import annotations

import pytest

from plclab.cli import main
from plclab.trace import Trace

TANK = """PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; n : INT; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2); n := n + 1;
END_PROGRAM
"""


@pytest.fixture
def files(tmp_path):
    prog = tmp_path / "tank.st"
    prog.write_text(TANK)
    table = tmp_path / "watch.toml"
    table.write_text('trigger = "scan_start"\n[[row]]\nname = "Main.n"\nformat = "hex"\n'
                     '[[row]]\nname = "%IX0.0"\nmodify = true\n')
    alarms = tmp_path / "alarms.toml"
    alarms.write_text('[[alarm]]\nid = "HIGH"\ntext = "level above 1.2 m"\ntag = "LEVEL"\n'
                      'kind = "H"\nlimit = 1.2\ndeadband = 0.05\nclass = "error"\n')
    return prog, table, alarms


def test_run_with_a_watch_table_prints_its_samples(files, capsys):
    prog, table, _ = files
    assert main(["run", str(prog), "--cycles", "3", "--watch", str(table)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "watch table watch: 3 sample(s) at scan_start:"
    assert out[1].split() == ["t", "(s)", "scan", "Main.n", "%IX0.0"]
    assert out[2].split() == ["0", "0", "16#0000", "TRUE"]  # modified once, at scan start
    assert out[3].split() == ["0.01", "1", "16#0001", "FALSE"]


def test_sim_records_the_alarm_log_and_the_watch_table(files, tmp_path, capsys):
    prog, table, alarms = files
    npz = tmp_path / "run.npz"
    assert main(["sim", "tank", str(prog), "--duration", "90s", "--param", "area=0.2",
                 "--alarms", str(alarms), "--watch-table", str(table), "--trace",
                 str(npz)]) == 0
    out = capsys.readouterr().out
    assert "alarm log (" in out and "HIGH         I    error" in out
    assert "watch table watch (scan_start, 9000 samples), last:" in out
    tr = Trace.load(npz)
    assert tr.events_of("alarm")[0].data["state"] == "I"
    assert "Main.n@scan_start" in tr.names


@pytest.mark.parametrize("args, code", [
    (["run", "{prog}", "--cycles", "1", "--watch", "{tmp}/nope.toml"], "PLC6010"),
    (["sim", "tank", "{prog}", "--duration", "1s", "--alarms", "{tmp}/nope.toml"], "PLC6020"),
    (["panel", "{prog}"], "PLC6050"),
])
def test_errors_name_their_code(files, tmp_path, capsys, args, code):
    prog = files[0]
    argv = [a.format(prog=prog, tmp=tmp_path) for a in args]
    assert main(argv) != 0
    err = capsys.readouterr().err
    assert code in err and "Traceback" not in err


def test_serve_samples_a_watch_table_on_the_live_plc(files, capsys):
    pytest.importorskip("pymodbus", reason="plclab serve needs pymodbus")
    prog, table, _ = files
    import socket

    with socket.socket() as sock:  # a free port
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    assert main(["serve", str(prog), "--port", str(port), "--duration", "0.3", "--watch",
                 str(table)]) == 0
    out = capsys.readouterr().out
    head = next(line for line in out.splitlines() if line.startswith("watch table watch:"))
    assert "sample(s) at scan_start" in head
