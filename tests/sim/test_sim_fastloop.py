"""The fused simulation loop (ADR 0032) gives the trace of the plain loop, scan for scan."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import plclab
from plclab.sim import Scenario, Simulation, fastloop

TANK = """
PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; LV AT %IW64 : INT;
    n : INT; d : INT := 1; r : REAL; tm : TON; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
n := n + 1; r := INT_TO_REAL(LV) / 27648.0;
tm(IN := M, PT := T#2s);
IF n > 1500 THEN n := 10 / (d - 1); END_IF;
END_PROGRAM
"""

CONVEYOR = """
PROGRAM Line
VAR START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL; X1 AT %IX0.2 : BOOL; X2 AT %IX0.3 : BOOL;
    CONVEYOR AT %QX0.0 : BOOL; REJECT AT %QX0.1 : BOOL; END_VAR
CONVEYOR := (START OR CONVEYOR) AND STOP;
REJECT := X2 AND NOT X1;
END_PROGRAM
"""

NOISY = [
    {"plc": "%IX0.0", "signal": "LS1", "module": "di", "bounce_ms": 4.0, "filter_ms": 3.0},
    {"plc": "%IX0.1", "signal": "LS2", "module": "di", "bounce_ms": 2.0},
    {"plc": "%QX0.0", "signal": "PUMP", "module": "do", "kind": "relay", "close_ms": 15,
     "open_ms": 8},
    {"plc": "%IW64", "signal": "LEVEL", "module": "ai", "lo": 0.0, "hi": 2.0, "noise": 0.01,
     "tau": 0.05},
]


def _same(a: Any, b: Any) -> None:
    np.testing.assert_array_equal(a.time, b.time)
    assert list(a.columns) == list(b.columns)
    for name in a.columns:
        np.testing.assert_array_equal(a.columns[name], b.columns[name], err_msg=name)
        assert a.columns[name].dtype == b.columns[name].dtype
    assert [repr(e) for e in a.events] == [repr(e) for e in b.events]
    assert a.edges.keys() == b.edges.keys()
    for k in a.edges:
        np.testing.assert_array_equal(a.edges[k][0], b.edges[k][0])
        np.testing.assert_array_equal(a.edges[k][1], b.edges[k][1])
    assert a.meta == b.meta
    assert len(a.wall["scan_s"]) == len(b.wall["scan_s"])


def _both(make: Any, *runs: tuple[str, Any]) -> tuple[Any, Any]:
    out = []
    for enabled in (False, True):
        fastloop.ENABLED = enabled
        try:
            sim = make()
            tr = None
            for how, arg in runs:
                if how == "step":
                    sim.step(arg)
                else:
                    tr = sim.run(arg)
            out.append((sim.trace if tr is None else tr, sim))
        finally:
            fastloop.ENABLED = True
    (a, sa), (b, sb) = out
    _same(a, b)
    assert sa.k == sb.k and sa.plant.time == sb.plant.time
    return sa, sb


def test_tank_default_wiring_is_fused() -> None:
    sa, sb = _both(lambda: Simulation(plclab.loads(TANK), "tank", seed=2,
                                      plant_params={"area": 0.2}), ("run", "20s"))
    assert sa._fast is None and sb._fast is not None  # the fused loop ran
    assert "L_adv(L_h)" in sb._fast[1].source  # the tank's step is inline


def test_faults_ramps_io_faults_forcing_and_a_plc_fault() -> None:
    sc = (Scenario().fault("leak", at="5s").set("VALVE", 40.0, at="8s")
          .ramp("VALVE", 90.0, at="10s", over="2s").fault("ls1_stuck_off", at="13s", hold="1s")
          .io_fault("%IW64", "wire_break", at="15s").io_clear("%IW64", at="16s")
          .io_fault("%IX0.1", "stuck_1", at="17s").io_clear("%IX0.1", at="18s")
          .force("%IX0.0", True, at="19s").unforce("%IX0.0", at="20s")
          .var("Main.d", 1, at="21s"))

    def make() -> Simulation:
        return Simulation(plclab.loads(TANK), "tank", wiring=NOISY, scenario=sc, seed=5,
                          watch=["Main.n", "Main.r", "tm.ET"], plant_params={"area": 0.2})

    sa, _ = _both(make, ("run", "40s"))
    kinds = {e.kind for e in sa.events}
    assert {"plc_fault", "relay"} <= kinds  # the program faulted at scan 1500


@pytest.mark.parametrize("decimate", [1, 3])
def test_decimate_substeps_and_step_by_step(decimate: int) -> None:
    def make() -> Simulation:
        return Simulation(plclab.loads(TANK), "tank", seed=3, decimate=decimate,
                          watch=["Main.n"], plant_params={"area": 0.2, "max_dt": 0.004})

    _, sb = _both(make, ("step", 1), ("step", 7), ("run", "3s"), ("step", 2), ("run", "5s"))
    assert sb.substeps == 3


def test_until_and_snapshot() -> None:
    _both(lambda: Simulation(plclab.loads(TANK), "tank", seed=1, snapshot=True,
                             plant_params={"area": 0.2}), ("run", "5s"),
          ("step", 300))
    fastloop.ENABLED = True
    sim = Simulation(plclab.loads(TANK), "tank", plant_params={"area": 0.2})
    sim.run("60s", until="Main.n > 700")
    assert sim.k == 701 and sim.stop_reason


def test_conveyor_with_bottles() -> None:
    def make() -> Simulation:
        sc = Scenario().press("START", at="0.5s")
        return Simulation(plclab.loads(CONVEYOR), "conveyor", scenario=sc,
                          plant_params={"belt_length": 4.0, "feed_pitch": 0.35})

    _both(make, ("run", "12s"))


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**16), times=st.lists(st.integers(1, 400), min_size=1, max_size=4),
       valve=st.floats(0.0, 100.0))
def test_random_scenarios(seed: int, times: list[int], valve: float) -> None:
    sc = Scenario()
    for i, t in enumerate(sorted(times)):
        sc = sc.set("VALVE", valve if i % 2 else 100.0 - valve, at=f"{t * 10}ms")
    _both(lambda: Simulation(plclab.loads(TANK), "tank", wiring=NOISY, seed=seed, scenario=sc,
                             plant_params={"area": 0.2}), ("run", "5s"))
