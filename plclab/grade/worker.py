"""The child process that grades one submission.

The autograder (:mod:`plclab.grade.grader`) starts one process per submission through a
multiprocessing *forkserver* that has already imported NumPy, the simulator, the plants,
rerun and Pillow (:func:`preload`), so a child starts in milliseconds. The child

0. confines itself (:mod:`plclab.grade.sandbox`): an empty temporary working folder, a minimal
   environment, death with its parent, a CPU-time limit; it gets the submission's text and the
   lab's data, not paths, and only sends results (JSON) -- the grader validates and writes them
   (:mod:`plclab.grade.protocol`);
1. limits its address space (``RLIMIT_AS``: what it has after start-up plus the memory limit)
   while it compiles and simulates -- a program with huge arrays gets ``MemoryError`` (PLC2009)
   instead of taking the machine down; the limit is lifted again to draw the feedback;
2. grades the submission (:func:`plclab.grade.engine.grade_sources`), sending each scenario's
   tests to the parent as soon as they are known, so a submission stopped at the time limit
   keeps what it earned;
3. sends the whole result and ends.

The parent kills a child that runs past the wall-clock limit. ``python -m plclab.grade.worker
LAB SUBMISSION [--media DIR]`` grades one submission in this process and prints the result as
JSON (for debugging, or as the body of a Gradescope ``run_autograder`` script).
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

PRELOAD = ("numpy", "plclab.sim", "plclab.trace", "plclab.grade.engine", "plclab.grade.feedback",
           "plclab.viz.from_trace", "plclab.viz.timing", "plants", "plclab.process", "rerun",
           "plclab.viz.recording", "plclab.viz.layout", "plclab.viz.failure_png",
           "plclab.viz.failure_model", "plclab.viz.failure_trace", "plclab.i18n_labs", "PIL.Image",
           "PIL.ImageDraw", "PIL.ImageFont", "PIL.PngImagePlugin", "plclab.grade.protocol",
           "plclab.lang.sfc_outline", "plclab.lang.unparse", "plclab.viz.sfc_lane",
           "plclab.process.alarms", "plclab.process.recipes",
           "numpy.ma", "dateutil.relativedelta")  # rerun imports these when it writes a file
"""Imported once by the forkserver. ``rerun`` costs 0.3-0.5 s to import: without it here every
failing submission (which writes a recording) paid it again in its child. Every module a
child imports itself is compiled again in that child (there may be no ``.pyc`` to read:
``PYTHONDONTWRITEBYTECODE``, a read-only install), about 30 ms per child for the dozen small
modules a simulation needs, so they are here too (a test checks that grading a lab imports
nothing new in the child). rerun imports ``numpy.ma`` (about 50 ms: it inspects the
signature of every masked-array method) and ``dateutil`` only when a recording is written."""
PRELOAD_PACKAGES = ("plclab.io", "plclab.trace", "plclab.sim")
"""Packages whose every module (but the CLI's ``commands``) the forkserver imports: the I/O
modules, trace and simulation parts a lab's wiring and criteria may use."""


def _preload_modules() -> list[str]:
    import importlib
    import pkgutil

    names = list(PRELOAD)
    for pkg in PRELOAD_PACKAGES:
        try:
            path = importlib.import_module(pkg).__path__
        except Exception:  # noqa: BLE001, S112 - optional speed-up only
            continue
        names += [m.name for m in pkgutil.walk_packages(path, pkg + ".")
                  if not m.name.endswith(".commands")]
    return names


def preload() -> None:
    """Import what every grading needs (run once in the forkserver; errors are ignored)."""
    import importlib

    for mod in _preload_modules() + ["pymunk"]:
        try:
            importlib.import_module(mod)
        except Exception:  # noqa: BLE001, S112 - optional speed-up only
            continue
    try:
        import plclab

        plclab.loads("PROGRAM WarmUp VAR x : INT; END_VAR x := x + 1; END_PROGRAM", "warm.st")
    except Exception:  # noqa: BLE001 - only a warm-up of the compiler's caches
        pass
    try:
        _warm_timing_diagram()
    except Exception:  # noqa: BLE001 - no Pillow: no diagrams
        pass
    settle_heap()


def settle_heap() -> None:
    """Collect the garbage the imports and warm-ups left, then freeze what is left (``gc``'s
    advice for a process that forks workers): otherwise each child's first collections
    free and traverse the forkserver's objects, and every page they write is copied into
    that child (a page fault costs 5-9 us here; a failing tank child took ~3000 fewer faults
    and 40 ms less CPU with this, ADR 0033)."""
    import gc

    gc.collect()
    gc.freeze()


def _warm_timing_diagram() -> None:
    """Draw one small failure diagram (every row kind, a limit, a marker) into memory: the
    first diagram of a process costs several times the next one (fonts, the PNG encoder),
    and every child forked after this gets them ready. The diagrams are drawn with Pillow
    (ADR 0033): the forkserver no longer imports matplotlib (about 1 s of its start-up)."""
    from plclab.viz.series import Series
    from plclab.viz.timing import failure_png

    ts = [0.0, 1.0, 2.0, 3.0]
    rows = [Series("RUN", ts, [False, True, True, False], "bool"),
            Series("STEP", ts, [0, 1, 2, 1], "int"),
            Series("LEVEL [m]", ts, [0.5, 1.0, 1.5, 1.2], "real")]
    failure_png(rows, None, 0.0, 3.0, title="warm-up: x", markers=[(1.5, "fails")],
                thresholds={"LEVEL [m]": [(1.4, "limit")]})


def _vm_bytes() -> int:
    try:
        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, AttributeError):
        return 0


