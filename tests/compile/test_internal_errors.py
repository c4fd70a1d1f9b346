"""Code Python refuses to compile is plclab's bug: it is reported as the internal compiler error
PLC9990 with a request to report it, never as the student's size limit PLC0191 (issue 30). A
PROPERTY written through ``THIS^`` inside a method (the canonical CODESYS form) compiles."""

import pytest

import plclab
from plclab.compile import codegen
from plclab.errors import PlcError
from plclab.runtime.plc import Plc

MOTOR = """
FUNCTION_BLOCK Motor
VAR _speed : REAL; END_VAR
METHOD Faster
THIS^.Speed := THIS^.Speed + 10.0;
END_METHOD
METHOD Slower
THIS^.Speed := THIS^.Speed - 1.0;
END_METHOD
PROPERTY Speed : REAL
GET
Speed := _speed;
END_GET
SET
_speed := Speed;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR m : Motor; x : REAL; END_VAR
m.Faster(); m.Faster(); m.Slower();
x := m.Speed;
END_PROGRAM
"""


def test_a_property_written_through_this_in_a_method():
    plc = Plc(plclab.compile_sources([(MOTOR, "motor.st")]))
    plc.scan()
    assert plc["Main.x"] == 19.0


def test_invalid_generated_code_is_an_internal_error_not_a_size_limit(monkeypatch):
    real = codegen.compile_lines

    def broken(lines, filename):  # as if the generator had written invalid Python
        return real([*lines, "x) = 1"], filename)

    monkeypatch.setattr(codegen, "compile_lines", broken)
    with pytest.raises(PlcError) as e:
        plclab.compile_sources([("PROGRAM Main VAR x : INT; END_VAR x := 1; END_PROGRAM",
                                 "p.st")])
    assert e.value.code == "PLC9990"
    assert "bug in plclab" in e.value.message and "report" in e.value.message
    assert "split it" not in e.value.message
