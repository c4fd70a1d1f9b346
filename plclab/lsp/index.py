"""What a document declares, where, and in which scope: the data behind symbols, hover,
go to definition and completion.

:func:`build` reads the parsed (and lowered) :class:`~plclab.lang.ast.SourceFile` of a document
and the library files: POUs with their variables, methods and actions, SFC steps, actions and
transitions, TYPEs with their fields and enumeration values, global variables, configurations
and TEST blocks. Names the lowering invents (``__SFC_TMR_S1``, ``__IL_ACC``) stay hidden.
Lines and columns are 1-based, as in :class:`~plclab.errors.Location`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from ..errors import Location
from ..lang import ast as A
from ..lang.unparse import expr as expr_text
from .stdlib_docs import pou_signature, type_text

# kinds of entries (the server maps them to LSP SymbolKind and CompletionItemKind)
VARIABLE, CONSTANT, POU, METHOD, ACTION, STEP, TRANSITION, TYPE, FIELD, ENUM, TEST, CONFIG = (
    "variable", "constant", "pou", "method", "action", "step", "transition", "type", "field",
    "enum", "test", "configuration")

STEP_FLAGS = {"X": ("BOOL", "TRUE while the step is active"),
              "T": ("TIME", "how long the step has been active")}


@dataclass(eq=False)
class Entry:
    """A declared name: what it is, where its name is written, and what it holds."""

    name: str  # as written
    kind: str
    loc: Location | None
    detail: str = ""  # the declaration as ST text, or a signature
    type_name: str | None = None  # the declared type's name (upper-case) for members
    node: Any = None
    children: list[Entry] = field(default_factory=list)
    end_line: int | None = None  # the last line of a POU, method or TEST
    container: str = ""  # the POU, TYPE or TEST it belongs to, as written


@dataclass(eq=False)
class Scope:
    """Lines ``start..end`` and the names they declare; ``parent``: the FB of a method."""

    entry: Entry
    start: int
    end: int
    names: dict[str, Entry] = field(default_factory=dict)
    parent: Scope | None = None
    pou: A.Pou | None = None


@dataclass(eq=False)
class Index:
    file: str
    top: list[Entry] = field(default_factory=list)  # the outline of the document
    scopes: list[Scope] = field(default_factory=list)
    globals: dict[str, Entry] = field(default_factory=dict)  # upper-case name -> entry
    pous: dict[str, A.Pou] = field(default_factory=dict)  # every POU, the library's too
    types: dict[str, A.TypeDecl] = field(default_factory=dict)
    tests: list[Entry] = field(default_factory=list)
    spellings: dict[str, str] = field(default_factory=dict)  # POU and TYPE names as declared
    error: str = ""  # why the index is empty (a bug of plclab: the server logs it)

    def scope_at(self, line: int) -> Scope | None:
        """The innermost scope around *line* (a method inside its block)."""
        best = None
        for s in self.scopes:
            if s.start <= line <= s.end and (best is None or s.start >= best.start):
                best = s
        return best

    def lookup(self, name: str, line: int) -> Entry | None:
        """The declaration *name* means on *line*: the scope's, its block's, then the file's."""
        key = name.upper()
        s = self.scope_at(line)
        while s is not None:
            if key in s.names:
                return s.names[key]
            s = s.parent
        return self.globals.get(key)

    def visible(self, line: int) -> list[Entry]:
        """Every name declared for *line*, the innermost first."""
        out: dict[str, Entry] = {}
        s = self.scope_at(line)
        while s is not None:
            for k, e in s.names.items():
                out.setdefault(k, e)
            s = s.parent
        for k, e in self.globals.items():
            out.setdefault(k, e)
        return list(out.values())


def _hidden(name: str) -> bool:
    return name.startswith("__")


def decl_text(d: A.VarDecl, spellings: dict[str, str] | None = None) -> str:
    """``VAR_INPUT limit : INT := 10`` (with AT, CONSTANT, RETAIN as declared)."""
    text = d.section + (" CONSTANT" if d.constant else "") + (" RETAIN" if d.retain else "")
    text += f" {d.spelling or d.name}"
    if d.address:
        text += f" AT {d.address}"
    text += f" : {type_text(d.type, spellings)}"
    if d.init is not None:
        try:
            text += f" := {expr_text(d.init)}"
        except Exception:  # noqa: BLE001 - an initialiser the unparser cannot print
            pass
    return text


