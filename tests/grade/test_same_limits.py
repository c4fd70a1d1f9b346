"""The same limits and the same reading of files in every command (issue 15): `lab check`
stops a slow program at the lab's time limit like `grade`; a Latin-1 file is the same clear
error (PLC5052) in `check`, `run`, `lab check` and `grade`."""

from __future__ import annotations

import shutil
import time

from plclab.cli import main
from plclab.grade.lab import load_lab

TANK = load_lab("tank-two-position")
LATIN1 = "PROGRAM Main (* Kühler *)\nVAR x : BOOL; END_VAR\nx := TRUE;\nEND_PROGRAM\n"


def test_a_latin1_file_is_the_same_error_everywhere(tmp_path, capsys):
    f = tmp_path / "main.st"
    f.write_bytes(LATIN1.encode("latin-1"))
    for args in (["check", str(f)], ["run", str(f), "--cycles", "1"],
                 ["lab", "check", "tank-two-position", str(f)]):
        assert main(args) == 1, args
        err = capsys.readouterr().err
        assert "PLC5052" in err and "main.st:1:18" in err and "UTF-8" in err, args
    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copyfile(f, subs / "alice.st")
    assert main(["grade", "tank-two-position", str(subs), "--out", str(tmp_path / "g"),
                 "--jobs", "1", "-q"]) == 0
    feedback = (tmp_path / "g" / "alice" / "feedback.md").read_text(encoding="utf-8")
    assert "PLC5052" in feedback


def test_utf8_with_a_bom_and_utf16_are_read_everywhere(tmp_path, capsys):
    for enc in ("utf-8-sig", "utf-16"):
        f = tmp_path / f"main-{enc}.st"
        f.write_bytes(LATIN1.encode(enc))
        assert main(["check", str(f)]) == 0, enc


def test_lab_check_stops_a_slow_program_at_the_labs_time_limit(tmp_path, capsys):
    lab = tmp_path / "tank-two-position"
    shutil.copytree(TANK.path, lab)
    toml = lab / "lab.toml"
    toml.write_text(toml.read_text(encoding="utf-8").replace('time_limit = "30s"',
                                                             'time_limit = "2s"'),
                    encoding="utf-8")
    assert load_lab(lab).time_limit == 2
    slow = (TANK.path / "solution" / "tank.st").read_text(encoding="utf-8")
    slow = slow.replace("END_PROGRAM", "FOR i := 1 TO 200000 DO k := k + 1; END_FOR;\n"
                        "END_PROGRAM", 1)
    slow = slow.replace("END_VAR", "END_VAR\nVAR i : DINT; k : DINT; END_VAR", 1)
    f = tmp_path / "slow.st"
    f.write_text(slow, encoding="utf-8")
    t = time.perf_counter()
    assert main(["lab", "check", str(lab), str(f)]) == 0
    assert time.perf_counter() - t < 30
    out = capsys.readouterr().out
    assert "PLC5023" in out and "2 s" in out
    assert out.rstrip().splitlines()[-1].startswith("score: 0/")
