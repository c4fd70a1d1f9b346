"""Grading integrity with real kills from outside (issue 30, ADR 0040): a grading child and the
forkserver are killed with ``os.kill`` from the grader's own process, as the OOM killer does,
and the gradebook equals a clean run's row for row; killed every time, the row says
"infrastructure" and ``plclab grade`` asks to run the same command again.

No timing: a victim is held after compiling (``PLCLAB_GRADE_SELFTEST_HOLD``) until it is killed,
so the kill lands mid-run however loaded the machine is; the kill is triggered by the
victim's "compiled" message, an event. Time limits are generous and only guard a failure."""

from __future__ import annotations

import csv
import os
import signal
from pathlib import Path

import pytest

from plclab.grade import grader as grader_mod
from plclab.grade.grader import Grader
from plclab.grade.lab import load_lab
from plclab.grade.protocol import INFRA_RETRIES

LAB = load_lab("motor-start-stop")
GOOD = (LAB.path / "solution" / "motor.st").read_text(encoding="utf-8")
WRONG = (LAB.path / "mistakes" / "set_dominant.st").read_text(encoding="utf-8")
LIMIT = 300.0  # only a guard: a held child nobody kills ends here, and the test fails

pytestmark = pytest.mark.slow


def _rows(out: Path) -> list[dict[str, str]]:
    """Every row of the gradebook, every test's points included."""
    with open(out / "grades.csv", encoding="utf-8") as f:
        return list(csv.DictReader(f))


@pytest.fixture
def subs(tmp_path):
    folder = tmp_path / "subs"
    folder.mkdir()
    (folder / "alice.st").write_text(GOOD, encoding="utf-8")
    (folder / "bob.st").write_text(WRONG, encoding="utf-8")
    (folder / "carol.st").write_text(GOOD, encoding="utf-8")
    return folder


@pytest.fixture
def clean(subs, tmp_path):
    """The gradebook of a run nobody disturbs."""
    Grader(LAB, tmp_path / "clean", jobs=2, timeout=LIMIT, media=False).grade_folder(subs)
    rows = _rows(tmp_path / "clean")
    assert {r["status"] for r in rows} == {"ok"}
    assert len({r["score"] for r in rows}) == 2  # bob's mistake costs points: rows differ
    return rows


def _on_compiled(monkeypatch, act) -> dict[str, int]:
    """Call ``act(running)`` in the grader's process when a child it started reports that it
    compiled the program (an event); returns student -> children started."""
    started: dict[str, int] = {}
    real_start = Grader._start

    def start(self, ctx, sub):
        r = real_start(self, ctx, sub)
        if not isinstance(r, grader_mod._Running):
            return r
        started[sub.student] = started.get(sub.student, 0) + 1
        receive = r.inbox.receive

        def receive_then_act(raw: bytes) -> None:
            receive(raw)
            if raw.startswith(b'["compiled"'):
                act(r)

        r.inbox.receive = receive_then_act
        return r

    monkeypatch.setattr(Grader, "_start", start)
    return started


def _hold(monkeypatch, student: str, n: int) -> None:
    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_HOLD", f"{student}:{n}")


# ---------------------------------------------------------------------------- killed children


def test_children_killed_from_outside_give_the_clean_gradebook(subs, clean, tmp_path,
                                                               monkeypatch, capfd):
    killed: list[str] = []

    def act(r):
        if r.sub.student == "alice" and len(killed) < INFRA_RETRIES:
            killed.append(r.sub.student)
            os.kill(r.proc.pid, signal.SIGKILL)

    _hold(monkeypatch, "alice", INFRA_RETRIES)  # both victims wait for their kill
    started = _on_compiled(monkeypatch, act)
    outs = Grader(LAB, tmp_path / "killed", jobs=2, timeout=LIMIT,
                  media=False).grade_folder(subs)
    assert killed == ["alice"] * INFRA_RETRIES
    assert started == {"alice": INFRA_RETRIES + 1, "bob": 1, "carol": 1}  # graded again
    assert _rows(tmp_path / "killed") == clean
    assert {o.result.student: o.result.status for o in outs} == dict.fromkeys(
        ("alice", "bob", "carol"), "ok")
    assert "Traceback" not in capfd.readouterr().err


