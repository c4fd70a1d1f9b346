"""The SFC lane of a run: which step was active when, the transition firings, and why the
chart did not advance at the end (docs/adr/0023).

The simulation records the step flags ``<program>.<step>.X`` of every chart of the running
programs like watched variables (one BOOL column each), writes the charts' outlines into
``trace.meta["sfc"]``, turns every change of the active steps into an ``sfc_step`` event
("Fill -> Boiling") and, at the end, describes each chart's active steps with their outgoing
transitions and the values of the conditions (``meta["sfc_end"]``): the lab feedback's "why
did it not advance".
"""

from __future__ import annotations

from typing import Any

from plclab.errors import PlcError
from plclab.lang.check.symbols import instance_label
from plclab.lang.sfc_outline import evaluate, outline

MAX_STEP_EVENTS = 2000  # per run: a chart that toggles every scan does not flood the events


def charts(plc: Any) -> list[tuple[str, Any]]:
    """``(instance label, pou)`` of every running program whose body is a chart."""
    out = []
    for inst, pou, _ in plc.project.symbols.programs():
        if getattr(pou, "sfc", None) is not None:
            out.append((instance_label(inst, pou), pou))
    return out


def step_paths(plc: Any) -> list[str]:
    """The step flags to record: ``Washer.Fill.X`` for every step of every chart."""
    return [f"{label}.{s.text}.X" for label, pou in charts(plc) for s in pou.sfc.steps]


def sfc_meta(plc: Any, columns: dict[str, str]) -> list[dict[str, Any]]:
    """Per chart: the instance, the outline and the trace column of each step."""
    out = []
    for label, pou in charts(plc):
        o = outline(pou.sfc)
        o["instance"] = label
        o["columns"] = {s.text: columns.get(f"{label}.{s.text}.X".upper(), "")
                        for s in pou.sfc.steps}
        out.append(o)
    return out


def step_events(meta: list[dict[str, Any]], time: Any, cols: dict[str, Any]) -> list[Any]:
    """An ``sfc_step`` event at every change of a chart's active steps (a transition fired),
    with the steps left and entered."""
    import numpy as np

    from plclab.trace.events import Event

    out: list[Any] = []
    for chart in meta:
        names = [n for n, c in chart["columns"].items() if c in cols]
        if not names or not len(time):
            continue
        flags = np.stack([np.asarray(cols[chart["columns"][n]], dtype=bool) for n in names])
        change = np.nonzero(np.any(flags[:, 1:] != flags[:, :-1], axis=0))[0] + 1
        for i in change[:MAX_STEP_EVENTS]:
            left = [n for k, n in enumerate(names) if flags[k, i - 1] and not flags[k, i]]
            entered = [n for k, n in enumerate(names) if flags[k, i] and not flags[k, i - 1]]
            msg = f"{', '.join(left) or '-'} -> {', '.join(entered) or '-'}"
            out.append(Event(float(time[i]), "sfc_step", chart["instance"], msg,
                             {"left": " ".join(left), "entered": " ".join(entered)}))
    return out


def why_stuck(plc: Any) -> list[str]:
    """For every chart: its active steps at this moment, each outgoing transition and the
    value of its condition (with the variables it reads)."""
    out = []
    for label, pou in charts(plc):
        chart = pou.sfc

        def value(path: str, label: str = label) -> Any:
            try:
                return plc[f"{label}.{path}"]
            except (PlcError, KeyError):
                return None

        def shown(path: str, label: str = label) -> str:
            try:
                return plc.format(f"{label}.{path}")
            except (PlcError, KeyError):
                return "?"

        active = [s for s in chart.steps if value(f"{s.text}.X")]
        if not active:
            out.append(f"{label}: no step is active")
            continue
        o = outline(chart)
        for s in active:
            leaving = [(t, ot) for t, ot in zip(chart.transitions, o["transitions"], strict=True)
                       if s.name in {n for n, _ in t.sources}]
            since = plc.format(f"{label}.{s.text}.T")
            head = f"{label} is in step {s.text} (active for {since})"
            if not leaving:
                out.append(f"{head}; no transition leaves it")
                continue
            parts = []
            for t, ot in leaving:
                if t.cond is not None:
                    v = evaluate(t.cond, value)
                    values = ", ".join(f"{r} = {shown(r)}" for r in ot["reads"])
                    got = "unknown" if v is None else _fmt(bool(v))
                    parts.append(f"to {', '.join(ot['to'])} when '{ot['condition']}': {got}"
                                 + (f" ({values})" if values else ""))
                else:
                    name = t.text or t.name or ""
                    v = value(name) if not name.startswith("__") else None
                    got = "unknown" if v is None else _fmt(bool(v))
                    parts.append(f"to {', '.join(ot['to'])} when {ot['condition']}: {got}")
            others = [a.text for a in active if a is not s]
            if others and any(len(t.sources) > 1 for t, _ in leaving):
                head += f" (with {', '.join(others)})"
            out.append(f"{head}; its transitions: " + "; ".join(parts))
    return out


def _fmt(v: Any) -> str:
    if isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    if isinstance(v, float):
        return f"{v:g}"
    return str(v)
