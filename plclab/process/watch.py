"""Watch tables: variables and addresses with display formats, sampled at a trigger point.

TIA Portal's watch table (``001_c648febd3bbd6efb.txt``, lines 3890-4080, Table 14) monitors
and modifies PLC tags at a chosen point of the scan cycle: at scan start (after the CPU has
read its inputs), at scan end (before it writes its outputs) or on the transition to STOP,
permanently or once. A row may also *modify* its tag (write it once, at the trigger point) or
*force* it (hold it every scan); see ADR 0025.

>>> import plclab
>>> plc = plclab.loads('''PROGRAM Main
... VAR a AT %IX0.0 : BOOL; n : INT; END_VAR
... IF a THEN n := n + 1; END_IF;
... END_PROGRAM''')
>>> table = WatchTable([WatchRow("a", "bool"), WatchRow("n", "hex")], trigger="scan_end")
>>> table.attach(plc)
>>> plc.modify("a", True)   # once, at the next scan start
>>> plc.scan(3)
>>> [s.values for s in table.samples]
[(True, 1), (False, 1), (False, 1)]
>>> table.show()
'a  FALSE\\nn  16#0001'
"""

from __future__ import annotations

import collections
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import PlcError, printable
from plclab.process.files import read_toml

TRIGGERS = ("scan_start", "scan_end", "stop")
FORMATS = ("auto", "bool", "dec", "hex", "bin", "oct", "float", "char", "time")


@dataclass
class WatchRow:
    """One row: a tag (variable path or address), its display format, an optional modify or
    force value."""

    name: str
    format: str = "auto"
    modify: Any = None
    force: Any = None
    comment: str = ""

    def __post_init__(self) -> None:
        if self.format not in FORMATS:
            raise PlcError("PLC6010", f"watch row {self.name}: display format {self.format!r} "
                           f"is unknown; use one of {', '.join(FORMATS)}")


@dataclass
class Sample:
    """The values of every row at one trigger point."""

    time: float
    trigger: str
    scan: int
    values: tuple[Any, ...]


