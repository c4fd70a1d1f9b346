"""Bounded Modbus TCP servers: at most ``max_clients`` connections at once, idle ones dropped.

pymodbus 3.16's :class:`ModbusTcpServer` accepts any number of connections and keeps a silent
one open for ever. :func:`bounded_server` returns a subclass that

* closes a new connection at once when ``max_clients`` are already open (the client sees the
  connection accepted and then closed: a reset or EOF on its first read), and
* closes a connection that has sent no complete request for ``idle_timeout`` wall-clock
  seconds (a client trickling one byte at a time does not keep a slot: only whole MBAP
  frames count, ADR 0041).

Request sizes are bounded by pymodbus itself: a frame longer than 260 bytes (MBAP length over
254) is dropped, and counts beyond the Modbus limits (2000 bits, 125 registers) are answered
with an exception response. Both servers of :mod:`plclab.modbus` use this class.
"""

from __future__ import annotations

import asyncio
import math
from collections.abc import Callable
from typing import Any

from ..errors import PlcError

DEFAULT_MAX_CLIENTS = 16
DEFAULT_IDLE_TIMEOUT = 60.0  # wall-clock seconds
MAX_CLIENTS_LIMIT = 1024


def check_limits(max_clients: Any, idle_timeout: Any) -> tuple[int, float]:
    """Validated ``(max_clients, idle_timeout)``; PlcError PLC9203 otherwise."""
    if isinstance(max_clients, bool) or not isinstance(max_clients, int) or \
            not 1 <= max_clients <= MAX_CLIENTS_LIMIT:
        raise PlcError("PLC9203", f"--max-clients {max_clients!r}: give a whole number of "
                       f"connections from 1 to {MAX_CLIENTS_LIMIT} (default "
                       f"{DEFAULT_MAX_CLIENTS})")
    if isinstance(idle_timeout, bool) or not isinstance(idle_timeout, int | float) or \
            not math.isfinite(idle_timeout) or not 0 < idle_timeout <= 86_400:
        raise PlcError("PLC9203", f"--idle-timeout {idle_timeout!r}: give the seconds after "
                       "which a silent client is disconnected, more than 0 and at most 86400 "
                       f"(default {DEFAULT_IDLE_TIMEOUT:g})")
    return max_clients, float(idle_timeout)


MAX_FRAME = 260  # MBAP header (6 bytes before the length's count) + at most 254


def take_frames(conn: Any, data: bytes) -> list[bytes]:
    """The Modbus TCP frames ``data`` completes on ``conn`` (the partial frame waits in
    ``conn.partial``, bounded). A header with an impossible length is handed on as it is
    (pymodbus discards such a frame) and the partial frame is dropped."""
    buf = getattr(conn, "partial", b"") + data
    out: list[bytes] = []
    while len(buf) >= 6:
        length = int.from_bytes(buf[4:6], "big")
        if not 2 <= length <= MAX_FRAME - 6:
            out.append(buf)
            buf = b""
            break
        if len(buf) < 6 + length:
            break
        out.append(buf[:6 + length])
        buf = buf[6 + length:]
    conn.partial = buf[-MAX_FRAME:]
    return out


def whole_request(frame: bytes) -> bool:
    """``frame`` is one complete MBAP frame of a possible length (what keeps a connection
    alive; a header announcing 0, 1 or more than 254 bytes does not, ADR 0041)."""
    if len(frame) < 8:
        return False
    length = int.from_bytes(frame[4:6], "big")
    return 2 <= length <= MAX_FRAME - 6 and len(frame) == 6 + length


def invalid_coil_value(frame: bytes) -> bytes | None:
    """The exception response (03, ILLEGAL DATA VALUE) to a Write Single Coil (FC5) whose
    value is neither 0xFF00 (ON) nor 0x0000 (OFF), as the Modbus specification requires
    (pymodbus would take any non-zero value as ON); None for any other frame."""
    if len(frame) != 12 or frame[7] != 5 or frame[10:12] in (b"\xff\x00", b"\x00\x00"):
        return None
    return frame[:4] + b"\x00\x03" + frame[6:7] + bytes([0x85, 0x03])


