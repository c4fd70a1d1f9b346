"""The ``lab`` figure kind: a chapter example run in one of a lab's scenarios, as the grader
runs it (the lab's plant, wiring, scan, plant parameters, alarms and recipe), drawn as a timing
diagram with the SFC lane and the alarm log as markers."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .model import course_error


def lab_run(source: Path, lab_id: str, scenario: str, watch: list[str] | None = None) -> Any:
    """The trace of ``source`` in the scenario ``scenario`` of the lab ``lab_id``; ``watch``
    adds PLC variables to the lab's watched ones."""
    import plclab
    from plclab.grade.lab import load_lab
    from plclab.sim import Simulation

    lab = load_lab(lab_id)
    try:
        sc = lab.scenario(scenario)
    except Exception as exc:  # an unknown scenario name: say which exist
        names = ", ".join(s.name for s in lab.scenarios)
        raise course_error(f"lab {lab_id} has no scenario {scenario!r}; its scenarios: "
                           f"{names}") from exc
    plc = plclab.load(source, cycle_time=lab.scan)
    sim = Simulation(plc, lab.plant, lab.wiring, seed=sc.seed, scenario=sc.scenario(),
                     watch=[*lab.all_watch(sc), *(watch or [])], plant_params={**lab.plant_params, **sc.plant_params})
    if lab.alarms:
        from plclab.process.alarms import AlarmServer

        sim.add_hook(AlarmServer.from_dict(lab.alarms, f"{lab.id}/alarms"))
    if lab.recipes and sc.recipe:
        from plclab.process.recipes import Recipe

        recipe = Recipe.from_dict(lab.recipes, f"{lab.id}/recipes")
        for at, record in sc.recipe:
            recipe.schedule(at, record)
        sim.add_hook(recipe)
    return sim.run()


def lab_figure(source: Path, spec: dict[str, Any], path: Path) -> str:
    """Draw the run; returns a note: switchings, alarm entries and SFC steps seen."""
    from plclab.process.alarms import alarm_log
    from plclab.viz.from_trace import series
    from plclab.viz.timing import timing_diagram

    if "lab" not in spec or "scenario" not in spec:
        raise course_error(f"{path.name}: a lab figure needs lab = \"ID\" and scenario = \"NAME\"")
    wanted = spec.get("signals") or []
    trace = lab_run(source, spec["lab"], spec["scenario"],  # PLC variables are watched
                    [n for n in wanted if "." in n])
    ss = series(trace, spec.get("signals"))
    log = alarm_log(trace)
    markers = [(e.time, f"{e.id} {e.state}") for e in log]
    timing_diagram(ss, path, title=spec.get("title", ""), markers=markers,
                   width=float(spec.get("width", 8)))
    sw = {s.name: trace.switchings(s.name) for s in ss if s.kind == "bool"}
    notes = [f"{n} switched {k}x" for n, k in sw.items()]
    if log:
        notes.append(f"{len(log)} alarm entries")
    return ", ".join(notes) or f"{len(ss)} signals"
