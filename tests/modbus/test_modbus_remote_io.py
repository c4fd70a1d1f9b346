"""Remote I/O: a plant served over Modbus (``plclab plant-serve``) and the PLC polling it.

Everything on 127.0.0.1, on free ports; every server is stopped at the end of its test.
"""

from __future__ import annotations

import signal

import pytest

pytest.importorskip("pymodbus", reason="pymodbus is not installed: pip install 'plclab[modbus]'")

from pymodbus.client import ModbusTcpClient  # noqa: E402

import plclab  # noqa: E402
from plclab.modbus import addressing as A  # noqa: E402
from plclab.modbus._testing import PlclabProcess, free_port, wait_until  # noqa: E402
from plclab.modbus.plant_server import PlantServer  # noqa: E402
from plclab.modbus.server import BackgroundServer  # noqa: E402

TANK = """PROGRAM TankLevel
VAR
    LS1 AT %IX0.0 : BOOL;    (* plant discrete input 0 *)
    LS2 AT %IX0.1 : BOOL;    (* plant discrete input 1 *)
    M   AT %QX0.0 : BOOL;    (* plant coil 0: PUMP *)
    level AT %IW64 : INT;    (* plant input register 0: LEVEL, 0..2 m = 0..27648 *)
    IO_OK : BOOL;            (* set by plclab: remote I/O answers *)
    ok AT %QX0.1 : BOOL;
    n AT %MD4 : DINT;        (* scan counter *)
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
ok := IO_OK;
n := n + 1;
END_PROGRAM
"""


def client(port: int) -> ModbusTcpClient:
    c = ModbusTcpClient("127.0.0.1", port=port, timeout=2, retries=0)
    assert c.connect()
    return c


def status(c: ModbusTcpClient) -> list[int]:
    return c.read_input_registers(A.IR_STATUS_BASE, count=A.STATUS_COUNT).registers


def counter(c: ModbusTcpClient) -> int:
    hi, lo = c.read_holding_registers(2, count=2).registers  # %MD4
    return hi << 16 | lo


def test_plant_server_map():
    from plants import get_plant

    tank = get_plant("tank", level0=1.0)
    port = free_port()
    with BackgroundServer(PlantServer(tank, port=port, speed=1.0)):
        c = client(port)
        try:
            assert c.read_discrete_inputs(0, count=2).bits[:2] == [True, False]
            level = c.read_input_registers(0, count=3).registers
            assert abs(A.from_register(level[0], 0, 2) - 1.0) < 0.01
            info = c.read_input_registers(1000, count=8).registers
            assert info[:6] == [2, 3, 2, 1, 0, 1]  # coils: PUMP, FAULT_LAMP
            assert not c.write_coil(0, True).isError()
            assert c.read_coils(0).bits[0] is True
            assert not c.write_register(0, A.to_register(50, 0, 100)).isError()
            assert not c.write_register(1000, A.to_register(25, 0, 100)).isError()  # VALVE
            assert c.read_coils(2).isError() and c.read_discrete_inputs(2).isError()
            assert c.read_input_registers(3).isError() and c.read_holding_registers(1).isError()
            assert c.write_registers(0, [1, 2]).isError()  # HR 1 does not exist
        finally:
            c.close()
    assert tank["PUMP"] is True and tank["PUMP_SPEED"] == pytest.approx(50, abs=0.01)
    assert tank["VALVE"] == pytest.approx(25, abs=0.01)


