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


BARE = """
VAR_GLOBAL Speed : REAL; END_VAR
FUNCTION_BLOCK Motor
VAR _speed : REAL; END_VAR
METHOD Faster
Speed := Speed + 10.0;
END_METHOD
PROPERTY Speed : REAL
GET
Speed := _speed;
END_GET
SET
_speed := Speed;
END_SET
END_PROPERTY
PROPERTY Double : REAL
GET
Double := Speed * 2.0;
END_GET
END_PROPERTY
END_FUNCTION_BLOCK
FUNCTION_BLOCK Fast EXTENDS Motor
METHOD Boost
Speed := Speed + 100.0;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR m : Motor; f : Fast; x : REAL; y : REAL; d : REAL; END_VAR
m.Faster(); m.Faster();
f.Boost(); f.Faster();
x := m.Speed; y := f.Speed; d := m.Double;
END_PROGRAM
"""


def test_a_bare_property_name_inside_its_own_block():
    """CODESYS: inside the block (its methods, its other accessors, derived blocks) a PROPERTY
    is used by its bare name; it is the property, not the global of the same name."""
    plc = Plc(plclab.compile_sources([(BARE, "bare.st")]))
    plc.scan()
    assert (plc["Main.x"], plc["Main.y"], plc["Main.d"]) == (20.0, 110.0, 40.0)
    assert plc["Speed"] == 0.0


def test_a_bare_property_name_is_not_a_name_outside_its_block():
    src = BARE.replace("VAR_GLOBAL Speed : REAL; END_VAR", "").replace(
        "x := m.Speed;", "x := Speed;")
    with pytest.raises(PlcError) as e:
        plclab.compile_sources([(src, "bare.st")])
    assert e.value.code == "PLC0100"


PROP_USE = """
FUNCTION Inc : INT
VAR_IN_OUT v : INT; END_VAR
v := v + 1; Inc := 0;
END_FUNCTION
FUNCTION_BLOCK Motor
VAR _n : INT; k : INT; p : POINTER TO INT; c : CTU; END_VAR
METHOD Run
%s
END_METHOD
PROPERTY Count : INT
GET
Count := _n;
END_GET
SET
_n := Count;
END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM Main
VAR m : Motor; x : INT; END_VAR
m.Run(); x := m.Count;
END_PROGRAM
"""


@pytest.mark.parametrize("stmt, code", [
    ("k := Inc(Count);", "PLC0107"), ("k := Inc(THIS^.Count);", "PLC0107"),
    ("p := ADR(Count);", "PLC0240"), ("p := ADR(THIS^.Count);", "PLC0240"),
    ("FOR Count := 1 TO 3 DO END_FOR;", "PLC0113")])
def test_a_property_where_a_variable_is_needed_is_the_students_error(stmt, code):
    """A PROPERTY is a GET and a SET, not a variable: VAR_IN_OUT, ADR and a FOR counter
    refuse it with the student's code (these were PLC9990, invalid generated Python)."""
    with pytest.raises(PlcError) as e:
        plclab.compile_sources([(PROP_USE % stmt, "p.st")])
    assert e.value.code == code, e.value
    assert "PROPERTY" in str(e.value)


@pytest.mark.parametrize("stmt", ["c(CU := TRUE, PV := 3, CV => Count);",
                                  "c(CU := TRUE, PV := 3, CV => THIS^.Count);"])
def test_an_output_connected_to_a_property_calls_its_set(stmt):
    plc = Plc(plclab.compile_sources([(PROP_USE % stmt, "p.st")]))
    plc.scan()
    assert plc["Main.x"] == 1
