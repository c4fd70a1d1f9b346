"""Hostile content for every place user text can reach: each case is a set of source files.

The payloads name the sentinel module ``pwned_sentinel`` (importing it leaves a marker file),
the secret file ``../secret/hidden.txt`` and shell commands, so that an escape into Python, the
file system or a shell is seen by the checks of the suite, not only a crash.
"""

from __future__ import annotations

S = "pwned_sentinel"

# identifiers that mean something to Python or to the generated code
IDENTS = ["__import__", "self", "_G", "_P", "_I", "_Q", "_M", "_B", "_CTX", "v_X", "F_X", "P_X",
          "S_X", "_sync_in", "_sync_out", "_sync_init", "_LOC", "_test_0", "_body", "_copy", "__slots__", "__init__",
          "__class__", "__dict__", "__builtins__", "__name__", "_Globals", "_Programs", "None",
          "True_", "exec", "eval", "lambda_", "import_", "os", "sys", "_f32", "_math", "_t1",
          "_r1", "_pc", "n", "_wd", "_oob", "pwned_sentinel", "a" * 300, "X" + "_9" * 40,
          "__X", "_X__", "__", "_", "data", "dims", "_VLA", "_vla_ix"]

# ST string literals (as written in source) that try to close a Python literal
STRINGS = [
    f"'$'); __import__($'{S}$')#'",
    f"'\"\"\"); __import__(\"{S}\")#'",
    f"''''); import {S} #'",
    "'\\'); import os; os.system($'touch /tmp/x$')#'",
    f"'\\\\'; import {S}'",
    "'$00$0A$R$L$T$P$$'",
    "'\\x00\\n\\r'",
    f"'{{native $'{S}:X$'}}'",
    f"'(* {S} *)'",
    "'$N$'$'$'$'$'$N'",
]
WSTRINGS = [f'"$"); __import__($"{S}$")#"', '"\\u0000\\"\\"\\""']

PRAGMAS = [f"{{native '{S}:X'}}", f'{{native "{S}:X"}}', f"{{ native {S} }}",
           f"{{NATIVE '{S}'}}", "{native 'TON'}", "{native}", "{native 'os:system'}",
           f"{{attribute 'x' := '{S}'}}", "{attribute 'qualified_only'}", "{}",
           "{ {native 'nested'} }", f"{{native '../../{S}.py:main'}}",
           f"{{native 'plclab.grade.lab:Path'}} {{native '{S}'}}"]

COMMENTS = [f"(* *) *) __import__('{S}') *)", f"(* (* nested *) {S} *)",
            f"// \n import {S}\n", f"/* */ */ {S}", f"(* ''' \"\"\" {S} *)", "*)", "(*", "/*"]


def _prog(body: str, decls: str = "", name: str = "Main") -> str:
    return f"PROGRAM {name}\nVAR\n{decls}END_VAR\n{body}\nEND_PROGRAM\n"


