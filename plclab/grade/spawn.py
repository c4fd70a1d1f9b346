"""Starting grading children: the forkserver context and the child's log (used by the local
grader, :mod:`plclab.grade.grader`, and by a cluster worker, :mod:`plclab.grade.cluster`)."""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import shutil
import signal
import stat
import sys
import tempfile
from pathlib import Path
from typing import Any

from .errors import grade_error
from .protocol import INFRA_RETRIES, LIMITS

FORKSERVER_LOST = 255
"""The exit code multiprocessing gives a child whose forkserver died: the child's status went
with the server (and the child died with its parent, :func:`plclab.grade.sandbox.die_with_parent`).
Never a program's own exit: the child's code ends by a message, a signal or exit code 0/1."""


def work_prefix() -> str:
    """The prefix of a grading child's temporary folder (local or on a Dask worker): it names
    the grading process, so a later run can remove what one killed with SIGKILL left behind
    (:func:`remove_stale_workdirs`)."""
    return f"plclab-grade-{os.getpid()}-"


def child_context() -> Any:
    """The multiprocessing context of grading children: a forkserver that has preloaded
    what they need (:mod:`plclab.grade._preload`), started with the minimal environment;
    *spawn* where there is no fork."""
    methods = multiprocessing.get_all_start_methods()
    _own_multiprocessing_tempdir()
    if "forkserver" in methods:
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(["__main__", "plclab.grade._preload"])
        _guard_restarts()
        _start_forkserver()
        return ctx
    return multiprocessing.get_context("spawn")


def direct_context() -> Any:
    """The multiprocessing context of a single submission's child (``plclab lab check``, ADR
    0057): ``fork``, a direct child of the command, where the system has it; else None (use
    :func:`child_context`).

    A forkserver costs a fresh interpreter and its preloads (0.54 s of a 0.87 s ``lab check``)
    and pays off only over many children. The child is confined exactly as a forkserver's
    (:func:`plclab.grade.sandbox.confine`: minimal environment, own empty folder, CPU limit,
    death with its parent) and the grader applies the same wall-clock and memory limits; what
    it inherits besides is the memory of the command that forked it, which in ``lab check`` is
    the student's own process holding the student's own files. Standard streams are flushed
    first, so text printed before the start is not written twice."""
    import multiprocessing

    if "fork" not in multiprocessing.get_all_start_methods() or sys.platform == "darwin":
        return None  # macOS: fork is unsafe with its system libraries (Python's default: spawn)
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    return multiprocessing.get_context("fork")


_AF_UNIX_PATH_MAX = 100
"""The longest socket path this module lets multiprocessing bind (Linux allows 107 bytes)."""


def _own_multiprocessing_tempdir() -> None:
    """Give multiprocessing's temporary folder (the forkserver's socket lives there) a name
    with :func:`work_prefix`, instead of ``pymp-*``: its own clean-up runs only at a normal
    exit, so a grader killed with SIGKILL left a ``pymp-*`` folder nobody removed; now
    :func:`remove_stale_workdirs` removes it with the grader's other folders. Done once per
    process, before multiprocessing makes its own (``util.get_temp_dir`` reads the same key)."""
    from multiprocessing import process, util

    config = process.current_process()._config  # noqa: SLF001 - the key get_temp_dir reads
    if config.get("tempdir") is not None:
        return
    if len(os.path.join(tempfile.gettempdir(), work_prefix(), "mp-12345678/listener-12345678")) \
            > _AF_UNIX_PATH_MAX:
        return  # a socket path this long cannot be bound: multiprocessing's shorter name
    tempdir = tempfile.mkdtemp(prefix=work_prefix() + "mp-")
    util.Finalize(None, shutil.rmtree, args=(tempdir, True), exitpriority=-100)
    config["tempdir"] = tempdir


def start_child(proc: Any) -> None:
    """``proc.start()`` for a grading child, the forkserver (re)started first with the minimal
    environment: one killed from outside (the OOM killer, an administrator) is replaced, and
    a start that fails on a dying server is tried again, at most INFRA_RETRIES more times;
    then PLC5073. Never a traceback of multiprocessing's socket (ADR 0040)."""
    forked = getattr(proc, "_start_method", None) == "forkserver"  # the context's own name
    last: BaseException | None = None
    for _ in range(INFRA_RETRIES + 1):
        try:
            if forked:
                _start_forkserver()  # a dead server is replaced here, not by proc.start(),
                # which would start it with the instructor's environment
            proc.start()
            return
        except (OSError, EOFError, ValueError) as e:  # ValueError: "too many fds", closed
            last = e
            if forked:
                _end_broken_forkserver()
    raise grade_error("PLC5073", "cannot start a grading process "
                      f"({type(last).__name__}: {last}): is the machine out of memory or of "
                      "processes? Nothing was graded wrongly: the submissions graded so far "
                      "are kept; run the same command again, with fewer --jobs") from None


