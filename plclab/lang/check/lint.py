"""Pass: the beginner lint -- warnings about programs that compile but rarely do what a
beginner meant (PLC0210-PLC0216). Runs on a checked program (the annotations of the other
passes: ``Expr.ty``, ``Name.sym``, ``Call.target``), in ``plclab check`` and before ``plclab
lab check``; never after a syntax error (its findings would be follow-ons).

* PLC0210 a timer, counter or edge block whose inputs are set or outputs read, never called;
* PLC0211 a timer, counter or edge block called only inside IF/CASE (it misses the edge);
* PLC0212 an output (``%Q``) assigned twice, unconditionally, in one scan (double coil);
* PLC0213 an integer division whose result becomes a REAL (the fraction is lost first);
* PLC0214 no located variables: the program reads no input and drives no output (a PLCopen
  XML export only with a lab's I/O table: its I/O mapping lives in the IDE's project);
* PLC0215 an address that contradicts the lab's I/O table (``lab check`` only);
* PLC0216 no program at all: an empty or comment-only file.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, Protocol

from ...errors import Diagnostic, Location
from .. import ast as A
from .. import types as T
from ..builtins import BLOCKS
from ..walk import walk

MEMORY_BLOCKS = frozenset(n for n, b in BLOCKS.items()
                          if b.library == "stdlib.st" and n not in ("SR", "RS"))
"""Blocks that remember an edge or a time: called only sometimes, they miss it."""
_CONDITIONAL = (A.If, A.Case)
_REAL = ("REAL", "LREAL")


class IoRow(Protocol):
    """A row of a lab's I/O table: a name and an address."""

    name: str
    address: str


def lint(files: list[A.SourceFile], io_table: Iterable[IoRow] | None = None
         ) -> list[Diagnostic]:
    """The beginner warnings of checked ``files`` (see the module docstring); with a lab's
    ``io_table`` also the addresses that contradict it."""
    out: list[Diagnostic] = []

    def warn(code: str, msg: str, loc: Location | None) -> None:
        out.append(Diagnostic(code, msg, loc, "warning"))

    files = [f for f in files if not f.file.startswith("<plclab>")]  # not the library
    pous = [p for f in files for p in f.pous if p.native is None]
    programs = [p for p in pous if p.kind == "PROGRAM"]
    if not pous and not any(f.tests or f.configs or f.globals or f.types for f in files):
        for f in files:
            warn("PLC0216", "the file holds no program: write PROGRAM Main ... END_PROGRAM "
                 "with the statements of your controller", Location(f.file, 1, 1))
        return out
    for p in programs:
        if not [s for s in p.body if not isinstance(s, A.Empty)]:
            warn("PLC0216", f"PROGRAM {p.spelling or p.name} has no statements: it does "
                 "nothing in any scan", p.loc)
    for p in pous:
        _blocks(p, warn)
        _double_writes(p, warn)
        _int_division(p, warn)
    located = [d for f in files for d in _decls(f) if d.address]
    direct = any(isinstance(n, A.DirectAddr) for p in pous for s in p.body for n in walk(s))
    # a configuration may wire the program instead: VAR_CONFIG addresses or its connections
    direct = direct or any(f.config_vars or any(c.config_vars or any(
        i.call is not None for i in c.instances) for c in f.configs) for f in files)
    # A PLCopen XML export keeps its I/O mapping in the IDE's project, outside the file
    # (Beremiz, OpenPLC Editor): without a lab's I/O table to hold it to, no PLC0214.
    exported = all(f.file.lower().endswith(".xml") for f in files)
    if programs and not located and not direct and (io_table is not None or not exported):
        p = programs[0]
        warn("PLC0214", f"PROGRAM {p.spelling or p.name} has no located variables: it reads "
             "no input and drives no output; declare them with AT, e.g. START AT %IX0.0 : "
             "BOOL;", p.loc)
    if io_table is not None:
        _io_table(located, list(io_table), warn)
    return out


def _decls(f: A.SourceFile) -> list[A.VarDecl]:
    out = [d for p in f.pous for d in p.decls]
    out += [d for g in f.globals for d in g.decls]
    out += [d for c in f.configs for d in c.globals]
    return out


def _name(d: A.VarDecl) -> str:
    return d.spelling or d.name


# ---------------------------------------------------------------------------- blocks


def _calls(stmts: list[A.Stmt], conditional: bool = False
           ) -> Iterable[tuple[A.Call, bool]]:
    """Every call in ``stmts`` with whether it sits inside an IF or CASE."""
    for s in stmts:
        inner = conditional or isinstance(s, _CONDITIONAL)
        if isinstance(s, A.If):
            for cond, body in s.branches:
                yield from ((c, conditional) for c in walk(cond) if isinstance(c, A.Call))
                yield from _calls(body, True)
            yield from _calls(s.orelse or [], True)
        elif isinstance(s, A.Case):
            yield from ((c, conditional) for c in walk(s.selector) if isinstance(c, A.Call))
            for b in s.branches:
                yield from _calls(b.body, True)
            yield from _calls(s.orelse or [], True)
        elif isinstance(s, A.For | A.While | A.Repeat):
            yield from _calls(s.body, inner)
            for n in walk(s):
                if isinstance(n, A.Call) and not any(n is x for b in s.body for x in walk(b)):
                    yield n, conditional
        else:
            yield from ((c, conditional) for c in walk(s) if isinstance(c, A.Call))


