"""PLCopen FBD bodies: negated and edge-triggered pins, in-out variables and pins, pin names in
any case, jumps, labels, returns, execution order (explicit or topological), diagnostics at
the element, Beremiz runtime blocks skipped with a warning."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))  # importlib mode: the builders next door
from plcopen_xml import block, conn, invar, outvar, pos, program, project, var  # noqa: E402

import plclab  # noqa: E402
from plclab.project import check_sources  # noqa: E402

BOOLS = "".join(var(n) for n in ("a", "b", "c", "x", "y", "z"))


def load(body: str, variables: str = BOOLS, extra_pous: str = ""):
    return plclab.loads(project(program(body, variables) + extra_pous), "t.xml")


def diagnostics(body: str, variables: str = BOOLS):
    return check_sources([(project(program(body, variables)), "t.xml")])[1]


def run(plc, steps: list[dict], watch: tuple[str, ...]) -> list[tuple]:
    out = []
    for inputs in steps:
        for k, v in inputs.items():
            plc[f"P.{k}"] = v
        plc.scan()
        out.append(tuple(plc[f"P.{w}"] for w in watch))
    return out


def test_negated_input_and_output_pins():
    body = (invar(1, "a") + invar(2, "b", y=40)
            + block(3, "AND", {"IN1": (1, None), "IN2": (2, None)}, ["OUT"],
                    pin_attrs={"IN2": ' negated="true"', "OUT": ' negated="true"'})
            + outvar(4, "y", 3, "OUT"))
    plc = load(body)
    got = run(plc, [dict(a=a, b=b) for a in (False, True) for b in (False, True)], ("y",))
    assert got == [(not (a and not b),) for a in (False, True) for b in (False, True)]


@pytest.mark.parametrize("edge, expect", [("rising", [False, True, False, False, False]),
                                          ("falling", [False, False, False, True, False])])
def test_edge_triggered_input_pin_is_true_for_one_scan(edge, expect):
    body = (invar(1, "a") + block(2, "OR", {"IN1": (1, None), "IN2": (3, None)}, ["OUT"],
                                  pin_attrs={"IN1": f' edge="{edge}"'})
            + invar(3, "FALSE", y=40) + outvar(4, "y", 2, "OUT"))
    plc = load(body)
    got = run(plc, [dict(a=v) for v in (False, True, True, False, False)], ("y",))
    assert [g[0] for g in got] == expect


def test_pin_names_are_case_insensitive():
    body = (invar(1, "a") + invar(2, "b", y=40)
            + block(3, "Or", {"in1": (1, None), "In2": (2, None)}, ["out"])
            + outvar(4, "y", 3, "Out"))
    plc = load(body)
    assert run(plc, [dict(a=False, b=True), dict(a=False, b=False)], ("y",)) == \
        [(True,), (False,)]


def test_in_out_variable_is_written_then_read():
    body = (invar(1, "a") + block(2, "NOT", {"IN": (1, None)}, ["OUT"])
            + outvar(3, "x", 2, "OUT", tag="inOutVariable", x=200)
            + block(4, "AND", {"IN1": (3, None), "IN2": (5, None)}, ["OUT"], x=300)
            + invar(5, "b", y=60) + outvar(6, "y", 4, "OUT", x=400))
    plc = load(body)
    assert run(plc, [dict(a=False, b=True), dict(a=True, b=True)], ("x", "y")) == \
        [(True, True), (False, False)]


def test_in_out_pin_of_a_function_block():
    bump = ('<pou name="BUMP" pouType="functionBlock"><interface><inOutVars>'
            + var("n", "INT") + '</inOutVars></interface><body><ST>n := n + 1;</ST></body></pou>')
    body = (invar(1, "k") + block(2, "BUMP", {}, [], instance="b1",
                                  inouts={"N": (1, None)})
            + outvar(3, "m", 2, "N", x=300))
    variables = var("k", "INT") + var("m", "INT") + var("b1", '<derived name="BUMP"/>')
    plc = load(body, variables, bump)
    plc.scan()
    plc.scan()
    assert (plc["P.k"], plc["P.m"]) == (2, 2)


def test_jump_and_label_skip_the_networks_between():
    body = (invar(1, "a") + '<jump localId="2" label="Skip">' + pos(100, 0) + conn(1) + '</jump>'
            + invar(3, "TRUE", y=100) + outvar(4, "y", 3, y=100)
            + '<label localId="5" label="skip">' + pos(0, 200) + '</label>'
            + invar(6, "b", y=300) + outvar(7, "z", 6, y=300))
    plc = load(body)
    assert run(plc, [dict(a=True, b=True)], ("y", "z")) == [(False, True)]
    assert run(plc, [dict(a=False, b=False)], ("y", "z")) == [(True, False)]


def test_return_ends_the_body_when_its_input_is_true():
    body = (invar(1, "a") + '<return localId="2">' + pos(100, 0) + conn(1) + '</return>'
            + invar(3, "b", y=100) + outvar(4, "y", 3, y=100))
    plc = load(body)
    assert run(plc, [dict(a=True, b=True), dict(a=False, b=True)], ("y",)) == \
        [(False,), (True,)]


def trig_net(out_y: int, block_y: int, eo_out: int = 0, eo_block: int = 0) -> str:
    return (invar(1, "a", y=block_y)
            + block(2, "R_TRIG", {"CLK": (1, None)}, ["Q"], instance="r", y=block_y, eo=eo_block)
            + outvar(3, "y", 2, "Q", y=out_y, eo=eo_out))


VARS_TRIG = BOOLS + var("r", '<derived name="R_TRIG"/>')


def test_topological_rule_runs_a_block_before_the_variable_it_feeds():
    plc = load(trig_net(out_y=0, block_y=100), VARS_TRIG)  # the output drawn above the block
    assert run(plc, [dict(a=False), dict(a=True), dict(a=True)], ("y",)) == \
        [(False,), (True,), (False,)]


def test_execution_order_ids_are_followed_as_written():
    plc = load(trig_net(out_y=0, block_y=100, eo_out=1, eo_block=2), VARS_TRIG)
    # the output is evaluated first: it shows the pulse of the previous scan
    assert run(plc, [dict(a=False), dict(a=True), dict(a=True)], ("y",)) == \
        [(False,), (False,), (True,)]


def test_comments_are_ignored():
    body = ('<comment localId="9" height="20" width="80">' + pos(0, 0)
            + '<content><xhtml:p xmlns:xhtml="http://www.w3.org/1999/xhtml">hi</xhtml:p>'
            '</content></comment>' + invar(1, "a") + outvar(2, "y", 1))
    plc = load(body)
    assert run(plc, [dict(a=True)], ("y",)) == [(True,)]


def test_pin_without_a_name_is_located_at_the_element():
    body = (invar(1, "a") + block(3, "NOT", {"": (1, None)}, ["OUT"], x=120, y=40)
            + outvar(4, "y", 3, "OUT"))
    ds = [d for d in diagnostics(body) if d.severity == "error"]
    assert ds[0].code == "PLC0183"
    assert "<block> (localId 3 at x=120 y=40)" in ds[0].message
    assert ds[0].location.file == "t.xml" and ds[0].location.line > 0


def test_unknown_pin_is_reported_at_the_block():
    body = (invar(1, "a") + block(3, "R_TRIG", {"CLOCK": (1, None)}, ["Q"], instance="r",
                                  x=120, y=40) + outvar(4, "y", 3, "Q"))
    text = project(program(body, VARS_TRIG))
    errs = [d for d in check_sources([(text, "t.xml")])[1] if d.severity == "error"]
    assert errs and "CLOCK" in errs[0].message
    line = next(i for i, t in enumerate(text.split("\n"), 1) if "<block" in t)
    assert errs[0].location.line == line


def test_edge_on_a_variable_is_refused():
    body = invar(1, "a", extra=' edge="rising"') + outvar(2, "y", 1)
    ds = [d for d in diagnostics(body) if d.severity == "error"]
    assert ds[0].code == "PLC0183" and "localId 1" in ds[0].message


def test_beremiz_runtime_blocks_are_skipped_with_a_warning():
    body = (invar(1, "a") + block(2, "python_eval", {"TRIG": (1, None), "CODE": (5, None)},
                                  ["ACK", "RESULT"], instance="py1")
            + invar(5, "'print(1)'", y=50) + outvar(3, "s", 2, "RESULT")
            + invar(6, "b", y=200) + outvar(7, "y", 6, y=200))
    variables = BOOLS + var("s", "<string/>") + var("py1", '<derived name="python_eval"/>')
    ds = check_sources([(project(program(body, variables)), "t.xml")])[1]
    assert [d.severity for d in ds if d.code == "PLC0250"] == ["warning", "warning"]
    assert not [d for d in ds if d.severity == "error"]
    plc = load(body, variables)
    assert run(plc, [dict(b=True)], ("y", "s")) == [(True, "")]


def test_a_project_that_declares_its_own_logger_uses_it():
    """Beremiz's tests/logging project declares a function block named LOGGER itself (its body
    calls C); a declared POU is the user's, not the runtime block, so it is not skipped."""
    logger = ('<pou name="LOGGER" pouType="functionBlock"><interface><inputVars>'
              + var("TRIG") + '</inputVars><outputVars>' + var("SEEN") + '</outputVars>'
              '</interface><body><ST><![CDATA[IF TRIG THEN SEEN := TRUE; END_IF;]]></ST>'
              '</body></pou>')
    body = (invar(1, "a") + block(2, "LOGGER", {"TRIG": (1, None)}, ["SEEN"], instance="log")
            + outvar(3, "y", 2, "SEEN"))
    variables = BOOLS + var("log", '<derived name="LOGGER"/>')
    text = project(program(body, variables) + logger)
    assert not [d for d in check_sources([(text, "t.xml")])[1] if d.code == "PLC0250"]
    plc = plclab.loads(text, "t.xml")
    assert run(plc, [dict(a=False), dict(a=True), dict(a=False)], ("y",)) == [
        (False,), (True,), (True,)]


