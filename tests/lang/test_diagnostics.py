"""Every diagnostic code at least once, with a location and a message that says what to do."""

import pytest

from plclab.problems import PROBLEMS
from plclab.project import check_sources

P = "PROGRAM P\nVAR x : INT; b : BOOL; r : REAL; d : DINT; END_VAR\n{body}\nEND_PROGRAM\n"

CASES = {
    "PLC0001": "PROGRAM P VAR x : INT; END_VAR x := 1 @ 2; END_PROGRAM",
    "PLC0002": "PROGRAM P (* never closed",
    "PLC0003": "PROGRAM P VAR s : STRING; END_VAR s := 'open; END_PROGRAM",
    "PLC0004": "PROGRAM P VAR x : INT; END_VAR x := 2#1021; END_PROGRAM",
    "PLC0005": "PROGRAM P VAR t : TIME; END_VAR t := T#5parsec; END_PROGRAM",
    "PLC0010": P.format(body="x := ;"),
    "PLC0011": P.format(body="WHILE b DO x := 1; END_WHILLE;"),
    "PLC0012": P.format(body="IF x == 1 THEN x := 2; END_IF"),
    "PLC0013": P.format(body="x = 5;"),
    "PLC0014": P.format(body="IF x := 1 THEN x := 2; END_IF"),
    "PLC0006": "PROGRAM P VAR my__var : INT; END_VAR my__var := 1; END_PROGRAM",
    "PLC0100": P.format(body="x := countr;"),
    "PLC0101": "PROGRAM P VAR x : INT; x : BOOL; END_VAR x := 1; END_PROGRAM",
    "PLC0102": "PROGRAM P VAR x : INTEGER; END_VAR x := 1; END_PROGRAM",
    "PLC0103": P.format(body="b := 'text';"),
    "PLC0104": P.format(body="x := x + b;"),
    "PLC0105": "PROGRAM P VAR CONSTANT k : INT := 1; END_VAR k := 2; END_PROGRAM",
    "PLC0106": P.format(body="x := NoSuchFunc(1);"),
    "PLC0107": P.format(body="x := LIMIT(1, 2);"),
    "PLC0108": P.format(body="IF x THEN x := 1; END_IF"),
    "PLC0109": "PROGRAM P VAR a : ARRAY[1..x] OF INT; x : INT; END_VAR a[1] := 1; END_PROGRAM",
    "PLC0110": "FUNCTION F : INT VAR_INPUT n : INT; END_VAR F := F(n - 1); END_FUNCTION",
    "PLC0111": P.format(body="x := 40000;"),
    "PLC0112": "PROGRAM P VAR a : ARRAY[1..3] OF INT; END_VAR a[4] := 1; END_PROGRAM",
    "PLC0113": P.format(body="FOR x := 1 TO 10 DO x := 5; END_FOR"),
    "PLC0114": P.format(body="EXIT;"),
    "PLC0115": P.format(body="CASE x OF 1: b := TRUE; 1: b := FALSE; END_CASE"),
    "PLC0116": "PROGRAM P VAR t : TON; q : BOOL; END_VAR t(IN := TRUE); q := t.QQ; END_PROGRAM",
    "PLC0117": P.format(body="x := x[1];"),
    "PLC0118": "{dialect 'iec'}\n" + P.format(body="x := d;"),
    "PLC0119": "FUNCTION F : INT VAR_INPUT n : INT; END_VAR n := n; END_FUNCTION",
    "PLC0120": "PROGRAM P VAR x AT %IX0.0 : INT; END_VAR END_PROGRAM",
    "PLC0121": ("FUNCTION_BLOCK FB VAR secret : INT; END_VAR secret := 1; END_FUNCTION_BLOCK\n"
                "PROGRAM P VAR f : FB; x : INT; END_VAR f(); x := f.secret; END_PROGRAM"),
    "PLC0131": ("{native 'os:system'}\nFUNCTION_BLOCK Evil VAR_INPUT i : INT; END_VAR "
                "END_FUNCTION_BLOCK\nPROGRAM P VAR e : Evil; END_VAR e(i := 1); END_PROGRAM"),
    "PLC0200": "PROGRAM P VAR unused : INT; x : INT; END_VAR x := 1; END_PROGRAM",
    "PLC0201": P.format(body="RETURN; x := 1;"),
    "PLC0202": P.format(body="r := d;"),
    "PLC0203": ("FUNCTION_BLOCK FB VAR_INPUT i : INT; END_VAR i := 1; END_FUNCTION_BLOCK"),
    "PLC0204": "PROGRAM P VAR u : UINT; END_VAR u := -u; END_PROGRAM",
}


@pytest.mark.parametrize("code", sorted(CASES))
def test_each_diagnostic_code(code):
    src = CASES[code]
    _, diags = check_sources([(src, "case.st")])
    found = [d for d in diags if d.code == code]
    assert found, f"{code} not reported; got {[str(d) for d in diags]}"
    d = found[0]
    assert d.location is not None and d.location.file == "case.st" and d.location.line >= 1
    assert len(d.message) > 15
    assert code in PROBLEMS


def test_did_you_mean_for_names_and_keywords():
    _, diags = check_sources([(P.format(body="x := y + countr;").replace("x : INT;",
                              "x : INT; counter : INT;"), "s.st")])
    msgs = [d.message for d in diags if d.code == "PLC0100"]
    assert any("did you mean COUNTER?" in m for m in msgs)


def test_extents_typo_suggests_keyword():
    _, diags = check_sources([("FUNCTION_BLOCK A END_FUNCTION_BLOCK\nFUNCTION_BLOCK B EXTENTS A\n"
                               "END_FUNCTION_BLOCK", "o.st")])
    assert any("did you mean" in d.message for d in diags)


def test_all_errors_in_a_file_are_reported():
    src = P.format(body="x := y;\nb := 5;\nr := 'a';\nx := zz;")
    _, diags = check_sources([(src, "m.st")])
    assert len([d for d in diags if d.severity == "error"]) == 4


def test_diagnostic_format():
    _, diags = check_sources([(P.format(body="x := undefinedName;"), "fmt.st")])
    assert str(diags[0]).startswith("fmt.st:3:6: error PLC0100: undefinedName is not declared")


def test_runtime_fault_codes_are_catalogued():
    for code in ("PLC2001", "PLC2002", "PLC2003", "PLC2004", "PLC2005", "PLC2010", "PLC3001",
                 "PLC3002", "PLC3003"):
        assert code in PROBLEMS
