"""Grammar-based generation of *valid* PLC programs, in ST, IL, text LD and PLCopen XML.

Every generator takes a ``random.Random`` and returns ``(text, filename)``. The programs are
small, typed and meant to pass the checker: a program the checker rejects is counted as
``rejected`` by the fuzzer (a generator gap or a checker bug to look at), never as a crash.
"""

from __future__ import annotations

import random
from xml.sax.saxutils import escape

INTS = {"SINT": (-128, 127), "INT": (-32768, 32767), "DINT": (-2**31, 2**31 - 1),
        "LINT": (-2**63, 2**63 - 1), "USINT": (0, 255), "UINT": (0, 65535),
        "UDINT": (0, 2**32 - 1), "BYTE": (0, 255), "WORD": (0, 65535), "DWORD": (0, 2**32 - 1)}
REALS = ("REAL", "LREAL")

# the variables of every generated program: name -> type
VARS = {"b0": "BOOL", "b1": "BOOL", "b2": "BOOL", "b3": "BOOL",
        "i0": "INT", "i1": "INT", "i2": "INT", "d0": "DINT", "d1": "DINT", "s0": "SINT",
        "u0": "UINT", "w0": "WORD", "l0": "LINT", "r0": "REAL", "r1": "REAL", "x0": "LREAL",
        "t0": "TIME", "str0": "STRING"}
ARRAY = "arr"  # ARRAY[0..9] OF INT
LOOP_VARS = ("k0", "k1", "k2")  # FOR control variables, never assigned elsewhere


def _int_lit(rng: random.Random, ty: str) -> str:
    lo, hi = INTS[ty]
    r = rng.random()
    if r < 0.5:
        v = rng.randint(max(lo, -20), min(hi, 20))
    elif r < 0.8:
        v = rng.randint(lo, hi)
    else:
        v = rng.choice([lo, hi, 0, 1])
    if ty in ("BYTE", "WORD", "DWORD") and rng.random() < 0.5:
        return f"{ty}#16#{v:X}"
    if ty in ("BYTE", "WORD", "DWORD") or rng.random() < 0.3:
        return f"{ty}#{v}"
    return f"({v})" if v < 0 else str(v)


def _real_lit(rng: random.Random, ty: str = "LREAL") -> str:
    """A REAL or LREAL literal (typed, so REAL functions of literals stay REAL)."""
    return f"{ty}#" + rng.choice(["0.0", "1.5", "-2.25", "1.0E3", "3.14159", "1.0E-5", "100.0",
                       f"{rng.uniform(-1000, 1000):.3f}"])


def _time_lit(rng: random.Random) -> str:
    return rng.choice(["T#0ms", "T#10ms", "T#1s", "T#1h2m3s4ms", "TIME#-5s", "T#2s_200ms",
                       f"T#{rng.randint(0, 5000)}ms"])


