"""PLCopen XML ``<SFC>`` bodies (plclab/lang/frontends/plcopen_sfc.py): the XML and the textual
washer give identical traces; every element kind (steps, jumps, macro steps, both kinds of
branches, action blocks, ST/IL/LD conditions inline, referenced and wired) and every code."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.project import check_sources

ROOT = Path(__file__).parent.parent.parent
LAB = ROOT / "labs" / "washing-machine" / "solution"
STEPS = ["Start", "Fill", "Boiling", "Warming", "Cooling", "Drain", "Abort"]
OUTPUTS = ["FILL_VALVE", "DRAIN_VALVE", "HEATER", "MOTOR"]
INPUTS = ["START_PB", "STOP_PB", "COTTON", "SILK", "LEVEL_SW", "EMPTY", "DOOR"]


def washer(suffix: str):
    path = LAB / f"washer.{suffix}"
    return plclab.loads(path.read_text(encoding="utf-8"), path.name, cycle_time="30s")


def state(plc) -> list:
    return [plc[f"Washer.{s}.X"] for s in STEPS] + [plc[f"Washer.{s}.T"] for s in STEPS] + \
        [plc[f"Washer.{o}"] for o in OUTPUTS]


# a 30 s cycle: Warming (5 min) ends after 10 scans, Boiling (10 min) after 20
@settings(max_examples=40, deadline=None, database=None)
@given(st.lists(st.tuples(st.lists(st.booleans(), min_size=7, max_size=7),
                          st.sampled_from([0, 11059, 11060, 27648])),
                min_size=1, max_size=80))
def test_the_xml_and_the_textual_washer_give_identical_traces(scans):
    text, xml = washer("st"), washer("xml")
    for n, (bits, temp) in enumerate(scans):
        for plc in (text, xml):
            for name, v in zip(INPUTS, bits, strict=True):
                plc[f"Washer.{name}"] = v
            plc["Washer.TEMP_RAW"] = temp
            plc.scan()
        assert state(text) == state(xml), f"scan {n}"


def test_a_whole_cotton_cycle_runs_the_same_in_both_forms():
    """A scripted cycle reaches every step of the cotton branch in both forms."""
    seen = set()
    text, xml = washer("st"), washer("xml")
    script = [dict(START_PB=True, STOP_PB=True, COTTON=True, DOOR=True)] + \
        [dict(START_PB=False, LEVEL_SW=True)] + [{}] * 21 + [dict(TEMP_RAW=10000)] + \
        [dict(EMPTY=True)] + [{}]
    for inputs in script:
        for plc in (text, xml):
            for k, v in inputs.items():
                plc[f"Washer.{k}"] = v
            plc.scan()
        assert state(text) == state(xml)
        seen |= {s for s in STEPS if xml[f"Washer.{s}.X"]}
    assert seen == {"Start", "Fill", "Boiling", "Cooling", "Drain"}


# -- element kinds ------------------------------------------------------------------------
HEAD = """<?xml version="1.0"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201" xmlns:xhtml="http://www.w3.org/1999/xhtml">
<types><pous><pou name="Main" pouType="program">
<interface><localVars>
  <variable name="go"><type><BOOL/></type></variable>
  <variable name="a"><type><BOOL/></type></variable>
  <variable name="b"><type><BOOL/></type></variable>
  <variable name="lamp"><type><BOOL/></type></variable>
  <variable name="n"><type><INT/></type></variable>
