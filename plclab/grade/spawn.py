"""Starting grading children: the forkserver context and the child's log (used by the local
grader, :mod:`plclab.grade.grader`, and by a cluster worker, :mod:`plclab.grade.cluster`)."""

from __future__ import annotations

import multiprocessing
import os
import stat
import tempfile
from pathlib import Path
from typing import Any

from .protocol import LIMITS


def work_prefix() -> str:
    """The prefix of a grading child's temporary folder (local or on a Dask worker): it names
    the grading process, so a later run can remove what one killed with SIGKILL left behind
    (:func:`plclab.grade.grader.remove_stale_workdirs`)."""
    return f"plclab-grade-{os.getpid()}-"


def child_context() -> Any:
    """The multiprocessing context of grading children: a forkserver that has preloaded
    what they need (:mod:`plclab.grade._preload`), started with the minimal environment;
    *spawn* where there is no fork."""
    methods = multiprocessing.get_all_start_methods()
    if "forkserver" in methods:
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(["__main__", "plclab.grade._preload"])
        _start_forkserver()
        return ctx
    return multiprocessing.get_context("spawn")


def _start_forkserver() -> None:
    """Start the forkserver (if it is not running) with the minimal environment, so neither
    it nor the children it forks ever hold the instructor's variables."""
    from multiprocessing import forkserver

    from .sandbox import environ_as, minimal_env

    tempfile.gettempdir()  # fixed now, from the grader's own TMPDIR
    with environ_as(minimal_env(None, "forkserver")):
        forkserver.ensure_running()


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
