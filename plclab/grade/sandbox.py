"""The grading child's confinement: environment, working folder, lifetime and CPU.

This is defence in depth, not a container: the child is a process of the same user. The
trust boundary is that student text never becomes Python (docs/adr/0001-grader-sandbox.md);
these measures limit what a mistake on that boundary, or a runaway submission, can reach:

* :func:`minimal_env` -- the only environment variables a child (and the forkserver that
  forks it) gets: no instructor tokens, ``HOME`` and ``TMPDIR`` in the child's empty
  temporary folder;
* :func:`die_with_parent` -- ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` on Linux, plus a watchdog
  thread that kills the process when the grader is gone (the fallback elsewhere);
* :func:`limit_cpu` -- ``RLIMIT_CPU``, so a child that escapes the wall-clock kill still
  stops.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import time
from collections.abc import Iterator, Mapping

MARKER = "PLCLAB_GRADE_CHILD"
"""Environment variable set in every grading process (the forkserver: ``forkserver``, a
child: ``child``), so tools and tests can find them in ``/proc``."""

_KEEP = ("PATH", "LANG", "LC_ALL", "LC_CTYPE", "LC_NUMERIC", "TZ", "PYTHONPATH", "PYTHONHOME",
         "PYTHONSAFEPATH", "PYTHONHASHSEED", "PYTHONUTF8", "PYTHONIOENCODING",
         "PYTHONDONTWRITEBYTECODE", "PYTHONNOUSERSITE", "SYSTEMROOT", "MPLBACKEND",
         "MPLCONFIGDIR")
"""Variables a grading process may inherit (Python and matplotlib need them); nothing else."""

KILL = getattr(signal, "SIGKILL", signal.SIGTERM)
"""The signal that ends a grading process (SIGTERM where there is no SIGKILL)."""
PR_SET_PDEATHSIG = 1
PR_SET_NAME = 15


def minimal_env(home: str | None, role: str, environ: Mapping[str, str] | None = None
                ) -> dict[str, str]:
    """The environment of a grading process: the variables of :data:`_KEEP` that are set,
    ``HOME``/``TMPDIR`` (``home``, when given) and :data:`MARKER` = ``role``."""
    src = os.environ if environ is None else environ
    env = {k: src[k] for k in _KEEP if k in src}
    env.setdefault("PATH", os.defpath)
    if home is not None:
        env["HOME"] = env["TMPDIR"] = home
    else:  # the forkserver: matplotlib finds its font cache under HOME
        env.update({k: src[k] for k in ("HOME", "TMPDIR") if k in src})
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env[var] = "1"  # one core a child: --jobs decides the parallelism, CPU time ~ wall
    env[MARKER] = role
    return env


@contextlib.contextmanager
def environ_as(env: Mapping[str, str]) -> Iterator[None]:
    """Run the body with exactly ``env`` as this process's environment (restored after).

    Used only around starting the forkserver, which inherits the environment; not
    thread-safe for other threads reading the environment meanwhile."""
    saved = dict(os.environ)
    os.environ.clear()
    os.environ.update(env)
    try:
        yield
    finally:
        os.environ.clear()
        os.environ.update(saved)


def replace_environ(env: Mapping[str, str]) -> None:
    """Make ``env`` this process's whole environment (for good)."""
    os.environ.clear()
    os.environ.update(env)


def _libc() -> object | None:
    if not sys.platform.startswith("linux"):
        return None
    try:
        import ctypes

        return ctypes.CDLL(None, use_errno=True)
    except (OSError, AttributeError):
        return None


def set_pdeathsig(sig: int = KILL) -> bool:
    """Ask Linux to send ``sig`` to this process when its parent ends (True when done)."""
    libc = _libc()
    if libc is None:
        return False
    try:
        return libc.prctl(PR_SET_PDEATHSIG, int(sig), 0, 0, 0) == 0  # type: ignore[attr-defined]
    except (AttributeError, OSError):
        return False


def set_process_name(name: str) -> None:
    """The short name ``ps`` and ``/proc/PID/comm`` show (Linux; at most 15 bytes)."""
    libc = _libc()
    if libc is None:
        return
    import ctypes

    with contextlib.suppress(AttributeError, OSError):
        libc.prctl(PR_SET_NAME, ctypes.c_char_p(name.encode()[:15]), 0, 0, 0)  # type: ignore


def alive(pid: int) -> bool:
    """Whether a process with this id exists."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def die_with_parent(grader_pid: int | None, interval: float = 0.5) -> bool:
    """End this process (SIGKILL) when its parent or the grader ends.

    ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` where Linux offers it; in every case a daemon thread
    also checks every ``interval`` s that the parent has not changed (re-parenting means it
    died) and that ``grader_pid`` still exists -- the forkserver's children have the
    forkserver as parent, the grader above it. Returns whether prctl was used."""
    ppid = os.getppid()
    used = set_pdeathsig(KILL)

    def gone() -> bool:
        return os.getppid() != ppid or (grader_pid is not None and not alive(grader_pid))

    if gone():  # the parent ended before prctl took effect
        os.kill(os.getpid(), KILL)

    def watch() -> None:
        while True:
            time.sleep(interval)
            if gone():
                os.kill(os.getpid(), KILL)

    threading.Thread(target=watch, name="plclab-parent-watchdog", daemon=True).start()
    return used


def limit_cpu(seconds: float) -> bool:
    """``RLIMIT_CPU``: SIGXCPU after ``seconds`` of CPU time, SIGKILL two seconds later."""
    try:
        import resource
    except ImportError:
        return False
    soft = max(1, int(seconds + 0.999))
    _, hard = resource.getrlimit(resource.RLIMIT_CPU)
    want_hard = soft + 2 if hard == resource.RLIM_INFINITY else min(hard, soft + 2)
    try:
        resource.setrlimit(resource.RLIMIT_CPU, (min(soft, want_hard), want_hard))
    except (ValueError, OSError):
        return False
    return True


def confine(workdir: str, grader_pid: int | None, cpu_seconds: float | None) -> None:
    """Everything a grading child does first: die with its parent, limit its CPU time, work
    in ``workdir`` (empty, private) with the minimal environment, and not import from the
    folder it was started in."""
    die_with_parent(grader_pid)
    set_process_name("plclab-grade")
    if cpu_seconds:
        limit_cpu(cpu_seconds)
    os.umask(0o077)
    os.chdir(workdir)
    replace_environ(minimal_env(workdir, "child"))
    import tempfile

    tempfile.tempdir = workdir
    sys.path[:] = [p for p in sys.path if p not in ("", ".")]
