"""The escape suite, in process: hostile identifiers, strings, comments, pragmas, enum values,
struct fields, TEST names, IL labels, ladder names and PLCopen XML names and entities.

Each case must either be refused with a ``PlcError`` (not the internal error PLC9999) or compile
to Python that keeps the design rule (``gencheck.problems``), load, scan and run its TESTs;
and nothing may import the sentinel module the payloads name.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

import plclab
from plclab.errors import PlcError
from plclab.project import compile_sources
from plclab.runtime.plc import Plc
from plclab.testing import run_compiled_tests

HERE = Path(__file__).resolve().parent


import gencheck  # noqa: E402
import harness  # noqa: E402
import known_issues  # noqa: E402
import payloads  # noqa: E402


@pytest.fixture
def sentinel(tmp_path, monkeypatch):
    """``pwned_sentinel`` importable from tmp_path; yields the marker its import creates."""
    (tmp_path / "pwned_sentinel.py").write_text(
        "import pathlib\npathlib.Path(__file__).with_name('PWNED').write_text('x')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    marker = tmp_path / "PWNED"
    yield marker
    assert not marker.exists(), "the payload imported pwned_sentinel"
    assert "pwned_sentinel" not in sys.modules


def _params():
    out = []
    for cid, files in payloads.all_cases():
        k = known_issues.match_escape(cid)
        marks = [pytest.mark.xfail(strict=False, reason=f"{k.id} ({k.area}): {k.reason}")] \
            if k else []
        out.append(pytest.param(files, id=cid, marks=marks))
    return out


@pytest.mark.parametrize("files", _params())
def test_hostile_source_stays_data(files, sentinel, tmp_path):
    sources = [(text.replace("../secret/hidden.txt", str(tmp_path / "hidden.txt")), name)
               for name, text in files.items()]
    (tmp_path / "hidden.txt").write_text("TOKEN-do-not-leak")
    try:
        compiled = compile_sources(sources)
    except PlcError as e:
        assert e.code != "PLC9999", str(e)
        assert "TOKEN-do-not-leak" not in str(e)
        return
    assert gencheck.problems(compiled.source) == []
    assert "TOKEN-do-not-leak" not in compiled.source, "an XML entity read a file"
    try:
        plc = Plc(compiled, watchdog=50_000)
        plc.scan(3)
        for name in plc.variables():
            plc.format(name)
    except PlcError as e:
        assert e.code != "PLC9999", str(e)
    for r in run_compiled_tests(compiled):
        assert "PLC9999" not in str(r), str(r)


def test_the_rule_holds_for_every_example_and_lab_file():
    """The check itself sees real programs pass: every repository program that compiles."""
    compiled = 0
    for text, name in harness.seed_files():
        try:
            c = compile_sources([(text, name)])
        except PlcError:
            continue
        compiled += 1
        assert gencheck.problems(c.source) == [], name
    assert compiled >= 30


def test_the_rule_catches_an_escape():
    """A hand-made escape is caught by each clause of the rule (the check can fail)."""
    good = compile_sources([("PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM",
                             "p.st")]).source
    assert gencheck.problems(good) == []
    bad = {
        "import": good + "import pwned_sentinel\n",
        "call": good + "__import__('os')\n",
        "name": good + "x = os\n",
        "private": good + "class P_X:\n    def _body(self):\n        self.__Y = 1\n",
        "word": good + "V_X = pwned_sentinel\n",
    }
    for what, src in bad.items():
        assert gencheck.problems(src), what


def test_the_native_pragma_attack_never_reaches_python(sentinel):
    src = ("{native 'pwned_sentinel:X'}\nFUNCTION_BLOCK Evil\nVAR_INPUT p : INT; END_VAR\n"
           "END_FUNCTION_BLOCK\nPROGRAM P VAR e : Evil; END_VAR e(p := 1); END_PROGRAM\n")
    with pytest.raises(PlcError) as ei:
        plclab.loads(src)
    assert ei.value.code == "PLC0131"
