"""``plclab serve`` in-process: pymodbus round trips for every area, exceptions, forcing,
malformed frames and floods. A real server on 127.0.0.1, stopped at the end of each test."""

from __future__ import annotations

import random
import socket
import struct

import pytest

pytest.importorskip("pymodbus", reason="pymodbus is not installed: pip install 'plclab[modbus]'")

from pymodbus.client import ModbusTcpClient  # noqa: E402

import plclab  # noqa: E402
from plclab.errors import PlcError  # noqa: E402
from plclab.modbus import addressing as A  # noqa: E402
from plclab.modbus._testing import free_port, wait_until  # noqa: E402
from plclab.modbus.server import BackgroundServer  # noqa: E402

PROG = """
PROGRAM Main
VAR
    sp AT %MW0 : INT; out AT %QW2 : INT; lamp AT %QX0.0 : BOOL;
    in1 AT %IX0.0 : BOOL; echo AT %QX0.1 : BOOL;
    ain AT %IW2 : INT; aecho AT %QW4 : INT;
    cnt AT %MD8 : DINT; last AT %QX1023.7 : BOOL;
END_VAR
out := sp * 2; lamp := sp > 10; echo := in1; aecho := ain + 1; cnt := cnt + 1; last := TRUE;
END_PROGRAM
"""
# (words and bits share bytes as on S7: %QW0 would overlap %QX0.0..%QX1.7, so the words of
# this program start at byte 2)


def serve(**options):
    plc = plclab.loads(PROG)
    port = free_port()
    srv = BackgroundServer(plc, port=port, speed=options.pop("speed", 2.0), **options)
    return plc, port, srv


def client(port) -> ModbusTcpClient:
    c = ModbusTcpClient("127.0.0.1", port=port, timeout=2, retries=0)
    assert c.connect()
    return c


def exc_code(rr) -> int | None:
    return rr.exception_code if rr.isError() else None


def test_round_trips_for_every_area():
    plc, port, srv = serve()
    with srv:
        c = client(port)
        try:
            # holding registers = %MW: the program uses the value at its next scan
            assert not c.write_register(0, 21).isError()
            assert wait_until(lambda: c.read_holding_registers(1025).registers == [42])
            assert c.read_holding_registers(0).registers == [21]
            assert c.read_coils(0).bits[0] is True  # lamp := sp > 10
            # %MD8 = holding registers 4 (high word) and 5 (low word): the counter runs
            hi, lo = c.read_holding_registers(4, count=2).registers
            first = hi << 16 | lo
            assert wait_until(lambda: (lambda r: r[0] << 16 | r[1])(
                c.read_holding_registers(4, count=2).registers) > first + 5)
            # input simulation window: coil 8192 = %IX0.0, register 2049 = %IW2
            assert not c.write_coil(A.COIL_INPUT_BASE, True).isError()
            assert c.read_discrete_inputs(0).bits[0] is True
            assert wait_until(lambda: c.read_coils(1).bits[0])  # echo := in1
            assert not c.write_register(A.HR_INPUT_BASE + 1, 7).isError()
            assert c.read_input_registers(1).registers == [7]
            assert wait_until(lambda: c.read_holding_registers(1026).registers == [8])
            # negative numbers are two's complement
            assert not c.write_register(0, (-5) & 0xFFFF).isError()
            assert wait_until(lambda: c.read_holding_registers(1025).registers == [(-10) & 0xFFFF])
            # the last mapped coil
            assert wait_until(lambda: c.read_coils(8191).bits[0])
            # multiple writes / mask write / read-write
            assert not c.write_registers(10, [1, 2, 3]).isError()
            assert c.read_holding_registers(10, count=3).registers == [1, 2, 3]
            assert not c.mask_write_register(address=10, and_mask=0x00FF, or_mask=0x0F00).isError()
            assert c.read_holding_registers(10).registers == [0x0F01]
            rr = c.readwrite_registers(read_address=10, read_count=2, write_address=11,
                                       values=[9])
            assert not rr.isError() and rr.registers == [0x0F01, 9]
            assert not c.write_coils(A.COIL_INPUT_BASE + 8, [True, False, True]).isError()
            assert c.read_discrete_inputs(8, count=3).bits[:3] == [True, False, True]
            # status block
            st = c.read_input_registers(A.IR_STATUS_BASE, count=A.STATUS_COUNT).registers
            assert st[0] == 1 and (st[1] << 16 | st[2]) > 0 and st[5] == 1 and st[6] == 0
        finally:
            c.close()
    assert plc["sp"] == -5 and plc.memory[20:22] == bytes([0x0F, 0x01])
    assert plc.inputs[1] == 0b101  # %IX1.0 and %IX1.2 from the window


