"""The autograder on a folder of awkward submissions: each gets its score and a clear message,
in Gradescope's results.json shape, with a gradebook; re-runs skip, --force regrades."""

import csv
import json
import shutil
import time

import pytest

from plclab.cli import main
from plclab.grade.grader import SIDECAR, Grader
from plclab.grade.gradescope import SCHEMA, validate_results
from plclab.grade.lab import load_lab

LAB = "motor-start-stop"

HEAD = """PROGRAM Motor
VAR
    START    AT %IX0.0 : BOOL;
    STOP     AT %IX0.1 : BOOL;
    OVERLOAD AT %IX0.4 : BOOL;
    K1       AT %QX0.0 : BOOL;
"""
GOOD = "K1 := (START OR K1) AND STOP AND NOT OVERLOAD;\n"

SUBMISSIONS = {
    "bad.st": HEAD + "END_VAR\nK1 := START AND STOP AND NOT OVERLOAD;\nEND_PROGRAM\n",
    "broken.st": HEAD + "END_VAR\nK1 := (START OR K1) AND STOPP\nEND_PROGRAM\n",
    "loop.st": HEAD + "END_VAR\nWHILE TRUE DO END_WHILE;\n" + GOOD + "END_PROGRAM\n",
    "hog.st": HEAD + "".join(f"    big{i} : ARRAY[1..10000000] OF LREAL;\n" for i in range(30))
    + "END_VAR\n" + GOOD + "big1[1] := 1.0;\nEND_PROGRAM\n",
    "crash.st": HEAD + "    n : INT;\n    k : INT;\nEND_VAR\n" + GOOD
    + "n := n + 1;\nIF n > 300 THEN k := 10 / (n - n); END_IF;\nEND_PROGRAM\n",
    "slow.st": HEAD + "    i : DINT;\n    x : LREAL;\nEND_VAR\n" + GOOD
    + "FOR i := 1 TO 300000 DO x := x + 1.0; END_FOR;\nEND_PROGRAM\n",
    "team/motor.st": "PROGRAM Motor\nVAR\n    START AT %IX0.0 : BOOL;\n    STOP AT %IX0.1 : BOOL;"
    "\n    OVERLOAD AT %IX0.4 : BOOL;\n    K1 AT %QX0.0 : BOOL;\n    latch : SealIn;\nEND_VAR\n"
    "latch(SET := START, RESET := NOT STOP OR OVERLOAD);\nK1 := latch.Q;\nEND_PROGRAM\n",
    "team/sealin.st": "FUNCTION_BLOCK SealIn\nVAR_INPUT SET : BOOL; RESET : BOOL; END_VAR\n"
    "VAR_OUTPUT Q : BOOL; END_VAR\nQ := (SET OR Q) AND NOT RESET;\nEND_FUNCTION_BLOCK\n",
    "team/notes.txt": "not a source file",
    "README.txt": "not a submission, but a row of the gradebook (PLC5071)",
}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    root = tmp_path_factory.mktemp("grading")
    subs = root / "subs"
    lab = load_lab(LAB)
    (subs / "team").mkdir(parents=True)
    shutil.copy(lab.path / "solution" / "motor.ld", subs / "good.ld")
    shutil.copy(lab.path / "solution" / "motor.st", subs / "segv.st")
    for name, text in SUBMISSIONS.items():
        (subs / name).write_text(text, encoding="utf-8")
    out = root / "out"
    mp = pytest.MonkeyPatch()
    mp.setenv("PLCLAB_GRADE_SELFTEST_CRASH", "segv")
    t0 = time.monotonic()
    try:
        outcomes = Grader(lab, out, jobs=2, timeout=8.0, memory_mb=600).grade_folder(subs)
    finally:
        mp.undo()
    return lab, subs, out, {o.result.student: o for o in outcomes}, time.monotonic() - t0


def feedback(out, student):
    return (out / student / "feedback.md").read_text(encoding="utf-8")


def test_every_student_is_graded(graded):
    lab, _, out, res, _ = graded
    assert set(res) == {"good", "segv", "bad", "broken", "loop", "hog", "crash", "slow",
                        "team", "README"}
    readme = res["README"].result
    assert readme.status == "rejected" and "PLC5071" in readme.message
    for student in res:
        for f in ("results.json", "feedback.md", SIDECAR):
            assert (out / student / f).is_file(), (student, f)
    assert not list(out.rglob(".*.tmp*")), "no temporary files left behind"


