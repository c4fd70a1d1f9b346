"""The core AST printed back as Structured Text (``plclab compile FILE --emit st``).

Every front end produces the same AST, so an IL body or a ladder network appears here as the ST
it was lowered to. Names and literals keep their spelling; parentheses are written only where
the precedence needs them. Jumps and labels (from IL) are printed as CODESYS writes them in ST
(``JMP L1;``, ``L1:``), which plclab's ST parser does not read.

>>> from plclab.lang.frontends.st import parse_st
>>> print(unparse(parse_st("PROGRAM P VAR x : INT; END_VAR x := (x + 1) * 2; END_PROGRAM")), end="")
PROGRAM P
VAR
    x : INT;
END_VAR
x := (x + 1) * 2;
END_PROGRAM
"""

from __future__ import annotations

import datetime as _dt

from . import ast as A
from .limits import compiler_guard

INDENT = "    "
# binary operator -> precedence (higher binds tighter); the same table as the ST parser's
PRECEDENCE = {"OR": 1, "XOR": 2, "AND": 3, "=": 4, "<>": 4, "<": 5, "<=": 5, ">": 5, ">=": 5,
              "+": 6, "-": 6, "*": 7, "/": 7, "MOD": 7, "**": 8}
_TOP = 100  # an operand that never needs parentheses (literals, names, calls, unary)
_TIME_UNITS = (("d", 86_400_000_000_000), ("h", 3_600_000_000_000), ("m", 60_000_000_000),
               ("s", 1_000_000_000), ("ms", 1_000_000), ("us", 1_000), ("ns", 1))
_ESCAPES = {"$": "$$", "\n": "$N", "\t": "$T", "\r": "$R", "\f": "$P"}


def unparse(node: object) -> str:
    """ST text of a :class:`~plclab.lang.ast.SourceFile`, a POU, a statement list, a statement
    or an expression."""
    with compiler_guard():
        if isinstance(node, A.Expr):
            return expr(node)
        out = _Writer()
        if isinstance(node, A.SourceFile):
            out.source_file(node)
        elif isinstance(node, A.Pou):
            out.pou(node)
        elif isinstance(node, list):
            out.stmts(node)
        elif isinstance(node, A.Stmt):
            out.stmt(node)
        else:
            raise TypeError(f"cannot unparse {type(node).__name__}")
        return "\n".join(out.lines) + "\n"


# -- expressions ------------------------------------------------------------------------------


def expr(e: A.Expr | None) -> str:
    """An expression as ST, with the parentheses its precedence needs."""
    if e is None:
        return ""
    if isinstance(e, A.Binary):
        return _binary(e)
    if isinstance(e, A.Literal):
        return literal(e)
    if isinstance(e, A.Name):
        if e.name in ("THIS", "SUPER") and e.text.endswith("^"):  # ADR 0021
            return e.text
        return _spelled(e.text, e.name)
    if isinstance(e, A.DirectAddr):
        return e.address
    if isinstance(e, A.Member) and e.field_name == "^":  # r^ (ADR 0021)
        return f"{_operand(e.obj, _TOP)}^"
    if isinstance(e, A.Member):
        field = _spelled(e.text, e.field_name)
        part = A.partial_access(e.field_name)
        if part is not None:  # x.3, x.%B1
            field = str(part[1]) if part[0] == "X" else e.field_name
        return f"{_operand(e.obj, _TOP)}.{field}"
    if isinstance(e, A.Index):
        return f"{_operand(e.obj, _TOP)}[{', '.join(expr(i) for i in e.indices)}]"
    if isinstance(e, A.Unary):
        inner = _operand(e.operand, _TOP)
        if e.op == "NOT":
            return f"NOT {inner}"
        return f"{e.op}({inner})" if inner.startswith(("-", "+")) else f"{e.op}{inner}"
    if isinstance(e, A.Call):
        return f"{_operand(e.func, _TOP)}({', '.join(_arg(a) for a in e.args)})"
    if isinstance(e, A.ArrayInit):
        items = [f"{expr(n)}({expr(v)})" if n is not None else expr(v) for n, v in e.items]
        return "[" + ", ".join(items) + "]"
    if isinstance(e, A.StructInit):
        return "(" + ", ".join(f"{name} := {expr(v)}" for name, v, _ in e.fields) + ")"
    raise TypeError(f"cannot unparse {type(e).__name__}")


