"""Bounded Modbus servers (``plclab serve`` and ``plclab plant-serve``): a cap on concurrent
clients, idle clients dropped, oversized requests refused, bad options and plant maps that do
not fit the image are PlcErrors. Real servers and clients on 127.0.0.1."""

from __future__ import annotations

import math
import socket
import struct
import time

import pytest

pytest.importorskip("pymodbus", reason="pymodbus is not installed: pip install 'plclab[modbus]'")

from pymodbus.client import ModbusTcpClient  # noqa: E402

import plclab  # noqa: E402
from plclab.errors import PlcError  # noqa: E402
from plclab.modbus._testing import free_port, wait_until  # noqa: E402
from plclab.modbus.plant_server import PlantServer  # noqa: E402
from plclab.modbus.server import BackgroundServer, PlcServer  # noqa: E402

PROG = "PROGRAM P VAR n AT %MW0 : INT; q AT %QW2 : INT; END_VAR q := 7; END_PROGRAM"


def request(tid: int = 1, pdu: bytes = b"\x03\x00\x01\x00\x01") -> bytes:
    """An MBAP frame for device 1; by default FC 3 reading holding register 1 (%MW2)."""
    return struct.pack(">HHHB", tid, 0, len(pdu) + 1, 1) + pdu


def answer(s: socket.socket, frame: bytes) -> bytes:
    """Send ``frame`` and return the reply; b"" when the server closed the connection."""
    try:
        s.sendall(frame)
        return s.recv(300)
    except OSError:  # reset by the server
        return b""


def closed_by_server(s: socket.socket, within: float) -> bool:
    """True when the server closes ``s`` (EOF or reset) within ``within`` seconds."""
    s.settimeout(within)
    try:
        return s.recv(100) == b""
    except TimeoutError:
        return False
    except OSError:
        return True


def connect(port: int) -> socket.socket:
    s = socket.create_connection(("127.0.0.1", port), timeout=30)  # an upper bound only
    s.settimeout(30)
    return s


def test_connections_beyond_the_cap_are_closed_and_a_freed_slot_is_reused():
    plc = plclab.loads(PROG)
    port = free_port()
    messages: list[str] = []
    with BackgroundServer(plc, port=port, speed=2.0, max_clients=2,
                          on_message=messages.append) as srv:
        a, b = connect(port), connect(port)
        try:
            assert answer(a, request(1))[7] == 3 and answer(b, request(2))[7] == 3
            extras = [connect(port) for _ in range(3)]
            for i, x in enumerate(extras):  # accepted by the kernel, closed by the server
                assert answer(x, request(10 + i)) == b""
                x.close()
            # the two clients inside the cap are still served
            assert answer(a, request(3))[7] == 3 and answer(b, request(4))[7] == 3
            a.close()
            assert wait_until(lambda: len(srv.server.server.active_connections) == 1)
            c = connect(port)
            assert answer(c, request(5))[7] == 3  # the freed slot serves a new client
            c.close()
        finally:
            a.close()
            b.close()
        assert srv.server.server.refused_clients == 3
    assert any("refused" in m and "2 clients" in m for m in messages)


def test_an_idle_client_is_dropped_and_an_active_one_is_kept():
    """A client polling every 0.1 s keeps its connection through a 2 s idle timeout (a
    margin of 20 polls, so a loaded machine does not make it idle); the silent one is
    dropped meanwhile."""
    plc = plclab.loads(PROG)
    port = free_port()
    messages: list[str] = []
    with BackgroundServer(plc, port=port, speed=2.0, idle_timeout=2.0,
                          on_message=messages.append):
        idle, busy = connect(port), connect(port)
        try:
            assert answer(idle, request(1))[7] == 3
            t0 = time.monotonic()
            dropped = False
            for i in range(600):  # poll until the idle client is gone (60 s at most)
                assert answer(busy, request(i % 60_000))[7] == 3
                if closed_by_server(idle, within=0.1):
                    dropped = True
                    break
            assert dropped
            assert time.monotonic() - t0 >= 2.0 - 0.1
            assert answer(busy, request(200))[7] == 3
        finally:
            idle.close()
            busy.close()
    assert any("idle" in m for m in messages)