def _type_name(t: A.TypeRef) -> str | None:
    if isinstance(t, A.NamedTypeRef):
        return t.name.upper()
    return None


def var_entry(d: A.VarDecl, container: str, spellings: dict[str, str] | None = None) -> Entry:
    return Entry(d.spelling or d.name, CONSTANT if d.constant else VARIABLE, d.loc,
                 decl_text(d, spellings), _type_name(d.type), d, container=container)


def pou_detail(p: A.Pou) -> str:
    return pou_signature(p)


_STEP_RE = re.compile(r"^\s*(INITIAL_STEP|STEP)\s+([A-Za-z_]\w*)", re.I | re.M)
_ACTION_RE = re.compile(r"^\s*ACTION\s+([A-Za-z_]\w*)", re.I | re.M)


def _chart_entries(p: A.Pou, text: str, start: int, end: int, name: str) -> list[Entry]:
    """Steps, actions and transitions of an SFC body; from the lowered chart, or (a chart with
    errors is not kept) from the ``STEP`` lines of the text."""
    out: list[Entry] = []
    chart = getattr(p, "sfc", None)
    if chart is not None:
        for s in chart.steps:
            out.append(Entry(s.text, STEP, s.loc, ("INITIAL_STEP " if s.initial else "STEP ")
                             + s.text, node=s, container=name))
        for a in chart.actions:
            out.append(Entry(a.text, ACTION, a.loc, f"ACTION {a.text}", node=a, container=name))
        for t in chart.transitions:
            srcs = ", ".join(t.spelling.get(s, s) for s, _ in t.sources)
            dsts = ", ".join(t.spelling.get(s, s) for s, _ in t.targets)
            label = t.text or f"{srcs} -> {dsts}"
            out.append(Entry(label, TRANSITION, t.loc, f"TRANSITION FROM {srcs} TO {dsts}",
                             node=t, container=name))
        return out
    if p.language != "SFC":
        return out
    lines = text.splitlines()
    for m in _STEP_RE.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        if start <= line <= end and line - 1 < len(lines):
            col = m.start(2) - (text.rfind("\n", 0, m.start(2)) + 1) + 1
            out.append(Entry(m.group(2), STEP, Location(p.loc.file, line, col),
                             f"{m.group(1).upper()} {m.group(2)}", container=name))
    return out


def _type_entries(t: A.TypeDecl) -> Entry:
    name = t.spelling or t.name
    e = Entry(name, TYPE, t.loc, f"TYPE {name} : {type_text(t.type)}", t.name.upper(), t)
    if isinstance(t.type, A.StructTypeRef):
        e.children = [Entry(d.spelling or d.name, FIELD, d.loc,
                            f"{d.spelling or d.name} : {type_text(d.type)}", _type_name(d.type),
                            d, container=name) for d in t.type.fields]
    elif isinstance(t.type, A.EnumTypeRef):
        e.children = [Entry(t.type.spellings.get(m, m), ENUM, loc, f"{name}#{t.type.spellings.get(m, m)}", node=t,
                            container=name) for m, _, loc in t.type.members]
    return e


