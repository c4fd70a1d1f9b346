"""``plclab grade`` around the grader: results beside the submissions by default, a course
manifest of many labs, an LMS export zip, the summary (statuses, histogram) and the progress
bar's rate and ETA."""

from __future__ import annotations

import io
import shutil
import zipfile
from pathlib import Path

import pytest

from plclab.errors import PlcError
from plclab.grade.batch import (
    default_out,
    histogram,
    read_manifest,
    run_summary,
    unpack_zip,
)
from plclab.grade.engine import Result
from plclab.grade.engine import TestResult as OneTest
from plclab.grade.grader import Outcome
from plclab.grade.progress import ProgressBar

ROOT = Path(__file__).resolve().parents[2]
TANK = ROOT / "labs" / "tank-two-position"
MOTOR = ROOT / "labs" / "motor-start-stop"


def _outcome(score: float, status: str = "ok", skipped: bool = False) -> Outcome:
    test = OneTest("t", "sc", "c", score, 10.0, score == 10.0, "")
    return Outcome(Result("l", student="s", tests=[test], status=status), skipped=skipped)


def test_default_output_is_beside_the_submissions(tmp_path):
    assert default_out(tmp_path / "subs") == tmp_path / "subs-grades"
    assert default_out(tmp_path / "export.zip") == tmp_path / "export-grades"


def test_grade_writes_nothing_into_the_current_folder(tmp_path, monkeypatch, capsys):
    from plclab.cli import main

    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(TANK / "solution" / "tank.st", subs / "ann.st")
    here = tmp_path / "cwd"
    here.mkdir()
    monkeypatch.chdir(here)
    assert main(["grade", "tank-two-position", str(subs), "--jobs", "1", "--no-media"]) == 0
    assert list(here.iterdir()) == []
    assert (tmp_path / "subs-grades" / "ann" / "results.json").is_file()
    text = capsys.readouterr().out
    assert "status: 1 ok" in text and "scores (of 26):" in text


def test_a_manifest_grades_many_labs_in_one_run(tmp_path, capsys):
    from plclab.cli import main

    for lab, src in (("tank", TANK / "solution" / "tank.st"),
                     ("motor", next((MOTOR / "solution").glob("*.st")))):
        (tmp_path / "subs" / lab).mkdir(parents=True)
        shutil.copy(src, tmp_path / "subs" / lab / f"ann{src.suffix}")
    manifest = tmp_path / "course.toml"
    manifest.write_text('[labs]\ntank-two-position = "subs/tank"\n'
                        'motor-start-stop = "subs/motor"\n', encoding="utf-8")
    assert read_manifest(manifest) == [("tank-two-position", tmp_path / "subs" / "tank"),
                                       ("motor-start-stop", tmp_path / "subs" / "motor")]
    out = tmp_path / "all"
    assert main(["grade", "--manifest", str(manifest), "--out", str(out), "--jobs", "2",
                 "--no-media"]) == 0
    assert (out / "tank-two-position" / "ann" / "results.json").is_file()
    assert (out / "motor-start-stop" / "ann" / "results.json").is_file()
    assert capsys.readouterr().out.count("status: 1 ok") == 2


def test_a_bad_manifest_says_what_to_write(tmp_path):
    m = tmp_path / "course.toml"
    m.write_text("labs = 3\n", encoding="utf-8")
    with pytest.raises(PlcError) as e:
        read_manifest(m)
    assert e.value.code == "PLC5062" and "[labs]" in e.value.message


def test_an_lms_zip_is_graded_per_student_folder_or_file(tmp_path):
    z = tmp_path / "export.zip"
    text = (TANK / "solution" / "tank.st").read_bytes()
    with zipfile.ZipFile(z, "w") as zf:
        zf.writestr("assignment1/Ann Lee_123_assignsubmission_file_/tank.st", text)
        zf.writestr("assignment1/ben_456_main.st", text)
        zf.writestr("assignment1/ben_456_notes.pdf", b"%PDF")
        zf.writestr("__MACOSX/._x.st", b"junk")
    folder = unpack_zip(z, tmp_path / "u")
    assert folder.name == "assignment1"
    assert sorted(p.name for p in folder.iterdir()) == [
        "Ann Lee_123_assignsubmission_file_", "ben_456_main.st", "ben_456_notes.pdf"]
    # the report is an empty stand-in (its row says "not a program", PLC5071), not its bytes
    assert (folder / "ben_456_notes.pdf").stat().st_size == 0


def test_an_lms_zip_with_a_path_outside_is_refused(tmp_path):
    z = tmp_path / "evil.zip"
    with zipfile.ZipFile(z, "w") as zf:
        zf.writestr("../../outside.st", b"PROGRAM P END_PROGRAM")
    with pytest.raises(PlcError) as e:
        unpack_zip(z, tmp_path / "u")
    assert e.value.code == "PLC5063"
    assert not (tmp_path / "outside.st").exists()


def test_summary_counts_statuses_and_draws_a_histogram():
    outs = [_outcome(10), _outcome(10), _outcome(4, "timeout"), _outcome(0, "compile_error"),
            _outcome(10, skipped=True)]
    text = run_summary(outs)
    assert text.splitlines()[0] == "status: 2 ok, 1 compile_error, 1 timeout, 1 unchanged"
    rows = histogram([o.result.score for o in outs], 10)
    assert len(rows) == 10 and rows[-1].endswith(" 3") and rows[0].endswith(" 1")
    assert rows[4].endswith(" 1") and rows[4].count("#") == 10


def test_progress_bar_shows_rate_and_eta():
    bar = ProgressBar(io.StringIO())
    bar.t0 = 0.0
    bar.line(1, 10, "ann", _outcome(10), now=15.0)
    line = bar.line(2, 10, "ben", _outcome(10), now=30.0)
    assert "2/10" in line and "4/min" in line and "ETA  2:00" in line
    skipped = ProgressBar(io.StringIO())
    assert "ETA    --" in skipped.line(1, 10, "ann", _outcome(10, skipped=True), now=5.0)
