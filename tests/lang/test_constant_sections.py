"""What CONSTANT forbids (IEC 61131-3 ed.3 Table 13): writing a VAR_EXTERNAL CONSTANT, a
VAR_IN_OUT CONSTANT, an element of a constant array, or handing a constant on to a VAR_IN_OUT
that could change it. Each is PLC0105 at the write. The allowed uses run in
tests/st/conformance_constant_sections.st."""

import pytest

from plclab.project import check_sources

CASES = {
    "external": ("VAR_GLOBAL g : INT; END_VAR\nFUNCTION_BLOCK F\n"
                 "VAR_EXTERNAL CONSTANT g : INT; END_VAR\ng := 1;\nEND_FUNCTION_BLOCK\n", 4,
                 "VAR_EXTERNAL CONSTANT"),
    "in_out": ("FUNCTION_BLOCK F\nVAR_IN_OUT CONSTANT v : INT; END_VAR\nv := 1;\n"
               "END_FUNCTION_BLOCK\n", 3, "v is a constant"),
    "array element": ("VAR_GLOBAL CONSTANT A : ARRAY[1..2] OF INT := [1, 2]; END_VAR\n"
                      "PROGRAM P\nA[1] := 5;\nEND_PROGRAM\n", 3, "A is a constant"),
    "passed on to a VAR_IN_OUT": (
        "FUNCTION_BLOCK G\nVAR_IN_OUT w : INT; END_VAR\nw := 2;\nEND_FUNCTION_BLOCK\n"
        "FUNCTION_BLOCK F\nVAR_IN_OUT CONSTANT v : INT; END_VAR\nVAR g : G; END_VAR\n"
        "g(w := v);\nEND_FUNCTION_BLOCK\n", 8, "v is a constant"),
}


@pytest.mark.parametrize("name", list(CASES))
def test_a_constant_cannot_be_written(name: str) -> None:
    src, line, words = CASES[name]
    _, diags = check_sources([(src, "t.st")])
    errors = [d for d in diags if d.severity == "error"]
    assert [(d.code, d.location.line) for d in errors] == [("PLC0105", line)]
    assert words in errors[0].message


def test_constant_sections_need_no_initial_value() -> None:
    src = ("VAR_GLOBAL CONSTANT K : INT := 3; END_VAR\nFUNCTION_BLOCK F\n"
           "VAR_EXTERNAL CONSTANT K : INT; END_VAR\nVAR_IN_OUT CONSTANT v : INT; END_VAR\n"
           "VAR_OUTPUT y : INT; END_VAR\ny := K + v;\nEND_FUNCTION_BLOCK\n")
    _, diags = check_sources([(src, "t.st")])
    assert [d.code for d in diags if d.severity == "error"] == []
