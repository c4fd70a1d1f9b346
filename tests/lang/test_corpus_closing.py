"""Forms the closing measure of issue 40 found in valid files (ADR 0060): each with the wrong
input the rule must still refuse."""

from __future__ import annotations

import pytest

from plclab.project import check_sources

EXPORT = """(*@PROPERTIES_EX@
TYPE: POU
LOCALE: 0
IEC_LANGUAGE: ST
*)
(*@KEY@:DESCRIPTION*)
version 1.1   12. mar. 2008
programmer    someone
the block counts: IF it is (* not *) closed here, the text is still description
(*@KEY@:END_DESCRIPTION*)
FUNCTION_BLOCK Count
VAR_OUTPUT n : INT; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
"""


def errors(text: str, dialect: str | None = None) -> list[str]:
    return [d.code for d in check_sources([(text, "f.st")], dialect)[1] if d.severity == "error"]


@pytest.mark.parametrize("dialect", ["codesys", "iec", "matiec", "s7"])
def test_the_description_of_a_codesys_2_3_export_is_not_code(dialect):
    assert errors(EXPORT, dialect) == []


def test_without_its_end_marker_the_description_is_code_again():
    broken = EXPORT.replace("(*@KEY@:END_DESCRIPTION*)", "")
    assert "PLC0010" in errors(broken, "codesys")
