"""Objects keep the design rule (ADR 0021): method, property, interface and VAR_INST names, and
references, reach the generated Python only as mangled upper-case identifiers."""

from __future__ import annotations

from pathlib import Path

import gencheck
import pytest

from plclab.project import compile_sources

EXAMPLES = sorted((Path(__file__).parents[2] / "examples" / "oop").glob("*.st"))

HOSTILE = """INTERFACE self METHOD import : INT END_METHOD PROPERTY class : INT END_PROPERTY
END_INTERFACE
FUNCTION_BLOCK exec IMPLEMENTS self
VAR _copy : INT; END_VAR
METHOD import : INT VAR_INST eval : INT; END_VAR eval := eval + 1; import := eval; END_METHOD
PROPERTY class : INT GET class := _copy; END_GET SET _copy := class; END_SET END_PROPERTY
METHOD FB_init : BOOL VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; END_VAR END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK open EXTENDS exec
VAR r : REF_TO INT; END_VAR
METHOD import : INT import := SUPER^.import() + THIS^.class; END_METHOD
r := REF(_copy);
r^ := 3;
END_FUNCTION_BLOCK
PROGRAM Main
VAR o : open; s : self; other : self; n : INT; ok : BOOL; END_VAR
s := o;
n := s.import();
s.class := 4;
ok := __QUERYINTERFACE(s, other) AND __ISVALIDREF(other);
o();
END_PROGRAM
"""


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_the_examples_keep_the_rule(path):
    compiled = compile_sources([(path.read_text(), path.name)])
    assert gencheck.problems(compiled.source) == []


def test_python_words_as_object_names_stay_mangled():
    compiled = compile_sources([(HOSTILE, "h.st")])
    assert gencheck.problems(compiled.source, ("import", "exec", "eval", "open")) == []
