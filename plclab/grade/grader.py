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

import contextlib
import json
import os
import shutil
import signal
import stat
import tempfile
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing.connection import wait
from pathlib import Path
from typing import Any

from plclab.errors import PlcError

from .engine import STUDENT_STATUSES, Result, failed_result, read_submission, source_hash
from .errors import grade_error
from .feedback import render_feedback
from .gradescope import gradebook_csv, results_json, write_atomic, write_json
from .lab import SOURCE_EXTS, Lab
from .protocol import INFRA_RETRIES, LIMITS, MEDIA_NAME, Inbox, Rejected
from .safety import clean_text, output_dirname
from .spawn import (  # noqa: F401 - remove_stale_workdirs: also the grader's name for it
    FORKSERVER_LOST,
    child_context,
    direct_context,
    read_child_log,
    remove_stale_workdirs,
    start_child,
    work_prefix,
)

GRADER_VERSION = "2"
_OUTSIDE_SIGNALS = {int(getattr(signal, n)) for n in ("SIGKILL", "SIGTERM", "SIGHUP", "SIGINT")
                    if hasattr(signal, n)}
SIDECAR = ".plclab-result.json"
LOG = ".plclab-grade.log"
CPU_MARGIN = 5.0
"""CPU seconds a child may use beyond the wall-clock limit before the kernel stops it."""


@dataclass
class Submission:
    """One student's files.

    ``student`` is the printable id shown everywhere, ``dirname`` the folder of the student's
    outputs (:func:`plclab.grade.safety.output_dirname`), ``files`` the display names of the
    sources and ``error`` the reason a submission is rejected without being run."""

    student: str
    paths: list[Path]
    sources: list[tuple[str, str]] = field(default_factory=list)
    hash: str = ""
    dirname: str = ""
    files: list[str] = field(default_factory=list)
    error: PlcError | None = None


@dataclass
class Outcome:
    """A graded (or skipped) submission."""

    result: Result
    skipped: bool = False
    wall_s: float = 0.0
    dirname: str = ""


def _group_key(p: Path) -> str | None:
    """The student id of an entry of the submissions folder (None: not a submission).
    Decided on the entry itself (``lstat``): a link is never followed, only reported."""
    try:
        mode = os.lstat(p).st_mode
    except OSError:
        return None
    suffix = p.suffix.lower()
    if stat.S_ISDIR(mode) or (stat.S_ISLNK(mode) and not suffix):
        return p.name
    return p.stem or p.name  # a source file, or another file: it gets a row too


def discover(folder: str | os.PathLike, exclude: Path | None = None) -> list[Submission]:
    """The submissions in a folder, sorted by student id (nothing is followed or run; each
    is read once, with every cap, to hash it)."""
    root = Path(folder)
    if not root.is_dir():
        raise grade_error("PLC5026", f"{root} is not a folder of submissions; give a folder "
                          "holding one file or one folder per student")
    groups: dict[str, list[Path]] = {}
    for p in sorted(root.iterdir()):
        if p.name in JUNK:  # what file managers and archivers leave, not a student's
            continue
        if exclude is not None and p.resolve() == exclude.resolve():
            continue
        key = _group_key(p)
        if key is not None:
            groups.setdefault(key, []).append(p)
    subs = []
    shown: set[str] = set()
    dirs: set[str] = set()
    for raw, paths in sorted(groups.items()):
        student = clean_text(raw)
        while student in shown:
            student += "~"
        shown.add(student)
        sub = Submission(student, paths, dirname=output_dirname(student, dirs))
        if not any(_is_program(p) for p in paths):
            names = ", ".join(clean_text(p.name) for p in paths)
            sub.error = grade_error("PLC5071", f"{names}: not a program (a .st, .il, .ld or "
                                    ".xml file, or a folder holding them); nothing to grade")
            sub.hash = "rejected"
        else:
            _read(sub)
        subs.append(sub)
    return subs


JUNK = frozenset({".DS_Store", "Thumbs.db", "desktop.ini", "__MACOSX", ".git", ".svn",
                  ".ipynb_checkpoints"})
"""Entries of a submissions folder that are never a student's (every other entry, a hidden
file or a stray PDF included, gets a gradebook row)."""


def _is_program(p: Path) -> bool:
    """A folder, a link (reported when read) or a source file: something to grade."""
    try:
        mode = os.lstat(p).st_mode
    except OSError:
        return False
    return stat.S_ISDIR(mode) or stat.S_ISLNK(mode) or p.suffix.lower() in SOURCE_EXTS


