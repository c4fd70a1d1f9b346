"""PLCopen XML (TC6 v2.01) import: data types, POU interfaces, ST/IL/LD/FBD bodies,
configurations, and the import diagnostics PLC0180-PLC0183 with XML locations."""

from pathlib import Path

import pytest

import plclab
from plclab.lang.frontends.plcopen import parse_plcopen, parse_plcopen_collect
from plclab.project import check_sources

EXAMPLES = Path(__file__).parent.parent.parent / "examples"


def project(pous: str, types: str = "", instances: str = "") -> str:
    return f"""<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201" xmlns:xhtml="http://www.w3.org/1999/xhtml">
  <fileHeader companyName="t" productName="t" productVersion="1" creationDateTime="2026-01-01T00:00:00"/>
  <contentHeader name="t"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo></contentHeader>
  <types>
    <dataTypes>{types}</dataTypes>
    <pous>
{pous}
    </pous>
  </types>
  <instances><configurations>{instances}</configurations></instances>
</project>
"""


def program(body: str, variables: str, name: str = "P") -> str:
    return f"""      <pou name="{name}" pouType="program">
        <interface><localVars>{variables}</localVars></interface>
        <body>{body}</body>
      </pou>"""


def var(name: str, ty: str = "BOOL", extra: str = "") -> str:
    t = f"<{ty}/>" if not ty.startswith("<") else ty
    return f'<variable name="{name}"{extra}><type>{t}</type></variable>'


BOOLS = "".join(var(n) for n in ("a", "b", "c", "x", "y"))


def errors(text: str, file: str = "t.xml"):
    _, ds = check_sources([(text, file)])
    return [d for d in ds if d.severity == "error"]


def test_mixed_project_imports_and_runs():
    plc = plclab.load(EXAMPLES / "project.xml")
    assert [t.name for t in plc.project.tasks] == ["FAST"]
    assert plc.project.programs[0][0] == "MAIN"
    assert [p.language for p in plc.project.pous.values() if p.name in ("CLAMP", "FLASHER",
                                                                          "MAIN")] == \
        ["ST", "IL", "ST"]
    plc["Main.raw"] = 120.0
    plc.scan()
    assert plc["Main.level"] == 80.0 and plc["Main.pct"] == 80   # global limits (5, 80)
    assert plc["Main.table[3]"] == 7 and plc.format("Main.mode") in ("AUTO", "Mode#AUTO")
    lamps = []
    for _ in range(60):  # 20 ms task: the IL flasher toggles every 500 ms
        plc.scan()
        lamps.append(plc["Main.lamp"])
    assert True in lamps and False in lamps
    plc["Main.raw"] = 50.0
    plc.scan(2)
    assert plc["Main.lamp"] is False


def test_ld_set_reset_edge_and_negated_coils():
    def contact(lid, ref, v, extra=""):
        return (f'<contact localId="{lid}" {extra}><position x="50" y="{lid * 40}"/>'
                f'<connectionPointIn><connection refLocalId="{ref}"/></connectionPointIn>'
                f'<connectionPointOut/><variable>{v}</variable></contact>')

    def coil(lid, ref, v, extra=""):
        return (f'<coil localId="{lid}" {extra}><position x="200" y="{ref * 40}"/>'
                f'<connectionPointIn><connection refLocalId="{ref}"/></connectionPointIn>'
                f'<connectionPointOut/><variable>{v}</variable></coil>')

    body = ("<LD><leftPowerRail localId=\"1\"><position x=\"0\" y=\"0\"/>"
            "<connectionPointOut formalParameter=\"\"/></leftPowerRail>" +
            contact(2, 1, "a") + coil(3, 2, "x", 'storage="set"') +
            contact(4, 1, "b") + coil(5, 4, "x", 'storage="reset"') +
            contact(6, 1, "c", 'edge="rising"') + coil(7, 6, "y") +
            coil(8, 2, "b", 'negated="true"') + "</LD>")
    plc = plclab.loads(project(program(body, BOOLS)), "ld.xml")
    rows = []
    for a, c in ((True, False), (False, True), (False, True), (False, False)):
        plc["a"], plc["c"] = a, c
        plc.scan()
        rows.append((plc["x"], plc["y"], plc["b"]))
    # order is top to bottom: b := NOT a (y=80) comes before the reset rung (y=160), so x is
    # reset in the very scan in which a falls; y pulses once on the rising edge of c
    assert rows == [(True, False, False), (False, True, True), (False, False, True),
                    (False, False, True)]


