""""Check against the lab" in the browser: a lab's visible scenarios run on the playground's
plant, and the lab's criteria are judged on the recorded rows, in pure Python (no NumPy).

The build writes each supported lab as JSON (:func:`lab_json`: the student part only, see
:mod:`plclab.grade.courseware`); the page passes it back to :func:`check_lab`. The PLC is wired
to the plant directly (no input filters, no relay delays, no bounce) and the checks are the
grader's most common ones (:data:`CHECKS`), so a pass here is a good sign, not the grade: the
grader (``plclab lab check``) stays the reference.

>>> from plclab.site.playground_api import TANK_EXAMPLE
>>> data = lab_json_from_dict("tank-two-position", {"plant": "tank", "scan": "20ms",
...     "plant_params": {"area": 0.2}, "wiring": [
...     {"plc": "%IX0.0", "signal": "LS1"}, {"plc": "%IX0.1", "signal": "LS2"},
...     {"plc": "%QX0.0", "signal": "PUMP"}],
...     "scenario": [{"name": "short", "duration": "3min"}],
...     "criterion": [{"name": "fills", "scenarios": ["short"], "check": "eventually",
...                    "condition": "LEVEL >= 1.45", "points": 2}]})
>>> [r["passed"] for r in check_lab(TANK_EXAMPLE, "st", data)["results"]]
[True]
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from plclab.durations import parse_duration
from plclab.errors import PlcError

from .playground_api import LANGUAGE_SUFFIX, diagnostic_dict, make_plant

CHECKS = ("never", "always", "always_after", "eventually", "within", "max_switchings",
          "no_chatter")
"""The criteria the page can judge; a lab's other criteria are listed as not checked here."""
BROWSER_LABS = ("tank-two-position", "motor-start-stop")
"""The first labs, whose plants the page has."""
SAMPLE_S = 0.02
"""Rows are recorded at least this often (every scan when scans are slower)."""


def seconds(value: Any) -> float:
    """A duration from lab.toml (``"200ms"``, ``"4min"``, a number of seconds) in seconds."""
    if isinstance(value, int | float):
        return float(value)
    ns = parse_duration(value)
    if ns is None:
        raise PlcError("PLC3045", f"{value!r} is not a duration (write e.g. \"200ms\" or \"4min\")")
    return ns / 1e9


