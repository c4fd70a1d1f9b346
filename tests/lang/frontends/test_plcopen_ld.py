"""PLCopen LD bodies: rails, contacts and coils of every kind, blocks in rungs with EN/ENO,
jumps, LD mixed with FBD elements; project data as Beremiz and OpenPLC Editor save it
(configurations, resources, tasks, global variables, addData)."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))  # importlib mode: the builders next door
from plcopen_xml import block, conn, invar, outvar, pos, program, project, var  # noqa: E402

import plclab  # noqa: E402

BOOLS = "".join(var(n) for n in ("a", "b", "c", "x", "y", "z"))


def rail(lid: int = 1) -> str:
    return f'<leftPowerRail localId="{lid}">{pos(0, 0)}<connectionPointOut formalParameter=""/>' \
           '</leftPowerRail>'


def contact(lid: int, v: str, src: int, y: int = 0, attrs: str = "", pin: str | None = None):
    return (f'<contact localId="{lid}"{attrs}>{pos(50, y)}{conn(src, pin)}<connectionPointOut/>'
            f'<variable>{v}</variable></contact>')


def coil(lid: int, v: str, src: int, y: int = 0, attrs: str = "", pin: str | None = None):
    return (f'<coil localId="{lid}"{attrs}>{pos(200, y)}{conn(src, pin)}<connectionPointOut/>'
            f'<variable>{v}</variable></coil>')


def load(body: str, variables: str = BOOLS):
    return plclab.loads(project(program(body, variables, lang="LD")), "t.xml")


def trace(plc, values: list[bool], watch: str) -> list:
    out = []
    for v in values:
        plc["P.a"] = v
        plc.scan()
        out.append(plc[f"P.{watch}"])
    return out


A = [False, True, True, False, False, True]


@pytest.mark.parametrize("attrs, expect", [
    ("", A),
    (' negated="true"', [not v for v in A]),
    (' edge="rising"', [False, True, False, False, False, True]),
    (' edge="falling"', [False, False, False, True, False, False]),
])
def test_contact_kinds(attrs, expect):
    plc = load(rail() + contact(2, "a", 1, attrs=attrs) + coil(3, "y", 2))
    assert trace(plc, A, "y") == expect


@pytest.mark.parametrize("attrs, expect", [
    ("", A),
    (' negated="true"', [not v for v in A]),
    (' storage="set"', [False, True, True, True, True, True]),
    (' edge="rising"', [False, True, False, False, False, True]),
    (' edge="falling"', [False, False, False, True, False, False]),
])
def test_coil_kinds(attrs, expect):
    plc = load(rail() + contact(2, "a", 1) + coil(3, "y", 2, attrs=attrs))
    assert trace(plc, A, "y") == expect


def test_reset_coil_clears_what_a_set_coil_latched():
    body = (rail() + contact(2, "a", 1) + coil(3, "y", 2, attrs=' storage="set"')
            + contact(4, "b", 1, y=60) + coil(5, "y", 4, y=60, attrs=' storage="reset"'))
    plc = load(body)
    got = []
    for a, b in [(True, False), (False, False), (False, True), (False, False)]:
        plc["P.a"], plc["P.b"] = a, b
        plc.scan()
        got.append(plc["P.y"])
    assert got == [True, True, False, False]


def test_block_in_a_rung_with_en_and_eno():
    """A contact feeds EN of an ADD box; ENO drives a coil; the sum goes to an outVariable
    (LD mixed with FBD elements, as Beremiz draws it)."""
    body = (rail() + contact(2, "a", 1)
            + block(3, "ADD", {"EN": (2, None), "IN1": (4, None), "IN2": (5, None)},
                    ["ENO", "OUT"], x=100)
            + invar(4, "n", y=40) + invar(5, "1", y=80)
            + outvar(6, "n", 3, "OUT", y=40) + coil(7, "y", 3, pin="ENO"))
    variables = BOOLS + var("n", "INT")
    plc = load(body, variables)
    got = []
    for v in (True, False, True):
        plc["P.a"] = v
        plc.scan()
        got.append((plc["P.n"], plc["P.y"]))
    assert got == [(1, True), (1, False), (2, True)]


def test_timer_block_in_a_rung():
    body = (rail() + contact(2, "a", 1)
            + block(3, "TON", {"IN": (2, None), "PT": (4, None)}, ["Q", "ET"], instance="t1")
            + invar(4, "T#30ms", y=40) + coil(5, "y", 3, pin="Q"))
    variables = BOOLS + var("t1", '<derived name="TON"/>')
    plc = load(body, variables)
    plc["P.a"] = True
    seen = []
    for _ in range(5):
        plc.scan()
        seen.append(plc["P.y"])
    assert seen[0] is False and seen[-1] is True


def test_jump_in_ladder_skips_the_rungs_before_its_label():
    body = (rail() + contact(2, "a", 1) + f'<jump localId="3" label="END">{pos(200, 0)}'
            f'{conn(2)}</jump>'
            + contact(4, "b", 1, y=60) + coil(5, "y", 4, y=60)
            + f'<label localId="6" label="end">{pos(0, 120)}</label>')
    plc = load(body)
    plc["P.a"], plc["P.b"] = True, True
    plc.scan()
    assert plc["P.y"] is False
    plc["P.a"] = False
    plc.scan()
    assert plc["P.y"] is True


def test_parallel_branches_join_at_a_coil():
    body = (rail() + contact(2, "a", 1) + contact(3, "b", 1, y=40)
            + '<coil localId="4">' + pos(200, 0) + '<connectionPointIn>'
            '<connection refLocalId="2"/><connection refLocalId="3"/></connectionPointIn>'
            '<connectionPointOut/><variable>y</variable></coil>')
    plc = load(body)
    got = []
    for a, b in [(False, False), (True, False), (False, True)]:
        plc["P.a"], plc["P.b"] = a, b
        plc.scan()
        got.append(plc["P.y"])
    assert got == [False, True, True]


BEREMIZ_STYLE = """<?xml version='1.0' encoding='utf-8'?>
<project xmlns:xhtml="http://www.w3.org/1999/xhtml" xmlns:xsd="http://www.w3.org/2001/XMLSchema"
         xmlns="http://www.plcopen.org/xml/tc6_0201">
  <fileHeader companyName="Beremiz" productName="Beremiz" productVersion="1"
              creationDateTime="2026-01-01T10:00:00"/>
  <contentHeader name="Unnamed"><coordinateInfo><fbd><scaling x="0" y="0"/></fbd>
    <ld><scaling x="0" y="0"/></ld><sfc><scaling x="0" y="0"/></sfc></coordinateInfo>
  </contentHeader>
  <types>
    <dataTypes/>
    <pous>
      <pou name="program0" pouType="program">
        <interface>
          <externalVars><variable name="Limit"><type><INT/></type></variable></externalVars>
          <localVars>
            <variable name="count"><type><INT/></type></variable>
            <variable name="full"><type><BOOL/></type>
              <documentation><xhtml:p><![CDATA[TRUE at the limit]]></xhtml:p></documentation>
            </variable>
          </localVars>
        </interface>
        <body>
          <FBD>
            <inVariable localId="1" executionOrderId="0" height="30" width="50" negated="false">
              <position x="20" y="40"/><connectionPointOut><relPosition x="50" y="15"/>
              </connectionPointOut><expression>count</expression>
            </inVariable>
            <inVariable localId="2" executionOrderId="0" height="30" width="20" negated="false">
              <position x="20" y="90"/><connectionPointOut><relPosition x="20" y="15"/>
              </connectionPointOut><expression>1</expression>
            </inVariable>
            <block localId="3" typeName="ADD" executionOrderId="0" height="60" width="60">
              <position x="120" y="30"/>
              <inputVariables>
                <variable formalParameter="IN1"><connectionPointIn><relPosition x="0" y="25"/>
                  <connection refLocalId="1"><position x="120" y="55"/><position x="70" y="55"/>
                  </connection></connectionPointIn></variable>
                <variable formalParameter="IN2"><connectionPointIn><relPosition x="0" y="50"/>
                  <connection refLocalId="2"/></connectionPointIn></variable>
              </inputVariables>
              <inOutVariables/>
              <outputVariables><variable formalParameter="OUT"><connectionPointOut>
                <relPosition x="60" y="25"/></connectionPointOut></variable></outputVariables>
            </block>
            <inOutVariable localId="4" executionOrderId="0" height="30" width="50"
                           negatedOut="false" negatedIn="false">
              <position x="220" y="40"/>
              <connectionPointIn><relPosition x="0" y="15"/>
                <connection refLocalId="3" formalParameter="Out"/></connectionPointIn>
              <connectionPointOut><relPosition x="50" y="15"/></connectionPointOut>
              <expression>count</expression>
            </inOutVariable>
            <block localId="5" typeName="GE" executionOrderId="0" height="60" width="60">
              <position x="320" y="30"/>
              <inputVariables>
                <variable formalParameter="IN1"><connectionPointIn>
                  <connection refLocalId="4"/></connectionPointIn></variable>
                <variable formalParameter="IN2"><connectionPointIn>
                  <connection refLocalId="6"/></connectionPointIn></variable>
              </inputVariables>
              <inOutVariables/>
              <outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable>
              </outputVariables>
            </block>
            <inVariable localId="6" executionOrderId="0" height="30" width="50" negated="false">
              <position x="220" y="90"/><connectionPointOut/><expression>Limit</expression>
            </inVariable>
            <outVariable localId="7" executionOrderId="0" height="30" width="50" negated="false">
              <position x="420" y="40"/>
              <connectionPointIn><connection refLocalId="5" formalParameter="OUT"/>
              </connectionPointIn><expression>full</expression>
            </outVariable>
            <comment localId="8" height="40" width="200"><position x="20" y="150"/>
              <content><xhtml:p><![CDATA[count up to Limit]]></xhtml:p></content>
            </comment>
          </FBD>
        </body>
        <addData><data name="http://www.beremiz.org/pou" handleUnknown="preserve">
          <anything/></data></addData>
      </pou>
    </pous>
  </types>
  <instances>
    <configurations>
      <configuration name="config">
        <resource name="resource1">
          <task name="task0" priority="0" interval="T#20ms">
            <pouInstance name="instance0" typeName="program0"/>
          </task>
        </resource>
        <globalVars constant="true">
          <variable name="Limit"><type><INT/></type>
            <initialValue><simpleValue value="3"/></initialValue></variable>
        </globalVars>
        <addData><data name="http://www.beremiz.org/config" handleUnknown="preserve"/></addData>
      </configuration>
    </configurations>
  </instances>
  <addData><data name="http://www.beremiz.org/project" handleUnknown="preserve"/></addData>