class StGen:
    """Random typed ST expressions and statements over :data:`VARS`."""

    def __init__(self, rng: random.Random, max_depth: int = 3) -> None:
        self.rng = rng
        self.max_depth = max_depth
        self.loop_depth = 0

    def vars_of(self, ty: str) -> list[str]:
        return [n for n, t in VARS.items() if t == ty]

    # -- expressions ----------------------------------------------------------------------
    def expr(self, ty: str, depth: int = 0) -> str:
        rng = self.rng
        leaf = depth >= self.max_depth or rng.random() < 0.3
        if ty == "BOOL":
            return self.bool_expr(depth, leaf)
        if ty in INTS:
            return self.int_expr(ty, depth, leaf)
        if ty in REALS:
            return self.real_expr(ty, depth, leaf)
        if ty == "TIME":
            if leaf or rng.random() < 0.5:
                return rng.choice([_time_lit(rng), "t0", "tm.ET", "tm.PT"])
            return f"({self.expr('TIME', depth + 1)} + {self.expr('TIME', depth + 1)})"
        if ty == "STRING":
            if leaf or rng.random() < 0.4:
                return rng.choice(["str0", "'abc'", "''", "'$'quoted$' $$ $N'", "'x'"])
            return rng.choice([f"CONCAT({self.expr('STRING', depth + 1)}, 'z')",
                               f"LEFT({self.expr('STRING', depth + 1)}, {rng.randint(0, 4)})"])
        raise ValueError(ty)

    def bool_expr(self, depth: int, leaf: bool) -> str:
        rng = self.rng
        if leaf:
            return rng.choice(self.vars_of("BOOL") + ["TRUE", "FALSE", "tm.Q", "ct.Q"])
        k = rng.randrange(6)
        if k == 0:
            return f"NOT {self.expr('BOOL', depth + 1)}"
        if k in (1, 2):
            op = rng.choice(["AND", "OR", "XOR", "&"])
            return f"({self.expr('BOOL', depth + 1)} {op} {self.expr('BOOL', depth + 1)})"
        ty = rng.choice(["INT", "DINT", "REAL", "TIME", "SINT"])
        op = rng.choice(["<", ">", "<=", ">=", "=", "<>"])
        return f"({self.expr(ty, depth + 1)} {op} {self.expr(ty, depth + 1)})"

    def int_expr(self, ty: str, depth: int, leaf: bool) -> str:
        rng = self.rng
        names = self.vars_of(ty) + (["arr[LIMIT(0, i0, 9)]", "ct.CV"] if ty == "INT" else [])
        if leaf:
            if names and rng.random() < 0.6:
                return rng.choice(names)
            return _int_lit(rng, ty)
        sub = lambda: self.expr(ty, depth + 1)  # noqa: E731
        k = rng.randrange(9)
        if k <= 2:
            bits = ty in ("BYTE", "WORD", "DWORD")
            op = rng.choice(["AND", "OR", "XOR"] if bits else ["+", "-", "*"])
            return f"({sub()} {op} {sub()})"
        if k == 3 and ty not in ("BYTE", "WORD", "DWORD"):
            op = rng.choice(["/", "MOD"])
            return f"({sub()} {op} {rng.choice(['1', '2', '3', '7'])})"
        if k == 4:
            f = rng.choice(["MIN", "MAX"])
            return f"{f}({sub()}, {sub()})"
        if k == 5:
            return f"SEL({self.expr('BOOL', depth + 1)}, {sub()}, {sub()})"
        if k == 6:
            src = rng.choice([t for t in ("INT", "DINT", "SINT", "REAL", "LREAL") if t != ty])
            return f"{src}_TO_{ty}({self.expr(src, depth + 1)})"
        if k == 7 and ty in ("BYTE", "WORD", "DWORD"):
            f = rng.choice(["SHL", "SHR", "ROL", "ROR"])
            return f"{f}({sub()}, {rng.randint(0, 9)})"
        if k == 7 and ty in ("INT", "DINT", "SINT", "LINT"):
            return f"ABS({sub()})"
        if k == 8 and ty == "WORD":  # partial access (IEC 61131-3 ed.3 Table 17)
            return "w0.%W0" if rng.random() < 0.5 else f"BYTE_TO_WORD(w0.%B{rng.randint(0, 1)})"
        return f"LIMIT({_int_lit(rng, ty)}, {sub()}, {_int_lit(rng, ty)})"

    def real_expr(self, ty: str, depth: int, leaf: bool) -> str:
        rng = self.rng
        if leaf:
            return rng.choice(self.vars_of(ty) + [_real_lit(rng, ty)])
        sub = lambda: self.expr(ty, depth + 1)  # noqa: E731
        k = rng.randrange(6)
        if k <= 2:
            return f"({sub()} {rng.choice(['+', '-', '*', '/'])} {sub()})"
        if k == 3:
            return f"{rng.choice(['SQRT', 'SIN', 'COS', 'ABS', 'EXP', 'LN', 'ATAN'])}({sub()})"
        if k == 4:
            src = rng.choice(["INT", "DINT", "SINT"])
            return f"{src}_TO_{ty}({self.expr(src, depth + 1)})"
        return f"EXPT({sub()}, {rng.randint(0, 3)})"

    # -- statements -----------------------------------------------------------------------
    def assignable(self) -> tuple[str, str]:
        rng = self.rng
        if rng.random() < 0.1:
            return f"arr[{rng.randint(0, 9)}]", "INT"
        name = rng.choice(list(VARS))
        return name, VARS[name]

    def stmts(self, n: int, depth: int = 0) -> list[str]:
        return [line for _ in range(n) for line in self.stmt(depth)]

    def stmt(self, depth: int) -> list[str]:
        rng = self.rng
        k = rng.randrange(12) if depth < 2 else 0
        ind = "    " * (depth + 1)
        if k <= 4:
            target, ty = self.assignable()
            return [f"{ind}{target} := {self.expr(ty)};"]
        if k == 5:
            out = [f"{ind}IF {self.expr('BOOL')} THEN"] + self.stmts(rng.randint(1, 3), depth + 1)
            if rng.random() < 0.5:
                out += [f"{ind}ELSIF {self.expr('BOOL')} THEN"] + self.stmts(1, depth + 1)
            if rng.random() < 0.5:
                out += [f"{ind}ELSE"] + self.stmts(1, depth + 1)
            return out + [f"{ind}END_IF;"]
        if k == 6:
            out = [f"{ind}CASE {self.expr('INT')} OF"]
            out += [f"{ind}1:"] + self.stmts(1, depth + 1)
            out += [f"{ind}2, 3:"] + self.stmts(1, depth + 1)
            out += [f"{ind}10..20:"] + self.stmts(1, depth + 1)
            if rng.random() < 0.5:
                out += [f"{ind}ELSE"] + self.stmts(1, depth + 1)
            return out + [f"{ind}END_CASE;"]
        if k == 7 and self.loop_depth < len(LOOP_VARS):
            v = LOOP_VARS[self.loop_depth]
            self.loop_depth += 1
            lo, hi = rng.randint(-3, 3), rng.randint(-3, 6)
            by = f" BY {rng.choice(['1', '2', '-1', '3'])}" if rng.random() < 0.5 else ""
            body = self.stmts(rng.randint(1, 2), depth + 1)
            self.loop_depth -= 1
            return [f"{ind}FOR {v} := {lo} TO {hi}{by} DO"] + body + [f"{ind}END_FOR;"]
        if k == 8 and self.loop_depth < len(LOOP_VARS):
            v = LOOP_VARS[self.loop_depth]
            self.loop_depth += 1
            body = self.stmts(1, depth + 1)
            self.loop_depth -= 1
            if rng.random() < 0.5:
                return ([f"{ind}{v} := 0;", f"{ind}WHILE {v} < {rng.randint(0, 5)} DO",
                         f"{ind}    {v} := {v} + 1;"] + body + [f"{ind}END_WHILE;"])
            return ([f"{ind}{v} := 0;", f"{ind}REPEAT", f"{ind}    {v} := {v} + 1;"] + body
                    + [f"{ind}UNTIL {v} >= {rng.randint(1, 4)} END_REPEAT;"])
        if k == 9:
            return [f"{ind}tm(IN := {self.expr('BOOL')}, PT := {_time_lit(rng)});"]
        if k == 10:
            return [f"{ind}ct(CU := {self.expr('BOOL')}, PV := {rng.randint(0, 5)});",
                    f"{ind}fb(x := {self.expr('INT')}, en := {self.expr('BOOL')});"]
        return [f"{ind}i1 := Twice(a := {self.expr('INT')});"]


