"""The grader on a Dask cluster (issue 20): a loopback cluster, scheduler and two workers as
separate processes, started once for the module, grades mixed submissions exactly as the local
executor does; a worker killed mid-run loses nothing; a second run skips what is done."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")

pytestmark = pytest.mark.cluster

ROOT = Path(__file__).resolve().parents[2]
LAB = ROOT / "labs" / "tank-two-position"
LOOP = ("PROGRAM Spin\nVAR n : DINT; i : DINT; p AT %QX0.0 : BOOL; END_VAR\n"
        "FOR i := 1 TO 1000000 DO n := n + 1; END_FOR;\np := n > 0;\nEND_PROGRAM\n")
"""An endless program the watchdog does not stop: a million iterations (half the watchdog's
budget) in every scan, about a second each, for thousands of scans."""
TIMEOUT = 60.0


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(ROOT), "DASK_DISTRIBUTED__WORKER__DAEMON": "False"}


def _start_scheduler() -> tuple[str, subprocess.Popen]:
    """A Dask scheduler on a free loopback port: its address and its process."""
    port = _free_port()
    sched = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler",
                              "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                             env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             start_new_session=True)
    return f"tcp://127.0.0.1:{port}", sched


def _start_worker(address: str, *extra: str, tmp: Path | None = None) -> subprocess.Popen:
    """A worker process (its own session); ``tmp``: its temporary folder, where its grading
    children's folders and logs are."""
    env = _env() if tmp is None else {**_env(), "TMPDIR": str(tmp)}
    return subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address,
                             "--nthreads", "1", "--no-dashboard", *extra], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)


def _wait_workers(address: str, n: int, timeout: float = 60.0) -> None:
    with distributed.Client(address, timeout="30s", set_as_default=False) as c:
        c.wait_for_workers(n, timeout=timeout)


def _stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=5)


@pytest.fixture(scope="module")
def cluster():
    """``tcp://127.0.0.1:PORT`` of a scheduler with two worker processes (one per module)."""
    address, sched = _start_scheduler()
    workers = _start_worker(address, "--nworkers", "2")
    try:
        _wait_workers(address, 2)
        yield address
    finally:
        _stop(workers)
        _stop(sched)


@pytest.fixture(scope="module")
def lab():
    from plclab.grade.lab import load_lab

    return load_lab(str(LAB), deep=True)


def _mixed(folder: Path) -> Path:
    folder.mkdir()
    shutil.copy(LAB / "solution" / "tank.st", folder / "correct.st")
    shutil.copy(LAB / "solution" / "tank.il", folder / "correct_il.il")
    shutil.copy(LAB / "mistakes" / "never_stops.st", folder / "wrong.st")
    (folder / "syntax.st").write_text("PROGRAM P\nVAR x : INT END_VAR\nEND_PROGRAM\n",
                                      encoding="utf-8")
    shutil.copy(LAB / "solution" / "tank.st", folder / "crash.st")
    return folder


def _results(out: Path) -> dict[str, bytes]:
    """Every student's results.json with the timing field blanked (the only allowed
    difference), as bytes."""
    got = {}
    for f in sorted(out.glob("*/results.json")):
        text = f.read_text(encoding="utf-8")
        data = json.loads(text)
        assert "execution_time" in data
        blank = text.replace(json.dumps(data["execution_time"]), "0", 1)
        got[f.parent.name] = blank.encode()
    return got


def test_cluster_grades_like_the_local_executor(cluster, lab, tmp_path, monkeypatch):
    from plclab.grade.grader import Grader

    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_CRASH", "crash")
    subs = _mixed(tmp_path / "subs")
    # a generous limit: on a loaded machine a correct program must not hit it
    local = Grader(lab, tmp_path / "local", jobs=2, timeout=120).grade_folder(subs)
    remote = Grader(lab, tmp_path / "dask", timeout=120, executor=cluster).grade_folder(subs)
    status = {o.result.student: o.result.status for o in remote}
    assert status == {o.result.student: o.result.status for o in local}
    assert status == {"correct": "ok", "correct_il": "ok", "wrong": "ok",
                      "syntax": "compile_error", "crash": "crash"}
    assert {o.result.student: o.result.score for o in remote}["wrong"] < lab.max_score
    a, b = _results(tmp_path / "local"), _results(tmp_path / "dask")
    assert a.keys() == b.keys() == status.keys()
    for student in a:
        assert a[student] == b[student], student
    pics = sorted(p.name for p in (tmp_path / "dask" / "wrong").iterdir())
    assert pics == sorted(p.name for p in (tmp_path / "local" / "wrong").iterdir())
    assert any(p.endswith(".png") for p in pics)
    assert (tmp_path / "dask" / "grades.csv").read_bytes().count(b"\n") == 6