def test_a_loop_through_an_in_out_variable_reads_the_variable():
    """A counter drawn the Beremiz way: cnt -> ADD(1, cnt) -> SEL(G := reset, IN0 := sum,
    IN1 := 0) -> inOutVariable cnt -> outVariable out. The ADD reads the variable's value."""
    body = (invar(1, "reset", y=0)
            + invar(6, "1", x=0, y=40)
            + block(4, "ADD", {"IN1": (6, None), "IN2": (3, None)}, ["OUT"], x=100, y=40)
            + invar(5, "0", x=100, y=120)
            + block(7, "SEL", {"G": (1, None), "IN0": (4, "OUT"), "IN1": (5, None)}, ["OUT"],
                    x=200, y=20)
            + outvar(3, "cnt", 7, "OUT", tag="inOutVariable", x=300, y=40)
            + outvar(2, "out", 3, x=400, y=40))
    variables = var("reset") + var("cnt", "INT") + var("out", "INT")
    plc = load(body, variables)
    got = []
    for r in (False, False, False, True, False):
        plc["P.reset"] = r
        plc.scan()
        got.append((plc["P.cnt"], plc["P.out"]))
    assert got == [(1, 1), (2, 2), (3, 3), (0, 0), (1, 1)]


def test_function_block_with_en_runs_only_when_enabled_and_eno_follows_en():
    body = (invar(1, "a") + invar(2, "b", y=40) + invar(5, "100", y=80)
            + block(3, "CTU", {"EN": (1, None), "CU": (2, None), "PV": (5, None)},
                    ["ENO", "Q", "CV"], instance="c1")
            + outvar(4, "y", 3, "ENO") + outvar(6, "n", 3, "CV", y=40))
    variables = BOOLS + var("n", "INT") + var("c1", '<derived name="CTU"/>')
    plc = load(body, variables)
    got = []
    for a, b in [(True, True), (True, False), (False, True), (False, False), (True, True)]:
        plc["P.a"], plc["P.b"] = a, b
        plc.scan()
        got.append((plc["P.y"], plc["P.n"]))
    # disabled, the counter does not see the rising edge of scan 3; enabled again, it sees
    # b rise against the value of its last run
    assert got == [(True, 1), (True, 1), (False, 1), (False, 1), (True, 2)]


