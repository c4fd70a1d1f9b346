"""PLCopen XML import at size and against hostile files: large projects import and run (the
importer is linear, see benchmarks/plcopen_bench.py), long rungs and box chains never exhaust
Python's stack, and DOCTYPE/ENTITY declarations are refused with PLC0180."""

import pytest

import plclab
from plclab.errors import PlcError
from plclab.lang.frontends.plcopen import MAX_BOX_CHAIN, parse_plcopen_collect, parse_xml_safely
from plclab.project import check_sources

HEAD = ('<?xml version="1.0" encoding="utf-8"?>\n'
        '<project xmlns="http://www.plcopen.org/xml/tc6_0201">\n<types><dataTypes/><pous>\n')
RAIL = '<leftPowerRail localId="1"><position x="0" y="0"/><connectionPointOut/></leftPowerRail>'


def pou(variables: list[str], lang: str, body: list[str]) -> str:
    return (HEAD + '<pou name="P" pouType="program"><interface><localVars>\n' +
            "\n".join(variables) + f"\n</localVars></interface><body><{lang}>\n" +
            "\n".join(body) + f"\n</{lang}></body></pou>\n</pous></types></project>\n")


def var(name: str, ty: str = "BOOL") -> str:
    return f'<variable name="{name}"><type><{ty}/></type></variable>'


def cpi(ref: int) -> str:
    return f'<connectionPointIn><connection refLocalId="{ref}"/></connectionPointIn>'


def contact(lid: int, ref: int, name: str, extra: str = "") -> str:
    return (f'<contact localId="{lid}"{extra}><position x="{lid}" y="0"/>{cpi(ref)}'
            f'<connectionPointOut/><variable>{name}</variable></contact>')


def coil(lid: int, ref: int, name: str) -> str:
    return (f'<coil localId="{lid}"><position x="{lid}" y="0"/>{cpi(ref)}'
            f'<connectionPointOut/><variable>{name}</variable></coil>')


def errors(text: str, file: str = "t.xml"):
    _, ds = check_sources([(text, file)])
    return [d for d in ds if d.severity == "error"]


def test_many_rungs_import_and_every_rung_runs():
    k = 1500  # 4,500 graphical elements and 4,500 variables
    variables = [var(f"{p}{i}") for i in range(k) for p in "abc"]
    body = [RAIL]
    for i in range(k):
        lid = 2 + 3 * i
        body += [contact(lid, 1, f"a{i}").replace('y="0"', f'y="{40 * i}"'),
                 contact(lid + 1, lid, f"b{i}", ' negated="true"').replace('y="0"', f'y="{40 * i}"'),
                 coil(lid + 2, lid + 1, f"c{i}").replace('y="0"', f'y="{40 * i}"')]
    plc = plclab.loads(pou(variables, "LD", body), "big.xml")
    for i in range(0, k, 3):
        plc[f"a{i}"] = True
    plc["b0"] = True
    plc.scan()
    got = [plc[f"c{i}"] for i in range(k)]
    assert got == [i % 3 == 0 and i != 0 for i in range(k)]


