"""plclab lab list/show/check/new, the Python API plclab.grade.check, the worker module."""

import json
import subprocess
import sys

import pytest

from plclab.cli import main
from plclab.grade import check
from plclab.grade.gradescope import validate_results
from plclab.grade.lab import load_lab

MOTOR = load_lab("motor-start-stop")


def visible_max(lab):
    return sum(c.points for s in lab.visible_scenarios for c in lab.criteria_for(s.name))


def test_lab_list(capsys):
    assert main(["lab", "list"]) == 0
    out = capsys.readouterr().out
    for lab in ("motor-start-stop", "tank-two-position", "relay-thermostat", "bottle-reject"):
        assert lab in out


def test_lab_show(capsys):
    assert main(["lab", "show", "tank-two-position"]) == 0
    out = capsys.readouterr().out
    assert load_lab("tank-two-position").io_table_markdown() in out
    assert "(hidden" in out


def test_lab_check_ends_with_the_score(capsys, tmp_path):
    sol = MOTOR.path / "solution" / "motor.st"
    assert main(["lab", "check", "motor-start-stop", str(sol), "--out", str(tmp_path / "fb")]) == 0
    out = capsys.readouterr().out
    n = visible_max(MOTOR)
    assert out.rstrip().splitlines()[-1] == f"score: {n:g}/{n:g}"
    assert "short-presses" not in out, "hidden scenarios are not run by students"


def test_lab_check_a_mistake_draws_and_exports(capsys, tmp_path):
    bad = MOTOR.path / "mistakes" / "no_seal_in.ld"
    png = tmp_path / "run.png"
    vcd = tmp_path / "run.vcd"
    args = ["lab", "check", "motor-start-stop", str(bad), "--out", str(tmp_path / "fb"),
            "--scenario", "start-stop", "--png", str(png), "--vcd", str(vcd)]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "FAIL" in out and "seal-in" in out
    assert out.rstrip().splitlines()[-1].startswith("score: ")
    assert png.is_file() and vcd.is_file()
    assert list((tmp_path / "fb").glob("start-stop--*.png"))
    assert (tmp_path / "fb" / "feedback.md").is_file()


def test_lab_check_refuses_hidden_scenarios(capsys):
    sol = MOTOR.path / "solution" / "motor.st"
    assert main(["lab", "check", "motor-start-stop", str(sol), "--scenario", "short-presses",
                 "--no-media"]) == 1
    assert "PLC5026" in capsys.readouterr().err


def test_unknown_lab(capsys):
    assert main(["lab", "show", "motor-start-stp"]) == 1
    err = capsys.readouterr().err
    assert "PLC5020" in err and "motor-start-stop" in err


def test_lab_new_is_a_working_example(tmp_path, capsys):
    assert main(["lab", "new", "my-first-lab", "--dir", str(tmp_path)]) == 0
    folder = tmp_path / "my-first-lab"
    lab = load_lab(folder, deep=True)
    res = check(folder, folder / "solution" / "solution.st", include_hidden=True)
    assert res.score == res.max_score == lab.max_score
    bad = check(folder, folder / "mistakes" / "follows_ls1.st", include_hidden=True)
    assert bad.score < bad.max_score and "chatter" in bad.feedback_markdown
    assert main(["lab", "new", "my-first-lab", "--dir", str(tmp_path)]) == 1
    assert main(["lab", "new", "Bad_Id", "--dir", str(tmp_path)]) == 1
    assert "PLC5027" in capsys.readouterr().err


def test_python_api_with_text():
    text = (MOTOR.path / "mistakes" / "stop_as_no.st").read_text(encoding="utf-8")
    res = check("motor-start-stop", text)
    assert res.max_score == visible_max(MOTOR) and res.score < res.max_score
    assert set(res.traces) == {s.name for s in MOTOR.visible_scenarios}
    assert "normally closed" in res._repr_markdown_()
    assert res.tests[0].name.startswith("start-stop: ")
    ld = (MOTOR.path / "solution" / "motor.ld").read_text(encoding="utf-8")
    assert check("motor-start-stop", ld).score == visible_max(MOTOR)  # guessed: LD
    assert check("motor-start-stop", ld, language="ld", include_hidden=True).score == \
        MOTOR.max_score


def test_language_not_allowed(tmp_path):
    lab = load_lab("motor-start-stop")
    lab.languages = ["ld"]
    from plclab.grade.engine import grade_sources

    res = grade_sources(lab, [("PROGRAM P END_PROGRAM", "p.st")])
    assert res.status == "language" and res.score == 0
    assert "PLC5022" in res.feedback_markdown


def test_worker_module_prints_gradescope_json(tmp_path):
    sol = MOTOR.path / "solution" / "motor.st"
    r = subprocess.run([sys.executable, "-m", "plclab.grade.worker", str(MOTOR.path), str(sol),
                        "--gradescope"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    assert validate_results(data) == []
    assert data["score"] == pytest.approx(MOTOR.max_score)