def test_exception_responses_and_read_only_areas():
    plc, port, srv = serve()
    with srv:
        c = client(port)
        try:
            before = bytes(plc.memory)
            assert exc_code(c.write_coil(0, True)) == 2  # coils are read-only by default
            assert exc_code(c.write_register(1024, 1)) == 2  # %QW are read-only
            assert exc_code(c.write_register(A.HR_COMMAND, 1)) == 2
            assert exc_code(c.read_holding_registers(600)) == 2  # a gap
            assert exc_code(c.read_holding_registers(510, count=5)) == 2  # runs into the gap
            assert exc_code(c.write_registers(510, [1, 2, 3, 4])) == 2
            assert exc_code(c.read_coils(16384)) == 2
            assert exc_code(c.read_discrete_inputs(8192)) == 2
            assert exc_code(c.read_input_registers(512)) == 2
            assert exc_code(c.read_input_registers(A.IR_STATUS_BASE + A.STATUS_COUNT)) == 2
            assert exc_code(c.read_holding_registers(60000, count=10)) == 2
            assert exc_code(c.write_coils(8190, [True, True, True])) == 2  # straddles windows
            assert c.read_coils(0, device_id=7).isError()  # only device id 1 exists
            assert plc.forced == {}
            # nothing of the refused writes landed (bytes 8..11 are the program's counter)
            assert plc.memory[1016:1024] == bytes(8) and plc.memory[:8] == before[:8]
        finally:
            c.close()


def test_forcing_coils_needs_the_flag():
    plc, port, srv = serve(allow_coil_writes=True)
    with srv:
        c = client(port)
        try:
            assert c.read_coils(0).bits[0] is False  # sp = 0: lamp off
            assert not c.write_coil(0, True).isError()
            assert c.read_coils(0).bits[0] is True
            st = c.read_input_registers(A.IR_STATUS_BASE + 6).registers[0]
            assert st == 1  # one forced address
            scans = c.read_input_registers(A.IR_STATUS_BASE + 2).registers[0]
            wait_until(lambda: c.read_input_registers(A.IR_STATUS_BASE + 2).registers[0]
                       > scans + 10)
            assert c.read_coils(0).bits[0] is True  # the program's FALSE does not win
            assert exc_code(c.write_register(A.HR_COMMAND, 5)) == 3
            assert not c.write_register(A.HR_COMMAND, A.CMD_RELEASE_FORCES).isError()
            assert wait_until(lambda: c.read_coils(0).bits[0] is False)
            assert c.read_input_registers(A.IR_STATUS_BASE + 6).registers[0] == 0
        finally:
            c.close()
    assert plc.forced == {}


def test_read_only_inputs_removes_the_windows():
    plc, port, srv = serve(read_only_inputs=True)
    with srv:
        c = client(port)
        try:
            assert exc_code(c.write_coil(A.COIL_INPUT_BASE, True)) == 2
            assert exc_code(c.write_register(A.HR_INPUT_BASE, 1)) == 2
            assert exc_code(c.read_holding_registers(A.HR_INPUT_BASE)) == 2
            assert not c.write_register(0, 3).isError()  # %MW stays writable
        finally:
            c.close()
    assert plc.inputs[:4] == bytes(4)


def _raw(port: int, payload: bytes, read: bool = True) -> bytes:
    with socket.create_connection(("127.0.0.1", port), timeout=1) as s:
        s.settimeout(0.3)
        try:
            s.sendall(payload)
            return s.recv(300) if read else b""
        except OSError:
            return b""


def mbap(tid: int, pdu: bytes, unit: int = 1, proto: int = 0, length: int | None = None):
    return struct.pack(">HHHB", tid, proto, len(pdu) + 1 if length is None else length,
                       unit) + pdu