def _spelled(text: str, name: str) -> str:
    """The name as the student wrote it, when that is a spelling of it (lowerings may put a
    description there)."""
    return text if text and text.upper() == name.upper() else name


def _prec(e: A.Expr) -> int:
    return PRECEDENCE[e.op] if isinstance(e, A.Binary) else _TOP


def _operand(e: A.Expr, need: int) -> str:
    """``e`` in parentheses when it binds less tightly than ``need``."""
    text = expr(e)
    return f"({text})" if _prec(e) < need else text


def _binary(e: A.Binary) -> str:
    # the left spine of a chain (a + b + c ..., 10,000 terms) is walked with a loop
    spine: list[A.Binary] = []
    node: A.Expr = e
    while isinstance(node, A.Binary) and (not spine or PRECEDENCE[node.op] ==
                                          PRECEDENCE[spine[-1].op]):
        spine.append(node)
        node = node.left
    text = _operand(node, PRECEDENCE[spine[-1].op])
    for b in reversed(spine):
        # operators are left-associative: a right operand of the same precedence needs ()
        text = f"{text} {b.op} {_operand(b.right, PRECEDENCE[b.op] + 1)}"
    return text


def _arg(a: A.Arg) -> str:
    if a.name is None:
        return expr(a.value)
    if a.output:
        return f"{'NOT ' if a.negated else ''}{a.name} => {expr(a.value)}".rstrip()
    return f"{a.name} := {expr(a.value)}"


def literal(e: A.Literal) -> str:
    """A literal as written, or (for literals a lowering made) as ST writes its value."""
    if e.text:
        return e.text
    v, kind = e.value, e.kind
    if kind == "BOOL":
        return "TRUE" if v else "FALSE"
    if kind == "INT":
        return f"{e.prefix}#{v}" if e.prefix else str(v)
    if kind == "REAL":
        text = repr(float(v)).upper()
        if "." not in text and "E" in text:
            text = text.replace("E", ".0E")
        return f"{e.prefix}#{text}" if e.prefix else text
    if kind in ("STRING", "WSTRING"):
        q = "'" if kind == "STRING" else '"'
        body = "".join(_ESCAPES.get(c, f"${q}" if c == q else c) for c in str(v))
        return f"{q}{body}{q}"
    if kind == "TIME":
        return ("LTIME#" if e.prefix == "LTIME" else "T#") + duration(v)
    if kind == "ENUM":
        return f"{v[0]}#{v[1]}"
    if kind == "DATE":
        return "D#" + _dt.date(1970, 1, 1).__add__(_dt.timedelta(seconds=v)).isoformat()
    return f"{e.prefix or kind}#{v}"


def duration(ns: int) -> str:
    """The body of a duration literal: ``1h2m3s4ms``, ``-5s``, ``0s``."""
    if ns == 0:
        return "0s"
    sign, ns = ("-" if ns < 0 else ""), abs(ns)
    parts = []
    for unit, size in _TIME_UNITS:
        if ns >= size:
            parts.append(f"{ns // size}{unit}")
            ns %= size
    return sign + "".join(parts)


# -- declarations and statements -------------------------------------------------------------


def _path(spelled: str, resources: set[str] | list[str] | None) -> str:
    """A configuration path with its resource renamed to the printer's one resource, Cpu
    (a direct address keeps a resource in front: ``Cpu.%IX1.1``); ``None``: the configuration
    has two or more resources, printed by their names, and the path stays as written."""
    if resources is None:
        return spelled
    head, _, rest = spelled.partition(".")
    if rest and head.upper() in {r.upper() for r in resources}:
        return f"Cpu.{rest}"
    return f"Cpu.{spelled}" if spelled.startswith("%") else spelled