def st_cases() -> list[tuple[str, dict[str, str]]]:
    cases: list[tuple[str, dict[str, str]]] = []
    for i, name in enumerate(IDENTS):
        cases.append((f"ident-var-{i}", {"p.st": _prog(f"{name} := {name} + 1;",
                                                        f"    {name} : INT;\n")}))
        cases.append((f"ident-pou-{i}", {"p.st": (
            f"FUNCTION {name} : INT\nVAR_INPUT {name}_in : INT; END_VAR\n"
            f"{name} := {name}_in * 2;\nEND_FUNCTION\n"
            f"FUNCTION_BLOCK FB_{name}\nVAR_INPUT {name} : INT; END_VAR\n"
            f"VAR_OUTPUT q_{name} : INT; END_VAR\nq_{name} := {name};\nEND_FUNCTION_BLOCK\n"
            + _prog(f"f({name} := 3); y := f.q_{name} + {name}({name}_in := 2);",
                    f"    f : FB_{name};\n    y : INT;\n"))}))
        cases.append((f"ident-type-{i}", {"p.st": (
            f"TYPE {name}_E : ({name}, other_{i}); END_TYPE\n"
            f"TYPE {name}_S : STRUCT {name} : INT; nested : {name}_E; END_STRUCT; END_TYPE\n"
            f"VAR_GLOBAL {name}_g : {name}_S; END_VAR\n"
            + _prog(f"s.{name} := 1; e := {name}; {name}_g.{name} := s.{name};"
                    f" IF e = {name} THEN s.nested := e; END_IF;",
                    f"    s : {name}_S;\n    e : {name}_E;\n", f"Prog_{i}"))}))
    for i, lit in enumerate(STRINGS):
        cases.append((f"string-{i}", {"p.st": _prog(
            f"s := {lit}; s := CONCAT(s, {lit}); n := LEN({lit});",
            f"    s : STRING[255] := {lit};\n    n : INT;\n")}))
    for i, lit in enumerate(WSTRINGS):
        cases.append((f"wstring-{i}", {"p.st": _prog(f"w := {lit};",
                                                      f"    w : WSTRING := {lit};\n")}))
    for i, prag in enumerate(PRAGMAS):
        cases.append((f"pragma-{i}", {"p.st": (
            f"{prag}\nFUNCTION_BLOCK Evil {prag}\nVAR_INPUT x : INT; END_VAR\n{prag}\n"
            "END_FUNCTION_BLOCK\n" + _prog(f"{prag} e(x := 1); {prag}", "    e : Evil;\n"))}))
    for i, com in enumerate(COMMENTS):
        cases.append((f"comment-{i}", {"p.st": _prog(f"x := 1; {com}\nx := 2;",
                                                      "    x : INT;\n")}))
    for i, lit in enumerate(STRINGS):
        cases.append((f"test-name-{i}", {"t.st": (
            _prog("x := x + 1;", "    x : INT;\n") +
            f"TEST {lit}\n  Main();\n  ASSERT_EQ(Main.x, 2);\n"
            f"  ASSERT_TRUE(LEN({lit}) > 1000);\nEND_TEST\n")}))
    cases.append(("config-names", {"p.st": (
        _prog("x := x + 1;", "    x : INT;\n", "__import__") +
        "CONFIGURATION __init__\n  RESOURCE _sync_in ON PLC\n"
        "    TASK __class__ (INTERVAL := T#10ms, PRIORITY := 1);\n"
        "    PROGRAM self WITH __class__ : __import__;\n  END_RESOURCE\nEND_CONFIGURATION\n")}))
    return cases


def il_cases() -> list[tuple[str, dict[str, str]]]:
    cases = []
    for i, name in enumerate(["__import__", "self", "_pc", "_G", "L1", "__X", "a" * 200,
                              "_sync_in", S]):
        cases.append((f"il-label-{i}", {"p.il": (
            f"PROGRAM Main\nVAR {name}_v : INT; b : BOOL; s : STRING; END_VAR\n"
            f"        LD b\n        JMPC {name}\n        LD {name}_v\n        ADD 1\n"
            f"        ST {name}_v\n{name}:\n        LD {STRINGS[0]}\n        ST s\n"
            f"        LD {name}_v\n        GT 5\n        JMPCN {name}\nEND_PROGRAM\n")}))
    cases.append(("il-pragma", {"p.il": (
        f"{PRAGMAS[0]}\nFUNCTION_BLOCK Evil\nVAR_INPUT i : INT; END_VAR\n"
        f"        LD i\n        ST i {PRAGMAS[1]}\nEND_FUNCTION_BLOCK\n")}))
    return cases


def ld_cases() -> list[tuple[str, dict[str, str]]]:
    cases = []
    for i, name in enumerate(["__import__", "self", "_G", "__X", "_P"]):
        cases.append((f"ld-names-{i}", {"p.ld": (
            f"PROGRAM Main\nVAR\n    {name} : BOOL;\n    q_{name} : BOOL;\n    s : STRING;\n"
            f"    t_{name} : TON;\nEND_VAR\n"
            f"|   {name}                          q_{name}\n"
            f"|---[ ]---[TON t_{name} PT:=T#1s]---( )---\n"
            f"|   {name}\n"
            f"|---[ ]---[MOVE {STRINGS[0]} -> s]---\nEND_PROGRAM\n")}))
    return cases


