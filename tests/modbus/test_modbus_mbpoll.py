"""A real client against a real ``plclab serve`` subprocess: Debian's ``mbpoll``.

mbpoll counts references from 1 (``-r 1`` is coil/register 0); ``-1`` polls once.
"""

from __future__ import annotations

import json
import re
import shutil
import signal
import subprocess

import pytest

pytest.importorskip("pymodbus", reason="pymodbus is not installed: pip install 'plclab[modbus]'")

from plclab.modbus._testing import PlclabProcess, free_port, wait_until  # noqa: E402

MBPOLL = shutil.which("mbpoll")
needs_mbpoll = pytest.mark.skipif(
    MBPOLL is None, reason="mbpoll not found: apt-get install mbpoll (.ci/run installs it)")

PROG = """PROGRAM Main
VAR
    sp AT %MW0 : INT;      (* holding register 0, written by the HMI *)
    out AT %QW2 : INT;     (* holding register 1025 *)
    lamp AT %QX0.0 : BOOL; (* coil 0 *)
    cnt AT %MW4 : INT;     (* holding register 2 *)
END_VAR
out := sp * 2;
lamp := sp > 10;
cnt := cnt + 1;
END_PROGRAM
"""


def mbpoll(port: int, *args: str) -> list[int]:
    """Run mbpoll once; return the values it printed (``[1]: 42`` lines)."""
    cmd = [MBPOLL, "-m", "tcp", "-p", str(port), "-a", "1", "-1", "-o", "2", *args,
           "127.0.0.1"]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=15)
    assert out.returncode == 0, out.stdout + out.stderr
    return [int(v) for v in re.findall(r"^\[\d+\]:\s+(-?\d+)", out.stdout, re.M)]


def mbpoll_write(port: int, *args: str) -> subprocess.CompletedProcess:
    cmd = [MBPOLL, "-m", "tcp", "-p", str(port), "-a", "1", "-o", "2", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=15)


@needs_mbpoll
def test_mbpoll_reads_and_writes_a_running_plc(tmp_path):
    prog = tmp_path / "prog.st"
    prog.write_text(PROG)
    port = free_port()
    map_file = tmp_path / "map.json"
    p = PlclabProcess(["serve", str(prog), "--port", str(port), "--speed", "1",
                       "--map", str(map_file)], port=port)
    with p:
        # coil 0 (reference 1) is FALSE, holding register 0 is 0
        assert mbpoll(port, "-t", "0", "-r", "1", "-c", "1") == [0]
        assert mbpoll(port, "-t", "4", "-r", "1", "-c", "1") == [0]
        # write holding register 0 (= %MW0 = sp) to 21
        w = mbpoll_write(port, "-t", "4", "-r", "1", "127.0.0.1", "21")
        assert w.returncode == 0, w.stdout + w.stderr
        # the program uses it at its next scan: out = %QW2 = holding register 1025
        assert wait_until(lambda: mbpoll(port, "-t", "4", "-r", "1026", "-c", "1") == [42],
                          timeout=30)
        assert mbpoll(port, "-t", "0", "-r", "1", "-c", "1") == [1]
        regs = mbpoll(port, "-t", "4", "-r", "1", "-c", "3")
        assert regs[0] == 21 and regs[2] > 0  # sp, (unused), cnt counting scans
        # discrete inputs and input registers are there (all zero: nothing drives them)
        assert mbpoll(port, "-t", "1", "-r", "1", "-c", "8") == [0] * 8
        assert mbpoll(port, "-t", "3", "-r", "1", "-c", "2") == [0, 0]
        # 0-based with -0: status block, state RUN
        assert mbpoll(port, "-0", "-t", "3", "-r", "1024", "-c", "1") == [1]
        # an illegal address is an exception, reported by mbpoll, and the server lives on
        bad = mbpoll_write(port, "-t", "4", "-r", "700", "-1", "127.0.0.1")
        assert "Illegal data address" in bad.stdout + bad.stderr
        w = mbpoll_write(port, "-t", "0", "-r", "1", "127.0.0.1", "1")  # coils read-only
        assert w.returncode != 0 or "Illegal" in w.stdout + w.stderr
        assert mbpoll(port, "-t", "4", "-r", "1", "-c", "1") == [21]
        rc = p.stop(signal.SIGINT)
    assert rc == 0, p.output
    assert "listening on 127.0.0.1:" in p.output and "stopped:" in p.output
    assert "Traceback" not in p.output
    rows = {r["name"]: r for r in json.loads(map_file.read_text())["variables"]}
    assert rows["Main.lamp"]["table"] == "coil" and rows["Main.lamp"]["number"] == 0
    assert rows["Main.out"]["number"] == 1025 and rows["Main.sp"]["number"] == 0


def test_serve_stops_cleanly_on_sigterm_and_duration(tmp_path):
    prog = tmp_path / "prog.st"
    prog.write_text(PROG)
    port = free_port()
    p = PlclabProcess(["serve", str(prog), "--port", str(port), "--speed", "5"], port=port)
    with p:
        rc = p.stop(signal.SIGTERM)
    assert rc == 0, p.output
    assert "stopped:" in p.output
    # --duration ends by itself; a second server can take the port at once
    p2 = PlclabProcess(["serve", str(prog), "--port", str(port), "--duration", "0.5"],
                       port=port)
    p2.start()
    assert wait_until(lambda: p2.proc is None or p2.proc.poll() is not None, timeout=10)
    assert p2.stop() == 0, p2.output


def test_serve_reports_user_errors(tmp_path):
    prog = tmp_path / "prog.st"
    prog.write_text(PROG)
    p = PlclabProcess(["serve", str(prog), "--port", "70000"])
    p.start()
    wait_until(lambda: p.proc.poll() is not None, timeout=15)
    assert p.stop() == 1 and "PLC9203" in p.output and "Traceback" not in p.output
    p = PlclabProcess(["serve", str(prog), "--map", str(tmp_path / "m.txt"), "--port",
                       str(free_port()), "--duration", "1"])
    p.start()
    wait_until(lambda: p.proc.poll() is not None, timeout=15)
    assert p.stop() == 1 and ".csv or .json" in p.output