def _decls(extra: str = "") -> str:
    lines = [f"    {n} : {t};" for n, t in VARS.items()]
    lines += [f"    {ARRAY} : ARRAY[0..9] OF INT;", "    tm : TON;", "    ct : CTU;",
              "    fb : Acc;"]
    lines += [f"    {v} : INT;" for v in LOOP_VARS]
    return "VAR\n" + "\n".join(lines) + extra + "\nEND_VAR\n"


LIBRARY_ST = """FUNCTION Twice : INT
VAR_INPUT a : INT; END_VAR
Twice := LIMIT(-16000, a, 16000) * 2;
END_FUNCTION

FUNCTION_BLOCK Acc
VAR_INPUT x : INT; en : BOOL; END_VAR
VAR_OUTPUT total : DINT; n : INT; END_VAR
IF en THEN total := total + x; n := n + 1; END_IF;
IF n > 1000 THEN n := 0; total := 0; END_IF;
END_FUNCTION_BLOCK
"""


def st_body(rng: random.Random) -> str:
    return "\n".join(StGen(rng).stmts(rng.randint(2, 10))) + "\n"


def gen_st(rng: random.Random) -> tuple[str, str]:
    """A valid ST program (with a FUNCTION, an FB and sometimes a TEST)."""
    text = LIBRARY_ST + "\nPROGRAM Main\n" + _decls() + st_body(rng) + "END_PROGRAM\n"
    if rng.random() < 0.3:
        text += ("\nTEST 'generated'\n    Main();\n    ASSERT_TRUE(Main.b0 OR NOT Main.b0);\n"
                 "END_TEST\n")
    return text, "gen.st"


