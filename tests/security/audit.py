"""Run ``plclab`` commands under a Python audit hook and judge what they did.

Every Python process of a run (the command, the multiprocessing forkserver, the grading
workers) loads ``sitecustomize.py`` from a folder put first on ``PYTHONPATH``; it installs a
``sys.addaudithook`` that appends one JSON line per interesting event to a log: files opened
(read or write), modules imported, processes started (``subprocess.Popen``, ``os.system``,
``os.exec*``, ``os.posix_spawn``, ``os.fork``...), files removed or renamed, sockets.

The same folder holds ``pwned_sentinel.py``: importing it creates a marker file. Payloads name
it everywhere they can; a run is clean when the marker is missing, no such import was
attempted, every read is inside the allow-list, every write inside the output folder, and no
process was started but plclab's own multiprocessing workers.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SENTINEL = "pwned_sentinel"

SITECUSTOMIZE = r'''
import json, os, sys
_LOG = os.environ.get("PLCLAB_AUDIT_LOG")
if _LOG:
    _fd = os.open(_LOG, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o600)
    _busy = []
    _WATCH = ("open", "import", "subprocess.Popen", "os.system", "os.exec", "os.posix_spawn",
              "os.spawn", "os.fork", "os.forkpty", "os.remove", "os.rename", "os.rmdir",
              "os.mkdir", "os.symlink", "os.link", "os.truncate", "shutil.", "socket.connect",
              "socket.bind", "ctypes.", "pty.spawn", "webbrowser.open", "urllib.Request")

    def _write(ev, args):
        line = json.dumps({"pid": os.getpid(), "ev": ev, "args": args}, default=repr) + "\n"
        os.write(_fd, line.encode("utf-8", "replace"))

    def _hook(ev, args):
        if _busy or not ev.startswith(_WATCH):
            return
        _busy.append(1)
        try:
            if ev == "import":
                args = [args[0]]
            elif ev == "open":
                p = args[0]
                if isinstance(p, int):
                    return
                if isinstance(p, bytes):
                    p = os.fsdecode(p)
                args = [os.path.abspath(str(p)), args[1], args[2]]
            _write(ev, [a if isinstance(a, (str, int, float, type(None))) else repr(a)
                        for a in args])
        finally:
            _busy.pop()

    _write("start", [list(getattr(sys, "orig_argv", sys.argv)), os.getcwd()])
    sys.addaudithook(_hook)
'''

SENTINEL_SOURCE = '''
import pathlib
pathlib.Path(__file__).with_name("PWNED").write_text("imported")
'''

WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_TRUNC | os.O_APPEND


@dataclass
class Run:
    returncode: int
    stdout: str
    stderr: str
    events: list[dict]
    cwd: Path
    created: list[Path] = field(default_factory=list)  # new files and folders in the sandbox

    @property
    def output(self) -> str:
        return self.stdout + self.stderr


class Sandbox:
    """A temporary world for one command: a hook folder, a home, a temp dir, a working dir, a
    secret file that nothing may read, and the audit log."""

    def __init__(self, tmp: Path) -> None:
        self.tmp = tmp
        self.hook = tmp / "hook"
        self.home = tmp / "home"
        self.tmpdir = tmp / "tmpdir"
        self.cwd = tmp / "work"
        self.secret = tmp / "secret" / "hidden.txt"
        for d in (self.hook, self.home, self.tmpdir, self.cwd, self.secret.parent):
            d.mkdir(parents=True, exist_ok=True)
        (self.hook / "sitecustomize.py").write_text(SITECUSTOMIZE)
        (self.hook / f"{SENTINEL}.py").write_text(SENTINEL_SOURCE)
        self.secret.write_text("TOKEN-do-not-leak\n")
        self.log = tmp / "audit.log"

    @property
    def marker(self) -> Path:
        return self.hook / "PWNED"

    def run(self, args: list[str], timeout: float = 240) -> Run:
        """``plclab ARGS`` in ``self.cwd`` under the audit hook."""
        self.log.write_text("")
        env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "PLCLAB"))}
        env.update(PYTHONPATH=os.pathsep.join([str(self.hook), str(ROOT)]),
                   PYTHONDONTWRITEBYTECODE="1", PLCLAB_AUDIT_LOG=str(self.log),
                   HOME=str(self.home), TMPDIR=str(self.tmpdir),
                   MPLCONFIGDIR=str(self.home / "mpl"), MPLBACKEND="Agg")
        code = "import sys, plclab.cli; sys.exit(plclab.cli.main(sys.argv[1:]))"
        before = self._snapshot()
        r = subprocess.run([sys.executable, "-c", code, *args], cwd=self.cwd, env=env,
                           capture_output=True, text=True, timeout=timeout)
        events = [json.loads(line) for line in self.log.read_text().splitlines() if line]
        created = sorted(self._snapshot() - before)
        return Run(r.returncode, r.stdout, r.stderr, events, self.cwd, created)

    def _snapshot(self) -> set[Path]:
        return {p for p in self.tmp.rglob("*") if p != self.log}


def _inside(path: str, roots: list[Path]) -> bool:
    p = os.path.realpath(path)
    return any(p == str(r) or p.startswith(str(r) + os.sep) for r in roots)


def _roots(paths) -> list[Path]:
    out = []
    for p in paths:
        out.append(Path(p))
        out.append(Path(os.path.realpath(p)))
    return out


SYSTEM_READ_ROOTS = _roots([sys.prefix, sys.base_prefix, sys.exec_prefix, "/dev", "/proc",
                            "/sys", "/usr/share", "/usr/lib", "/usr/local/lib", "/lib",
                            "/etc/localtime", "/etc/fonts", "/etc/ssl", "/etc/mime.types",
                            "/etc/os-release"])


def violations(run: Run, box: Sandbox, reads: list[Path], writes: list[Path]) -> list[str]:
    """Everything the run did that it should not have (empty when clean).

    ``reads``: what the command legitimately reads besides Python and plclab (the source files,
    the lab folder); ``writes``: where it may write (its output folder)."""
    bad: list[str] = []
    if box.marker.exists():
        bad.append(f"{SENTINEL} was imported (marker file {box.marker})")
    write_roots = _roots([box.tmpdir, box.home, *writes])
    bad += [f"created {p}" for p in run.created if not _inside(str(p), write_roots)]
    read_ok = SYSTEM_READ_ROOTS + _roots([ROOT / "plclab", ROOT / "plants", ROOT / "labs",
                                          ROOT / "course",  # plclab explain links chapters
                                          box.hook / "sitecustomize.py", box.tmpdir,
                                          box.home, *reads, *writes])
    write_ok = _roots([box.tmpdir, box.home, "/dev/null", *writes])
    for e in run.events:
        ev, args = e["ev"], e["args"]
        if ev == "import" and SENTINEL in str(args[0]):
            bad.append(f"import of {args[0]} attempted")
        elif ev == "open":
            path, mode, flags = args
            writing = (isinstance(flags, int) and flags & WRITE_FLAGS) or (
                isinstance(mode, str) and any(c in mode for c in "wax+"))
            if "hidden.txt" in path or SENTINEL in path and path.endswith(".py"):
                bad.append(f"opened {path}")
            elif writing and not _inside(path, write_ok):
                bad.append(f"wrote {path}")
            elif not writing and not _inside(path, read_ok):
                bad.append(f"read {path}")
        elif ev in ("os.remove", "os.rename", "os.rmdir", "os.mkdir", "os.symlink", "os.link",
                    "os.truncate") or ev.startswith("shutil."):
            if ev in ("os.remove", "os.rmdir") and args[-1] not in (-1, None):
                continue  # relative to a dir_fd: shutil.rmtree, judged by its own event
            for p in (_path_arg(a) for a in args if isinstance(a, str)):
                if not _inside(os.path.join(str(run.cwd), p), write_ok):
                    bad.append(f"{ev} {p}")
        elif ev in ("subprocess.Popen", "os.system", "os.posix_spawn", "os.spawn", "os.forkpty",
                    "pty.spawn") or ev.startswith("os.exec"):
            if not _multiprocessing_start(args) and args[1] not in MATPLOTLIB_FC_LIST:
                bad.append(f"started a process: {ev} {args}")
        elif ev == "os.fork" and not _is_forkserver(run, e["pid"]) and not _is_lab_check(
                run, e["pid"]):
            bad.append("os.fork in a process that is not plclab's multiprocessing forkserver "
                       "or a `plclab lab check` (its direct grading child, ADR 0057)")
        elif ev.startswith(("socket.", "ctypes.", "webbrowser", "urllib")):
            local = any(str(box.tmpdir) in str(a) for a in args)  # the forkserver's socket
            # the sandbox's own prctl (PR_SET_PDEATHSIG, PR_SET_NAME) in a forked grading
            # child: audited only since lab check forks it directly (a forkserver's children
            # run with the minimal environment, without this audit's log)
            local = local or (ev == "ctypes.dlsym" and args[1:] == ["prctl"]
                              and _is_forked_child(run, e["pid"]))
            if not local and args != [None]:  # ctypes.dlopen(None): a library's own symbols
                bad.append(f"{ev} {args}")
    for e in run.events:
        if e["ev"] == "start":
            argv = " ".join(e["args"][0])
            if "plclab.cli" not in argv and "multiprocessing" not in argv:
                bad.append(f"a process started: {argv}")
    return bad


# matplotlib runs fc-list (a fixed command line) once, when its font cache is new
MATPLOTLIB_FC_LIST = ("['fc-list', '--help']", "['fc-list', '--format=%{file}\\\\n']")


def _path_arg(a: str) -> str:
    """An event argument as a path (a logged ``PosixPath('/x')`` is ``/x``)."""
    m = re.fullmatch(r"""\w*Path\((['"])(.*)\1\)""", a)
    return m.group(2) if m else a


def _multiprocessing_start(args: list) -> bool:
    text = " ".join(str(a) for a in args)
    return sys.executable in text and "multiprocessing" in text


def _is_lab_check(run: Run, pid: int) -> bool:
    """The process ``pid`` is a ``plclab lab check`` command (it forks its grading child)."""
    return any(e["ev"] == "start" and e["pid"] == pid
               and " lab check " in " ".join(e["args"][0]) + " " for e in run.events)


def _is_forked_child(run: Run, pid: int) -> bool:
    """``pid`` logged events but never started an interpreter: a child forked by an audited
    process (the grading child of ``lab check``)."""
    return not any(e["ev"] == "start" and e["pid"] == pid for e in run.events)


def _is_forkserver(run: Run, pid: int) -> bool:
    return any(e["ev"] == "start" and e["pid"] == pid and "forkserver" in " ".join(e["args"][0])
               for e in run.events)
