"""The editor features as plain functions of an :class:`~plclab.lsp.documents.Analysis`:
hover, go to definition, completion, the outline and the TEST code lenses. Lines and columns
are 1-based here; :mod:`plclab.lsp.server` converts them to LSP's 0-based positions.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from ..errors import Location
from ..lang import ast as A
from ..lang.lexer import KEYWORDS
from . import index as I
from . import stdlib_docs

IL_OPERATORS = ("LD", "LDN", "ST", "STN", "S", "R", "AND", "ANDN", "OR", "ORN", "XOR", "XORN",
                "NOT", "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT",
                "JMP", "JMPC", "JMPCN", "CAL", "CALC", "CALCN", "RET", "RETC", "RETCN")
MORE_KEYWORDS = ("INITIAL_STEP", "STEP", "END_STEP", "TRANSITION", "FROM", "END_TRANSITION",
                 "ACTION", "END_ACTION", "METHOD", "END_METHOD", "INTERFACE", "END_INTERFACE",
                 "EXTENDS", "IMPLEMENTS", "THIS", "SUPER", "REF_TO", "BOOL", "INT", "DINT",
                 "REAL", "LREAL", "TIME", "BYTE", "WORD", "DWORD", "SINT", "UINT", "UDINT",
                 "LINT", "ULINT", "USINT", "LWORD", "DATE", "TOD", "DT")

_WORD = re.compile(r"[A-Za-z0-9_]")


@dataclass
class Word:
    """The identifier under the cursor and the names before it (``a.b.c``: ``['a', 'b']``)."""

    text: str
    start: int  # 1-based column of its first character
    end: int  # 1-based column after its last character
    chain: list[str]


def line_text(text: str, line: int) -> str:
    lines = text.splitlines()
    return lines[line - 1] if 0 < line <= len(lines) else ""


def word_at(text: str, line: int, col: int, *, before_only: bool = False) -> Word | None:
    """The identifier at (line, col) (the cursor may stand right after it) with its member
    chain. ``before_only``: the part before the cursor (completion)."""
    s = line_text(text, line)
    i = min(max(col - 1, 0), len(s))
    a = i
    while a > 0 and _WORD.match(s[a - 1]):
        a -= 1
    b = i
    if not before_only:
        while b < len(s) and _WORD.match(s[b]):
            b += 1
    chain: list[str] = []
    k = a
    while k > 0 and s[k - 1] == ".":
        j = k - 1
        while j > 0 and s[j - 1] == "]":  # a[i].x, a[i][j].x: skip the indexes
            depth = 0
            while j > 0:
                j -= 1
                depth += {"]": 1, "[": -1}.get(s[j], 0)
                if depth == 0:
                    break
        e = j
        while j > 0 and _WORD.match(s[j - 1]):
            j -= 1
        if j == e:
            break
        chain.insert(0, s[j:e])
        k = j
    word = s[a:b]
    if not word and not chain and not before_only:
        return None
    if word and word[0].isdigit():
        return None
    return Word(word, a + 1, b + 1, chain)


# ---------------------------------------------------------------------------- member types


def _pou_members(idx: I.Index, pou: A.Pou, seen: set[str] | None = None) -> list[I.Entry]:
    """The members of an instance of *pou* another POU may name: inputs, outputs, in-outs,
    (for a PROGRAM every variable), methods and actions, inherited ones too."""
    seen = seen or set()
    if pou.name in seen:
        return []
    seen.add(pou.name)
    name = pou.spelling or pou.name
    out = []
    for d in pou.decls:
        if d.name.startswith("__"):
            continue
        if pou.kind == "PROGRAM" or d.section in ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT"):
            out.append(I.var_entry(d, name, idx.spellings))
    for m in pou.methods:
        out.append(I.Entry(m.spelling or m.name, I.ACTION if m.action else I.METHOD, m.loc,
                           I.pou_detail(m), None, m, container=name))
    chart = getattr(pou, "sfc", None)
    if chart is not None and pou.kind == "PROGRAM":
        out += [I.Entry(s.text, I.STEP, s.loc, f"STEP {s.text}", None, s, container=name)
                for s in chart.steps]
    for base in pou.extends:
        parent = idx.pous.get(base.upper())
        if parent is not None:
            out += _pou_members(idx, parent, seen)
    return out


def _members_of_type(idx: I.Index, type_name: str | None, depth: int = 0) -> list[I.Entry]:
    if not type_name or depth > 8:
        return []
    pou = idx.pous.get(type_name)
    if pou is not None:
        return _pou_members(idx, pou)
    t = idx.types.get(type_name)
    if t is None:
        return []
    return _members_of_typeref(idx, t.type, t.spelling or t.name, depth)


def _members_of_typeref(idx: I.Index, t: A.TypeRef, container: str, depth: int
                        ) -> list[I.Entry]:
    if isinstance(t, A.StructTypeRef):
        return [I.Entry(d.spelling or d.name, I.FIELD, d.loc,
                        f"{d.spelling or d.name} : {stdlib_docs.type_text(d.type)}", I._type_name(d.type), d,
                        container=container) for d in t.fields]
    if isinstance(t, A.NamedTypeRef):
        return _members_of_type(idx, t.name.upper(), depth + 1)
    if isinstance(t, A.ArrayTypeRef | A.RefTypeRef):
        inner = t.elem if isinstance(t, A.ArrayTypeRef) else t.target
        return _members_of_typeref(idx, inner, container, depth + 1)
    return []


def _step_flags(step: I.Entry) -> list[I.Entry]:
    return [I.Entry(flag, I.FIELD, step.loc, f"{step.name}.{flag} : {ty}  ({why})", ty)
            for flag, (ty, why) in I.STEP_FLAGS.items()]


def members(idx: I.Index, chain: list[str], line: int) -> list[I.Entry]:
    """What may follow ``chain[0].chain[1]. ...`` on *line*."""
    if not chain:
        return []
    first = chain[0].upper()
    entry = idx.lookup(first, line)
    if first == "THIS" or first == "SUPER":
        s = idx.scope_at(line)
        while s is not None and s.parent is not None:
            s = s.parent
        if s is None or s.pou is None:
            return []
        cur = _pou_members(idx, s.pou) + [e for e in s.names.values()]
        if first == "SUPER":
            cur = [m for b in s.pou.extends if (p := idx.pous.get(b.upper()))
                   for m in _pou_members(idx, p)]
    elif entry is None:
        pou = idx.pous.get(first)  # a program's name in a TEST: Main.x
        if pou is None:
            return []
        cur = _pou_members(idx, pou)
    elif entry.kind == I.STEP:
        cur = _step_flags(entry)
    elif entry.kind == I.POU and isinstance(entry.node, A.Pou):
        cur = _pou_members(idx, entry.node)
    elif isinstance(entry.node, A.VarDecl):
        cur = _members_of_typeref(idx, entry.node.type, entry.name, 0)
    else:
        cur = _members_of_type(idx, entry.type_name)
    for part in chain[1:]:
        nxt = next((m for m in cur if m.name.upper() == part.upper()), None)
        if nxt is None:
            return []
        if nxt.kind == I.STEP:
            cur = _step_flags(nxt)
        elif isinstance(nxt.node, A.VarDecl):
            cur = _members_of_typeref(idx, nxt.node.type, nxt.name, 0)
        else:
            cur = _members_of_type(idx, nxt.type_name)
    return cur


# ---------------------------------------------------------------------------- resolution


@dataclass
class Target:
    """What a name under the cursor refers to."""

    name: str
    kind: str  # an index kind, "function" (a standard function) or "block" (a library POU)
    detail: str
    doc: str = ""
    loc: Location | None = None  # in this document; None for the library
    entry: I.Entry | None = None


def _library_target(idx: I.Index, name: str) -> Target | None:
    key = name.upper()
    desc = stdlib_docs.describe(key)
    if desc is not None:
        return Target(key, "function", desc[0], desc[1])
    pou = idx.pous.get(key)
    if pou is not None and pou.loc is not None and pou.loc.file.startswith("<plclab>"):
        return Target(pou.spelling or pou.name, "block", stdlib_docs.pou_signature(pou),
                      stdlib_docs.block_doc(pou) or "")
    return None


def resolve(analysis: Any, line: int, col: int) -> Target | None:
    """The declaration the identifier at (line, col) names."""
    w = word_at(analysis.text, line, col)
    if w is None or not w.text:
        return None
    idx = analysis.index
    if w.chain:
        for m in members(idx, w.chain, line):
            if m.name.upper() == w.text.upper():
                own = m.loc is not None and m.loc.file == idx.file
                return Target(m.name, m.kind, m.detail, _doc_of(m), m.loc if own else None, m)
        return None
    e = idx.lookup(w.text, line)
    if e is not None:
        return Target(e.name, e.kind, e.detail, _doc_of(e), e.loc, e)
    t = _library_target(idx, w.text)
    if t is not None:
        return t
    # a TEST may name a program of the file: the POU entry
    pou = idx.pous.get(w.text.upper())
    if pou is not None and pou.loc is not None and pou.loc.file == idx.file:
        return Target(pou.spelling or pou.name, I.POU, I.pou_detail(pou), "", pou.loc)
    return None


def _doc_of(e: I.Entry) -> str:
    where = f" of {e.container}" if e.container else ""
    if e.loc is not None and not e.loc.file.startswith("<plclab>"):
        return f"{e.kind}{where}, declared on line {e.loc.line}"
    return f"{e.kind}{where}"


def hover(analysis: Any, line: int, col: int, results: dict[str, Any] | None = None
          ) -> str | None:
    """Markdown for the name at (line, col): its declaration (or the signature and one line of
    a standard function or block); on a TEST's first line its last result."""
    idx = analysis.index
    for t in idx.tests:
        if t.loc is not None and t.loc.line == line and results:
            r = results.get(t.name)
            if r is not None:
                state = "passed" if r.passed else "FAILED"
                text = f"**TEST '{t.name}'**: {state}"
                if not r.passed and r.message:
                    text += f"\n\n{r.message}"
                return text
    target = resolve(analysis, line, col)
    if target is None:
        return None
    lang = "iec-st"
    text = f"```{lang}\n{target.detail}\n```"
    if target.doc:
        text += f"\n\n{target.doc}"
    return text


