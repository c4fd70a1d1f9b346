"""``plclab serve``: a PLC scanning in real time behind a Modbus TCP server.

Everything runs in one asyncio loop: the pymodbus server (a :class:`SimDevice` whose
``action=`` hook reads and writes the PLC's process image on every request), the scan task
(paces the virtual clock to the wall clock times ``speed``) and, with remote I/O, the poller.
A Modbus request is served between two scans, so it always sees a consistent image and a
write is seen by the program at its next scan. The PLC itself never reads the wall clock.

>>> import plclab, asyncio
>>> from plclab.modbus.server import PlcServer
>>> plc = plclab.loads("PROGRAM P VAR n AT %MW0 : INT; END_VAR n := n + 1; END_PROGRAM")
>>> srv = PlcServer(plc, port=0, speed=100.0)   # port 0: do not listen (tests, notebooks)
>>> asyncio.run(srv.run(duration=0.05)); plc["n"] > 100
True
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable
from typing import Any

from ..errors import PlcError, PlcRuntimeFault
from .addressing import (
    CMD_RELEASE_FORCES,
    COIL_INPUT_BASE,
    HR_COMMAND,
    HR_INPUT_BASE,
    HR_OUTPUT_BASE,
    IR_STATUS_BASE,
    MAPPED_BITS,
    MAPPED_WORDS,
    STATUS_COUNT,
)
from .limits import DEFAULT_IDLE_TIMEOUT, DEFAULT_MAX_CLIENTS, bounded_server, check_limits

_FC_COILS = (1, 5, 15)
_FC_HOLDING = (3, 6, 16, 22, 23)


class ImageBridge:
    """Serve a PLC's process image through a pymodbus ``SimDevice`` ``action=`` hook.

    The pymodbus block is only a scratch copy: before each read the hook refreshes the
    requested registers from the image, and a write is applied to the image (and checked)
    before pymodbus stores it.
    """

    def __init__(self, plc, *, allow_coil_writes: bool = False,
                 read_only_inputs: bool = False) -> None:
        self.plc = plc
        self.allow_coil_writes = allow_coil_writes
        self.read_only_inputs = read_only_inputs
        self.words = min(plc.image_size // 2, MAPPED_WORDS)
        self.io_ok = True
        self.forced_keys: set[str] = set()
        self.requests = 0
        self.refused = 0

    # -- the device --------------------------------------------------------------------------
    def device(self, device_id: int = 1):
        from pymodbus.simulator import DataType, SimData, SimDevice

        bits = MAPPED_BITS if self.read_only_inputs else 2 * MAPPED_BITS
        # values= as a list with count=1: pymodbus' block check is quadratic in count for bits
        coils = [SimData(0, values=[False] * bits, datatype=DataType.BITS)]
        discrete = [SimData(0, values=[False] * MAPPED_BITS, datatype=DataType.BITS)]
        holding = [SimData(0, count=MAPPED_WORDS, datatype=DataType.REGISTERS),
                   SimData(HR_OUTPUT_BASE, count=MAPPED_WORDS, datatype=DataType.REGISTERS),
                   SimData(HR_COMMAND, count=1, datatype=DataType.REGISTERS)]
        if not self.read_only_inputs:
            holding.append(SimData(HR_INPUT_BASE, count=MAPPED_WORDS,
                                   datatype=DataType.REGISTERS))
        inputs = [SimData(0, count=MAPPED_WORDS, datatype=DataType.REGISTERS),
                  SimData(IR_STATUS_BASE, count=STATUS_COUNT, datatype=DataType.REGISTERS)]
        return SimDevice(id=device_id, simdata=(coils, discrete, holding, inputs),
                         action=self.action)

    async def action(self, fc: int, start: int, address: int, count: int,
                     regs: list[int], values) -> Any:
        """The pymodbus hook: refresh ``regs`` for reads, apply ``values`` for writes."""
        from pymodbus.constants import ExcCodes

        self.requests += 1
        try:
            if fc in _FC_COILS or fc == 2:
                r0 = address // 16 - start
                if values is not None:
                    code = self._write_bits(fc, address, list(values))
                else:
                    code = None
                    for r in range(max(r0, 0), min(r0 + count, len(regs))):
                        regs[r] = self._bit_register(fc, r + start)
            elif fc == 4 or fc in _FC_HOLDING:
                if values is not None:
                    code = self._write_registers(address, list(values))
                else:
                    code = None
                    for r in range(address, address + count):
                        if 0 <= r - start < len(regs):
                            regs[r - start] = self._register(fc, r)
            else:
                code = ExcCodes.ILLEGAL_FUNCTION
        except Exception:  # noqa: BLE001 - a request must never break the server
            code = ExcCodes.DEVICE_FAILURE
        if code is not None:
            self.refused += 1
        return code

    # -- reads --------------------------------------------------------------------------------
    def _bit_register(self, fc: int, r: int) -> int:
        """16 coils/discrete inputs packed as pymodbus keeps them (bit 0 = lowest number)."""
        if fc == 2:
            buf, w = self.plc.inputs, r
        elif r * 16 < COIL_INPUT_BASE:
            buf, w = self.plc.outputs, r
        else:
            buf, w = self.plc.inputs, r - COIL_INPUT_BASE // 16
        if w >= self.words:
            return 0
        return buf[2 * w] | buf[2 * w + 1] << 8

    def _register(self, fc: int, r: int) -> int:
        plc = self.plc
        if fc == 4:
            if r < IR_STATUS_BASE:
                buf, w = plc.inputs, r
            else:
                return self._status(r - IR_STATUS_BASE)
        elif r < HR_OUTPUT_BASE:
            buf, w = plc.memory, r
        elif r < HR_INPUT_BASE:
            buf, w = plc.outputs, r - HR_OUTPUT_BASE
        elif r < HR_COMMAND:
            buf, w = plc.inputs, r - HR_INPUT_BASE
        else:
            return 0
        if w >= self.words:
            return 0
        return buf[2 * w] << 8 | buf[2 * w + 1]

    def _status(self, i: int) -> int:
        plc = self.plc
        scans = plc.scan_count & 0xFFFFFFFF
        ms = (plc.ctx.now_ns // 1_000_000) & 0xFFFFFFFF
        return [1 if plc.state == "RUN" else 0, scans >> 16, scans & 0xFFFF, ms >> 16,
                ms & 0xFFFF, 1 if self.io_ok else 0, len(plc.forced) & 0xFFFF][i]

    # -- writes -------------------------------------------------------------------------------
    def _write_bits(self, fc: int, address: int, values: list) -> Any:
        from pymodbus.constants import ExcCodes

        if fc == 2:
            return ExcCodes.ILLEGAL_FUNCTION
        end = address + len(values)
        outputs = address < COIL_INPUT_BASE
        if outputs and (not self.allow_coil_writes or end > COIL_INPUT_BASE):
            return ExcCodes.ILLEGAL_ADDRESS
        if not outputs and (self.read_only_inputs or end > 2 * MAPPED_BITS):
            return ExcCodes.ILLEGAL_ADDRESS
        if end - (0 if outputs else COIL_INPUT_BASE) > self.words * 16:
            return ExcCodes.ILLEGAL_ADDRESS
        for i, v in enumerate(values):
            k = address + i
            if outputs:
                self._force_bit(k, bool(v))
            else:
                self._set_bit(self.plc.inputs, k - COIL_INPUT_BASE, bool(v))
        return None

    @staticmethod
    def _set_bit(buf: bytearray, k: int, v: bool) -> None:
        byte, bit = divmod(k, 8)
        if v:
            buf[byte] |= 1 << bit
        else:
            buf[byte] &= 0xFF ^ (1 << bit)

    def _force_bit(self, k: int, v: bool) -> None:
        key = f"%QX{k // 8}.{k % 8}"
        self.plc.force(key, v)
        self.forced_keys.add(key)
        # visible at once (the scan applies the force from now on)
        self._set_bit(self.plc.outputs, k, v)
        self._set_bit(self.plc.image_out, k, v)

    def release_forces(self) -> None:
        for key in self.forced_keys:
            self.plc.unforce(key)
        self.forced_keys.clear()

    def _write_registers(self, address: int, values: list[int]) -> Any:
        from pymodbus.constants import ExcCodes

        end = address + len(values)
        if address == HR_COMMAND and end == HR_COMMAND + 1:
            if not self.allow_coil_writes:
                return ExcCodes.ILLEGAL_ADDRESS
            if values[0] == CMD_RELEASE_FORCES:
                self.release_forces()
            elif values[0] != 0:
                return ExcCodes.ILLEGAL_VALUE
            return None
        if end <= MAPPED_WORDS:
            buf, w0 = self.plc.memory, address
        elif HR_INPUT_BASE <= address and end <= HR_INPUT_BASE + MAPPED_WORDS \
                and not self.read_only_inputs:
            buf, w0 = self.plc.inputs, address - HR_INPUT_BASE
        else:
            return ExcCodes.ILLEGAL_ADDRESS  # %QW, the command register in a block, gaps
        if w0 + len(values) > self.words:
            return ExcCodes.ILLEGAL_ADDRESS
        for i, v in enumerate(values):
            w = w0 + i
            buf[2 * w:2 * w + 2] = (int(v) & 0xFFFF).to_bytes(2, "big")
        return None


class PlcServer:
    """A PLC running in real time behind a Modbus TCP server.

    Parameters
    ----------
    plc : Plc
        A loaded PLC (``plclab.load(...)``); the server owns it while it runs.
    host, port : str, int
        Where to listen; ``127.0.0.1`` by default. ``port=0`` runs without a server.
    speed : float
        Virtual seconds per wall-clock second (``50`` = fifty times faster than real time).
    allow_coil_writes : bool
        Let clients force outputs by writing coils (and release forces, holding register 4096).
    read_only_inputs : bool
        Remove the input simulation windows (coils 8192.., holding registers 2048..).
    plant : Plant, optional
        A plant from :mod:`plants` joined directly to the PLC (signal order, see
        :mod:`plclab.modbus.plantmap`), stepped with every scan.
    io : str, optional
        ``modbus://HOST:PORT`` of a remote-I/O server (``plclab plant-serve``).
    io_period, io_timeout : float
        Poll period and request timeout of remote I/O, wall-clock seconds.
    io_status : str, optional
        A ``%IX`` address that also carries the remote-I/O status bit.
    on_message : callable, optional
        Receives one line of text for each notable event (faults, I/O lost/back, refused
        and idle clients).
    max_clients : int
        Connections served at once (default 16); more are closed as soon as they open.
    idle_timeout : float
        Wall-clock seconds after which a client that sent nothing is disconnected (60).
    """

    def __init__(self, plc, *, host: str = "127.0.0.1", port: int = 5020, speed: float = 1.0,
                 allow_coil_writes: bool = False, read_only_inputs: bool = False,
                 plant=None, io: str | None = None, io_period: float = 0.02,
                 io_timeout: float = 0.5, io_status: str | None = None,
                 device_id: int = 1, on_message: Callable[[str], None] | None = None,
                 max_clients: int = DEFAULT_MAX_CLIENTS,
                 idle_timeout: float = DEFAULT_IDLE_TIMEOUT) -> None:
        check_speed(speed)
        self.max_clients, self.idle_timeout = check_limits(max_clients, idle_timeout)
        if io_status and io is None:
            raise PlcError("PLC3002", "--io-status goes with remote I/O (--io modbus://...)")
        if plant is not None and io is not None:
            raise PlcError("PLC3002", "give either a local plant (--plant) or remote I/O "
                           "(--io), not both")
        self.plc = plc
        self.host, self.port, self.speed = host, port, float(speed)
        self.device_id = device_id
        self.bridge = ImageBridge(plc, allow_coil_writes=allow_coil_writes,
                                  read_only_inputs=read_only_inputs)
        self.on_message = on_message or (lambda text: None)
        self.coupling = None
        if plant is not None:
            from .plantmap import PlantCoupling

            self.coupling = PlantCoupling(plant, plc)
        self.remote = None
        self._io_vars = []
        if io is not None:
            from .remote_io import RemoteIO

            self.remote = RemoteIO(plc, io, period=io_period, timeout=io_timeout,
                                   on_message=self._message)
            self._io_vars = io_status_vars(plc, io_status)
            self.bridge.io_ok = False
        self.server = None
        self.lagging = 0
        self._fault_reported = False
        self._stop: asyncio.Event | None = None
        self.ready = threading.Event()

    def _message(self, text: str) -> None:
        self.on_message(text)

    # -- life cycle ---------------------------------------------------------------------------
    async def start(self) -> None:
        """Open the server socket (raises PLC9202 when the port is taken)."""
        from ._deps import need_pymodbus

        need_pymodbus()
        self._stop = asyncio.Event()
        if self.port:
            self.server = bounded_server(self.bridge.device(self.device_id),
                                         (self.host, self.port), max_clients=self.max_clients,
                                         idle_timeout=self.idle_timeout, notify=self._message)
            try:
                await self.server.serve_forever(background=True)
            except (RuntimeError, OSError) as exc:
                self.server = None
                raise PlcError("PLC9202", f"cannot listen on {self.host}:{self.port} ({exc}); "
                               "is another server running there? choose another --port") \
                    from None

    def request_stop(self) -> None:
        """Ask :meth:`run` to finish (safe from signal handlers in the loop)."""
        if self._stop is not None:
            self._stop.set()

    async def run(self, duration: float | None = None) -> None:
        """Start (if needed), scan in real time until ``duration`` wall seconds or a stop."""
        if self._stop is None:
            await self.start()
        assert self._stop is not None
        tasks = [asyncio.create_task(self._scan_loop(), name="plclab-scan")]
        if self.remote is not None:
            tasks.append(asyncio.create_task(self.remote.run(), name="plclab-remote-io"))
        stopper = asyncio.create_task(self._stop.wait())
        self.ready.set()
        try:
            await asyncio.wait([stopper, *tasks], timeout=duration,
                               return_when=asyncio.FIRST_COMPLETED)
            for t in tasks:
                if t.done() and not t.cancelled() and t.exception() is not None:
                    raise t.exception()
        finally:
            for t in [stopper, *tasks]:
                t.cancel()
            await asyncio.gather(stopper, *tasks, return_exceptions=True)
            await self.close()

    async def close(self) -> None:
        if self.remote is not None:
            self.remote.close()
        if self.server is not None:
            srv, self.server = self.server, None
            await srv.shutdown()

    # -- scanning -----------------------------------------------------------------------------
    def _one_scan(self) -> None:
        plc = self.plc
        if self.remote is not None:
            ok = self.remote.ok
            self.bridge.io_ok = ok
            for var in self._io_vars:
                var(ok)
        if self.coupling is not None:
            self.coupling.to_plc()
        before = plc.ctx.now_ns
        try:
            plc.scan()
        except PlcRuntimeFault as fault:
            if not self._fault_reported:
                self._fault_reported = True
                self._message(f"PLC stopped on a fault: {fault}")
        if self.coupling is not None:
            self.coupling.from_plc()
            self.coupling.plant.step((plc.ctx.now_ns - before) / 1e9)

    async def _scan_loop(self) -> None:
        loop = asyncio.get_running_loop()
        plc = self.plc
        rate = self.speed * 1e9  # virtual ns per wall second
        t0, v0 = loop.time(), plc.ctx.now_ns
        while True:
            target = v0 + (loop.time() - t0) * rate
            budget_end = loop.time() + 0.02  # never hold the loop for more than ~20 ms
            while plc.ctx.now_ns <= target and loop.time() < budget_end:
                for _ in range(20):
                    if plc.ctx.now_ns > target:
                        break
                    self._one_scan()
            behind = (target - plc.ctx.now_ns) / rate
            if behind > 0.5:
                # the machine cannot keep up with --speed: run as fast as it can
                if not self.lagging:
                    self._message(f"warning: cannot keep up with --speed {self.speed:g}; "
                                  "the virtual clock runs slower than requested")
                self.lagging += 1
                t0, v0 = loop.time(), plc.ctx.now_ns
            due = t0 + (plc.ctx.now_ns - v0) / rate
            await asyncio.sleep(max(0.0, due - loop.time()))


def check_speed(speed: Any) -> float:
    """``--speed``: virtual seconds per wall second, a finite positive number (PLC3002)."""
    if isinstance(speed, bool) or not isinstance(speed, int | float) or \
            not 0 < speed < float("inf"):
        raise PlcError("PLC3002", f"--speed must be a positive number of virtual seconds per "
                       f"wall second (e.g. 1 or 50), not {speed!r}")
    return float(speed)


def io_status_vars(plc, io_status: str | None) -> list[Callable[[bool], None]]:
    """Setters for the remote-I/O status: every BOOL named IO_OK, and ``io_status``."""
    from ..lang import types as T

    setters = []
    project = plc.project
    paths = []
    if "IO_OK" in project.globals:
        paths.append("IO_OK")
    symbols = project.symbols
    for inst, pou in symbols.programs_declaring("IO_OK"):
        if symbols.members(pou)["IO_OK"].section not in ("VAR_EXTERNAL", "VAR_TEMP"):
            paths.append(f"{inst}.IO_OK")
    for p in paths:
        var = plc.var(p)
        if T.resolve(var.type) is not T.BOOL:
            raise PlcError("PLC3002", f"{p} must be a BOOL to carry the remote-I/O status, "
                           f"not {var.type}")
        setters.append(lambda v, _s=var.set: _s(v))
    if io_status:
        from .addressing import parse_address

        try:
            area, size, byte, bit = parse_address(io_status)
        except ValueError as exc:
            raise PlcError("PLC9203", f"--io-status: {exc}") from None
        if area != "I" or size != "X" or byte >= plc.image_size:
            raise PlcError("PLC9203", f"--io-status {io_status}: give an input bit such as "
                           "%IX100.0")

        def set_input(v, _b=byte, _i=bit, _buf=plc.inputs):
            if v:
                _buf[_b] |= 1 << _i
            else:
                _buf[_b] &= 0xFF ^ (1 << _i)

        setters.append(set_input)
    return setters


class BackgroundServer:
    """Run a :class:`PlcServer` in a thread with its own event loop (notebooks and tests).

    >>> # with BackgroundServer(plc, port=5020, speed=10) as srv: ... talk Modbus ...
    >>> # with BackgroundServer(PlantServer(get_plant("tank"), port=5021)): ...

    The PLC belongs to the server thread while it runs: talk to it over Modbus, and read
    ``plc[...]`` again only after the ``with`` block.
    """

    def __init__(self, plc_or_server, **options: Any) -> None:
        if hasattr(plc_or_server, "request_stop"):  # a PlcServer or a PlantServer
            if options:
                raise TypeError("give options to the server, not to BackgroundServer")
            self.server = plc_or_server
        else:
            self.server = PlcServer(plc_or_server, **options)
        self._thread: threading.Thread | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._error: BaseException | None = None

    def start(self, timeout: float = 10.0) -> BackgroundServer:
        started = threading.Event()

        def main():
            async def go():
                self._loop = asyncio.get_running_loop()
                try:
                    await self.server.start()
                except BaseException as exc:  # noqa: BLE001 - reported to the caller
                    self._error = exc
                    return
                finally:
                    started.set()
                await self.server.run()

            try:
                asyncio.run(go())
            except BaseException as exc:  # noqa: BLE001 - reported to the caller
                self._error = exc
                started.set()

        self._thread = threading.Thread(target=main, name="plclab-modbus", daemon=True)
        self._thread.start()
        started.wait(timeout)
        if self._error is not None:
            self._thread.join(timeout)
            err, self._error = self._error, None
            raise err
        self.server.ready.wait(timeout)
        return self

    def stop(self, timeout: float = 10.0) -> None:
        if self._loop is not None and self._thread is not None and self._thread.is_alive():
            try:
                self._loop.call_soon_threadsafe(self.server.request_stop)
            except RuntimeError:  # the loop has just finished
                pass
            self._thread.join(timeout)
        if self._error is not None and not isinstance(self._error, asyncio.CancelledError):
            err, self._error = self._error, None
            raise err

    def __enter__(self) -> BackgroundServer:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()
