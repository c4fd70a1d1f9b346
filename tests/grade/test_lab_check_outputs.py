"""`plclab lab check` writes only where it is asked (--out), and each run replaces its folder
(issue 15)."""

from __future__ import annotations

import os

from plclab.cli import main
from plclab.grade.lab import load_lab

MOTOR = load_lab("motor-start-stop")
SOLUTION = MOTOR.path / "solution" / "motor.st"
NO_SEAL_IN = MOTOR.path / "mistakes" / "no_seal_in.ld"


def test_without_out_nothing_is_written(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["lab", "check", "motor-start-stop", str(NO_SEAL_IN)]) == 0
    out = capsys.readouterr().out
    assert "FAIL" in out and "--out DIR" in out
    assert os.listdir(tmp_path) == []


def test_each_run_replaces_its_folder(tmp_path, capsys):
    fb = tmp_path / "fb"
    assert main(["lab", "check", "motor-start-stop", str(NO_SEAL_IN), "--out", str(fb)]) == 0
    assert list(fb.glob("*.png")), "a failing program gets its diagrams"
    assert main(["lab", "check", "motor-start-stop", str(SOLUTION), "--out", str(fb)]) == 0
    assert sorted(p.name for p in fb.iterdir()) == ["feedback.md"], "no stale diagrams"
    assert "PASS" in (fb / "feedback.md").read_text(encoding="utf-8")


def test_a_folder_with_other_files_is_never_replaced(tmp_path, capsys):
    (tmp_path / "work.st").write_text("my work", encoding="utf-8")
    assert main(["lab", "check", "motor-start-stop", str(SOLUTION), "--out",
                 str(tmp_path)]) == 1
    assert "PLC5051" in capsys.readouterr().err
    assert (tmp_path / "work.st").read_text(encoding="utf-8") == "my work"


def test_lab_check_prints_the_beginner_warnings_first(tmp_path, capsys):
    moved = SOLUTION.read_text(encoding="utf-8").replace("%IX0.0", "%IX0.7", 1)
    f = tmp_path / "moved.st"
    f.write_text(moved, encoding="utf-8")
    assert main(["lab", "check", "motor-start-stop", str(f)]) == 0
    out = capsys.readouterr().out
    assert "PLC0215" in out.split("score:")[0].splitlines()[1]


def test_png_shows_the_labs_signals_and_the_students_variable(tmp_path, capsys, monkeypatch):
    from plclab.viz import from_trace

    drawn = {}
    real = from_trace.export

    def spy(trace, **kw):
        drawn.update(kw)
        return real(trace, **kw)

    monkeypatch.setattr(from_trace, "export", spy)
    lab = load_lab("relay-thermostat")
    bad = lab.path / "mistakes" / "no_hysteresis.st"
    png = tmp_path / "t.png"
    assert main(["lab", "check", "relay-thermostat", str(bad), "--watch", "Thermostat.temp",
                 "--png", str(png)]) == 0
    assert png.is_file()
    assert drawn["signals"] == [*lab.diagram_signals, "Thermostat.temp"]
    t0, _, t1 = drawn["window"].partition("..")
    assert float(t0.rstrip("s")) > 0  # the failure window, not the start of the run
