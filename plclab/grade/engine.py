"""Grading one submission: compile, run every scenario, evaluate the criteria.

:func:`grade_sources` is the whole job for one student, in this process; the autograder runs it
in a child process per submission (:mod:`plclab.grade.worker`), ``plclab lab check`` and
:func:`plclab.grade.check` run it directly.

The outcome is a :class:`Result`: one :class:`TestResult` per (scenario, criterion) pair with
its points, a message, the time of the failure and the timing diagram drawn around it.
"""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from plclab.errors import PlcError

from .criteria import Verdict
from .lab import SOURCE_EXTS, Lab, ScenarioSpec

STATUSES = ("ok", "compile_error", "no_source", "language", "timeout", "memory", "crash",
            "rejected", "infrastructure")
STUDENT_STATUSES = ("ok", "compile_error", "no_source", "language", "timeout", "memory",
                    "rejected")
"""Outcomes caused by the submission itself: the only ones a later run may reuse. A ``crash``
(plclab's bug) and ``infrastructure`` (a grading process or cluster worker killed from outside:
the OOM killer, a lost worker) are graded again on the next run (ADR 0040)."""


@dataclass
class TestResult:
    """One test: a criterion evaluated on the trace of one scenario."""

    name: str
    scenario: str
    criterion: str
    score: float
    max_score: float
    passed: bool
    message: str
    detail: str = ""
    t_fail: float | None = None
    visible: bool = True
    hint: str = ""
    diagram: str | None = None
    number: str = ""
    critical: bool = False  # a failure caps the whole result (Result.critical_cap)

    def to_json(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> TestResult:
        return cls(**d)


@dataclass
class ScenarioRun:
    """What happened in one scenario (apart from the tests)."""

    name: str
    description: str = ""
    visible: bool = True
    ran: bool = False
    error: str = ""
    notes: list[str] = field(default_factory=list)
    duration: float = 0.0
    wall_s: float = 0.0
    rrd: str | None = None
    rrd_note: str = ""
    code: str = ""

    def to_json(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> ScenarioRun:
        return cls(**d)


@dataclass
class Result:
    """The grade of one submission.

    ``score``/``max_score``, ``tests`` (one per scenario and criterion), ``scenarios``,
    ``status`` (``ok``, ``compile_error``, ``no_source``, ``language``, ``timeout``,
    ``memory``, ``crash``, ``rejected``: a link, an oversized file or results the grader
    refused), ``diagnostics`` (compiler messages), ``message`` (a word on the
    whole submission), ``traces`` (scenario name -> Trace, in-process runs only) and
    :attr:`feedback_markdown`. In Jupyter the result shows itself as Markdown.
    """

    lab_id: str
    student: str = ""
    tests: list[TestResult] = field(default_factory=list)
    scenarios: list[ScenarioRun] = field(default_factory=list)
    status: str = "ok"
    message: str = ""
    diagnostics: list[str] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    execution_time: float = 0.0
    lab_title: str = ""
    submission_hash: str = ""
    lab_hash: str = ""
    critical_cap: float = 0.5
    traces: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def points(self) -> float:
        """The sum of the tests' points, before the cap of a failed critical criterion."""
        return float(sum(t.score for t in self.tests))

    @property
    def critical_failures(self) -> list[TestResult]:
        """The failed tests of critical criteria (safety or the lab's core function)."""
        return [t for t in self.tests if t.critical and not t.passed]

    @property
    def capped(self) -> bool:
        """True when a failed critical criterion lowered the score below :attr:`points`."""
        return bool(self.critical_failures) and self.points > self.critical_cap * self.max_score

    @property
    def score(self) -> float:
        """The grade: the tests' points, at most ``critical_cap`` of the maximum when a
        critical criterion failed."""
        pts = self.points
        if self.critical_failures:
            return min(pts, float(self.critical_cap * self.max_score))
        return pts

    @property
    def max_score(self) -> float:
        return float(sum(t.max_score for t in self.tests))

    @property
    def feedback_markdown(self) -> str:
        from .feedback import render_feedback

        return render_feedback(self)

    def _repr_markdown_(self) -> str:
        return self.feedback_markdown

    def __repr__(self) -> str:
        return (f"<Result {self.lab_id} {self.student or ''}: {self.score:g}/{self.max_score:g} "
                f"{self.status}>")

    def to_json(self) -> dict[str, Any]:
        d = {k: v for k, v in asdict(self).items() if k != "traces"}
        d["tests"] = [t.to_json() for t in self.tests]
        d["scenarios"] = [s.to_json() for s in self.scenarios]
        d["score"] = self.score
        d["max_score"] = self.max_score
        return d

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> Result:
        d = dict(d)
        d.pop("score", None)
        d.pop("max_score", None)
        d["tests"] = [TestResult.from_json(t) for t in d.get("tests", [])]
        d["scenarios"] = [ScenarioRun.from_json(s) for s in d.get("scenarios", [])]
        return cls(**d)


# ---------------------------------------------------------------------------- submissions


def language_of(filename: str) -> str | None:
    """``st``/``il``/``ld``/``xml`` by extension (None for other files); ``Path.suffix``, as
    the grader's folder walk uses, so ``..st`` and ``.x.st`` are ST too (``splitext`` sees no
    extension in ``..st``)."""
    return SOURCE_EXTS.get(Path(filename).suffix.lower())


def guess_language(text: str) -> str:
    """The language of program text given without a file name."""
    s = text.lstrip()
    if s.startswith("<?xml") or s.startswith("<project"):
        return "xml"
    if any(ln.lstrip().startswith("|") and ("[" in ln or "(" in ln) for ln in text.splitlines()):
        return "ld"
    return "st"


def read_submission(path: str | os.PathLike) -> tuple[list[tuple[str, str]], list[str]]:
    """Source files of a submission (a file or a folder): ``[(text, display name)]`` and the
    other files found (ignored). Display names are relative to the submission's parent.

    Symbolic links are never followed and sizes are capped (:mod:`plclab.grade.safety`):
    a link, a special file, a file over the size cap or too many files is a PlcError."""
    from .safety import read_sources

    return read_sources(path, SOURCE_EXTS)


MAX_DIAGNOSTICS_PER_FILE = 50
"""Compiler messages kept per file; the rest become one "... and K more" line."""
MAX_DIAGNOSTIC_CHARS = 1000
"""Characters kept of one compiler message."""
MAX_DIAGNOSTICS = 200
"""Compiler messages kept of a whole submission."""


def cap_diagnostics(diags: Iterable[Any], per_file: int = MAX_DIAGNOSTICS_PER_FILE,
                    total: int = MAX_DIAGNOSTICS) -> list[str]:
    """Compiler messages as text: at most ``per_file`` of each file and ``total`` in all (in
    order), plus one ``... and K more in FILE`` line per file that had more; each message
    cut to :data:`MAX_DIAGNOSTIC_CHARS`. Bounded whatever the compiler produced."""
    kept: list[str] = []
    count: dict[str, int] = {}
    dropped: dict[str, int] = {}
    for d in diags:
        loc = getattr(d, "location", None)
        key = str(getattr(loc, "file", "") or "")
        count[key] = count.get(key, 0) + 1
        if count[key] > per_file or len(kept) >= total:
            dropped[key] = dropped.get(key, 0) + 1
            continue
        text = str(d)
        if len(text) > MAX_DIAGNOSTIC_CHARS:
            text = text[:MAX_DIAGNOSTIC_CHARS - 1] + "…"
        kept.append(text)
    for key, n in dropped.items():
        where = f" in {key[:MAX_DIAGNOSTIC_CHARS]}" if key else ""
        kept.append(f"note PLC5036: ... and {n} more{where} (only the first {per_file} "
                    f"messages of a file, {total} in all, are kept: fix those first)")
    return kept


# ---------------------------------------------------------------------------- grading


NOT_RUN = {
    "compile_error": "not run: the program does not compile",
    "no_source": "not run: no source file",
    "language": "not run: language not accepted",
    "timeout": "not run: stopped at the time limit",
    "memory": "not run: the program needs too much memory",
    "crash": "not run: the grading process crashed",
    "rejected": "not run: the submission or its results were rejected",
    "infrastructure": "not run: the grading machine failed (not the program); grade again",
    "setup": "not run: the scenario could not start with this program",
}
"""Short test messages for scenarios that did not run (the reason is given once above)."""


def _tests_failed(lab: Lab, sc: ScenarioSpec, message: str, first: int) -> list[TestResult]:
    out = []
    for j, c in enumerate(lab.criteria_for(sc.name)):
        out.append(TestResult(f"{sc.name}: {c.name}", sc.name, c.name, 0.0, c.points, False,
                              message, message, None, sc.visible, c.hint,
                              number=f"{first}.{j + 1}", critical=c.critical))
    return out


def failed_result(lab: Lab, status: str, message: str, scenarios: Iterable[ScenarioSpec],
                  diagnostics: Iterable[str] = (), first: int = 1) -> Result:
    """A result in which no test of ``scenarios`` ran: ``message`` says why (once)."""
    res = Result(lab.id, status=status, message=message, diagnostics=list(diagnostics),
                 lab_title=lab.title, lab_hash=lab.hash)
    short = NOT_RUN.get(status, "not run")
    numbers = {s.name: i for i, s in enumerate(lab.scenarios, 1)}
    for sc in scenarios:
        res.scenarios.append(ScenarioRun(sc.name, sc.description, sc.visible, False, short))
        res.tests += _tests_failed(lab, sc, short, numbers.get(sc.name, first))
    return res


def compile_submission(lab: Lab, sources: list[tuple[str, str]]) -> tuple[Any, list[str], str]:
    """(compiled or None, diagnostics as text, status)."""
    from plclab.project import compile_sources

    if not sources:
        return None, [], "no_source"
    bad = [n for _, n in sources if language_of(n) not in lab.languages]
    if bad:
        allowed = ", ".join(lab.languages)
        return None, [f"error PLC5022: {n}: this lab accepts {allowed} programs" for n in bad], \
            "language"
    try:
        compiled = compile_sources(sources, dialect=lab.dialect)
    except PlcError as e:
        return None, cap_diagnostics(e.diagnostics), "compile_error"
    diags = cap_diagnostics(getattr(compiled, "diagnostics", []))
    return compiled, diags, "ok"


def grade_sources(lab: Lab, sources: list[tuple[str, str]], *, student: str = "",
                  scenarios: Iterable[str] | None = None, include_hidden: bool = True,
                  media_dir: str | os.PathLike | None = None, rrd: bool = True,
                  keep_traces: bool = False,
                  on_scenario: Callable[[ScenarioRun, list[TestResult]], None] | None = None,
                  on_compiled: Callable[[list[str]], None] | None = None,
                  guard: Callable[[], Any] | None = None) -> Result:
    """Grade program sources ``[(text, name)]`` against a lab.

    Parameters
    ----------
    scenarios : names, optional
        Only these scenarios (default: all, or the visible ones with ``include_hidden=False``).
    media_dir : path, optional
        Where the timing diagrams (PNG) of failed criteria and the ``.rrd`` recordings of
        scenarios with a failure go. None: no pictures.
    rrd : bool
        Write rerun recordings (when rerun is installed).
    keep_traces : bool
        Keep every scenario's Trace in ``Result.traces``.
    on_scenario : callable, optional
        Called after each scenario with its run and tests (the worker streams them).
    guard : callable, optional
        A context manager factory wrapped around compiling and simulating (the worker's
        memory limit); drawing the feedback happens outside it.
    """
    t_start = time.perf_counter()
    specs = [s for s in lab.scenarios if include_hidden or s.visible]
    if scenarios is not None:
        wanted = list(scenarios)
        specs = [lab.scenario(n) for n in wanted]
    guard = guard or contextlib.nullcontext
    with guard():
        compiled, diags, status = compile_submission(lab, sources)
    if on_compiled is not None:
        on_compiled(diags)
    if compiled is None:
        msg = {"no_source": "no source file (.st, .il, .ld, .xml) in the submission (PLC5021)",
               "language": "this lab does not accept that language (PLC5022)",
               "compile_error": "the program does not compile: fix the errors below"}[status]
        res = failed_result(lab, status, msg, specs, diags)
        res.student = student
        res.files = [n for _, n in sources]
        res.execution_time = time.perf_counter() - t_start
        for sc in res.scenarios:
            if on_scenario is not None:
                on_scenario(sc, [t for t in res.tests if t.scenario == sc.name])
        return res
    res = Result(lab.id, student, diagnostics=diags, files=[n for _, n in sources],
                 lab_title=lab.title, lab_hash=lab.hash, critical_cap=lab.critical_cap)
    numbers = {s.name: i for i, s in enumerate(lab.scenarios, 1)}
    for sc in specs:
        # one recording per submission: the first scenario with a failure
        run, tests, trace = run_scenario(lab, compiled, sc, numbers[sc.name], media_dir, rrd,
                                         guard)
        if run.rrd or run.rrd_note.startswith("no .rrd"):
            rrd = False
        res.scenarios.append(run)
        res.tests.extend(tests)
        if keep_traces and trace is not None:
            res.traces[sc.name] = trace
        if on_scenario is not None:
            on_scenario(run, tests)
    if any(r.code == "PLC5024" for r in res.scenarios):
        res.status = "memory"
    if res.scenarios and all(not r.ran for r in res.scenarios):
        res.message = res.scenarios[0].error
    res.execution_time = time.perf_counter() - t_start
    return res


def run_scenario(lab: Lab, compiled: Any, sc: ScenarioSpec, number: int,
                 media_dir: str | os.PathLike | None = None, rrd: bool = True,
                 guard: Callable[[], Any] | None = None
                 ) -> tuple[ScenarioRun, list[TestResult], Any]:
    """Run one scenario of a compiled program; evaluate its criteria."""
    run = ScenarioRun(sc.name, sc.description, sc.visible, duration=sc.duration)
    t0 = time.perf_counter()
    try:
        with (guard or contextlib.nullcontext)():
            trace = _simulate(lab, compiled, sc)
    except PlcError as e:
        if e.code == "PLC2009":
            msg = ("the program needs more memory than the grader allows (PLC5024): are there "
                   "huge arrays?")
            run.code = "PLC5024"
        else:
            msg = (f"the scenario could not run with this program: {e} (PLC5028). Check that "
                   "your program declares the I/O addresses of the lab's I/O table with their "
                   "types")
            run.code = "PLC5028"
        run.error = msg
        run.wall_s = time.perf_counter() - t0
        short = NOT_RUN["memory" if run.code == "PLC5024" else "setup"]
        return run, _tests_failed(lab, sc, short, number), None
    run.ran = True
    run.wall_s = time.perf_counter() - t0
    faults = trace.events_of("plc_fault")
    for f in faults:
        run.notes.append(f"The PLC stopped at t = {f.time:.2f} s: {f.message}")
    tests: list[TestResult] = []
    passed: dict[str, bool] = {}
    for j, c in enumerate(lab.criteria_for(sc.name), 1):
        missing = [r for r in c.requires if r in passed and not passed[r]]
        if missing:
            v = Verdict(False, f"not earned: this criterion counts only when '{missing[0]}' "
                        "passes")
        else:
            v = c.evaluate(trace)
        passed[c.name] = v.passed
        if v.passed or missing:
            msg = v.message
        else:
            msg = f"{c.message}: {v.message}" if c.message else v.message
            if faults and (v.t_fail is None or v.t_fail >= faults[0].time):
                msg += f" (the PLC was in STOP after its fault at t = {faults[0].time:.2f} s)"
        tests.append(TestResult(f"{sc.name}: {c.name}", sc.name, c.name,
                                c.points if v.passed else 0.0, c.points, v.passed, msg,
                                v.message, v.t_fail, sc.visible, c.hint, number=f"{number}.{j}",
                                critical=c.critical))
    if any(not t.passed for t in tests):  # an SFC: where the chart stands, and why
        run.notes.extend(f"At the end: {line}" for line in trace.meta.get("sfc_end", []))
    # what is shown (pictures, kept traces) reads each address as its declared type
    from plclab.trace.typed import declared_view

    from .feedback import declared_types

    trace = declared_view(trace, declared_types(compiled, lab.io))
    if media_dir is not None and any(not t.passed for t in tests):
        from .feedback import draw_failures

        draw_failures(lab, sc, trace, tests, Path(media_dir), run, rrd=rrd)
    return run, tests, trace


def _simulate(lab: Lab, compiled: Any, sc: ScenarioSpec) -> Any:
    """The trace of one scenario (the PLC and the simulation are dropped on return)."""
    from plclab.runtime.plc import Plc
    from plclab.sim import Simulation

    plc = Plc(compiled, cycle_time=lab.scan, task_intervals=sc.task_intervals)
    sim = Simulation(plc, lab.plant, lab.wiring, seed=sc.seed, scenario=sc.scenario(),
                     watch=lab.all_watch(sc), plant_params={**lab.plant_params,
                                                            **sc.plant_params})
    if lab.alarms:  # the alarm log goes into the trace (plclab.scada, ADR 0025)
        from plclab.process.alarms import AlarmServer

        sim.add_hook(AlarmServer.from_dict(lab.alarms, f"{lab.id}/alarms"))
    if lab.recipes and sc.recipe:  # records written into the PLC at their times
        from plclab.process.recipes import Recipe

        recipe = Recipe.from_dict(lab.recipes, f"{lab.id}/recipes")
        for at, record in sc.recipe:
            recipe.schedule(at, record)
        sim.add_hook(recipe)
    return sim.run()


def source_hash(sources: list[tuple[str, str]]) -> str:
    """A hash of a submission's files (names relative to the submission, and contents)."""
    import hashlib

    h = hashlib.sha256()
    for text, name in sorted(sources, key=lambda s: s[1]):
        rel = name.split("/", 1)[-1]
        h.update(rel.encode() + b"\0" + text.encode("utf-8", "surrogatepass") + b"\0")
    return h.hexdigest()[:16]