def test_killed_every_time_is_infrastructure_and_the_next_run_grades_it(subs, clean, tmp_path,
                                                                        monkeypatch):
    out = tmp_path / "out"
    _hold(monkeypatch, "bob", INFRA_RETRIES + 1)
    started = _on_compiled(monkeypatch, lambda r: r.sub.student == "bob" and os.kill(
        r.proc.pid, signal.SIGKILL))
    first = {o.result.student: o.result for o in
             Grader(LAB, out, jobs=2, timeout=LIMIT, media=False).grade_folder(subs)}
    assert started["bob"] == INFRA_RETRIES + 1
    assert first["bob"].status == "infrastructure" and "PLC5070" in first["bob"].message
    assert "killed by SIGKILL" in first["bob"].message
    monkeypatch.undo()
    again = {o.result.student: o for o in
             Grader(LAB, out, jobs=2, timeout=LIMIT, media=False).grade_folder(subs)}
    assert not again["bob"].skipped and again["alice"].skipped and again["carol"].skipped
    assert _rows(out) == clean


def test_a_killed_forkserver_is_started_again_and_its_children_graded_again(
        subs, clean, tmp_path, monkeypatch, capfd):
    """The OOM killer may pick the forkserver: its children die with it (their status is
    lost: exit code 255) and the next start finds no server. The grader starts a new one
    (with the minimal environment) and grades them again: no traceback, no crash."""
    from multiprocessing import forkserver

    from plclab.grade.spawn import child_context

    child_context()
    killed: list[int] = []

    def act(r):
        if r.sub.student == "alice" and not killed:
            killed.append(forkserver._forkserver._forkserver_pid)
            os.kill(killed[0], signal.SIGKILL)

    _hold(monkeypatch, "alice", 1)  # alice's first child waits; the server is killed under it
    monkeypatch.setenv("PLCLAB_GRADE_SECRET_OF_THE_INSTRUCTOR", "x")
    started = _on_compiled(monkeypatch, act)
    outs = Grader(LAB, tmp_path / "killed", jobs=2, timeout=LIMIT,
                  media=False).grade_folder(subs)
    new = forkserver._forkserver._forkserver_pid
    assert killed and new != killed[0]  # a new server
    assert started["alice"] == 2
    assert _rows(tmp_path / "killed") == clean
    assert all(o.result.status == "ok" for o in outs)
    with open(f"/proc/{new}/environ", "rb") as f:
        assert b"PLCLAB_GRADE_SECRET_OF_THE_INSTRUCTOR" not in f.read()
    assert "Traceback" not in capfd.readouterr().err


def test_every_restart_of_the_forkserver_has_the_minimal_environment(monkeypatch):
    """Whoever restarts a dead forkserver (plclab's own start, ``proc.start()``, or
    multiprocessing's ``ensure_running`` called directly, as when the server dies between a
    look and a start) starts it without the instructor's variables: the guard is where the
    process is made, so no order of events gets round it. CI once saw the race."""
    import time
    from multiprocessing import forkserver

    from plclab.grade import spawn

    spawn.child_context()
    monkeypatch.setenv("PLCLAB_GRADE_SECRET_OF_THE_INSTRUCTOR", "x")
    # any look of plclab's sees the server alive, as it was a moment before it died
    monkeypatch.setattr(spawn, "_forkserver_runs", lambda: True)
    for _ in range(2):
        old = forkserver._forkserver._forkserver_pid
        os.kill(old, signal.SIGKILL)
        os.waitid(os.P_PID, old, os.WEXITED | os.WNOWAIT)  # dead, not reaped
        forkserver._forkserver.ensure_running()  # multiprocessing's own restart
        new = forkserver._forkserver._forkserver_pid
        assert new != old
        deadline = time.monotonic() + 30
        with open(f"/proc/{new}/environ", "rb") as f:
            env = f.read()
        while not env and time.monotonic() < deadline:  # read before its exec ended
            time.sleep(0.05)
            with open(f"/proc/{new}/environ", "rb") as f:
                env = f.read()
        assert b"PATH=" in env
        assert b"PLCLAB_GRADE_SECRET_OF_THE_INSTRUCTOR" not in env
    assert os.environ["PLCLAB_GRADE_SECRET_OF_THE_INSTRUCTOR"] == "x"  # ours is untouched


