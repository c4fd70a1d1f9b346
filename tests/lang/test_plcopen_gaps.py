"""PLCopen gaps of issue 40 (ADR 0053): unquoted STRING initial values, unconnected output
variables, feedback loops in FBD/LD networks, the LD/FBD word in SFC conditions."""

import pytest

import plclab
from plclab.project import check_sources

HEAD = """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201" xmlns:xhtml="http://www.w3.org/1999/xhtml">
  <fileHeader companyName="t" productName="t" productVersion="1" creationDateTime="2026-01-01T00:00:00"/>
  <contentHeader name="t"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo></contentHeader>
  <types><dataTypes/><pous>
"""
TAIL = "</pous></types><instances><configurations/></instances></project>\n"


def project(body: str, variables: str, kind: str = "program") -> str:
    return (HEAD + f'<pou name="P" pouType="{kind}"><interface><localVars>{variables}'
            f"</localVars></interface><body>{body}</body></pou>" + TAIL)


def var(name: str, ty: str = "BOOL", init: str | None = None) -> str:
    t = f"<{ty}/>" if not ty.startswith("<") else ty
    iv = f'<initialValue><simpleValue value="{init}"/></initialValue>' if init is not None else ""
    return f'<variable name="{name}"><type>{t}</type>{iv}</variable>'


def diags(text: str):
    return check_sources([(text, "t.xml")])[1]


def errors(text: str):
    return [d for d in diags(text) if d.severity == "error"]


ST_EMPTY = "<ST><xhtml:p>n := n;</xhtml:p></ST>"


# -- item 5: <simpleValue value="hello"/> on a STRING is a string -------------------------------
@pytest.mark.parametrize("ty,init,expected", [
    ("string", "hello", "hello"),
    ("string", "'quoted'", "quoted"),             # quoted values still work
    ("string", "it's $5", "it's $5"),             # quote and dollar escaped, read back as is
    ('<string length="20"/>', "hello world", "hello world"),
    ("wstring", "wide", "wide"),
    ("wstring", '"dq"', "dq"),
    ("string", "", ""),
])
def test_unquoted_string_initial_value_is_a_string(ty, init, expected):
    v = var("s", ty, init.replace('"', "&quot;").replace("'", "&apos;")) + var("n", "INT")
    plc = plclab.loads(project(ST_EMPTY, v), "s.xml")
    plc.scan()
    assert plc["s"] == expected


def test_unquoted_string_in_an_array_of_strings():
    ty = ('<array><dimension lower="0" upper="1"/><baseType><string/></baseType></array>')
    v = ('<variable name="a"><type>' + ty + '</type><initialValue><arrayValue>'
         '<value><simpleValue value="one"/></value><value><simpleValue value="two"/></value>'
         '</arrayValue></initialValue></variable>' + var("n", "INT"))
    plc = plclab.loads(project(ST_EMPTY, v), "s.xml")
    assert (plc["a[0]"], plc["a[1]"]) == ("one", "two")


def test_unquoted_value_on_a_non_string_is_still_an_expression():
    errs = errors(project(ST_EMPTY, var("n", "INT", "hello")))
    assert errs and "HELLO" in errs[0].message.upper()


# -- item 6: an unconnected outVariable writes nothing ------------------------------------------
def unconnected(target: str, ty: str) -> str:
    body = f"""<FBD>
      <inVariable localId="1"><position x="0" y="0"/><connectionPointOut/><expression>src</expression></inVariable>
      <outVariable localId="2"><position x="100" y="0"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><expression>copy</expression></outVariable>
      <outVariable localId="3"><position x="100" y="60"/><connectionPointIn/><expression>{target}</expression></outVariable>
    </FBD>"""
    return project(body, var("src", ty) + var("copy", ty) + var(target, ty, "TRUE" if ty == "BOOL" else "42"))