def _instance_of(e: Any) -> A.VarDecl | None:
    sym = getattr(e, "sym", None)
    decl = getattr(sym, "decl", None)
    return decl if isinstance(decl, A.VarDecl) else None


def _blocks(p: A.Pou, warn: Any) -> None:
    insts = {id(d): d for d in p.decls if _block_name(d) in MEMORY_BLOCKS}
    if not insts:
        return
    called: dict[int, list[bool]] = {}
    for call, conditional in _calls(p.body):
        d = _instance_of(call.func)
        if d is not None and id(d) in insts:
            called.setdefault(id(d), []).append(conditional)
    touched: dict[int, A.Member] = {}
    for s in p.body:
        for n in walk(s):
            if isinstance(n, A.Member):
                d = _instance_of(n.obj)
                if d is not None and id(d) in insts:
                    touched.setdefault(id(d), n)
    for key, d in insts.items():
        kind = _block_name(d)
        if key not in called and key in touched:
            warn("PLC0210", f"{_name(d)} ({kind}) is never called: setting its inputs or "
                 f"reading {_name(d)}.Q does not run it; call it once every scan, e.g. "
                 f"{_name(d)}(IN := ..., PT := T#5s);" if kind in ("TON", "TOF", "TP", "TONR")
                 else f"{_name(d)} ({kind}) is never called: setting its inputs or reading "
                 f"its outputs does not run it; call it once every scan",
                 touched[key].loc)
        elif key in called and all(called[key]):
            warn("PLC0211", f"{_name(d)} ({kind}) is called only inside IF/CASE: in the scans "
                 "it is not called it does not see its input fall or time pass; call it "
                 "unconditionally, every scan, and use the condition as its input", d.loc)


def _block_name(d: A.VarDecl) -> str:
    ty = getattr(d, "ty", None)
    if isinstance(ty, T.FBType):
        return ty.name.upper()
    tref = d.type
    return getattr(tref, "name", "").upper() if isinstance(tref, A.NamedTypeRef) else ""


# ---------------------------------------------------------------------------- outputs


def _output_key(e: A.Expr) -> str | None:
    if isinstance(e, A.DirectAddr) and e.address.upper().startswith("%Q"):
        return e.address.upper()
    d = _instance_of(e) if isinstance(e, A.Name) else None
    if d is not None and d.address and d.address.upper().startswith("%Q"):
        return d.address.upper()
    return None


def _double_writes(p: A.Pou, warn: Any) -> None:
    first: dict[str, A.Assign] = {}
    for s in p.body:  # the top level only: writes inside IF/CASE are set/reset patterns
        if not isinstance(s, A.Assign) or s.op != ":=":
            continue
        key = _output_key(s.target)
        if key is None:
            continue
        if key in first:
            prev = first[key]
            warn("PLC0212", f"the output {key} is written twice in every scan (first at line "
                 f"{prev.loc.line}): only the last write reaches the output; combine the "
                 "conditions into one assignment (a OR b)", s.loc)
        else:
            first[key] = s


# ---------------------------------------------------------------------------- division


def _is_int(e: Any) -> bool:
    ty = getattr(e, "ty", None)
    return ty is not None and T.resolve(ty).kind in ("int", "bits")


def _int_divisions(e: A.Expr) -> list[A.Binary]:
    out = []
    for n in walk(e):
        if isinstance(n, A.Binary) and n.op == "/" and _is_int(n.left) and _is_int(n.right):
            out.append(n)
    return out


def _real_sinks(p: A.Pou) -> Iterable[A.Expr]:
    """Expressions whose value becomes a REAL: assigned to one, or converted to one."""
    for s in p.body:
        for n in walk(s):
            if isinstance(n, A.Assign):
                ty = getattr(n.target, "ty", None)
                if ty is not None and T.resolve(ty).name in _REAL:
                    yield n.value
            elif isinstance(n, A.Call) and isinstance(n.func, A.Name):
                fn = n.func.name.upper()
                if fn.endswith(("_TO_REAL", "_TO_LREAL")) or fn in ("TO_REAL", "TO_LREAL"):
                    yield from (a.value for a in n.args if a.value is not None)


def _int_division(p: A.Pou, warn: Any) -> None:
    seen: set[int] = set()
    for e in _real_sinks(p):
        for b in _int_divisions(e):
            if id(b) in seen:
                continue
            seen.add(id(b))
            warn("PLC0213", "an integer division in a REAL formula: the fraction is cut off "
                 "before the result becomes a REAL (7 / 2 = 3); convert first, e.g. "
                 "INT_TO_REAL(a) / INT_TO_REAL(b), or write 2.0", b.loc)


# ---------------------------------------------------------------------------- I/O table


def _io_table(located: list[A.VarDecl], rows: list[IoRow], warn: Any) -> None:
    by_name = {r.name.upper(): r for r in rows}
    by_addr = {r.address.upper(): r for r in rows}
    for d in located:
        addr = (d.address or "").upper()
        row = by_name.get(d.name.upper())
        if row is not None and row.address.upper() != addr:
            warn("PLC0215", f"{_name(d)} is at {d.address}, but the lab's I/O table has "
                 f"{row.name} at {row.address}: write {_name(d)} AT {row.address}", d.loc)
        elif row is None and addr[:2] in ("%I", "%Q") and addr not in by_addr:
            table = ", ".join(f"{r.name} {r.address}" for r in rows)
            warn("PLC0215", f"{_name(d)} AT {d.address}: the lab wires nothing to that "
                 f"address (its I/O table: {table})", d.loc)
