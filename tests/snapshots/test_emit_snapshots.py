"""Snapshots of ``plclab compile --emit python|st|ast`` for a few small programs in ST, IL,
LD and PLCopen FBD: a change in a front end, the lowering or the code generator shows up as a
diff of a stored file.

The programs are ``programs/*``; the expected outputs ``expected/<program>.<emit>``. After an
intended change, regenerate them and review the diff before committing::

    PLCLAB_UPDATE_SNAPSHOTS=1 python -m pytest tests/snapshots -q
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from plclab.cli import main
from plclab.compile.commands import EMITS, emit
from plclab.project import check_sources

HERE = Path(__file__).parent
PROGRAMS = sorted((HERE / "programs").iterdir())
SUFFIX = {"python": "py.txt", "st": "st", "ast": "ast"}  # .py.txt: not linted as code
UPDATE = os.environ.get("PLCLAB_UPDATE_SNAPSHOTS") == "1"


def expected_path(program: Path, kind: str) -> Path:
    return HERE / "expected" / f"{program.name}.{SUFFIX[kind]}"


@pytest.mark.parametrize("kind", EMITS)
@pytest.mark.parametrize("program", PROGRAMS, ids=lambda p: p.name)
def test_emit_matches_snapshot(program, kind):
    # the file name as the sources are given, so the snapshot does not depend on the checkout
    text, _ = emit([(program.read_text(encoding="utf-8"), program.name)], kind)
    path = expected_path(program, kind)
    if UPDATE:
        path.write_text(text, encoding="utf-8")
    assert path.exists(), f"no snapshot {path.name}: run with PLCLAB_UPDATE_SNAPSHOTS=1"
    assert text == path.read_text(encoding="utf-8"), (
        f"{path.name} changed; if intended, regenerate with PLCLAB_UPDATE_SNAPSHOTS=1 and "
        "review the diff")


def test_snapshot_programs_cover_each_front_end():
    assert {p.suffix for p in PROGRAMS} >= {".st", ".il", ".ld", ".xml"}


def test_lowered_st_checks_clean_again():
    """The ST a ladder network or an FBD lowers to is a program the checker accepts (IL bodies
    keep their current-result variables and jumps, SFC charts their hidden step timers and
    transition flags: neither is user ST)."""
    for program in PROGRAMS:
        if program.suffix == ".il" or program.name.startswith("sfc"):
            continue
        st_text, _ = emit([(program.read_text(encoding="utf-8"), program.name)], "st")
        assert "|---" not in st_text and "<FBD>" not in st_text
        _, diags = check_sources([(st_text, program.name + ".st")])
        assert not [str(d) for d in diags if d.severity == "error"], program.name


def test_command_writes_to_a_file(tmp_path, capsys):
    out = tmp_path / "tank.py"
    program = HERE / "programs" / "tank_level.st"
    assert main(["compile", str(program), "--emit", "python", "-o", str(out)]) == 0
    assert out.read_text(encoding="utf-8") == expected_path(program, "python").read_text(
        encoding="utf-8")
    assert capsys.readouterr().out == ""


def test_command_prints_to_stdout_and_reports_errors(tmp_path, capsys):
    assert main(["compile", str(HERE / "programs" / "tank.il"), "--emit", "st"]) == 0
    assert capsys.readouterr().out.startswith("(* ")
    bad = tmp_path / "bad.st"
    bad.write_text("PROGRAM P VAR x : INT; END_VAR x := y; END_PROGRAM\n")
    assert main(["compile", str(bad), "--emit", "ast"]) == 1
    assert "error PLC0100" in capsys.readouterr().err


def test_unwritable_output_is_plc3014(tmp_path, capsys):
    program = str(HERE / "programs" / "tank_level.st")
    assert main(["compile", program, "-o", str(tmp_path / "no" / "such" / "x.py")]) == 1
    assert "error PLC3014" in capsys.readouterr().err