def test_a_runtime_block_called_from_st_is_left_out_with_its_call():
    """Beremiz's tests/projects/modbus_test_tcp calls a LOGGER from an ST function block, with
    LEVEL := CRITICAL (an enumerated value of the runtime's LOGLEVEL): the call goes too."""
    st = ('<pou name="P" pouType="program"><interface><localVars>' + var("x") + var("n", "INT")
          + var("log", '<derived name="LOGGER"/>') + '</localVars></interface><body><ST>'
          '<![CDATA[IF x THEN\n  log(TRIG := TRUE, MSG := \'OK\', LEVEL := CRITICAL);\n'
          '  n := n + 1;\nEND_IF;]]></ST></body></pou>')
    text = project(st)
    ds = check_sources([(text, "t.xml")])[1]
    assert not [d for d in ds if d.severity == "error"]
    calls = [d for d in ds if d.code == "PLC0250" and "call of" in d.message]
    assert len(calls) == 1 and calls[0].location.line > 0
    plc = plclab.loads(text, "t.xml")
    assert run(plc, [dict(x=True), dict(x=True)], ("n",)) == [(1,), (2,)]


def test_beremiz_loglevel_is_declared_when_a_project_names_it():
    """Beremiz's NativeLib declares TYPE LOGLEVEL : (CRITICAL, WARNING, INFO, DEBUG) := INFO;
    projects use it undeclared (tests/projects/c_runtime); a project's own declaration wins."""
    variables = BOOLS + var("lvl", '<derived name="LOGLEVEL"/>')
    body = (invar(1, "lvl") + invar(2, "WARNING", y=40)
            + block(3, "EQ", {"IN1": (1, None), "IN2": (2, None)}, ["OUT"])
            + outvar(4, "y", 3, "OUT"))
    text = project(program(body, variables))
    assert not [d for d in check_sources([(text, "t.xml")])[1] if d.severity == "error"]
    plc = plclab.loads(text, "t.xml")
    assert run(plc, [{}], ("y",)) == [(False,)]  # INFO, the type's initial value
    own = text.replace("<dataTypes/>", '<dataTypes><dataType name="LOGLEVEL"><baseType><enum>'
                       '<values><value name="WARNING"/><value name="INFO"/></values></enum>'
                       '</baseType></dataType></dataTypes>')
    plc = plclab.loads(own, "t.xml")
    assert run(plc, [{}], ("y",)) == [(True,)]  # its first value, WARNING


