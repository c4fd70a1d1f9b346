"""The bounds of the run-time API (PLC3010-PLC3012): durations, cycle times and task intervals,
scans per call, the process image's size and its addresses (moved out of plc.py)."""


from __future__ import annotations

import math
from typing import Any

from ..durations import parse_duration
from ..errors import Location, PlcError
from ..lang.addresses import LOCATED_RE, SIZE_BYTES, canonical
from ..lang.limits import MAX_INTERVAL_NS, MIN_INTERVAL_NS


def to_ns(value: Any) -> int:
    """Accept 0.01 (seconds), '10ms', '1min', 'T#10ms' or a timedelta and return nanoseconds
    (:func:`plclab.durations.parse_duration`)."""
    ns = None if isinstance(value, float) and not math.isfinite(value) else \
        parse_duration(value)
    if ns is not None:
        return ns
    if isinstance(value, float):
        raise PlcError("PLC3002", f"{value!r} is not a duration; give a finite number of "
                       "seconds or e.g. '10ms'")
    if isinstance(value, str):
        raise PlcError("PLC3002", f"'{value}' is not a duration; write e.g. 10ms, 1.5s or "
                       "T#1m30s")
    raise PlcError("PLC3002", f"{value!r} is not a duration")


# Bounds of the run-time API (documented in docs and in problems.py PLC3010-PLC3012).
MIN_CYCLE_NS = MIN_INTERVAL_NS  # 0.1 ms: the fastest task a PLC of the course runs
MAX_CYCLE_NS = MAX_INTERVAL_NS  # one day
MAX_SCANS = 100_000_000  # scans per run()/scan() call
MAX_IMAGE = 65_536  # bytes of each process image area (%I, %Q, %M)
ADDR_RE = LOCATED_RE  # the one parser of direct addresses (plclab.lang.addresses)


def check_cycle_ns(ns: int, what: str, location: Location | None = None) -> int:
    """``ns`` when it is a usable cycle time or task interval; else PlcError PLC3011."""
    if not MIN_CYCLE_NS <= ns <= MAX_CYCLE_NS:
        raise PlcError("PLC3011", f"{what} is {fmt_ns(ns)}; it must lie between 0.1 ms and "
                       "1 day (e.g. 10ms)", location)
    return ns


def parse_task_intervals(mapping: Any) -> dict[int, int]:
    """``{"10ms": "20ms"}`` as nanoseconds, each side checked like a cycle time (PLC3011)."""
    if not mapping:
        return {}
    if not hasattr(mapping, "items"):
        raise PlcError("PLC3011", f"task_intervals={mapping!r}: give a table from the "
                       "configured interval to the one to run, e.g. {'10ms': '20ms'}")
    return {check_cycle_ns(to_ns(k), "a task interval"): check_cycle_ns(to_ns(v), "a task "
            "interval") for k, v in mapping.items()}


def fmt_ns(ns: int) -> str:
    if ns <= 0 or ns % 1_000_000:
        return f"{ns} ns"
    if ns % 1_000_000_000 == 0:
        return f"{ns // 1_000_000_000} s"
    return f"{ns // 1_000_000} ms"


def check_address(addr: str, image_size: int, location: Location | None = None,
                  what: str = "") -> tuple[str, str, int, int | None]:
    """Split ``%QX1.2``/``%IW4`` into (area, size, byte, bit), checking that it lies inside a
    process image of ``image_size`` bytes: PlcError PLC3001 (not an address) or PLC3010."""
    m = ADDR_RE.fullmatch(canonical(addr))
    if not m:
        raise PlcError("PLC3001", f"{what}{addr} is not a direct address (e.g. %IX0.0, %QW2, "
                       "%MD4)", location)
    area, size, byte = m.group(1), m.group(2) or "X", int(m.group(3))
    bit = int(m.group(4)) if m.group(4) is not None else None
    if size == "X" and bit is None:
        raise PlcError("PLC3001", f"{what}{addr}: a bit address needs byte.bit, e.g. "
                       f"%{area}X{byte}.0", location)
    if size != "X" and bit is not None:
        raise PlcError("PLC3001", f"{what}{addr}: only bit addresses (X) have a .bit part",
                       location)
    if bit is not None and bit > 7:
        raise PlcError("PLC3010", f"{what}{addr}: a byte has bits 0..7, not {bit}", location)
    n = SIZE_BYTES[size]
    if byte + n > image_size:
        last = image_size - n
        raise PlcError("PLC3010", f"{what}{addr} is beyond the process image ({image_size} "
                       f"bytes: %{area}{size}0{'.0' if size == 'X' else ''}..%{area}{size}{last}"
                       f"{'.7' if size == 'X' else ''}); use a lower address or a larger "
                       "image_size", location)
    return area, size, byte, bit


DEFAULT_IMAGE = 1024  # bytes of each process image area unless the program needs more


def auto_image_size(need: int) -> int:
    """The process image for a program whose located variables end at byte ``need``: 1024
    bytes, or the next multiple of 1024 (at most MAX_IMAGE; the checker refuses more).

    >>> auto_image_size(0), auto_image_size(1024), auto_image_size(1033), auto_image_size(65536)
    (1024, 1024, 2048, 65536)
    """
    return min(MAX_IMAGE, max(DEFAULT_IMAGE, -(-need // 1024) * 1024))


def check_image_size(size: Any) -> int:
    if isinstance(size, bool) or not isinstance(size, int) or not 8 <= size <= MAX_IMAGE:
        raise PlcError("PLC3012", f"image_size={size!r}: the process image is a whole number of "
                       f"bytes from 8 to {MAX_IMAGE} (default: sized from the program's addresses, at least "
                       "1024)")
    return size


def check_memory_byte(byte: Any, image_size: int, what: str) -> int | None:
    if byte is None:
        return None
    if isinstance(byte, bool) or not isinstance(byte, int) or not 0 <= byte < image_size:
        raise PlcError("PLC3012", f"{what}={byte!r}: give a byte number of %M from 0 to "
                       f"{image_size - 1}, or None")
    return byte


def check_count(n: Any, what: str) -> int:
    """A number of scans: a whole number from 0 to MAX_SCANS, else PlcError PLC3011."""
    if isinstance(n, bool) or not isinstance(n, int):
        raise PlcError("PLC3011", f"{what}={n!r}: give a whole number of scans")
    if not 0 <= n <= MAX_SCANS:
        raise PlcError("PLC3011", f"{what}={n}: one call runs 0 to {MAX_SCANS:,} scans; split a "
                       "longer run into several calls")
    return n