@dataclass
class WatchTable:
    """Rows sampled at ``trigger`` (``scan_start``, ``scan_end``, ``stop``), every time
    (``once=False``, TIA's *permanently*) or the first time only."""

    rows: list[WatchRow]
    trigger: str = "scan_end"
    once: bool = False
    modify_at: str = "scan_start"
    name: str = "watch"
    max_samples: int = 100_000
    samples: collections.deque = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if self.trigger not in TRIGGERS:
            raise PlcError("PLC6010", f"watch table {self.name}: trigger {self.trigger!r} is "
                           f"unknown; use one of {', '.join(TRIGGERS)}")
        if self.modify_at not in ("scan_start", "scan_end"):
            raise PlcError("PLC6010", f"watch table {self.name}: modify_at is 'scan_start' or "
                           "'scan_end'")
        self.samples = collections.deque(maxlen=self.max_samples)
        self._plc: Any = None
        self._getters: list[Any] = []
        self._types: list[Any] = []

    # ----------------------------------------------------------------- attaching
    def attach(self, plc: Any) -> None:
        """Sample on ``plc``'s trigger point; apply the rows' forces and one-shot modifies."""
        if self._plc is not None:
            raise PlcError("PLC6010", f"watch table {self.name} is already attached to a PLC")
        self._plc = plc
        self._getters, self._types = [], []
        for r in self.rows:
            try:
                v = plc.var(r.name)
            except PlcError as e:
                raise PlcError("PLC6011", f"watch row {r.name}: {e.message}") from None
            self._getters.append(_image_getter(plc, r.name) if r.name.lstrip().startswith("%")
                                 else v.get)
            self._types.append(v.type)
            if r.force is not None:
                plc.force(r.name, r.force)
            if r.modify is not None:
                plc.modify(r.name, r.modify, at=self.modify_at)
        plc.triggers[self.trigger].append(self._on_trigger)

    def detach(self) -> None:
        """Stop sampling (forces stay until ``plc.unforce()``)."""
        if self._plc is not None:
            cbs = self._plc.triggers[self.trigger]
            if self._on_trigger in cbs:
                cbs.remove(self._on_trigger)
            self._plc = None

    def _on_trigger(self, plc: Any, at: str) -> None:
        self.samples.append(Sample(plc.ctx.now_ns / 1e9, at, plc.ctx.scan_count,
                                   tuple(g() for g in self._getters)))
        if self.once:
            plc.triggers[at].remove(self._on_trigger)

    def monitor_now(self) -> tuple[Any, ...]:
        """TIA's *Monitor now*: the values at once, outside the trigger point."""
        if self._plc is None:
            raise PlcError("PLC6011", f"watch table {self.name} is not attached; call "
                           "table.attach(plc) first")
        return tuple(g() for g in self._getters)

    # ----------------------------------------------------------------- display
    def show(self, values: tuple[Any, ...] | None = None) -> str:
        """The table as text: name and formatted value, one row a line (last sample)."""
        if values is None:
            values = self.samples[-1].values if self.samples else self.monitor_now()
        width = max((len(r.name) for r in self.rows), default=0)
        return "\n".join(f"{printable(r.name):<{width}}  {format_value(v, r.format)}"
                         for r, v in zip(self.rows, values, strict=True))

    def report(self, last: int = 10) -> str:
        """The last ``last`` samples as a table: time, scan, then one column a row."""
        rows = list(self.samples)[-last:]
        head = ["t (s)", "scan"] + [printable(r.name) for r in self.rows]
        body = [[f"{s.time:g}", str(s.scan)] + [format_value(v, r.format)
                                               for r, v in zip(self.rows, s.values, strict=True)]
                for s in rows]
        widths = [max(len(x) for x in col) for col in zip(head, *body, strict=True)]
        lines = [f"watch table {self.name}: {len(self.samples)} sample(s) at {self.trigger}"
                 f"{' (once)' if self.once else ''}" + (f", the last {len(rows)}:"
                                                        if len(self.samples) > len(rows) else ":")]
        for r in [head, *body]:
            lines.append("  ".join(x.rjust(w) for x, w in zip(r, widths, strict=True)))
        return "\n".join(lines)

    # ----------------------------------------------------------------- files
    @classmethod
    def load(cls, path: str | Path) -> WatchTable:
        """Read a watch table from TOML (see ``docs/scada.md``)."""
        return cls.from_dict(read_toml(path, "PLC6010", "watch table"), str(path))

    @classmethod
    def from_dict(cls, data: dict[str, Any], source: str = "watch table") -> WatchTable:
        known = {"name", "trigger", "once", "modify_at", "row"}
        extra = set(data) - known
        if extra:
            raise PlcError("PLC6010", f"{source}: unknown key(s) {', '.join(sorted(extra))}; "
                           f"a watch table has {', '.join(sorted(known))}")
        rows = []
        for i, r in enumerate(data.get("row", []), 1):
            if not isinstance(r, dict) or not isinstance(r.get("name"), str):
                raise PlcError("PLC6010", f"{source}: [[row]] {i} needs name = \"Main.X\" or an "
                               "address such as \"%IX0.0\"")
            bad = set(r) - {"name", "format", "modify", "force", "comment"}
            if bad:
                raise PlcError("PLC6010", f"{source}: [[row]] {r['name']}: unknown key(s) "
                               f"{', '.join(sorted(bad))}; a row has name, format, modify, "
                               "force, comment")
            rows.append(WatchRow(r["name"], str(r.get("format", "auto")), r.get("modify"),
                                 r.get("force"), str(r.get("comment", ""))))
        if not rows:
            raise PlcError("PLC6010", f"{source}: the table has no [[row]]")
        return cls(rows, str(data.get("trigger", "scan_end")), bool(data.get("once", False)),
                   str(data.get("modify_at", "scan_start")), str(data.get("name", "watch")))

    # ----------------------------------------------------------------- simulation hook
    def bind(self, sim: Any) -> None:
        """Simulation hook: attach to its PLC; scan-start/end samples become Trace columns
        ``<name>@<trigger>``, STOP samples become ``watch`` events."""
        self.attach(sim.plc)
        self._group = None
        self._col_rows: list[int] = []
        if self.trigger == "stop":
            return
        names, kinds = [], []
        for i, (r, ty) in enumerate(zip(self.rows, self._types, strict=True)):
            kind = _kind_of(ty)
            if kind is None:
                continue
            self._col_rows.append(i)
            names.append(f"{r.name}@{self.trigger}")
            kinds.append(kind)
        self._group = sim.recorder.add(f"watchtable:{self.name}", names, kinds)
        self._row: tuple[Any, ...] = tuple(False if k == "bool" else 0 for k in kinds)
        self._seen: Sample | None = None

    def after_scan(self, sim: Any, t_ns: int, recorded: bool) -> None:
        """Record the newest sample (a value holds between samples, e.g. with ``once``)."""
        if self._group is None or not recorded:
            return
        if self.samples and self.samples[-1] is not self._seen:
            last = self._seen = self.samples[-1]
            self._row = tuple(_num(last.values[i]) for i in self._col_rows)
        self._group.rows.append(self._row)

    def finish(self, sim: Any) -> tuple[list[Any], dict[str, Any]]:
        from plclab.trace.events import Event

        events = []
        if self.trigger == "stop":
            for s in self.samples:
                text = ", ".join(f"{r.name}={format_value(v, r.format)}"
                                 for r, v in zip(self.rows, s.values, strict=True))
                events.append(Event(s.time, "watch", self.name, f"on STOP: {text}",
                                    {r.name: v for r, v in zip(self.rows, s.values,
                                                               strict=True)}))
        meta = {"watch_tables": {self.name: {
            "trigger": self.trigger, "once": self.once,
            "rows": [{"name": r.name, "format": r.format} for r in self.rows]}}}
        return events, meta