</localVars></interface>
"""
TAIL = "</pou></pous></types></project>\n"


def project(sfc: str, extra: str = "") -> str:
    return f"{HEAD}{extra}<body><SFC>\n{sfc}\n</SFC></body>\n{TAIL}"


def step(lid, name, src=None, initial=False):
    cpi = f'<connectionPointIn><connection refLocalId="{src}"/></connectionPointIn>' \
        if src is not None else ""
    ini = ' initialStep="true"' if initial else ""
    return f'<step localId="{lid}" name="{name}"{ini}>{cpi}<connectionPointOut/></step>'


def trans(lid, src, cond, x=0, prio=None):
    p = f' priority="{prio}"' if prio is not None else ""
    return (f'<transition localId="{lid}"{p}><position x="{x}" y="0"/>'
            f'<connectionPointIn><connection refLocalId="{src}"/></connectionPointIn>'
            f'<connectionPointOut/><condition>{cond}</condition></transition>')


def inline(text):
    return f'<inline name=""><ST><xhtml:p><![CDATA[{text}]]></xhtml:p></ST></inline>'


def bar(kind, lid, *srcs):
    ins = "".join(f'<connectionPointIn><connection refLocalId="{s}"/></connectionPointIn>'
                  for s in srcs)
    return f'<{kind} localId="{lid}">{ins}<connectionPointOut/></{kind}>'


def jump(lid, src, target):
    return (f'<jumpStep localId="{lid}" targetName="{target}"><connectionPointIn>'
            f'<connection refLocalId="{src}"/></connectionPointIn></jumpStep>')


def load(xml: str):
    return plclab.loads(xml, "chart.xml")


def codes(xml: str) -> list[tuple[str, int]]:
    return [(d.code, d.location.line) for d in check_sources([(xml, "chart.xml")])[1]]


def test_simultaneous_branches_and_a_jump():
    xml = project("\n".join([
        step(1, "Idle", initial=True), trans(2, 1, inline("go")),
        bar("simultaneousDivergence", 3, 2), step(4, "PA", 3), step(5, "PB", 3),
        trans(6, 4, inline("a")), step(7, "PA2", 6),
        bar("simultaneousConvergence", 8, 7, 5), trans(9, 8, inline("b")),
        jump(10, 9, "Idle")]))
    plc = load(xml)
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.PA.X"] and plc["Main.PB.X"] and not plc["Main.Idle.X"]
    plc["Main.b"] = True
    plc.scan()
    assert plc["Main.PA.X"], "the convergence waits for PA2"
    plc["Main.a"] = True
    plc.scan()
    assert plc["Main.PA2.X"] and plc["Main.PB.X"]
    plc["Main.go"] = False
    plc.scan()
    assert plc["Main.Idle.X"] and not plc["Main.PA2.X"] and not plc["Main.PB.X"]


def test_selection_divergence_goes_left_to_right_unless_a_priority_says_otherwise():
    def chart(prio_right):
        return project("\n".join([
            step(1, "Idle", initial=True), bar("selectionDivergence", 2, 1),
            trans(3, 2, inline("go"), x=200), trans(4, 2, inline("go"), x=10,
                                                   prio=None if not prio_right else 5),
            step(5, "Right", 3), step(6, "Left", 4)]))
    plc = load(chart(False))
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.Left.X"] and not plc["Main.Right.X"]
    plc = load(chart(True))  # Left has a priority (5), Right none: Left still first
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.Left.X"]


def test_a_macro_step_is_expanded_in_place():
    inner = "\n".join([step(21, "M_in", initial=True), trans(22, 21, inline("a")),
                       step(23, "M_out", 22)])
    xml = project("\n".join([
        step(1, "Idle", initial=True), trans(2, 1, inline("go")),
        f'<macroStep localId="3" name="Macro"><connectionPointIn><connection refLocalId="2"/>'
        f'</connectionPointIn><connectionPointOut/><body><SFC>{inner}</SFC></body></macroStep>',
        trans(4, 3, inline("b")), step(5, "Done", 4)]))
    plc = load(xml)
    assert plc["Main.Idle.X"] and not plc["Main.M_in.X"], "only the chart's initial step"
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.M_in.X"]
    plc["Main.b"] = True
    plc.scan()
    assert plc["Main.M_in.X"], "the macro step is left from its exit step only"
    plc["Main.a"] = True
    plc.scan()
    plc.scan()
    assert plc["Main.Done.X"] and not plc["Main.M_out.X"]


ACTIONS = """<actions>
  <action name="CountST"><body><ST><xhtml:p><![CDATA[n := n + 1;]]></xhtml:p></ST></body></action>
  <action name="CountIL"><body><IL><xhtml:p><![CDATA[LD n
ADD 10
ST n]]></xhtml:p></IL></body></action>
</actions>
"""


def test_action_blocks_with_qualifiers_durations_and_inline_bodies():
    block = ('<actionBlock localId="9"><connectionPointIn><connection refLocalId="3"/>'
             '</connectionPointIn>'
             '<action localId="0" qualifier="N"><reference name="CountST"/></action>'
             '<action localId="1" qualifier="P"><reference name="CountIL"/></action>'
             '<action localId="2" qualifier="L" duration="PT0.03S"><reference name="lamp"/>'
             '</action>'
             '<action localId="3" qualifier="N"><inline><ST><xhtml:p><![CDATA[a := TRUE;]]>'
             '</xhtml:p></ST></inline></action></actionBlock>')
    xml = project("\n".join([step(1, "Idle", initial=True), trans(2, 1, inline("go")),
                             step(3, "Run", 2), block]), ACTIONS)
    plc = load(xml)
    plc["Main.go"] = True
    plc.scan()
    # N: +1; P: +10 (its pulse) — both bodies run in the activation scan
    assert plc["Main.n"] == 11 and plc["Main.lamp"] and plc["Main.a"]
    assert plc["Main.Run_INLINE1.Q"], "an inline action is named <STEP>_INLINE<n> (Beremiz)"
    plc.scan(3)
    assert not plc["Main.lamp"], "L for 30 ms (ISO duration PT0.03S)"


TRANSITIONS = """<transitions>
  <transition name="Beremiz"><body><ST><xhtml:p><![CDATA[:= a AND b;]]></xhtml:p></ST></body>
  </transition>
  <transition name="Codesys"><body><ST><xhtml:p><![CDATA[a OR b]]></xhtml:p></ST></body>
  </transition>
  <transition name="Stmts"><body><ST><xhtml:p><![CDATA[Stmts := a; IF b THEN Stmts := FALSE;
END_IF;]]></xhtml:p></ST></body></transition>
  <transition name="InIL"><body><IL><xhtml:p><![CDATA[LD a
ANDN b]]></xhtml:p></IL></body></transition>
  <transition name="InFBD"><body><FBD>
    <inVariable localId="1"><connectionPointOut/><expression>a</expression></inVariable>
    <outVariable localId="2"><connectionPointIn><connection refLocalId="1"/></connectionPointIn>
      <expression>InFBD</expression></outVariable>
  </FBD></body></transition>