def test_an_endless_program_stops_at_the_limit_on_a_worker(cluster, lab, tmp_path):
    from plclab.grade.grader import Grader

    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "loop.st").write_text(LOOP, encoding="utf-8")
    # how far a stopped program got depends on the machine's speed: status and message only
    local = Grader(lab, tmp_path / "local", timeout=3.0).grade_folder(subs)[0].result
    remote = Grader(lab, tmp_path / "dask", timeout=3.0, executor=cluster).grade_folder(
        subs)[0].result
    assert local.status == remote.status == "timeout"
    assert "PLC5023" in remote.message and remote.message == local.message


def test_a_second_run_skips_what_is_done(cluster, lab, tmp_path):
    from plclab.grade.grader import Grader

    subs = tmp_path / "subs"
    subs.mkdir()
    for name in ("a", "b", "c"):
        shutil.copy(LAB / "solution" / "tank.st", subs / f"{name}.st")
    out = tmp_path / "out"
    first = Grader(lab, out, timeout=TIMEOUT, executor=cluster).grade_folder(subs)
    assert [o.skipped for o in first] == [False] * 3
    (subs / "b.st").write_text((LAB / "mistakes" / "follows_ls1.st").read_text())
    again = Grader(lab, out, timeout=TIMEOUT, executor=cluster).grade_folder(subs)
    assert {o.result.student: o.skipped for o in again} == {"a": True, "b": False,
                                                             "c": True}
    assert {o.result.student: o.result.score == lab.max_score for o in again} == {
        "a": True, "b": False, "c": True}


def test_a_worker_killed_mid_run_loses_no_submission(cluster, lab, tmp_path):
    from plclab.grade.grader import Grader

    tmp = tmp_path / "doomed"
    tmp.mkdir()
    doomed = _start_worker(cluster, "--no-nanny", "--name", "doomed", tmp=tmp)
    try:
        _wait_workers(cluster, 3)
        subs = tmp_path / "subs"
        subs.mkdir()
        for k in range(6):
            (subs / f"spin{k}.st").write_text(LOOP, encoding="utf-8")
        shutil.copy(LAB / "solution" / "tank.st", subs / "tank.st")
        outcomes: list = []
        run = threading.Thread(target=lambda: outcomes.extend(
            Grader(lab, tmp_path / "out", timeout=4.0, executor=cluster).grade_folder(subs)))
        run.start()
        deadline = time.monotonic() + 600  # a guard only: the event is a child's log
        while not list(tmp.glob("plclab-grade-*/child.log")):
            assert run.is_alive() and time.monotonic() < deadline, \
                "the third worker never started a grading child"
            time.sleep(0.05)
        os.killpg(doomed.pid, signal.SIGKILL)
        run.join(timeout=900)  # a guard only
        assert not run.is_alive()
    finally:
        _stop(doomed)
    status = {o.result.student: o.result.status for o in outcomes}
    assert sorted(status) == [*(f"spin{k}" for k in range(6)), "tank"]
    # a task lost with its worker would be a crash (or missing): each ran again elsewhere
    assert [status[f"spin{k}"] for k in range(6)] == ["timeout"] * 6
    assert status["tank"] in ("ok", "timeout")  # timeout only on a very loaded machine
    assert all((tmp_path / "out" / s / "results.json").is_file() for s in status)


def test_a_child_killed_on_a_worker_is_graded_again(cluster, lab, tmp_path, monkeypatch):
    """A child killed from outside on a worker (as the OOM killer does): the client submits
    the task again, and the gradebook equals a clean local run's (ADR 0040)."""
    import csv

    from plclab.grade.grader import Grader
    from plclab.grade.protocol import INFRA_RETRIES

    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(LAB / "solution" / "tank.st", subs / "alice.st")
    shutil.copy(LAB / "solution" / "tank.st", subs / "bob.st")
    Grader(lab, tmp_path / "clean", timeout=120, media=False).grade_folder(subs)
    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_KILL", f"alice:{INFRA_RETRIES}")
    outs = Grader(lab, tmp_path / "dask", timeout=120, media=False,
                  executor=cluster).grade_folder(subs)
    assert {o.result.student: o.result.status for o in outs} == {"alice": "ok", "bob": "ok"}

    def grades(out):
        with open(out / "grades.csv", encoding="utf-8") as f:
            return {r["student"]: (r["score"], r["status"]) for r in csv.DictReader(f)}
    assert grades(tmp_path / "dask") == grades(tmp_path / "clean")


