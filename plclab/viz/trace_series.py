"""A trace's columns as the step series every picture draws, and the plant's own marks on
them: shared by :mod:`plclab.viz.from_trace` (rerun, exports) and
:mod:`plclab.viz.failure_trace` (the failure diagram), below both.
"""

from __future__ import annotations

from .series import Series


def series(trace, names: list[str] | None = None, t0: float | None = None,
           t1: float | None = None) -> list[Series]:
    """The named columns of a trace as step series (default: plant signals, then wired I/O),
    then the SFC lane of each chart (its active steps), if the program has charts."""
    if names is None:
        names = list(trace.signals) + [r["column"] for r in trace.io
                                       if r.get("column") in trace.columns]
    units = trace.meta.get("units", {})
    out = []
    for name in names:
        col = trace.resolve(name)  # a PlcError names an unknown signal
        kind = trace.kind(col)
        kind = {"float": "real"}.get(kind, kind)
        s = Series(col, trace.time, trace.columns[col], kind, units.get(col, ""))
        out.append(s.window(t0, t1) if (t0 is not None or t1 is not None) else s)
    from .sfc_lane import sfc_series  # the active steps of each chart, at the bottom

    return out + sfc_series(trace, t0, t1)


def plant_of(trace):
    """The plant a trace was recorded from, with its parameters (None: unknown, or it cannot
    be built here)."""
    name = trace.meta.get("plant")
    if not name:
        return None
    try:
        import plants

        return plants.get_plant(name, **(trace.meta.get("plant_params") or {}))
    except Exception:  # noqa: BLE001 - a picture is optional
        return None


def plant_limits(trace) -> dict[str, list[tuple[float, str]]]:
    """The plant's own marks (switch heights, the rim) per signal as (value, label), for a
    diagram's lines."""
    marks = plant_marks(trace, plant_of(trace))
    return {k: [(v, name) for name, v in lst] for k, lst in marks.items()}


def plant_marks(trace, plant) -> dict[str, list[tuple[str, float]]]:
    """Switch heights and vessel rims worth drawing as limits, from the plant's geometry: the
    marks beside a filled vessel are limits of its level, the end switches of a piston limits
    of its position."""
    out: dict[str, list[tuple[str, float]]] = {}
    if plant is None:
        return out
    try:
        geo = plant.geometry() or {}
    except Exception:  # noqa: BLE001 - a picture is optional
        return out
    shapes = geo.get("shapes", [])
    fill = geo.get("fill")
    if fill and fill.get("signal") in trace.columns:
        sig = fill["signal"]
        for s in shapes:
            if s.get("type") == "mark" and s.get("name") in trace.columns:
                out.setdefault(sig, []).append((s["name"], float(s["y"])))
        vessel = next((s for s in shapes if s.get("type") == "rect"
                       and abs(s["x"] - fill["x"]) < 1e-9), None)
        if vessel is not None:
            out.setdefault(sig, []).append(("rim", float(vessel["y"] + vessel["h"])))
    piston = geo.get("piston")
    if piston and piston.get("signal") in trace.columns:
        scale = float(piston["scale"])
        for s in shapes:
            if s.get("type") == "mark" and s.get("name") in trace.columns and scale:
                out.setdefault(piston["signal"], []).append((s["name"], float(s["y"]) / scale))
    for v in out.values():
        v.sort(key=lambda lv: lv[1])
    return out