@pytest.mark.parametrize("k", [31, 32, 33, 65, 3000])
def test_a_long_series_rung_is_one_and_of_all_contacts(k):
    variables = [var(f"a{i}") for i in range(k)] + [var("q")]
    body = [RAIL] + [contact(i + 2, i + 1, f"a{i}") for i in range(k)] + [coil(k + 2, k + 1, "q")]
    plc = plclab.loads(pou(variables, "LD", body), "series.xml")
    for i in range(k):
        plc[f"a{i}"] = True
    plc.scan()
    assert plc["q"] is True
    for off in (0, k // 2, k - 1):  # any open contact breaks the rung, wherever it is
        plc[f"a{off}"] = False
        plc.scan()
        assert plc["q"] is False
        plc[f"a{off}"] = True
    plc.scan()
    assert plc["q"] is True


def test_an_edge_contact_inside_a_long_series_rung_pulses_once():
    k = 70
    variables = [var(f"a{i}") for i in range(k)] + [var("q")]
    body = [RAIL] + [contact(i + 2, i + 1, f"a{i}", ' edge="rising"' if i == 50 else "")
                     for i in range(k)] + [coil(k + 2, k + 1, "q")]
    plc = plclab.loads(pou(variables, "LD", body), "edge.xml")
    for i in range(k):
        plc[f"a{i}"] = i != 50
    plc.scan()
    plc["a50"] = True
    qs = []
    for _ in range(3):
        plc.scan()
        qs.append(plc["q"])
    assert qs == [True, False, False]


def fbd_chain(n: int) -> str:
    body = ['<inVariable localId="1"><position x="0" y="0"/><connectionPointOut/>'
            '<expression>x</expression></inVariable>']
    prev, lid = 1, 2
    for i in range(n):
        body += [f'<inVariable localId="{lid}"><position x="{i}" y="40"/><connectionPointOut/>'
                 '<expression>1</expression></inVariable>',
                 f'<block localId="{lid + 1}" typeName="ADD"><position x="{i}" y="0"/>'
                 f'<inputVariables><variable formalParameter="IN1">{cpi(prev)}</variable>'
                 f'<variable formalParameter="IN2">{cpi(lid)}</variable></inputVariables>'
                 '<inOutVariables/><outputVariables><variable formalParameter="OUT">'
                 '<connectionPointOut/></variable></outputVariables></block>']
        prev, lid = lid + 1, lid + 2
    body.append(f'<outVariable localId="{lid}"><position x="{n}" y="0"/>{cpi(prev)}'
                '<expression>y</expression></outVariable>')
    return pou([var("x", "INT"), var("y", "INT")], "FBD", body)


def test_a_chain_of_function_boxes_up_to_the_limit_computes():
    plc = plclab.loads(fbd_chain(MAX_BOX_CHAIN), "chain.xml")
    plc["x"] = 5
    plc.scan()
    assert plc["y"] == 5 + MAX_BOX_CHAIN


@pytest.mark.parametrize("n", [MAX_BOX_CHAIN + 1, 5000])
def test_a_longer_chain_of_function_boxes_is_plc0181(n):
    errs = errors(fbd_chain(n), "chain.xml")
    assert [e.code for e in errs] == ["PLC0181"]
    assert "intermediate result" in errs[0].message and errs[0].location.file == "chain.xml"


def test_expression_errors_keep_their_place_in_a_large_file():
    k = 400
    variables = [var(f"a{i}") for i in range(k)] + [var("q")]
    body = [RAIL] + [contact(i + 2, 1, f"a{i}") for i in range(k)]
    body.append('<coil localId="999"><position x="0" y="0"/>' + cpi(2) +
                '<connectionPointOut/><variable>q @ a1</variable></coil>')
    text = pou(variables, "LD", body)
    _, ds = parse_plcopen_collect(text, "where.xml")
    line_no, line = next((i, t) for i, t in enumerate(text.split("\n"), 1) if "q @ a1" in t)
    assert ds and ds[0].code == "PLC0001"
    assert (ds[0].location.line, ds[0].location.col) == (line_no, line.index("@") + 1)


def test_an_st_body_on_a_late_line_reports_its_own_line_and_column():
    text = pou([var(f"v{i}") for i in range(300)], "ST",
               ["<![CDATA[v1 := TRUE;", "  v2 := ?;]]>"])
    errs = errors(text)
    line_no, line = next((i, t) for i, t in enumerate(text.split("\n"), 1) if "v2 := ?" in t)
    assert errs[0].location.line == line_no and errs[0].location.col == line.index("?") + 1


LAUGHS = ('<?xml version="1.0"?>\n<!DOCTYPE lolz [\n <!ENTITY lol "lol">\n' +
          "".join(f' <!ENTITY lol{i + 1} "' + f"&lol{i if i else ''};" * 10 + '">\n'
                  for i in range(9)) +
          ']>\n<project xmlns="http://www.plcopen.org/xml/tc6_0201">&lol9;</project>\n')


@pytest.mark.parametrize("text", [
    LAUGHS,
    '<?xml version="1.0"?>\n<!DOCTYPE project SYSTEM "file:///etc/passwd">\n'
    '<project xmlns="http://www.plcopen.org/xml/tc6_0201"/>\n',
    '<?xml version="1.0"?>\n<!DOCTYPE p [<!ENTITY x SYSTEM "file:///etc/hostname">]>\n'
    '<project xmlns="http://www.plcopen.org/xml/tc6_0201">&x;</project>\n',
    '<?xml version="1.0"?>\n<!DOCTYPE p [<!ENTITY % x SYSTEM "http://127.0.0.1:9/x"> %x;]>\n'
    '<project xmlns="http://www.plcopen.org/xml/tc6_0201"/>\n',
])
def test_doctype_and_entities_are_refused(text):
    errs = errors(text, "evil.xml")
    assert [e.code for e in errs] == ["PLC0180"]
    assert "DOCTYPE" in errs[0].message and errs[0].location.line == 2
    with pytest.raises(PlcError) as exc:
        parse_xml_safely(text, "evil.xml")
    assert exc.value.code == "PLC0180"


def test_an_undeclared_entity_is_malformed_xml():
    text = '<project xmlns="http://www.plcopen.org/xml/tc6_0201">&xxe;</project>'
    errs = errors(text)
    assert [e.code for e in errs] == ["PLC0180"] and "well-formed" in errs[0].message


def test_the_ladder_drawing_refuses_a_doctype_too():
    from plclab.viz.ladder_svg import render_xml

    with pytest.raises(PlcError) as exc:
        render_xml(LAUGHS)
    assert exc.value.code == "PLC0180"


@pytest.mark.parametrize("kind,depth", [("struct", 329), ("array", 983), ("struct", 40),
                                        ("array", 33)])
def test_deeply_nested_types_are_plc0124_not_a_recursion_error(kind, depth):
    """PLCopen XML nests types as elements; beyond 32 levels it stops with PLC0124 like ST."""
    inner = "<INT/>"
    for _ in range(depth):
        if kind == "struct":
            inner = f'<struct><variable name="f"><type>{inner}</type></variable></struct>'
        else:
            inner = (f'<array><dimension lower="0" upper="1"/><baseType>{inner}</baseType>'
                     '</array>')
    text = pou([f'<variable name="x"><type>{inner}</type></variable>'], "ST",
               ["<xhtml xmlns=\"http://www.w3.org/1999/xhtml\">x := x;</xhtml>"])
    with pytest.raises(PlcError) as e:
        _compile(text)
    assert e.value.code == "PLC0124" or any(d.code == "PLC0124" for d in e.value.diagnostics)


def _compile(text: str):
    import plclab

    return plclab.compile_sources([(text, "deep.xml")])
