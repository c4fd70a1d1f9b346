"""Feedback: the Markdown a student reads, the timing diagram of each failed criterion around
the moment it failed, and a rerun recording of the scenario around its first failure.

Hidden scenarios are reported by name and pass/fail only (no diagram, no message), so their
details stay with the instructor (``Result.to_json()`` keeps everything).
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

from .safety import clean_text, md_code, md_fence, md_line, md_text

RRD_SPAN = (40.0, 20.0)
"""The rerun recording covers this much before and after the first failure, seconds."""
RRD_FPS = 4.0
"""Frames per second of the plant picture in the recording."""
MAX_DIAGNOSTICS = 20
MAX_FILES = 20


def slug(text: str) -> str:
    """A file-name-safe form of a name."""
    s = re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()
    return s or "x"


def _atomic_tmp(path: Path) -> Path:
    return path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")


def real_failure(t: Any) -> bool:
    """A failed test that was evaluated (not 'not run', not 'not earned')."""
    return not t.passed and not t.detail.startswith(("not earned", "not run"))


def declared_types(compiled: Any, io: Any = ()) -> dict[str, str]:
    """``{address: elementary type name}`` as the student declared them: the program's
    located variables (``LEVEL_MM AT %MW22 : INT`` gives ``INT``; ``INT(0..100)`` too), then
    the lab's I/O table (``io`` rows with ``address`` and ``type``) for the addresses the
    program uses without a declaration. For :func:`plclab.trace.typed.declared_view`."""
    from plclab.lang import types as T

    out: dict[str, str] = {}
    symbols = getattr(getattr(compiled, "project", None), "symbols", None)
    for lv in symbols.located_vars() if symbols is not None else ():
        addr = str(lv.address).upper()
        name = getattr(T.base_of(T.resolve(lv.decl.ty)), "name", None)
        if not addr.endswith("*") and isinstance(name, str):
            out.setdefault(addr, name.upper())
    for r in io or ():
        if getattr(r, "address", "") and getattr(r, "type", ""):
            out.setdefault(str(r.address).upper(), str(r.type).upper())
    return out


def failure_window(tf: float | None, w: float, t_end: float) -> tuple[float, float]:
    """The window of width ``w`` a diagram shows around a failure at ``tf`` (None: the end)."""
    if tf is None:
        return max(0.0, t_end - w), t_end
    t0 = max(0.0, tf - 0.6 * w)
    t1 = min(t_end, t0 + w)
    return max(0.0, min(t0, t1 - w)), t1


def judged_at_end(t_fail: float, t_end: float) -> bool:
    """A failure dated at the end of the run (a count or a value judged there): the window
    before it shows what led to it only when it is the whole run."""
    return t_fail >= t_end - 1e-6


def thresholds_of(crit: Any) -> dict[str, list[tuple[float, str]]]:
    """The values a criterion compares signals with, from its own definition
    (:func:`plclab.grade.criteria.criterion_limits`: ``LEVEL >= 1.75``, a band's edges, a
    set point): signal name -> [(value, label)]."""
    from .criteria import criterion_limits

    out: dict[str, list[tuple[float, str]]] = {}
    for lim in criterion_limits(crit):
        if lim.kind not in ("level", "band", "target") or not lim.signal or lim.value is None:
            continue
        for value in [lim.value] + ([lim.hi] if lim.kind == "band" and lim.hi is not None
                                    else []):
            lst = out.setdefault(lim.signal, [])
            if all(v != value for v, _ in lst):
                lst.append((float(value), lim.label))
    return out


_COUNTING = ("event_count", "counter", "max_switchings", "no_chatter")


def run_limits(lab: Any) -> Any:
    """What each criterion of ``lab`` checks on one run, for the rerun recordings of ``lab
    check --rrd``: ``f(criterion, trace)``, its :func:`criterion_limits` with the run's
    counts (:func:`counted_limits`: a counter's plant count as a dashed line on its row)."""
    from .criteria import criterion_limits

    crits = {c.name: c for c in lab.criteria}

    def limits(name: str, trace: Any) -> list[Any]:
        crit = crits.get(name)
        return [] if crit is None else counted_limits(trace, crit, criterion_limits(crit))

    return limits


def counted_limits(trace: Any, crit: Any, limits: list[Any]) -> list[Any]:
    """``limits`` with what the run counted beside what the criterion expects, for the
    criteria that count (events, switchings, a program's counter): ``exactly 90 bottle passed
    events, counted 84``; a counter also gets a dashed line at the plant's count on its own
    row (``plant counted 84``). Other criteria: ``limits`` unchanged."""
    from dataclasses import replace

    from plclab.i18n import tr

    from .criteria_base import window
    from .criteria_limits import Limit
    from .criteria_values import plant_count

    check = getattr(crit, "check", "") if getattr(crit, "function", None) is None else ""
    if check not in _COUNTING or trace is None or not hasattr(trace, "events_of"):
        return limits
    try:
        verdict = crit.evaluate(trace)
    except Exception:  # noqa: BLE001 - a picture never stops on its criterion
        return limits
    seen = verdict.value
    if not isinstance(seen, int | float) or isinstance(seen, bool):
        return limits
    p = dict(crit.params)
    out = []
    for lim in limits:
        if lim.kind != "count":
            out.append(lim)
            continue
        if check == "counter":
            try:
                n = plant_count(trace, p, *window(trace, p))
            except Exception:  # noqa: BLE001
                out.append(lim)
                continue
            out.append(replace(lim, label=tr("{what}: the plant counted {n}, {signal} = {seen}",
                                             what=lim.label, n=n, signal=lim.signal,
                                             seen=f"{seen:g}")))
            out.append(Limit("level", lim.signal, tr("plant counted {n}", n=n), float(n)))
        elif check == "no_chatter":
            out.append(replace(lim, label=tr("{what}: {n} in chatter", what=lim.label,
                                             n=f"{seen:g}")))
        elif check == "max_switchings":
            out.append(replace(lim, label=tr("{what}, switched {n}", what=lim.label,
                                             n=f"{seen:g}")))
        else:
            out.append(replace(lim, label=tr("{what}, counted {n}", what=lim.label,
                                             n=f"{seen:g}")))
    return out


def criterion_picture(trace: Any, crit: Any, rows: list[str], analog: Any = None) -> Any:
    """What ``crit`` checks, drawn over the diagram rows ``rows`` (trace columns): the
    :class:`plclab.viz.failure_model.Drawing` every picture of a failure shares."""
    from plclab.viz.failure_model import criterion_drawing

    from .criteria import criterion_limits

    def row_of(name: str) -> str | None:
        try:
            col = trace.resolve(name) if name in trace else None
        except Exception:  # noqa: BLE001 - a name the trace does not know
            return None
        return col if col in rows else None

    def is_analog(col: str) -> bool:
        try:
            return trace.kind(col) != "bool"
        except Exception:  # noqa: BLE001
            return False

    return criterion_drawing(counted_limits(trace, crit, criterion_limits(crit)), row_of,
                             trace.meta.get("units", {}) if hasattr(trace, "meta") else {},
                             analog or is_analog)


def diagram_names(trace: Any, lab: Any, crit: Any) -> list[str]:
    """The signals of a failure diagram: the lab's, the criterion's, the student's --watch
    (all of them: a picture with too many rows names those it leaves out and keeps the
    criterion's own, :func:`plclab.viz.failure_model.describe`)."""
    out: list[str] = []
    watch = list(getattr(lab, "student_watch", []))
    for n in list(lab.diagram_signals) + list(crit.relevant_signals()) + watch:
        if n in trace and trace.resolve(n) not in out:
            out.append(trace.resolve(n))
    if not out:
        return [r["plant_column"] for r in trace.io]
    return out


def picture_texts(lab: Any, crit: Any, scenario: str) -> dict[str, Any]:
    """The words of a failure picture in the reader's language: its title (scenario and
    criterion), its caption (the criterion's own message) and the failure line's label;
    with ``keep``, the criterion's signals (always drawn)."""
    from plclab.i18n import tr
    from plclab.i18n_labs import criterion_text, lab_texts

    texts = lab_texts(lab)
    name = criterion_text(texts, crit.name, "name", crit.name)
    return {"title": tr("{scenario}: {criterion} (FAILED)", scenario=scenario, criterion=name),
            "caption": criterion_text(texts, crit.name, "message", crit.message or ""),
            "marker": tr("{criterion} fails", criterion=name),
            "keep": list(crit.relevant_signals())}


def draw_failures(lab: Any, sc: Any, trace: Any, tests: list[Any], media_dir: Path, run: Any,
                  rrd: bool = True) -> None:
    """Timing diagrams (PNG) of the failed tests of a visible scenario, and (``rrd``) its
    recording around the first failure."""
    failed = [t for t in tests if real_failure(t)]
    if not failed or not sc.visible:
        return
    media_dir.mkdir(parents=True, exist_ok=True)
    crits = {c.name: c for c in lab.criteria_for(sc.name)}
    from plclab.i18n import tr

    faults = [(e.time, tr("PLC fault")) for e in trace.events_of("plc_fault")]
    drawn: dict[tuple[Any, ...], str] = {}
    from plclab.viz.layout import signal_labels

    labels = signal_labels(lab.io, trace)
    for t in failed:
        crit = crits[t.criterion]
        w = crit.window or lab.diagram_window
        if t.t_fail is None or judged_at_end(t.t_fail, trace.t_end):
            t0, t1 = 0.0, trace.t_end  # no single moment to blame: the whole scenario
        else:
            t0, t1 = failure_window(t.t_fail, w, trace.t_end)
        names = diagram_names(trace, lab, crit)
        key = (tuple(names), round(t0, 3), round(t1, 3), crit.name)
        if key in drawn:  # same picture as another failed criterion
            t.diagram = drawn[key]
            continue
        fname = f"{slug(sc.name)}--{slug(crit.name)}.png"
        words = picture_texts(lab, crit, sc.name)
        markers = [(t.t_fail, words["marker"])] if t.t_fail is not None else []
        markers += [m for m in faults if t0 <= m[0] <= t1]
        try:
            timing_png(trace, names, media_dir / fname, t0, t1, markers, words["title"],
                       labels, drawing=criterion_picture(trace, crit, names),
                       caption=words["caption"], keep=words["keep"])
        except Exception as e:  # noqa: BLE001 - a picture must never cost a grade
            run.notes.append(f"(no diagram for {crit.name}: {type(e).__name__}: {e})")
            continue
        t.diagram = fname
        drawn[key] = fname
    if rrd:
        write_rrd(trace, lab, sc, failed, media_dir, run)


def timing_png(trace: Any, names: list[str], path: Path, t0: float, t1: float,
               markers: list[tuple[float, str]], title: str,
               labels: dict[str, str] | None = None,
               thresholds: dict[str, list[tuple[float, str]]] | None = None,
               drawing: Any = None, caption: str = "", keep: list[str] | None = None) -> None:
    """A timing diagram of ``names`` over [t0, t1], written atomically: the description of
    :func:`plclab.viz.failure_trace.trace_diagram` (``labels`` rename columns for the reader,
    ``%QX0.1`` -> ``REJECT %QX0.1``; ``drawing`` is what the failed criterion checks,
    :func:`criterion_picture`; ``caption`` its words; ``keep`` its signals, never left out;
    ``thresholds`` extra lines), drawn with Pillow, or matplotlib for a ``.svg`` path."""
    from plclab.viz.failure_trace import trace_diagram, write_diagram

    write_diagram(trace_diagram(trace, names, t0, t1, markers, title, labels, drawing,
                                caption, keep, thresholds), path)


def rerun_available() -> bool:
    try:
        import rerun  # noqa: F401
    except ImportError:
        return False
    return True


def write_rrd(trace: Any, lab: Any, sc: Any, failed: list[Any], media_dir: Path,
              run: Any) -> None:
    """The scenario's rerun recording around its first failure (skipped quietly, with a note,
    when rerun is not installed)."""
    if not rerun_available():
        run.rrd_note = ("no .rrd recording: rerun is not installed "
                        "(pip install 'plclab[viz]')")
        return
    from plclab.viz.from_trace import recording
    from plclab.viz.layout import Verdict, run_info
    from plclab.viz.recording import write_rrd as _write

    times = [t.t_fail for t in failed if t.t_fail is not None]
    tf = min(times) if times else trace.t_end
    t0 = max(0.0, tf - RRD_SPAN[0])
    t1 = min(trace.t_end, tf + RRD_SPAN[1])
    crits = {c.name: c for c in lab.criteria_for(sc.name)}
    names: list[str] = []
    for t in failed:
        for n in diagram_names(trace, lab, crits[t.criterion]):
            if n not in names:
                names.append(n)
    for r in trace.io:
        for n in (r["plant_column"], r["column"]):
            if n not in names and n in trace:
                names.append(n)
    path = media_dir / f"{slug(sc.name)}.rrd"
    tmp = _atomic_tmp(path)
    try:
        info = run_info(lab, None, sc.name)
        from .criteria import criterion_limits

        info.verdicts = [Verdict(t.criterion, False, t.t_fail, t.detail or t.message,
                                 list(crits[t.criterion].relevant_signals()),
                                 criterion_limits(crits[t.criterion])) for t in failed]
        _write(recording(trace, names, t0, t1, fps=RRD_FPS, info=info), tmp)
        os.replace(tmp, path)
    except Exception as e:  # noqa: BLE001 - a recording must never cost a grade
        run.rrd_note = f"no .rrd recording ({type(e).__name__}: {e})"
        if tmp.exists():
            tmp.unlink()
        return
    run.rrd = path.name
    run.rrd_note = f"{t0:.0f}..{t1:.0f} s"


# ---------------------------------------------------------------------------- Markdown


def _pts(x: float) -> str:
    return f"{x:g}"


def _cell(text: str) -> str:
    return clean_text(text, 4000).replace("|", "\\|")


"""What the feedback says of a result that is not "ok" (translated through ``ui.toml``)."""
STATUS_WORDS = {
    "compile_error": "The program does not compile, so no scenario could run.",
    "no_source": "No source file was found in the submission.",
    "language": "The submission uses a language this lab does not accept.",
    "timeout": "The grading was stopped at the time limit.",
    "memory": "The program needed more memory than allowed.",
    "crash": "The grading process crashed.",
    "rejected": "The submission was not graded (see below).",
    "infrastructure": "The grading machine failed (not your program): it will be "
                      "graded again.",
}
"""What the feedback says of a result whose status is not ``ok``."""


def render_feedback(result: Any, instructor: bool = False, hint_level: int = 1,
                    fixes: dict[str, str] | None = None) -> str:
    """The feedback of a :class:`~plclab.grade.engine.Result` as Markdown.

    ``instructor=True`` shows the hidden scenarios in full too. Hints come in tiers
    (``lab check --hint N``): 0 none, 1 the concept (each criterion's ``hint``, the default and
    all the grader shows), 2 also the literal fix (``hint_fix``, from *fixes*: criterion name
    -> text).
    """
    from plclab.i18n import decimal, localize_line, tr

    lines: list[str] = []
    who = f" — {md_text(result.student)}" if result.student else ""
    title = result.lab_title or result.lab_id
    lines.append(f"# {title}{who}")
    lines.append("")
    lines.append(tr("**Score: {score} / {max_score}**", score=decimal(_pts(result.score)),
                    max_score=decimal(_pts(result.max_score))))
    failed_critical = [t for t in getattr(result, "critical_failures", [])
                       if t.visible or instructor]
    if failed_critical:  # first: a safety requirement or the lab's core function failed
        names = list(dict.fromkeys(t.criterion for t in failed_critical))
        capped = getattr(result, "capped", False)
        cap = (tr(" (the score is capped at {share} of the points until it passes)",
                  share=f"{result.critical_cap:.0%}") if capped else "")
        lines += ["", tr("**A critical requirement failed**{cap}: ", cap=cap) + "; ".join(
            md_text(n) for n in names) + tr(". First failure: ")
            + md_line(failed_critical[0].message)]
    elif getattr(result, "capped", False):  # a hidden scenario's critical check failed
        lines += ["", tr("**A critical requirement failed in a hidden scenario:** the score is "
                         "capped at {share} of the points.", share=f"{result.critical_cap:.0%}")]
    if result.status in STATUS_WORDS:
        lines += ["", tr(STATUS_WORDS[result.status])]
    if result.message:
        lines += ["", md_line(result.message)]
    if result.files:
        lines += ["", tr("Files: ") + ", ".join(md_code(f) for f in result.files[:MAX_FILES])
                  + (tr(" and {n} more", n=len(result.files) - MAX_FILES)
                     if len(result.files) > MAX_FILES else "")]
    if result.diagnostics:
        errors = [d for d in result.diagnostics if " error " in f" {d} "]
        head = tr("Compiler errors") if errors else tr("Compiler warnings")
        shown = [localize_line(d) for d in result.diagnostics[:MAX_DIAGNOSTICS]]
        more = len(result.diagnostics) - len(shown)
        if more:
            shown = shown + [tr("... and {n} more", n=more)]
        lines += ["", f"## {head}", "", *md_fence([clean_text(d, 4000) for d in shown])]
    by_sc: dict[str, list[Any]] = {}
    for t in result.tests:
        by_sc.setdefault(t.scenario, []).append(t)
    runs = {s.name: s for s in result.scenarios}
    hidden: list[str] = []
    for name, tests in by_sc.items():
        run = runs.get(name)
        visible = tests[0].visible
        if not visible and not instructor:
            hidden.append(name)
            continue
        got = sum(t.score for t in tests)
        mx = sum(t.max_score for t in tests)
        desc = f" — {run.description}" if run and run.description else ""
        tag = "" if visible else tr(" (hidden)")
        lines += ["", tr("## Scenario `{name}`{tag}{desc}", name=name, tag=tag, desc=desc), "",
                  tr("{got} / {max} points", got=decimal(_pts(got)), max=decimal(_pts(mx)))]
        if run and run.error and not run.ran:
            lines += ["", f"**{md_line(run.error)}**"]
        for note in (run.notes if run else []):
            lines += ["", f"**{md_line(note)}**"]
        lines += ["", tr("| | Criterion | Points | What happened |"), "|---|---|---|---|"]
        for t in tests:
            mark = tr("PASS") if t.passed else tr("FAIL")
            lines.append(f"| {mark} | {_cell(t.criterion)} | {decimal(_pts(t.score))}/"
                         f"{decimal(_pts(t.max_score))} | {_cell(t.message)} |")
        for t in tests:
            if not real_failure(t):
                continue
            lines += ["", tr("### FAIL: {criterion}", criterion=t.criterion), "", t.message + "."
                      if not t.message.endswith(".") else t.message]
            if t.hint and hint_level >= 1:
                lines += ["", tr("Hint: {hint}", hint=t.hint)]
            if hint_level >= 2 and (fixes or {}).get(t.criterion):
                lines += ["", tr("The fix: {fix}", fix=(fixes or {})[t.criterion])]
            if t.diagram:
                at = (tr(" around t = {t:num} s", t=f"{t.t_fail:.2f}")
                      if t.t_fail is not None else "")
                lines += ["", tr("![timing diagram of {criterion}{at}]({path})",
                                 criterion=t.criterion, at=at, path=t.diagram)]
        if run and run.rrd:
            lines += ["", tr("Recording of this scenario ({note}): [{rrd}]({rrd}) — open it "
                             "with `rerun {rrd}`.", note=run.rrd_note, rrd=run.rrd)]
        elif run and run.rrd_note:
            lines += ["", f"({run.rrd_note})"]
    if hidden:
        lines += ["", tr("## Hidden scenarios"), "",
                  tr("These scenarios are not shown before the grades are published; you see "
                     "only whether each test passed."), "", tr("| | Test | Points |"),
                  "|---|---|---|"]
        for name in hidden:
            for t in by_sc[name]:
                mark = tr("PASS") if t.passed else tr("FAIL")
                lines.append(f"| {mark} | {_cell(t.name)} | {decimal(_pts(t.score))}/"
                             f"{decimal(_pts(t.max_score))} |")
    return "\n".join(lines) + "\n"


def hidden_output(test: Any) -> str:
    """What a student sees of a hidden test."""
    return "passed" if test.passed else "failed (hidden scenario: details are not shown)"