def _held(tmp: Path, guard: threading.Thread, limit: float = 600.0) -> int:
    """The pid of a grading child held after compiling (``PLCLAB_GRADE_SELFTEST_HOLD``) by a
    worker whose temporary folder is ``tmp``, once its log says so (an event, not a delay;
    ``limit`` only guards a failure)."""
    from plclab.grade.worker import HOLDING

    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        assert guard.is_alive(), "the run ended before a child was held"
        for log in tmp.glob("plclab-grade-*/child.log"):
            with contextlib.suppress(OSError):
                for line in log.read_text(encoding="utf-8", errors="replace").splitlines():
                    if line.startswith(HOLDING):
                        return int(line.rsplit("pid ", 1)[1].rstrip(")"))
        time.sleep(0.05)
    raise AssertionError(f"no held child in {tmp} within {limit:g} s")


def test_a_worker_killed_mid_task_gives_the_clean_gradebook(lab, tmp_path, monkeypatch):
    """kill -9 of a worker while its grading child runs: the scheduler runs the task again on
    another worker (the lab travels with it); the child there is killed from outside too, so
    the client submits it once more; every row of the gradebook equals a clean local run's,
    and the next run removes the folder the killed worker left (ADR 0040). The victim's
    child holds after compiling until it is killed, so the kills land mid-task however loaded
    the machine is; a test-only cluster, so the victim runs on the worker we kill."""
    import csv

    from plclab.grade.grader import Grader, remove_stale_workdirs

    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(LAB / "solution" / "tank.st", subs / "alice.st")
    shutil.copy(LAB / "mistakes" / "never_stops.st", subs / "bob.st")
    shutil.copy(LAB / "solution" / "tank.il", subs / "carol.il")
    Grader(lab, tmp_path / "clean", jobs=2, timeout=300, media=False).grade_folder(subs)
    address, sched = _start_scheduler()
    tmp = {k: tmp_path / k for k in ("doomed", "healthy")}
    workers: dict[str, subprocess.Popen] = {}

    def worker(name: str) -> subprocess.Popen:
        tmp[name].mkdir(exist_ok=True)
        workers[name] = _start_worker(address, "--no-nanny", "--name", name, tmp=tmp[name])
        return workers[name]

    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_HOLD", "alice:1")
    outcomes: list = []
    try:
        doomed = worker("doomed")
        _wait_workers(address, 1)
        run = threading.Thread(target=lambda: outcomes.extend(
            Grader(lab, tmp_path / "dask", timeout=300, media=False,
                   executor=address).grade_folder(subs)))
        run.start()
        _held(tmp["doomed"], run)
        os.killpg(doomed.pid, signal.SIGKILL)  # kill -9 of the worker, mid-task
        doomed.wait(timeout=60)
        dead = subprocess.Popen([sys.executable, "-c", "pass"])
        dead.wait()
        tmp["healthy"].mkdir()
        stale = tmp["healthy"] / f"plclab-grade-{dead.pid}-left"  # a worker killed earlier
        (stale / "media").mkdir(parents=True)
        worker("healthy")
        os.kill(_held(tmp["healthy"], run), signal.SIGKILL)  # the same task, run again
        run.join(timeout=900)
        assert not run.is_alive()
    finally:
        for p in [*workers.values(), sched]:
            _stop(p)

    def rows(out):
        with open(out / "grades.csv", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    assert {o.result.student: o.result.status for o in outcomes} == dict.fromkeys(
        ("alice", "bob", "carol"), "ok")
    assert rows(tmp_path / "dask") == rows(tmp_path / "clean")
    left = sorted(p.name for p in tmp["doomed"].iterdir())
    assert any(n.startswith(f"plclab-grade-{doomed.pid}-") for n in left)  # it was mid-task
    assert not stale.exists()  # the healthy worker swept what a dead one left
    assert remove_stale_workdirs(tmp["doomed"]) >= 1
    assert not any(p.name.startswith(f"plclab-grade-{doomed.pid}-")
                   for p in tmp["doomed"].iterdir())
