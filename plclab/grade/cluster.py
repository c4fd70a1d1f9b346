"""Grading on a Dask cluster: ``plclab grade LAB SUBS --executor dask://HOST:PORT``.

The client (the instructor's ``plclab grade``) keeps every decision of the local grader:
which submissions to grade (unchanged ones are skipped), the checks of what a child sent,
the files. A cluster only replaces *where the child runs*:

* the lab (its data and the text of its check modules, :func:`plclab.grade.worker.lab_payload`)
  is scattered once to every worker (``broadcast=True``); a task refers to it;
* one submission is one task, :func:`run_on_worker`: on the worker it starts the same
  sandboxed child as the local grader (forkserver, confinement, the lab's wall-clock, CPU and
  memory limits) and returns the child's raw messages, its exit code and its log -- never a
  result the worker built;
* the client replays those messages through its own :class:`~plclab.grade.protocol.Inbox`
  (:class:`Replayed`) and writes the student's files atomically as each task completes, so
  ``results.json`` is byte for byte the local executor's apart from timings, and an
  interrupted run resumes where it stopped;
* a worker that dies takes its children with it (they die with their parent); the scheduler
  runs its tasks again on another worker, and a task lost for good (or a child killed from
  outside) is submitted again by the client, then reported as "infrastructure", never as the
  student's crash (ADR 0040). The lab travels with each task: data scattered to a worker would
  die with it.

Dask (not Ray): see docs/adr/0026-grading-on-dask.md.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import shutil
import signal
import tempfile
import time
from collections import deque
from multiprocessing.connection import wait
from pathlib import Path
from typing import Any

from .errors import grade_error
from .protocol import LIMITS, Inbox, Rejected
from .spawn import work_prefix

SCHEME = "dask://"
FINAL_KINDS = (b'["done"', b'["memory"', b'["error"')


def is_cluster(executor: str | None) -> bool:
    """Whether ``--executor`` names a cluster (``dask://HOST:PORT``) rather than ``local``."""
    return bool(executor) and str(executor).startswith(SCHEME)


def parse_executor(text: str | None) -> str | None:
    """``local`` (None) or a Dask scheduler address ``tcp://HOST:PORT`` (PLC5060)."""
    if text is None or text == "local":
        return None
    if not text.startswith(SCHEME) or ":" not in text[len(SCHEME):]:
        raise grade_error("PLC5060", f"--executor {text}: write local (the default) or "
                          "dask://HOST:PORT, the address of a Dask scheduler")
    host, _, port = text[len(SCHEME):].rpartition(":")
    if not host or not port.isdigit():
        raise grade_error("PLC5060", f"--executor {text}: write dask://HOST:PORT with a port "
                          "number, e.g. dask://10.0.0.5:8786")
    return f"tcp://{host}:{port}"


# ---------------------------------------------------------------------------- the worker side


def collect_child(job: dict[str, Any], timeout: float) -> dict[str, Any]:
    """Run one grading child here (as the local grader does) and return what it sent, raw:
    ``{"messages": [bytes], "exitcode", "timed_out", "rejected", "wall", "log"}``."""
    from .spawn import child_context, read_child_log, start_child
    from .worker import child_main

    ctx = child_context()
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=child_main, args=(job, child), daemon=True,
                       name="plclab-grade-task")
    try:
        with _may_have_children():
            start_child(proc)
    except BaseException:
        with contextlib.suppress(OSError):
            parent.close()
        child.close()
        raise
    child.close()
    start = time.monotonic()
    messages: list[bytes] = []
    size = 0
    rejected = ""
    final = eof = False
    timed_out = False
    try:
        while True:
            wait([parent, proc.sentinel] if not eof else [proc.sentinel], timeout=0.05)
            while not eof and not rejected and parent.poll():
                try:
                    raw = parent.recv_bytes(LIMITS["message"])
                except EOFError:
                    eof = True
                    break
                except OSError as e:
                    if "message length" in str(e):
                        rejected = "a message larger than the grader accepts"
                    eof = True
                    break
                size += len(raw)
                if size > 2 * LIMITS["media_total"]:
                    rejected = "more data than the grader accepts"
                    break
                messages.append(raw)
                final = final or raw.startswith(FINAL_KINDS)
            timed_out = time.monotonic() - start > timeout and not final
            if proc.exitcode is None and not final and not timed_out and not rejected:
                continue
            if (timed_out or rejected) and proc.exitcode is None:
                proc.kill()
            proc.join(timeout=5)
            if proc.exitcode is None:
                proc.kill()
                proc.join(timeout=5)
            while not eof and not rejected and parent.poll():
                try:
                    raw = parent.recv_bytes(LIMITS["message"])
                except (EOFError, OSError):
                    break
                messages.append(raw)
            break
    finally:
        if proc.exitcode is None:
            proc.kill()
            proc.join(timeout=5)
        with contextlib.suppress(OSError):
            parent.close()
    return {"messages": messages, "exitcode": proc.exitcode, "timed_out": timed_out,
            "rejected": rejected, "wall": time.monotonic() - start,
            "log": read_child_log(Path(job["workdir"]))}


@contextlib.contextmanager
def _may_have_children():
    """Let this process start a child even if it is daemonic (a Dask worker under a nanny
    is): the child dies with its parent anyway (:func:`plclab.grade.sandbox.die_with_parent`),
    which is all the daemon rule protects."""
    cur = multiprocessing.current_process()
    was = cur._config.get("daemon")  # noqa: SLF001 - the only place multiprocessing keeps it
    cur._config["daemon"] = False  # noqa: SLF001
    try:
        yield
    finally:
        cur._config["daemon"] = was  # noqa: SLF001


