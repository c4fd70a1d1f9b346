"""``plclab plant-serve``: a plant from :mod:`plants` running in real time as a Modbus server.

The plant plays the part of remote I/O (or of Factory I/O): a PLC started with
``plclab serve prog.st --io modbus://127.0.0.1:5021`` polls it. The address layout is in
:mod:`plclab.modbus.plantmap`.
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable
from typing import Any

from ..errors import PlcError
from .addressing import from_register, to_register
from .limits import DEFAULT_IDLE_TIMEOUT, DEFAULT_MAX_CLIENTS, bounded_server, check_limits
from .plantmap import INFO_BASE, INFO_COUNT, PANEL_BASE, plant_layout

_FC_COILS = (1, 5, 15)
_FC_HOLDING = (3, 6, 16, 22, 23)


class PlantServer:
    """Serve ``plant`` over Modbus TCP and step it with the wall clock times ``speed``."""

    def __init__(self, plant, *, host: str = "127.0.0.1", port: int = 5021, speed: float = 1.0,
                 device_id: int = 1, on_message: Callable[[str], None] | None = None,
                 max_clients: int = DEFAULT_MAX_CLIENTS,
                 idle_timeout: float = DEFAULT_IDLE_TIMEOUT) -> None:
        from .server import check_speed

        check_speed(speed)
        self.max_clients, self.idle_timeout = check_limits(max_clients, idle_timeout)
        self.plant = plant
        self.host, self.port, self.speed, self.device_id = host, port, float(speed), device_id
        self.layout = plant_layout(plant)
        self.on_message = on_message or (lambda text: None)
        self.server = None
        self._stop: asyncio.Event | None = None
        self.ready = threading.Event()

    # -- the device --------------------------------------------------------------------------
    def device(self):
        from pymodbus.simulator import DataType, SimData, SimDevice

        lay = self.layout

        def bits(n: int, base: int = 0) -> list:
            # values= as a list with count=1 (pymodbus' block check is quadratic in count)
            return [SimData(base, values=[False] * max(n, 1), datatype=DataType.BITS)]

        def regs(n: int, base: int = 0) -> list:
            return [SimData(base, count=n, datatype=DataType.REGISTERS)] if n else []

        coils = bits(len(lay.coils)) + (bits(len(lay.panel_coils), PANEL_BASE)
                                        if lay.panel_coils else [])
        holding = regs(len(lay.hr)) + regs(len(lay.panel_hr), PANEL_BASE)
        if not holding:
            holding = [SimData(0, count=1, datatype=DataType.INVALID)]
        inputs = regs(len(lay.ir)) + regs(INFO_COUNT, INFO_BASE)
        return SimDevice(id=self.device_id, simdata=(coils, bits(len(lay.di)), holding, inputs),
                         action=self.action)

    def _group(self, fc: int, number: int):
        """(signals, index) for a coil/register number, or (None, None)."""
        lay = self.layout
        if fc == 2:
            pairs = [(lay.di, 0)]
        elif fc in _FC_COILS:
            pairs = [(lay.coils, 0), (lay.panel_coils, PANEL_BASE)]
        elif fc == 4:
            pairs = [(lay.ir, 0)]
        else:
            pairs = [(lay.hr, 0), (lay.panel_hr, PANEL_BASE)]
        for sigs, base in pairs:
            if base <= number < base + len(sigs):
                return sigs, number - base
        return None, None

    async def action(self, fc: int, start: int, address: int, count: int,
                     regs: list[int], values) -> Any:
        from pymodbus.constants import ExcCodes

        try:
            return self._action(fc, start, address, count, regs, values)
        except Exception:  # noqa: BLE001 - a request must never break the server
            return ExcCodes.DEVICE_FAILURE

    def _action(self, fc, start, address, count, regs, values):
        from pymodbus.constants import ExcCodes

        p = self.plant
        bitwise = fc in _FC_COILS or fc == 2
        if fc == 4 and INFO_BASE <= address < INFO_BASE + INFO_COUNT:
            ms = int(p.time * 1000) & 0xFFFFFFFF
            info = self.layout.counts() + [ms >> 16, ms & 0xFFFF]
            for r in range(address, address + count):
                if 0 <= r - start < len(regs) and INFO_BASE <= r < INFO_BASE + INFO_COUNT:
                    regs[r - start] = info[r - INFO_BASE]
            return None
        sigs, _ = self._group(fc, address)
        if sigs is None:
            return ExcCodes.ILLEGAL_ADDRESS
        if values is not None:
            if fc in (2, 4):
                return ExcCodes.ILLEGAL_FUNCTION
            items = []
            for i, v in enumerate(values):
                s2, k = self._group(fc, address + i)
                if s2 is not sigs:
                    return ExcCodes.ILLEGAL_ADDRESS
                items.append((s2[k], v))
            for s, v in items:
                if bitwise:
                    p.write(s.name, bool(v))
                else:
                    p.write(s.name, from_register(int(v), s.range[0], s.range[1]))
            return None
        if bitwise:
            r0 = address // 16 - start
            for r in range(max(r0, 0), min(r0 + count, len(regs))):
                word = 0
                for i in range(16):
                    s2, k = self._group(fc, (r + start) * 16 + i)
                    if s2 is not None and p.read(s2[k].name):
                        word |= 1 << i
                regs[r] = word
        else:
            for r in range(address, address + count):
                s2, k = self._group(fc, r)
                if s2 is None:
                    return ExcCodes.ILLEGAL_ADDRESS
                s = s2[k]
                regs[r - start] = to_register(p.read(s.name), s.range[0], s.range[1])
        return None

    # -- life cycle ---------------------------------------------------------------------------
    async def start(self) -> None:
        from ._deps import need_pymodbus

        need_pymodbus()
        self._stop = asyncio.Event()
        self.server = bounded_server(self.device(), (self.host, self.port),
                                     max_clients=self.max_clients,
                                     idle_timeout=self.idle_timeout, notify=self.on_message)
        try:
            await self.server.serve_forever(background=True)
        except (RuntimeError, OSError) as exc:
            self.server = None
            raise PlcError("PLC9202", f"cannot listen on {self.host}:{self.port} ({exc}); "
                           "choose another --port") from None

    def request_stop(self) -> None:
        if self._stop is not None:
            self._stop.set()

    async def run(self, duration: float | None = None) -> None:
        if self._stop is None:
            await self.start()
        assert self._stop is not None
        task = asyncio.create_task(self._step_loop(), name="plclab-plant")
        stopper = asyncio.create_task(self._stop.wait())
        self.ready.set()
        try:
            await asyncio.wait([stopper, task], timeout=duration,
                               return_when=asyncio.FIRST_COMPLETED)
            if task.done() and not task.cancelled() and task.exception() is not None:
                raise task.exception()
        finally:
            for t in (stopper, task):
                t.cancel()
            await asyncio.gather(stopper, task, return_exceptions=True)
            await self.close()

    async def close(self) -> None:
        if self.server is not None:
            srv, self.server = self.server, None
            await srv.shutdown()

    async def _step_loop(self) -> None:
        loop = asyncio.get_running_loop()
        last = loop.time()
        tick = 0.005  # wall seconds between steps
        while True:
            await asyncio.sleep(tick)
            now = loop.time()
            dt = min(now - last, 0.5) * self.speed  # a stalled loop does not jump the plant
            last = now
            if dt > 0:
                self.plant.step(dt)
            for ev in self.plant.drain_events():
                self.on_message(f"t={ev.time:.1f}s {ev.kind}: {ev.message}")