def test_a_forkserver_that_cannot_be_started_is_plc5073(monkeypatch, tmp_path, subs):
    """When no grading process can be started at all (here every start fails as on a machine
    out of processes), the run stops with PLC5073 after a few tries, not a traceback."""
    from multiprocessing.process import BaseProcess

    from plclab.errors import PlcError

    tries: list[int] = []

    def refuse(self):
        tries.append(1)
        raise BlockingIOError(11, "Resource temporarily unavailable")

    monkeypatch.setattr(BaseProcess, "start", refuse)
    with pytest.raises(PlcError) as e:
        Grader(LAB, tmp_path / "out", jobs=1, timeout=LIMIT, media=False).grade_folder(subs)
    assert e.value.code == "PLC5073" and "run the same command again" in e.value.message
    assert len(tries) == INFRA_RETRIES + 1
    assert not list((tmp_path / "out").glob("*/results.json"))  # nothing graded wrongly


def test_a_crash_inside_the_child_is_not_retried(subs, tmp_path, monkeypatch):
    """The other side of the line: a child that fails by itself (a real SIGSEGV) is graded
    once and reported as a crash, not as the machine's failure."""
    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_CRASH", "carol")
    started = _on_compiled(monkeypatch, lambda r: None)
    outs = {o.result.student: o.result for o in
            Grader(LAB, tmp_path / "out", jobs=2, timeout=LIMIT, media=False).grade_folder(subs)}
    assert started["carol"] == 1
    assert outs["carol"].status == "crash" and "PLC5070" not in outs["carol"].message


