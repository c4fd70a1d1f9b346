"""The trust boundary: a user's file can never bind a block to Python code.

The attack found in issue 11: ``{native 'module:Name'}`` in a student's file bound a FUNCTION or
FUNCTION_BLOCK to any attribute of any module under ``plclab.``; three such bindings wrote a file,
loaded it as Python and ran a shell command inside ``plclab grade``.
"""

from __future__ import annotations

import importlib

import pytest

import plclab
from plclab.errors import PlcError
from plclab.project import check_sources
from plclab.runtime import natives

ATTACK = """\
{native 'plclab.grade.lab:Path'}
FUNCTION_BLOCK Opener
VAR_INPUT p : STRING; END_VAR
END_FUNCTION_BLOCK
FUNCTION Writer : BOOL {native 'plclab.runtime.rt:HELPERS'}
VAR_INPUT s : STRING; END_VAR
END_FUNCTION
(* a pragma anywhere else is no better *)
PROGRAM P
VAR o : Opener; ok : BOOL; END_VAR
{ native 'os:system' }
o(p := '/tmp/x'); ok := Writer('import os');
END_PROGRAM
"""


@pytest.fixture
def no_imports(monkeypatch):
    """Fail if anything imports a module while the attack is handled."""

    def refuse(name, *args, **kwargs):
        raise AssertionError(f"imported {name} while handling user text")

    monkeypatch.setattr(importlib, "import_module", refuse)


@pytest.mark.parametrize("filename", ["attack.st", "attack.txt"])
def test_native_pragma_in_a_user_file_is_a_compile_error(filename, no_imports):
    project, diags = check_sources([(ATTACK, filename)])
    assert project is None
    found = [d for d in diags if d.code == "PLC0131"]
    assert [d.location.line for d in found] == [1, 5, 11]
    assert found[0].location.file == filename and found[0].location.col == 1
    assert found[1].location.col == 24
    assert "reserved for plclab's own block library" in found[0].message


def test_load_refuses_the_attack_before_anything_runs(tmp_path, no_imports):
    with pytest.raises(PlcError) as ei:
        plclab.loads(ATTACK)
    assert ei.value.code == "PLC0131"
    assert list(tmp_path.iterdir()) == []


def test_native_pragma_in_an_il_file():
    src = ("{native 'plclab.runtime.stdfb:TON'}\nFUNCTION_BLOCK Evil\nVAR_INPUT i : INT; END_VAR\n"
           "LD i\nST i\nEND_FUNCTION_BLOCK\n")
    _, diags = check_sources([(src, "evil.il")])
    assert any(d.code == "PLC0131" and d.location.line == 1 for d in diags)


def test_native_pragma_in_a_plcopen_st_body():
    xml = """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">
 <fileHeader companyName="x" productName="x" productVersion="1" creationDateTime="2024-01-01T00:00:00"/>
 <contentHeader name="x"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo></contentHeader>
 <types><dataTypes/><pous>
  <pou name="P" pouType="program">
   <interface><localVars><variable name="x"><type><INT/></type></variable></localVars></interface>
   <body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">{native 'os:system'}
x := x + 1;</xhtml></ST></body>
  </pou>
 </pous></types>
 <instances><configurations/></instances>
</project>"""
    _, diags = check_sources([(xml, "evil.xml")])
    assert any(d.code == "PLC0131" for d in diags), [str(d) for d in diags]


def test_library_blocks_bind_only_through_the_registry():
    project, diags = check_sources([])
    assert not diags
    bound = {p.name: p.native for p in project.pous.values() if p.native}
    # RTC is kept only in an iec or matiec project that names it (ADR 0037)
    rtc, _ = check_sources([("{dialect 'matiec'}\nPROGRAM P VAR c : RTC; END_VAR END_PROGRAM",
                             "p.st")])
    assert rtc is not None and rtc.pous["RTC"].native == "RTC"
    bound["RTC"] = rtc.pous["RTC"].native
    # SFC_TIMER comes with the SFC library, loaded only for a project with a chart (ADR 0016)
    sfc, _ = check_sources([("PROGRAM P\nINITIAL_STEP S0: END_STEP\nEND_PROGRAM", "p.st")])
    assert sfc is not None and sfc.pous["SFC_TIMER"].native == "SFC_TIMER"
    bound["SFC_TIMER"] = sfc.pous["SFC_TIMER"].native
    assert set(bound.values()) == natives.names()
    assert all(name == key for name, key in bound.items())
    for key in bound.values():
        assert natives.resolve(key).__module__ in (
            "plclab.runtime.stdfb", "plclab.runtime.ctrlfb", "plclab.runtime.ctrlfb_signals")


def test_an_unregistered_name_is_refused():
    with pytest.raises(PlcError) as ei:
        natives.resolve("plclab.runtime.rt:HELPERS")
    assert ei.value.code == "PLC0130"


def test_library_blocks_still_run():
    plc = plclab.loads("PROGRAM P VAR t : TON; q : BOOL; END_VAR "
                       "t(IN := TRUE, PT := T#20ms); q := t.Q; END_PROGRAM")
    plc.scan(4)
    assert plc["q"] is True