def lab_json_from_dict(lab_id: str, data: dict[str, Any],
                       wiring_rows: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    """What the page needs of a lab's student data: plant, scan, boolean wiring rows, visible
    scenarios and criteria."""
    rows = wiring_rows if wiring_rows is not None else data.get("wiring", [])
    if not isinstance(rows, list):
        rows = []
    return {
        "id": lab_id, "title": data.get("title", lab_id), "plant": data["plant"],
        "plant_params": data.get("plant_params", {}), "scan": seconds(data.get("scan", "10ms")),
        "wiring": [{"plc": r["plc"], "signal": r["signal"]} for r in rows
                   if str(r.get("plc", "")).startswith(("%IX", "%QX"))],
        "scenarios": [s for s in data.get("scenario", []) if s.get("visible", True) is not False],
        "criteria": list(data.get("criterion", [])),
    }


# ------------------------------------------------------------------------------ the run


def _scenario_actions(scen: dict[str, Any], rest: dict[str, Any]) -> list[tuple[float, str, Any]]:
    """(time, kind, argument) of a scenario, sorted; ``press`` becomes a write and a release."""
    out: list[tuple[float, str, Any]] = []
    for a in scen.get("actions", []):
        at = seconds(a.get("at", 0))
        if "set" in a:
            out.append((at, "write", (a["set"], a.get("value"))))
        elif "press" in a:
            sig = a["press"]
            pressed = not rest.get(sig, False)  # a normally closed button reads FALSE pressed
            out.append((at, "hold", (sig, pressed)))
            out.append((at + seconds(a.get("for", "200ms")), "release", sig))
        elif "fault" in a:
            out.append((at, "inject", (a["fault"], a.get("params", {}))))
            if "for" in a:
                out.append((at + seconds(a["for"]), "clear", a["fault"]))
        elif "clear" in a:
            out.append((at, "clear", a["clear"]))
    return sorted(out, key=lambda x: x[0])


def run_scenario(plc: Any, lab: dict[str, Any], scen: dict[str, Any]) -> list[dict[str, Any]]:
    """Run one scenario; the rows hold ``t``, every plant signal and the wired addresses."""
    plant = make_plant(lab["plant"], {**lab.get("plant_params", {}),
                                      **scen.get("plant_params", {})})
    plant.reset(int(scen.get("seed", 0)))
    plc.cold_restart()
    names = list(plant.signals)
    rest = {n: plant.read(n) for n in names}
    actions = _scenario_actions(scen, rest)
    held: dict[str, Any] = {}
    scan = float(lab["scan"])
    n = int(round(seconds(scen.get("duration", "10s")) / scan))
    every = max(1, int(round(SAMPLE_S / scan)))
    rows: list[dict[str, Any]] = []
    k = 0
    for i in range(n + 1):
        t = i * scan
        while k < len(actions) and actions[k][0] <= t + 1e-9:
            _, kind, arg = actions[k]
            if kind == "write":
                plant.write(*arg)
            elif kind == "hold":
                held[arg[0]] = arg[1]
            elif kind == "release":
                held.pop(arg, None)
                plant.write(arg, rest[arg])
            elif kind == "inject":
                plant.inject(arg[0], **arg[1])
            elif kind == "clear":
                plant.clear(arg)
            k += 1
        for sig, v in held.items():
            plant.write(sig, v)
        for r in lab["wiring"]:
            if r["plc"].startswith("%IX"):
                plc[r["plc"]] = bool(plant.read(r["signal"]))
        plc.scan()
        for r in lab["wiring"]:
            if r["plc"].startswith("%QX"):
                plant.write(r["signal"], bool(plc[r["plc"]]))
        if i % every == 0 or i == n:
            row = {"t": t, **{s: plant.read(s) for s in names}}
            row.update({r["plc"]: plc[r["plc"]] for r in lab["wiring"]})
            rows.append(row)
        plant.step(scan)
    return rows


# ------------------------------------------------------------------------------ the checks


def _cond(text: str, row_keys: list[str]) -> Callable[[dict[str, Any]], bool]:
    from plclab.trace.expr import parse_condition

    c = parse_condition(text)
    unknown = sorted(n for n in c.names if n not in row_keys and n not in ("t", "time"))
    if unknown:
        raise PlcError("PLC3045", f"the condition {text!r} reads {', '.join(unknown)}, which "
                       "the playground does not record")
    f = c.scalar({k: k for k in row_keys})
    return lambda row: f(row, row["t"])


def _window(p: dict[str, Any], rows: list[dict[str, Any]]) -> tuple[float, float]:
    a = seconds(p["from"]) if "from" in p else rows[0]["t"]
    b = seconds(p["to"]) if "to" in p else rows[-1]["t"]
    return a, min(b, rows[-1]["t"])


def _changes(rows: list[dict[str, Any]], sig: str, a: float, b: float) -> list[float]:
    out = []
    for prev, row in zip(rows, rows[1:], strict=False):
        if a <= row["t"] <= b and bool(row[sig]) != bool(prev[sig]):
            out.append(row["t"])
    return out


def judge(check: str, p: dict[str, Any], rows: list[dict[str, Any]]) -> tuple[bool, str]:
    """Passed, and why, for one criterion on one scenario's rows."""
    keys = list(rows[0])
    a, b = _window(p, rows)
    inside = [r for r in rows if a - 1e-9 <= r["t"] <= b + 1e-9]
    if check in ("never", "always", "always_after", "eventually"):
        f = _cond(p["condition"], keys)
        if check == "always_after":
            inside = [r for r in inside if r["t"] >= seconds(p["after"]) - 1e-9]
        if check == "never":
            bad = next((r for r in inside if f(r)), None)
            return bad is None, (f"`{p['condition']}` never held" if bad is None
                                 else f"`{p['condition']}` at t = {bad['t']:.2f} s")
        if check == "eventually":
            hit = next((r for r in inside if f(r)), None)
            return hit is not None, (f"`{p['condition']}` at t = {hit['t']:.2f} s" if hit
                                     else f"`{p['condition']}` never held")
        bad = next((r for r in inside if not f(r)), None)
        return bad is None, (f"`{p['condition']}` held" if bad is None
                             else f"`{p['condition']}` did not hold at t = {bad['t']:.2f} s")
    if check == "within":
        trig, resp = _cond(p["trigger"], keys), _cond(p["response"], keys)
        limit = seconds(p["time"])
        edges = [r["t"] for prev, r in zip([None] + inside, inside, strict=False)
                 if trig(r) and (prev is None or not trig(prev))]
        if not edges:
            ok = p.get("need_trigger") is False
            return ok, f"`{p['trigger']}` never happened"
        for te in edges:
            if te + limit > rows[-1]["t"] + 1e-9:
                continue
            if not any(resp(r) for r in rows if te <= r["t"] <= te + limit + 1e-9):
                return False, (f"`{p['trigger']}` at t = {te:.2f} s, but `{p['response']}` did "
                               f"not follow within {limit:g} s")
        return True, f"`{p['response']}` followed `{p['trigger']}` within {limit:g} s"
    if check == "max_switchings":
        n = len(_changes(rows, p["signal"], a, b))
        return n <= int(p["max"]), f"{p['signal']} switched {n} times (at most {p['max']})"
    if check == "no_chatter":
        k, w = int(p.get("min_toggles", 4)), seconds(p.get("window", 1.0))
        ts = _changes(rows, p["signal"], a, b)
        for i in range(len(ts) - k + 1):
            if ts[i + k - 1] - ts[i] <= w:
                return False, f"{p['signal']} switched {k} times within {w:g} s at t = {ts[i]:.2f} s"
        return True, f"{p['signal']} did not chatter"
    raise PlcError("PLC3045", f"the playground cannot judge a {check!r} criterion")


def check_lab(text: str, language: str, lab: dict[str, Any]) -> dict[str, Any]:
    """Compile the program, run every visible scenario of ``lab`` (from :func:`lab_json_from_dict`)
    and judge its criteria. Returns diagnostics, one result per (scenario, criterion) and the
    points earned out of the points judged."""
    from plclab.i18n import message
    from plclab.project import loads

    try:
        plc = loads(text, "lab" + LANGUAGE_SUFFIX.get(language, ".st"),
                    cycle_time=f"{lab['scan'] * 1000:g}ms")
    except PlcError as e:
        diags = list(getattr(e, "diagnostics", None) or [])
        return {"diagnostics": [diagnostic_dict(d) for d in diags] or
                [{"code": e.code, "message": message(e.code, e.message), "severity": "error",
                  "line": 0, "col": 0}], "results": [], "points": 0, "of": 0}
    results: list[dict[str, Any]] = []
    for scen in lab["scenarios"]:
        try:
            rows = run_scenario(plc, lab, scen)
        except PlcError as e:
            results.append({"scenario": scen["name"], "criterion": "runs", "passed": False,
                            "why": f"{e.code}: {message(e.code, e.message)}", "points": 0})
            continue
        passed: dict[str, bool] = {}
        for c in lab["criteria"]:
            names = c.get("scenarios") or ([c["scenario"]] if "scenario" in c else [])
            if scen["name"] not in names:
                continue
            if c["check"] not in CHECKS:
                results.append({"scenario": scen["name"], "criterion": c.get("label", c["name"]),
                                "passed": None,
                                "why": f"a {c['check']} check runs only in `plclab lab check`",
                                "points": c.get("points", 1)})
                continue
            blocked = [r for r in c.get("requires", []) if passed.get(r) is False]
            if blocked:
                ok, why = False, f"not judged: needs {', '.join(blocked)}"
            else:
                ok, why = judge(c["check"], c, rows)
            passed[c["name"]] = ok
            results.append({"scenario": scen["name"], "criterion": c.get("label", c["name"]),
                            "passed": ok,
                            "why": why if ok else f"{c.get('message', why)} ({why})",
                            "points": c.get("points", 1)})
    judged = [r for r in results if r["passed"] is not None]
    return {"diagnostics": [], "results": results,
            "points": sum(r["points"] for r in judged if r["passed"]),
            "of": sum(r["points"] for r in judged)}
