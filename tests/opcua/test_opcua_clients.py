"""``plclab opcua`` judged by independent clients in their own processes (issue 36).

asyncua's command-line tools (``uals``, ``uaread``, ``uawrite``, ``uasubscribe``) and the
asyncua client scripts of ``clients.py`` talk to a ``plclab opcua`` subprocess on a free
loopback port: browse, read with types and timestamps, writes allowed and refused by the access
rules, subscriptions with and without an absolute deadband, quality on a wire break and on a
stopped PLC, alarm acknowledgement, and a bounded load test. Every wait is for a condition, with
a generous timeout: nothing depends on the machine's speed.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("asyncua")

from plclab.modbus._testing import PlclabProcess, free_port, wait_until  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
CLIENTS = HERE / "clients.py"
WAIT = 90.0  # seconds: a ceiling for a loaded machine, never a measured speed
TOOLS = {name: shutil.which(name) for name in ("uals", "uaread", "uawrite", "uasubscribe")}

PROGRAM = """\
TYPE Pair : STRUCT lo : INT; hi : REAL; END_STRUCT; END_TYPE
VAR_GLOBAL g_count : UDINT; END_VAR
PROGRAM Main
VAR
  raw AT %IW2 : INT;
  sp : REAL := 50.0;
  sp1 : LREAL; sp2 : LREAL; sp3 : LREAL; sp4 : LREAL; sp5 : LREAL;
  alarm_bit : BOOL;
  div : INT := 1;
  q : INT;
  pump AT %QX0.0 : BOOL;
  n : DINT;
  small : SINT := -5;
  big : LINT := 123456789012;
  u : USINT := 200;
  w : WORD := 16#BEEF;
  tm : TIME := T#1500ms;
  text : STRING := 'hello';
  arr : ARRAY[1..3] OF INT := [1, 2, 3];
  pair : Pair;
  t1 : TON;