def definition(analysis: Any, line: int, col: int) -> Location | None:
    """Where the name at (line, col) is declared in this document (None: elsewhere or not)."""
    t = resolve(analysis, line, col)
    if t is None or t.loc is None or t.loc.file != analysis.index.file:
        return None
    return t.loc


@dataclass
class Completion:
    label: str
    kind: str  # an index kind, "function", "block", "keyword"
    detail: str = ""
    doc: str = ""


def completions(analysis: Any, text: str, line: int, col: int) -> list[Completion]:
    """Completion at (line, col) of *text* (the current text; *analysis* may be an older one):
    members after ``.``, else declared names, standard functions and blocks, keywords."""
    w = word_at(text, line, col, before_only=True)
    idx = analysis.index
    s = line_text(text, line)
    if w is not None and w.chain and s[w.start - 2:w.start - 1] == ".":
        return [Completion(m.name, m.kind, m.detail, _doc_of(m))
                for m in members(idx, w.chain, line)]
    out = [Completion(e.name, e.kind, e.detail, _doc_of(e)) for e in idx.visible(line)]
    seen = {c.label.upper() for c in out}
    for name, pou in idx.pous.items():
        if name not in seen and pou.loc is not None and pou.loc.file.startswith("<plclab>") \
                and not name.startswith("__") and pou.kind != "PROGRAM":
            out.append(Completion(pou.spelling or pou.name, "block",
                                  stdlib_docs.pou_signature(pou),
                                  stdlib_docs.block_doc(pou) or ""))
            seen.add(name)
    from ..lang.builtins import BUILTINS

    for name in BUILTINS:
        if name not in seen:
            sig, doc = stdlib_docs.describe(name) or (name, "")
            out.append(Completion(name, "function", sig, doc))
            seen.add(name)
    words = sorted(KEYWORDS) + list(MORE_KEYWORDS)
    if analysis.filename.lower().endswith(".il"):
        words += list(IL_OPERATORS)
    for k in words:
        if k not in seen:
            out.append(Completion(k, "keyword"))
            seen.add(k)
    return out


def test_lenses(analysis: Any) -> list[tuple[str, Location]]:
    """(title, line of ``TEST``) of each TEST block of the document."""
    return [(t.name, t.loc) for t in analysis.index.tests if t.loc is not None]


def run_test(text: str, filename: str, title: str, dialect: str | None = None) -> Any:
    """Compile the document and run its TEST *title*: a :class:`plclab.testing.TestResult`
    (a document that does not compile: a failed result with the first error)."""
    from ..errors import PlcError
    from ..project import compile_sources
    from ..testing import TestResult, run_compiled_tests

    try:
        compiled = compile_sources([(text, filename)], dialect=dialect)
    except PlcError as e:
        return TestResult(title, e.location or Location(filename), False,
                          f"the file does not compile: {e.code}: {e.message}",
                          e.location, e.code)
    compiled.tests = [t for t in compiled.tests if t[0] == title]
    results = run_compiled_tests(compiled)
    if not results:
        return TestResult(title, Location(filename), False, f"no TEST '{title}' in the file")
    return results[0]
