"""The SFC lane of a timing diagram: one bus row per chart whose segments are labelled with the
active step(s), from the step columns the simulation records (``trace.meta["sfc"]``, ADR 0023).

>>> import numpy as np
>>> from plclab.trace import Trace
>>> tr = Trace(np.arange(4.0), {"P.A.X": np.array([1, 0, 0, 1], bool),
...                             "P.B.X": np.array([0, 1, 1, 0], bool)},
...            meta={"sfc": [{"instance": "P", "columns": {"A": "P.A.X", "B": "P.B.X"}}]})
>>> s = sfc_series(tr)[0]
>>> s.name, [(t, s.label(v)) for t, v in s.changes()]
('SFC P', [(0.0, 'A'), (1.0, 'B'), (3.0, 'A')])
"""

from __future__ import annotations

from typing import Any

from .series import Series

MAX_BITS = 62  # steps per chart packed into one integer per row


def sfc_series(trace: Any, t0: float | None = None, t1: float | None = None) -> list[Series]:
    """One enumeration series per chart of the trace: the active steps, joined with ``+``
    when several are active (parallel branches), ``-`` when none is."""
    import numpy as np

    out = []
    for chart in trace.meta.get("sfc", []) or []:
        cols = [(n, c) for n, c in chart.get("columns", {}).items() if c in trace.columns]
        if not cols or len(cols) > MAX_BITS:
            continue
        key = np.zeros(len(trace.time), dtype=np.int64)
        for bit, (_, c) in enumerate(cols):
            key |= np.asarray(trace.columns[c], dtype=bool).astype(np.int64) << bit
        labels = {}
        for k in np.unique(key):
            active = [n for bit, (n, _) in enumerate(cols) if (int(k) >> bit) & 1]
            labels[int(k)] = "+".join(active) or "-"
        s = Series(f"SFC {chart.get('instance', '')}".strip(), trace.time, key, "enum",
                   labels=labels)
        out.append(s.window(t0, t1) if (t0 is not None or t1 is not None) else s)
    return out


def step_columns(trace: Any) -> list[tuple[str, str]]:
    """``(label, column)`` of every recorded step flag, chart by chart."""
    out = []
    for chart in trace.meta.get("sfc", []) or []:
        for name, col in chart.get("columns", {}).items():
            if col in trace.columns:
                out.append((f"step {name}", col))
    return out