def _read(sub: Submission) -> None:
    """Read a submission's files (texts kept in ``sub.sources``) or note why it is rejected."""
    sources: list[tuple[str, str]] = []
    try:
        for p in sub.paths:
            got, _ = read_submission(p)
            sources += got
    except PlcError as e:
        sub.error, sub.sources, sub.files = e, [], []
        sub.hash = "rejected"
        return
    sub.sources = sources
    sub.files = [n for _, n in sources]
    sub.hash = source_hash(sources)


def _signame(code: int | None) -> str:
    if code is None:
        return "still running"
    if code == FORKSERVER_LOST:
        return "its forkserver was killed"
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exit code {code}"


class _Running:
    """A child at work: its process, pipe, working folder and what it sent (checked)."""

    def __init__(self, sub: Submission, proc: Any, conn: Any, media: Path, workdir: Path,
                 inbox: Inbox) -> None:
        self.sub = sub
        self.proc = proc
        self.conn = conn
        self.media = media
        self.workdir = workdir
        self.inbox = inbox
        self.start = time.monotonic()
        self.rejected = ""
        self.eof = False

    @property
    def final(self) -> bool:
        return (self.inbox.done is not None or self.inbox.failure is not None
                or bool(self.rejected))

    @property
    def exitcode(self) -> int | None:
        return self.proc.exitcode

    def log_text(self) -> str:
        return read_child_log(self.workdir)

    def close(self) -> None:
        with_conn_closed(self.conn)
        shutil.rmtree(self.workdir, ignore_errors=True)

    def drain(self) -> None:
        """Take every message waiting on the pipe; a bad one rejects the child's results."""
        while not self.eof and not self.rejected:
            try:
                if not self.conn.poll():
                    return
                raw = self.conn.recv_bytes(LIMITS["message"])
            except EOFError:
                self.eof = True
                return
            except OSError as e:
                if "message length" in str(e):
                    self.rejected = "a message larger than the grader accepts"
                self.eof = True
                return
            try:
                self.inbox.receive(raw)
            except Rejected as e:
                self.rejected = str(e)


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
    scenarios : names, optional
        Only these scenarios (``plclab lab check``: the visible ones); default: all.
    direct : bool, optional
        :meth:`grade_one` starts its child directly (``fork``) instead of through a
        forkserver (``plclab lab check``: the student's own process; ADR 0057).
    executor : str, optional
        None: a local process pool of ``jobs`` children; ``tcp://HOST:PORT``: the Dask
        scheduler whose workers run the children (:mod:`plclab.grade.cluster`).
    """

    def __init__(self, lab: Lab, out: str | os.PathLike, jobs: int = 2,
                 timeout: float | None = None, memory_mb: int | None = None,
                 force: bool = False, media: bool = True,
                 progress: Callable[[int, int, str, Outcome], None] | None = None,
                 scenarios: list[str] | None = None, executor: str | None = None,
                 direct: bool = False) -> None:
        self.lab = lab
        self.direct = direct  # grade_one in a direct child, no forkserver (spawn.direct_context)
        self.executor = executor
        self.out = Path(out)
        self.jobs = max(1, int(jobs))
        self.timeout = float(timeout if timeout is not None else lab.time_limit)
        self.memory_mb = int(memory_mb if memory_mb is not None else lab.memory_limit_mb)
        self.force = force
        self.media = media
        self.progress = progress
        self.scenarios = None if scenarios is None else list(scenarios)
        self.selftest_crash = os.environ.get("PLCLAB_GRADE_SELFTEST_CRASH", "")
        self._tries: dict[str, int] = {}  # submissions graded again after an outside kill
        self._payload: tuple[Any, dict[str, str]] | None = None

    # ------------------------------------------------------------------ the run
    def grade_folder(self, folder: str | os.PathLike) -> list[Outcome]:
        remove_stale_workdirs()
        subs = discover(folder, exclude=self.out)
        self.out.mkdir(parents=True, exist_ok=True)
        outcomes: dict[str, Outcome] = {}
        todo: deque[Submission] = deque()
        for s in subs:
            prev = None if self.force or s.error else self._previous(s)
            if prev is not None:
                outcomes[s.student] = Outcome(prev, skipped=True, dirname=s.dirname)
            elif s.error is not None:
                outcomes[s.student] = self._rejected(s)
            else:
                todo.append(s)
            s.sources = []  # read again when it is its turn: memory stays small
        total = len(subs)
        done_n = len(outcomes)
        if self.progress:
            for st, oc in sorted(outcomes.items()):
                self.progress(done_n, total, st, oc)
        if todo and self.executor:
            from .cluster import run_on_cluster

            for oc in run_on_cluster(self, self.executor, todo, total, done_n):
                outcomes[oc.result.student] = oc
        elif todo:
            for oc in self._run(todo, total, done_n):
                outcomes[oc.result.student] = oc
        results = [outcomes[s.student] for s in subs]
        self._write_gradebook([o.result for o in results])
        return results

    def grade_one(self, sources: list[tuple[str, str]], student: str = "") -> Outcome:
        """Grade sources already read (``plclab lab check``) in a child process with the same
        limits as :meth:`grade_folder`; the files go to ``out/check/``."""
        sub = Submission(student, [], sources=list(sources), hash=source_hash(sources),
                         dirname="check", files=[n for _, n in sources])
        self.out.mkdir(parents=True, exist_ok=True)
        return self._run(deque([sub]), 1, 0)[0]

    def _previous(self, s: Submission) -> Result | None:
        """The result of an earlier run, if the submission, lab and grader are unchanged and
        the stored result still passes the same checks as a child's."""
        d = self.out / s.dirname
        side = d / SIDECAR
        try:
            if not side.is_file() or side.is_symlink() or not (d / "results.json").is_file():
                return None
            if side.stat().st_size > 4 * LIMITS["message"]:
                return None
            data = json.loads(side.read_text(encoding="utf-8"))
            if (data.get("submission_hash") != s.hash or data.get("lab_hash") != self.lab.hash
                    or data.get("grader") != GRADER_VERSION
                    or data.get("scenarios") != self.scenarios  # the same selection only
                    or data["result"].get("status") not in STUDENT_STATUSES):
                return None  # changed, or not the student's outcome: grade it again
            inbox = Inbox(self.lab, None)
            inbox.media = {p.name for p in d.iterdir() if MEDIA_NAME.match(p.name)}
            inbox.receive(json.dumps(["done", data["result"]]).encode())
            res = inbox.done
            exec_s = data["result"].get("execution_time", 0.0)
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            return None
        assert res is not None
        self._stamp(res, s, exec_s if isinstance(exec_s, float | int) else 0.0)
        return res

    def _run(self, todo: deque[Submission], total: int, done_n: int) -> list[Outcome]:
        ctx = (direct_context() if self.direct and len(todo) == 1 else None) or child_context()
        running: list[_Running] = []
        closing: list[_Running] = []  # finished, being joined and written out
        finished: list[Outcome] = []

        def start_more() -> int:
            """Start children up to ``jobs``; the number of submissions rejected instead."""
            rejected = 0
            while todo and len(running) < self.jobs:
                started = self._start(ctx, todo.popleft())
                if isinstance(started, Outcome):  # changed since discover: rejected now
                    finished.append(started)
                    rejected += 1
                    continue
                running.append(started)
            return rejected

        try:
            while todo or running:
                done_n += start_more()
                objs = [r.conn for r in running if not r.eof] + [r.proc.sentinel
                                                                   for r in running]
                wait(objs, timeout=0.05)
                now = time.monotonic()
                for r in list(running):
                    r.drain()
                    timed_out = now - r.start > self.timeout and not r.final
                    if r.proc.exitcode is None and not r.final and not timed_out:
                        continue
                    if (timed_out or r.rejected) and r.proc.exitcode is None:
                        r.proc.kill()
                    running.remove(r)
                    closing.append(r)
                    # the next child starts now, while this one exits and its files are
                    # written (a core would idle meanwhile, ~8 ms a submission)
                    done_n += start_more()
                    r.proc.join(timeout=5)
                    if r.proc.exitcode is None:
                        r.proc.kill()
                        r.proc.join(timeout=5)
                    r.drain()
                    if self._grade_again(r, timed_out):
                        # not the student's doing: grade it again, nothing is written
                        r.close()
                        shutil.rmtree(r.workdir, ignore_errors=True)
                        closing.remove(r)
                        todo.append(r.sub)
                        continue
                    oc = self._finish(r, timed_out)
                    closing.remove(r)
                    finished.append(oc)
                    done_n += 1
                    if self.progress:
                        self.progress(done_n, total, r.sub.student, oc)
        except BaseException:
            for r in running + closing:
                if r.proc.exitcode is None:
                    r.proc.kill()
                r.proc.join(timeout=5)
                shutil.rmtree(r.workdir, ignore_errors=True)
            raise
        return finished

    def _grade_again(self, r: Any, timed_out: bool) -> bool:
        """Whether a finished child (local or replayed from a cluster worker) was killed from
        outside and may be tried again (at most INFRA_RETRIES times); counts the try."""
        if not self._killed_from_outside(r, timed_out) or \
                self._tries.get(r.sub.dirname, 0) >= INFRA_RETRIES:
            return False
        self._tries[r.sub.dirname] = self._tries.get(r.sub.dirname, 0) + 1
        return True

    @staticmethod
    def _killed_from_outside(r: Any, timed_out: bool) -> bool:
        """A child that ended by a signal the grader did not send, with no result: the OOM
        killer, an administrator, a lost machine, or its forkserver killed (the child died
        with it and its status is lost, :data:`~plclab.grade.spawn.FORKSERVER_LOST`); never
        something the program did inside its limits (those end as a result, a timeout,
        SIGXCPU or a memory failure)."""
        code = r.exitcode
        return (not timed_out and not r.rejected and r.inbox.done is None
                and r.inbox.failure is None and code is not None
                and (-code in _OUTSIDE_SIGNALS or code == FORKSERVER_LOST))

    def _lab_payload(self) -> tuple[Any, dict[str, str]]:
        if self._payload is None:
            from .worker import lab_payload

            self._payload = lab_payload(self.lab)
        return self._payload

    def job_of(self, sub: Submission) -> dict[str, Any]:
        """What a child needs besides the lab and its working folder (the same on every
        executor)."""
        return {"sources": sub.sources, "student": sub.student, "media": self.media,
                "memory_mb": self.memory_mb, "scenarios": self.scenarios,
                "cpu_seconds": self.timeout + CPU_MARGIN,
                "selftest_crash": bool(self.selftest_crash)
                and self.selftest_crash == sub.student,
                "selftest_kill": self._selftest("KILL", sub),
                "selftest_hold": self._selftest("HOLD", sub)}

    def _selftest(self, what: str, sub: Submission) -> bool:
        """The grader's own tests of ADR 0040, ``PLCLAB_GRADE_SELFTEST_<what>=student:N``:
        the first N processes grading that student SIGKILL themselves after one scenario, as
        the OOM killer would (``KILL``; the parent cannot tell it from a kill from outside),
        or wait after compiling, until the test kills them or their time limit (``HOLD``:
        a test's kill from outside lands mid-run however loaded the machine is)."""
        who, _, n = os.environ.get(f"PLCLAB_GRADE_SELFTEST_{what}", "").rpartition(":")
        return bool(who) and who == sub.student and n.isdigit() and \
            self._tries.get(sub.dirname, 0) < int(n)

    def prepare(self, sub: Submission) -> Path | Outcome:
        """Read a submission again (it may have changed since :func:`discover`) and empty the
        student's folder of old pictures; the rejected outcome when it cannot be run."""
        if not sub.sources:
            _read(sub)
            if sub.error is not None:
                return self._rejected(sub)
        d = self.out / sub.dirname
        d.mkdir(parents=True, exist_ok=True)
        for old in list(d.glob("*.png")) + list(d.glob("*.rrd")):
            old.unlink()
        return d

    def _start(self, ctx: Any, sub: Submission) -> _Running | Outcome:
        d = self.prepare(sub)
        if isinstance(d, Outcome):
            return d
        workdir = Path(tempfile.mkdtemp(prefix=work_prefix()))
        lab, checks = self._lab_payload()
        job = {"lab": lab, "checks": checks, **self.job_of(sub), "workdir": str(workdir),
               "grader_pid": os.getpid()}
        sub.sources = []
        from .worker import child_main

        parent, child = ctx.Pipe(duplex=False)
        proc = ctx.Process(target=child_main, args=(job, child), daemon=True,
                           name=f"plclab-grade-{sub.dirname}")
        try:
            start_child(proc)
        except BaseException:
            with_conn_closed(parent)
            with_conn_closed(child)
            shutil.rmtree(workdir, ignore_errors=True)
            raise
        child.close()
        return _Running(sub, proc, parent, d, workdir, Inbox(self.lab, d if self.media else None))

    def _rejected(self, sub: Submission) -> Outcome:
        """A submission that was not run: links, sizes, special files (PLC5030..PLC5033)."""
        err = sub.error
        assert err is not None
        msg = (f"This submission was not graded: {err.message} ({err.code}). Nothing of it "
               "was run; fix it and submit again.")
        res = failed_result(self.lab, "rejected", msg, self.lab.scenarios)
        self._stamp(res, sub, 0.0)
        self._write_student(res, sub.dirname)
        return Outcome(res, False, 0.0, sub.dirname)

    def _stamp(self, res: Result, sub: Submission, wall: float) -> None:
        """What only the grader knows: who, which files, hashes, time."""
        res.student = sub.student
        res.files = list(sub.files)
        res.submission_hash = sub.hash
        res.lab_hash = self.lab.hash
        res.lab_title = self.lab.title
        res.execution_time = float(wall)

    def _finish(self, r: Any, timed_out: bool) -> Outcome:
        """The outcome of a child (a :class:`_Running` here, or one replayed from a cluster
        worker, :class:`plclab.grade.cluster.Replayed`), written to the student's folder."""
        wall = time.monotonic() - r.start
        lab = self.lab
        box = r.inbox
        code = r.exitcode
        cpu = code == -getattr(signal, "SIGXCPU", 0)  # RLIMIT_CPU: a late wall-clock kill
        if r.rejected:
            res = failed_result(lab, "rejected", "The grading process sent results the grader "
                                f"does not accept ({clean_text(r.rejected, 300)}; PLC5034): "
                                "nothing it sent counts. Please tell your instructor.",
                                lab.scenarios)
            for p in list(r.media.glob("*.png")) + list(r.media.glob("*.rrd")):
                p.unlink()
        elif box.done is not None and not timed_out:
            res = box.done
            self._complete(res, box.diags)
        else:
            if timed_out or cpu:
                status = "timeout"
                why = ("time limit, PLC5023" if timed_out else
                       f"CPU time limit of {self.timeout + CPU_MARGIN:g} s, PLC5035")
                msg = (f"The grading of this submission was stopped after {self.timeout:g} s "
                       f"({why}). Scenarios that finished count; the others score "
                       "0. Is there a loop that runs a very long time in every scan?")
            elif box.failure is not None and box.failure[0] == "memory":
                status = "memory"
                msg = (f"The program needs more than {self.memory_mb} MB of memory (PLC5024): "
                       "are there huge arrays? Scenarios that finished count.")
            elif box.failure is not None:
                status = "crash"
                msg = (f"The grading process failed: {box.failure[1]} (PLC5025). Scenarios that "
                       "finished count; please tell your instructor.")
            elif self._killed_from_outside(r, timed_out):
                status = "infrastructure"
                msg = (f"The grading process was stopped from outside ({_signame(code)}) "
                       f"{INFRA_RETRIES + 1} times: the grading machine, not the program "
                       "(PLC5070). Nothing is kept: grade again, with fewer --jobs or more "
                       "memory.")
            else:
                status = "crash"
                msg = (f"The grading process crashed ({_signame(code)}, PLC5025). "
                       "Scenarios that finished count; please tell your instructor.")
            res = failed_result(lab, status, msg, [], box.diags or [])
            res.scenarios = list(box.scenarios)
            res.tests = list(box.tests)
            self._complete(res, box.diags)
        self._stamp(res, r.sub, wall)
        self._write_student(res, r.sub.dirname)
        self._keep_log(r)
        r.close()
        return Outcome(res, False, wall, r.sub.dirname)

    def _complete(self, res: Result, diags: list[str] | None) -> None:
        """Add the lab's scenarios a child did not report (0 points, "not run") and put
        scenarios and tests in the lab's order."""
        lab = self.lab
        got = {s.name for s in res.scenarios}
        rest = [s for s in lab.scenarios if s.name not in got
                and (self.scenarios is None or s.name in self.scenarios)]
        if rest:
            why = res.status if res.status != "ok" else "crash"
            filler = failed_result(lab, why, "", rest)
            res.scenarios += filler.scenarios
            res.tests += filler.tests
        if not res.diagnostics and diags:
            res.diagnostics = list(diags)
        order = {s.name: i for i, s in enumerate(lab.scenarios)}
        res.scenarios.sort(key=lambda s: order.get(s.name, 0))
        res.tests.sort(key=lambda t: order.get(t.scenario, 0))

    def _keep_log(self, r: Any) -> None:
        """The end of the child's stdout/stderr, if it wrote any."""
        log = r.media / LOG
        text = r.log_text()
        if text.strip():
            write_atomic(log, text)
        else:
            with contextlib.suppress(OSError):
                log.unlink()

    # ------------------------------------------------------------------ files
    def _write_student(self, res: Result, dirname: str) -> None:
        d = self.out / dirname
        write_json(d / "results.json", results_json(res))
        from plclab.i18n_labs import localize_result

        shown, _ = localize_result(res, self.lab)  # the language chosen (ADR 0063)
        write_atomic(d / "feedback.md", render_feedback(shown))
        write_json(d / SIDECAR, {"grader": GRADER_VERSION, "lab": self.lab.id,
                                 "submission_hash": res.submission_hash,
                                 "lab_hash": self.lab.hash, "scenarios": self.scenarios,
                                 "result": res.to_json()})

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
