"""A grading process killed from outside (the OOM killer, an administrator) is the machine's
failure, not the student's (issue 30, ADR 0040): the submission is graded again and the
gradebook equals a clean run's; killed every time it is "infrastructure", never cached, and the
next run grades it afresh. A crash is never reused either; a student's own outcome is."""

import csv
import os

import pytest

from plclab.grade.grader import Grader
from plclab.grade.lab import load_lab
from plclab.grade.protocol import INFRA_RETRIES

LAB = load_lab("motor-start-stop")
SCENARIOS = ["start-stop", "stop-wins"]


@pytest.fixture
def subs(tmp_path):
    folder = tmp_path / "subs"
    folder.mkdir()
    (folder / "alice.st").write_text((LAB.path / "solution" / "motor.st").read_text(),
                                     encoding="utf-8")
    (folder / "bob.st").write_text((LAB.path / "mistakes" / "set_dominant.st").read_text(),
                                   encoding="utf-8")
    return folder


def _grades(out):
    with open(out / "grades.csv", encoding="utf-8") as f:
        return {r["student"]: (r["score"], r["max"], r["status"]) for r in csv.DictReader(f)}


def _grade(folder, out, **kw):
    return Grader(LAB, out, jobs=2, timeout=60, scenarios=SCENARIOS, media=False,
                  **kw).grade_folder(folder)


def test_a_child_killed_from_outside_is_graded_again(subs, tmp_path, monkeypatch):
    _grade(subs, tmp_path / "clean")
    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_KILL", f"alice:{INFRA_RETRIES}")
    outcomes = _grade(subs, tmp_path / "killed")
    assert _grades(tmp_path / "killed") == _grades(tmp_path / "clean")
    alice = next(o.result for o in outcomes if o.result.student == "alice")
    assert alice.status == "ok" and alice.score == alice.max_score


def test_killed_every_time_is_infrastructure_and_never_reused(subs, tmp_path, monkeypatch):
    out = tmp_path / "out"
    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_KILL", f"alice:{INFRA_RETRIES + 1}")
    first = {o.result.student: o for o in _grade(subs, out)}
    assert first["alice"].result.status == "infrastructure"
    assert "PLC5070" in first["alice"].result.message
    assert first["bob"].result.status == "ok"
    monkeypatch.delenv("PLCLAB_GRADE_SELFTEST_KILL")
    again = {o.result.student: o for o in _grade(subs, out)}
    assert not again["alice"].skipped and again["alice"].result.status == "ok"
    assert again["alice"].result.score == again["alice"].result.max_score
    assert again["bob"].skipped  # the student's own outcome is kept


def test_every_entry_gets_a_gradebook_row(subs, tmp_path):
    """Hidden-looking names and stray documents are rows too (PLC5071: not a program); only
    what file managers leave (.DS_Store, __MACOSX) is skipped."""
    good = (LAB.path / "solution" / "motor.st").read_text()
    (subs / ".x.st").write_text(good, encoding="utf-8")
    (subs / "..st").write_text(good, encoding="utf-8")
    (subs / "report.pdf").write_bytes(b"%PDF-1.4\n")
    (subs / "essay.docx").write_bytes(b"PK\x03\x04")
    (subs / ".DS_Store").write_bytes(b"\0\0")
    out = tmp_path / "out"
    results = {o.result.student: o.result for o in _grade(subs, out)}
    assert set(results) == {"alice", "bob", ".x", ".", "report", "essay"}
    assert results[".x"].status == "ok" and results[".x"].score == results[".x"].max_score
    assert results["."].status == "ok"
    for who in ("report", "essay"):
        assert results[who].status == "rejected" and "PLC5071" in results[who].message
    assert set(_grades(out)) == set(results)


def test_a_killed_graders_temporary_folders_are_removed(tmp_path):
    import subprocess
    import sys

    from plclab.grade.grader import remove_stale_workdirs

    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f"plclab-grade-{dead.pid}-abc"
    live = tmp_path / f"plclab-grade-{os.getpid()}-def"
    other = tmp_path / "plclab-grade-notapid-x"
    for d in (stale, live, other):
        (d / "media").mkdir(parents=True)
    assert remove_stale_workdirs(tmp_path) == 1
    assert not stale.exists() and live.exists() and other.exists()


def test_a_killed_grader_leaves_no_multiprocessing_folder_behind():
    """multiprocessing's own temporary folder (the forkserver's socket) carries the grader's
    prefix: after kill -9 of the grader, the next run's sweep removes it, and no ``pymp-*``
    folder is left that nothing would ever remove."""
    import shutil
    import signal
    import subprocess
    import sys
    import tempfile
    from pathlib import Path

    from plclab.grade.grader import remove_stale_workdirs

    tmp_path = Path(tempfile.mkdtemp(prefix="mp", dir="/tmp"))  # short: a socket lives in it
    script = ("import os, signal\n"
              "from plclab.grade.spawn import child_context\n"
              "ctx = child_context()\n"
              "p = ctx.Process(target=int)\n"
              "p.start(); p.join()\n"
              "print(p.exitcode, flush=True)\n"
              "os.kill(os.getpid(), signal.SIGKILL)\n")
    try:
        env = {**os.environ, "TMPDIR": str(tmp_path)}
        done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                              text=True, timeout=300)
        assert done.returncode == -signal.SIGKILL and done.stdout.strip() == "0", done.stderr
        left = sorted(p.name for p in tmp_path.iterdir())
        assert left and not any(n.startswith("pymp-") for n in left), left
        assert all(n.startswith("plclab-grade-") for n in left), left
        assert remove_stale_workdirs(tmp_path) == len(left)
        assert not list(tmp_path.iterdir())
    finally:
        shutil.rmtree(tmp_path, ignore_errors=True)