@pytest.mark.parametrize("ty", ["BOOL", "DINT"])
def test_unconnected_out_variable_is_left_out_with_a_warning(ty):
    text = unconnected("keep", ty)
    ds = diags(text)
    assert not [d for d in ds if d.severity == "error"], ds
    w = [d for d in ds if d.code == "PLC0331"]
    assert len(w) == 1 and w[0].severity == "warning" and "keep" in w[0].message
    assert "localId 3" in w[0].message and w[0].location.line == text.splitlines().index(
        next(ln for ln in text.splitlines() if 'localId="3"' in ln)) + 1
    plc = plclab.loads(text, "u.xml")
    plc["src"] = True if ty == "BOOL" else 7
    plc.scan(3)
    assert plc["keep"] == (True if ty == "BOOL" else 42)  # not overwritten with FALSE/0
    assert plc["copy"] == plc["src"]                      # the connected one still writes


# -- item 7: feedback loops ---------------------------------------------------------------------
def block(lid, typ, x, y, ins, outs=("OUT",), inst=None):
    def pin(p, r, fp, neg):
        n = ' negated="true"' if neg else ""
        f = f' formalParameter="{fp}"' if fp else ""
        return (f'<variable formalParameter="{p}"{n}><connectionPointIn>'
                f'<connection refLocalId="{r}"{f}/></connectionPointIn></variable>')

    iv = "".join(pin(*x) for x in ins)
    ov = "".join(f'<variable formalParameter="{p}"><connectionPointOut/></variable>'
                 for p in outs)
    name = f' instanceName="{inst}"' if inst else ""
    return (f'<block localId="{lid}" typeName="{typ}"{name}><position x="{x}" y="{y}"/>'
            f"<inputVariables>{iv}</inputVariables><inOutVariables/>"
            f"<outputVariables>{ov}</outputVariables></block>")


def invar(lid, expr, x=0, y=0):
    return (f'<inVariable localId="{lid}"><position x="{x}" y="{y}"/><connectionPointOut/>'
            f"<expression>{expr}</expression></inVariable>")


def outvar(lid, expr, ref, fp="", x=500, y=0):
    f = f' formalParameter="{fp}"' if fp else ""
    return (f'<outVariable localId="{lid}"><position x="{x}" y="{y}"/><connectionPointIn>'
            f'<connection refLocalId="{ref}"{f}/></connectionPointIn>'
            f"<expression>{expr}</expression></outVariable>")


def two_tons(order: bool = False) -> str:
    """A blinker: T1.IN := NOT T2.Q, T2.IN := T1.Q, both 50 ms (two TONs wired in a loop)."""
    body = "<FBD>" + invar(1, "T#50ms", 0, 100) + \
        block(2, "TON", 100, 0, [("IN", 3, "Q", True), ("PT", 1, "", False)], ("Q", "ET"), "T1") + \
        block(3, "TON", 300, 0, [("IN", 2, "Q", False), ("PT", 1, "", False)], ("Q", "ET"), "T2") + \
        outvar(4, "lamp", 2, "Q") + "</FBD>"
    v = var("T1", '<derived name="TON"/>') + var("T2", '<derived name="TON"/>') + var("lamp")
    return project(body, v)


def test_two_tons_in_a_loop_blink():
    """T1 runs first (top left): it reads T2.Q of the previous scan. The lamp stays off 50 ms
    (T1 timing), then on while T2 times 50 ms, plus one scan for each fed-back value."""
    text = two_tons()
    assert not errors(text), errors(text)
    plc = plclab.loads(text, "loop.xml")
    per = round(50_000_000 / plc.cycle_ns)  # scans in 50 ms
    seen = []
    for _ in range(6 * per):
        plc.scan()
        seen.append(plc["lamp"])
    runs, k = [], 0
    while k < len(seen):
        j = k
        while j < len(seen) and seen[j] == seen[k]:
            j += 1
        runs.append((seen[k], j - k))
        k = j
    assert runs[0] == (False, per)  # the first rise after exactly 50 ms
    full = runs[1:-1]
    assert len(full) >= 3, runs
    for _value, n in full:
        assert per <= n <= per + 2, runs  # 50 ms each, give or take the fed-back scan


