"""The Trace: one columnar record of a simulation run.

A :class:`Trace` holds, for every recorded scan, the time and one NumPy array per column:

* every plant signal, under its own name (``LEVEL``, ``PUMP``);
* the PLC side of every wiring row, under the row's PLC address or variable (``%IX0.0``,
  ``%IW64``, ``Main.SP``); the plant side of a row is the plant signal's column
  (``trace.io`` lists the pairs);
* the watched PLC variables (``watch=[...]``), under the names given;
* optionally the plant's ``snapshot()`` extras under their keys (``volume``, ``bottle3.x``;
  ``snapshot:<key>`` when the name is taken).

Values are sample-and-hold: row ``i`` holds from ``time[i]`` until ``time[i+1]`` (the last row
until :attr:`Trace.t_end`). Besides the columns a trace has the events (plant events, faults,
operator actions, relay operations...), the exact edge times of digital I/O (``edges``) and, kept
apart because it is the only thing that differs between two runs of the same seed, the wall-clock
time of each PLC scan (``wall``).

Helpers answer the questions of labs and graders: :meth:`~Trace.value_at`,
:meth:`~Trace.time_in_band`, :meth:`~Trace.rise_time`, :meth:`~Trace.settling_time`,
:meth:`~Trace.overshoot`, :meth:`~Trace.switchings`, :meth:`~Trace.chatter_episodes`,
:meth:`~Trace.min_dwell`, :meth:`~Trace.first_time`, :meth:`~Trace.events_of`.

>>> import numpy as np
>>> tr = Trace(np.arange(5) * 1.0, {"X": np.array([0, 0, 1, 1, 0], dtype=bool)},
...            meta={"period": 1.0})
>>> tr.value_at("X", 2.5), tr.switchings("X"), tr.min_dwell("X")
(True, 2, (2.0, None))
>>> tr.time_in_band("X", 1, 1)
2.0
"""

from __future__ import annotations

import csv
import json
import math
import os
from collections.abc import Callable, Iterable
from typing import Any

from plclab.errors import PlcError

from .events import Event

FORMAT = "plclab-trace"
VERSION = 1
_DTYPES = {"bool": "bool", "int": "int64", "float": "float64"}


def _np():
    try:
        import numpy as np
    except ModuleNotFoundError:  # pragma: no cover - numpy is in the [sim] extra
        raise PlcError("PLC4021", "traces need NumPy: pip install 'plclab[sim]'") from None
    return np


def _err(msg: str) -> PlcError:
    return PlcError("PLC4021", msg)


