"""Controller tuning on a plant model with python-control, for the course's ``model`` figures.

A ``[[figure]]`` of kind ``model`` describes a linear plant, a first-order lag with an optional
second (sensor) lag, ``G(s) = gain / ((tau s + 1) (lag s + 1))``, and a list of controllers
(``kp``, optional ``tn`` and ``tv`` in seconds, CODESYS PID parameters). The build computes
the closed-loop response of each to a set-point step of ``step`` units with python-control and
draws the process value and the controller output; :func:`step_summary` gives the numbers the
chapter quotes (overshoot, settling time, remaining error, phase margin), which the course
tests recompute.

>>> s = step_summary({"gain": 1.0, "tau": 697.7, "lag": 4.0}, {"kp": 20.0})
>>> round(s["steady_state"], 3)
0.952
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .model import course_error


def _tf(plant: dict[str, Any], ctl: dict[str, Any]) -> tuple[Any, Any]:
    """(plant G, controller C) as python-control transfer functions."""
    import control as ct

    s = ct.tf("s")
    try:
        gain, tau = float(plant["gain"]), float(plant["tau"])
        lag = float(plant.get("lag", 0.0))
        kp = float(ctl["kp"])
    except (KeyError, TypeError, ValueError) as e:
        raise course_error(f"model figure: plant needs gain and tau, a controller kp ({e})") \
            from None
    g = gain / (tau * s + 1)
    if lag > 0:
        g = g / (lag * s + 1)
    c = kp + 0 * s
    tn, tv = float(ctl.get("tn", 0.0)), float(ctl.get("tv", 0.0))
    if tn > 0:
        c = c + kp / (tn * s)
    if tv > 0:  # a derivative with a small filter, as a real PID has
        c = c + kp * tv * s / (tv / 10.0 * s + 1)
    return g, c


def step_summary(plant: dict[str, Any], ctl: dict[str, Any], horizon: float = 3600.0
                 ) -> dict[str, float]:
    """Closed-loop response to a unit set-point step: overshoot (%), settling time (s, 2 %),
    rise time (s), the steady-state value (1.0 = no remaining error) and the phase margin."""
    import control as ct
    import numpy as np

    g, c = _tf(plant, ctl)
    closed = ct.feedback(c * g, 1)
    info = ct.step_info(closed, T=np.linspace(0.0, horizon, 36001))
    margins = ct.stability_margins(c * g)
    return {"overshoot": float(info["Overshoot"]), "settling": float(info["SettlingTime"]),
            "rise": float(info["RiseTime"]), "steady_state": float(ct.dcgain(closed)),
            "phase_margin": float(margins[1])}


def model_figure(spec: dict[str, Any], path: Path) -> str:
    """Draw the step responses of ``spec['controllers']`` on ``spec['plant']``."""
    import control as ct
    import numpy as np

    from ..sim.durations import parse_seconds
    from ..viz.series import Series
    from ..viz.timing import timing_diagram

    plant = spec.get("plant") or {}
    ctls = spec.get("controllers") or []
    if not ctls:
        raise course_error(f"model figure {spec.get('file')}: no controllers")
    step = float(spec.get("step", 1.0))
    t = np.linspace(0.0, parse_seconds(spec.get("duration", "20min")), 1201)
    unit_y, unit_u = spec.get("unit", ""), spec.get("output_unit", "")
    series, notes = [], []
    for k, ctl in enumerate(ctls, 1):
        g, c = _tf(plant, ctl)
        name = ctl.get("name", f"controller {k}")
        _, y = ct.step_response(ct.feedback(c * g, 1) * step, t)
        _, u = ct.step_response(ct.feedback(c, g) * step, t)
        series.append(Series(f"{name}: value", list(t), [float(v) for v in y], "real", unit_y))
        series.append(Series(f"{name}: output", list(t), [float(v) for v in u], "real", unit_u))
        sm = step_summary(plant, ctl)
        notes.append(f"{name}: overshoot {sm['overshoot']:.1f} %, settling {sm['settling']:.0f} s,"
                     f" steady state {sm['steady_state']:.3f}")
    timing_diagram(series, path, title=spec.get("title", ""), width=float(spec.get("width", 8)))
    return "; ".join(notes)