def type_ref(t: A.TypeRef) -> str:
    """A type as written in a declaration."""
    if isinstance(t, A.NamedTypeRef):
        return t.name if t.args is None else f"{t.name}({', '.join(_arg(a) for a in t.args)})"
    if isinstance(t, A.StringTypeRef):
        name = "WSTRING" if t.wide else "STRING"
        return f"{name}[{expr(t.length)}]" if t.length is not None else name
    if isinstance(t, A.ArrayTypeRef):
        dims = ", ".join(f"{expr(lo)}..{expr(hi)}" for lo, hi in t.ranges) or ", ".join(
            "*" * t.star)
        return f"ARRAY[{dims}] OF {type_ref(t.elem)}"
    if isinstance(t, A.SubrangeTypeRef):
        return f"{type_ref(t.base)}({expr(t.lo)}..{expr(t.hi)})"
    if isinstance(t, A.RefTypeRef):
        return ("REF_TO " if t.kind == "REF_TO" else f"{t.kind} TO ") + type_ref(t.target)
    if isinstance(t, A.EnumTypeRef):
        members = ", ".join(t.spellings.get(n, n) + (f" := {expr(v)}" if v is not None else "")
                            for n, v, _ in t.members)
        return (f"{type_ref(t.base)} " if t.base is not None else "") + f"({members})"
    raise TypeError(f"cannot unparse {type(t).__name__}")