def test_a_silent_connection_that_never_sends_is_dropped():
    plc = plclab.loads(PROG)
    port = free_port()
    with BackgroundServer(plc, port=port, speed=2.0, idle_timeout=0.3):
        s = connect(port)
        try:
            assert closed_by_server(s, within=30.0)
        finally:
            s.close()


def test_pymodbus_clients_work_within_the_limits():
    plc = plclab.loads(PROG)
    port = free_port()
    with BackgroundServer(plc, port=port, speed=2.0, max_clients=3, idle_timeout=5):
        clients = [ModbusTcpClient("127.0.0.1", port=port, timeout=2, retries=0)
                   for _ in range(3)]
        try:
            for c in clients:
                assert c.connect()
            assert all(wait_until(lambda c=c: c.read_holding_registers(1025).registers == [7])
                       for c in clients)
        finally:
            for c in clients:
                c.close()


def test_oversized_requests_are_refused_and_the_connection_stays_usable():
    plc = plclab.loads(PROG)
    port = free_port()
    with BackgroundServer(plc, port=port, speed=2.0):
        s = connect(port)
        try:
            # counts beyond the Modbus limits: an exception response (pymodbus cannot decode
            # them, so it answers "illegal function" under function code 0x80)
            too_many = answer(s, request(1, b"\x03\x00\x00\x00\x7e"))  # 126 registers
            assert too_many[:2] == b"\x00\x01" and too_many[7] & 0x80
            coils = answer(s, request(2, b"\x01\x00\x00\x07\xd1"))  # 2001 coils
            assert coils[:2] == b"\x00\x02" and coils[7] & 0x80
            s.settimeout(0.3)
            assert answer(s, request(3, b"\x03" + b"\x00" * 300)) == b""  # frame > 260 bytes
            s.settimeout(3)
            assert answer(s, request(4))[7] == 3
        finally:
            s.close()


def test_the_plant_server_is_bounded_too():
    from plants import get_plant

    port = free_port()
    with BackgroundServer(PlantServer(get_plant("tank"), port=port, speed=2.0, max_clients=1,
                                      idle_timeout=2.0)):
        a = connect(port)
        try:
            assert answer(a, request(1, b"\x04\x00\x00\x00\x01"))[7] == 4
            b = connect(port)
            assert answer(b, request(2, b"\x04\x00\x00\x00\x01")) == b""
            b.close()
            assert closed_by_server(a, within=30.0)  # then dropped as idle
        finally:
            a.close()


@pytest.mark.parametrize("opts", [{"max_clients": 0}, {"max_clients": -3}, {"max_clients": 1.5},
                                  {"max_clients": 10 ** 6}, {"max_clients": True},
                                  {"idle_timeout": 0}, {"idle_timeout": -1},
                                  {"idle_timeout": math.nan}, {"idle_timeout": math.inf},
                                  {"idle_timeout": "60"}])
def test_bad_limits_are_plc9203(opts):
    plc = plclab.loads(PROG)
    with pytest.raises(PlcError) as exc:
        PlcServer(plc, port=0, **opts)
    assert exc.value.code == "PLC9203"
    from plants import get_plant

    with pytest.raises(PlcError) as exc:
        PlantServer(get_plant("tank"), port=0, **opts)
    assert exc.value.code == "PLC9203"


@pytest.mark.parametrize("speed", [0, -1, math.nan, math.inf, "2", True])
def test_bad_speed_is_plc3002(speed):
    with pytest.raises(PlcError) as exc:
        PlcServer(plclab.loads(PROG), port=0, speed=speed)
    assert exc.value.code == "PLC3002"