def test_a_function_result_pin_without_a_name_is_its_result():
    """TC6 v2.00 files (Beremiz 2008) write a function block's result pin as
    formalParameter="" (v2.01: OUT), and wire from it without a formalParameter."""
    fn = ('<pou name="TWICE" pouType="function"><interface><returnType><INT/></returnType>'
          '<inputVars>' + var("X", "INT") + '</inputVars></interface><body><ST>'
          '<![CDATA[TWICE := X * 2;]]></ST></body></pou>')
    body = (invar(1, "n") + block(2, "TWICE", {"X": (1, None)}, [""]) + outvar(3, "m", 2))
    variables = BOOLS + var("n", "INT") + var("m", "INT")
    text = project(program(body, variables) + fn)
    assert not [d for d in check_sources([(text, "t.xml")])[1] if d.severity == "error"]
    plc = plclab.loads(text, "t.xml")
    assert run(plc, [dict(n=21)], ("m",)) == [(42,)]
    # an instance's pin still needs its name
    bad = project(program(invar(1, "a") + block(2, "R_TRIG", {"CLK": (1, None)}, [""],
                                                instance="r") + outvar(3, "y", 2),
                          BOOLS + var("r", '<derived name="R_TRIG"/>')))
    errs = [d for d in check_sources([(bad, "t.xml")])[1] if d.severity == "error"]
    assert errs and errs[0].code == "PLC0183"