# -- IL --------------------------------------------------------------------------------------
IL_BOOL = ["b0", "b1", "b2", "b3"]
IL_INT = ["i0", "i1", "i2"]


def il_body(rng: random.Random) -> str:
    """A valid IL body over BOOL and INT variables: loads, operators, stores, forward jumps,
    deferred operations, FB calls, functions with the current result as first argument."""
    out: list[str] = []
    labels = 0
    pending: list[str] = []
    for _ in range(rng.randint(1, 8)):
        if pending and rng.random() < 0.3:
            out.append(f"{pending.pop(0)}:")
        k = rng.randrange(6)
        if k <= 1:  # boolean
            out.append(f"LD{rng.choice(['', 'N'])} {rng.choice(IL_BOOL + ['TRUE', 'tm.Q'])}")
            for _ in range(rng.randint(0, 3)):
                op = rng.choice(["AND", "OR", "XOR", "ANDN", "ORN"])
                out.append(f"{op} {rng.choice(IL_BOOL)}")
            if rng.random() < 0.3:
                out += [f"AND( {rng.choice(IL_BOOL)}", f"OR {rng.choice(IL_BOOL)}", ")"]
            store = rng.choice(["ST", "STN", "S", "R", "JMPC", "JMPCN"])
            if store.startswith("JMP"):
                labels += 1
                pending.append(f"L{labels}")
                out.append(f"{store} L{labels}")
            else:
                out.append(f"{store} {rng.choice(IL_BOOL)}")
        elif k <= 3:  # arithmetic
            out.append(f"LD {rng.choice(IL_INT + [str(rng.randint(-100, 100))])}")
            for _ in range(rng.randint(0, 3)):
                op = rng.choice(["ADD", "SUB", "MUL"])
                out.append(f"{op} {rng.choice(IL_INT + [str(rng.randint(-9, 9))])}")
            if rng.random() < 0.3:
                out.append(f"LIMIT {rng.choice(IL_INT)}, 100")
            if rng.random() < 0.4:
                out.append(f"{rng.choice(['GT', 'LT', 'EQ', 'NE'])} {rng.choice(IL_INT)}")
                out.append(f"ST {rng.choice(IL_BOOL)}")
            else:
                out.append(f"ST {rng.choice(IL_INT)}")
        elif k == 4:
            out.append(f"CAL tm(IN := {rng.choice(IL_BOOL)}, PT := {_time_lit(rng)})")
        else:
            out += [f"LD {rng.choice(IL_BOOL)}", "ST ct.CU", f"LD {rng.randint(0, 5)}",
                    "ST ct.PV", "CAL ct", "LD ct.CV", f"ST {rng.choice(IL_INT)}"]
    out += [f"{lab}:" for lab in pending]
    if out[-1].endswith(":"):
        out.append(f"LD {rng.choice(IL_BOOL)}")
        out.append(f"ST {rng.choice(IL_BOOL)}")
    return "\n".join("        " + line if not line.endswith(":") else line for line in out) + "\n"


def gen_il(rng: random.Random) -> tuple[str, str]:
    return LIBRARY_ST + "PROGRAM Main\n" + _decls() + il_body(rng) + "END_PROGRAM\n", "gen.il"


# -- text LD ---------------------------------------------------------------------------------
def _ld_contact(rng: random.Random) -> tuple[str, str]:
    name = rng.choice(IL_BOOL + ["tm.Q", "ct.Q"])
    return name, rng.choice(["[ ]", "[/]", "[P]", "[N]"])