</transitions>
"""


@pytest.mark.parametrize("ref, truth", [
    ("Beremiz", lambda a, b: a and b), ("Codesys", lambda a, b: a or b),
    ("Stmts", lambda a, b: a and not b), ("InIL", lambda a, b: a and not b),
    ("InFBD", lambda a, b: a)])
def test_referenced_conditions_in_st_il_and_fbd(ref, truth):
    xml = project("\n".join([step(1, "Idle", initial=True),
                             trans(2, 1, f'<reference name="{ref}"/>'), step(3, "Next", 2)]),
                  TRANSITIONS)
    for a in (False, True):
        for b in (False, True):
            plc = load(xml)
            plc["Main.a"], plc["Main.b"] = a, b
            plc.scan()
            assert plc["Main.Next.X"] == truth(a, b), (ref, a, b)


def test_a_transition_referenced_twice_and_an_inline_il_condition():
    xml = project("\n".join([
        step(1, "Idle", initial=True), trans(2, 1, '<reference name="Stmts"/>'),
        step(3, "Mid", 2), trans(4, 3, '<reference name="Stmts"/>'), step(5, "End", 4),
        trans(6, 5, '<inline name=""><IL><xhtml:p><![CDATA[LDN a]]></xhtml:p></IL></inline>'),
        jump(7, 6, "Idle")]), TRANSITIONS)
    plc = load(xml)
    plc["Main.a"] = True
    plc.scan(2)
    assert plc["Main.End.X"]
    plc["Main.a"] = False
    plc.scan()
    assert plc["Main.Idle.X"]


def test_an_ld_condition_wired_in_the_sfc_body():
    ld = ('<leftPowerRail localId="20"><connectionPointOut formalParameter=""/></leftPowerRail>'
          '<contact localId="21"><connectionPointIn><connection refLocalId="20"/>'
          '</connectionPointIn><connectionPointOut/><variable>a</variable></contact>'
          '<contact localId="22" negated="true"><connectionPointIn><connection refLocalId="21"/>'
          '</connectionPointIn><connectionPointOut/><variable>b</variable></contact>')
    cond = '<connectionPointIn><connection refLocalId="22"/></connectionPointIn>'
    xml = project("\n".join([step(1, "Idle", initial=True), ld, trans(2, 1, cond),
                             step(3, "Next", 2)]))
    plc = load(xml)
    plc["Main.a"], plc["Main.b"] = True, True
    plc.scan()
    assert plc["Main.Idle.X"]
    plc["Main.b"] = False
    plc.scan()
    assert plc["Main.Next.X"]


def test_a_condition_wired_the_tc6_v200_way_without_connection_point_in():
    """TC6 v2.00 files (Beremiz 2008, tests/linux/test_master_DS401GUI) put the <connection>
    in <condition> itself; v2.01 wraps it in <connectionPointIn>. Both read the same."""
    ld = ('<leftPowerRail localId="20"><connectionPointOut formalParameter=""/></leftPowerRail>'
          '<contact localId="21"><connectionPointIn><connection refLocalId="20"/>'
          '</connectionPointIn><connectionPointOut/><variable>a</variable></contact>')
    xml = project("\n".join([step(1, "Idle", initial=True), ld,
                             trans(2, 1, '<connection refLocalId="21"/>'), step(3, "Next", 2)]))
    plc = load(xml)
    plc.scan()
    assert plc["Main.Idle.X"]
    plc["Main.a"] = True
    plc.scan()
    assert plc["Main.Next.X"]


# -- diagnostics ----------------------------------------------------------------------------
@pytest.mark.parametrize("sfc, extra, code", [
    # a transition fed by a transition
    (step(1, "Idle", initial=True) + "\n" + trans(2, 1, inline("go")) + "\n" +
     trans(3, 2, inline("go")) + "\n" + step(4, "X", 3), "", "PLC0184"),
    # a transition leading nowhere
    (step(1, "Idle", initial=True) + "\n" + trans(2, 1, inline("go")), "", "PLC0184"),
    # a reference to a transition that is not there
    (step(1, "Idle", initial=True) + "\n" + trans(2, 1, '<reference name="Nope"/>') + "\n" +
     step(3, "X", 2), TRANSITIONS, "PLC0185"),
    # no condition at all
    (step(1, "Idle", initial=True) + "\n" + '<transition localId="2"><connectionPointIn>'
     '<connection refLocalId="1"/></connectionPointIn></transition>' + "\n" + step(3, "X", 2),
     "", "PLC0186"),
    # a macro step without a body
    (step(1, "Idle", initial=True) + "\n" + trans(2, 1, inline("go")) + "\n" +
     '<macroStep localId="3" name="M"><connectionPointIn><connection refLocalId="2"/>'
     '</connectionPointIn></macroStep>', "", "PLC0188"),
    # an FBD block among the steps, wired to nothing
    (step(1, "Idle", initial=True) + "\n" + '<label localId="5" label="L"/>', "", "PLC0189"),
    # a jump to a step that does not exist: the chart check names it
    (step(1, "Idle", initial=True) + "\n" + trans(2, 1, inline("go")) + "\n" +
     jump(3, 2, "Nowhere"), "", "PLC0150"),
])
def test_broken_charts_are_reported_with_a_code_at_the_element(sfc, extra, code):
    xml = project(sfc, extra)
    found = [(c, line) for c, line in codes(xml) if c == code]
    assert found, codes(xml)
    assert found[0][1] > 1


def test_a_graphical_transition_body_must_write_the_transition():
    bad = TRANSITIONS.replace("<expression>InFBD</expression>", "<expression>a</expression>")
    xml = project("\n".join([step(1, "Idle", initial=True),
                             trans(2, 1, '<reference name="InFBD"/>'), step(3, "Next", 2)]), bad)
    found = [c for c, _ in codes(xml)]
    assert "PLC0186" in found


def test_beremiz_defaults_an_action_without_qualifier_is_n_and_initial_false_is_a_step():
    """Beremiz writes ``<action localId="0">`` without a qualifier (the schema's default N)
    and ``initialStep="false"`` (the shape of its first_steps example, written anew)."""
    block = ('<actionBlock localId="9"><connectionPointIn><connection refLocalId="3"/>'
             '</connectionPointIn><action localId="0"><relPosition x="0" y="0"/><inline><ST>'
             '<xhtml:p><![CDATA[n := n + 1;]]></xhtml:p></ST></inline></action></actionBlock>')
    xml = project("\n".join([step(1, "Idle", initial=True), trans(2, 1, inline("go")),
                             step(3, "Run", 2).replace('name="Run"',
                                                       'name="Run" initialStep="false"'),
                             trans(4, 3, inline("NOT go")), jump(5, 4, "Idle"), block]),
                  "<actions/>")
    plc = load(xml)
    plc["Main.go"] = True
    plc.scan(3)
    assert plc["Main.n"] == 3
    plc["Main.go"] = False
    plc.scan(2)
    assert plc["Main.n"] == 4 and plc["Main.Idle.X"], "N: one final scan after the step"
