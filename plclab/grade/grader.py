"""The autograder: a folder of submissions -> one process each -> results, feedback, gradebook.

``plclab grade LAB SUBMISSIONS_DIR [--jobs N] [--out DIR] [--timeout 30s] [--force]``:

* a submission is a file (student id = its stem; files with the same stem belong together)
  or a folder (student id = the folder name; every .st/.il/.ld/.xml inside counts);
* each runs in its own process (multiprocessing *forkserver*, or *spawn* where there is no
  fork) with a wall-clock limit (the process is killed) and a memory limit (``RLIMIT_AS`` in
  the child), so a submission that hangs, crashes or eats memory gets a clear message and the
  score it earned, and never stops or slows the others;
* ``DIR/<student>/results.json`` (Gradescope), ``feedback.md`` (+ PNG diagrams, ``.rrd``),
  ``.plclab-result.json`` (everything, for re-runs and instructors) and ``DIR/grades.csv``,
  all written atomically;
* a submission whose files, lab and grader are unchanged since the last run is not graded
  again (``--force`` regrades).
"""

from __future__ import annotations

import json
import multiprocessing
import os
import sys
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing.connection import wait
from pathlib import Path
from typing import Any

from .engine import Result, ScenarioRun, TestResult, failed_result, read_submission, source_hash
from .errors import grade_error
from .feedback import render_feedback
from .gradescope import gradebook_csv, results_json, write_atomic, write_json
from .lab import SOURCE_EXTS, Lab

GRADER_VERSION = "1"
SIDECAR = ".plclab-result.json"
LOG = ".plclab-grade.log"


@dataclass
class Submission:
    """One student's files."""

    student: str
    paths: list[Path]
    sources: list[tuple[str, str]] = field(default_factory=list)
    hash: str = ""


@dataclass
class Outcome:
    """A graded (or skipped) submission."""

    result: Result
    skipped: bool = False
    wall_s: float = 0.0


def discover(folder: str | os.PathLike, exclude: Path | None = None) -> list[Submission]:
    """The submissions in a folder, sorted by student id."""
    root = Path(folder)
    if not root.is_dir():
        raise grade_error("PLC5026", f"{root} is not a folder of submissions; give a folder "
                          "holding one file or one folder per student")
    groups: dict[str, list[Path]] = {}
    for p in sorted(root.iterdir()):
        if p.name.startswith(".") or p.name == "__MACOSX":
            continue
        if exclude is not None and p.resolve() == exclude.resolve():
            continue
        if p.is_dir():
            groups.setdefault(p.name, []).append(p)
        elif p.suffix.lower() in SOURCE_EXTS:
            groups.setdefault(p.stem, []).append(p)
    subs = []
    for student, paths in sorted(groups.items()):
        sources: list[tuple[str, str]] = []
        for p in paths:
            s, _ = read_submission(p)
            sources += s
        subs.append(Submission(student, paths, sources, source_hash(sources)))
    return subs


def _context() -> Any:
    methods = multiprocessing.get_all_start_methods()
    if "forkserver" in methods:
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(["__main__", "plclab.grade._preload"])
        return ctx
    return multiprocessing.get_context("spawn")


def _signame(code: int | None) -> str:
    if code is None:
        return "still running"
    if code < 0:
        import signal

        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exit code {code}"


class _Running:
    def __init__(self, sub: Submission, proc: Any, conn: Any, media: Path) -> None:
        self.sub = sub
        self.proc = proc
        self.conn = conn
        self.media = media
        self.start = time.monotonic()
        self.diags: list[str] | None = None
        self.scenarios: list[ScenarioRun] = []
        self.tests: list[TestResult] = []
        self.done: Result | None = None
        self.failure: tuple[str, str] | None = None
        self.eof = False

    def drain(self) -> None:
        while not self.eof:
            try:
                if not self.conn.poll():
                    return
                msg = self.conn.recv()
            except (EOFError, OSError):
                self.eof = True
                return
            kind = msg[0]
            if kind == "compiled":
                self.diags = list(msg[1])
            elif kind == "scenario":
                self.scenarios.append(ScenarioRun.from_json(msg[1]))
                self.tests += [TestResult.from_json(t) for t in msg[2]]
            elif kind == "done":
                self.done = Result.from_json(msg[1])
            else:
                self.failure = (kind, msg[1])