class _Writer:
    def __init__(self) -> None:
        self.lines: list[str] = []
        self.depth = 0

    def line(self, text: str) -> None:
        self.lines.append(INDENT * self.depth + text)

    # files and POUs
    def source_file(self, f: A.SourceFile) -> None:
        blocks: list[tuple[A.Location | None, object]] = []
        blocks += [(t.loc, t) for t in f.types]
        blocks += [(g.loc, g) for g in f.globals]
        blocks += [(p.loc, p) for p in f.pous]
        blocks += [(c.loc, c) for c in f.configs]
        if f.config_vars:
            blocks.append((f.config_vars[0].loc, f.config_vars))
        blocks += [(t.loc, t) for t in f.tests]
        blocks.sort(key=lambda b: (b[0].line, b[0].col) if b[0] is not None else (0, 0))
        for i, (_, b) in enumerate(blocks):
            if i:
                self.lines.append("")
            if isinstance(b, A.TypeDecl):
                self.type_decl(b)
            elif isinstance(b, A.GlobalVars):
                self.decls(b.decls, "VAR_GLOBAL")
            elif isinstance(b, A.Pou):
                self.pou(b)
            elif isinstance(b, A.Configuration):
                self.configuration(b)
            elif isinstance(b, A.TestBlock):
                self.test(b)
            elif isinstance(b, list):
                self.config_vars(b, set())

    def type_decl(self, t: A.TypeDecl) -> None:
        name = _spelled(t.spelling, t.name)
        init = f" := {expr(t.init)}" if t.init is not None else ""
        if isinstance(t.type, A.StructTypeRef):
            self.line("TYPE " + name + " :")
            self.line("STRUCT")
            self.depth += 1
            for d in t.type.fields:
                self.var(d)
            self.depth -= 1
            self.line("END_STRUCT;")
        else:
            self.line(f"TYPE {name} : {type_ref(t.type)}{init};")
        self.line("END_TYPE")

    def pou(self, p: A.Pou) -> None:
        if p.native:
            self.line(f"{{native '{p.native}'}}")
        ret = f" : {type_ref(p.return_type)}" if p.return_type is not None else ""
        mods = "".join(f"{m} " for m in p.modifiers)
        head = "".join(f" {w} {', '.join(ns)}" for w, ns in (("EXTENDS", p.extends),
                                                              ("IMPLEMENTS", p.implements)) if ns)
        kind = "CLASS" if p.is_class else p.kind
        self.line(f"{kind} {mods}{_spelled(p.spelling, p.name)}{ret}{head}")
        inst = {A.method_inst_name(p.name, m.name, d.name) for m in p.methods for d in m.decls
                if d.section == "VAR_INST"}
        self.decls([d for d in p.decls if d.name not in inst])
        self.access_paths(p.access_paths, None)
        self.members(p)
        self.stmts(p.body)
        self.line(f"END_{kind}")

    def members(self, p: A.Pou) -> None:
        """The METHODs and PROPERTYs of a block or interface (ADR 0021)."""
        done: set[str] = set()
        for m in p.methods:
            prop, _, acc = m.name.rpartition("__")
            if not prop or acc not in ("GET", "SET"):
                ret = f" : {type_ref(m.return_type)}" if m.return_type is not None else ""
                mods = "".join(f" {x}" for x in m.modifiers)
                self.line(f"METHOD{mods} {_spelled(m.spelling, m.name)}{ret}")
                self.decls(m.decls)
                self.stmts(m.body)
                self.line("END_METHOD")
                continue
            if prop in done:
                continue
            done.add(prop)
            accs = [a for a in p.methods if a.name in (f"{prop}__GET", f"{prop}__SET")]
            get = next((a for a in accs if a.name.endswith("GET")), None)
            tref = get.return_type if get is not None else accs[0].decls[0].type
            mods = "".join(f" {x}" for x in m.modifiers)
            self.line(f"PROPERTY{mods} {m.spelling.rpartition('.')[0] or prop} : {type_ref(tref)}")
            for a in accs:
                word = a.name[-3:]
                self.line(word)
                self.decls(a.decls[1:] if word == "SET" else a.decls)
                self.stmts(a.body)
                self.line(f"END_{word}")
            self.line("END_PROPERTY")

    def configuration(self, c: A.Configuration) -> None:
        self.line(f"CONFIGURATION {c.name}")
        self.depth += 1
        if c.globals:
            self.decls(c.globals, "VAR_GLOBAL")
        # one resource (as Cpu), or each of two or more with its own globals (ADR 0037)
        scoped = any(x.resource for x in [*c.tasks, *c.instances]) or c.resource_globals
        for r in (c.resources if scoped else [None]):
            self.line(f"RESOURCE {r or 'Cpu'} ON PLC")
            self.depth += 1
            if c.resource_globals.get(r or ""):
                self.decls(c.resource_globals[r or ""], "VAR_GLOBAL")
            for t in c.tasks:
                if t.resource != r:
                    continue
                props = [(k, v) for k, v in (("SINGLE", t.single), ("INTERVAL", t.interval),
                                             ("PRIORITY", t.priority)) if v is not None]
                self.line(f"TASK {t.name} ({', '.join(f'{k} := {expr(v)}' for k, v in props)});")
            for i in c.instances:
                if i.resource != r:
                    continue
                task = f" WITH {i.task}" if i.task else ""
                prog = expr(i.call) if i.call is not None else i.program
                self.line(f"PROGRAM {i.name}{task} : {prog};")
            self.depth -= 1
            self.line("END_RESOURCE")
        self.config_vars(c.config_vars, None if scoped else set(c.resources))
        self.access_paths(c.access_paths, None if scoped else c.resources)
        self.depth -= 1
        self.line("END_CONFIGURATION")

    def access_paths(self, paths: list[A.AccessPath], resources: list[str] | None) -> None:
        """A VAR_ACCESS section (a configuration's or a PROGRAM's), if there are paths."""
        if not paths:
            return
        self.line("VAR_ACCESS")
        self.depth += 1
        for a in paths:
            mode = "READ_ONLY" if a.read_only else "READ_WRITE"
            self.line(f"{_spelled(a.spelling, a.name)} : {_path(a.spelled, resources)} : "
                      f"{type_ref(a.type)} {mode};")
        self.depth -= 1
        self.line("END_VAR")

    def config_vars(self, lines: list[A.ConfigVar], resources: set[str] | None) -> None:
        """VAR_CONFIG, its paths written from the one resource this printer names (Cpu)."""
        if not lines:
            return
        self.line("VAR_CONFIG")
        self.depth += 1
        for v in lines:
            at = f" AT {v.address}" if v.address else ""
            init = f" := {expr(v.init)}" if v.init is not None else ""
            self.line(f"{_path(v.spelled, resources)}{at} : {type_ref(v.type)}{init};")
        self.depth -= 1
        self.line("END_VAR")

    def test(self, t: A.TestBlock) -> None:
        title = t.title.replace("$", "$$").replace("'", "$'")
        self.line(f"TEST '{title}'")
        self.depth += 1
        self.decls(t.decls)
        self.stmts(t.body)
        self.depth -= 1
        self.line("END_TEST")

    def decls(self, decls: list[A.VarDecl], section: str | None = None) -> None:
        """Consecutive declarations of one section and kind share one VAR ... END_VAR."""
        group: tuple[str, bool, bool] | None = None
        for d in decls:
            key = (section or d.section, d.constant, d.retain)
            if key != group:
                if group is not None:
                    self.line("END_VAR")
                words = [key[0]] + ["CONSTANT"] * key[1] + ["RETAIN"] * key[2]
                self.line(" ".join(words))
                group = key
            self.depth += 1
            self.var(d)
            self.depth -= 1
        if group is not None:
            self.line("END_VAR")

    def var(self, d: A.VarDecl) -> None:
        at = f" AT {d.address}" if d.address else ""
        init = f" := {expr(d.init)}" if d.init is not None else ""
        self.line(f"{_spelled(d.spelling, d.name)}{at} : {type_ref(d.type)}{init};")

    # statements
    def stmts(self, body: list[A.Stmt]) -> None:
        for s in body:
            self.stmt(s)

    def block(self, body: list[A.Stmt]) -> None:
        self.depth += 1
        self.stmts(body)
        self.depth -= 1

    def stmt(self, s: A.Stmt) -> None:
        if isinstance(s, A.Assign):
            if s.op in ("S=", "R="):  # a set or reset coil of a ladder network
                self.line(f"IF {expr(s.value)} THEN")
                self.depth += 1
                self.line(f"{expr(s.target)} := {'TRUE' if s.op == 'S=' else 'FALSE'};")
                self.depth -= 1
                self.line("END_IF;")
            else:
                self.line(f"{expr(s.target)} := {expr(s.value)};")
        elif isinstance(s, A.CallStmt):
            self.line(expr(s.call) + ";")
        elif isinstance(s, A.If):
            for i, (cond, body) in enumerate(s.branches):
                self.line(f"{'IF' if i == 0 else 'ELSIF'} {expr(cond)} THEN")
                self.block(body)
            if s.orelse is not None:
                self.line("ELSE")
                self.block(s.orelse)
            self.line("END_IF;")
        elif isinstance(s, A.Case):
            self.line(f"CASE {expr(s.selector)} OF")
            for b in s.branches:
                labels = ", ".join(f"{expr(x[0])}..{expr(x[1])}" if isinstance(x, tuple)
                                   else expr(x) for x in b.labels)
                self.line(f"{labels}:")
                self.block(b.body)
            if s.orelse is not None:
                self.line("ELSE")
                self.block(s.orelse)
            self.line("END_CASE;")
        elif isinstance(s, A.For):
            by = f" BY {expr(s.step)}" if s.step is not None else ""
            self.line(f"FOR {expr(s.var)} := {expr(s.start)} TO {expr(s.end)}{by} DO")
            self.block(s.body)
            self.line("END_FOR;")
        elif isinstance(s, A.While):
            self.line(f"WHILE {expr(s.cond)} DO")
            self.block(s.body)
            self.line("END_WHILE;")
        elif isinstance(s, A.Repeat):
            self.line("REPEAT")
            self.block(s.body)
            self.line(f"UNTIL {expr(s.cond)}")
            self.line("END_REPEAT;")
        elif isinstance(s, A.Exit | A.Continue | A.Return):
            self.line(type(s).__name__.upper() + ";")
        elif isinstance(s, A.Empty):
            self.line(";")
        elif isinstance(s, A.Label):
            self.line(f"{s.name}:")
        elif isinstance(s, A.Jump):
            if s.cond is None:
                self.line(f"JMP {s.label};")
            else:
                self.line(f"IF {expr(s.cond)} THEN JMP {s.label}; END_IF;")
        else:
            raise TypeError(f"cannot unparse {type(s).__name__}")