def test_the_cli_checks_the_limits(capsys, tmp_path):
    from plclab.cli import main

    prog = tmp_path / "p.st"
    prog.write_text(PROG, encoding="utf-8")
    for args in (["serve", str(prog), "--max-clients", "0"],
                 ["serve", str(prog), "--idle-timeout", "-1"],
                 ["plant-serve", "tank", "--max-clients", "2000"]):
        rc = main([*args, "--port", str(free_port()), "--duration", "0.1"])
        assert rc != 0
        err = capsys.readouterr().err
        assert "PLC9203" in err and "Traceback" not in err


def test_a_plant_that_does_not_fit_a_small_image_is_plc3010():
    from plants import get_plant
    from plclab.modbus.plantmap import PlantCoupling

    plc = plclab.loads(PROG, image_size=16)
    with pytest.raises(PlcError) as exc:
        PlantCoupling(get_plant("tank"), plc)
    assert exc.value.code == "PLC3010" and "image_size" in exc.value.message


def _held_by(s: socket.socket, chunks: list[bytes]) -> bool:
    """Send ``chunks`` one by one while the server keeps ``s`` open; False once it closes."""
    for chunk in chunks:
        try:
            s.sendall(chunk)
        except OSError:
            return False
        if closed_by_server(s, within=0.1):
            return False
    return True


def test_a_client_trickling_bytes_does_not_keep_its_slot():
    """Only whole requests keep a connection alive: a 259-byte frame (FC16, 123 registers)
    sent one byte every 0.1 s (26 s, far beyond the 0.5 s idle timeout however loaded the machine) is dropped
    before its last byte."""
    plc = plclab.loads(PROG)
    port = free_port()
    with BackgroundServer(plc, port=port, speed=2.0, idle_timeout=0.5):
        s = connect(port)
        try:
            frame = request(1, b"\x10\x00\x01\x00\x7b\xf6" + bytes(246))[:-1]  # never whole
            assert len(frame) == 258
            assert not _held_by(s, [bytes([b]) for b in frame])
        finally:
            s.close()


@pytest.mark.parametrize("header", [b"\x00\x01\x00\x00\x00\x00",  # length 0
                                    b"\x00\x01\x00\x00\x00\x01\x01",  # a unit id, no PDU
                                    b"\x00\x01\x00\x00\xff\xff"])  # beyond 254
def test_malformed_frames_do_not_keep_a_slot(header):
    """A header announcing an impossible length is no request: sent again and again it does
    not keep the connection alive."""
    plc = plclab.loads(PROG)
    port = free_port()
    with BackgroundServer(plc, port=port, speed=2.0, idle_timeout=0.5):
        s = connect(port)
        try:
            assert not _held_by(s, [header] * 300)  # 30 s of them at most
        finally:
            s.close()
    from plclab.modbus.limits import whole_request

    assert whole_request(request(1)) and not whole_request(header)


def test_write_single_coil_accepts_only_on_and_off():
    """FC5's value is 0xFF00 (ON) or 0x0000 (OFF); anything else is the exception 03."""
    plc = plclab.loads(PROG)
    port = free_port()
    with BackgroundServer(plc, port=port, speed=2.0):
        s = connect(port)
        try:
            bad = answer(s, request(7, b"\x05\x00\x00\x12\x34"))
            assert bad[:2] == b"\x00\x07" and bad[7:9] == b"\x85\x03"
            good = answer(s, request(8, b"\x05\x00\x00\xff\x00"))
            assert good[:2] == b"\x00\x08" and good[7:9] != b"\x85\x03"
            assert answer(s, request(9))[7] == 3  # the connection stays usable
        finally:
            s.close()


def test_the_host_warning_names_what_a_remote_client_may_write(capsys):
    """Serving beyond loopback warns, and names the writable areas (not only "read")."""
    from plclab.modbus.commands import _check_endpoint

    _check_endpoint("127.0.0.1", 5020, "its inputs %I and %IW, %MW (memory words)")
    _check_endpoint("::1", 5020, "x")
    assert capsys.readouterr().err == ""
    _check_endpoint("0.0.0.0", 5020, "its inputs %I and %IW, %MW (memory words)")
    err = capsys.readouterr().err
    assert err.startswith("warning: serving on 0.0.0.0") and "write its inputs %I and %IW" in err
    assert "%MW" in err
