"""The figures of a chapter, drawn from real runs by ``plclab course build``.

Each ``[[figure]]`` of a chapter's ``figures.toml`` names a ``file`` (``.svg`` or ``.png``) and a
``kind``:

* ``block``      - the timing diagram of a standard block (``block = "TON"``), from
  :func:`plclab.viz.figures.block_figure`.
* ``scan_cycle`` - phases of consecutive scans and the reaction time, from a real run.
* ``program``    - a chapter example driven by input patterns: ``program`` (a file in
  ``examples/``), ``inputs`` (BOOL name -> list of ``[start, end]`` seconds where it is TRUE),
  ``values`` (name -> ``[[t, value], ...]`` steps), ``signals`` to draw, ``duration``, ``cycle``.
* ``plant``      - an example on a physics plant: ``program``, ``plant``, ``duration``,
  ``signals``, optional ``scenario`` (a list of actions as in a lab scenario) and
  ``plant_params``.
* ``ladder``     - a ``.ld`` example rendered as a ladder diagram (SVG only).
* ``model``      - closed-loop step responses of controllers on a linear plant model, computed
  with python-control (:mod:`plclab.course.models`).
* ``render``     - an example drawn as ``plclab render`` draws it (SVG): an FBD or LD network, an
  SFC chart, or a listing; ``pou`` picks the POU (default: the first).
* ``lab``        - an example run in a lab's scenario (``lab``, ``scenario``): the lab's plant,
  wiring, scan, plant parameters, alarms and recipe, as the grader runs it; the timing diagram
  shows ``signals``, the SFC lane of each chart, and every alarm state change as a marker.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .model import Chapter, course_error

KINDS = ("block", "scan_cycle", "program", "plant", "ladder", "model", "render", "lab")


def draw(chapter: Chapter, spec: dict[str, Any], out_dir: Path) -> tuple[Path, str]:
    """Draw one figure into ``out_dir``; returns (path, a short note of what the run showed)."""
    kind = spec.get("kind")
    name = spec.get("file", "")
    where = f"course/{chapter.slug}/figures.toml ({name or '?'})"
    if kind not in KINDS:
        raise course_error(f"{where}: kind must be one of {', '.join(KINDS)}, not {kind!r}")
    if not name.endswith((".svg", ".png")) or "/" in name:
        raise course_error(f"{where}: file must be a plain name ending in .svg or .png")
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / name
    if kind == "block":
        from ..viz.figures import block_figure

        block_figure(spec["block"], path)
        return path, f"{spec['block']} timing diagram"
    if kind == "scan_cycle":
        from ..viz.timing import scan_cycle_diagram

        _, reaction = scan_cycle_diagram(path, cycle_ms=float(spec.get("cycle_ms", 10.0)),
                                         input_at_ms=float(spec.get("input_at_ms", 13.0)))
        return path, f"reaction {reaction:.1f} ms"
    if kind == "model":
        from .models import model_figure

        return path, model_figure(spec, path)
    source = chapter.folder / "examples" / spec.get("program", spec.get("source", ""))
    if not source.is_file():
        raise course_error(f"{where}: no example {source.name} in examples/")
    if kind == "ladder":
        from ..viz.ladder_svg import render

        if not name.endswith(".svg"):
            raise course_error(f"{where}: ladder figures are SVG")
        path.write_text(render(source), encoding="utf-8")
        return path, f"ladder of {source.name}"
    if kind == "render":
        if not name.endswith(".svg"):
            raise course_error(f"{where}: render figures are SVG")
        path.write_text(_render(source, spec.get("pou"), where), encoding="utf-8")
        return path, f"render of {source.name}"
    if kind == "program":
        return path, _program_figure(source, spec, path)
    if kind == "lab":
        from .lab_figures import lab_figure

        return path, lab_figure(source, spec, path)
    return path, _plant_figure(source, spec, path)


def _render(source: Path, pou: str | None, where: str) -> str:
    """The SVG of an FBD or LD network or an SFC chart, drawn as ``plclab render`` draws it."""
    from ..lang.frontends.registry import for_file
    from ..project import read_sources

    [(text, fname)] = read_sources([str(source)])
    src, diags = for_file(fname).parse(text, fname)
    errors = [d for d in diags if d.severity == "error"]
    if errors:
        raise course_error(f"{where}: {errors[0]}")
    chosen = [p for p in src.pous if pou is None or p.name == pou.upper()]
    if not chosen:
        raise course_error(f"{where}: {source.name} has no POU {pou}")
    p = chosen[0]
    if any(b.kind == "NETWORK" for b in p.pending):
        from ..viz.render_network import render_source

        return render_source(text, fname, p.name, None)
    if any(b.kind == "SFC" for b in p.pending) or p.language == "SFC":
        from ..viz.render_sfc import render_sfc_svg

        return render_sfc_svg(p)
    raise course_error(f"{where}: render figures draw FBD, LD or SFC; {p.name} is {p.language}")


def _program_figure(source: Path, spec: dict[str, Any], path: Path) -> str:
    import plclab

    from ..sim.durations import parse_seconds
    from ..viz.series import Series, kind_of
    from ..viz.timing import timing_diagram

    cycle = spec.get("cycle", "10ms")
    plc = plclab.load(source, cycle_time=cycle)
    cycle_s = parse_seconds(cycle)
    steps = int(round(parse_seconds(spec.get("duration", "1s")) / cycle_s))
    inputs: dict[str, Any] = spec.get("inputs", {})
    values: dict[str, Any] = spec.get("values", {})
    signals = spec.get("signals") or list(inputs) + list(values)
    times: list[float] = []
    cols: dict[str, list[Any]] = {s: [] for s in signals}
    for k in range(steps):
        t = round(k * cycle_s, 9)
        for n, p in inputs.items():
            plc[n] = any(a <= t + 1e-9 < b for a, b in p)
        for n, p in values.items():
            v = _step_at(p, t)
            if v is not None:
                plc[n] = v
        plc.scan()
        times.append(t)
        for s in signals:
            cols[s].append(plc[s])
    series = []
    for s in signals:
        kind = kind_of(cols[s])
        vals = cols[s]
        unit = ""
        if plc.format(s).upper().startswith(("T#", "TIME#")):  # TIME is whole ms in the PLC
            vals, kind, unit = [v / 1000 for v in vals], "real", "s"
        series.append(Series(s, times, vals, kind, unit))
    # the whole run, not only up to the last change (digital rows are reduced to their changes)
    timing_diagram(series, path, t0=0.0, t1=times[-1] if times else None,
                   title=spec.get("title", ""), width=float(spec.get("width", 8)))
    return f"{len(signals)} signals over {len(times)} scans"


def _step_at(pattern: list[Any], t: float) -> Any:
    value = None
    for when, v in pattern:
        if t + 1e-9 >= when:
            value = v
    return value


def _plant_figure(source: Path, spec: dict[str, Any], path: Path) -> str:
    from ..sim import run
    from ..viz.from_trace import series
    from ..viz.timing import timing_diagram

    trace = run([str(source)], plant=spec["plant"], duration=spec.get("duration", "1min"),
                scenario=spec.get("scenario"), seed=int(spec.get("seed", 1)),
                plant_params=spec.get("plant_params"))
    ss = series(trace, spec.get("signals"))
    timing_diagram(ss, path, title=spec.get("title", ""), width=float(spec.get("width", 8)))
    sw = {s.name: trace.switchings(s.name) for s in ss if s.kind == "bool"}
    return ", ".join(f"{n} switched {k}x" for n, k in sw.items()) or f"{len(ss)} signals"