def test_malformed_frames_and_floods_leave_the_server_answering():
    plc, port, srv = serve(speed=5.0)
    rnd = random.Random(7)
    with srv:
        c = client(port)
        try:
            assert not c.write_register(0, 1234).isError()
            image = bytes(plc.memory[:4])
            frames = [
                bytes(rnd.randrange(256) for _ in range(600)),  # junk
                b"\x00\x01\x00",  # truncated MBAP header
                b"\x00\x01\x00\x00\x00",  # truncated MBAP header
                mbap(1, b"\x03\x00\x00\x00\x01", length=0),  # length 0
                mbap(2, b"\x03\x00\x00\x00\x01", length=300),  # length beyond the maximum
                mbap(3, b"\x03\x00\x00", length=6),  # shorter than announced
                mbap(4, b"\x03\x00\x00\x00\x01\xff\xff\xff"),  # longer PDU than FC 3 has
                mbap(5, b"\x03\x00\x00\x00\x01", proto=7),  # not the Modbus protocol id
                mbap(6, b"\x7f\x00\x00"),  # unknown function code
                mbap(7, b"\x14\x00"),  # FC 20 read file record, no data
                mbap(8, b"\x03\x00\x00\x00\x00"),  # count 0
                mbap(9, b"\x03\x00\x00\x00\xc8"),  # count 200 > 125
                mbap(10, b"\x10\x00\x00\x00\x02\x03\x00\x01"),  # FC 16, byte count mismatch
                mbap(11, b"\x0f\x00\x00\x00\x10\x01\xff"),  # FC 15, byte count mismatch
                mbap(12, b"\x06\x04\x00"),  # FC 6 truncated
                b"\xff" * 7 + b"\x03" * 300,
            ]
            answers = []
            for f in frames:
                answers.append(_raw(port, f))
            # a whole burst on one connection
            _raw(port, b"".join(frames) * 5)
            # what came back: exception responses, or (for frames pymodbus can still decode)
            # a normal answer to the same function code; the junk got nothing
            for f, a in zip(frames, answers, strict=True):
                if a:
                    assert len(a) >= 9 and a[:2] == f[:2]
                    assert a[7] & 0x80 or a[7] == f[7], a
            assert _raw(port, mbap(20, b"\x2b\x0e\x01\x00"))  # FC 43 read device id: answered
            # flood: many requests and many connections
            for i in range(300):
                c.read_holding_registers(i % 600, count=1)
            socks = []
            for _ in range(40):
                s = socket.create_connection(("127.0.0.1", port), timeout=1)
                socks.append(s)
            for s in socks:
                s.close()
            # still answering, image untouched
            assert c.read_holding_registers(0).registers == [1234]
            assert bytes(plc.memory[:2]) == image[:2]
            c2 = client(port)
            assert c2.read_holding_registers(1025).registers == [2468]
            c2.close()
        finally:
            c.close()


def test_notebook_client(capfd):
    plc, port, srv = serve(allow_coil_writes=True)
    with srv:
        c = plclab.modbus.connect(port=port)
        try:
            c["%MW0"] = 12
            assert wait_until(lambda: c["%QW2"] == 24)
            assert c["%QX0.0"] is True and c.read_coils(0, 2) == [True, False]
            c["%IX0.0"] = True
            assert c["%IX0.0"] is True and c.read_inputs(0, 1) == [True]
            assert wait_until(lambda: c["%QX0.1"])
            c["%IW2"] = 100
            assert c["%IW2"] == 100 and c.read_registers(1, input=True) == [100]
            assert wait_until(lambda: c["%QW4"] == 101)
            c["%MD20"] = 0x12345678
            assert c["%MD20"] == 0x12345678 and c.read_registers(10, 2) == [0x1234, 0x5678]
            c["%MX30.1"] = True
            c["%MB31"] = 0x0F
            assert c["%MX30.1"] is True and c["%MB31"] == 0x0F
            assert c.read_registers(15) == [0x020F]
            assert c["%MD8"] > 0
            st = c.status()
            assert st["state"] == 1 and st["io_ok"] == 1 and st["scans"] > 0
            c["%QX0.5"] = True  # forcing, allowed here
            assert c["%QX0.5"] is True
            with pytest.raises(PlcError) as e:
                c.write_register(1024, 1)
            assert e.value.code == "PLC9204" and "illegal data address" in str(e.value)
            with pytest.raises(PlcError):
                c["%QW0"] = 1
            with pytest.raises(PlcError):
                c["%IW1"]
            with pytest.raises(PlcError):
                c["%MW4000"]
        finally:
            c.close()
    with pytest.raises(PlcError) as e:
        plclab.modbus.connect(port=free_port(), timeout=0.5)
    assert e.value.code == "PLC9205"
    assert capfd.readouterr().err == ""  # pymodbus logs nothing on stderr


def test_port_in_use_is_a_plc_error():
    plc, port, srv = serve()
    with srv:
        plc2 = plclab.loads(PROG)
        with pytest.raises(PlcError) as e:
            BackgroundServer(plc2, port=port).start()
        assert e.value.code == "PLC9202"