class _Refuse(asyncio.Protocol):
    """Accepts a connection only to close it (the server is full)."""

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        transport.close()


_CLASSES: dict[str, type] = {}


def _classes() -> tuple[type, type]:
    """The server and connection-handler classes (pymodbus imported on first use)."""
    if not _CLASSES:
        from pymodbus.server import ModbusTcpServer
        from pymodbus.server.requesthandler import ServerRequestHandler

        class IdleHandler(ServerRequestHandler):
            """One client connection, closed after ``idle_timeout`` s without data."""

            def __init__(self, owner, *args) -> None:
                super().__init__(owner, *args)
                self.owner = owner
                self.last_data = owner.loop.time()
                self.timer: asyncio.TimerHandle | None = None

            def callback_connected(self) -> None:
                super().callback_connected()
                self.last_data = self.loop.time()
                self._arm()

            def data_received(self, data: bytes) -> None:
                frames = take_frames(self, data)
                if any(whole_request(f) for f in frames):  # requests keep it alive, not bytes
                    self.last_data = self.loop.time()
                for frame in frames:
                    refusal = invalid_coil_value(frame)
                    if refusal is None:
                        super().data_received(frame)
                    elif self.transport is not None:
                        self.transport.write(refusal)

            def _arm(self) -> None:
                due = self.last_data + self.owner.idle_timeout
                self.timer = self.loop.call_at(due, self._check)

            def _check(self) -> None:
                self.timer = None
                if self.transport is None or self.is_closing:
                    return
                if self.loop.time() - self.last_data >= self.owner.idle_timeout:
                    self.owner.dropped_idle += 1
                    self.owner.notify(f"Modbus client idle for {self.owner.idle_timeout:g} s: "
                                      "disconnected")
                    self.close()
                else:
                    self._arm()

            def callback_disconnected(self, exc: Exception | None) -> None:
                if self.timer is not None:
                    self.timer.cancel()
                    self.timer = None
                super().callback_disconnected(exc)

        class BoundedTcpServer(ModbusTcpServer):
            """A ModbusTcpServer with a connection cap and an idle timeout."""

            max_clients = DEFAULT_MAX_CLIENTS
            idle_timeout = DEFAULT_IDLE_TIMEOUT
            refused_clients = 0
            dropped_idle = 0
            notify: Callable[[str], None] = staticmethod(lambda text: None)

            def handle_new_connection(self):
                if len(self.active_connections) >= self.max_clients:
                    self.refused_clients += 1
                    if self.refused_clients == 1 or self.refused_clients % 100 == 0:
                        self.notify(f"Modbus connection refused: {self.max_clients} clients "
                                    f"are connected already ({self.refused_clients} refused "
                                    "so far)")
                    return _Refuse()
                return super().handle_new_connection()

            def callback_new_connection(self):
                return IdleHandler(self, self.trace_packet, self.trace_pdu, self.trace_connect)

        _CLASSES["server"] = BoundedTcpServer
        _CLASSES["handler"] = IdleHandler
    return _CLASSES["server"], _CLASSES["handler"]


def bounded_server(device, address: tuple[str, int], *, max_clients: int = DEFAULT_MAX_CLIENTS,
                   idle_timeout: float = DEFAULT_IDLE_TIMEOUT,
                   notify: Callable[[str], None] | None = None):
    """A pymodbus TCP server for ``device`` on ``address`` with the two limits (call it inside
    the running event loop, as ``ModbusTcpServer`` itself)."""
    max_clients, idle_timeout = check_limits(max_clients, idle_timeout)
    cls, _ = _classes()
    srv = cls(device, address=address)
    srv.max_clients = max_clients
    srv.idle_timeout = idle_timeout
    if notify is not None:
        srv.notify = notify
    return srv
