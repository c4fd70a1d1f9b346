"""Signals as step series: the common currency of timing diagrams, VCD, WaveDrom and chatter
analysis. A :class:`Series` holds sample times (seconds) and values; a BOOL/integer signal is
piecewise constant between samples (step-after), a REAL one is drawn as a line.

>>> s = Series("PUMP", [0.0, 0.01, 0.02, 0.03], [False, True, True, False], "bool")
>>> s.changes()
[(0.0, False), (0.01, True), (0.03, False)]
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any


@dataclass
class Series:
    name: str
    times: Sequence[float]
    values: Sequence[Any]
    kind: str = "real"  # bool | int | real | enum | string
    unit: str = ""
    labels: dict[int, str] = field(default_factory=dict)  # enum value -> name

    def __post_init__(self) -> None:
        if len(self.times) != len(self.values):
            raise ValueError(f"{self.name}: {len(self.times)} times but {len(self.values)} "
                             "values")

    def changes(self) -> list[tuple[float, Any]]:
        """(time, value) at the first sample and wherever the value changes."""
        if _is_array(self.times) and _is_array(self.values) and len(self.values) > 1:
            return _array_changes(self.times, self.values)
        if len(self.values) > 64:  # a windowed column (lists): NumPy is many times faster
            arrays = _as_arrays(self.times, self.values)
            if arrays is not None:
                return _array_changes(*arrays)
        out: list[tuple[float, Any]] = []
        prev = object()
        for t, v in zip(self.times, self.values, strict=True):
            v = _py(v)
            if v != prev:
                out.append((float(t), v))
                prev = v
        return out

    def window(self, t0: float | None, t1: float | None) -> Series:
        """The samples with t0 <= t <= t1 (the value holding at t0 is kept as a first sample)."""
        if t0 is None and t1 is None:
            return self
        lo = float("-inf") if t0 is None else t0
        hi = float("inf") if t1 is None else t1
        if len(self.times) and self.times[0] >= lo and self.times[-1] <= hi:
            return self  # already inside (a windowed series drawn again): no copy
        if _is_array(self.times) and _is_array(self.values):
            ts, vs = _array_window(self.times, self.values, lo, hi)
            return Series(self.name, ts, vs, self.kind, self.unit, self.labels)
        ts, vs = [], []
        before = None
        for t, v in zip(self.times, self.values, strict=True):
            if t < lo:
                before = v
                continue
            if t > hi:
                break
            if not ts and before is not None and t > lo:
                ts.append(lo)
                vs.append(before)
            ts.append(t)
            vs.append(v)
        if not ts and before is not None:
            ts, vs = [lo], [before]
        return Series(self.name, ts, vs, self.kind, self.unit, self.labels)

    def label(self, v: Any) -> str:
        if self.kind == "enum" and int(v) in self.labels:
            return self.labels[int(v)]
        if self.kind == "bool":
            return "TRUE" if v else "FALSE"
        if isinstance(v, float):
            return f"{v:.4g}"
        return str(v)


def _is_array(x: Any) -> bool:
    """A NumPy array (a trace's column): windowed and scanned by NumPy, not element-wise."""
    return hasattr(x, "dtype") and hasattr(x, "searchsorted") and getattr(x, "ndim", 0) == 1


def _array_window(times: Any, values: Any, lo: float, hi: float) -> tuple[list, list]:
    """:meth:`Series.window` of sorted NumPy columns (binary search, then one slice)."""
    i = int(times.searchsorted(lo, "left"))
    j = int(times.searchsorted(hi, "right"))
    ts, vs = times[i:j].tolist(), values[i:j].tolist()
    if i > 0 and (not ts or ts[0] > lo):
        ts.insert(0, lo)
        vs.insert(0, values[i - 1].item())
    return ts, vs


def _as_arrays(times: Sequence[float], values: Sequence[Any]) -> tuple[Any, Any] | None:
    """Plain lists of numbers or booleans as NumPy arrays (None: NumPy missing, or values of
    another or mixed type, which keep the element-wise path)."""
    try:
        import numpy as np
    except ImportError:
        return None
    first = type(_py(values[0]))
    if first not in (bool, int, float) or any(type(v) is not first for v in values):
        return None
    return np.asarray(times, dtype=float), np.asarray(values)


def _array_changes(times: Any, values: Any) -> list[tuple[float, Any]]:
    """:meth:`Series.changes` of NumPy columns (one vectorised comparison)."""
    import numpy as np

    at = np.flatnonzero(values[1:] != values[:-1]) + 1
    keep = np.concatenate(([0], at))
    return list(zip(times[keep].astype(float).tolist(), values[keep].tolist(), strict=True))


def _py(v: Any) -> Any:
    """NumPy scalars to plain Python (so comparisons and JSON work)."""
    item = getattr(v, "item", None)
    return item() if callable(item) else v


def kind_of(values: Sequence[Any]) -> str:
    """Guess a series kind from its values."""
    for v in values:
        v = _py(v)
        if isinstance(v, bool):
            return "bool"
        if isinstance(v, int):
            return "int"
        if isinstance(v, float):
            return "real"
        if isinstance(v, str):
            return "string"
    return "real"