END_VAR
VAR CONSTANT K : INT := 3; END_VAR
n := n + 1;
g_count := g_count + 1;
pump := raw > 100;
pair.lo := raw;
q := 100 / div;
t1(IN := pump, PT := T#1s);
END_PROGRAM
"""

CONFIG = """\
anonymous = "read"
writable = ["Main.raw", "Main.sp", "Main.sp?", "Main.alarm_bit", "Main.div"]

[[user]]
name = "operator"
password = "s3cret"

[[user]]
name = "viewer"
password = "look"
role = "read"
"""

ALARMS = """\
[[alarm]]
id = "HIGH"
text = "the alarm bit is set"
tag = "Main.alarm_bit"
class = "error"
"""


def tool(name: str, url: str, *args: str, user: str | None = None,
         password: str | None = None) -> subprocess.CompletedProcess:
    """One run of an asyncua command-line tool against the server (its own process)."""
    if TOOLS[name] is None:
        pytest.skip(f"{name} is not installed (it comes with asyncua)")
    cmd = [TOOLS[name], "-u", url, "--timeout", "10", *args]
    if user:
        cmd += ["--user", user, "--password", password or ""]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=WAIT)


def read(url: str, node: str, kind: str = "python", **kw) -> str:
    return tool("uaread", url, "-n", node, "-t", kind, **kw).stdout.strip()


def client(*args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, str(CLIENTS), *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def result(proc: subprocess.Popen) -> dict:
    out, err = proc.communicate(timeout=WAIT * 2)
    lines = [ln for ln in out.splitlines() if ln.startswith("{")]
    assert proc.returncode == 0 and lines, f"client failed:\n{out}\n{err[-3000:]}"
    return json.loads(lines[-1])


def start(tmp_path: Path, *args: str) -> tuple[PlclabProcess, str]:
    port = free_port()
    p = PlclabProcess(["opcua", *args, "--port", str(port)], port=port, cwd=str(tmp_path),
                      timeout=WAIT)
    p.start()
    return p, f"opc.tcp://127.0.0.1:{port}"


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    d = tmp_path_factory.mktemp("opcua")
    (d / "main.st").write_text(PROGRAM, encoding="utf-8")
    (d / "opcua.toml").write_text(CONFIG, encoding="utf-8")
    (d / "alarms.toml").write_text(ALARMS, encoding="utf-8")
    p, url = start(d, "main.st", "--config", "opcua.toml", "--alarms", "alarms.toml")
    yield url
    p.stop()
    assert "OPC UA server on" in p.output, p.output


# ---------------------------------------------------------------------- browse and read


def test_browse_shows_globals_programs_instances_and_structures(server):
    r = tool("uals", server, "-n", "ns=2;s=PLC:", "-d", "4")
    assert r.returncode == 0, r.stderr
    out = r.stdout
    for node in ("ns=2;s=PLC:Programs.Main", "ns=2;s=PLC:Globals", "ns=2;s=g_count",
                 "ns=2;s=Main.sp", "ns=2;s=Main.t1.ET", "ns=2;s=Main.t1.Q",
                 "ns=2;s=Main.pair.lo", "ns=2;s=Main.pair.hi", "ns=2;s=PLC:Alarms.HIGH",
                 "ns=2;s=PLC:Status.State"):
        assert node in out, f"{node} not browsed:\n{out}"
    assert "Main.K" in out  # constants are read-only tags, still shown
    assert "__" not in re.sub(r"<[^>]*>", "", out.split("Alarms")[0])  # no compiler internals


@pytest.mark.parametrize("node, vtype, value", [
    ("Main.small", "SByte", "-5"),
    ("Main.big", "Int64", "123456789012"),
    ("Main.u", "Byte", "200"),
    ("Main.w", "UInt16", "48879"),
    ("Main.sp", "Float", "50.0"),
    ("Main.sp1", "Double", "0.0"),
    ("Main.tm", "Double", "1500.0"),     # Duration: milliseconds as a Double
    ("Main.text", "String", "'hello'"),
    ("Main.arr", "Int16", "[1, 2, 3]"),
    ("g_count", "UInt32", None),
    ("Main.t1.Q", "Boolean", "False"),
])
def test_read_maps_each_iec_type(server, node, vtype, value):
    out = read(server, f"ns=2;s={node}", "variant")
    assert f"VariantType.{vtype}:" in out, out
    if value is not None:
        assert f"Value={value}," in out, out


def test_time_is_a_duration_and_arrays_are_arrays(server):
    dtype = tool("uaread", server, "-n", "ns=2;s=Main.tm", "-a", "14").stdout  # DataType
    assert "Identifier=290," in dtype, dtype  # i=290 Duration
    rank = tool("uaread", server, "-n", "ns=2;s=Main.arr", "-a", "15").stdout  # ValueRank
    dims = tool("uaread", server, "-n", "ns=2;s=Main.arr", "-a", "16").stdout  # ArrayDimensions
    assert rank.strip() == "1" and dims.strip() == "[3]", (rank, dims)


def test_values_carry_good_quality_and_plc_clock_timestamps(server):
    def stamp():
        out = read(server, "ns=2;s=Main.n", "datavalue")
        assert "StatusCode=StatusCode(value=0)" in out, out
        m = re.search(r"SourceTimestamp=datetime\.datetime\(([\d, ]+)", out)
        assert m, out
        return tuple(int(x) for x in re.findall(r"\d+", m.group(1)))

    first = stamp()
    assert wait_until(lambda: stamp() > first, WAIT), "the source timestamp does not advance"


# ---------------------------------------------------------------------- writes


def test_write_by_an_operator_reaches_the_program(server):
    r = tool("uawrite", server, "-n", "ns=2;s=Main.raw", "-t", "int16", "150",
             user="operator", password="s3cret")
    assert r.returncode == 0, r.stdout + r.stderr
    # the program computes pump := raw > 100 and pair.lo := raw from the written input
    assert wait_until(lambda: read(server, "ns=2;s=Main.pump") == "True", WAIT)
    assert wait_until(lambda: read(server, "ns=2;s=Main.pair.lo") == "150", WAIT)
    r = tool("uawrite", server, "-n", "ns=2;s=Main.sp", "-t", "float", "42.5",
             user="operator", password="s3cret")
    assert r.returncode == 0, r.stdout + r.stderr
    assert wait_until(lambda: read(server, "ns=2;s=Main.sp") == "42.5", WAIT)


@pytest.mark.parametrize("node, dtype, value, who, refused", [
    ("Main.sp", "float", "1.0", None, "BadUserAccessDenied"),            # anonymous: read only
    ("Main.sp", "float", "1.0", "viewer", "BadUserAccessDenied"),        # a read-only user
    ("Main.sp", "float", "1.0", "intruder", "BadUserAccessDenied"),      # unknown user
    ("Main.pump", "bool", "true", "operator", "BadNotWritable"),         # an output: no rule
    ("Main.n", "int32", "7", "operator", "BadNotWritable"),              # no rule names it
    ("Main.sp", "int32", "7", "operator", "BadTypeMismatch"),            # REAL is a Float
    ("Main.sp", "float", "nan", "operator", "BadOutOfRange"),            # not a finite number
])
def test_write_refused(server, node, dtype, value, who, refused):
    before = read(server, f"ns=2;s={node}")
    password = {"operator": "s3cret", "viewer": "look", "intruder": "x"}.get(who or "")
    r = tool("uawrite", server, "-n", f"ns=2;s={node}", "-t", dtype, value, user=who,
             password=password)
    assert r.returncode != 0 and refused in r.stdout + r.stderr, r.stdout + r.stderr
    if node != "Main.n":  # n counts scans
        assert read(server, f"ns=2;s={node}") == before


# ---------------------------------------------------------------------- subscriptions


def test_uasubscribe_reports_the_changes_of_a_counter(server):
    if TOOLS["uasubscribe"] is None:
        pytest.skip("uasubscribe is not installed")
    proc = subprocess.Popen([TOOLS["uasubscribe"], "-u", server, "-n", "ns=2;s=Main.n"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    values = []
    try:
        end = time.monotonic() + WAIT
        while len(values) < 4 and time.monotonic() < end:
            line = proc.stdout.readline()
            m = re.search(r"DataChangeEvent\(.*?value=(-?\d+),", line)
            if m:
                values.append(int(m.group(1)))
    finally:
        proc.terminate()
        proc.wait(10)
    assert len(values) == 4 and values == sorted(values) and len(set(values)) == 4, values


def test_absolute_deadband_drops_small_changes(server):
    proc = client("deadband", server, "ns=2;s=Main.sp1", "1.0", "10.0")
    try:
        assert wait_until(lambda: proc.stdout.readline().strip() == "READY", WAIT)
        for v in ("0.3", "3.0", "3.5", "10.0"):
            r = tool("uawrite", server, "-n", "ns=2;s=Main.sp1", "-t", "double", v,
                     user="operator", password="s3cret")
            assert r.returncode == 0, r.stdout + r.stderr
            assert wait_until(lambda v=v: read(server, "ns=2;s=Main.sp1") == v, WAIT)
        got = result(proc)
    finally:
        proc.kill() if proc.poll() is None else None
    # the subscription without a filter saw every change; the one with a deadband of 1.0
    # only those that moved more than 1.0 from the last value it reported
    assert got["plain"] == [0.0, 0.3, 3.0, 3.5, 10.0], got
    assert got["deadband"] == [0.0, 3.0, 10.0], got


# ---------------------------------------------------------------------- alarms


def test_alarm_comes_and_an_operator_acknowledges_it(server):
    got = result(client("alarm", server, "operator", "s3cret", "ns=2;s=PLC:Alarms.HIGH",
                        "ns=2;s=Main.alarm_bit"))
    assert got["anonymous_write"] == "BadUserAccessDenied", got
    assert got["came"]["message"] == "I: the alarm bit is set" and got["came"]["severity"] == 800
    assert got["acked_before"] == "Unacknowledged"
    assert got["anonymous_ack"] == "BadUserAccessDenied", got
    assert got["events"][-1] == "IA: the alarm bit is set", got
    assert got["acked_after"] == "Acknowledged"
    assert got["second_ack"] == "BadConditionBranchAlreadyAcked", got


# ---------------------------------------------------------------------- load


def test_load_100_subscriptions_20_clients_every_update_arrives(server):
    nodes = ",".join(f"ns=2;s=Main.sp{i}" for i in range(1, 6))
    steps = 5
    got = result(client("load", server, "operator", "s3cret", "20", nodes, str(steps)))
    assert got["sessions"] == 20 and got["subscriptions"] == 100
    for values in got["values"]:
        # the initial value, then each written value exactly once and in order
        assert values[1:] == [float(k) for k in range(1001, 1001 + steps)], values


# ---------------------------------------------------------------------- quality


def test_a_stopped_plc_makes_every_tag_bad_out_of_service(tmp_path):
    (tmp_path / "main.st").write_text(PROGRAM, encoding="utf-8")
    (tmp_path / "opcua.toml").write_text(CONFIG, encoding="utf-8")
    p, url = start(tmp_path, "main.st", "--config", "opcua.toml")
    try:
        assert "StatusCode(value=0)" in read(url, "ns=2;s=Main.sp", "datavalue")
        r = tool("uawrite", url, "-n", "ns=2;s=Main.div", "-t", "int16", "0",
                 user="operator", password="s3cret")  # 100 / 0: a run-time fault, STOP
        assert r.returncode == 0, r.stdout + r.stderr
        assert wait_until(lambda: "BadOutOfService" in read(url, "ns=2;s=Main.sp",
                                                              "datavalue"), WAIT)
        assert "BadOutOfService" in read(url, "ns=2;s=Main.t1.ET", "datavalue")
        assert read(url, "ns=2;s=PLC:Status.State") != "RUN"
    finally:
        p.stop()
    assert "every tag is BadOutOfService" in p.output and "PLC2" in p.output, p.output


WIRE_BREAK = """\
description = "the level transmitter's cable breaks"

[[action]]
at = "30s"
io_fault = "wire_break"
plc = "%IW66"
description = "the 4-20 mA loop opens"
"""


def test_wire_break_turns_the_input_bad_and_leaves_the_rest_good(tmp_path):
    (tmp_path / "break.toml").write_text(WIRE_BREAK, encoding="utf-8")
    prog = ROOT / "labs" / "water-boiler" / "solution" / "boiler.st"
    p, url = start(tmp_path, str(prog), "--lab", "water-boiler", "--scenario", "break.toml")
    try:
        before = read(url, "ns=2;s=Boiler.LEVEL_RAW", "datavalue")
        t_after = float(read(url, "ns=2;s=PLC:Status.Time"))  # ms of PLC time
        if t_after < 30_000:  # read before the break (a machine this loaded: nearly always)
            assert "StatusCode(value=0)" in before, before
        assert wait_until(lambda: "BadSensorFailure" in read(url, "ns=2;s=Boiler.LEVEL_RAW",
                                                               "datavalue"), WAIT)
        # only the broken input: the level switch on %IX0.0 and the outputs stay Good
        assert "StatusCode(value=0)" in read(url, "ns=2;s=Boiler.LEVEL_MIN", "datavalue")
        assert "StatusCode(value=0)" in read(url, "ns=2;s=Boiler.HEATER", "datavalue")
    finally:
        p.stop()
    assert "OPC UA server on" in p.output


def test_uals_of_the_boiler_lists_its_alarms(tmp_path):
    prog = ROOT / "labs" / "water-boiler" / "solution" / "boiler.st"
    p, url = start(tmp_path, str(prog), "--lab", "water-boiler")
    try:
        out = tool("uals", url, "-n", "ns=2;s=PLC:Alarms").stdout
    finally:
        p.stop()
    assert "ns=2;s=PLC:Alarms.NO_WATER" in out and "ns=2;s=PLC:Alarms.LEVEL_HIGH" in out, out


if os.environ.get("PLCLAB_OPCUA_SHOW"):  # pragma: no cover - prints the closing note
    def test_show(server):
        print(tool("uals", server, "-n", "ns=2;s=PLC:Programs.Main").stdout)