def test_fbd_functions_with_en_connectors_and_continuations():
    body = """<FBD>
      <inVariable localId="1"><position x="0" y="0"/><connectionPointOut/><expression>a</expression></inVariable>
      <inVariable localId="2"><position x="0" y="40"/><connectionPointOut/><expression>n</expression></inVariable>
      <inVariable localId="3"><position x="0" y="80"/><connectionPointOut/><expression>10</expression></inVariable>
      <block localId="4" typeName="ADD"><position x="100" y="40"/>
        <inputVariables>
          <variable formalParameter="EN"><connectionPointIn><connection refLocalId="1"/></connectionPointIn></variable>
          <variable formalParameter="IN1"><connectionPointIn><connection refLocalId="2"/></connectionPointIn></variable>
          <variable formalParameter="IN2"><connectionPointIn><connection refLocalId="3"/></connectionPointIn></variable>
        </inputVariables><inOutVariables/>
        <outputVariables><variable formalParameter="ENO"><connectionPointOut/></variable>
          <variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables>
      </block>
      <connector name="sum" localId="5"><position x="200" y="40"/>
        <connectionPointIn><connection refLocalId="4" formalParameter="OUT"/></connectionPointIn></connector>
      <continuation name="sum" localId="6"><position x="300" y="40"/><connectionPointOut/></continuation>
      <outVariable localId="7"><position x="400" y="40"/>
        <connectionPointIn><connection refLocalId="6"/></connectionPointIn><expression>m</expression></outVariable>
      <block localId="8" typeName="GT"><position x="100" y="140"/>
        <inputVariables>
          <variable formalParameter="IN1"><connectionPointIn><connection refLocalId="2"/></connectionPointIn></variable>
          <variable formalParameter="IN2"><connectionPointIn><connection refLocalId="3"/></connectionPointIn></variable>
        </inputVariables><inOutVariables/>
        <outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables>
      </block>
      <outVariable localId="9"><position x="400" y="140"/>
        <connectionPointIn><connection refLocalId="8" formalParameter="OUT"/></connectionPointIn><expression>x</expression></outVariable>
      <outVariable localId="10"><position x="400" y="200"/>
        <connectionPointIn><connection refLocalId="4" formalParameter="ENO"/></connectionPointIn><expression>y</expression></outVariable>
    </FBD>"""
    variables = BOOLS + var("n", "INT") + var("m", "INT")
    plc = plclab.loads(project(program(body, variables)), "fbd.xml")
    plc["n"] = 15
    plc.scan()
    assert (plc["m"], plc["x"], plc["y"]) == (0, True, False)  # EN FALSE: m not written
    plc["a"] = True
    plc.scan()
    assert (plc["m"], plc["y"]) == (25, True)


def test_xml_il_body_is_translated_with_jumps():
    body = """<IL><xhtml:p><![CDATA[
    LD a
    JMPCN skip
    LD 1
    ADD n
    ST n
skip:
    LD n
    GE 3
    ST x
]]></xhtml:p></IL>"""
    plc = plclab.loads(project(program(body, BOOLS + var("n", "INT"))), "il.xml")
    plc["a"] = True
    plc.scan(3)
    assert plc["n"] == 3 and plc["x"] is True


def test_types_and_initial_values():
    types = """<dataType name="Color"><baseType><enum><values><value name="Red"/>
      <value name="Green" value="5"/></values></enum></baseType></dataType>
      <dataType name="Pt"><baseType><struct>""" + var("x", "INT") + var("y", "INT") + \
        """</struct></baseType></dataType>
      <dataType name="Speed"><baseType><derived name="INT"/></baseType></dataType>
      <dataType name="Name"><baseType><string length="8"/></baseType></dataType>"""
    variables = ('<variable name="c"><type><derived name="Color"/></type><initialValue>'
                 '<simpleValue value="Green"/></initialValue></variable>'
                 '<variable name="pt"><type><derived name="Pt"/></type><initialValue><structValue>'
                 '<value member="y"><simpleValue value="4"/></value></structValue></initialValue>'
                 '</variable>'
                 '<variable name="s"><type><derived name="Speed"/></type></variable>'
                 '<variable name="nm"><type><derived name="Name"/></type><initialValue>'
                 "<simpleValue value=\"'abc'\"/></initialValue></variable>"
                 '<variable name="k"><type><INT/></type></variable>')
    body = "<ST><xhtml:p><![CDATA[k := pt.y + COLOR_TO_INT(c); s := LEN(nm);]]></xhtml:p></ST>"
    body = body.replace("COLOR_TO_INT(c)", "5")
    plc = plclab.loads(project(program(body, variables), types), "ty.xml")
    plc.scan()
    assert plc["k"] == 9 and plc["s"] == 3 and plc["pt.x"] == 0


def test_parse_plcopen_api():
    f = parse_plcopen((EXAMPLES / "bottle.xml").read_text(encoding="utf-8"), "bottle.xml")
    assert f.pous[0].name == "BOTTLE" and f.pous[0].language == "LD"
    assert f.pous[0].body  # translated


# --- diagnostics ---------------------------------------------------------------------------
def test_malformed_xml_is_plc0180_with_line():
    errs = errors("<?xml version='1.0'?>\n<project>\n<types>\n</project>\n")
    assert errs[0].code == "PLC0180" and errs[0].location.line == 4


def test_not_a_plcopen_project_is_plc0180():
    errs = errors("<?xml version='1.0'?>\n<root xmlns='urn:other'/>\n")
    assert errs[0].code == "PLC0180" and "<project" in errs[0].message