def test_the_command_names_the_lost_submissions_and_asks_to_run_again(subs, tmp_path,
                                                                      monkeypatch, capsys):
    from plclab.cli import main

    monkeypatch.setenv("PLCLAB_GRADE_SELFTEST_KILL", f"bob:{INFRA_RETRIES + 1}")
    argv = ["grade", LAB.id, str(subs), "--out", str(tmp_path / "out"), "--jobs", "2",
            "--no-media", "-q"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    last = text.strip().splitlines()[-1]
    assert "bob" in last and "PLC5070" in last and "run the same command again" in last.lower()
    assert "alice" not in last and "carol" not in last
    monkeypatch.delenv("PLCLAB_GRADE_SELFTEST_KILL")
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "PLC5070" not in text and "1 graded, 2 unchanged" in text


# ---------------------------------------------------------------------------- an LMS zip


def test_every_entry_of_an_lms_zip_gets_a_row(tmp_path):
    """As in a folder: a report handed in instead of a program, or a student folder holding
    only a picture, gets its row (an empty stand-in is unpacked, never the file's bytes); what
    archivers and file managers leave does not; a report beside the wrapper folder is kept."""
    import zipfile

    from plclab.grade.batch import Unpacked

    z = tmp_path / "export.zip"
    with zipfile.ZipFile(z, "w") as zf:
        zf.writestr("course/alice_1_2_motor.st", GOOD)
        zf.writestr("course/bob_3_4_report.pdf", b"%PDF-1.4 secret text never unpacked")
        zf.writestr("course/carol_5_6_assignsubmission_file_/photo.jpg", b"\xff\xd8\xff")
        zf.writestr("course/dave_7_8_assignsubmission_file_/motor.st", WRONG)
        zf.writestr("course/dave_7_8_assignsubmission_file_/notes.txt", b"mine")
        zf.writestr("course/.DS_Store", b"\x00")
        zf.writestr("__MACOSX/course/._alice_1_2_motor.st", b"\x00")
        zf.writestr("readme.docx", b"PK\x03\x04")
    with Unpacked(z) as folder:
        assert folder.name == "course"
        report = folder / "bob_3_4_report.pdf"
        assert report.is_file() and report.stat().st_size == 0  # a stand-in, not the file
        outs = Grader(LAB, tmp_path / "out", jobs=2, timeout=LIMIT, media=False,
                      scenarios=[LAB.scenarios[0].name]).grade_folder(folder)
    rows = {r["student"]: r["status"] for r in _rows(tmp_path / "out")}
    assert rows == {"alice_1_2_motor": "ok", "bob_3_4_report": "rejected",
                    "carol_5_6_assignsubmission_file_": "no_source",
                    "dave_7_8_assignsubmission_file_": "ok", "readme": "rejected"}
    msg = {o.result.student: o.result.message for o in outs}
    assert "PLC5071" in msg["bob_3_4_report"] and "bob_3_4_report.pdf" in msg["bob_3_4_report"]


# ---------------------------------------------------------------------------- the student copy


@pytest.fixture
def student_labs(tmp_path):
    """A labs folder as a pip install carries it: the student copy of motor-start-stop, made
    as the build makes it."""
    from plclab.grade.courseware import copy_student_lab

    labs = tmp_path / "pip-labs"
    copy_student_lab(LAB.path, labs / LAB.id)
    return labs


def test_the_student_copy_counts_the_hidden_scenarios_it_lacks(student_labs):
    hidden = [s.name for s in LAB.scenarios if not s.visible]
    assert hidden and LAB.withheld is None and not LAB.student_copy  # the instructor's lab
    copy = load_lab(student_labs / LAB.id)
    assert copy.student_copy and copy.withheld == len(hidden)
    assert not {s.name for s in copy.scenarios} & set(hidden)
    assert copy.max_score < LAB.max_score


@pytest.mark.parametrize("value", ["-1", "true", '"2"', "1.5"])
def test_a_wrong_count_of_withheld_scenarios_is_a_lab_error(student_labs, value):
    from plclab.errors import PlcError

    toml = student_labs / LAB.id / "lab.toml"
    text = toml.read_text(encoding="utf-8")
    n = len([s for s in LAB.scenarios if not s.visible])
    assert f"hidden_scenarios_withheld = {n}\n" in text
    toml.write_text(text.replace(f"hidden_scenarios_withheld = {n}\n",
                                 f"hidden_scenarios_withheld = {value}\n"), encoding="utf-8")
    with pytest.raises(PlcError) as e:
        load_lab(student_labs / LAB.id)
    assert e.value.code == "PLC5004" and "hidden_scenarios_withheld" in e.value.message


def test_lab_check_hidden_on_the_student_copy_says_it_runs_without_them(student_labs,
                                                                        tmp_path, capsys):
    from plclab.cli import main

    prog = tmp_path / "motor.st"
    prog.write_text(GOOD, encoding="utf-8")
    n = len([s for s in LAB.scenarios if not s.visible])
    assert main(["lab", "check", LAB.id, str(prog), "--hidden", "--no-media",
                 "--labs", str(student_labs)]) == 0
    out = capsys.readouterr().out
    assert f"its {n} hidden scenario" in out and "visible ones only" in out
    copy = load_lab(student_labs / LAB.id)
    assert out.strip().splitlines()[-1] == f"score: {copy.max_score:g}/{copy.max_score:g}"
    for argv in (["--labs", str(student_labs)], ["--hidden"]):  # without --hidden, or the
        assert main(["lab", "check", LAB.id, str(prog), "--no-media", *argv]) == 0  # full lab
        assert "hidden scenario" not in capsys.readouterr().out


def test_grading_with_the_student_copy_names_what_it_lacks(student_labs, subs, tmp_path,
                                                           capsys):
    from plclab.cli import main

    n = len([s for s in LAB.scenarios if not s.visible])
    argv = ["grade", LAB.id, str(subs), "--labs", str(student_labs), "--out",
            str(tmp_path / "out"), "--jobs", "2", "--no-media", "-q"]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert "PLC5072" in err and f"its {n} hidden scenario" in err
    assert not (tmp_path / "out" / "grades.csv").exists()
    assert main([*argv, "--visible-only"]) == 0
    out = capsys.readouterr().out
    assert "visible scenarios only" in out and f"its {n} hidden scenario" in out