def test_results_json_has_the_gradescope_shape(graded):
    _, _, out, res, _ = graded
    try:
        import jsonschema
    except ImportError:
        jsonschema = None
    for student, oc in res.items():
        data = json.loads((out / student / "results.json").read_text(encoding="utf-8"))
        assert validate_results(data) == [], student
        if jsonschema is not None:
            jsonschema.validate(data, SCHEMA)
        assert data["score"] == pytest.approx(oc.result.score)
        assert {t["status"] for t in data["tests"]} <= {"passed", "failed"}
        hidden = [t for t in data["tests"] if t["visibility"] == "after_published"]
        assert hidden and all(t["output"].startswith(("passed", "failed")) for t in hidden)


def test_scores_and_messages(graded):
    lab, _, out, res, _ = graded
    full = lab.max_score
    assert res["good"].result.score == full and res["good"].result.status == "ok"
    assert res["team"].result.score == full, feedback(out, "team")
    assert 0 < res["bad"].result.score < full and "seal-in" in feedback(out, "bad")
    broken = res["broken"].result
    assert broken.status == "compile_error" and broken.score == 0
    assert "broken.st:9:1: error PLC0010" in feedback(out, "broken")
    assert res["loop"].result.score == 0 and "PLC2003" in feedback(out, "loop")
    # 2.4 GB of arrays: rejected at compile time (PLC0124), before any memory is taken
    assert res["hog"].result.status == "compile_error" and "PLC0124" in feedback(out, "hog")
    crash = res["crash"].result
    assert "PLC2001" in feedback(out, "crash") and crash.score < full
    slow = res["slow"].result
    assert slow.status == "timeout" and "time limit" in feedback(out, "slow")
    segv = res["segv"].result
    assert segv.status == "crash" and "SIGSEGV" in feedback(out, "segv")
    assert segv.score == full, "scenarios finished before the crash keep their points"


def test_failed_criteria_get_timing_diagrams(graded):
    _, _, out, res, _ = graded
    pngs = list((out / "bad").glob("*.png"))
    assert pngs, "a diagram of the failed seal-in"
    assert pngs[0].name in feedback(out, "bad")
    assert not list((out / "good").glob("*.png")), "nothing drawn when nothing failed"
    text = feedback(out, "bad")
    assert ".rrd" in text or "rerun is not installed" in text


def test_gradebook(graded):
    lab, _, out, res, _ = graded
    rows = list(csv.DictReader((out / "grades.csv").open(encoding="utf-8")))
    assert sorted(r["student"] for r in rows) == sorted(res)
    names = [f"{s.name}: {c.name}" for s in lab.scenarios for c in lab.criteria_for(s.name)]
    assert list(rows[0])[:4] == ["student", "score", "max", "status"]
    assert list(rows[0])[4:] == names
    good = next(r for r in rows if r["student"] == "good")
    assert float(good["score"]) == lab.max_score == float(good["max"])


def test_rerun_skips_unchanged_submissions(graded):
    lab, subs, out, _, _ = graded
    again = Grader(lab, out, jobs=2, timeout=8.0, memory_mb=600).grade_folder(subs)
    # the student's own outcomes are reused; a crash (plclab's) and a rejected entry are not
    kept = {o.result.student for o in again if o.skipped}
    assert kept == {o.result.student for o in again} - {"segv", "README"}


def test_force_regrades_and_changes_are_regraded(tmp_path, capsys):
    lab = load_lab(LAB)
    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(lab.path / "solution" / "motor.st", subs / "ann.st")
    (subs / "ben.st").write_text(SUBMISSIONS["bad.st"], encoding="utf-8")
    out = tmp_path / "out"
    args = ["grade", LAB, str(subs), "--out", str(out), "--jobs", "2", "--no-media"]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "ann" in text and "2 graded" in text
    assert main(args) == 0
    assert "0 graded, 2 unchanged" in capsys.readouterr().out
    (subs / "ben.st").write_text(HEAD + "END_VAR\n" + GOOD + "END_PROGRAM\n", encoding="utf-8")
    assert main(args) == 0
    assert "1 graded, 1 unchanged" in capsys.readouterr().out
    assert main(args + ["--force"]) == 0
    assert "2 graded, 0 unchanged" in capsys.readouterr().out
    rows = list(csv.DictReader((out / "grades.csv").open(encoding="utf-8")))
    assert all(float(r["score"]) == lab.max_score for r in rows)