def _xml(pou_name: str, var_name: str, body: str, extra: str = "", doctype: str = "") -> str:
    return (f'<?xml version="1.0" encoding="utf-8"?>\n{doctype}'
            '<project xmlns="http://www.plcopen.org/xml/tc6_0201">\n'
            '<fileHeader companyName="x" productName="x" productVersion="1" '
            'creationDateTime="2024-01-01T00:00:00"/>\n'
            '<contentHeader name="x"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd>'
            '<ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc>'
            '</coordinateInfo></contentHeader>\n<types><dataTypes/><pous>\n'
            f'<pou name="{pou_name}" pouType="program">{extra}<interface><localVars>'
            f'<variable name="{var_name}"><type><INT/></type></variable>'
            '<variable name="s"><type><string/></type></variable></localVars></interface>'
            f'<body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">{body}</xhtml></ST></body>'
            "</pou>\n</pous></types>\n</project>\n")


def xml_cases(secret: str = "../secret/hidden.txt") -> list[tuple[str, dict[str, str]]]:
    q = "&quot;"
    names = [f"x{q}); __import__({q}{S}{q})#", "x&#10;y", "__import__", "_G", "__X",
             "x']; import os #", "a&amp;b", "x y", "&lt;script&gt;"]
    cases = []
    for i, n in enumerate(names):
        cases.append((f"xml-pou-name-{i}", {"p.xml": _xml(n, "v", "v := v + 1;")}))
        cases.append((f"xml-var-name-{i}", {"p.xml": _xml("Main", n, f"{n} := 1;")}))
    cases.append(("xml-cdata-end", {"p.xml": _xml(
        "Main", "v", f"<![CDATA[s := ']]]]><![CDATA[>'; (* ]]]]><![CDATA[> {S} *) v := 1;]]>")}))
    cases.append(("xml-string", {"p.xml": _xml("Main", "v", f"s := {STRINGS[0]}; v := 2;")}))
    cases.append(("xml-pragma", {"p.xml": _xml("Main", "v", f"{PRAGMAS[0]} v := 3;")}))
    cases.append(("xml-xxe", {"p.xml": _xml(
        "Main", "v", "s := '&xxe;'; v := 1;",
        doctype=f'<!DOCTYPE project [<!ENTITY xxe SYSTEM "{secret}">]>\n')}))
    cases.append(("xml-xxe-file-url", {"p.xml": _xml(
        "Main", "v", "s := '&xxe;';",
        doctype=f'<!DOCTYPE project [<!ENTITY xxe SYSTEM "file://{secret}">]>\n')}))
    laughs = "".join(f'<!ENTITY l{k} "{f"&l{k - 1};" * 10}">' for k in range(1, 9))
    cases.append(("xml-billion-laughs", {"p.xml": _xml(
        "Main", "v", "s := '&l8;';",
        doctype=f'<!DOCTYPE project [<!ENTITY l0 "lol">{laughs}]>\n')}))
    for i, n in enumerate(names):  # TC6 v2.00: the program named by <pouInstance type=...>
        cases.append((f"xml-v200-instance-type-{i}", {"p.xml": _xml(
            "Main", "v", "v := v + 1;").replace("</types>\n</project>", (
                '</types>\n<instances><configurations><configuration name="c"><resource '
                'name="r"><task name="t" interval="00:00:00.010000" priority="0"><pouInstance '
                f'name="i" type="{n}"/></task></resource></configuration></configurations>'
                "</instances>\n</project>"))}))
    logger = '<variable name="log"><type><derived name="LOGGER"/></type></variable>'
    cases.append(("xml-dropped-logger-call", {"p.xml": _xml(  # the call is left out (PLC0250)
        "Main", "v", f"log(TRIG := TRUE, MSG := {STRINGS[0]}, LEVEL := CRITICAL); v := 1;"
    ).replace('<variable name="s">', logger + '<variable name="s">')}))
    cases.append(("xml-attr-newline", {"p.xml": _xml(
        "Main", "v", "v := 1;", extra=f'<documentation><xhtml xmlns="http://www.w3.org/1999/'
        f'xhtml">{S}\n"""</xhtml></documentation>')}))
    return cases


def _sfc(sfc: str, extra: str = "") -> str:
    return _xml("Main", "v", "v := 1;", extra=extra).replace(
        '<body><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">v := 1;</xhtml></ST></body>',
        f"<body><SFC>{sfc}</SFC></body>")


