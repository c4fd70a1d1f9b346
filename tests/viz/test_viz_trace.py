"""Recordings and exports of real simulation runs; rerun stays optional."""

import subprocess
import sys
import textwrap

import pytest

import plclab.sim as sim
from plclab.cli import main
from plclab.errors import PlcError

TANK = """PROGRAM P VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2); END_PROGRAM"""
CHATTER = TANK.replace("((NOT LS1) OR M) AND (NOT LS2)", "NOT LS1")


@pytest.fixture(scope="module")
def tank_trace():
    return sim.run(CHATTER, plant="tank", duration="4min")


def test_rrd_has_the_expected_entities(tank_trace, tmp_path):
    pytest.importorskip("rerun")
    from plclab.viz import to_rerun
    from plclab.viz.recording import read_entity_paths

    path = to_rerun(tank_trace, tmp_path / "tank.rrd", scan=True)
    paths = read_entity_paths(path)
    for p in ("/plots/m/LEVEL", "/plots/m/limits/3_LS1", "/plots/m/limits/2_LS2",
              "/digital/03_PUMP", "/digital/01_LS1", "/events", "/summary", "/plant/static/tank",
              "/plant/water", "/scan/duration_us", "/plots/edges/markers/PUMP_chatter",
              "/digital/03_PUMP_chatter"):
        assert p in paths, p
    assert "/scan/duration_us" not in read_entity_paths(to_rerun(tank_trace, tmp_path / "b.rrd"))


def test_chatter_becomes_warning_events(tank_trace):
    from plclab.viz.from_trace import chatter_events

    evs = chatter_events(tank_trace)
    assert evs and all(e.level == "WARN" and e.kind == "chatter" for e in evs)
    assert {e.source for e in evs} >= {"PUMP"}


def test_conveyor_bottles_in_the_2d_view(tmp_path):
    pytest.importorskip("rerun")
    pytest.importorskip("pymunk")
    from plclab.viz import to_rerun
    from plclab.viz.recording import read_entity_paths

    prog = """PROGRAM B VAR X1 AT %IX0.2 : BOOL; X2 AT %IX0.3 : BOOL; C AT %QX0.0 : BOOL;
    R AT %QX0.1 : BOOL; END_VAR C := TRUE; R := X2 AND NOT X1; END_PROGRAM"""
    tr = sim.run(prog, plant="conveyor", duration="20s")  # bottles are recorded by default
    paths = read_entity_paths(to_rerun(tr, tmp_path / "c.rrd"))
    assert "/plant/bottles/upright" in paths and "/plant/static/belt" in paths
    assert "/plant/counters" in paths


def test_sim_command_exports_everything(tmp_path, capsys):
    pytest.importorskip("rerun")
    prog = tmp_path / "tank.st"
    prog.write_text(TANK)
    out = {k: tmp_path / f"o.{k}" for k in ("rrd", "vcd", "json", "svg", "npz")}
    rc = main(["sim", "tank", str(prog), "--duration", "2min", "--rrd", str(out["rrd"]),
               "--vcd", str(out["vcd"]), "--wavedrom", str(out["json"]), "--png",
               str(out["svg"]), "--signals", "LEVEL,PUMP,LS1,LS2", "--window", "0s..60s",
               "--trace", str(out["npz"])])
    assert rc == 0
    for p in out.values():
        assert p.exists() and p.stat().st_size > 0
    svg = out["svg"].read_text()
    # the student's variable and its address (the program calls the pump's output M), one
    # row for the plant side (PUMP) and the PLC side (%QX0.0) of the wire
    for label in (">LEVEL [m]<", ">M %QX0.0<", ">LS1 %IX0.0<"):
        assert label in svg
    assert ">PUMP %QX0.0<" not in svg and ">%QX0.0<" not in svg
    rc = main(["view", str(out["npz"]), "--report", "--vcd", str(tmp_path / "v.vcd"),
               "--png", str(tmp_path / "v.svg"), "--signals", "LEVEL,PUMP,LS1,LS2"])
    assert rc == 0
    assert "Relay / output switching" in capsys.readouterr().out
    seen = (tmp_path / "v.svg").read_text()  # the saved trace keeps the student's names
    assert ">M %QX0.0<" in seen and ">LS1 %IX0.0<" in seen and ">PUMP %QX0.0<" not in seen


def test_vcd_of_a_trace_matches_it(tank_trace, tmp_path):
    vcdvcd = pytest.importorskip("vcdvcd")
    pytest.importorskip("vcd")
    from plclab.viz.exports import write_vcd
    from plclab.viz.from_trace import series

    ss = series(tank_trace, ["PUMP", "LEVEL", "%IW64"])
    v = vcdvcd.VCDVCD(str(write_vcd(ss, tmp_path / "t.vcd", timescale_us=1000)))
    pump = v["plclab.PUMP"].tv
    assert len(pump) == len(ss[0].changes())
    for ts, raw in pump:
        assert bool(int(raw)) == bool(tank_trace.value_at("PUMP", ts / 1000))


def test_window_parsing():
    from plclab.viz.from_trace import parse_window

    assert parse_window("0s..20s") == (0.0, 20.0)
    assert parse_window("1min..") == (60.0, None)
    with pytest.raises(PlcError):
        parse_window("20s..5s")


def test_core_and_sim_run_without_rerun():
    code = textwrap.dedent("""
        import sys
        sys.modules['rerun'] = None          # as if rerun-sdk were not installed
        import plclab, plclab.sim, plclab.viz
        from plclab.errors import PlcError
        tr = plclab.sim.run('''%s''', plant='tank', duration='30s')
        try:
            plclab.viz.to_rerun(tr, 'x.rrd')
        except PlcError as e:
            print(e.code)
    """) % TANK
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "PLC3005"


def test_live_streaming_equals_the_finished_run(tmp_path):
    """run_live streams chunk by chunk (here into a file instead of a viewer): the trace is the
    same as a plain run and the recording has every entity."""
    pytest.importorskip("rerun")
    from plclab.runtime.plc import Plc  # noqa: F401
    from plclab.sim import Simulation, load_plc
    from plclab.viz.live import run_live
    from plclab.viz.recording import read_entity_paths

    live_sim = Simulation(load_plc(TANK), "tank")
    tr_live = run_live(live_sim, "90s", spawn=False, path=tmp_path / "live.rrd", chunks=9)
    tr_plain = sim.run(TANK, plant="tank", duration="90s")
    assert tr_live.equals(tr_plain)
    paths = read_entity_paths(tmp_path / "live.rrd")
    assert {"/plots/m/LEVEL", "/digital/03_PUMP", "/summary", "/plant/water"} <= paths
