"""A tiny synchronous Modbus client for notebooks: ``plclab.modbus.connect()``.

With ``plclab serve`` running::

    c = plclab.modbus.connect(port=5020)
    c["%QX0.0"], c["%MW0"], c.read_registers(0, 2)
    c["%MW0"] = 42          # holding register 0
    c.close()

Addresses in ``c["..."]`` follow the map of ``plclab serve`` (see
:mod:`plclab.modbus.addressing`); words read back unsigned, as ``plc["%IW0"]`` does.
Errors are :class:`~plclab.errors.PlcError` (PLC9204 exception response, PLC9205 no
connection); pymodbus logs nothing to stderr.
"""

from __future__ import annotations

from typing import Any

from ..errors import PlcError
from .addressing import (
    COIL_INPUT_BASE,
    HR_INPUT_BASE,
    IR_STATUS_BASE,
    STATUS_FIELDS,
    parse_address,
)
from .addressing import locate as _locate

_EXC_NAMES = {1: "illegal function", 2: "illegal data address", 3: "illegal data value",
              4: "server device failure", 6: "server busy", 10: "gateway path unavailable",
              11: "gateway target did not respond"}


class ModbusClient:
    """Synchronous Modbus TCP client (see :func:`connect`)."""

    def __init__(self, host: str = "127.0.0.1", port: int = 5020, device_id: int = 1,
                 timeout: float = 2.0) -> None:
        from ._deps import need_pymodbus

        need_pymodbus()
        from pymodbus.client import ModbusTcpClient

        self.host, self.port, self.device_id = host, port, device_id
        self._c = ModbusTcpClient(host, port=port, timeout=timeout, retries=0)
        if not self._c.connect():
            raise PlcError("PLC9205", f"no Modbus server at {host}:{port}; start one with "
                           f"plclab serve PROGRAM --port {port}")

    # -- plain function codes -----------------------------------------------------------------
    def _do(self, what: str, *args, **kw):
        from pymodbus.exceptions import ModbusException

        try:
            rr = getattr(self._c, what)(*args, device_id=self.device_id, **kw)
        except ModbusException as exc:
            raise PlcError("PLC9205", f"{what} at {self.host}:{self.port} failed: {exc}") \
                from None
        if rr.isError():
            code = getattr(rr, "exception_code", 0)
            raise PlcError("PLC9204", f"{what}({', '.join(map(str, args))}): the server "
                           f"answered exception {code} ({_EXC_NAMES.get(code, 'unknown')})")
        return rr

    def read_coils(self, address: int, count: int = 1) -> list[bool]:
        """Coils ``address .. address+count-1`` (FC 1)."""
        return list(self._do("read_coils", address, count=count).bits[:count])

    def read_inputs(self, address: int, count: int = 1) -> list[bool]:
        """Discrete inputs (FC 2)."""
        return list(self._do("read_discrete_inputs", address, count=count).bits[:count])

    read_discrete_inputs = read_inputs

    def read_registers(self, address: int, count: int = 1, *, input: bool = False) -> list[int]:
        """Holding registers (FC 3), or input registers with ``input=True`` (FC 4)."""
        fn = "read_input_registers" if input else "read_holding_registers"
        return list(self._do(fn, address, count=count).registers)

    def read_input_registers(self, address: int, count: int = 1) -> list[int]:
        return self.read_registers(address, count, input=True)

    def write_register(self, address: int, value: int) -> None:
        """Write one holding register (FC 6); negative values are stored as two's complement."""
        self._do("write_register", address, int(value) & 0xFFFF)

    def write_registers(self, address: int, values: list[int]) -> None:
        self._do("write_registers", address, [int(v) & 0xFFFF for v in values])

    def write_coil(self, address: int, value: bool) -> None:
        self._do("write_coil", address, bool(value))

    def status(self) -> dict[str, int]:
        """The status block of ``plclab serve`` (state, scans, time_ms, io_ok, forced)."""
        r = self.read_registers(IR_STATUS_BASE, len(STATUS_FIELDS), input=True)
        return {"state": r[0], "scans": r[1] << 16 | r[2], "time_ms": r[3] << 16 | r[4],
                "io_ok": r[5], "forced": r[6]}

    # -- by PLC address -----------------------------------------------------------------------
    def __getitem__(self, address: str) -> Any:
        e, size = self._entry(address)
        if e.table == "coil":
            return self.read_coils(e.number)[0]
        if e.table == "discrete_input":
            return self.read_inputs(e.number)[0]
        regs = self.read_registers(e.number, e.words, input=e.table == "input_register")
        value = 0
        for r in regs:
            value = value << 16 | r
        if size == "X":
            return bool(value >> e.bit & 1)
        if size == "B":
            return value >> e.bit & 0xFF
        return value

    def __setitem__(self, address: str, value: Any) -> None:
        e, size = self._entry(address)
        area = parse_address(address)[0]
        if area == "I":  # the input simulation window
            if size == "X":
                self.write_coil(COIL_INPUT_BASE + e.number, bool(value))
                return
            e = type(e)("holding_register", HR_INPUT_BASE + e.number, e.bit, e.words,
                        "read/write")
        elif area == "Q" and size == "X":
            self.write_coil(e.number, bool(value))  # forcing: needs --allow-coil-writes
            return
        elif area == "Q":
            raise PlcError("PLC9204", f"{address} is an output word: read only over Modbus "
                           f"(holding register {e.number})")
        if size in ("X", "B"):
            old = self.read_registers(e.number)[0]
            mask = (1 if size == "X" else 0xFF) << e.bit
            v = (1 if value else 0) if size == "X" else int(value) & 0xFF
            self.write_register(e.number, (old & ~mask) | (v << e.bit))
            return
        v = int(value) & ((1 << (16 * e.words)) - 1)
        regs = [(v >> (16 * (e.words - 1 - i))) & 0xFFFF for i in range(e.words)]
        if len(regs) == 1:
            self.write_register(e.number, regs[0])
        else:
            self.write_registers(e.number, regs)

    @staticmethod
    def _entry(address: str):
        try:
            _, size, byte, _ = parse_address(address)
            e = _locate(address)
        except ValueError as exc:
            raise PlcError("PLC9203", str(exc)) from None
        if e is None:
            raise PlcError("PLC9203", f"{address} is outside the Modbus map (the first 1024 "
                           "bytes of each area are mapped)")
        if size in ("W", "D", "L") and byte % 2:
            raise PlcError("PLC9203", f"{address}: words at odd byte addresses are not "
                           "register-aligned; read the registers with read_registers()")
        return e, size

    # -- housekeeping -------------------------------------------------------------------------
    def close(self) -> None:
        self._c.close()

    def __del__(self) -> None:
        c = getattr(self, "_c", None)
        if c is not None:
            try:
                c.close()
            except Exception:  # noqa: BLE001 - interpreter shutdown
                pass

    def __enter__(self) -> ModbusClient:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"<plclab.modbus client {self.host}:{self.port} device {self.device_id}>"


def connect(host: str = "127.0.0.1", port: int = 5020, device_id: int = 1,
            timeout: float = 2.0) -> ModbusClient:
    """Connect to a Modbus TCP server (``plclab serve``) and return a :class:`ModbusClient`."""
    return ModbusClient(host, port, device_id, timeout)


__all__ = ["ModbusClient", "connect"]
