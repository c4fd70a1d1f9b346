"""Exports of step series: VCD (GTKWave), WaveDrom WaveJSON and CSV.

VCD: BOOLs are 1-bit wires, integers and enumerations 32/64-bit vectors (``integer``), REALs
``real``; every signal's changes are merged and sorted so time never runs backwards.
"""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .series import Series


def _ident(name: str) -> str:
    """VCD/WaveDrom-safe signal name (no spaces; dots kept as in the PLC path)."""
    return "".join(c if c.isalnum() or c in "._[]" else "_" for c in name)


def write_vcd(series: Sequence[Series], path: str | Path, timescale_us: int = 1000,
              scope: str = "plclab") -> Path:
    """Write a VCD file; ``timescale_us`` is the time unit in µs (default 1 ms)."""
    from vcd import VCDWriter  # pyvcd, from the [viz] extra

    path = Path(path)
    unit = {1: "1 us", 10: "10 us", 100: "100 us", 1000: "1 ms", 10000: "10 ms",
            100000: "100 ms", 1000000: "1 s"}[timescale_us]
    events: list[tuple[int, int, Any]] = []
    with open(path, "w", encoding="ascii") as fh, VCDWriter(fh, timescale=unit,
                                                            date="plclab") as w:
        handles = []
        for k, s in enumerate(series):
            ch = s.changes()
            init = ch[0][1] if ch else None
            if s.kind == "bool":
                var = w.register_var(scope, _ident(s.name), "wire", size=1,
                                     init=bool(init) if init is not None else False)
            elif s.kind == "real":
                var = w.register_var(scope, _ident(s.name), "real",
                                     init=float(init) if init is not None else 0.0)
            elif s.kind == "string":
                var = w.register_var(scope, _ident(s.name), "string",
                                     init=str(init) if init is not None else "")
            else:
                var = w.register_var(scope, _ident(s.name), "integer", size=64,
                                     init=int(init) if init is not None else 0)
            handles.append(var)
            for t, v in ch[1:]:
                events.append((round(t * 1e6 / timescale_us), k, v))
        events.sort(key=lambda e: (e[0], e[1]))
        for ts, k, v in events:
            s = series[k]
            if s.kind == "bool":
                v = bool(v)
            elif s.kind == "real":
                v = float(v)
            elif s.kind != "string":
                v = int(v)
            w.change(handles[k], ts, v)
    return path


def wavejson(series: Sequence[Series], tick: float | None = None, t0: float | None = None,
             t1: float | None = None, max_ticks: int = 200, title: str = "") -> dict:
    """WaveDrom WaveJSON: one character per tick ('0'/'1' for BOOLs, '=' with data labels for
    integers, enumerations and REALs, '.' while unchanged)."""
    if not series:
        return {"signal": []}
    start = t0 if t0 is not None else min(s.times[0] for s in series if len(s.times))
    end = t1 if t1 is not None else max(s.times[-1] for s in series if len(s.times))
    span = max(end - start, 1e-9)
    if tick is None or span / tick + 1 > max_ticks:
        tick = span / (max_ticks - 1)
    n = max(1, int(round(span / tick)) + 1)  # one character per sample, both ends included
    signals = []
    for s in series:
        wave, data = [], []
        prev: Any = object()
        idx = 0
        times, values = s.times, s.values
        for i in range(n):
            t = start + i * tick
            while idx + 1 < len(times) and times[idx + 1] <= t + 1e-12:
                idx += 1
            v = values[idx] if len(values) else None
            v = v.item() if hasattr(v, "item") else v
            if v == prev:
                wave.append(".")
                continue
            prev = v
            if s.kind == "bool":
                wave.append("1" if v else "0")
            else:
                wave.append("=")
                data.append(s.label(v))
        entry: dict[str, Any] = {"name": s.name, "wave": "".join(wave)}
        if data:
            entry["data"] = data
        signals.append(entry)
    out: dict[str, Any] = {"signal": signals, "config": {"hscale": 1}}
    out["head"] = {"text": title or f"{start:g} s .. {end:g} s, tick {tick * 1000:g} ms"}
    return out


def write_wavedrom(series: Sequence[Series], path: str | Path, **kw) -> Path:
    path = Path(path)
    path.write_text(json.dumps(wavejson(series, **kw), indent=1), encoding="utf-8")
    return path


def render_wavedrom_svg(wave: dict, path: str | Path) -> Path:
    """Render WaveJSON to SVG with the ``wavedrom`` package (offline)."""
    import wavedrom

    path = Path(path)
    wavedrom.render(json.dumps(wave)).saveas(str(path))
    return path


def to_csv(series: Sequence[Series], path: str | Path | None = None) -> str:
    """CSV with one column per signal on the union of all sample times (step-after)."""
    times = sorted({float(t) for s in series for t in s.times})
    cursors = [0] * len(series)
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["time_s"] + [s.name for s in series])
    for t in times:
        row: list[Any] = [f"{t:.6f}"]
        for k, s in enumerate(series):
            while cursors[k] + 1 < len(s.times) and s.times[cursors[k] + 1] <= t:
                cursors[k] += 1
            if len(s.times) and s.times[cursors[k]] <= t:
                v = s.values[cursors[k]]
                v = v.item() if hasattr(v, "item") else v
                row.append(int(v) if isinstance(v, bool) else v)
            else:
                row.append("")
        w.writerow(row)
    text = buf.getvalue()
    if path is not None:
        Path(path).write_text(text, encoding="utf-8")
    return text