def sfc_cases() -> list[tuple[str, dict[str, str]]]:
    """PLCopen <SFC> bodies whose localIds, names, targets, references, qualifiers and
    durations carry payloads (plclab/lang/frontends/plcopen_sfc.py generates its own names)."""
    q = "&quot;"
    evil = [f"1{q}); __import__({q}{S}{q})#", "x']; import os #", "__import__", "a&amp;b"]
    cases = []
    for i, e in enumerate(evil):
        cond = ('<condition><inline name=""><IL><xhtml xmlns="http://www.w3.org/1999/xhtml">'
                "LD TRUE</xhtml></IL></inline></condition>")
        wired = ('<leftPowerRail localId="L"/><contact localId="C"><connectionPointIn>'
                 '<connection refLocalId="L"/></connectionPointIn><variable>TRUE</variable>'
                 '</contact>')
        chart = (f'<step localId="{e}" name="Init" initialStep="true"/>'
                 f'<transition localId="t{e}"><connectionPointIn><connection refLocalId="{e}"/>'
                 f'</connectionPointIn>{cond}</transition>'
                 f'<step localId="s{e}" name="Next"><connectionPointIn><connection '
                 f'refLocalId="t{e}"/></connectionPointIn></step>{wired}'
                 f'<transition localId="u{e}"><connectionPointIn><connection '
                 f'refLocalId="s{e}"/></connectionPointIn><condition><connectionPointIn>'
                 '<connection refLocalId="C"/></connectionPointIn></condition></transition>'
                 f'<jumpStep localId="j{e}" targetName="Init"><connectionPointIn><connection '
                 f'refLocalId="u{e}"/></connectionPointIn></jumpStep>'
                 f'<actionBlock localId="a{e}"><connectionPointIn><connection refLocalId="{e}"/>'
                 '</connectionPointIn><action localId="0" qualifier="L" duration="T#1s">'
                 '<inline><ST><xhtml xmlns="http://www.w3.org/1999/xhtml">v := v + 1;</xhtml>'
                 '</ST></inline></action></actionBlock>')
        cases.append((f"sfc-local-id-{i}", {"p.xml": _sfc(chart)}))
        for where in ("step", "reference", "target", "qualifier", "action"):
            def f(field: str, default: str, where: str = where, e: str = e) -> str:
                return e if field == where else default
            names = (f'<step localId="1" name="{f("step", "Init")}" initialStep="true"/>'
                     '<transition localId="2"><connectionPointIn><connection refLocalId="1"/>'
                     f'</connectionPointIn><condition><reference name="{f("reference", "T1")}"'
                     f'/></condition></transition><jumpStep localId="3" targetName='
                     f'"{f("target", "Init")}"><connectionPointIn><connection refLocalId="2"/>'
                     '</connectionPointIn></jumpStep><actionBlock localId="4">'
                     '<connectionPointIn><connection refLocalId="1"/></connectionPointIn>'
                     f'<action localId="0" qualifier="{f("qualifier", "N")}"><reference '
                     f'name="{f("action", "A1")}"/></action></actionBlock>')
            extra = ('<transitions><transition name="T1"><body><ST><xhtml xmlns="http://www.w3.'
                     'org/1999/xhtml">:= v &gt; 0;</xhtml></ST></body></transition></transitions>'
                     '<actions><action name="A1"><body><ST><xhtml xmlns="http://www.w3.org/1999'
                     '/xhtml">v := v + 1;</xhtml></ST></body></action></actions>')
            cases.append((f"sfc-{where}-{i}", {"p.xml": _sfc(names, extra)}))
    return cases


def all_cases() -> list[tuple[str, dict[str, str]]]:
    return st_cases() + il_cases() + ld_cases() + xml_cases() + sfc_cases()


# file names a student can choose (each holds a valid program)
FILE_NAMES = ["a b.st", "it's.st", '"q".st', "new\nline.st", "$(touch pwned).st",
              "; rm -rf x.st", "=HYPERLINK(\"http://x\").st", "`id`.st", "--help.st",
              "\u202etxt.st", "x" * 200 + ".st", f"{S}.st", "__init__.st", "-.st"]