def sr_latch(with_variable: bool) -> str:
    """q := s OR (q AND NOT r), drawn with a wire from the OR output back into the AND."""
    body = "<FBD>" + invar(1, "s", 0, 0) + invar(2, "r", 0, 100) + \
        block(3, "OR", 200, 0, [("IN1", 1, "", False), ("IN2", 4, "OUT", False)]) + \
        block(4, "AND", 100, 60, [("IN1", 3, "OUT", False), ("IN2", 2, "", True)])
    if with_variable:
        body += outvar(5, "q", 3, "OUT")
    else:  # the latch's state read only through a second box: a hidden BOOL holds it
        body += block(6, "AND", 300, 0, [("IN1", 3, "OUT", False), ("IN2", 3, "OUT", False)]) \
            + outvar(5, "q", 6, "OUT")
    return project(body + "</FBD>", var("s") + var("r") + var("q"))


@pytest.mark.parametrize("with_variable", [True, False])
def test_sr_latch_built_from_a_feedback(with_variable):
    text = sr_latch(with_variable)
    assert not errors(text), errors(text)
    plc = plclab.loads(text, "sr.xml")
    plc.scan(2)
    assert plc["q"] is False
    plc["s"] = True
    plc.scan()
    assert plc["q"] is True
    plc["s"] = False
    plc.scan(3)
    assert plc["q"] is True   # held by the feedback
    plc["r"] = True
    plc.scan(2)
    assert plc["q"] is False
    plc["r"] = False
    plc.scan(3)
    assert plc["q"] is False  # stays reset


def test_feedback_loop_nothing_holds_is_plc0330():
    """ADD feeding ADD feeding the first: no variable, no FB output, not BOOL: refused."""
    body = "<FBD>" + invar(1, "1", 0, 0) + \
        block(2, "ADD", 100, 0, [("IN1", 1, "", False), ("IN2", 3, "OUT", False)]) + \
        block(3, "ADD", 200, 0, [("IN1", 2, "OUT", False), ("IN2", 1, "", False)]) + "</FBD>"
    errs = errors(project(body, var("n", "INT")))
    assert [e.code for e in errs] == ["PLC0330"] and "ADD" in errs[0].message
    assert errs[0].location.line > 1


def test_same_loop_with_a_feedback_variable_counts():
    body = "<FBD>" + invar(1, "1", 0, 0) + \
        block(2, "ADD", 100, 0, [("IN1", 1, "", False), ("IN2", 3, "OUT", False)]) + \
        block(3, "ADD", 200, 0, [("IN1", 2, "OUT", False), ("IN2", 1, "", False)]) + \
        outvar(4, "n", 3, "OUT") + "</FBD>"
    text = project(body, var("n", "INT"))
    assert not errors(text), errors(text)
    plc = plclab.loads(text, "c.xml")
    plc.scan(5)
    assert plc["n"] == 10  # n := (1 + n_prev) + 1 each scan


def test_fbd_condition_in_an_sfc_body_is_called_fbd():
    """An SFC body with LD elements elsewhere: an FBD condition's feedback is named FBD."""
    sfc = """<SFC>
      <leftPowerRail localId="90"><position x="0" y="400"/><connectionPointOut formalParameter=""/></leftPowerRail>
      <step localId="1" name="S0" initialStep="true"><position x="0" y="0"/><connectionPointIn/><connectionPointOut formalParameter=""/></step>
      <transition localId="2"><position x="0" y="50"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><connectionPointOut/>
        <condition><connectionPointIn><connection refLocalId="11" formalParameter="OUT"/></connectionPointIn></condition></transition>
      """ + block(10, "ADD", 100, 50, [("IN1", 11, "OUT", False), ("IN2", 12, "", False)]) + \
        block(11, "ADD", 200, 50, [("IN1", 10, "OUT", False), ("IN2", 12, "", False)]) + \
        invar(12, "1", 50, 50) + """
      <step localId="3" name="S1"><position x="0" y="100"/><connectionPointIn><connection refLocalId="2"/></connectionPointIn><connectionPointOut formalParameter=""/></step>
      <jumpStep localId="4" targetName="S0"><position x="0" y="150"/><connectionPointIn><connection refLocalId="3"/></connectionPointIn></jumpStep>
    </SFC>"""
    errs = errors(project(sfc, var("n", "INT")))
    msg = " ".join(e.message for e in errs)
    assert "FBD network" in msg and "LD network" not in msg, msg