SWEEP_EVERY = 60.0
"""Seconds between two looks of a worker process for the folders of dead graders."""
_swept: list[float] = []


def sweep_stale_workdirs() -> None:
    """On a long-lived worker: remove the working folders that killed workers (``kill -9``,
    a lost machine's restart) left in this machine's temporary folder, at most once every
    SWEEP_EVERY seconds per process (ADR 0040)."""
    now = time.monotonic()
    if _swept and now - _swept[0] < SWEEP_EVERY:
        return
    _swept[:] = [now]
    from .spawn import remove_stale_workdirs

    remove_stale_workdirs()


def run_on_worker(payload: tuple[Any, dict[str, str]], job: dict[str, Any],
                  timeout: float) -> dict[str, Any]:
    """The Dask task: one submission graded in a sandboxed child on this worker."""
    sweep_stale_workdirs()
    lab, checks = payload
    workdir = Path(tempfile.mkdtemp(prefix=work_prefix()))
    try:
        full = {**job, "lab": lab, "checks": checks, "workdir": str(workdir),
                "grader_pid": os.getpid()}
        return collect_child(full, timeout)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


# ---------------------------------------------------------------------------- the client side


class _ExitCode:
    def __init__(self, code: int | None) -> None:
        self.exitcode = code


class Replayed:
    """A child that ran on a worker, as :meth:`Grader._finish` reads a local one: its
    messages checked by the client's own :class:`Inbox` in the order they were sent."""

    def __init__(self, sub: Any, media: Path, inbox: Inbox, got: dict[str, Any]) -> None:
        self.sub = sub
        self.media = media
        self.inbox = inbox
        self.rejected = str(got.get("rejected") or "")
        self.timed_out = bool(got.get("timed_out"))
        self.exitcode = got.get("exitcode")
        self.proc = _ExitCode(self.exitcode)
        self.start = time.monotonic() - float(got.get("wall") or 0.0)
        self._log = str(got.get("log") or "")
        for raw in got.get("messages") or []:
            if self.rejected:
                break
            try:
                inbox.receive(raw)
            except Rejected as e:
                self.rejected = str(e)

    def log_text(self) -> str:
        return self._log

    def close(self) -> None:
        """Nothing to close: the worker removed the child's folder."""


def lost(sub: Any, media: Path, inbox: Inbox, why: str) -> Replayed:
    """A task the cluster could not run (its worker died every time the scheduler tried, the
    future was lost): the machine's failure, as if the child had been killed from outside, so
    the grader tries again and finally reports "infrastructure", never the student's crash
    (ADR 0040)."""
    return Replayed(sub, media, inbox, {"exitcode": -signal.SIGKILL, "log": why,
                                        "messages": []})


def connect(address: str) -> Any:
    """A Dask client of the scheduler at ``address`` (PLC5061 when it cannot be reached or
    Dask is not installed)."""
    try:
        from distributed import Client
    except ImportError:
        raise grade_error("PLC5061", "--executor dask://...: Dask is not installed; pip "
                          "install 'plclab[cluster]' here and on every worker") from None
    try:
        return Client(address, timeout="20s", set_as_default=False)
    except (OSError, TimeoutError) as e:
        raise grade_error("PLC5061", f"cannot reach the Dask scheduler at {address} ({e}); "
                          "is `dask scheduler` running there and the port open?") from None


def run_on_cluster(grader: Any, address: str, todo: deque[Any], total: int,
                   done_n: int) -> list[Any]:
    """Grade ``todo`` on the cluster; each outcome is written and reported as its task
    completes (the order of completion, like the local pool)."""
    from distributed import as_completed

    client = connect(address)
    finished: list[Any] = []
    try:
        # the lab goes with every task, not scattered: data held by a worker dies with it
        payload = grader._lab_payload()  # noqa: SLF001
        futures: dict[Any, tuple[Any, Path, dict[str, Any]]] = {}

        def submit(sub: Any, d: Path, job: dict[str, Any]) -> Any:
            fut = client.submit(run_on_worker, payload, job, grader.timeout, pure=False,
                                key=f"plclab-grade-{grader.lab.id}-{sub.dirname}-"
                                f"{time.time_ns()}")
            futures[fut] = (sub, d, job)
            return fut

        for sub in todo:
            d = grader.prepare(sub)
            if not isinstance(d, Path):  # changed since discover: rejected now (an Outcome)
                finished.append(d)
                done_n += 1
                continue
            job = grader.job_of(sub)
            sub.sources = []
            submit(sub, d, job)
        pending = as_completed(list(futures), loop=client.loop)
        for fut in pending:
            sub, d, job = futures.pop(fut)
            inbox = Inbox(grader.lab, d if grader.media else None)
            try:
                r = Replayed(sub, d, inbox, fut.result())
            except Exception as e:  # noqa: BLE001 - a lost task: the cluster's failure
                r = lost(sub, d, inbox, f"the cluster could not run this submission: "
                         f"{type(e).__name__}: {e}")
            fut.release()
            if grader._grade_again(r, r.timed_out):  # noqa: SLF001
                for p in list(d.glob("*.png")) + list(d.glob("*.rrd")):
                    p.unlink()  # nothing of the lost try is kept
                pending.add(submit(sub, d, grader.job_of(sub) | {"sources": job["sources"]}))
                continue
            oc = grader._finish(r, r.timed_out)  # noqa: SLF001
            finished.append(oc)
            done_n += 1
            if grader.progress:
                grader.progress(done_n, total, sub.student, oc)
    finally:
        with contextlib.suppress(Exception):
            client.close()
    return finished