def test_sfc_body_is_read_as_a_chart_and_actions_outside_sfc_are_unsupported():
    text = project(program("<SFC><step localId=\"3\" name=\"Init\"/></SFC>", BOOLS))
    assert errors(text)[0].code == "PLC0152"  # read (tests/lang/test_plcopen_sfc.py): no initial step
    pou = program("<ST><xhtml:p>a := b;</xhtml:p></ST>", BOOLS).replace(
        "<body>", "<actions><action name=\"A1\"><body><ST><xhtml:p>a := TRUE;</xhtml:p></ST>"
        "</body></action></actions><body>")
    errs = errors(project(pou))
    assert errs[0].code == "PLC0181" and "<actions>" in errs[0].message


def test_unsupported_graphic_element_names_its_local_id():
    body = ('<LD><leftPowerRail localId="1"><position x="0" y="0"/><connectionPointOut/>'
            '</leftPowerRail>\n<actionBlock localId="17"><position x="10" y="10"/>'
            '<connectionPointIn><connection refLocalId="1"/></connectionPointIn></actionBlock>'
            '</LD>')
    text = project(program(body, BOOLS))
    errs = errors(text)
    assert errs[0].code == "PLC0181"
    assert "<actionBlock> (localId 17 at x=10 y=10)" in errs[0].message
    line = next(i for i, t in enumerate(text.split("\n"), 1) if "<actionBlock" in t)
    assert errs[0].location.line == line


def test_connection_to_missing_element_is_plc0182():
    body = ('<LD><leftPowerRail localId="1"><position x="0" y="0"/><connectionPointOut/>'
            '</leftPowerRail><coil localId="2"><position x="0" y="0"/><connectionPointIn>'
            '<connection refLocalId="99"/></connectionPointIn><connectionPointOut/>'
            '<variable>x</variable></coil></LD>')
    errs = errors(project(program(body, BOOLS)))
    assert errs[0].code == "PLC0182" and "99" in errs[0].message


def test_feedback_loop_through_bool_boxes_reads_the_previous_value():
    """AND -> NOT -> AND: a loop of BOOL boxes is cut, a hidden BOOL holds the fed-back value
    (ADR 0053); the refused loops are tested in test_plcopen_gaps.py (PLC0330)."""
    body = """<FBD>
      <block localId="1" typeName="AND"><position x="0" y="0"/><inputVariables>
        <variable formalParameter="IN1"><connectionPointIn><connection refLocalId="2" formalParameter="OUT"/></connectionPointIn></variable>
      </inputVariables><inOutVariables/><outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>
      <block localId="2" typeName="NOT"><position x="0" y="0"/><inputVariables>
        <variable formalParameter="IN"><connectionPointIn><connection refLocalId="1" formalParameter="OUT"/></connectionPointIn></variable>
      </inputVariables><inOutVariables/><outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>
    </FBD>"""
    assert not errors(project(program(body, BOOLS)))


@pytest.mark.parametrize("bad,word", [
    ('<variable name="1x"><type><BOOL/></type></variable>', "identifier"),
    ('<variable name="q"></variable>', "no <type>"),
    ('<variable name="q" address="%ZZ1"><type><BOOL/></type></variable>', "direct address"),
    ('<variable name="q"><type><pointer><baseType><INT/></baseType></pointer></type></variable>',
     "<pointer>"),
])
def test_bad_declarations(bad, word):
    errs = errors(project(program("<ST><xhtml:p>x := a;</xhtml:p></ST>", BOOLS + bad)))
    assert errs and errs[0].code in ("PLC0181", "PLC0183") and word in errs[0].message


@pytest.mark.parametrize("body", [
    "<ST><xhtml:p><![CDATA[x := a;\ny := undefinedVar;]]></xhtml:p></ST>",
    "\n  <ST>\n    <xhtml:p><![CDATA[x := a;\ny := undefinedVar;]]></xhtml:p>\n  </ST>\n",
    "<ST>x := a;\ny := undefinedVar;</ST>",
])
def test_st_errors_point_into_the_xml_file(body):
    text = project(program(body, BOOLS))
    errs = errors(text, "loc.xml")
    line = next(i for i, t in enumerate(text.split("\n"), 1) if "undefinedVar" in t)
    assert errs[0].code == "PLC0100" and errs[0].location.line == line
    assert errs[0].location.col == 6 and errs[0].location.file == "loc.xml"


def test_il_errors_point_into_the_xml_file():
    body = "<IL><xhtml:p><![CDATA[\n  LD a\n  ANDD b\n  ST x\n]]></xhtml:p></IL>"
    text = project(program(body, BOOLS))
    errs = errors(text)
    line = next(i for i, t in enumerate(text.split("\n"), 1) if "ANDD" in t)
    assert [e.code for e in errs] == ["PLC0141"] and errs[0].location.line == line


def test_collect_never_raises():
    f, ds = parse_plcopen_collect("not xml at all", "n.xml")
    assert ds and ds[0].code == "PLC0180" and f.pous == []
