"""The problem catalogue (plclab/problems.toml) tells the truth: every wrong example raises its
code, every fix compiles (and, for run-time faults, runs the same scans) cleanly, and the codes
of the catalogue are exactly the codes plclab's source uses (or are marked reserved)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import plclab
from plclab.cli import main
from plclab.problems import LANGUAGES, PROBLEMS, catalogue, close_codes, describe
from plclab.project import check_sources
from plclab.testing import run_test_sources

ROOT = Path(plclab.__file__).parent
ENTRIES = catalogue()
STUDENT = [c for c, p in ENTRIES.items() if c.startswith(("PLC0", "PLC2"))]
EXAMPLES = [c for c in STUDENT if ENTRIES[c].wrong is not None]
COMPILE = [c for c in EXAMPLES if not c.startswith("PLC2")]
RUNTIME = [c for c in EXAMPLES if c.startswith("PLC2")]


def diagnostics(code: str, which: str):
    p = ENTRIES[code]
    return check_sources([(getattr(p, which), f"{which}.{p.language}")], lint=True)[1]


def run(code: str, which: str) -> str | None:
    """The code of the fault that running ``which`` (wrong or fix) raises, or None."""
    p = ENTRIES[code]
    text, name = getattr(p, which), f"{which}.{p.language}"
    if p.run == "test":
        failed = [r for r in run_test_sources([(text, name)]) if not r.passed]
        return failed[0].code if failed else None
    plc = plclab.loads(text, name)
    try:
        plc.scan(p.scans)
    except plclab.PlcRuntimeFault as e:
        return e.code
    return None


def test_every_student_code_has_an_example_or_says_why_not():
    missing = [c for c in STUDENT if ENTRIES[c].wrong is None and not ENTRIES[c].no_example]
    assert not missing
    for c in EXAMPLES:
        p = ENTRIES[c]
        assert p.fix is not None and p.language in LANGUAGES, c
        if c in RUNTIME:
            assert p.run == "test" or (p.scans or 0) >= 1, c


@pytest.mark.parametrize("code", COMPILE)
def test_wrong_example_raises_its_code(code):
    diags = diagnostics(code, "wrong")
    found = [d for d in diags if d.code == code]
    assert found, f"{code}: got {[str(d) for d in diags][:5]}"
    if code.startswith("PLC02") and not "PLC0220" <= code <= "PLC0249":
        assert found[0].severity == "warning"  # PLC0220-0249: object-oriented checks, errors


@pytest.mark.parametrize("code", COMPILE)
def test_fix_compiles_without_errors(code):
    diags = diagnostics(code, "fix")
    bad = [str(d) for d in diags if d.severity == "error" or d.code == code]
    assert not bad, f"{code}: {bad[:5]}"


@pytest.mark.parametrize("code", RUNTIME)
def test_run_time_example_faults_and_fix_runs_clean(code):
    assert not [d for d in diagnostics(code, "wrong") if d.severity == "error"]
    assert run(code, "wrong") == code
    assert run(code, "fix") is None


def _codes_in_source() -> dict[str, list[str]]:
    """Every PLCnnnn written in plclab's Python and ST files (not the catalogue itself); the
    upper end of a range (``PLC5001-PLC5099``) is not a code."""
    found: dict[str, list[str]] = {}
    for path in sorted(ROOT.rglob("*")):
        if path.suffix not in (".py", ".st") or path.name == "problems.py":
            continue
        text = re.sub(r"-PLC\d{4}", "", path.read_text(encoding="utf-8"))
        for code in re.findall(r"PLC\d{4}", text):
            found.setdefault(code, []).append(str(path.relative_to(ROOT)))
    return found


def test_every_code_in_the_source_is_catalogued():
    used = _codes_in_source()
    assert len(used) > 100
    missing = {c: files[:2] for c, files in used.items() if c not in ENTRIES}
    assert not missing


def test_every_catalogued_code_is_used_or_reserved():
    used = _codes_in_source()
    unused = [c for c, p in ENTRIES.items() if c not in used and not p.reserved]
    assert not unused
    for c, p in ENTRIES.items():
        assert not p.reserved or p.reserved_why, c


def test_problems_keeps_its_api():
    assert PROBLEMS["PLC0100"] == (ENTRIES["PLC0100"].title, ENTRIES["PLC0100"].explanation)
    assert list(PROBLEMS) == list(ENTRIES) and all(len(v) == 2 for v in PROBLEMS.values())


def test_explain_prints_the_example_and_the_fix(capsys):
    assert main(["explain", "plc0113"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("PLC0113: bad FOR loop")
    wrong, _, fix = out.partition("Fix:")
    assert "Wrong (ST)" in wrong and "i := i + 1;" in wrong and "i := i + 1;" not in fix
    assert "scan it 4 times" in describe("PLC2002")


def test_explain_list_names_every_code(capsys):
    assert main(["explain", "--list"]) == 0
    lines = capsys.readouterr().out.strip().split("\n")
    assert [line.split()[0] for line in lines] == sorted(ENTRIES)


def test_unknown_code_is_plc3002_with_close_codes(capsys):
    assert main(["explain", "PLC0l13"]) == 1
    err = capsys.readouterr().err
    assert "error PLC3002: PLC0l13 is not a plclab diagnostic code" in err
    assert close_codes("PLC0l13")[0] in err
    assert close_codes("113") == ["PLC0113"]
    assert close_codes("PLC9998")[0] == "PLC9999"