class Grader:
    """Grade a folder of submissions (see the module docstring).

    Parameters
    ----------
    lab : Lab
    out : path
        Output folder (``DIR/<student>/...``, ``DIR/grades.csv``).
    jobs : int
        Submissions graded at the same time.
    timeout : float, optional
        Wall-clock limit per submission, s (default: the lab's ``time_limit``).
    memory_mb : int, optional
        Memory limit per submission (default: the lab's ``memory_limit``).
    force : bool
        Regrade unchanged submissions.
    media : bool
        Draw diagrams and recordings of failures.
    progress : callable, optional
        ``progress(done, total, student, outcome)`` after each submission.
    """

    def __init__(self, lab: Lab, out: str | os.PathLike, jobs: int = 2,
                 timeout: float | None = None, memory_mb: int | None = None,
                 force: bool = False, media: bool = True,
                 progress: Callable[[int, int, str, Outcome], None] | None = None) -> None:
        self.lab = lab
        self.out = Path(out)
        self.jobs = max(1, int(jobs))
        self.timeout = float(timeout if timeout is not None else lab.time_limit)
        self.memory_mb = int(memory_mb if memory_mb is not None else lab.memory_limit_mb)
        self.force = force
        self.media = media
        self.progress = progress
        self.selftest_crash = os.environ.get("PLCLAB_GRADE_SELFTEST_CRASH", "")

    # ------------------------------------------------------------------ the run
    def grade_folder(self, folder: str | os.PathLike) -> list[Outcome]:
        subs = discover(folder, exclude=self.out)
        self.out.mkdir(parents=True, exist_ok=True)
        outcomes: dict[str, Outcome] = {}
        todo: deque[Submission] = deque()
        for s in subs:
            prev = None if self.force else self._previous(s)
            if prev is not None:
                outcomes[s.student] = Outcome(prev, skipped=True)
            else:
                todo.append(s)
        total = len(subs)
        done_n = len(outcomes)
        if self.progress:
            for st, oc in sorted(outcomes.items()):
                self.progress(done_n, total, st, oc)
        if todo:
            for oc in self._run(todo, total, done_n):
                outcomes[oc.result.student] = oc
        results = [outcomes[s.student] for s in subs]
        self._write_gradebook([o.result for o in results])
        return results

    def _previous(self, s: Submission) -> Result | None:
        d = self.out / s.student
        side = d / SIDECAR
        if not side.is_file() or not (d / "results.json").is_file():
            return None
        try:
            data = json.loads(side.read_text(encoding="utf-8"))
            if (data.get("submission_hash") != s.hash or data.get("lab_hash") != self.lab.hash
                    or data.get("grader") != GRADER_VERSION):
                return None
            return Result.from_json(data["result"])
        except (OSError, ValueError, KeyError, TypeError):
            return None

    def _run(self, todo: deque[Submission], total: int, done_n: int) -> list[Outcome]:
        ctx = _context()
        running: list[_Running] = []
        finished: list[Outcome] = []
        try:
            while todo or running:
                while todo and len(running) < self.jobs:
                    running.append(self._start(ctx, todo.popleft()))
                objs = [r.conn for r in running if not r.eof] + [r.proc.sentinel
                                                                   for r in running]
                wait(objs, timeout=0.05)
                now = time.monotonic()
                for r in list(running):
                    r.drain()
                    final = r.done is not None or r.failure is not None
                    timed_out = now - r.start > self.timeout and not final
                    if r.proc.exitcode is None and not final and not timed_out:
                        continue
                    if timed_out and r.proc.exitcode is None:
                        r.proc.kill()
                    r.proc.join(timeout=5)
                    if r.proc.exitcode is None:
                        r.proc.kill()
                        r.proc.join(timeout=5)
                    r.drain()
                    running.remove(r)
                    oc = self._finish(r, timed_out)
                    finished.append(oc)
                    done_n += 1
                    if self.progress:
                        self.progress(done_n, total, r.sub.student, oc)
        except BaseException:
            for r in running:
                if r.proc.exitcode is None:
                    r.proc.kill()
                r.proc.join(timeout=5)
            raise
        return finished

    def _start(self, ctx: Any, sub: Submission) -> _Running:
        d = self.out / sub.student
        d.mkdir(parents=True, exist_ok=True)
        for old in list(d.glob("*.png")) + list(d.glob("*.rrd")):
            old.unlink()
        job = {"lab": str(self.lab.path), "paths": [str(p) for p in sub.paths],
               "student": sub.student, "media_dir": str(d) if self.media else None,
               "rrd": self.media, "memory_mb": self.memory_mb,
               "selftest_crash": self.selftest_crash, "log": str(d / LOG)}
        from .worker import child_main

        parent, child = ctx.Pipe(duplex=False)
        proc = ctx.Process(target=child_main, args=(job, child), daemon=True,
                           name=f"plclab-grade-{sub.student}")
        proc.start()
        child.close()
        return _Running(sub, proc, parent, d)

    def _finish(self, r: _Running, timed_out: bool) -> Outcome:
        wall = time.monotonic() - r.start
        lab = self.lab
        if r.done is not None and not timed_out:
            res = r.done
        else:
            if timed_out:
                status = "timeout"
                msg = (f"The grading of this submission was stopped after {self.timeout:g} s "
                       "(time limit, PLC5023). Scenarios that finished count; the others score "
                       "0. Is there a loop that runs a very long time in every scan?")
            elif r.failure is not None and r.failure[0] == "memory":
                status = "memory"
                msg = (f"The program needs more than {self.memory_mb} MB of memory (PLC5024): "
                       "are there huge arrays? Scenarios that finished count.")
            elif r.failure is not None:
                status = "crash"
                msg = (f"The grading process failed: {r.failure[1]} (PLC5025). Scenarios that "
                       "finished count; please tell your instructor.")
            else:
                status = "crash"
                msg = (f"The grading process crashed ({_signame(r.proc.exitcode)}, PLC5025). "
                       "Scenarios that finished count; please tell your instructor.")
            got = {s.name for s in r.scenarios}
            rest = [s for s in lab.scenarios if s.name not in got]
            res = failed_result(lab, status, msg, rest, r.diags or [])
            res.scenarios = r.scenarios + res.scenarios
            res.tests = r.tests + res.tests
            order = {s.name: i for i, s in enumerate(lab.scenarios)}
            res.scenarios.sort(key=lambda s: order.get(s.name, 0))
            res.tests.sort(key=lambda t: order.get(t.scenario, 0))
            res.files = [n for _, n in r.sub.sources]
        res.student = r.sub.student
        res.submission_hash = r.sub.hash
        res.lab_hash = lab.hash
        res.execution_time = wall
        self._write_student(res)
        with_conn_closed(r.conn)
        log = r.media / LOG
        try:
            if log.is_file() and log.stat().st_size == 0:
                log.unlink()
        except OSError:
            pass
        return Outcome(res, False, wall)

    # ------------------------------------------------------------------ files
    def _write_student(self, res: Result) -> None:
        d = self.out / res.student
        write_json(d / "results.json", results_json(res))
        write_atomic(d / "feedback.md", render_feedback(res))
        write_json(d / SIDECAR, {"grader": GRADER_VERSION, "lab": self.lab.id,
                                 "submission_hash": res.submission_hash,
                                 "lab_hash": self.lab.hash, "result": res.to_json()})

    def test_names(self) -> list[str]:
        return [f"{s.name}: {c.name}" for s in self.lab.scenarios
                for c in self.lab.criteria_for(s.name)]

    def _write_gradebook(self, results: list[Result]) -> None:
        write_atomic(self.out / "grades.csv", gradebook_csv(results, self.test_names()))


