"""The Modbus address map of ``plclab serve``: pure Python, no pymodbus.

Every Modbus number below is the 0-based number that travels in the frame (the PDU address).
Tools that count from 1 (``mbpoll`` without ``-0``, Modicon references ``00001``/``40001``)
show each one plus one.

=======================  ===========  ==================================  ======================
Table                    Numbers      PLC                                 Access
=======================  ===========  ==================================  ======================
coils                    0..8191      %QX0.0..%QX1023.7 (coil n =         read; write forces the
                                      %QX(n//8).(n%8))                    bit (--allow-coil-writes)
coils                    8192..16383  input terminals %IX (coil 8192+n =  read/write, not with
                                      %IX(n//8).(n%8))                    --read-only-inputs
discrete inputs          0..8191      %IX0.0..%IX1023.7                   read
input registers          0..511       %IW0..%IW1022 (register n = %IW2n)  read
input registers          1024..1030   status block (see STATUS_FIELDS)    read
holding registers        0..511       %MW0..%MW1022 (register n = %MW2n)  read/write
holding registers        1024..1535   %QW0..%QW1022 (1024+n = %QW2n)      read
holding registers        2048..2559   input terminals %IW (2048+n =       read/write, not with
                                      %IW2n)                              --read-only-inputs
holding register         4096         command: write 1 = release every    --allow-coil-writes
                                      force set through Modbus
=======================  ===========  ==================================  ======================

plclab words are byte-addressed as on S7: ``%IW2`` is bytes 2 and 3, so register ``n`` holds
bytes ``2n`` (high byte) and ``2n+1`` (low byte). A ``%MD4`` is registers 2 (high word) and 3
(low word); a ``%MX0.0`` is bit 8 of holding register 0 (even bytes are the high byte).

>>> locate("%QX1.2")
Entry(table='coil', number=10, bit=None, words=1, access='read')
>>> locate("%IW6").number, locate("%MD4").words, locate("%MX0.0").bit
(3, 2, 8)
>>> locate("%QW2").number
1025
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import dataclass

from ..lang.addresses import LOCATED_RE, canonical

#: bytes of each area that are mapped (8192 bits, 512 words)
MAPPED_BYTES = 1024
MAPPED_BITS = MAPPED_BYTES * 8
MAPPED_WORDS = MAPPED_BYTES // 2

COIL_OUTPUT_BASE = 0  # coils 0..8191 = %QX
COIL_INPUT_BASE = 8192  # coils 8192..16383 = %IX terminals (input simulation window)
DI_INPUT_BASE = 0  # discrete inputs 0..8191 = %IX
IR_INPUT_BASE = 0  # input registers 0..511 = %IW
IR_STATUS_BASE = 1024  # input registers 1024.. = status block
HR_MEMORY_BASE = 0  # holding registers 0..511 = %MW
HR_OUTPUT_BASE = 1024  # holding registers 1024..1535 = %QW
HR_INPUT_BASE = 2048  # holding registers 2048..2559 = %IW terminals (input simulation window)
HR_COMMAND = 4096  # holding register 4096: command register

#: value written to the command register to release every force made through Modbus
CMD_RELEASE_FORCES = 1

#: the status block, input registers from IR_STATUS_BASE on: (offset, name, description)
STATUS_FIELDS = [
    (0, "state", "1 = RUN, 0 = STOP (the PLC stopped on a fault)"),
    (1, "scans_hi", "scan count, high word (UDINT over two registers)"),
    (2, "scans_lo", "scan count, low word"),
    (3, "time_ms_hi", "virtual time in ms, high word (UDINT, wraps after 49 days)"),
    (4, "time_ms_lo", "virtual time in ms, low word"),
    (5, "io_ok", "1 = remote I/O answers (or no remote I/O), 0 = communication lost"),
    (6, "forced", "number of forced addresses"),
]
STATUS_COUNT = len(STATUS_FIELDS)

#: Modbus tables, as the map file names them
COIL, DISCRETE_INPUT, INPUT_REGISTER, HOLDING_REGISTER = (
    "coil", "discrete_input", "input_register", "holding_register")

_ADDR_RE = LOCATED_RE  # the one parser of direct addresses (plclab.lang.addresses)
_WORDS = {"X": 1, "B": 1, "W": 1, "D": 2, "L": 4}
_BYTES = {"X": 1, "B": 1, "W": 2, "D": 4, "L": 8}


@dataclass(frozen=True)
class Entry:
    """Where a direct address lives in the Modbus map.

    ``bit`` is the bit inside a register for ``%?X``/``%?B`` items in a register table (the
    lowest bit of a byte), ``None`` for coils, discrete inputs and whole words. ``words`` is the
    number of registers (1 for bits, bytes and words, 2 for D, 4 for L).
    """

    table: str
    number: int
    bit: int | None
    words: int
    access: str


def parse_address(address: str) -> tuple[str, str, int, int | None]:
    """``"%QX1.2"`` -> ``("Q", "X", 1, 2)``; ``"%MW4"`` -> ``("M", "W", 4, None)``."""
    m = _ADDR_RE.fullmatch(canonical(address))
    if not m:
        raise ValueError(f"{address} is not a direct address (e.g. %IX0.0, %QW2, %MD4)")
    area, size = m.group(1), m.group(2) or "X"
    byte, bit = int(m.group(3)), m.group(4)
    if size == "X":
        if bit is None or not 0 <= int(bit) <= 7:
            raise ValueError(f"{address}: a bit address needs byte.bit with bit 0..7, e.g. %IX0.3")
        return area, size, byte, int(bit)
    if bit is not None:
        raise ValueError(f"{address}: only X (bit) addresses take a .bit part")
    return area, size, byte, None


def locate(address: str, *, allow_coil_writes: bool = False,
           read_only_inputs: bool = False) -> Entry | None:
    """The Modbus entry of a direct address, or ``None`` if it lies outside the mapped bytes."""
    area, size, byte, bit = parse_address(address)
    if byte + _BYTES[size] > MAPPED_BYTES:
        return None
    if size == "X" and area in ("I", "Q"):
        n = byte * 8 + bit
        if area == "I":
            return Entry(DISCRETE_INPUT, DI_INPUT_BASE + n, None, 1, "read")
        return Entry(COIL, COIL_OUTPUT_BASE + n, None, 1,
                     "read/force" if allow_coil_writes else "read")
    reg = byte // 2
    sub = None
    if size == "X":
        sub = (8 if byte % 2 == 0 else 0) + bit
    elif size == "B":
        sub = 8 if byte % 2 == 0 else 0
    elif byte % 2:
        # words at odd bytes straddle two registers: map them by their first register
        sub = 0
    if area == "I":
        return Entry(INPUT_REGISTER, IR_INPUT_BASE + reg, sub, _WORDS[size], "read")
    if area == "Q":
        return Entry(HOLDING_REGISTER, HR_OUTPUT_BASE + reg, sub, _WORDS[size], "read")
    return Entry(HOLDING_REGISTER, HR_MEMORY_BASE + reg, sub, _WORDS[size], "read/write")


def input_window(address: str) -> Entry | None:
    """Where a test or an external plant writes the input terminal ``%I...`` (if mapped)."""
    area, size, byte, bit = parse_address(address)
    if area != "I" or byte + _BYTES[size] > MAPPED_BYTES:
        return None
    if size == "X":
        return Entry(COIL, COIL_INPUT_BASE + byte * 8 + bit, None, 1, "read/write")
    e = locate(address)
    assert e is not None
    return Entry(HOLDING_REGISTER, HR_INPUT_BASE + byte // 2, e.bit, e.words, "read/write")


# -- the map of a program ----------------------------------------------------------------------
MAP_COLUMNS = ["name", "address", "type", "table", "number", "ref", "bit", "words", "access",
               "write_table", "write_number"]


def located_variables(plc) -> list[tuple[str, str, str]]:
    """``(name, address, type)`` of every located variable of a loaded :class:`Plc`."""
    return [(v.path, v.address, str(v.decl.ty)) for v in plc.project.symbols.located_vars()
            if not v.wildcard]


def overlaps(plc) -> list[str]:
    """Pairs of located variables that share bits (``%QW0`` and ``%QX0.0`` do, as on S7).

    >>> import plclab
    >>> overlaps(plclab.loads("PROGRAM P VAR w AT %QW0 : INT; b AT %QX0.0 : BOOL; END_VAR "
    ...                       "b := TRUE; END_PROGRAM"))
    ['P.w (%QW0) and P.b (%QX0.0) share bits']
    """
    items = []
    for name, address, _ in located_variables(plc):
        area, size, byte, bit = parse_address(address)
        if size == "X":
            bits = {(area, byte, bit)}
        else:
            bits = {(area, b, i) for b in range(byte, byte + _BYTES[size]) for i in range(8)}
        items.append((name, address, bits))
    out = []
    for i, (n1, a1, b1) in enumerate(items):
        for n2, a2, b2 in items[i + 1:]:
            if b1 & b2:
                out.append(f"{n1} ({a1}) and {n2} ({a2}) share bits")
    return out


def map_rows(plc, *, allow_coil_writes: bool = False,
             read_only_inputs: bool = False) -> tuple[list[dict], list[str]]:
    """One row per located variable (see :data:`MAP_COLUMNS`) and the names left unmapped."""
    rows, unmapped = [], []
    for name, address, ty in located_variables(plc):
        e = locate(address, allow_coil_writes=allow_coil_writes)
        if e is None:
            unmapped.append(f"{name} AT {address}")
            continue
        w = None if read_only_inputs else input_window(address)
        rows.append({
            "name": name, "address": address, "type": ty, "table": e.table,
            "number": e.number, "ref": e.number + 1, "bit": "" if e.bit is None else e.bit,
            "words": e.words, "access": e.access,
            "write_table": w.table if w else (e.table if "write" in e.access
                                               or "force" in e.access else ""),
            "write_number": w.number if w else (e.number if "write" in e.access
                                                 or "force" in e.access else ""),
        })
    order = {COIL: 0, DISCRETE_INPUT: 1, INPUT_REGISTER: 2, HOLDING_REGISTER: 3}
    rows.sort(key=lambda r: (order[r["table"]], r["number"], r["bit"] if r["bit"] != "" else -1))
    return rows, unmapped


def write_map(path: str, rows: list[dict]) -> None:
    """Write the map as CSV (``.csv``) or JSON (``.json``)."""
    low = path.lower()
    if low.endswith(".json"):
        text = json.dumps({"device_id": 1, "numbers": "0-based (ref = number + 1)",
                           "variables": rows}, indent=2) + "\n"
    elif low.endswith(".csv"):
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=MAP_COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
        text = buf.getvalue()
    else:
        raise ValueError(f"--map {path}: give a .csv or .json file name")
    with open(path, "w", encoding="utf-8", newline="") as fh:
        fh.write(text)


def format_map(rows: list[dict], *, allow_coil_writes: bool, read_only_inputs: bool,
               unmapped: list[str] | None = None, shared: list[str] | None = None) -> str:
    """The address map as printed by ``plclab serve``."""
    coil_access = "read, write = force" if allow_coil_writes else "read only"
    win = "not mapped (--read-only-inputs)" if read_only_inputs else "read/write"
    lines = [
        "Modbus address map (device id 1, numbers 0-based; add 1 for mbpoll without -0):",
        f"  coils             0..8191      %QX0.0..%QX1023.7, coil n = %QX(n//8).(n%8)  [{coil_access}]",
        f"  coils             8192..16383  input terminals %IX, coil 8192+n  [{win}]",
        "  discrete inputs   0..8191      %IX0.0..%IX1023.7, input n = %IX(n//8).(n%8)",
        "  input registers   0..511       %IW0..%IW1022, register n = %IW(2n)",
        "  input registers   1024..1030   status: state, scans hi/lo, time ms hi/lo, io_ok, forced",
        "  holding registers 0..511       %MW0..%MW1022, register n = %MW(2n)  [read/write]",
        "  holding registers 1024..1535   %QW0..%QW1022, register 1024+n = %QW(2n)  [read only]",
        f"  holding registers 2048..2559   input terminals %IW, register 2048+n = %IW(2n)  [{win}]",
        "  holding register  4096         command: 1 = release forces  "
        + ("[write]" if allow_coil_writes else "[not writable]"),
    ]
    if rows:
        lines.append("Located variables:")
        for r in rows:
            bit = f" bit {r['bit']}" if r["bit"] != "" else ""
            words = f" ({r['words']} registers)" if r["words"] > 1 else ""
            lines.append(f"  {r['name']:<24} {r['address']:<9} {r['type']:<8} "
                         f"{r['table']} {r['number']}{bit}{words}")
    for u in unmapped or []:
        lines.append(f"  {u}: beyond the first {MAPPED_BYTES} bytes, not mapped")
    for o in shared or []:
        lines.append(f"note: {o} (words are byte-addressed: %QW0 is %QX0.0..%QX1.7)")
    return "\n".join(lines)


# -- plant signals <-> registers -------------------------------------------------------------
#: full scale of an analog value in a register, as on an S7 analog module (0..27648)
ANALOG_FULL_SCALE = 27648


def to_register(value: float, low: float, high: float) -> int:
    """Scale an engineering value to a 16-bit register: ``low`` -> 0, ``high`` -> 27648.

    The result is a signed INT stored as two's complement (0..65535 on the wire).

    >>> to_register(1.0, 0.0, 2.0), to_register(-1.0, 0.0, 2.0)
    (13824, 51712)
    """
    span = (high - low) or 1.0
    raw = round((float(value) - low) / span * ANALOG_FULL_SCALE)
    raw = max(-32768, min(32767, raw))
    return raw & 0xFFFF


def from_register(reg: int, low: float, high: float) -> float:
    """The inverse of :func:`to_register` (the register read as a signed INT).

    >>> from_register(13824, 0.0, 2.0)
    1.0
    """
    raw = reg - 65536 if reg >= 32768 else reg
    return low + raw * (high - low) / ANALOG_FULL_SCALE
