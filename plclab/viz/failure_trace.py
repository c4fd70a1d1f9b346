"""A failure diagram's description built from a trace (ADR 0069): the one place that decides
which rows a picture of a run holds and what they are called, for ``lab check --png``, the
``--out`` feedback and ``plclab sim --png`` / ``plclab view --png`` alike.

Rows are named as a logic analyser names them: the student's variable and its address
(``PUMP %QX0.0``, :func:`plclab.viz.layout.signal_labels`); the plant side and the PLC side of
one wire are one row; the plant's own marks (switch heights, a vessel's rim) and the failed
criterion's limits (:class:`plclab.viz.failure_model.Drawing`) are lines on their rows.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .failure_model import MAX_ROWS, Drawing, FailureDiagram, describe, rename


def trace_diagram(trace: Any, names: list[str] | None, t0: float | None, t1: float | None,
                  markers: list[tuple[float, str]], title: str,
                  labels: dict[str, str] | None = None, drawing: Drawing | None = None,
                  caption: str = "", keep: list[str] | None = None,
                  thresholds: dict[str, list[tuple[float, str]]] | None = None,
                  width: float = 9.0, max_rows: int | None = MAX_ROWS) -> FailureDiagram:
    """The description of the diagram of ``names`` (trace columns; None: the plant's signals
    and the wired I/O) over [t0, t1]. ``labels`` renames columns for the reader (``%QX0.1``
    -> ``REJECT %QX0.1``; default :func:`plclab.viz.layout.signal_labels` of the trace);
    ``drawing`` is what the failed criterion checks, ``caption`` its own words, ``keep`` its
    signals (always drawn); ``thresholds`` extra lines; ``max_rows`` None: every row."""
    from .layout import signal_labels
    from .trace_series import plant_limits, series

    if labels is None:
        labels = signal_labels(None, trace)

    def shown(name: str) -> str:
        return labels.get(name, labels.get(name.upper(), name))

    ss = series(trace, names, t0, t1)
    lines = {k: list(v) for k, v in plant_limits(trace).items()}  # switch heights, rims
    for more in [thresholds or {}] + ([drawing.thresholds] if drawing is not None else []):
        for k, v in more.items():
            have = lines.setdefault(k, [])
            have += [(x, lab) for x, lab in v if all(abs(x - y) > 1e-9 for y, _ in have)]
    rows, limits, bands = [], {}, {}
    for s in ss:  # the plant side and the PLC side of one wire are one row
        name = shown(s.name)
        if any(r.name == name for r in rows):
            continue
        if s.name in lines:
            limits[name] = lines[s.name]
        if drawing is not None and s.name in drawing.bands:
            bands[name] = drawing.bands[s.name]
        rows.append(s.__class__(name, s.times, s.values, s.kind, s.unit, s.labels))
    keep_rows = [shown(trace.resolve(n)) for n in keep or () if n in trace]
    named = {k: v for k, v in labels.items() if k != v}
    note = rename(drawing.note, named) if drawing is not None else ""
    return describe(rows, t0, t1, title, markers, width, limits, bands,
                    drawing.spans if drawing is not None else (), note,
                    caption, keep_rows, max_rows)


def write_diagram(d: FailureDiagram, path: str | Path, dpi: int = 72) -> None:
    """Write ``d`` to ``path``: a ``.svg`` (or ``.pdf``) with matplotlib, anything else as a
    PNG with Pillow (ADR 0033), written atomically (a reader never sees half a file)."""
    import os

    path = Path(path)
    if path.suffix.lower() in (".svg", ".pdf"):
        import matplotlib

        from .failure_diagram import failure_figure

        with matplotlib.rc_context({"svg.fonttype": "none"}):  # text stays text: searchable
            failure_figure(d).savefig(str(path), dpi=dpi)
        return
    from .failure_png import failure_png

    data = failure_png(d)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    tmp.write_bytes(data)
    os.replace(tmp, path)