def _ld_rung(rng: random.Random) -> list[str]:
    """One rung: an optional parallel pair of contacts, contacts in series, a box, a coil."""
    names, wire = "|", "|"
    lower_names, lower_wire = None, None
    if rng.random() < 0.4:  # parallel branch of two contacts at the start
        a, ea = _ld_contact(rng)
        c, ec = _ld_contact(rng)
        width = max(len(a), len(c)) + 2
        names += "   " + a.ljust(width)
        wire += "---" + ea + "-" * (width - 3)
        lower_names = "|   " + c.ljust(width)
        lower_wire = "|---" + ec + "-" * (width - 3)
        names += " "
        wire += "+"
        lower_names += "|"
        lower_wire += "+"
    for _ in range(rng.randint(0, 3)):
        n, e = _ld_contact(rng)
        gap = max(len(n), 3) + 2
        names += "   " + n.ljust(gap)
        wire += "---" + e + "-" * (gap - 3)
    if rng.random() < 0.3:
        box = rng.choice([f"[TON tm PT:={_time_lit(rng)}]", f"[GT i0, {rng.randint(-5, 5)}]",
                          f"[MOVE {rng.randint(0, 9)} -> i1]", "[ADD i0, i2 -> i1]",
                          "[CTU ct PV:=3, CV=>i2]"])
        names += " " * (len(box) + 3)
        wire += "---" + box
    coil_name = rng.choice(IL_BOOL)
    coil = rng.choice(["( )", "(/)", "(S)", "(R)", "(P)", "(N)"])
    names += "   " + coil_name
    wire += "---" + coil + "---"
    out = [names.rstrip(), wire]
    if lower_names is not None:
        out += [lower_names.rstrip(), lower_wire]
    return out


def gen_ld(rng: random.Random) -> tuple[str, str]:
    rungs: list[str] = []
    for _ in range(rng.randint(1, 5)):
        rungs += _ld_rung(rng)
        if rng.random() < 0.5:
            rungs.append("")
    return LIBRARY_ST + "PROGRAM Main\n" + _decls() + "\n".join(rungs) + "\nEND_PROGRAM\n", "gen.ld"


# -- PLCopen XML -----------------------------------------------------------------------------
XML_TYPES = {"BOOL": "<BOOL/>", "INT": "<INT/>", "DINT": "<DINT/>", "SINT": "<SINT/>",
             "UINT": "<UINT/>", "WORD": "<WORD/>", "LINT": "<LINT/>", "REAL": "<REAL/>",
             "LREAL": "<LREAL/>", "TIME": "<TIME/>", "STRING": "<string/>"}


def _xml_var(name: str, type_xml: str) -> str:
    return f'<variable name="{name}"><type>{type_xml}</type></variable>'


def xml_project(pous: list[tuple[str, str, str, str]]) -> str:
    """A PLCopen project from (name, pouType, interface xml, body xml) tuples."""
    body = "".join(f'<pou name="{n}" pouType="{k}"><interface>{i}</interface>'
                   f"<body>{b}</body></pou>" for n, k, i, b in pous)
    return ('<?xml version="1.0" encoding="utf-8"?>\n'
            '<project xmlns="http://www.plcopen.org/xml/tc6_0201" '
            'xmlns:xhtml="http://www.w3.org/1999/xhtml">\n'
            '<fileHeader companyName="fuzz" productName="fuzz" productVersion="1" '
            'creationDateTime="2026-01-01T00:00:00"/>\n'
            '<contentHeader name="fuzz"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd>'
            '<ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc>'
            "</coordinateInfo></contentHeader>\n"
            f"<types><dataTypes/><pous>\n{body}\n</pous></types>\n</project>\n")


def _main_interface() -> str:
    vs = [_xml_var(n, XML_TYPES[t]) for n, t in VARS.items()]
    vs.append(_xml_var(ARRAY, '<array><dimension lower="0" upper="9"/><baseType><INT/>'
                       "</baseType></array>"))
    vs += [_xml_var("tm", '<derived name="TON"/>'), _xml_var("ct", '<derived name="CTU"/>'),
           _xml_var("fb", '<derived name="Acc"/>')]
    vs += [_xml_var(v, "<INT/>") for v in LOOP_VARS]
    return "<localVars>" + "".join(vs) + "</localVars>"