@contextlib.contextmanager
def memory_limit(mb: int | None) -> Iterator[None]:
    """Limit the address space this process may add by ``mb`` megabytes while inside."""
    try:
        import resource
    except ImportError:  # Windows: no limit
        yield
        return
    if not mb:
        yield
        return
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    want = _vm_bytes() + int(mb) * 2**20
    if hard != resource.RLIM_INFINITY:
        want = min(want, hard)
    try:
        resource.setrlimit(resource.RLIMIT_AS, (want, hard))
    except (ValueError, OSError):
        yield
        return
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def _redirect_output(log: str | None) -> None:
    """Send the child's stdout/stderr to a log file (or nowhere): warnings of one submission
    must not garble the parent's progress bar."""
    try:
        fd = os.open(log or os.devnull, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    except OSError:
        return
    for std in (1, 2):
        with contextlib.suppress(OSError):
            os.dup2(fd, std)
    os.close(fd)


def lab_payload(lab: Any) -> tuple[Any, dict[str, str]]:
    """What a child needs of a lab: a copy without paths into the lab folder and without the
    imported check functions, and the text of the lab's check modules (``{module: text}``)."""
    import copy
    import dataclasses

    crits = [dataclasses.replace(c, function=None) for c in lab.criteria]
    wiring = copy.deepcopy(lab.wiring)
    _base_names(wiring)
    clone = dataclasses.replace(lab, criteria=crits, path=Path(lab.id), wiring=wiring,
                                wiring_source=os.path.basename(lab.wiring_source))
    checks: dict[str, str] = {}
    for c in lab.criteria:
        mod = c.python.partition(":")[0]
        if c.python and mod not in checks:
            checks[mod] = (lab.path / f"{mod}.py").read_text(encoding="utf-8")
    return clone, checks


def _base_names(obj: Any, depth: int = 0) -> None:
    """Replace file paths in the wiring's locations by their base names (a child names the
    file in a message; it never needs to open it)."""
    import dataclasses

    from plclab.errors import Location

    if depth > 6:
        return

    def put(key: Any, value: Any) -> None:
        if isinstance(obj, dict | list):
            obj[key] = value
        else:
            object.__setattr__(obj, key, value)

    items = (obj.items() if isinstance(obj, dict) else enumerate(obj)
             if isinstance(obj, list) else vars(obj).items() if hasattr(obj, "__dict__")
             else ())
    for key, v in list(items):
        if isinstance(v, Location) and v.file:
            put(key, dataclasses.replace(v, file=os.path.basename(v.file)))
        elif key == "source" and isinstance(v, str):
            put(key, os.path.basename(v))
        elif isinstance(v, dict | list) or hasattr(v, "__dict__"):
            _base_names(v, depth + 1)


def lab_from_payload(lab: Any, checks: dict[str, str]) -> Any:
    """The lab of :func:`lab_payload` with its check functions bound again. The check
    modules are the instructor's code (trusted, as in the grader); they are compiled from the
    text the grader sent, not imported from the lab folder."""
    import types

    mods: dict[str, Any] = {}
    for name, text in checks.items():
        mod = types.ModuleType(f"plclab_lab_check_{name}")
        mod.__file__ = f"<lab {lab.id}>/{name}.py"
        exec(compile(text, mod.__file__, "exec"), mod.__dict__)  # noqa: S102 - instructor code
        mods[name] = mod
    for c in lab.criteria:
        if c.python:
            mod, _, fn = c.python.partition(":")
            c.function = getattr(mods[mod], fn)
    return lab


class _Outbox:
    """The child's side of the pipe: JSON messages, pictures sent as capped bytes."""

    def __init__(self, conn: Any, media_dir: Path | None) -> None:
        self.conn = conn
        self.media_dir = media_dir
        self.dropped: set[str] = set()

    def send(self, kind: str, *payload: Any) -> None:
        from .protocol import encode

        self.conn.send_bytes(encode(kind, *payload))

    def send_media(self) -> None:
        """Send (then delete) every picture drawn so far; over-size ones are dropped."""
        from .protocol import encode_media

        if self.media_dir is None or not self.media_dir.is_dir():
            return
        for f in sorted(self.media_dir.iterdir()):
            msg = encode_media(f) if f.is_file() and not f.is_symlink() else None
            if msg is None:
                self.dropped.add(f.name)
            else:
                self.conn.send_bytes(msg)
            with contextlib.suppress(OSError):
                f.unlink()

    def scenario(self, run: Any, tests: list[Any]) -> None:
        self.send_media()
        for t in tests:
            if t.diagram in self.dropped:
                t.diagram = None
        if run.rrd in self.dropped:
            run.rrd, run.rrd_note = None, "no .rrd recording (larger than the grader accepts)"
        self.send("scenario", run.to_json(), [t.to_json() for t in tests])


def child_main(job: dict[str, Any], conn: Any) -> None:
    """Grade one submission (``job`` from the grader) and report through ``conn``.

    The job holds the submission's text and the lab's data, never paths: the child confines
    itself (:func:`plclab.grade.sandbox.confine`) to the empty folder ``job["workdir"]``,
    draws its pictures there and sends everything to the grader, which alone writes results.
    """
    from .sandbox import confine

    with contextlib.suppress(ValueError, OSError):
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's business
    _redirect_output(os.path.join(job["workdir"], LOG_NAME))  # first: no trace on the terminal
    confine(job["workdir"], job.get("grader_pid"), job.get("cpu_seconds"))
    media = Path(job["workdir"]) / "media" if job.get("media") else None
    out = _Outbox(conn, media)
    failure: tuple[str, ...] | None = None
    on_scenario = out.scenario
    if job.get("selftest_kill"):  # the grader's own test: killed mid-run from "outside"
        def on_scenario(run: Any, tests: Any) -> None:
            out.scenario(run, tests)
            os.kill(os.getpid(), signal.SIGKILL)
    try:
        from .engine import grade_sources

        lab = lab_from_payload(job["lab"], job.get("checks", {}))
        res = grade_sources(lab, [tuple(s) for s in job["sources"]], student=job["student"],
                            scenarios=job.get("scenarios"), media_dir=media, rrd=bool(job.get("media")),
                            on_scenario=on_scenario,
                            on_compiled=lambda diags: compiled(out, diags, job),
                            guard=lambda: memory_limit(job.get("memory_mb")))
        if job.get("selftest_crash"):
            import faulthandler

            faulthandler._sigsegv()  # a real crash, for the grader's own tests
        out.send("done", res.to_json())
    except MemoryError:
        failure = ("memory",)
    except BaseException as e:  # noqa: BLE001 - report anything, never a traceback
        failure = ("error", f"{type(e).__name__}: {e}")
    if failure is not None:
        with contextlib.suppress(Exception):
            out.send(*failure)
    with contextlib.suppress(Exception):
        conn.close()


def compiled(out: _Outbox, diags: Any, job: dict[str, Any]) -> None:
    """Report the compilation; a test's held child (``selftest_hold``) then says so in its
    log and waits to be killed from outside (its time limit ends it otherwise)."""
    out.send("compiled", diags)
    if job.get("selftest_hold"):
        print(f"{HOLDING} (pid {os.getpid()})", flush=True)
        while True:
            time.sleep(1.0)


HOLDING = "plclab selftest: compiled, holding until killed"
"""The log line of a held child (``PLCLAB_GRADE_SELFTEST_HOLD``) that a test waits for."""
LOG_NAME = "child.log"
"""The child's stdout and stderr, in its working folder (the grader keeps the end of it)."""


def main(argv: list[str] | None = None) -> int:
    import argparse

    from plclab.errors import PlcError

    from .engine import grade_sources, read_submission
    from .lab import load_lab, require_hidden

    p = argparse.ArgumentParser(prog="python -m plclab.grade.worker",
                                description="grade one submission; print the result as JSON")
    p.add_argument("lab")
    p.add_argument("submission")
    p.add_argument("--media", default=None, help="folder for diagrams and recordings")
    p.add_argument("--memory", type=int, default=1536, help="memory limit, MB")
    p.add_argument("--gradescope", action="store_true",
                   help="print Gradescope's results.json instead of the full result")
    p.add_argument("--visible-only", action="store_true",
                   help="accept a lab without its hidden scenarios (the student copy)")
    ns = p.parse_args(argv)
    lab = load_lab(ns.lab)
    try:
        require_hidden(lab, ns.visible_only)
    except PlcError as e:
        print(str(e), file=sys.stderr)
        return 2
    sources, _ = read_submission(ns.submission)
    res = grade_sources(lab, sources, student=os.path.basename(ns.submission.rstrip("/")),
                        media_dir=ns.media, guard=lambda: memory_limit(ns.memory))
    if ns.gradescope:
        from .gradescope import results_json

        print(json.dumps(results_json(res), indent=2))
    else:
        print(json.dumps(res.to_json(), indent=2))
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
