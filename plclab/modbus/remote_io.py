"""Remote I/O: the PLC polls a plant served over Modbus TCP (``serve --io modbus://...``).

Each poll (every ``period`` wall seconds) reads the discrete inputs into ``%IX0.0...`` and the
input registers into ``%IW64, %IW66...`` (the PLC's input terminals), then writes the coils from
``%QX0.0...`` and the holding registers from ``%QW64, %QW66...`` -- only those covered by a
located output of the program (see :mod:`plclab.modbus.plantmap`).

How many of each: ``modbus://host:port?di=2&ir=3&coils=1&hr=1`` if given; otherwise the info
block of ``plclab plant-serve`` (input registers 1000..1005); otherwise (a server that is not
plclab's) as many as the program's located variables reach.

On a communication loss (timeout, refused connection, exception response) :attr:`ok` goes
False at once; the input terminals keep their last values; the poller tries to reconnect
every ``max(period, 0.2)`` s and :attr:`ok` is True again after the first complete poll.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from urllib.parse import parse_qs, urlsplit

from ..errors import PlcError
from .addressing import located_variables, parse_address
from .plantmap import (
    ANALOG_BYTE,
    INFO_BASE,
    MAX_BITS,
    MAX_WORDS,
    coil_covered,
    covered_outputs,
    get_bit,
    get_word,
    register_covered,
    set_bit,
    set_word,
)

_COUNT_KEYS = ("di", "ir", "coils", "hr")


def parse_io_url(url: str) -> tuple[str, int, dict[str, int], int]:
    """``modbus://127.0.0.1:5021?di=2`` -> ``("127.0.0.1", 5021, {"di": 2}, device_id)``."""
    parts = urlsplit(url)
    if parts.scheme != "modbus" or not parts.hostname:
        raise PlcError("PLC9203", f"--io {url}: write modbus://HOST:PORT, e.g. "
                       "modbus://127.0.0.1:5021")
    try:
        port = parts.port or 502
    except ValueError:
        raise PlcError("PLC9203", f"--io {url}: the port must be a number 1..65535") from None
    counts: dict[str, int] = {}
    device_id = 1
    for key, vals in parse_qs(parts.query).items():
        try:
            n = int(vals[-1])
        except ValueError:
            raise PlcError("PLC9203", f"--io {url}: {key}= needs a whole number") from None
        if key in _COUNT_KEYS:
            limit = MAX_BITS if key in ("di", "coils") else MAX_WORDS
            if not 0 <= n <= limit:
                raise PlcError("PLC9203", f"--io {url}: {key} must be 0..{limit}")
            counts[key] = n
        elif key in ("unit", "device", "device_id"):
            if not 0 <= n <= 255:
                raise PlcError("PLC9203", f"--io {url}: the device id must be 0..255")
            device_id = n
        else:
            raise PlcError("PLC9203", f"--io {url}: unknown option {key}= (use di, ir, coils, "
                           "hr, unit)")
    return parts.hostname, port, counts, device_id


def counts_from_program(plc) -> dict[str, int]:
    """How far the program's located variables reach in each table."""
    c = dict.fromkeys(_COUNT_KEYS, 0)
    for _, address, _ in located_variables(plc):
        area, size, byte, bit = parse_address(address)
        if area == "M":
            continue
        n = {"X": 1, "B": 1, "W": 2, "D": 4, "L": 8}[size]
        if size == "X" and byte < ANALOG_BYTE:
            key, reach = ("di" if area == "I" else "coils"), byte * 8 + bit + 1
        elif size != "X" and byte >= ANALOG_BYTE:
            key, reach = ("ir" if area == "I" else "hr"), (byte - ANALOG_BYTE + n + 1) // 2
        else:
            continue
        c[key] = max(c[key], reach)
    c["di"], c["coils"] = min(c["di"], MAX_BITS), min(c["coils"], MAX_BITS)
    c["ir"], c["hr"] = min(c["ir"], MAX_WORDS), min(c["hr"], MAX_WORDS)
    return c