def gen_xml(rng: random.Random) -> tuple[str, str]:
    """The generated ST or IL body of Main inside a PLCopen project (escaped or as CDATA)."""
    lang = rng.choice(["ST", "IL"])
    text = st_body(rng) if lang == "ST" else il_body(rng)
    inner = f"<![CDATA[{text}]]>" if rng.random() < 0.5 else escape(text)
    pous = _xml_library() + [
        ("Main", "program", _main_interface(), f"<{lang}><xhtml:p>{inner}</xhtml:p></{lang}>"),
    ]
    return xml_project(pous), "gen.xml"


def _xml_library() -> list[tuple[str, str, str, str]]:
    """The FUNCTION Twice and the FUNCTION_BLOCK Acc of :data:`LIBRARY_ST` as PLCopen POUs."""
    twice = ('<inputVars><variable name="a"><type><INT/></type></variable></inputVars>'
             "</interface><interface>")
    acc_if = ("<inputVars>" + _xml_var("x", "<INT/>") + _xml_var("en", "<BOOL/>") +
              "</inputVars><outputVars>" + _xml_var("total", "<DINT/>") +
              _xml_var("n", "<INT/>") + "</outputVars>")
    return [
        ("Twice", "function", "<returnType><INT/></returnType>" + twice.split("</interface>")[0],
         "<ST><xhtml:p>Twice := LIMIT(-16000, a, 16000) * 2;</xhtml:p></ST>"),
        ("Acc", "functionBlock", acc_if,
         "<ST><xhtml:p>IF en THEN total := total + x; n := n + 1; END_IF;\n"
         "IF n &gt; 1000 THEN n := 0; total := 0; END_IF;</xhtml:p></ST>"),
    ]


# -- SFC ---------------------------------------------------------------------------------------
QUALIFIERS = ("N", "R", "S", "P", "P1", "P0", "L", "D", "SD", "DS", "SL")


def _chart(rng: random.Random) -> tuple[list[str], list[tuple[list[int], list[int], str, int | None]],
                                        dict[int, list[tuple[str, str, str | None]]], list[str]]:
    """A random chart: step names, transitions (from, to, condition, priority), the action
    associations of each step (action, qualifier, time) and the declared actions' bodies."""
    g = StGen(rng, max_depth=2)
    steps = [f"Step{k}" for k in range(rng.randint(2, 7))]
    trans = []
    for k in range(1, len(steps)):  # a spine, so every step is reachable
        trans.append(([rng.randrange(k)], [k], g.expr("BOOL"), None))
    for _ in range(rng.randint(0, 4)):  # loops, alternatives, parallel branches
        src = rng.sample(range(len(steps)), rng.choice([1, 1, 1, 2]) if len(steps) > 1 else 1)
        dst = rng.sample(range(len(steps)), rng.choice([1, 1, 2]) if len(steps) > 1 else 1)
        cond = rng.choice([g.expr("BOOL"), f"{steps[src[0]]}.T >= {_time_lit(rng)}",
                           f"{steps[src[0]]}.X AND b0"])
        trans.append((src, dst, cond, rng.choice([None, None, rng.randint(0, 3)])))
    bodies = [" ".join(StGen(rng, max_depth=2).stmts(rng.randint(1, 3)))
              for _ in range(rng.randint(0, 2))]
    assoc: dict[int, list[tuple[str, str, str | None]]] = {}
    names = [f"A{k}" for k in range(len(bodies))] + ["b1", "b2", "b3"]
    for k in range(len(steps)):
        for _ in range(rng.randint(0, 2)):
            q = rng.choice(QUALIFIERS)
            t = _time_lit(rng).replace("TIME#-5s", "T#5ms") if q in QUALIFIERS[6:] else None
            assoc.setdefault(k, []).append((rng.choice(names), q, t))
    return steps, trans, assoc, bodies