def build(files: list[A.SourceFile], own: A.SourceFile | None, text: str) -> Index:
    """The index of *own* (the document's file) among *files* (the library's too)."""
    idx = Index(own.file if own else "")
    for f in files:
        for p in f.pous:
            idx.pous.setdefault(p.name.upper(), p)
        for t in f.types:
            idx.types.setdefault(t.name.upper(), t)
    for name, p in idx.pous.items():
        idx.spellings[name] = p.spelling or p.name
    for name, t in idx.types.items():
        idx.spellings[name] = t.spelling or t.name
    sp = idx.spellings
    if own is None:
        return idx
    n_lines = text.count("\n") + 1
    starts = sorted([p.loc.line for p in own.pous] + [t.loc.line for t in own.tests]
                    + [t.loc.line for t in own.types] + [g.loc.line for g in own.globals]
                    + [c.loc.line for c in own.configs])

    def end_of(node: Any) -> int:
        end = getattr(node, "end_loc", None)
        if end is not None and end.line >= node.loc.line:
            return end.line
        later = [s for s in starts if s > node.loc.line]
        return (later[0] - 1) if later else n_lines

    for t in own.types:
        e = _type_entries(t)
        idx.top.append(e)
        idx.globals[t.name.upper()] = e
        for c in e.children:
            if c.kind == ENUM:
                idx.globals.setdefault(c.name.upper(), c)
    for g in own.globals:
        for d in g.decls:
            e = var_entry(d, "VAR_GLOBAL", sp)
            idx.top.append(e)
            idx.globals[d.name.upper()] = e
    for p in own.pous:
        name = p.spelling or p.name
        e = Entry(name, POU, p.loc, pou_detail(p), p.name.upper(), p, end_line=end_of(p))
        idx.top.append(e)
        idx.globals[p.name.upper()] = e
        scope = Scope(e, p.loc.line, e.end_line or n_lines, pou=p)
        chart = _chart_entries(p, text, scope.start, scope.end, name)
        chart_names = {c.name.upper() for c in chart if c.kind in (STEP, ACTION)}
        for d in p.decls:
            if _hidden(d.name) or d.name.upper() in chart_names:
                continue
            v = var_entry(d, name, sp)
            e.children.append(v)
            scope.names[d.name.upper()] = v
        for c in chart:
            e.children.append(c)
            if c.kind in (STEP, ACTION):
                scope.names[c.name.upper()] = c
        idx.scopes.append(scope)
        for m in p.methods:
            mname = m.spelling or m.name
            kind = ACTION if m.action else METHOD
            me = Entry(mname, kind, m.loc, pou_detail(m) if not m.action else f"ACTION {mname}",
                       m.return_type and _type_name(m.return_type), m, end_line=end_of(m),
                       container=name)
            e.children.append(me)
            scope.names.setdefault(m.name.upper(), me)
            ms = Scope(me, m.loc.line, me.end_line or scope.end, parent=scope, pou=m)
            for d in m.decls:
                if not _hidden(d.name):
                    v = var_entry(d, f"{name}.{mname}", sp)
                    me.children.append(v)
                    ms.names[d.name.upper()] = v
            idx.scopes.append(ms)
    lines = text.splitlines()

    def as_written(name: str, loc: Location | None) -> str:
        """*name* as the text spells it on *loc*'s line (the AST keeps some names upper-case)."""
        if loc is None or not 0 < loc.line <= len(lines):
            return name
        m = re.search(r"(?<!\w)" + re.escape(name) + r"(?!\w)", lines[loc.line - 1], re.I)
        return m.group(0) if m else name

    for c in own.configs:
        e = Entry(as_written(c.name, c.loc), CONFIG, c.loc, f"CONFIGURATION {as_written(c.name, c.loc)}", node=c, end_line=end_of(c))
        for d in c.globals:
            v = var_entry(d, c.name, sp)
            e.children.append(v)
            idx.globals.setdefault(d.name.upper(), v)
        for inst in c.instances:
            v = Entry(as_written(inst.name, inst.loc), VARIABLE, inst.loc, f"PROGRAM {inst.name} : {inst.program}",
                      inst.program.upper(), inst, container=c.name)
            e.children.append(v)
            idx.globals.setdefault(inst.name.upper(), v)
        idx.top.append(e)
    for t in own.tests:
        e = Entry(t.title, TEST, t.loc, f"TEST '{t.title}'", node=t, end_line=end_of(t))
        scope = Scope(e, t.loc.line, e.end_line or n_lines)
        for d in t.decls:
            v = var_entry(d, f"TEST '{t.title}'", sp)
            e.children.append(v)
            scope.names[d.name.upper()] = v
        idx.scopes.append(scope)
        idx.top.append(e)
        idx.tests.append(e)
    idx.top.sort(key=lambda e: (e.loc.line, e.loc.col) if e.loc else (0, 0))
    return idx