def _image_getter(plc: Any, address: str) -> Any:
    """Read an address from the process image the program sees (%I: the input image, %Q:
    the output image before it reaches the terminals, %M: memory), as TIA monitors it."""
    from plclab.runtime.plc import check_address

    area, size, byte, bit = check_address(address.strip().upper(), plc.image_size)
    n = {"X": 1, "B": 1, "W": 2, "D": 4, "L": 8}[size]
    attr = {"I": "image_in", "Q": "image_out", "M": "memory"}[area]

    def get() -> Any:
        b = getattr(plc, attr)
        if size == "X":
            return bool(b[byte] >> int(bit or 0) & 1)
        return int.from_bytes(b[byte:byte + n], "big")

    return get


def _kind_of(ty: Any) -> str | None:
    from plclab.lang import types as T

    k = T.base_of(ty).kind
    if k == "bool":
        return "bool"
    if k in ("int", "bits", "time", "enum"):
        return "int"
    if k == "real":
        return "float"
    return None


def _num(v: Any) -> Any:
    if isinstance(v, bool | int | float):
        return v
    ns = getattr(v, "ns", None)
    return ns if isinstance(ns, int) else math.nan


def format_value(value: Any, fmt: str = "auto") -> str:
    """A value in one of TIA Portal's display formats.

    >>> format_value(True, "bool"), format_value(255, "hex"), format_value(5, "bin")
    ('TRUE', '16#00FF', '2#0000_0101')
    >>> format_value(65, "char"), format_value(1500, "time"), format_value(2.5, "float")
    ("'A'", 'T#1s500ms', '2.500000')
    """
    if isinstance(value, bool):
        if fmt in ("auto", "bool"):
            return "TRUE" if value else "FALSE"
        value = int(value)
    if not isinstance(value, int | float):  # a string or a block: an IEC form, never raw
        return _iec_text(value)
    if fmt == "auto":
        return f"{value:g}" if isinstance(value, float) else str(value)
    if fmt == "float":
        return f"{float(value):.6f}"
    if isinstance(value, float):
        if not math.isfinite(value):
            return str(value)
        value = int(value)
    if fmt == "dec":
        return str(value)
    if fmt == "bool":
        return "TRUE" if value else "FALSE"
    width = 16 if -32768 <= value < 65536 else 32
    u = value & ((1 << width) - 1)
    if fmt == "hex":
        return f"16#{u:0{width // 4}X}"
    if fmt == "oct":
        return f"8#{u:o}"
    if fmt == "bin":
        digits = f"{u:0{8 if u < 256 else width}b}"
        return "2#" + "_".join(digits[i:i + 4] for i in range(0, len(digits), 4))
    if fmt == "char":
        return repr(chr(value)) if 32 <= value < 127 else f"'${value:02X}'"
    if fmt == "time":
        return _time_text(value)
    return str(value)


def _iec_text(value: Any) -> str:
    """A string as an IEC literal (``$1B`` for an escape: nothing a terminal acts on), a
    block instance as its type, never a Python repr (ADR 0041)."""
    from plclab.runtime.rt import format_value as iec_format

    return printable(iec_format(value, ""))


def _time_text(ms: int) -> str:
    if ms == 0:
        return "T#0ms"
    sign = "-" if ms < 0 else ""
    ms = abs(ms)
    parts = []
    for unit, size in (("d", 86_400_000), ("h", 3_600_000), ("m", 60_000), ("s", 1000)):
        if ms >= size:
            parts.append(f"{ms // size}{unit}")
            ms %= size
    if ms:
        parts.append(f"{ms}ms")
    return f"T#{sign}{''.join(parts)}"