def gen_sfc(rng: random.Random) -> tuple[str, str]:
    """A random chart in textual SFC or as a PLCopen XML <SFC> body (single-source
    transitions only, divergences and jumps the way Beremiz draws them)."""
    steps, trans, assoc, bodies = _chart(rng)
    if rng.random() < 0.5:
        out = [LIBRARY_ST, "PROGRAM Main", _decls()]
        for k, name in enumerate(steps):
            acts = " ".join(f"{a}({q}{', ' + t if t else ''});" for a, q, t in assoc.get(k, []))
            out.append(f"{'INITIAL_STEP' if k == 0 else 'STEP'} {name}: {acts} END_STEP")
        for src, dst, cond, prio in trans:
            p = f" (PRIORITY := {prio})" if prio is not None else ""

            def lst(ix: list[int]) -> str:
                names = [steps[i] for i in ix]
                return names[0] if len(names) == 1 else "(" + ", ".join(names) + ")"
            out.append(f"TRANSITION{p} FROM {lst(src)} TO {lst(dst)} := {cond}; END_TRANSITION")
        out += [f"ACTION A{k}: {b} END_ACTION" for k, b in enumerate(bodies)]
        return "\n".join(out + ["END_PROGRAM", ""]), "gen_sfc.st"
    ids = iter(range(1, 10_000))
    sid = {k: next(ids) for k in range(len(steps))}
    els = []
    single = [(s[0], d, c, p) for s, d, c, p in trans]
    for k, name in enumerate(steps):
        cpi = ""
        ini = ' initialStep="true"' if k == 0 else ""
        els.append(f'<step localId="{sid[k]}" name="{name}"{ini}>{cpi}<connectionPointOut/></step>')
        acts = assoc.get(k, [])
        if acts:
            inner = "".join(f'<action localId="{j}" qualifier="{q}"'
                            + (f' duration="{t}"' if t else "")
                            + f'><reference name="{a}"/></action>'
                            for j, (a, q, t) in enumerate(acts))
            els.append(f'<actionBlock localId="{next(ids)}"><connectionPointIn><connection '
                       f'refLocalId="{sid[k]}"/></connectionPointIn>{inner}</actionBlock>')
    incoming: dict[int, list[int]] = {}
    for k in range(len(steps)):
        outs = [t for t in single if t[0] == k]
        src = sid[k]
        if len(outs) > 1:
            src = next(ids)
            els.append(f'<selectionDivergence localId="{src}"><connectionPointIn><connection '
                       f'refLocalId="{sid[k]}"/></connectionPointIn></selectionDivergence>')
        for x, (_, dst, cond, prio) in enumerate(outs):
            tid = next(ids)
            p = f' priority="{prio}"' if prio is not None else ""
            els.append(f'<transition localId="{tid}"{p}><position x="{x * 100}" y="0"/>'
                       f'<connectionPointIn><connection refLocalId="{src}"/></connectionPointIn>'
                       f'<connectionPointOut/><condition><inline name=""><ST><xhtml:p>'
                       f'<![CDATA[{cond}]]></xhtml:p></ST></inline></condition></transition>')
            if len(dst) > 1:
                did = next(ids)
                els.append(f'<simultaneousDivergence localId="{did}"><connectionPointIn>'
                           f'<connection refLocalId="{tid}"/></connectionPointIn>'
                           '</simultaneousDivergence>')
                tid = did
            for d in dst:
                if rng.random() < 0.5:
                    incoming.setdefault(d, []).append(tid)
                else:
                    els.append(f'<jumpStep localId="{next(ids)}" targetName="{steps[d]}">'
                               f'<connectionPointIn><connection refLocalId="{tid}"/>'
                               '</connectionPointIn></jumpStep>')
    for d, tids in incoming.items():  # wire the steps' inputs (a convergence for several)
        conn = "".join(f'<connectionPointIn><connection refLocalId="{t}"/></connectionPointIn>'
                       for t in tids)
        if len(tids) > 1:
            cid = next(ids)
            els.append(f'<selectionConvergence localId="{cid}">{conn}<connectionPointOut/>'
                       '</selectionConvergence>')
            conn = f'<connectionPointIn><connection refLocalId="{cid}"/></connectionPointIn>'
        k = next(i for i, e in enumerate(els) if e.startswith(f'<step localId="{sid[d]}"'))
        els[k] = els[k].replace("<connectionPointOut/>", conn + "<connectionPointOut/>", 1)
    actions = "".join(f'<action name="A{k}"><body><ST><xhtml:p><![CDATA[{b}]]></xhtml:p></ST>'
                      "</body></action>" for k, b in enumerate(bodies))
    iface = _main_interface()
    if actions:  # the POU's <actions> sit between its interface and its body (TC6 order)
        iface += "</interface><actions>" + actions + "</actions><interface>"
    body = "<SFC>" + "\n".join(els) + "</SFC>"
    return xml_project(_xml_library() + [("Main", "program", iface, body)]), "gen_sfc.xml"