def test_remote_io_loses_and_regains_the_plant(tmp_path):
    plant_port, plc_port = free_port(), free_port()
    plant_args = ["plant-serve", "tank", "--port", str(plant_port), "--param", "level0=1.0"]
    plc = plclab.loads(TANK)
    messages: list[str] = []
    srv = BackgroundServer(plc, port=plc_port, speed=1.0,
                           io=f"modbus://127.0.0.1:{plant_port}", io_period=0.02,
                           # 2 s: a loaded machine's slow answer is not a lost plant (a
                           # stopped plant refuses the connection at once)
                           io_timeout=2.0, io_status="%IX10.0", on_message=messages.append)
    plant = PlclabProcess(plant_args, port=plant_port).start()
    try:
        with srv:
            c = client(plc_port)
            try:
                # connected: IO_OK TRUE, inputs from the plant (level 1 m: LS1 on, LS2 off)
                assert wait_until(lambda: status(c)[5] == 1 and c.read_coils(1).bits[0],
                                  timeout=30)
                assert c.read_discrete_inputs(0, count=2).bits[:2] == [True, False]
                assert c.read_discrete_inputs(80).bits[0] is True  # --io-status %IX10.0
                level = c.read_input_registers(32).registers[0]  # %IW64
                assert abs(A.from_register(level, 0, 2) - 1.0) < 0.05
                # the plant goes away
                assert plant.stop(signal.SIGTERM) == 0
                assert wait_until(lambda: status(c)[5] == 0, timeout=30)
                assert wait_until(lambda: not c.read_coils(1).bits[0], timeout=30)  # IO_OK
                assert c.read_discrete_inputs(80).bits[0] is False
                n_lost = counter(c)
                held = c.read_input_registers(32).registers[0]
                # the level fell meanwhile, by how much depends on the machine's load
                assert 0 < A.from_register(held, 0, 2) <= A.from_register(level, 0, 2) + 0.05
                # the PLC keeps scanning; the inputs keep their last values
                assert wait_until(lambda: counter(c) > n_lost + 20, timeout=30)
                assert c.read_discrete_inputs(0, count=2).bits[:2] == [True, False]
                assert c.read_input_registers(32).registers[0] == held
                assert status(c)[0] == 1
                # the plant comes back on the same port
                plant = PlclabProcess(plant_args, port=plant_port).start()
                assert wait_until(lambda: status(c)[5] == 1, timeout=30)
                assert wait_until(lambda: c.read_coils(1).bits[0], timeout=30)
                assert counter(c) > n_lost + 20  # no restart: the counter went on
            finally:
                c.close()
    finally:
        plant.stop()
    assert plc.state == "RUN" and plc["n"] > 40
    # lost, then regained (a loaded machine may log another loss after that; never none)
    first_loss = next(i for i, m in enumerate(messages) if "lost" in m)
    assert any(m.endswith("OK") for m in messages[first_loss + 1:]), messages


def test_closed_loop_over_modbus(tmp_path):
    """Two-position level control: the tank as remote I/O, the PLC 50 x faster than real time.

    A simulated tank of 0.25 m2 cycles between LS1 (0.5 m) and LS2 (1.5 m) in about 200 s,
    so 8 wall seconds at 50 x (400 s) show the first fill and one whole cycle.
    """
    prog = tmp_path / "tank.st"
    prog.write_text(TANK)
    plant_port, plc_port = free_port(), free_port()
    plant = PlclabProcess(["plant-serve", "tank", "--port", str(plant_port), "--speed", "50",
                           "--param", "area=0.25"], port=plant_port)
    plc = PlclabProcess(["serve", str(prog), "--port", str(plc_port), "--speed", "50",
                         "--io", f"modbus://127.0.0.1:{plant_port}"], port=plc_port)
    levels, pump = [], []
    with plant, plc:
        p, c = client(plant_port), client(plc_port)
        try:
            phase = {"full": False, "low": False}

            def sample():  # done after: full, drained to LS1, pump on again
                levels.append(A.from_register(p.read_input_registers(0).registers[0], 0, 2))
                pump.append(p.read_coils(0).bits[0])
                phase["full"] = phase["full"] or levels[-1] >= 1.45
                phase["low"] = phase["low"] or (phase["full"] and levels[-1] < 0.6)
                return phase["low"] and pump[-1] and levels[-1] > 0.6

            assert wait_until(sample, timeout=15, interval=0.1), (levels, pump)
            st = status(c)
        finally:
            p.close()
            c.close()
        assert plc.stop() == 0 and plant.stop() == 0
    assert st[0] == 1 and st[5] == 1
    assert True in pump and False in pump
    first_full = next(i for i, x in enumerate(levels) if x >= 1.45)
    after = levels[first_full:]
    # The level stays between the switches, give or take what it moves while the loop reacts:
    # the plant runs 50 x faster than the wall clock, so a loaded machine that delays a poll
    # by a tenth of a second lets the level move several centimetres. The allowance is
    # measured, not guessed: one and a half of the largest move between two of the test's own
    # samples (each at least 0.1 s apart, longer than a poll of the loop), at least 5 cm. A
    # controller that misses a switch still fails (it drains to empty or spills at the rim).
    steps = [b - a for a, b in zip(levels, levels[1:], strict=False)]
    slack_down = max(0.05, 1.5 * max((-d for d in steps if d < 0), default=0.0))
    slack_up = max(0.1, 1.5 * max((d for d in steps if d > 0), default=0.0))
    assert min(after) > 0.5 - slack_down and max(levels) < 1.5 + slack_up, \
        (min(after), slack_down, max(levels), slack_up)
    # the pump switched off at the top and on again at the bottom
    assert any(x < 0.6 for x in after), after
    assert "Traceback" not in plc.output + plant.output