def with_conn_closed(conn: Any) -> None:
    try:
        conn.close()
    except OSError:
        pass


# ---------------------------------------------------------------------------- terminal


class ProgressBar:
    """A one-line progress bar (only used when stdout is a terminal)."""

    def __init__(self, stream: Any = None, width: int = 30) -> None:
        self.stream = stream or sys.stdout
        self.width = width
        self.t0 = time.monotonic()

    def __call__(self, done: int, total: int, student: str, oc: Outcome) -> None:
        frac = done / total if total else 1.0
        n = int(round(frac * self.width))
        bar = "#" * n + "." * (self.width - n)
        el = time.monotonic() - self.t0
        what = "skipped" if oc.skipped else f"{oc.result.score:g}/{oc.result.max_score:g}"
        line = f"\r[{bar}] {done}/{total} {el:5.1f} s  {student[:24]:<24} {what:<12}"
        self.stream.write(line)
        if done == total:
            self.stream.write("\n")
        self.stream.flush()


def summary_table(outcomes: list[Outcome]) -> str:
    """The end-of-run table: student, score, status, time."""
    rows = [("student", "score", "status", "time")]
    for o in outcomes:
        r = o.result
        rows.append((r.student, f"{r.score:g}/{r.max_score:g}",
                     r.status + (" (unchanged)" if o.skipped else ""),
                     "-" if o.skipped else f"{o.wall_s:.1f} s"))
    widths = [max(len(r[i]) for r in rows) for i in range(4)]
    lines = []
    for i, row in enumerate(rows):
        lines.append("  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip())
        if i == 0:
            lines.append("  ".join("-" * w for w in widths))
    graded = list(outcomes)
    if graded:
        scores = [o.result.score for o in graded]
        mx = graded[0].result.max_score
        lines.append("")
        lines.append(f"{len(graded)} submissions, mean {sum(scores) / len(scores):.1f}/{mx:g}, "
                     f"{sum(1 for s in scores if s >= mx)} with full marks")
    return "\n".join(lines)