class RemoteIO:
    """Poll a Modbus TCP server as the PLC's I/O (runs in the server's asyncio loop)."""

    def __init__(self, plc, url: str, *, period: float = 0.02, timeout: float = 0.5,
                 on_message: Callable[[str], None] | None = None) -> None:
        if not period > 0 or not timeout > 0:
            raise PlcError("PLC3002", "--io-period and --io-timeout must be positive")
        self.plc = plc
        self.url = url
        self.host, self.port, self.fixed_counts, self.device_id = parse_io_url(url)
        self.period, self.timeout = float(period), float(timeout)
        self.on_message = on_message or (lambda text: None)
        self.ok = False
        self.polls = 0
        self.failures = 0
        self.counts: dict[str, int] | None = None
        self._client = None
        self._was_ok: bool | None = None
        self._covered = covered_outputs(plc)

    # -- one poll -----------------------------------------------------------------------------
    async def _connect(self) -> None:
        from pymodbus.client import AsyncModbusTcpClient

        self.close()
        client = AsyncModbusTcpClient(self.host, port=self.port, timeout=self.timeout,
                                      retries=0, reconnect_delay=0)
        ok = await asyncio.wait_for(client.connect(), self.timeout + 0.5)
        if not ok:
            client.close()
            raise ConnectionError(f"no Modbus server at {self.host}:{self.port}")
        self._client = client
        self.counts = None

    async def _learn_counts(self) -> dict[str, int]:
        counts = dict(self.fixed_counts)
        if len(counts) < 4:
            info = None
            try:
                rr = await self._call("read_input_registers", INFO_BASE, count=4)
                info = dict(zip(_COUNT_KEYS, rr.registers, strict=True))
            except _ExceptionResponse:
                info = None  # not a plclab plant server
            fallback = info or counts_from_program(self.plc)
            for k in _COUNT_KEYS:
                counts.setdefault(k, min(fallback[k], MAX_BITS if k in ("di", "coils")
                                         else MAX_WORDS))
        return counts

    async def _call(self, name: str, *args, **kw):
        assert self._client is not None
        rr = await asyncio.wait_for(getattr(self._client, name)(*args, device_id=self.device_id,
                                                                 **kw), self.timeout + 0.5)
        if rr.isError():
            raise _ExceptionResponse(f"{name}: exception {getattr(rr, 'exception_code', '?')}")
        return rr

    async def poll_once(self) -> None:
        """Read the inputs, write the outputs; raise on any communication problem."""
        if self._client is None or not self._client.connected:
            await self._connect()
        if self.counts is None:
            self.counts = await self._learn_counts()
        c = self.counts
        plc = self.plc
        di = ir = None
        if c["di"]:
            di = (await self._call("read_discrete_inputs", 0, count=c["di"])).bits
        if c["ir"]:
            ir = (await self._call("read_input_registers", 0, count=c["ir"])).registers
        # all reads succeeded: update the input terminals at once
        if di is not None:
            for k in range(c["di"]):
                set_bit(plc.inputs, k, bool(di[k]))
        if ir is not None:
            for k in range(c["ir"]):
                set_word(plc.inputs, k, ir[k])
        out = plc.outputs
        for start, vals in _runs([(k, get_bit(out, k)) for k in range(c["coils"])
                                  if coil_covered(self._covered, k)], 1968):
            await self._call("write_coils", start, vals)
        for start, vals in _runs([(k, get_word(out, k)) for k in range(c["hr"])
                                  if register_covered(self._covered, k)], 123):
            await self._call("write_registers", start, vals)
        self.polls += 1

    # -- the poll loop ------------------------------------------------------------------------
    async def run(self) -> None:
        from pymodbus.exceptions import ModbusException

        loop = asyncio.get_running_loop()
        while True:
            t = loop.time()
            wait = self.period
            try:
                await self.poll_once()
                self._set_ok(True, "")
            except (ModbusException, OSError, TimeoutError, _ExceptionResponse) as exc:
                failed = str(exc) or type(exc).__name__
            except Exception as exc:  # noqa: BLE001 - a poll must never stop the PLC
                failed = f"{type(exc).__name__}: {exc}"
            else:
                failed = None
            if failed is not None:
                self.failures += 1
                self.close()
                self._set_ok(False, failed)
                wait = max(self.period, 0.2)
            await asyncio.sleep(max(0.0, t + wait - loop.time()))

    def _set_ok(self, ok: bool, why: str) -> None:
        self.ok = ok
        if ok != self._was_ok:
            if ok:
                self.on_message(f"remote I/O {self.host}:{self.port} OK")
            elif self._was_ok is not None or self.failures == 1:
                self.on_message(f"remote I/O {self.host}:{self.port} lost ({why}); inputs keep "
                                "their last values")
            self._was_ok = ok

    def close(self) -> None:
        if self._client is not None:
            client, self._client = self._client, None
            try:
                client.close()
            except Exception:  # noqa: BLE001 - closing a broken connection
                pass


class _ExceptionResponse(Exception):
    """The remote server answered with a Modbus exception."""


def _runs(items: list[tuple[int, object]], limit: int) -> list[tuple[int, list]]:
    """Group ``(index, value)`` pairs into runs of consecutive indices, ``limit`` at most.

    >>> _runs([(0, 1), (1, 2), (5, 3)], 10)
    [(0, [1, 2]), (5, [3])]
    """
    runs: list[tuple[int, list]] = []
    for k, v in items:
        if runs and runs[-1][0] + len(runs[-1][1]) == k and len(runs[-1][1]) < limit:
            runs[-1][1].append(v)
        else:
            runs.append((k, [v]))
    return runs
