"""Dialects (ADR 0017): how a file's dialect is chosen and what each profile changes."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

import plclab
from plclab.cli import main
from plclab.errors import PlcError
from plclab.lang.dialect import DEFAULT, PROFILES
from plclab.project import check_sources

BOOK = """PROGRAM P
VAR CONSTANT Array_Sz : BYTE := 4; END_VAR
VAR Iter : BYTE; arr : ARRAY [1..Array_Sz] OF REAL := [3.2, 4.2, 1.4, 7.8];
    fnd_max : REAL := -1.2E38; END_VAR
FOR Iter := 1 TO Array_Sz DO
  fnd_max := MAX(fnd_max, arr[Iter]);
END_FOR
END_PROGRAM
"""
STRUCT = "TYPE Pt : STRUCT x : INT; END_STRUCT END_TYPE\nPROGRAM P VAR p : Pt; END_VAR p.x := 1; END_PROGRAM\n"
WIDTH = "PROGRAM P VAR raw : INT := 9216; d : DINT; END_VAR d := raw * 150; END_PROGRAM\n"


def codes(text: str, dialect: str | None = None, name: str = "f.st") -> list[tuple[str, str]]:
    return [(d.code, d.severity) for d in check_sources([(text, name)], dialect)[1]]


def test_the_default_is_codesys_and_reads_the_textbook():
    assert DEFAULT == "codesys" and set(PROFILES) == {"iec", "codesys", "s7", "matiec"}
    assert set(codes(BOOK)) == {("PLC0173", "warning")}
    plc = plclab.loads(BOOK)
    plc.scan()
    assert plc["P.fnd_max"] == pytest.approx(7.8, abs=1e-6)


@pytest.mark.parametrize("dialect,expected", [
    ("iec", {"PLC0113", "PLC0117"}), ("matiec", {"PLC0113", "PLC0117"}),
    ("s7", {"PLC0173"}), ("codesys", {"PLC0173"})])
def test_bit_string_counters_per_dialect(dialect, expected):
    assert {c for c, _ in codes(BOOK, dialect)} == expected


def test_pragma_wins_over_the_argument():
    assert codes("{dialect 'codesys'}\n" + STRUCT, "iec") == []
    assert ("PLC0171", "error") in codes(STRUCT, "iec")
    assert ("PLC0171", "error") in codes("{dialect 'matiec'}\n" + STRUCT)


def test_operand_width_only_in_s7():
    for dialect, value in (("codesys", 1382400), ("iec", 1382400), ("s7", 6144)):
        plc = plclab.loads(WIDTH, dialect=dialect)
        plc.scan()
        assert plc["P.d"] == value, dialect


def test_unknown_dialect_is_a_diagnostic_with_a_place():
    diags = check_sources([("\n{dialect 'twincat'}\nPROGRAM P END_PROGRAM\n", "u.st")])[1]
    assert [(d.code, d.location.line) for d in diags] == [("PLC0170", 2)]
    with pytest.raises(PlcError) as ei:
        plclab.loads("PROGRAM P END_PROGRAM", dialect="twincat")
    assert ei.value.code == "PLC0170"


def test_cli_flag(tmp_path, capsys):
    f = tmp_path / "s.st"
    f.write_text(STRUCT)
    assert main(["check", str(f)]) == 0
    assert main(["check", "--dialect", "iec", str(f)]) == 1
    assert "PLC0171" in capsys.readouterr().out


def test_lab_toml_key_reaches_the_compiler(tmp_path):
    from plclab.grade.lab import load_lab

    labs = Path(plclab.__file__).parent.parent / "labs"
    lab_dir = sorted(p for p in labs.iterdir() if (p / "lab.toml").exists())[0]
    copy = tmp_path / lab_dir.name
    shutil.copytree(lab_dir, copy)
    toml = (copy / "lab.toml").read_text()
    (copy / "lab.toml").write_text('dialect = "s7"\n' + toml)
    assert load_lab(copy).dialect == "s7"
    (copy / "lab.toml").write_text('dialect = "nope"\n' + toml)
    with pytest.raises(PlcError) as ei:
        load_lab(copy)
    assert ei.value.code == "PLC5004"


def test_iec_address_forms_reach_the_image():
    """%QX75 = %Q75 = byte 9 bit 3; the unnamed AT and the hierarchical word (PLC0175)."""
    plc = plclab.loads("PROGRAM P VAR a AT %QX75 : BOOL; b AT %Q76 : BOOL; AT %QX9.7 : BOOL;\n"
                       "w AT %IW2.5.7.1 : WORD; x : WORD; END_VAR\n"
                       "a := TRUE; b := 1; x := w; END_PROGRAM")
    assert [d.code for d in plc.compiled.diagnostics] == ["PLC0175"]
    plc["%IW1"] = 1234
    plc.scan()
    assert plc.outputs[9] == 0b0001_1000 and plc["%QX75"] and plc["%Q76"]
    assert plc["P.x"] == 1234