class Trace:
    """A columnar record of a run (see the module docstring).

    Parameters
    ----------
    time : array of float
        Time of each row, s (simulation time: 0 at the start of the run).
    columns : dict of str -> array
        One array per column, as long as ``time``.
    kinds : dict of str -> {"bool", "int", "float"}, optional
        Column types (guessed from the arrays when missing).
    meta : dict, optional
        Run description: plant, signals, io rows, scan, seed... (JSON-able).
    events : list of Event, optional
    wall : dict, optional
        Wall-clock measurements: ``scan_s`` (array, s per PLC scan, aligned with ``time``)
        and ``run_s`` (float). Never compared by :meth:`equals`.
    edges : dict of str -> (times, values), optional
        Exact edge times: ``<plc>.raw`` (a digital input's bouncing contact), ``<plc>.filtered``
        (the bit after the input filter), ``<plc>.contact`` (a digital output's contact).
    """

    def __init__(self, time: Any, columns: dict[str, Any], kinds: dict[str, str] | None = None,
                 meta: dict[str, Any] | None = None, events: Iterable[Event] | None = None,
                 wall: dict[str, Any] | None = None,
                 edges: dict[str, tuple[Any, Any]] | None = None) -> None:
        np = _np()
        self.time = np.asarray(time, dtype=np.float64)
        self.columns: dict[str, Any] = {}
        self.kinds: dict[str, str] = {}
        kinds = kinds or {}
        for name, col in columns.items():
            arr = np.asarray(col)
            if arr.shape != self.time.shape:
                raise _err(f"column {name!r} has {arr.shape[0] if arr.ndim else 0} rows, the "
                           f"time has {self.time.shape[0]}")
            kind = kinds.get(name) or ("bool" if arr.dtype == bool else
                                       "int" if arr.dtype.kind in "iu" else "float")
            self.columns[name] = arr.astype(_DTYPES[kind], copy=False)
            self.kinds[name] = kind
        self.meta: dict[str, Any] = dict(meta or {})
        self.events: list[Event] = list(events or [])
        self.wall: dict[str, Any] = dict(wall or {})
        self.edges: dict[str, tuple[Any, Any]] = {
            k: (np.asarray(t, dtype=np.float64), np.asarray(v)) for k, (t, v) in
            (edges or {}).items()}

    # ------------------------------------------------------------------ basics
    @property
    def names(self) -> list[str]:
        """Every column name."""
        return list(self.columns)

    @property
    def signals(self) -> list[str]:
        """The plant signals (the columns that are plant signals)."""
        sig = self.meta.get("signals")
        if sig:
            return [s for s in sig if s in self.columns]
        return [n for n in self.columns if ":" not in n and not n.startswith("%")]

    @property
    def io(self) -> list[dict[str, Any]]:
        """The wiring rows: plc, signal, module, direction, column (PLC side), plant_column."""
        return list(self.meta.get("io", []))

    @property
    def period(self) -> float:
        """Time between rows, s (scan time x decimation)."""
        p = self.meta.get("period")
        if p:
            return float(p)
        if len(self.time) > 1:
            return float(self.time[1] - self.time[0])
        return 0.0

    @property
    def t_end(self) -> float:
        """End of the last row's hold interval, s."""
        if "t_end" in self.meta:
            return float(self.meta["t_end"])
        if len(self.time) == 0:
            return 0.0
        return float(self.time[-1]) + self.period

    def __len__(self) -> int:
        return int(self.time.shape[0])

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and self._find(name) is not None

    def __getitem__(self, name: str) -> Any:
        return self.columns[self.resolve(name)]

    def __repr__(self) -> str:
        plant = self.meta.get("plant", "?")
        return (f"<Trace {plant}: {len(self)} rows, {len(self.columns)} columns, "
                f"{len(self.events)} events, {self.t_end:g} s>")

    def _find(self, name: str) -> str | None:
        cols = self.columns
        bare = name.split(":", 1)[1] if name.startswith(("plc:", "snapshot:")) else name
        cands = (name, f"plc:{name}", f"snapshot:{name}", bare)
        for cand in cands:
            if cand in cols:
                return cand
        low = [c.lower() for c in cands]
        for cand in low:
            for n in cols:
                if n.lower() == cand:
                    return n
        return None

    def resolve(self, name: str) -> str:
        """The column name for ``name``: exact, then with or without a ``plc:``/``snapshot:``
        prefix, then the same in any case."""
        found = self._find(str(name))
        if found is None:
            from ..suggest import did_you_mean

            hint = did_you_mean(name, self.columns, n=3)
            some = ", ".join(list(self.columns)[:30])
            raise _err(f"the trace has no column {name!r}.{hint} Columns: {some}"
                       + (" ..." if len(self.columns) > 30 else ""))
        return found

    def kind(self, name: str) -> str:
        """``bool``, ``int`` or ``float``."""
        return self.kinds[self.resolve(name)]

    # ------------------------------------------------------------------ windows
    def _range(self, t0: float | None, t1: float | None) -> tuple[float, float]:
        lo = float(self.time[0]) if (t0 is None and len(self)) else (t0 or 0.0)
        hi = self.t_end if t1 is None else float(t1)
        return float(lo), hi

    def _rows(self, t0: float | None, t1: float | None) -> slice:
        """Rows whose time lies in [t0, t1]."""
        np = _np()
        i0 = 0 if t0 is None else int(np.searchsorted(self.time, t0 - 1e-12, "left"))
        i1 = len(self) if t1 is None else int(np.searchsorted(self.time, t1 + 1e-12, "right"))
        return slice(i0, i1)

    def window(self, t0: float | None = None, t1: float | None = None) -> Trace:
        """A new trace with the rows in [t0, t1] (events and edges in that span too)."""
        sl = self._rows(t0, t1)
        lo, hi = self._range(t0, t1)
        meta = dict(self.meta)
        if t1 is not None:
            meta["t_end"] = min(hi, self.t_end)
        cols = {k: v[sl] for k, v in self.columns.items()}
        ev = [e for e in self.events if lo <= e.time <= hi]
        edges = {}
        for k, (t, v) in self.edges.items():
            m = (t >= lo) & (t <= hi)
            edges[k] = (t[m], v[m])
        wall = {k: (v[sl] if hasattr(v, "shape") and getattr(v, "shape", ()) == self.time.shape
                    else v) for k, v in self.wall.items()}
        return Trace(self.time[sl], cols, dict(self.kinds), meta, ev, wall, edges)

    # ------------------------------------------------------------------ helpers
    def value_at(self, name: str, t: float) -> Any:
        """The value of a column at time ``t`` (the last row at or before ``t``; the first
        row for earlier times).

        >>> import numpy as np
        >>> Trace([0.0, 1.0], {"A": np.array([1.0, 2.0])}).value_at("A", 0.99)
        1.0
        """
        np = _np()
        col = self[name]
        if len(col) == 0:
            raise _err("the trace is empty")
        i = int(np.searchsorted(self.time, t + 1e-12, "right")) - 1
        return col[max(i, 0)].item()

    def _hold(self, t0: float | None, t1: float | None) -> tuple[Any, Any]:
        """Start and end of every row's hold interval, clipped to [t0, t1]."""
        np = _np()
        lo, hi = self._range(t0, t1)
        ends = np.append(self.time[1:], max(self.t_end, float(self.time[-1]) if len(self) else 0))
        return np.clip(self.time, lo, hi), np.clip(ends, lo, hi)

    def time_in_band(self, name: str, lo: float, hi: float, t0: float | None = None,
                     t1: float | None = None, fraction: bool = False) -> float:
        """Seconds (or the fraction of [t0, t1] with ``fraction=True``) during which
        ``lo <= value <= hi``, with sample-and-hold between rows.

        >>> import numpy as np
        >>> tr = Trace([0.0, 1.0, 2.0, 3.0], {"T": np.array([10.0, 20.0, 30.0, 20.0])},
        ...            meta={"t_end": 4.0})
        >>> tr.time_in_band("T", 15, 25), tr.time_in_band("T", 15, 25, t0=0.5, t1=3.5)
        (2.0, 1.5)
        """
        if len(self) == 0:
            return 0.0
        x = self[name].astype(float)
        s, e = self._hold(t0, t1)
        inside = (x >= lo) & (x <= hi)
        total = float(((e - s) * inside).sum())
        if fraction:
            a, b = self._range(t0, t1)
            return total / (b - a) if b > a else 0.0
        return total

    def _window_xy(self, name: str, t0: float | None, t1: float | None) -> tuple[Any, Any]:
        sl = self._rows(t0, t1)
        t = self.time[sl]
        x = self[name][sl].astype(float)
        if len(t) == 0:
            raise _err(f"no rows of {name!r} between t0={t0} and t1={t1}")
        return t, x

    @staticmethod
    def _crossing(t: Any, x: Any, level: float, sign: float, start: int = 0) -> float | None:
        np = _np()
        idx = np.nonzero(sign * (x[start:] - level) >= 0)[0]
        if len(idx) == 0:
            return None
        i = int(idx[0]) + start
        if i == 0 or x[i] == x[i - 1]:
            return float(t[i])
        frac = (level - x[i - 1]) / (x[i] - x[i - 1])
        frac = min(max(frac, 0.0), 1.0)
        return float(t[i - 1] + frac * (t[i] - t[i - 1]))

    def rise_time(self, name: str, t0: float | None = None, t1: float | None = None,
                  low: float = 0.1, high: float = 0.9, initial: float | None = None,
                  final: float | None = None) -> float | None:
        """Time to go from ``low`` to ``high`` (fractions) of the step from ``initial`` (the
        value at ``t0``) to ``final`` (the value at ``t1``), with linear interpolation between
        rows; works for falling steps too. ``None`` when the signal does not get there.

        >>> import numpy as np
        >>> t = np.arange(0.0, 20.0, 0.5)
        >>> tr = Trace(t, {"Y": np.clip(t - 5.0, 0.0, 10.0)})
        >>> tr.rise_time("Y")                       # 1 .. 9 on a ramp of slope 1
        8.0
        """
        t, x = self._window_xy(name, t0, t1)
        y0 = float(x[0]) if initial is None else float(initial)
        y1 = float(x[-1]) if final is None else float(final)
        if y1 == y0:
            return None
        sign = 1.0 if y1 > y0 else -1.0
        ta = self._crossing(t, x, y0 + low * (y1 - y0), sign)
        if ta is None:
            return None
        np = _np()
        start = int(np.searchsorted(t, ta, "left"))
        tb = self._crossing(t, x, y0 + high * (y1 - y0), sign, max(start - 1, 0))
        return None if tb is None else tb - ta

    def settling_time(self, name: str, t0: float | None = None, tol: float = 0.02,
                      final: float | None = None, t1: float | None = None,
                      band: float | None = None, initial: float | None = None) -> float | None:
        """Seconds after ``t0`` from which the value stays within ``final +- band``.

        ``band`` defaults to ``tol`` x the step size ``|final - initial|`` (2 %); ``final``
        to the last value in the window, ``initial`` to the first. 0.0 when the value never
        leaves the band; ``None`` when it is still outside at the end.

        >>> import numpy as np
        >>> t = np.arange(0.0, 10.0, 1.0)
        >>> y = np.array([0, 5, 12, 9, 10.5, 10.1, 9.95, 10, 10, 10])
        >>> Trace(t, {"Y": y}).settling_time("Y", band=0.5)   # |9 - 10| > 0.5 at t = 3
        4.0
        """
        np = _np()
        t, x = self._window_xy(name, t0, t1)
        y1 = float(x[-1]) if final is None else float(final)
        y0 = float(x[0]) if initial is None else float(initial)
        if band is None:
            band = tol * abs(y1 - y0) or tol * abs(y1) or tol
        start = float(t[0]) if t0 is None else float(t0)
        out = np.nonzero(np.abs(x - y1) > band)[0]
        if len(out) == 0:
            return 0.0
        last = int(out[-1])
        if last == len(x) - 1:
            return None
        return float(t[last + 1]) - start

    def overshoot(self, name: str, t0: float | None = None, t1: float | None = None,
                  initial: float | None = None, final: float | None = None) -> float | None:
        """Overshoot as a fraction of the step (0.25 = 25 %): how far the value went beyond
        ``final`` (the last value in the window), relative to ``final - initial``. 0.0 when it
        never went beyond; ``None`` for a zero step.

        >>> import numpy as np
        >>> y = np.array([0.0, 6.0, 12.5, 9.0, 10.0])
        >>> Trace(np.arange(5.0), {"Y": y}).overshoot("Y")
        0.25
        """
        t, x = self._window_xy(name, t0, t1)
        y0 = float(x[0]) if initial is None else float(initial)
        y1 = float(x[-1]) if final is None else float(final)
        if y1 == y0:
            return None
        if y1 > y0:
            peak = float(x.max())
            return max(0.0, (peak - y1) / (y1 - y0))
        peak = float(x.min())
        return max(0.0, (y1 - peak) / (y0 - y1))

    def _changes(self, name: str, t0: float | None, t1: float | None) -> tuple[Any, Any]:
        """Rows where the value differs from the row before, within (t0, t1]."""
        np = _np()
        x = self[name]
        idx = np.nonzero(x[1:] != x[:-1])[0] + 1
        t = self.time[idx]
        m = np.ones(len(idx), dtype=bool)
        if t0 is not None:
            m &= t > t0
        if t1 is not None:
            m &= t <= t1
        return idx[m], t[m]

    def switchings(self, name: str, t0: float | None = None, t1: float | None = None) -> int:
        """Number of value changes at row times ``t`` with ``t0 < t <= t1``."""
        return int(len(self._changes(name, t0, t1)[0]))

    def chatter_episodes(self, name: str, min_toggles: int = 4, window: float = 1.0,
                         t0: float | None = None, t1: float | None = None
                         ) -> list[tuple[float, float, int]]:
        """Stretches where the value changed at least ``min_toggles`` times within ``window``
        seconds: ``[(start, end, changes), ...]`` (overlapping stretches are merged; start and
        end are the times of the first and last change).

        >>> import numpy as np
        >>> x = np.zeros(100, dtype=bool); x[10:20:2] = True; x[60] = True
        >>> Trace(np.arange(100.0), {"K": x}).chatter_episodes("K", 4, 10.0)
        [(10.0, 19.0, 10)]
        """
        np = _np()
        _, c = self._changes(name, t0, t1)
        if len(c) < min_toggles or min_toggles < 1:
            return []
        out: list[list[float]] = []
        for i in range(len(c)):
            j = int(np.searchsorted(c, c[i] + window + 1e-12, "right")) - 1
            if j - i + 1 >= min_toggles:
                a, b = float(c[i]), float(c[j])
                if out and a <= out[-1][1]:
                    out[-1][1] = max(out[-1][1], b)
                else:
                    out.append([a, b])
        return [(a, b, int(((c >= a) & (c <= b)).sum())) for a, b in out]

    def min_dwell(self, name: str, t0: float | None = None, t1: float | None = None
                  ) -> tuple[float | None, float | None]:
        """``(min_on, min_off)``: the shortest completed ON and OFF intervals (between two
        changes), s; ``None`` when there is none. Non-zero counts as ON."""
        idx, c = self._changes(name, t0, t1)
        if len(c) < 2:
            return None, None
        x = self[name]
        on = x[idx[:-1]].astype(bool)
        d = c[1:] - c[:-1]
        mon = float(d[on].min()) if on.any() else None
        moff = float(d[~on].min()) if (~on).any() else None
        return mon, moff

    def first_time(self, condition: str | Callable[[Trace], Any], t0: float | None = None
                   ) -> float | None:
        """The first row time (at or after ``t0``) at which ``condition`` holds, or ``None``.

        ``condition`` is an expression such as ``"LEVEL > 1.9 and not PUMP"`` (see
        :mod:`plclab.trace.expr`; names are columns, ``t`` is the time) or a callable that
        takes the trace and returns a boolean array.

        >>> import numpy as np
        >>> tr = Trace(np.arange(5.0), {"L": np.array([0.0, 1.0, 2.0, 3.0, 4.0])})
        >>> tr.first_time("L >= 2.5"), tr.first_time(lambda tr: tr["L"] > 9)
        (3.0, None)
        """
        np = _np()
        if callable(condition):
            mask = np.asarray(condition(self), dtype=bool)
        else:
            from .expr import parse_condition

            mask = parse_condition(condition).vector(self.__getitem__, self.time)
        if mask.shape != self.time.shape:
            raise _err("the condition must give one boolean per row")
        if t0 is not None:
            mask = mask & (self.time >= t0 - 1e-12)
        idx = np.nonzero(mask)[0]
        return float(self.time[idx[0]]) if len(idx) else None

    def events_of(self, kind: str | None = None, source: str | None = None,
                  t0: float | None = None, t1: float | None = None) -> list[Event]:
        """The events of one kind (and/or source) in [t0, t1], in time order."""
        out = []
        for e in self.events:
            if kind is not None and e.kind != kind:
                continue
            if source is not None and e.source != source:
                continue
            if t0 is not None and e.time < t0 or t1 is not None and e.time > t1:
                continue
            out.append(e)
        return out

    def event_counts(self) -> dict[str, tuple[int, float]]:
        """kind -> (count, first time), in order of first appearance."""
        out: dict[str, tuple[int, float]] = {}
        for e in self.events:
            n, first = out.get(e.kind, (0, e.time))
            out[e.kind] = (n + 1, first)
        return out

    def io_pair(self, target: str) -> tuple[Any, Any]:
        """``(plant_side, plc_side)`` arrays of the wiring row whose PLC side or signal is
        ``target``."""
        for row in self.io:
            if target in (row["plc"], row["column"], row["signal"]):
                return self[row["plant_column"]], self[row["column"]]
        raise _err(f"no wiring row for {target!r}; rows: "
                   + ", ".join(r["plc"] for r in self.io))

    def edge_series(self, name: str, dt: float = 0.001, t0: float | None = None,
                    t1: float | None = None) -> tuple[Any, Any]:
        """An edge record (``trace.edges``) sampled every ``dt`` s: ``(times, values)``.

        With ``dt=0.001`` a digital input's ``<plc>.raw`` edges show the contact bounce.
        """
        np = _np()
        if name not in self.edges:
            raise _err(f"no edge record {name!r}; records: {', '.join(self.edges) or '(none)'}")
        et, ev = self.edges[name]
        a, b = self._range(t0, t1)
        n = int(math.floor((b - a) / dt + 1e-9)) + 1
        ts = a + np.arange(n) * dt
        initial = self.meta.get("edge_initial", {}).get(name, False)
        i = np.searchsorted(et, ts + 1e-12, "right") - 1
        vals = np.where(i >= 0, ev[np.clip(i, 0, None)] if len(ev) else initial, initial)
        return ts, vals.astype(bool)

    # ------------------------------------------------------------------ comparing
    def equals(self, other: Trace) -> bool:
        """Same times, columns, events and edges (the wall-clock record is ignored)."""
        np = _np()
        if self.kinds != other.kinds or not np.array_equal(self.time, other.time):
            return False
        for k, v in self.columns.items():
            w = other.columns[k]
            if v.dtype.kind == "f":
                if not np.array_equal(v, w, equal_nan=True):
                    return False
            elif not np.array_equal(v, w):
                return False
        if [tuple(e) + (e.data,) for e in self.events] != \
                [tuple(e) + (e.data,) for e in other.events]:
            return False
        if set(self.edges) != set(other.edges):
            return False
        return all(np.array_equal(self.edges[k][0], other.edges[k][0])
                   and np.array_equal(self.edges[k][1], other.edges[k][1]) for k in self.edges)

    # ------------------------------------------------------------------ files
    def save(self, path: str | os.PathLike) -> None:
        """Save as ``.npz``: the arrays, the events as a JSON string array, the metadata as
        JSON; ``Trace.load`` reads it back (no pickle involved)."""
        np = _np()
        arrays: dict[str, Any] = {"time": self.time}
        names = []
        for i, (name, col) in enumerate(self.columns.items()):
            arrays[f"c{i:05d}"] = col
            names.append([name, self.kinds[name]])
        edges = []
        for i, (name, (t, v)) in enumerate(self.edges.items()):
            arrays[f"e{i:05d}_t"] = t
            arrays[f"e{i:05d}_v"] = v
            edges.append(name)
        wall_scalars = {}
        for k, v in self.wall.items():
            if hasattr(v, "shape") and getattr(v, "ndim", 0) > 0:
                arrays[f"wall_{k}"] = v
            else:
                wall_scalars[k] = v
        head = {"format": FORMAT, "version": VERSION, "columns": names, "edges": edges,
                "meta": self.meta, "wall": wall_scalars}
        arrays["meta"] = np.array(json.dumps(head, default=_json_default))
        arrays["events"] = np.array([json.dumps(e.to_json(), default=_json_default)
                                     for e in self.events], dtype=str)
        path = os.fspath(path)
        with open(path, "wb") as fh:
            np.savez_compressed(fh, **arrays)

    @classmethod
    def load(cls, path: str | os.PathLike) -> Trace:
        """Read a trace saved by :meth:`save`."""
        np = _np()
        path = os.fspath(path)
        try:
            z = np.load(path, allow_pickle=False)
        except FileNotFoundError:
            raise _err(f"{path}: no such trace file") from None
        except (OSError, ValueError) as e:
            raise _err(f"{path} is not a trace saved by plclab ({e})") from None
        with z:
            if "meta" not in z.files:
                raise _err(f"{path} is not a trace saved by plclab (no metadata)")
            head = json.loads(str(z["meta"][()]))
            if head.get("format") != FORMAT:
                raise _err(f"{path} is not a trace saved by plclab")
            cols = {}
            kinds = {}
            for i, (name, kind) in enumerate(head["columns"]):
                cols[name] = z[f"c{i:05d}"]
                kinds[name] = kind
            edges = {name: (z[f"e{i:05d}_t"], z[f"e{i:05d}_v"])
                     for i, name in enumerate(head.get("edges", []))}
            wall: dict[str, Any] = dict(head.get("wall", {}))
            for f in z.files:
                if f.startswith("wall_"):
                    wall[f[5:]] = z[f]
            events = [Event.from_json(json.loads(s)) for s in z["events"].tolist()]
            return cls(z["time"], cols, kinds, head.get("meta", {}), events, wall, edges)

    def to_csv(self, path: str | os.PathLike, names: Iterable[str] | None = None,
               events_path: str | os.PathLike | None = None) -> None:
        """Write ``time`` and the columns (all, or ``names``) as CSV; BOOL as 0/1, REAL with
        full precision. ``events_path`` also writes the events (time, kind, source, message)."""
        np = _np()
        cols = [self.resolve(n) for n in names] if names is not None else list(self.columns)
        texts = [[repr(float(x)) for x in self.time.tolist()]]
        for c in cols:
            arr = self.columns[c]
            if arr.dtype == bool:
                texts.append(np.where(arr, "1", "0").tolist())
            elif arr.dtype.kind in "iu":
                texts.append([str(v) for v in arr.tolist()])
            else:
                texts.append([repr(v) for v in arr.tolist()])
        with open(os.fspath(path), "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(["time"] + cols)
            w.writerows(zip(*texts, strict=True))
        if events_path is not None:
            with open(os.fspath(events_path), "w", newline="", encoding="utf-8") as fh:
                w = csv.writer(fh)
                w.writerow(["time", "kind", "source", "message"])
                for e in self.events:
                    w.writerow([repr(e.time), e.kind, e.source, e.message])

    # ------------------------------------------------------------------ reports
    def summary(self, finals: bool = True) -> str:
        """A short text report: span, events by kind with first times, final values."""
        lines = [f"{self.meta.get('plant', '?')}: {self.t_end:g} s simulated, {len(self)} rows "
                 f"of {len(self.columns)} columns"]
        reason = self.meta.get("stop_reason")
        if reason:
            lines.append(f"stopped: {reason}")
        counts = self.event_counts()
        if counts:
            lines.append("events:")
            for kind, (n, first) in counts.items():
                lines.append(f"  {kind:<22} {n:>6} x   first at {first:.3f} s")
        else:
            lines.append("events: none")
        if finals and len(self):
            lines.append("final values:")
            for name in self.signals:
                v = self.columns[name][-1].item()
                unit = self.meta.get("units", {}).get(name, "")
                lines.append(f"  {name:<16} {_fmt(v)} {unit}".rstrip())
        return "\n".join(lines)


def _fmt(v: Any) -> str:
    if isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def _json_default(o: Any) -> Any:
    if hasattr(o, "tolist"):
        return o.tolist()
    if isinstance(o, tuple | set):
        return list(o)
    return str(o)


def load(path: str | os.PathLike) -> Trace:
    """Read a ``.npz`` trace (same as :meth:`Trace.load`)."""
    return Trace.load(path)
