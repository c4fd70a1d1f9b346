"""Writing a physical input (ADR 0037): the error PLC0105 in iec, codesys and s7; in matiec
the warning PLC0284, the value stored and overwritten by the next scan's input read."""

import pytest

import plclab
from plclab.project import check_sources

WRITES = """PROGRAM Main
VAR level AT %IW0 : INT; seen : INT; bit : BOOL; END_VAR
seen := level;
level := 42;
%IX2.0 := TRUE;
bit := %IX2.0;
END_PROGRAM
"""


@pytest.mark.parametrize("dialect", ["iec", "codesys", "s7"])
def test_writing_an_input_is_an_error_outside_matiec(dialect: str) -> None:
    _, diags = check_sources([(f"{{dialect '{dialect}'}}\n" + WRITES, "main.st")])
    assert [d.code for d in diags if d.severity == "error"] == ["PLC0105", "PLC0105"]


def test_matiec_warns_and_the_next_input_read_overwrites_the_value() -> None:
    src = "{dialect 'matiec'}\n" + WRITES
    project, diags = check_sources([(src, "main.st")])
    assert project is not None
    assert [(d.code, d.severity) for d in diags] == [("PLC0284", "warning")] * 2
    plc = plclab.loads(src)
    plc.scan(1)
    assert plc["Main.level"] == 42 and plc["Main.bit"] is True  # written, read in the scan
    plc.inputs[0:2] = (7).to_bytes(2, "big")
    plc.scan(1)
    assert plc["Main.seen"] == 7  # the input read of the next scan overwrote the 42
    assert plc["Main.level"] == 42


def test_an_output_connection_to_an_input_follows_the_same_rule() -> None:
    src = """PROGRAM Main
VAR t : TON; done AT %IX0.0 : BOOL; END_VAR
t(IN := TRUE, PT := T#1s, Q => done);
END_PROGRAM
"""
    codes = {d.code for d in check_sources([(src, "m.st")])[1]}
    assert "PLC0105" in codes
    codes = {d.code for d in check_sources([("{dialect 'matiec'}\n" + src, "m.st")])[1]}
    assert "PLC0284" in codes and "PLC0105" not in codes