# -- OOP with names that look generated (issue 30) ------------------------------------------
LOOKALIKES = ["X", "M_X", "M_M_X", "GO", "M_GO", "_ITF", "ITF", "_BODY", "BODY", "_COPY", "COPY",
              "SELF", "V_X", "F_X", "P_X", "P_FB", "EDGE_X", "EDGE_M_X", "EDGE_MEM", "CR_INT",
              "LD_M3", "SFC_TR0", "THIS_X", "_G", "_B", "_X_", "Q", "G_X", "_R", "_P", "MAIN_",
              "M_GO_", "_M_X"]


def gen_oop(rng: random.Random) -> tuple[str, str]:
    """A valid program of blocks, an interface, a PROPERTY, methods overriding through SUPER^,
    a FUNCTION, ACTIONs, an edge input and a global, every name drawn from names that look
    like plclab's generated ones (M_X beside METHOD X, _ITF, EDGE_..., FB_init as an action);
    initial values read variables declared after them."""
    (base, der, fn, itf, prop, glob, edge, bv0, bv1, dv0, bm, dm, l0, l1, l2, inst, ref, n,
     act) = rng.sample(LOOKALIKES, 19)
    if rng.random() < 0.3:
        act = "FB_init"
    bare = rng.random() < 0.5  # a bare property name inside its block, or THIS^.name
    p = prop if bare else f"THIS^.{prop}"
    text = (
        f"VAR_GLOBAL {glob} : INT; END_VAR\n"
        f"INTERFACE {itf}\nMETHOD {bm} : INT\nEND_METHOD\nEND_INTERFACE\n"
        f"FUNCTION_BLOCK {base} IMPLEMENTS {itf}\nVAR_INPUT {edge} : BOOL R_EDGE; END_VAR\n"
        f"VAR {bv0} : INT := {bv1}; {bv1} : INT := {rng.randint(0, 9)}; END_VAR\n"
        f"METHOD {bm} : INT\n{p} := ({p} + {rng.randint(1, 5)}) MOD 100;\n"
        f"{bm} := {bv0} + {bv1};\nEND_METHOD\n"
        f"PROPERTY {prop} : INT\nGET\n{prop} := {bv1};\nEND_GET\n"
        f"SET\n{bv1} := {prop};\nEND_SET\nEND_PROPERTY\n"
        f"IF {edge} THEN {bv0} := ({bv0} + 1) MOD 1000; END_IF;\nEND_FUNCTION_BLOCK\n"
        f"FUNCTION_BLOCK {der} EXTENDS {base}\nVAR {dv0} : INT; END_VAR\n"
        f"METHOD {bm} : INT\n{bm} := SUPER^.{bm}() + {dv0};\nEND_METHOD\n"
        f"METHOD {dm} : INT\n{dm} := {p} + 1;\nEND_METHOD\n"
        f"{dv0} := ({dv0} + 1) MOD 7;\nEND_FUNCTION_BLOCK\n"
        f"FUNCTION {fn} : INT\nVAR_INPUT {l0} : INT; END_VAR\n"
        f"VAR {l1} : INT := {l2}; {l2} : INT := 3; END_VAR\n"
        f"{fn} := {l0} MOD 100 + {l1} + {l2};\nEND_FUNCTION\n"
        f"PROGRAM Main\nVAR {inst} : {der}; {ref} : {itf}; {n} : INT; END_VAR\n"
        f"{inst}({edge} := {rng.choice(['TRUE', 'FALSE', f'{n} > 3'])});\n{ref} := {inst};\n"
        f"{n} := {ref}.{bm}() + {inst}.{dm}() + {inst}.{prop};\n{n} := {fn}({n});\n"
        f"{glob} := {n};\n{act}();\nEND_PROGRAM\n"
        f"ACTION Main.{act}\n{n} := {n} MOD 1000;\nEND_ACTION\n")
    return text, "gen_oop.st"


GENERATORS = {"st": gen_st, "il": gen_il, "ld": gen_ld, "xml": gen_xml, "sfc": gen_sfc,
              "oop": gen_oop}