</project>
"""


def test_a_project_as_beremiz_saves_it_runs_with_its_task_and_globals():
    plc = plclab.loads(BEREMIZ_STYLE, "plc.xml")
    assert [t.name for t in plc.project.tasks] == ["TASK0"]
    got = []
    for _ in range(4):
        plc.scan()
        got.append((plc["instance0.count"], plc["instance0.full"]))
    assert got == [(1, False), (2, False), (3, True), (4, True)]


def test_a_contact_drives_a_block_input_without_a_coil():
    """LD mixed with FBD as Beremiz draws a counter: a contact on reset feeds G of SEL; the
    sum loops through the in-out variable cnt; no coil, no right rail."""
    body = (rail() + contact(9, "reset", 1)
            + invar(6, "1", y=40)
            + block(4, "ADD", {"IN1": (6, None), "IN2": (3, None)}, ["OUT"], x=100, y=40)
            + invar(5, "17", y=120)
            + block(7, "SEL", {"G": (9, None), "IN0": (4, "OUT"), "IN1": (5, None)}, ["OUT"],
                    x=200, y=20)
            + outvar(3, "cnt", 7, "OUT", tag="inOutVariable", x=300, y=40))
    variables = var("reset") + var("cnt", "INT")
    plc = load(body, variables)
    got = []
    for r in (False, False, True, False):
        plc["P.reset"] = r
        plc.scan()
        got.append(plc["P.cnt"])
    assert got == [1, 2, 17, 18]


def test_a_tc6_v200_project_names_its_program_with_type_and_its_interval_as_a_time():
    """Beremiz's projects before TC6 v2.01 (tests/linux/test_master, 2008): the namespace
    http://www.plcopen.org/xml/tc6.xsd, ``<pouInstance type=...>`` and the task interval as an
    ``xsd:time`` (``00:00:00.050000``)."""
    old = (BEREMIZ_STYLE.replace("http://www.plcopen.org/xml/tc6_0201",
                                 "http://www.plcopen.org/xml/tc6.xsd")
           .replace('interval="T#20ms"', 'interval="00:00:00.050000"')
           .replace('<pouInstance name="instance0" typeName="program0"/>',
                    '<pouInstance name="instance0" type="program0"/>'))
    assert 'type="program0"' in old and "00:00:00.050000" in old
    plc = plclab.loads(old, "plc.xml")
    assert [(t.name, t.interval.value) for t in plc.project.tasks] == [("TASK0", 50_000_000)]
    plc.scan()
    assert plc["instance0.count"] == 1
