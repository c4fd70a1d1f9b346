"""Tag logging: process values archived from a Trace, cyclically or on change.

WinCC's *Tag Logging* (``001_c648febd3bbd6efb.txt``, lines 6250-6300) collects process values
into archives, on a cycle or when a value changes, and shows them as trends or tables. Here the
Trace is the record of the run (design principle 6), so an archive is a view of a Trace:
one row per logged value, ``(time, tag, value)`` in WinCC's narrow table form, written to
CSV or, when ``pyarrow`` is installed, Parquet.

>>> import numpy as np
>>> from plclab.trace import Trace
>>> tr = Trace(np.arange(5) * 0.5, {"T": np.array([20.0, 20.0, 21.0, 21.05, 23.0])},
...            meta={"t_end": 2.5})
>>> [(r.time, r.value) for r in archive(tr, ["T"], mode="cycle", cycle=1.0)]
[(0.0, 20.0), (1.0, 21.0), (2.0, 23.0)]
>>> [(r.time, r.value) for r in archive(tr, ["T"], mode="on_change", deadband=0.1)]
[(0.0, 20.0), (1.0, 21.0), (2.0, 23.0)]
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from plclab.errors import PlcError

MODES = ("cycle", "on_change")


@dataclass(frozen=True)
class ArchiveRow:
    """One archived value."""

    time: float
    tag: str
    value: float | bool | int


def archive(trace: Any, tags: list[str], mode: str = "cycle", cycle: Any = 1.0,
            deadband: float = 0.0) -> list[ArchiveRow]:
    """The archive of ``tags`` (Trace columns): every ``cycle`` seconds, or each time a value
    moves by more than ``deadband`` from the last logged one (``on_change``), by time."""
    if mode not in MODES:
        raise PlcError("PLC6030", f"archive mode {mode!r}: use 'cycle' or 'on_change'")
    if isinstance(cycle, str):
        from plclab.durations import parse_duration

        ns = parse_duration(cycle)
        if ns is None:
            raise PlcError("PLC6030", f"archive cycle {cycle!r} is not a duration (e.g. \"1s\")")
        cycle = ns / 1e9
    if isinstance(cycle, bool) or not isinstance(cycle, int | float) or cycle <= 0:
        raise PlcError("PLC6030", f"archive cycle {cycle!r}: give a positive time, e.g. 1.0")
    if deadband < 0:
        raise PlcError("PLC6030", "archive deadband is 0 or more")
    t = trace.time
    rows: list[ArchiveRow] = []
    for tag in tags:
        try:
            name = trace.resolve(tag)
        except PlcError as e:
            raise PlcError("PLC6030", f"archive tag {tag}: {e.message}") from None
        col = trace[name]
        last: Any = None
        next_t = float(t[0]) if len(t) else 0.0
        for i in range(len(t)):
            ti = float(t[i])
            v = col[i].item()
            if mode == "cycle":
                if ti + 1e-9 < next_t:
                    continue
                next_t += cycle * max(1, int((ti - next_t) // cycle) + 1)
            elif last is not None and (v == last if isinstance(v, bool) else
                                       abs(v - last) <= deadband):
                continue
            last = v
            rows.append(ArchiveRow(round(ti, 9), tag, v))
    rows.sort(key=lambda r: (r.time, tags.index(r.tag)))
    return rows


def write_csv(rows: list[ArchiveRow], path: str | Path) -> Path:
    """Rows as CSV: ``time_s,tag,value``."""
    path = Path(path)
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "tag", "value"])
        for r in rows:
            w.writerow([f"{r.time:.9g}", r.tag, r.value])
    return path


def write_parquet(rows: list[ArchiveRow], path: str | Path) -> Path:
    """Rows as Parquet (needs ``pyarrow``): columns time_s, tag, value (float)."""
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise PlcError("PLC6030", "Parquet archives need pyarrow: pip install pyarrow, or "
                       "write CSV") from None
    table = pa.table({"time_s": [r.time for r in rows], "tag": [r.tag for r in rows],
                      "value": [float(r.value) for r in rows]})
    pq.write_table(table, str(path))
    return Path(path)