def _end_broken_forkserver() -> None:
    """The forkserver could not start a child: make sure it is dead (it may be dying of a
    SIGKILL right now, still seen alive by ``ensure_running``) and wait until it is, without
    reaping it, so that the next ``ensure_running`` reaps it and starts another."""
    from multiprocessing import forkserver

    pid = getattr(forkserver._forkserver, "_forkserver_pid", None)  # noqa: SLF001
    if pid is None or not hasattr(os, "waitid"):
        return
    with contextlib.suppress(OSError):
        os.kill(pid, signal.SIGKILL)
        os.waitid(os.P_PID, pid, os.WEXITED | os.WNOWAIT)


def _start_forkserver() -> None:
    """Start the forkserver if it is not running (with the minimal environment: see
    :func:`_guard_restarts`)."""
    from multiprocessing import forkserver

    if _forkserver_runs():
        return
    tempfile.gettempdir()  # fixed now, from the grader's own TMPDIR
    forkserver.ensure_running()


def _guard_restarts() -> None:
    """Make every (re)start of the forkserver use the minimal environment, so neither it nor
    the children it forks ever hold the instructor's variables: also the start that
    ``proc.start()`` makes when the server died between :func:`start_child`'s look and the
    start (a SIGKILL is delivered a moment after ``os.kill`` returns). The guard sits where
    the server's process is made, multiprocessing's ``util.spawnv_passfds`` (wrapped once per
    process), not around ``ensure_running``: that one decides to restart after any look of
    ours, so a guard there can always be raced (ADR 0040)."""
    from multiprocessing import util

    from .sandbox import environ_as, minimal_env

    original = util.spawnv_passfds
    if getattr(original, "_plclab_guarded", False):
        return

    def spawnv_passfds(path: Any, args: Any, passfds: Any) -> int:
        with environ_as(minimal_env(None, "forkserver")):
            return original(path, args, passfds)

    spawnv_passfds._plclab_guarded = True  # type: ignore[attr-defined]
    util.spawnv_passfds = spawnv_passfds


def _forkserver_runs() -> bool:
    """Whether this process's forkserver was started and has not ended (looked at without
    reaping it: ``ensure_running`` reaps it and starts another)."""
    from multiprocessing import forkserver

    pid = getattr(forkserver._forkserver, "_forkserver_pid", None)  # noqa: SLF001
    if pid is None or not hasattr(os, "waitid"):
        return False
    try:
        return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is None
    except ChildProcessError:
        return False


def remove_stale_workdirs(tmp: str | os.PathLike | None = None) -> int:
    """Remove the temporary folders of graders that no longer run (``kill -9`` leaves them);
    the number removed. A folder of a running grader (this one included) is kept."""
    removed = 0
    for d in Path(tmp or tempfile.gettempdir()).glob("plclab-grade-*-*"):
        pid = d.name.split("-")[2]
        if not pid.isdigit() or int(pid) == os.getpid() or not d.is_dir() or d.is_symlink():
            continue
        try:
            os.kill(int(pid), 0)
            continue  # its grader still runs
        except ProcessLookupError:
            pass
        except OSError:
            continue  # another user's process: not ours to judge
        shutil.rmtree(d, ignore_errors=True)
        removed += 1
    return removed


def read_child_log(workdir: Path) -> str:
    """The end of a child's stdout/stderr file in its working folder (read without following
    a link, at most LIMITS["log"] bytes; "" when there is none)."""
    from .worker import LOG_NAME

    text = ""
    try:
        fd = os.open(workdir / LOG_NAME, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0)
                     | getattr(os, "O_NONBLOCK", 0))
    except OSError:
        return ""
    try:
        st = os.fstat(fd)
        if stat.S_ISREG(st.st_mode) and st.st_size:
            os.lseek(fd, max(0, st.st_size - LIMITS["log"]), os.SEEK_SET)
            text = os.read(fd, LIMITS["log"]).decode("utf-8", "replace")
    finally:
        os.close(fd)
    return text