# -- item 14: one initial step per SFC network, in PLCopen too ----------------------------------
def sfc_network(base: int, first: str, second: str, cond: str, back: str, linked: str = ""):
    """Two steps and two inline-ST transitions, localIds from ``base``."""
    b = base
    return f"""
      <step localId="{b}" name="{first}" initialStep="true"><position x="{b}" y="0"/><connectionPointIn>{linked}</connectionPointIn><connectionPointOut formalParameter=""/></step>
      <transition localId="{b + 1}"><position x="{b}" y="50"/><connectionPointIn><connection refLocalId="{b}"/></connectionPointIn><connectionPointOut/>
        <condition><inline name=""><ST><xhtml:p>{cond}</xhtml:p></ST></inline></condition></transition>
      <step localId="{b + 2}" name="{second}"><position x="{b}" y="100"/><connectionPointIn><connection refLocalId="{b + 1}"/></connectionPointIn><connectionPointOut formalParameter=""/></step>
      <transition localId="{b + 3}"><position x="{b}" y="150"/><connectionPointIn><connection refLocalId="{b + 2}"/></connectionPointIn><connectionPointOut/>
        <condition><inline name=""><ST><xhtml:p>{back}</xhtml:p></ST></inline></condition></transition>
      <jumpStep localId="{b + 4}" targetName="{first}"><position x="{b}" y="200"/><connectionPointIn><connection refLocalId="{b + 3}"/></connectionPointIn></jumpStep>"""


def test_plcopen_sfc_body_with_two_networks_each_initial():
    body = "<SFC>" + sfc_network(10, "Idle", "Run", "go", "NOT go") + \
        sfc_network(30, "Empty", "Filling", "fill", "NOT fill") + "</SFC>"
    text = project(body, var("go") + var("fill"))
    assert not errors(text), errors(text)
    plc = plclab.loads(text, "two.xml")
    assert plc["Idle.X"] and plc["Empty.X"]
    plc["fill"] = True
    plc.scan()
    assert plc["Idle.X"] and plc["Filling.X"]


def test_plcopen_two_initial_steps_in_one_network_are_plc0152():
    body = "<SFC>" + sfc_network(10, "Idle", "Run", "go", "NOT go") + \
        sfc_network(30, "Empty", "Filling", "fill", "NOT fill") \
        .replace('<jumpStep localId="34" targetName="Empty">', '<jumpStep localId="34" targetName="Run">') \
        + "</SFC>"
    errs = errors(project(body, var("go") + var("fill")))
    assert [e.code for e in errs] == ["PLC0152"] and "EMPTY" in errs[0].message.upper()


def test_unconnected_in_out_variable_is_only_read():
    body = """<FBD>
      <inOutVariable localId="1"><position x="0" y="0"/><connectionPointIn/><connectionPointOut/><expression>keep</expression></inOutVariable>
      <outVariable localId="2"><position x="200" y="0"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><expression>copy</expression></outVariable>
    </FBD>"""
    text = project(body, var("keep", "INT", "42") + var("copy", "INT"))
    ds = diags(text)
    assert [d.code for d in ds if d.code == "PLC0331"] == ["PLC0331"], ds
    plc = plclab.loads(text, "io.xml")
    plc.scan(2)
    assert (plc["keep"], plc["copy"]) == (42, 42)


def test_feedback_with_explicit_execution_order():
    """Every acting element numbered (executionOrderId): the order is followed, the loop cut."""
    text = sr_latch(False)
    for lid, n in ((3, 2), (4, 1), (6, 3), (5, 4)):
        text = text.replace(f'localId="{lid}"', f'localId="{lid}" executionOrderId="{n}"', 1)
    assert not errors(text), errors(text)
    plc = plclab.loads(text, "eo.xml")
    plc["s"] = True
    plc.scan()
    plc["s"] = False
    plc.scan(3)
    assert plc["q"] is True
    plc["r"] = True
    plc.scan(2)
    assert plc["q"] is False
