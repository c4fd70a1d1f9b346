"""The compiler: a checked :class:`~plclab.lang.check.Project` -> Python source -> code object.

Design rules (DESIGN.md, principle 2):

* every POU becomes a plain Python class or function; a scan calls ``_body()`` methods;
* user text reaches the generated code only as upper-cased identifiers (``[A-Z0-9_]``, which
  can never be a Python keyword or builtin) or as ``repr()`` literals;
* each generated line remembers the source location it came from, so a runtime fault can be
  reported at ``file:line:col`` of the ST source.
"""

from __future__ import annotations

import bisect
import heapq
import math
import re
from dataclasses import dataclass, field
from typing import Any

from ..errors import Location, PlcError
from ..lang import ast as A
from ..lang import types as T
from ..lang.builtins import BUILTINS
from ..lang.check import CallInfo, EnumSym, ProgSym, Project, VarSym
from ..lang.dialect import profile as dialect_profile
from ..lang.limits import compiler_guard
from ..lang.walk import UnhandledNode, walk
from . import oop_emit
from .builtins_emit import EMITTERS, Emission, const_int
from .fastpaths import FastPaths
from .pycompile import compile_lines
from .real32 import f32 as _f32

_IDENT = re.compile(r"^[A-Z_][A-Z0-9_]*$")
_SIMPLE = (A.Name, A.Member, A.Index, A.Literal)


_IDENTS: dict[str, str] = {}  # name -> its checked spelling (the generator asks many times)


def ident(name: str) -> str:
    """The Python spelling of an ST identifier: upper case, checked to be a plain identifier."""
    up = _IDENTS.get(name)
    if up is not None:
        return up
    up = name.upper()
    if not _IDENT.match(up):
        raise ValueError(f"not an identifier: {name!r}")
    if len(_IDENTS) > 100_000:  # a long-lived process compiling many programs
        _IDENTS.clear()
    _IDENTS[name] = up
    return up


def program_attr(instance: str) -> str:
    """The attribute of ``_P`` holding a program instance: its name, ``RESA.MAIN`` (a program
    of one of two or more resources, ADR 0037) as ``RESA__MAIN``."""
    return ident(instance.replace(".", "__"))


def member_path(owner: str, via: tuple[str, ...], decl: A.VarDecl) -> str:
    """``owner.fb1.x``: the Python path of ``decl`` reached through the members ``via``."""
    return owner + "".join(f".{ident(m)}" for m in via) + f".{ident(decl.name)}"


@dataclass
class Compiled:
    source: str
    code: tuple[Any, ...]  # code objects, executed in order into one namespace (ADR 0034)
    filename: str
    line_where: list[int]  # generated line (1-based index - 1) -> index into locations
    locations: list[Location | None]
    project: Project
    natives: dict[str, str]
    tests: list[tuple[str, str, Location]] = field(default_factory=list)  # (title, fn, loc)
    assert_texts: dict[int, str] = field(default_factory=dict)
    located: list[str] = field(default_factory=list)  # addresses of located variables

    def location_of_line(self, lineno: int) -> Location | None:
        if 1 <= lineno <= len(self.line_where):
            return self.locations[self.line_where[lineno - 1]]
        return None


class Codegen(FastPaths):
    def __init__(self, project: Project, filename: str = "<plclab>") -> None:
        self.p = project
        self.filename = filename
        self.lines: list[str] = []
        self.line_where: list[int] = []
        self.locations: list[Location | None] = [None]
        self._loc_index: dict[Location, int] = {}
        self.where_now = 0
        self.ind = 0
        self.tmp = 0
        self.pre: list[str] = []
        self.natives: dict[str, str] = {}
        self.pou: A.Pou | None = None
        self.loops: list[tuple[str, A.Expr | None]] = []
        self.safe: dict[str, tuple[int, int]] = {}  # loop var code -> (min, max) known range
        self.struct_names: dict[int, str] = {}
        self.assert_texts: dict[int, str] = {}
        self.tests: list[tuple[str, str, Location]] = []
        self.jump_labels: dict[str, int] | None = None  # label -> state while in a jump body
        self.seg_index = 0
        # size handling (see "-- sizes" below)
        self._levels = [0]  # expression nesting since the last temporary, per open ex() call
        self._memo: dict[int, tuple[str, int]] = {}  # code of chain nodes made ahead, by id
        self.helpers: list[tuple[list[str], list[int]]] = []  # outlined blocks (module level)
        self.struct_cls: dict[int, str] = {}  # id(StructType) -> its generated class
        self.tables: list[str] = []  # module-level CASE tables
        self.locals: set[str] = set()  # Python locals (v_X) of the function being generated
        self.has_self = False  # the function being generated is a method (self.X members)
        self.helper: _Helper | None = None  # the outlined block being generated, if any
        self.init_fast_paths()  # fastpaths.py (ADR 0024)

    # -- emission -----------------------------------------------------------------------------
    def where(self, loc: Location | None) -> int:
        if loc is None:
            return 0
        i = self._loc_index.get(loc)
        if i is None:
            i = len(self.locations)
            self.locations.append(loc)
            self._loc_index[loc] = i
        return i

    def emit(self, line: str) -> None:
        self.lines.append("    " * self.ind + line)
        self.line_where.append(self.where_now)

    def flush_pre(self) -> None:
        pre, self.pre = self.pre, []
        for line in pre:
            self.emit(line)

    def new_tmp(self, stem: str = "_t") -> str:
        self.tmp += 1
        return f"{stem}{self.tmp}"

    def forward_defaults(self, decls: list[A.VarDecl], lhs) -> None:
        """Before the initial values of ``decls`` (in order): the default value of every
        variable that an initial value reads before its own declaration gives it one
        (``a : INT := b; b : INT := 7;`` reads b's default 0, as the PLC's zeroed memory
        would); ``lhs(d)`` is the code of a variable."""
        index = {id(d): i for i, d in enumerate(decls)}
        early: list[A.VarDecl] = []
        for i, d in enumerate(decls):
            if d.init is None:
                continue
            for n in walk(d.init):
                if isinstance(n, A.Name) and isinstance(n.sym, VarSym):
                    j = index.get(id(n.sym.decl))
                    if j is not None and j >= i and n.sym.decl not in early:
                        early.append(n.sym.decl)
        for d in early:
            self.emit(f"{lhs(d)} = {self.default_code(d.ty)}")

    def emit_init(self, lhs: str, d: A.VarDecl, init: A.Expr | None = None) -> None:
        """``lhs = <initial value of d>`` (or of ``init`` when given), after the temporaries
        the value needs."""
        code = self.init_code(init if init is not None else d.init, d.ty)
        bound = getattr(d.type, "bound", None)
        if bound and init is None and d.init is None:  # a : FB(k := 3): FB_init's inputs
            code = code[:-1] + ", ".join(
                self.coerce(self.ex(v), v.ty, x.ty, v) if v is not None else
                self.init_code(x.init, x.ty) for x, v in bound) + ")"
        self.flush_pre()
        self.emit(f"{lhs} = {code}")

    # -- driver -------------------------------------------------------------------------------
    def generate(self) -> Compiled:
        with compiler_guard():  # nesting recurses; the checker enforced the limits
            try:
                self.generate_source()
            except RecursionError:  # a safety net: the limits should prevent it
                raise PlcError("PLC0191", "this part of the program is too large or too deeply "
                               "nested to compile; split it into smaller parts (FUNCTIONs, "
                               "intermediate variables)",
                               self.locations[self.where_now]) from None
        src = "\n".join(self.lines) + "\n"
        try:  # Python's own compiler recursion stays at its normal limit (no C stack overflow)
            with compiler_guard(recursion_limit=0):
                code = compile_lines(self.lines, self.filename)  # in pieces (ADR 0034)
        except (SyntaxError, RecursionError, MemoryError) as exc:
            line = getattr(exc, "lineno", None) or 0
            loc = self.locations[self.line_where[line - 1]] if 0 < line <= len(
                self.line_where) else None
            if not isinstance(exc, MemoryError):
                # the generator wrote code Python refuses (the checker's limits keep programs
                # within Python's): plclab's bug, never the student's size limit
                what = exc.msg if isinstance(exc, SyntaxError) else type(exc).__name__
                raise PlcError("PLC9990", "internal compiler error: plclab generated code that "
                               f"Python cannot compile ({what}). This is a bug in plclab, "
                               "not in your program; please report it with the program. Writing "
                               "this statement another way may avoid it", loc) from None
            raise PlcError("PLC0191", "this part of the program is too large or too deeply "
                           f"nested to compile ({type(exc).__name__}: {exc}); split it into "
                           "smaller parts (FUNCTIONs, intermediate variables)", loc) from None
        return Compiled(src, code, self.filename, self.line_where, self.locations, self.p,
                        self.natives, self.tests, self.assert_texts,
                        [v.address for v, _ in self.located()])

    def generate_source(self) -> None:
        # one class per structure type: TYPEs by name, a STRUCT written in a VAR section under
        # the __STRUCT_n key the checker gave it
        structs = [(name, t) for name, t in self.p.types.items() if isinstance(t, T.StructType)]
        self.struct_cls.update({id(t): f"S_{ident(name)}" for name, t in structs})
        for name, t in structs:
            self.struct_class(name, t)
        for pou in self.p.pous.values():
            if pou.kind == "FUNCTION":
                if pou.native:
                    self.natives[f"F_{ident(pou.name)}"] = pou.native
                else:
                    self.function(pou)
            elif pou.native:
                self.natives[f"P_{ident(pou.name)}"] = pou.native
            elif pou.kind != "INTERFACE":  # an interface has no code (ADR 0021)
                self.block_class(pou)
        oop_emit.inherit_methods(self)
        self.globals_class()
        self.programs_class()
        self.sync_functions()
        for i, t in enumerate(self.p.tests):
            self.test_function(i, t)
        self.where_now = 0
        for line in self.tables:
            self.emit(line)
        for lines, where in self.helpers:
            self.lines.extend(lines)
            self.line_where.extend(where)

    # -- defaults and initial values ----------------------------------------------------------
    def default_code(self, ty: T.Type) -> str:
        declared = T.declared_init(ty)
        if declared is not None:  # TYPE LEVEL : (LOW, HIGH) := HIGH
            return self.init_code(declared, ty)
        t = T.resolve(ty)
        if isinstance(t, T.VarArrayType):  # an ARRAY[*] in-out: bound at each call
            return "None"
        if isinstance(t, T.ArrayType):
            d = self.default_code(t.elem)
            if T.resolve(t.elem).is_aggregate:
                return f"[{d} for _ in range({t.size})]"
            return f"[{d}] * {t.size}"
        if isinstance(t, T.StructType):
            return f"{self.struct_cls[id(t)]}()"
        if isinstance(t, T.FBType):
            if t.pou.native:
                return f"P_{ident(t.name)}(_CTX)"
            return f"P_{ident(t.name)}()"
        return repr(T.default_value(t))

    def init_code(self, e: A.Expr | None, ty: T.Type) -> str:
        if e is None:
            return self.default_code(ty)
        t = T.resolve(ty)
        if isinstance(e, A.ArrayInit) and isinstance(t, T.ArrayType):
            vals: list[str] = []
            for rep, val in e.items:
                n = 1 if rep is None else int(rep.value)
                if isinstance(val, A.Literal) and val.kind == "DEFAULT":
                    code = self.default_code(t.elem)
                else:
                    code = self.init_code(val, t.elem)
                vals.extend([code] * n)
            vals = vals[: t.size]
            if len(vals) < t.size:
                d = self.default_code(t.elem)
                if T.resolve(t.elem).is_aggregate:
                    return "[" + ", ".join(vals) + f"] + [{d} for _ in range({t.size - len(vals)})]"
                return "[" + ", ".join(vals) + f"] + [{d}] * {t.size - len(vals)}"
            return "[" + ", ".join(vals) + "]"
        if isinstance(e, A.StructInit):
            fields = t.fields if isinstance(t, T.StructType) else {
                d.name: d for d in t.pou.decls}
            kv = ", ".join(
                f"{ident(n)}={self.init_code(v, fields[n].ty)}" for n, v, _ in e.fields
                if n in fields
            )
            return f"_setattrs({self.default_code(t)}, {kv})" if kv else self.default_code(t)
        return self.coerce(self.ex(e), e.ty, ty, e)

    # -- classes ------------------------------------------------------------------------------
    def struct_class(self, name: str, st: T.StructType) -> None:
        cls = f"S_{ident(name)}"
        fields = list(st.fields.values())
        self.emit(f"class {cls}:")
        self.ind += 1
        self.emit("__slots__ = (" + "".join(f"{ident(d.name)!r}, " for d in fields) + ")")
        self.emit("def __init__(self):")
        self.ind += 1
        for d in fields:
            self.where_now = self.where(d.loc)
            self.emit_init(f"self.{ident(d.name)}", d)
        if not fields:
            self.emit("pass")
        self.ind -= 1
        self.emit(self.copier_line(fields))
        self.ind -= 1
        self.emit("")

    def copier_line(self, decls: list[A.VarDecl]) -> str:
        """``_copy = _copier(...)``: the class's copy method, made by one runtime helper from
        the names of its members grouped the way :meth:`copy_code` copies them (ADR 0034)."""
        groups: tuple[list[str], ...] = ([], [], [], [])
        for d in decls:
            t = T.resolve(d.ty)
            if isinstance(t, T.ArrayType):
                groups[3 if T.resolve(t.elem).is_aggregate else 2].append(ident(d.name))
            elif isinstance(t, T.StructType | T.FBType):
                groups[1].append(ident(d.name))
            else:
                groups[0].append(ident(d.name))
        return "_copy = _copier(" + ", ".join(
            "(" + "".join(f"{n!r}, " for n in g) + ")" for g in groups) + ")"

    def copy_code(self, code: str, ty: T.Type) -> str:
        t = T.resolve(ty)
        if isinstance(t, T.ArrayType):
            if T.resolve(t.elem).is_aggregate:
                return f"[_e._copy() for _e in {code}]"
            return f"list({code})"
        if isinstance(t, T.StructType | T.FBType):
            return f"{code}._copy()"
        return code

    def member_decls(self, pou: A.Pou) -> list[A.VarDecl]:
        """The instance variables of ``pou``, inherited ones (EXTENDS) first."""
        return [d for d in self.p.symbols.members(pou).values()
                if d.section not in ("VAR_TEMP", "VAR_EXTERNAL")]

    def block_class(self, pou: A.Pou) -> None:
        cls = f"P_{ident(pou.name)}"
        self.pou = pou
        members = self.member_decls(pou)
        self.where_now = self.where(pou.loc)
        self.emit(f"class {cls}:")
        self.ind += 1
        self.emit("__slots__ = (" + "".join(f"{ident(d.name)!r}, " for d in members) + ")")
        oop_emit.interfaces_line(self, pou)
        # _fbinit: the values of FB_init's further inputs (a : FB(3)), for a block that has them
        self.emit("def __init__(self, *_fbinit):" if oop_emit.fb_init_inputs(self, pou) else
                  "def __init__(self):")
        self.ind += 1
        self.forward_defaults(members, lambda d: f"self.{ident(d.name)}")
        for d in members:
            self.where_now = self.where(d.loc)
            self.emit_init(f"self.{ident(d.name)}", d)
        oop_emit.init_calls(self, pou)
        self.emit("pass")
        self.ind -= 1
        self.emit(self.copier_line(members))
        self.emit("def _body(self):")
        self.ind += 1
        self.where_now = self.where(pou.loc)
        temps = [d for d in pou.decls if d.section == "VAR_TEMP"]
        self.forward_defaults(temps, lambda d: f"v_{ident(d.name)}")
        for d in temps:
            self.emit_init(f"v_{ident(d.name)}", d)
        self.function_body(pou.body, [d.name for d in pou.decls if d.section == "VAR_TEMP"], True)
        self.emit("return")
        self.ind -= 1
        oop_emit.emit_methods(self, pou)
        self.ind -= 1
        self.emit("")
        self.pou = None

    def function(self, pou: A.Pou) -> None:
        self.pou = pou
        params = [d for d in pou.decls if d.section in ("VAR_INPUT", "VAR_IN_OUT")]
        self.where_now = self.where(pou.loc)
        self.emit(f"def F_{ident(pou.name)}(" + ", ".join(f"v_{ident(d.name)}" for d in params)
                  + "):")
        self.ind += 1
        rd = pou.return_decl
        if rd.ty is not T.VOID:
            self.emit(f"v_{ident(pou.name)} = {self.default_code(rd.ty)}")
        own = [d for d in pou.decls if d.section in ("VAR", "VAR_TEMP", "VAR_OUTPUT")]
        self.forward_defaults(own, lambda d: f"v_{ident(d.name)}")
        for d in own:
            self.where_now = self.where(d.loc)
            self.emit_init(f"v_{ident(d.name)}", d)
        self.function_body(pou.body, [pou.name] + [d.name for d in pou.decls
                                                    if d.section != "VAR_EXTERNAL"], False)
        self.emit(self.function_return(pou))
        self.ind -= 1
        self.emit("")
        self.pou = None

    def function_return(self, pou: A.Pou) -> str:
        rd = pou.return_decl
        res = f"v_{ident(pou.name)}" if rd.ty is not T.VOID else "None"
        outs = [d for d in pou.decls if d.section in ("VAR_OUTPUT", "VAR_IN_OUT")]
        if not outs:
            return f"return {res}"
        return "return (" + res + ", " + ", ".join(f"v_{ident(d.name)}" for d in outs) + ")"

    def globals_class(self) -> None:
        self.emit("class _Globals:")
        self.ind += 1
        gl = list(self.p.globals.values())
        self.emit("__slots__ = (" + "".join(f"{ident(d.name)!r}, " for d in gl) + ")")
        self.emit("def __init__(self):")
        self.ind += 1
        self.emit("global _G")  # a global's initial value may name the globals above it
        self.emit("_G = self")
        self.forward_defaults(gl, lambda d: f"self.{ident(d.name)}")
        for d in gl:
            self.where_now = self.where(d.loc)
            self.emit_init(f"self.{ident(d.name)}", d)
        for r in self.p.symbols.resource_globals:  # after the configuration's (ADR 0037)
            self.emit(f"global _RG_{ident(r)}")
            self.emit(f"_RG_{ident(r)} = _Res_{ident(r)}()")
        self.emit("pass")
        self.ind -= 2
        self.emit("")
        for r, gs in self.p.symbols.resource_globals.items():
            self.emit(f"class _Res_{ident(r)}:")
            self.ind += 1
            self.emit("__slots__ = (" + "".join(f"{ident(n)!r}, " for n in gs) + ")")
            self.emit("def __init__(self):")
            self.ind += 1
            for d in gs.values():
                self.where_now = self.where(d.loc)
                self.emit_init(f"self.{ident(d.name)}", d)
            self.emit("pass")
            self.ind -= 2
            self.emit("")
        if self.p.symbols.resource_globals:
            self.emit("_R = None")

    def connected_program(self, name: str, pou: A.Pou, info: CallInfo) -> str:
        """``PROGRAM P1 : Prog(x := %IX1.1, y => %QX0.0)``: a class of the instance whose body
        takes its inputs, runs the program, then hands its outputs on; its name."""
        cls = f"C_{program_attr(name)}"
        base = f"P_{ident(pou.name)}"
        self.emit(f"class {cls}({base}):")
        self.ind += 1
        self.emit("__slots__ = ()")
        self.emit("def _body(self):")
        self.ind += 1
        vals = [(ident(d.name), self.coerce(self.ex(e), e.ty, d.ty, e)) for d, e in info.inputs]
        vals += [(ident(d.name), self.ex(e)) for d, e in info.inouts]
        self.flush_pre()
        for n, v in vals:
            self.emit(f"self.{n} = {v}")
        self.emit(f"{base}._body(self)")
        for d, e in info.inouts:
            if not T.resolve(d.ty).is_aggregate:
                self.assign_to(e, f"self.{ident(d.name)}")
        for d, target, neg in info.outputs:
            v = f"self.{ident(d.name)}"
            self.assign_to(target, self.coerce(f"(not {v})" if neg else v, d.ty, target.ty,
                                               None))
        self.ind -= 2
        self.emit("")
        return cls

    def programs_class(self) -> None:
        connected = {i.key: i.call.target for c in self.p.symbols.configs for i in c.instances
                     if i.call is not None and isinstance(i.call.target, CallInfo)}
        classes = {n: self.connected_program(n, pou, connected[n])
                   for n, pou, _ in self.p.programs if n in connected}
        for n, pou, _ in self.p.programs:  # a resource's instance sets its globals first
            res = self.p.symbols.resource_of(n)
            if res is not None and self.p.symbols.resource_globals:
                base = classes.get(n, f"P_{ident(pou.name)}")
                classes[n] = cls = f"R_{program_attr(n)}"
                self.emit(f"class {cls}({base}):")
                self.ind += 1
                self.emit("__slots__ = ()")
                self.emit("def _body(self):")
                self.ind += 1
                self.emit("global _R")
                self.emit(f"_R = {f'_RG_{ident(res)}' if res in self.p.symbols.resource_globals else 'None'}")
                self.emit(f"{base}._body(self)")
                self.ind -= 2
                self.emit("")
        self.emit("class _Programs:")
        self.ind += 1
        names = [n for n, _, _ in self.p.programs]
        self.emit("__slots__ = (" + "".join(f"{program_attr(n)!r}, " for n in names) + ")")
        self.emit("def __init__(self):")
        self.ind += 1
        for n, pou, _ in self.p.programs:
            self.emit(f"self.{program_attr(n)} = {classes.get(n, f'P_{ident(pou.name)}')}()")
        for b in self.p.symbols.config_bindings:  # VAR_CONFIG initial values, after the POUs'
            if b.init is not None:
                self.emit_init(member_path(f"self.{program_attr(b.instance)}", b.via, b.decl),
                               b.decl, b.init)
        self.emit("pass")
        self.ind -= 2
        self.emit("")

    def sync_functions(self) -> None:
        """The copies between located variables and the process image (ADR 0056): the image
        is the one truth, a located variable an alias of its bytes. ``_sync_in`` (scan start)
        loads every located variable from its bytes (%I, and %Q and %M too, so that a direct
        address, an overlapping variable or a write from outside the program is seen) and
        remembers what it loaded; ``_sync_out`` (scan end) writes back only the %Q and %M
        variables the program changed, so an unchanged word does not wipe a bit written
        through ``%QX3.0``, then loads them all again, so that after a scan every variable
        shows its bytes; ``_sync_init`` (after a restart) writes every %Q and %M variable
        with its initial value."""
        ins: list[str] = []
        outs: list[str] = []
        reload: list[str] = []
        init: list[str] = []
        k = 0
        for v, path in self.located():
            area = v.address[1]
            rd = self.addr_read(v.address, v.decl.ty)
            if area == "I":
                ins.append(f"{path} = {rd}")
                continue
            write = self.addr_write(v.address, path, v.decl.ty)
            ins.append(f"{path} = _LOC[{k}] = {rd}")
            outs.append(f"if {path} != _LOC[{k}]: {write}")
            reload.append(f"{path} = {rd}")
            init.append(write)
            k += 1
        self.emit(f"_LOC = [None] * {k}")
        for name, body in (("_sync_in", ins), ("_sync_out", outs + reload), ("_sync_init", init)):
            self.emit(f"def {name}():")
            self.ind += 1
            for line in body:
                self.emit(line)
            self.emit("pass")
            self.ind -= 1
        self.emit("")

    def located(self):
        """(declaration, Python path) of every located variable with a concrete address."""
        for v in self.p.symbols.located_vars():
            if not v.wildcard:
                owner = (f"_RG_{ident(v.resource)}" if v.resource else "_G") \
                    if v.instance is None else f"_P.{program_attr(v.instance)}"
                yield v, member_path(owner, v.via, v.decl)

    # -- process image access -----------------------------------------------------------------
    @staticmethod
    def parse_addr(addr: str) -> tuple[str, str, int, int]:
        area = addr[1]
        size = addr[2] if addr[2].isalpha() else "X"
        rest = addr[3:] if addr[2].isalpha() else addr[2:]
        parts = rest.split(".")
        return area, size, int(parts[0]), int(parts[1]) if len(parts) > 1 else 0

    def addr_read(self, addr: str, ty: T.Type | None = None) -> str:
        area, size, byte, bit = self.parse_addr(addr)
        buf = f"_{area}"
        if size == "X":
            return f"({buf}[{byte}] >> {bit} & 1 != 0)"
        n = {"B": 1, "W": 2, "D": 4, "L": 8}[size]
        t = T.base_of(ty) if ty is not None else None
        if t is not None and t.kind == "real":
            fmt = ">f" if n == 4 else ">d"
            return f"_unpack_from({fmt!r}, {buf}, {byte})[0]"
        signed = bool(t is not None and getattr(t, "signed", False) and t.kind in ("int", "time"))
        if n == 1 and not signed:
            return f"{buf}[{byte}]"
        return f"int.from_bytes({buf}[{byte}:{byte + n}], 'big', signed={signed})"

    def addr_write(self, addr: str, value: str, ty: T.Type | None = None) -> str:
        area, size, byte, bit = self.parse_addr(addr)
        buf = f"_{area}"
        if size == "X":
            return (f"{buf}[{byte}] = ({buf}[{byte}] | {1 << bit}) if {value} else "
                    f"({buf}[{byte}] & {0xFF ^ (1 << bit)})")
        n = {"B": 1, "W": 2, "D": 4, "L": 8}[size]
        t = T.base_of(ty) if ty is not None else None
        if t is not None and t.kind == "real":
            fmt = ">f" if n == 4 else ">d"
            return f"_pack_into({fmt!r}, {buf}, {byte}, {value})"
        mask = (1 << (8 * n)) - 1
        return f"{buf}[{byte}:{byte + n}] = (({value}) & {mask}).to_bytes({n}, 'big')"

    # -- tests --------------------------------------------------------------------------------
    def test_function(self, i: int, t: A.TestBlock) -> None:
        fn = f"_test_{i}"
        self.tests.append((t.title, fn, t.loc))
        self.where_now = self.where(t.loc)
        self.emit(f"def {fn}():")
        self.ind += 1
        for d in t.decls:
            self.where_now = self.where(d.loc)
            self.emit_init(f"v_{ident(d.name)}", d)
        self.function_body(t.body, [d.name for d in t.decls], False)
        self.emit("return")
        self.ind -= 1
        self.emit("")

    # -- statements ---------------------------------------------------------------------------
    def function_body(self, stmts: list[A.Stmt], local_names: list[str], has_self: bool) -> None:
        """The statements of a generated function whose ST locals are ``v_X`` Python locals."""
        self.locals = {f"v_{ident(n)}" for n in local_names}
        self.has_self = has_self
        self.block(stmts)
        self.locals = set()

    def block(self, stmts: list[A.Stmt]) -> None:
        if self.jump_labels is None and any(isinstance(s, A.Jump) for s in stmts):
            self.jump_block(stmts)
            return
        if stmts and (self.ind >= OUTLINE_INDENT or len(self.loops) >= OUTLINE_LOOPS):
            self.outline(stmts)
            return
        n = len(self.lines)
        for s in stmts:
            self.stmt(s)
        if len(self.lines) == n:
            self.emit("pass")

    def jump_block(self, stmts: list[A.Stmt]) -> None:
        """A body with jumps (IL) becomes a program-counter state machine: one ``if _pc <= k``
        block per label, in order, so falling through needs no code; a jump sets ``_pc`` and
        restarts the loop. Backward jumps are charged to the watchdog budget like loops."""
        segs: list[list[A.Stmt]] = [[]]
        labels: dict[str, int] = {}
        for s in stmts:
            if isinstance(s, A.Label):
                if segs[-1] or len(segs) > 1 or labels:
                    segs.append([])
                labels[s.name] = len(segs) - 1
            else:
                segs[-1].append(s)
        self.jump_labels = labels
        self.emit("_pc = 0")
        self.emit("while True:")
        self.ind += 1
        for k, seg in enumerate(segs):
            self.seg_index = k
            self.emit(f"if _pc <= {k}:")
            self.ind += 1
            n = len(self.lines)
            for s in seg:
                self.stmt(s)
            if len(self.lines) == n:
                self.emit("pass")
            self.ind -= 1
        self.emit("break")
        self.ind -= 1
        self.jump_labels = None

    def s_Label(self, s: A.Label) -> None:
        pass

    def s_Jump(self, s: A.Jump) -> None:
        labels = self.jump_labels or {}
        target = labels[s.label]
        if s.cond is not None:
            cond = self.ex(s.cond)
            self.flush_pre()
            self.emit(f"if {cond}:")
            self.ind += 1
        if target <= self.seg_index:  # backward: may loop, so it costs watchdog budget
            self._watchdog(s.loc)
        self.emit(f"_pc = {target}")
        self.emit("continue")
        if s.cond is not None:
            self.ind -= 1

    def stmt(self, s: A.Stmt) -> None:
        self.where_now = self.where(s.loc)
        m = getattr(self, "s_" + type(s).__name__, None)
        if m is None:
            raise UnhandledNode("Codegen.stmt", s)
        m(s)

    def s_Empty(self, s: A.Empty) -> None:
        pass

    def s_Assign(self, s: A.Assign) -> None:
        tt = s.target.ty
        if s.op in ("S=", "R="):
            val = self.ex(s.value)
            self.flush_pre()
            self.emit(f"if {val}:")
            self.ind += 1
            self.assign_to(s.target, "True" if s.op == "S=" else "False")
            self.ind -= 1
            return
        raw = self.ex(s.value)
        val = self.coerce(raw, s.value.ty, tt, s.value)
        if T.resolve(tt).is_aggregate and not isinstance(s.value, A.Call):
            val = self.copy_code(val, tt)
        self.flush_pre()
        if not self.real_store(s.target, raw, val):  # fast path (fastpaths.py)
            self.assign_to(s.target, val)

    def assign_to(self, target: A.Expr, val: str) -> None:
        if isinstance(target, A.Member) and isinstance(target.sym, A.Pou):  # a PROPERTY's SET
            code = oop_emit.property_call(self, target, val)
            self.flush_pre()
            self.emit(code)
            return
        if isinstance(target, A.Name) and isinstance(target.sym, A.Pou):  # bare PROPERTY: SET
            self.emit(f"self.{oop_emit.method_name(target.sym)}({val})")
            return
        if isinstance(target, A.Member) and target.field_name == "^":  # r^ := v (ADR 0021)
            code = oop_emit.deref(self, target)
            self.flush_pre()
            self.emit(f"{code}.set({val})")
            return
        if isinstance(target, A.Member) and target.field_name.startswith("%"):
            code = self.store_code(target, val)
            self.flush_pre()
            self.emit(code)
            return
        if isinstance(target, A.DirectAddr):
            self.emit(self.addr_write(target.address, val))
            return
        lv = self.ex(target)
        self.flush_pre()
        self.emit(f"{lv} = {val}")

    def s_CallStmt(self, s: A.CallStmt) -> None:
        c = s.call
        info: CallInfo | None = c.target
        if info is None:
            return
        if info.kind in ("fb", "program"):
            if info.en is None and info.eno is None:
                self.fb_call(c, info)
                return
            # EN/ENO (IEC 61131-3 ed.3 6.6.1.6): the body runs only when EN; ENO tells whether
            en = self.new_tmp()
            code = self.ex(info.en) if info.en is not None else "True"
            self.flush_pre()
            self.emit(f"{en} = {code}")
            self.emit(f"if {en}:")
            self.ind += 1
            self.fb_call(c, info)
            self.emit("pass")
            self.ind -= 1
            for code in self.eno_false(info, en):
                self.emit(code)
            if info.eno is not None:
                self.assign_to(info.eno, en)
            return
        if info.kind == "action":  # inst.A(...): the POU's inputs, its action, its outputs
            self.fb_call(c, info)
            return
        if info.kind == "builtin" and info.callee.statement_only:
            self.test_builtin(c, info)
            return
        code = self.ex(c)
        self.flush_pre()
        self.emit(code)

    def fb_call(self, c: A.Call, info: CallInfo) -> None:
        run = "_body()"
        if info.kind == "action":  # CODESYS action (ADR 0035): on the instance before the dot
            assert isinstance(c.func, A.Member)
            inst = self.ex(c.func.obj)
            run = f"{oop_emit.method_name(info.callee)}()"
        elif info.kind == "program":
            inst = f"_P.{ident(c.func.name)}"  # type: ignore[union-attr]
        elif oop_emit.is_super(c.func):  # SUPER^(): the base block's body on this instance
            self.flush_pre()
            self.emit(f"P_{ident(info.callee.name)}._body(self)")
            return
        else:
            inst = self.ex(c.func)
        fb = inst
        if not (info.inputs or info.outputs or info.inouts) and "[" not in inst:
            self.flush_pre()
            self.emit(f"{inst}.{run}")
            return
        if "." in inst or "[" in inst:
            fb = "_fb"
        vals = [(ident(d.name), self.coerce(self.ex(e), e.ty, d.ty, e)) for d, e in info.inputs]
        inouts = [(d, self.inout_code(d, e), e) for d, e in info.inouts]
        self.flush_pre()
        if fb != inst:
            self.emit(f"{fb} = {inst}")
        for n, v in vals:
            self.emit(f"{fb}.{n} = {v}")
        for d, code, _ in inouts:
            self.emit(f"{fb}.{ident(d.name)} = {code}")
        self.emit(f"{fb}.{run}")
        for d, _code, e in inouts:
            if not T.resolve(d.ty).is_aggregate and not d.constant:
                self.assign_to(e, f"{fb}.{ident(d.name)}")
        for d, target, neg in info.outputs:
            v = f"{fb}.{ident(d.name)}"
            if neg:
                v = f"(not {v})"
            self.assign_to(target, self.coerce(v, d.ty, target.ty, None))

    def test_builtin(self, c: A.Call, info: CallInfo) -> None:
        name = info.callee.name
        args = [self.ex(e) for _, e in info.inputs]
        self.flush_pre()
        w = self.where(c.loc)
        if name == "ADVANCE_TIME":
            e = info.inputs[0][1]
            scale = 1 if T.resolve(e.ty) is T.TIME else None
            if scale is None:
                self.emit(f"_CTX.advance_ns({args[0]})")
            else:
                self.emit(f"_CTX.advance_ns({args[0]} * 1000000)")
            return
        nargs = {"ASSERT_EQ": 2, "ASSERT_NE": 2, "ASSERT_NEAR": 3}.get(name, 1)
        texts = [A.expr_text(e) for _, e in info.inputs[:nargs]]
        msg = info.inputs[nargs][1] if len(info.inputs) > nargs else None
        self.assert_texts[w] = ", ".join(texts) + (
            f": {msg.value}" if isinstance(msg, A.Literal) else "")
        kinds = [kind_name(e.ty) for _, e in info.inputs]
        if name in ("ASSERT_EQ", "ASSERT_NE"):
            k = kinds[0] if kinds[0] != "int?" else kinds[1]
            self.emit(f"_assert_cmp({args[0]}, {args[1]}, {name == 'ASSERT_EQ'}, {w}, {k!r})")
        elif name in ("ASSERT_TRUE", "ASSERT_FALSE"):
            self.emit(f"_assert_bool({args[0]}, {name == 'ASSERT_TRUE'}, {w})")
        elif name == "ASSERT_NEAR":
            self.emit(f"_assert_near({args[0]}, {args[1]}, {args[2]}, {w})")

    def s_If(self, s: A.If) -> None:
        if len(s.branches) > MAX_ELIF:
            self.if_flag(s)
            return
        first = True
        depth = 0
        for cond, body in s.branches:
            code = self.ex(cond)
            if first:
                self.flush_pre()
                self.emit(f"if {code}:")
            elif self.pre:
                self.emit("else:")
                self.ind += 1
                depth += 1
                self.flush_pre()
                self.emit(f"if {code}:")
            else:
                self.emit(f"elif {code}:")
            first = False
            self.ind += 1
            self.block(body)
            self.ind -= 1
            self.where_now = self.where(s.loc)
        if s.orelse:
            self.emit("else:")
            self.ind += 1
            self.block(s.orelse)
            self.ind -= 1
        self.ind -= depth

    def if_flag(self, s: A.If) -> None:
        """A long IF/ELSIF chain without nesting: a flag says that no branch was taken yet
        (``elif`` nests in Python's tree, and thousands of them overflow its compiler)."""
        todo = self.new_tmp("_m")
        self.emit(f"{todo} = True")
        for i, (cond, body) in enumerate(s.branches):
            self.where_now = self.where(s.loc)
            if i:
                self.emit(f"if {todo}:")
                self.ind += 1
            code = self.ex(cond)
            self.flush_pre()
            self.emit(f"if {code}:")
            self.ind += 1
            self.emit(f"{todo} = False")
            self.block(body)
            self.ind -= 2 if i else 1
        if s.orelse:
            self.where_now = self.where(s.loc)
            self.emit(f"if {todo}:")
            self.ind += 1
            self.block(s.orelse)
            self.ind -= 1

    def s_Case(self, s: A.Case) -> None:
        sel = self.own_value(self.ex(s.selector), s.selector)
        self.flush_pre()
        tmp = self.new_tmp("_c")
        self.emit(f"{tmp} = {sel}")
        if sum(len(b.labels) for b in s.branches) > SMALL_CASE and self.case_table(s, tmp):
            return
        kw = "if"
        for b in s.branches:
            tests = []
            for lab in b.labels:
                if isinstance(lab, tuple):
                    tests.append(f"{self.ex(lab[0])} <= {tmp} <= {self.ex(lab[1])}")
                else:
                    tests.append(f"{tmp} == {self.ex(lab)}")
            self.emit(f"{kw} " + " or ".join(tests) + ":")
            kw = "elif"
            self.ind += 1
            self.block(b.body)
            self.ind -= 1
        if s.orelse:
            if kw == "if":
                self.block(s.orelse)
            else:
                self.emit("else:")
                self.ind += 1
                self.block(s.orelse)
                self.ind -= 1

    def _watchdog(self, loc: Location) -> None:
        for line in self.watchdog_lines(self.where(loc)):  # fastpaths.py
            self.emit(line)

    def s_While(self, s: A.While) -> None:
        if not self.local_watchdog(s.body, s.cond, lambda: self.plain_while(s)):
            self.plain_while(s)

    def plain_while(self, s: A.While) -> None:
        cond = self.ex(s.cond)
        if self.pre:
            pre, self.pre = self.pre, []
            self.emit("while True:")
            self.ind += 1
            self._watchdog(s.loc)
            for line in pre:
                self.emit(line)
            self.emit(f"if not {cond}: break")
        else:
            self.emit(f"while {cond}:")
            self.ind += 1
            self._watchdog(s.loc)
        self.loops.append(("while", None))
        self.block(s.body)
        self.loops.pop()
        self.ind -= 1

    def s_Repeat(self, s: A.Repeat) -> None:
        if not self.local_watchdog(s.body, s.cond, lambda: self.plain_repeat(s)):
            self.plain_repeat(s)

    def plain_repeat(self, s: A.Repeat) -> None:
        self.emit("while True:")
        self.ind += 1
        self._watchdog(s.loc)
        self.loops.append(("repeat", s.cond))
        self.block(s.body)
        self.loops.pop()
        self.where_now = self.where(s.cond.loc)
        cond = self.ex(s.cond)
        self.flush_pre()
        self.emit(f"if {cond}: break")
        self.ind -= 1

    def s_Exit(self, s: A.Exit) -> None:
        if self.helper is not None and not self.loops:  # the loop is outside this helper
            self.helper_return(EXIT)
            return
        self.emit("break")

    def s_Continue(self, s: A.Continue) -> None:
        if self.helper is not None and not self.loops:
            self.helper_return(CONTINUE)
            return
        kind, cond = self.loops[-1] if self.loops else ("while", None)
        if kind == "repeat" and cond is not None:
            c = self.ex(cond)
            self.flush_pre()
            self.emit(f"if {c}: break")
        self.emit("continue")

    def s_Return(self, s: A.Return) -> None:
        if self.helper is not None:
            self.helper_return(RETURN)
            return
        if self.pou is not None and self.pou.kind in ("FUNCTION", "METHOD"):
            self.emit(self.function_return(self.pou))
        else:
            self.emit("return")

    def s_For(self, s: A.For) -> None:
        if not self.local_for(s, self.plain_for):  # fastpaths.py
            self.plain_for(s)

    def plain_for(self, s: A.For) -> None:
        """FOR as the hardware runs it: ``v := v + step`` wraps at the variable's type limits.
        When the bounds and a literal step prove that the loop ends without wrapping, it is a
        plain Python ``range`` charged to the watchdog up front; otherwise ``_frange`` decides
        at run time (a ``range``, or a wrapping iterator that charges each pass)."""
        var = self.ex(s.var)
        start = self.coerce(self.ex(s.start), s.start.ty, s.var.ty, s.start)
        end = self.coerce(self.ex(s.end), s.end.ty, s.var.ty, s.end)
        self.flush_pre()
        w = self.where(s.loc)
        vt = T.base_of(s.var.ty)
        lo, hi = (vt.lo, vt.hi) if isinstance(vt, T.Elementary) and vt.bits else (None, None)
        step_v = None
        if s.step is None:
            step_v = 1
        elif isinstance(s.step, A.Literal) and isinstance(s.step.value, int):
            step_v = s.step.value
        has_exit = any(isinstance(x, A.Exit | A.Return) for x in A.walk_stmts(s.body))
        rng = self.new_tmp("_r")
        r_end = self._bound_range(s.end)
        proven = step_v is not None and step_v != 0 and (lo is None or r_end is not None and (
            r_end[1] + step_v <= hi if step_v > 0 else r_end[0] + step_v >= lo))
        if proven:
            stop = f"{end} + 1" if step_v > 0 else f"{end} - 1"
            if step_v == 1:
                self.emit(f"{rng} = range({start}, {stop})")
            else:
                self.emit(f"{rng} = range({start}, {stop}, {step_v})")
        else:
            step = self.ex(s.step) if s.step is not None else "1"
            self.flush_pre()
            budget = "None" if has_exit else "_B"
            self.emit(f"{rng} = _frange({start}, {end}, {step}, {lo}, {hi}, {w}, {budget})")
        if not has_exit:
            self.emit(f"_B.left -= len({rng})")
            self.emit(f"if _B.left < 0: _wd({w})")
        # a known range for the loop variable lets array indexing skip its bounds check
        r_start, r_end = self.interval(s.start), self.interval(s.end)
        saved = self.safe.get(var)
        if proven and r_start is not None and r_end is not None and self.loop_var_guarded(s):
            # inside the body the variable lies between start and end, whatever the step
            self.safe[var] = (min(r_start[0], r_end[0]), max(r_start[1], r_end[1]))
        else:
            self.safe.pop(var, None)
        self.emit(f"for {var} in {rng}:")
        self.ind += 1
        if has_exit:
            self._watchdog(s.loc)
        self.loops.append(("for", None))
        self.block(s.body)
        self.loops.pop()
        self.ind -= 1
        self.emit("else:")
        self.ind += 1
        if proven:
            self.emit(f"{var} = {rng}.start + len({rng}) * {rng}.step")
        else:
            self.emit(f"{var} = _fend({rng})")
        self.ind -= 1
        if saved is not None:
            self.safe[var] = saved
        else:
            self.safe.pop(var, None)

    # -- sizes: deep blocks, large CASEs ------------------------------------------------------
    # Python limits what it compiles: 100 levels of indentation, 20 nested loops, nesting of
    # its own syntax tree (each ``elif`` is one level deeper), 200 nested parentheses. The
    # generated code stays under those limits whatever the size of the ST program:
    # * a block nested deeper than OUTLINE_INDENT (or inside OUTLINE_LOOPS loops) becomes a
    #   module-level helper function ``_hN`` (see :meth:`outline`);
    # * a CASE with many labels dispatches through a table and a binary tree of ifs;
    # * a long IF/ELSIF chain uses a flag instead of nested ``elif``;
    # * an expression gets a temporary every SPILL_LEVEL levels of nesting (see :meth:`ex`).
    def outline(self, stmts: list[A.Stmt]) -> None:
        """Emit ``stmts`` as a helper function at module level, and its call here.

        The helper takes ``self`` (in a method) and the ``v_X`` locals its code uses, and
        returns ``(signal, *locals)``: the locals it may have changed, and whether the block
        ended normally or by EXIT, CONTINUE or RETURN of a loop or function outside it; the
        call site then does the same in its own context (which may be another helper)."""
        self.outline_code(lambda: self.block(stmts), stmts[0].loc)

    def outline_code(self, make, loc: Location, extra: tuple[str, ...] = ()) -> None:
        """Like :meth:`outline` for the code that ``make()`` emits; ``extra`` are temporaries
        it reads (passed in, not returned)."""
        name = self.new_tmp("_h")
        call_where = self.where_now
        outer = (self.lines, self.line_where, self.ind, self.loops, self.helper, self.pre)
        self.lines, self.line_where, self.ind, self.loops, self.pre = [], [], 1, [], []
        helper = self.helper = _Helper()
        self.where_now = self.where(loc)
        make()
        self.helper_return(NORMAL)
        lines, where = self.lines, self.line_where
        self.lines, self.line_where, self.ind, self.loops, self.helper, self.pre = outer
        used = sorted(self.locals & set(_LOCAL_NAME.findall("\n".join(lines))))
        params = (["self"] if self.has_self else []) + list(extra) + used
        tail = "".join(f", {v}" for v in used)
        lines = [line.replace(_LOCALS, tail) for line in lines]
        self.helpers.append(([f"def {name}({', '.join(params)}):"] + lines + [""],
                             [where[0] if where else call_where] + where + [0]))
        self.where_now = call_where
        sig = self.new_tmp("_s")
        self.emit(f"{sig}{tail} = {name}({', '.join(params)})")
        for signal, stmt in ((EXIT, A.Exit), (CONTINUE, A.Continue), (RETURN, A.Return)):
            if signal in helper.signals:
                self.emit(f"if {sig} == {signal}:")
                self.ind += 1
                self.stmt(stmt(self.locations[call_where] or Location()))
                self.ind -= 1
                self.where_now = call_where

    def helper_return(self, signal: int) -> None:
        """Leave the helper being generated with ``signal`` (the locals are filled in later)."""
        assert self.helper is not None
        self.helper.signals.add(signal)
        self.emit(f"return {signal}{_LOCALS}")

    def case_table(self, s: A.Case, sel: str) -> bool:
        """A large CASE: the branch number from a dict (single values) or a binary search
        (ranges), then a balanced tree of ``if`` on that number. False if a label is not a
        known constant (the checker reports that), so the plain if-chain is used."""
        singles: dict[int, int] = {}
        ranges: list[tuple[int, int, int]] = []
        for k, b in enumerate(s.branches):
            for lab in b.labels:
                if isinstance(lab, tuple):
                    lo, hi = self.label_const(lab[0]), self.label_const(lab[1])
                    if lo is None or hi is None:
                        return False
                    if lo <= hi:
                        ranges.append((lo, hi, k))
                else:
                    v = self.label_const(lab)
                    if v is None:
                        return False
                    singles.setdefault(v, k)
        segments = _segments(ranges)
        if segments:  # a value in an earlier branch's range is not the later single's
            starts = [lo for lo, _, _ in segments]
            for v, k in list(singles.items()):
                i = bisect.bisect_right(starts, v) - 1
                if i >= 0 and v <= segments[i][1] and segments[i][2] < k:
                    del singles[v]
        nb = len(s.branches)
        table = self.new_tmp("_CASE")
        self.tables.append(f"{table} = dict(zip({tuple(singles)!r}, {tuple(singles.values())!r}))")
        k = self.new_tmp("_k")
        if segments:
            rng = self.new_tmp("_CASE")
            self.tables.append(f"{rng} = ({tuple(x[0] for x in segments)!r}, "
                               f"{tuple(x[1] for x in segments)!r}, "
                               f"{tuple(x[2] for x in segments)!r})")
            self.emit(f"{k} = {table}.get({sel})")
            self.emit(f"if {k} is None: {k} = _case_range({sel}, {rng}, {nb})")
        else:
            self.emit(f"{k} = {table}.get({sel}, {nb})")
        bodies = [b.body for b in s.branches] + ([s.orelse] if s.orelse else [])
        self.case_tree(s, k, bodies, 0, len(bodies))
        return True

    def case_tree(self, s: A.Case, k: str, bodies: list[list[A.Stmt]], lo: int, hi: int,
                  top: bool = True) -> None:
        """Branches ``lo..hi-1``: halve the range until a few are left, then test each. Parts
        of CASE_CHUNK branches go into helper functions (Python compiles many medium-sized
        functions faster than one huge one)."""
        self.where_now = self.where(s.loc)
        if top and hi - lo <= CASE_CHUNK < len(bodies):
            self.outline_code(lambda: self.case_tree(s, k, bodies, lo, hi, False), s.loc, (k,))
            return
        if hi - lo <= MAX_ELIF:
            for i in range(lo, hi):
                self.emit(f"{'if' if i == lo else 'elif'} {k} == {i}:")
                self.ind += 1
                self.block(bodies[i])
                self.ind -= 1
                self.where_now = self.where(s.loc)
            return
        mid = (lo + hi) // 2
        self.emit(f"if {k} < {mid}:")
        self.ind += 1
        self.case_tree(s, k, bodies, lo, mid, top)
        self.ind -= 1
        self.emit("else:")
        self.ind += 1
        self.case_tree(s, k, bodies, mid, hi, top)
        self.ind -= 1

    def label_const(self, e: A.Expr) -> int | None:
        """The value of a CASE label: a literal, an enumeration value or a constant."""
        if isinstance(e, A.Unary) and e.op == "-":
            v = self.label_const(e.operand)
            return None if v is None else -v
        if isinstance(e, A.Literal):
            if e.kind == "ENUM":
                return e.enum_value
            v = e.value
        elif isinstance(e, A.Name) and isinstance(e.sym, EnumSym):
            v = e.sym.value
        elif isinstance(e, A.Name) and isinstance(e.sym, VarSym) and e.sym.decl.constant:
            v = self.p.const_values.get(id(e.sym.decl))
        else:
            return None
        return int(v) if isinstance(v, int) else None

    def _bound_range(self, e: A.Expr) -> tuple[int, int] | None:
        """The values a FOR bound can take: a known interval, or its type's range when it is
        a stored value (stored integers always lie in their type)."""
        r = self.interval(e)
        if r is not None:
            return r
        t = T.resolve(e.ty) if e.ty is not None else None
        if isinstance(e, _SIMPLE) and isinstance(t, T.Elementary | T.Subrange) and \
                t.kind == "int":
            return (t.lo, t.hi)
        return None

    # -- coercion on store --------------------------------------------------------------------
    def coerce(self, code: str, src: T.Type | None, dst: T.Type | None, e: A.Expr | None) -> str:
        if dst is None or src is None:
            return code
        d = T.resolve(dst)
        s = T.resolve(src)
        if d is T.ANY or s is T.ANY:
            return code
        simple = isinstance(e, _SIMPLE) or (isinstance(e, A.Call) and e.target is not None and
                                            (e.target.kind in ("function", "conv") or
                                             _in_range_builtin(e)))
        if isinstance(d, T.Subrange):
            if isinstance(e, A.Literal) and isinstance(e.value, int):
                return code
            if isinstance(s, T.Subrange) and d.lo <= s.lo and s.hi <= d.hi:
                return code
            return f"_subr({code}, {d.lo}, {d.hi}, {self.where_now})"
        if isinstance(d, T.Elementary):
            k = d.kind
            if k in ("int", "bits", "time", "date", "tod", "dt"):
                if isinstance(e, A.Literal) and isinstance(e.value, int) and not isinstance(
                        e.value, bool):
                    return code
                sb = T.base_of(s)
                if s is T.BOOL or sb is T.BOOL:
                    return f"int({code})"
                if k == "time" and d is T.LTIME and sb is T.TIME:
                    return f"({code} * 1000000)" if simple else self.wrap(f"{code} * 1000000", d)
                if simple and (sb is d or (T.can_widen(sb, d) and sb.kind in ("int", "bits"))):
                    return code
                if isinstance(s, T.EnumType):
                    return code
                if sb.kind == "real":
                    return self.wrap(f"_round({code})", d)
                return self.wrap(code, d)
            if d is T.REAL:
                if isinstance(e, A.Literal) and isinstance(e.value, int | float) and not \
                        isinstance(e.value, bool):
                    return _float_code(e.value, single=True)
                if T.base_of(s) is T.REAL and simple and not _from_native(e):
                    return code
                if T.base_of(s).kind in ("int", "bits"):
                    return f"_i2r({code})"
                return f"_f32({code})"
            if d is T.LREAL:
                if isinstance(e, A.Literal) and isinstance(e.value, int | float):
                    return _float_code(e.value, single=False)
                if T.base_of(s) is T.REAL and e is not None:  # a REAL sum is a REAL value
                    return self.own_value(code, e)  # (ADR 0038): as REAL_TO_LREAL sees it
                if T.base_of(s).kind == "real":
                    return code
                return f"_fl({code})"
            return code
        if isinstance(d, T.StringType):
            if isinstance(s, T.StringType) and s.length <= d.length:
                return code
            return f"{code}[:{d.length}]"
        return code

    def own_value(self, code: str, e: A.Expr) -> str:
        """The value of ``e`` as its own type holds it, where it is used without a store: a
        conversion's argument, a CASE selector, an array index. Operators compute exactly (in
        a register), so ``s * s * s`` of SINTs may lie outside SINT; ``SINT_TO_INT`` then sees
        the SINT the hardware would hold, wrapped, and a REAL sum is rounded to single
        precision first (``REAL_TO_DINT(r + 1.0)``). A stored value, a literal, a call of a
        function or conversion and a value proven in range need nothing (ADR 0038)."""
        if e.ty is None:
            return code
        t = T.base_of(e.ty)
        if not isinstance(t, T.Elementary) or t is T.ANY_INT_LIT:
            return code
        if t.kind in _WRAPPED_KINDS and t.bits:
            if isinstance(e, A.Literal) or (_stored_value(e) and t.kind != "real"):
                return code
            r = self.interval(e)
            if r is not None and t.lo <= r[0] and r[1] <= t.hi:
                return code
            return self.wrap(code, t)
        if t is T.REAL and not (_stored_value(e) and not _from_native(e)) and \
                not isinstance(e, A.Literal):
            return f"_f32({code})"
        return code

    @staticmethod
    def wrap(code: str, t: T.Elementary) -> str:
        bits = t.bits
        mask = (1 << bits) - 1
        if t.signed:
            half = 1 << (bits - 1)
            return f"(((({code}) + {half}) & {mask}) - {half})"
        return f"(({code}) & {mask})"

    # -- expressions --------------------------------------------------------------------------
    def ex(self, e: A.Expr) -> str:
        """The Python code of ``e``. Long left chains (``a + b + c + ...``) are generated
        bottom-up with a loop (:meth:`chain`); every SPILL_LEVEL levels of nesting the code
        so far goes into a temporary (a line in ``self.pre``), so no generated line nests
        deeper than Python can parse. Targets of assignments are never moved."""
        made = self._memo.pop(id(e), None)
        if made is None:
            if isinstance(e, A.Binary) and isinstance(e.left, A.Binary):
                self.chain(e.left)
            made = self.ex_node(e)
        code, level = made
        if self._levels[-1] < level:
            self._levels[-1] = level
        return code

    def ex_node(self, e: A.Expr) -> tuple[str, int]:
        """(code, nesting since the last temporary) of one node."""
        self._levels.append(0)
        try:
            method = getattr(self, "e_" + type(e).__name__, None)
            if method is None:  # ArrayInit / StructInit go through init_code
                raise UnhandledNode("Codegen.ex_node", e)
            code = method(e)
        finally:
            level = self._levels.pop() + 1
        if level >= SPILL_LEVEL and not e.is_target:
            tmp = self.new_tmp()
            self.pre.append(f"{tmp} = {code}")
            return tmp, 0
        return code, level

    def chain(self, e: A.Expr) -> None:
        """Make the code of a long left spine of binary operators ahead, deepest first, so
        that each node finds its left operand made (no recursion along the chain)."""
        spine = []
        while isinstance(e, A.Binary) and id(e) not in self._memo:
            spine.append(e)
            e = e.left
        if len(spine) >= 8:
            for node in reversed(spine):
                self._memo[id(node)] = self.ex_node(node)

    def e_Literal(self, e: A.Literal) -> str:
        v = e.value
        k = e.kind
        if k == "BOOL" or (k == "INT" and e.ty is T.BOOL):  # TRUE, FALSE, and 0/1 as BOOL
            return "True" if v else "False"
        if k == "TIME":
            t = T.resolve(e.ty) if e.ty is not None else T.TIME
            if t is T.LTIME:
                return repr(int(v))
            q = abs(v) // 1_000_000
            return repr(-q if v < 0 else q)
        if k == "ENUM":
            return repr(e.enum_value or 0)
        if k == "REAL":
            return _float_code(v, single=T.resolve(e.ty) is T.REAL)
        if k == "INT" and e.ty is not None and T.resolve(e.ty).kind == "real":
            return _float_code(v, single=False)
        return repr(v)

    def e_Name(self, e: A.Name) -> str:
        sym = e.sym
        if isinstance(sym, VarSym):
            if sym.storage == "global":
                return f"_G.{ident(sym.decl.name)}"
            if sym.storage == "resource":  # the resource running this instance's (ADR 0037)
                return f"_R.{ident(sym.decl.name)}"
            if sym.storage == "self":
                code = f"self.{ident(sym.decl.name)}"
                return self.local_names.get(code, code)  # a local in a fast loop
            if sym.storage in ("this", "super"):  # THIS^, SUPER^ (ADR 0021)
                return "self"
            return f"v_{ident(sym.decl.name)}"
        if isinstance(sym, EnumSym):
            return repr(sym.value)
        if isinstance(sym, ProgSym):
            return f"_P.{ident(sym.instance)}"
        if isinstance(sym, A.Pou):  # a bare PROPERTY name in its own block: its GET
            return f"self.{oop_emit.method_name(sym)}()"
        return "None"

    def e_DirectAddr(self, e: A.DirectAddr) -> str:
        return self.addr_read(e.address)

    def e_Member(self, e: A.Member) -> str:
        if isinstance(e.sym, EnumSym):  # Color.Red (CODESYS)
            return repr(e.sym.value)
        if isinstance(e.sym, A.Pou):  # a PROPERTY's GET (ADR 0021)
            return oop_emit.property_call(self, e, None)
        if e.field_name == "^":  # r^ (ADR 0021)
            return f"{oop_emit.deref(self, e)}.get()"
        obj = self.ex(e.obj)
        part = A.partial_access(e.field_name)
        if part is not None and part[0] == "X":
            return f"({obj} >> {part[1]} & 1 != 0)"
        if part is not None:  # x.%B1: a byte of x (IEC 61131-3 ed.3 Table 17)
            width = A.PARTIAL_WIDTHS[part[0]]
            return f"({obj} >> {part[1] * width} & {(1 << width) - 1})"
        return f"{obj}.{ident(e.field_name)}"

    def e_Index(self, e: A.Index) -> str:
        obj = self.ex(e.obj)
        at = T.resolve(e.obj.ty)
        if isinstance(at, T.VarArrayType):  # ARRAY[*]: bounds of the argument (ADR 0060)
            ixs = "".join(f"{self.own_value(self.ex(ix), ix)}, " for ix in e.indices)
            return f"{obj}.data[_vla_ix({obj}, ({ixs}), {self.where(e.loc)})]"
        if not isinstance(at, T.ArrayType):
            return f"{obj}[0]"
        parts = []
        stride = 1
        strides = []
        for lo, hi in reversed(at.dims):
            strides.append(stride)
            stride *= hi - lo + 1
        strides.reverse()
        for ix, (lo, hi), st in zip(e.indices, at.dims, strides, strict=True):
            parts.append((self.index_code(ix, lo, hi), st))
        flat = " + ".join(p if st == 1 else f"({p}) * {st}" for p, st in parts)
        return f"{obj}[{flat}]"

    def index_code(self, ix: A.Expr, lo: int, hi: int) -> str:
        code = self.own_value(self.ex(ix), ix)
        c = const_int(ix)
        off = f" - {lo}" if lo > 0 else (f" + {-lo}" if lo < 0 else "")
        if c is not None:
            return str(c - lo)
        rng = self.interval(ix)
        if rng is not None and lo <= rng[0] and rng[1] <= hi:
            folded = self.folded_index(ix, lo)  # fastpaths.py
            if folded is not None:
                return folded
            return f"({code}){off}" if off else code
        w = self.where(ix.loc)
        if isinstance(ix, A.Name | A.Member):
            return f"({code}{off} if {lo} <= {code} <= {hi} else _oob({code}, {lo}, {hi}, {w}))"
        t = self.new_tmp()
        return f"({t}{off} if {lo} <= ({t} := {code}) <= {hi} else _oob({t}, {lo}, {hi}, {w}))"

    def interval(self, e: A.Expr) -> tuple[int, int] | None:
        """The range an integer expression surely lies in (literals, FOR variables with known
        bounds, + and - of those), or None: lets indexing skip its bounds check."""
        c = const_int(e)
        if c is not None:
            return (c, c)
        if isinstance(e, A.Name):
            return self.safe.get(self.e_Name(e))
        if isinstance(e, A.Binary) and e.op in ("+", "-"):
            a, b = self.interval(e.left), self.interval(e.right)
            if a is None or b is None:
                return None
            r = (a[0] + b[0], a[1] + b[1]) if e.op == "+" else (a[0] - b[1], a[1] - b[0])
            t = T.base_of(e.ty) if e.ty is not None else None
            if self.operand_width(e.loc) and isinstance(t, T.Elementary) and t.bits and \
                    t.kind in ("int", "bits") and not t.lo <= r[0] <= r[1] <= t.hi:
                return None  # S7 wraps the sum in the operands' width: no interval known
            return r
        return None

    def e_Unary(self, e: A.Unary) -> str:
        x = self.ex(e.operand)
        t = T.base_of(e.ty) if e.ty is not None else T.ANY
        if e.op == "NOT":
            if t is T.BOOL:
                return f"(not {x})"
            if isinstance(t, T.Elementary) and not t.signed:
                return f"({x} ^ {(1 << t.bits) - 1})"
            return f"(~{x})"
        return f"(-{x})"

    def e_Binary(self, e: A.Binary) -> str:
        op = e.op
        left, right = self.ex(e.left), self.ex(e.right)
        t = T.base_of(e.ty) if e.ty is not None else T.ANY
        lt = T.base_of(e.left.ty) if e.left.ty is not None else T.ANY
        rt = T.base_of(e.right.ty) if e.right.ty is not None else T.ANY
        if op in ("AND", "OR", "XOR"):
            return f"({left} {dict(AND='&', OR='|', XOR='^')[op]} {right})"
        if op in ("=", "<>", "<", "<=", ">", ">="):
            if lt is T.LREAL and rt is T.REAL:  # compared as LREAL: the REAL value (ADR 0038)
                right = self.own_value(right, e.right)
            elif rt is T.LREAL and lt is T.REAL:
                left = self.own_value(left, e.left)
            if lt is T.LTIME and rt is T.TIME:
                right = f"({right} * 1000000)"
            elif rt is T.LTIME and lt is T.TIME:
                left = f"({left} * 1000000)"
            if isinstance(lt, T.RefType | T.InterfaceType) and _is_zero(e.right):
                right = "None"  # CODESYS: IF itf <> 0 (ed.3 writes NULL; ADR 0059)
            elif isinstance(rt, T.RefType | T.InterfaceType) and _is_zero(e.left):
                left = "None"
            pyop = {"=": "==", "<>": "!="}.get(op, op)
            return f"({left} {pyop} {right})"
        if t is T.LREAL:  # a REAL operand of an LREAL operation is a REAL value (ADR 0038)
            if lt is T.REAL:
                left = self.own_value(left, e.left)
            if rt is T.REAL and op != "**":  # an exponent is not widened: it keeps its type
                right = self.own_value(right, e.right)
        if t.kind == "time" and t is T.LTIME:
            if lt is T.TIME:
                left = f"({left} * 1000000)"
            if rt is T.TIME:
                right = f"({right} * 1000000)"
        if op in ("/", "MOD"):
            fast = self.div_by_literal(e, left)  # fastpaths.py
            if fast is not None:
                return fast
        if op == "/":
            if t.kind in ("int", "bits") or (t.kind == "time" and rt.kind in ("int", "bits")):
                return f"_idiv({left}, {right})"
            if t.kind == "time":
                return f"_round(_rdiv({left}, {right}))"
            fast = self.real_division(e, left, right)  # fastpaths.py
            return fast if fast is not None else f"_rdiv({left}, {right})"
        if op == "MOD":
            return f"_imod({left}, {right})"
        if op == "-" and lt.kind == "date" and rt.kind == "date":  # seconds -> TIME in ms
            return f"(({left} - {right}) * 1000)"
        if op == "**":
            return f"_expt({left}, {right})"
        if op == "*" and t.kind == "time" and (lt.kind == "real" or rt.kind == "real"):
            return f"_round({left} * {right})"
        if op in ("+", "-", "*") and t.kind in ("int", "bits") and isinstance(t, T.Elementary) \
                and t is not T.ANY_INT_LIT and self.operand_width(e.loc):
            return self.wrap(f"{left} {op} {right}", t)  # S7: the operand type's width
        return f"({left} {op} {right})"

    def dialect_at(self, loc: Location | None):
        """The dialect of the file ``loc`` is in (ADR 0017)."""
        if not self.p.dialects:  # every file in the default dialect (the common case)
            return dialect_profile(None)
        return dialect_profile(self.p.dialects.get(loc.file) if loc is not None else None)

    def operand_width(self, loc: Location | None) -> bool:
        """Whether integer intermediates wrap to their type here (the S7 dialect, ADR 0017)
        instead of staying exact (CODESYS computes them in a register)."""
        return self.dialect_at(loc).operand_width

    def e_Call(self, e: A.Call) -> str:
        info: CallInfo | None = e.target
        if info is None:
            return "None"
        if info.en is not None or info.eno is not None:
            return self.enabled_call(e, info)
        return self.plain_call(e, info)

    def enabled_call(self, e: A.Call, info: CallInfo) -> str:
        """A function call with EN/ENO (IEC 61131-3 ed.3 6.6.1.6): EN is evaluated first; when
        it is FALSE the function is not called, the result is its type's default (as MATIEC)
        and ENO is FALSE; else ENO is TRUE."""
        en = self.new_tmp()
        self.pre.append(f"{en} = {self.ex(info.en) if info.en is not None else 'True'}")
        mark = len(self.pre)
        code = self.plain_call(e, info)
        inner = self.pre[mark:]
        del self.pre[mark:]
        if inner:  # the call's own statements (outputs, spilled temporaries) run only if EN
            self.pre.append(f"if {en}: " + "; ".join(inner))
        self.pre.extend(self.eno_false(info, en))
        if info.eno is not None:
            self.pre.append(self.store_code(info.eno, en))
        default = self.default_code(e.ty) if e.ty is not None and e.ty is not T.VOID \
            else "None"
        return f"({code} if {en} else {default})"

    def eno_false(self, info: CallInfo, en: str) -> list[str]:
        """``ENO => ok`` bound to a callee's own ENO output (declared, or the implicit one a
        body assigns, :mod:`plclab.lang.lower.implicit_eno`): FALSE when EN was FALSE and the
        body did not run (IEC 61131-3 ed.3 6.6.1.6)."""
        return [f"if not {en}: {self.store_code(tgt, 'False')}" for d, tgt, neg in info.outputs
                if getattr(d, "name", None) == "ENO" and not neg]

    def store_code(self, target: A.Expr, val: str) -> str:
        """One line storing ``val`` (a BOOL) into ``target`` (see :meth:`assign_to`)."""
        part = A.partial_access(target.field_name) if isinstance(target, A.Member) else None
        if part is not None:  # x.3 := v, x.%B1 := v (IEC 61131-3 ed.3 Table 17): x changes
            obj = self.ex(target.obj)
            kind, n = part
            if kind == "X":
                whole = f"(({obj}) | {1 << n}) if {val} else (({obj}) & ~{1 << n})"
            else:
                width = A.PARTIAL_WIDTHS[kind]
                mask, shift = (1 << width) - 1, n * width
                whole = f"(({obj}) & ~{mask << shift}) | ((({val}) & {mask}) << {shift})"
            return self.store_code(target.obj, whole)  # x.%W1.%B0 := v stores x.%W1
        if isinstance(target, A.DirectAddr):
            return self.addr_write(target.address, val)
        return f"{self.ex(target)} = {val}"

    def plain_call(self, e: A.Call, info: CallInfo) -> str:
        if info.kind == "conv":
            return self.conversion(info, e)
        if info.kind == "builtin":
            return self.builtin(info.callee.name, [x for _, x in info.inputs], e)
        if info.kind == "function":
            return self.user_function(info)
        if info.kind == "method":
            return oop_emit.method_call(self, e, info)
        if info.kind == "reference":
            return oop_emit.reference_operator(self, e, info)
        if info.kind == "sizeof":  # a constant the checker computed (plclab.lang.sizeof)
            return repr(int(info.callee))
        if info.kind == "bound":  # LOWER_BOUND / UPPER_BOUND (ADR 0060)
            upper, dim, static = info.callee
            if static is not None:
                return repr(static)
            return f"{self.ex(info.inputs[0][1])}.dims[{dim}][{int(upper)}]"
        return "None"

    def inout_code(self, d: A.VarDecl, e: A.Expr) -> str:
        """The value a VAR_IN_OUT receives: the variable itself, or for VAR_IN_OUT CONSTANT any
        value of the type, converted as an input would be."""
        want = T.resolve(d.ty)
        if isinstance(want, T.VarArrayType):  # an ARRAY[*] gets the array and its bounds
            at = T.resolve(e.ty)
            return f"_VLA({self.ex(e)}, {at.dims!r})" if isinstance(at, T.ArrayType) \
                else self.ex(e)
        return self.coerce(self.ex(e), e.ty, d.ty, e) if d.constant else self.ex(e)

    def user_function(self, info: CallInfo) -> str:
        pou: A.Pou = info.callee
        args = self.call_arguments(pou.decls, info)
        return self.call_with_results(f"F_{ident(pou.name)}({', '.join(args)})", pou.decls, info)

    def call_arguments(self, decls: list[A.VarDecl], info: CallInfo) -> list[str]:
        """The Python arguments of a FUNCTION or METHOD call: each VAR_INPUT (its initial value
        when not given) and VAR_IN_OUT, in declaration order."""
        given = {d.name: x for d, x in info.inputs}
        given_io = {d.name: x for d, x in info.inouts}
        args = []
        for d in decls:
            if d.section == "VAR_INPUT":
                x = given.get(d.name)
                if x is None:
                    args.append(self.init_code(d.init, d.ty))
                else:
                    code = self.coerce(self.ex(x), x.ty, d.ty, x)
                    if T.resolve(d.ty).is_aggregate:
                        code = self.copy_code(code, d.ty)
                    args.append(code)
            elif d.section == "VAR_IN_OUT":
                x = given_io.get(d.name)
                args.append(self.inout_code(d, x) if x is not None else "None")
        return args

    def call_with_results(self, call: str, decls: list[A.VarDecl], info: CallInfo) -> str:
        """``call`` (Python returning the result, then the VAR_OUTPUT and VAR_IN_OUT values) as
        an expression of its result; the outputs and in-outs go to their targets in ``pre``."""
        outs = [d for d in decls if d.section in ("VAR_OUTPUT", "VAR_IN_OUT")]
        if not outs:
            return call
        tmp = self.new_tmp("_f")
        self.pre.append(f"{tmp} = {call}")
        bound = {d.name: (tgt, neg) for d, tgt, neg in info.outputs}
        for d, x in info.inouts:
            if not T.resolve(d.ty).is_aggregate and not d.constant:
                bound[d.name] = (x, False)
        for i, d in enumerate(outs, start=1):
            if d.name in bound:
                tgt, neg = bound[d.name]
                v = f"{tmp}[{i}]"
                if neg:
                    v = f"(not {v})"
                lv = self.ex(tgt)
                self.pre.append(f"{lv} = {self.coerce(v, d.ty, tgt.ty, None)}")
        return f"{tmp}[0]"

    def conversion(self, info: CallInfo, e: A.Call) -> str:
        src_name, dst = info.callee
        x = info.inputs[0][1]
        code = self.own_value(self.ex(x), x)
        s = T.base_of(x.ty)
        d = T.resolve(dst)
        want = T.lookup_elementary(src_name) if src_name not in (None, "__TRUNC__") else None
        if want is not None and want.kind in ("int", "bits") and s.kind in ("int", "bits") and \
                s is not T.BOOL and not T.can_widen(s, want) and s is not want:
            code, s = self.wrap(code, want), want  # INT_TO_BYTE(d) of a DINT (PLC0285)
        if src_name == "__TRUNC__":
            return self.wrap(f"_trunc({code})", d) if d.kind in ("int", "bits") else code
        if isinstance(d, T.StringType):
            kind = ("bool" if s is T.BOOL else "real32" if s is T.REAL else
                    "real" if s.kind == "real" else "time" if s is T.TIME else
                    "ltime" if s is T.LTIME else "str" if isinstance(s, T.StringType) else "int")
            return f"_to_string({code}, {kind!r})"
        if isinstance(s, T.StringType):
            if d is T.BOOL:
                return f"_str_to_bool({code})"
            if d.kind == "real":
                return f"_str_to_real({code})" if d is T.LREAL else f"_f32(_str_to_real({code}))"
            if d.kind == "time":
                return f"_str_to_time({code})"
            return self.wrap(f"_str_to_int({code})", d)
        if s is T.DT and (d.kind in ("int", "bits", "real") or d is T.BOOL):
            # DT as a number counts seconds since 1970 (CODESYS "Conversion: DATE, DT, TOD",
            # Beckhoff "DT_TO conversions", MATIEC __time_to_int); plclab holds milliseconds
            code, s = f"({code} // 1000)", T.LINT
        elif d is T.DT and s.kind in ("int", "bits", "real"):
            whole = self.wrap(f"_round({code})", T.LINT) if s.kind == "real" else code
            return self.wrap(f"({whole} * 1000)", d)
        if d is T.BOOL:
            return f"({code} != 0)"
        if (s.kind == "time") != (d.kind == "time") and self.dialect_at(e.loc).time_in_seconds:
            return self.seconds_conversion(code, s, d)
        if d.kind == "real":
            if s.kind == "real":
                return f"_f32({code})" if d is T.REAL else code
            return f"_i2r({code})" if d is T.REAL else f"_fl({code})"
        if d.kind in ("int", "bits", "time", "date", "tod", "dt"):
            if s.kind == "real":
                return self.wrap(f"_round({code})", d)
            if s is T.LTIME and d is T.TIME:
                return self.wrap(f"_idiv({code}, 1000000)", d)
            if s is T.TIME and d is T.LTIME:
                return f"({code} * 1000000)"
            if s is T.BOOL:
                return f"int({code})"
            if s is T.DT and d is T.DATE:  # DT counts ms since 1970, DATE seconds
                return f"({code} // 86400000 * 86400)"
            if s is T.DT and d is T.TOD:  # ... TOD ms since midnight
                return f"({code} % 86400000)"
            if isinstance(s, T.Elementary) and s.kind in ("int", "bits", "time", "date", "tod",
                                                          "dt") and T.can_widen(s, d):
                return code
            return self.wrap(code, d)
        return code

    def seconds_conversion(self, code: str, s: T.Type, d: T.Type) -> str:
        """TIME <-> number in the MATIEC dialect: the number counts seconds (its
        ``__time_to_real`` is tv_sec + tv_nsec / 1e9, ``__time_to_int`` tv_sec; ``__int_to_time``
        and ``__real_to_time`` read seconds). TIME holds ms, LTIME ns."""
        if s.kind == "time":
            unit = 1_000 if s is T.TIME else 1_000_000_000
            if d.kind == "real":
                return f"_f32({code} / {unit})" if d is T.REAL else f"({code} / {unit})"
            return self.wrap(f"_idiv({code}, {unit})", d)  # whole seconds, toward zero
        unit = 1_000 if d is T.TIME else 1_000_000_000
        if s.kind == "real":
            return self.wrap(f"_round({code} * {unit})", d)
        return self.wrap(f"({code} * {unit})", d)

    def widen(self, code: str, src: T.Type | None, dst: T.Type | None,
              e: A.Expr | None = None) -> str:
        """An implicit widening inside an expression (MIN, SEL, GT...): an integer keeps its
        exact value but becomes a float for a REAL result, TIME becomes LTIME nanoseconds, and a
        REAL expression ``e`` widened to LREAL is its REAL value (ADR 0038, decision 4)."""
        if src is None or dst is None:
            return code
        s, d = T.base_of(src), T.base_of(dst)
        if s is d:
            return code
        if s is T.REAL and d is T.LREAL and e is not None:
            return self.own_value(code, e)
        if d.kind == "real" and s.kind in ("int", "bits") and s is not T.ANY_INT_LIT:
            return f"_fl({code})"
        if d is T.LTIME and s is T.TIME:
            return f"({code} * 1000000)"
        return code

    def builtin(self, name: str, args: list[A.Expr], e: A.Call) -> str:
        """A standard function call, by its emitter (``Builtin.emit``, :mod:`.builtins_emit`)."""
        spec = BUILTINS[name]
        t = T.base_of(e.ty) if e.ty is not None else T.ANY
        return EMITTERS[spec.emit](Emission(self, spec, [self.ex(a) for a in args], args, t, e))


# limits of the generated code (see "-- sizes" in Codegen)
OUTLINE_INDENT = 40  # Python allows 100 levels of indentation
OUTLINE_LOOPS = 12  # ... and 20 nested loops
MAX_ELIF = 8  # ... and a few hundred elif (they nest in its syntax tree)
CASE_CHUNK = 128  # branches of a large CASE per helper function
SMALL_CASE = 16  # up to this many labels a CASE is an if/elif chain (fastest when small)
SPILL_LEVEL = 12  # expression nesting between temporaries (Python allows 200 parentheses)
NORMAL, EXIT, CONTINUE, RETURN = 0, 1, 2, 3  # how an outlined block ended
_LOCALS = "\x00"  # placeholder for the locals a helper returns (repr() never writes a NUL)
_LOCAL_NAME = re.compile(r"\bv_[A-Z0-9_]+\b")


@dataclass
class _Helper:
    """An outlined block being generated: the signals its code may return."""

    signals: set[int] = field(default_factory=set)


def _segments(ranges: list[tuple[int, int, int]]) -> list[tuple[int, int, int]]:
    """Disjoint sorted (lo, hi, branch) from CASE ranges (lo, hi, branch) that may overlap;
    where they do, the first branch wins, as in the if-chain.

    >>> _segments([(1, 10, 0), (5, 20, 1)])
    [(1, 10, 0), (11, 20, 1)]
    """
    points = sorted({lo for lo, _, _ in ranges} | {hi + 1 for _, hi, _ in ranges})
    starts = sorted(ranges)
    active: list[tuple[int, int]] = []  # heap of (branch, hi)
    out: list[tuple[int, int, int]] = []
    i = 0
    for a, b in zip(points, points[1:], strict=False):
        while i < len(starts) and starts[i][0] <= a:
            heapq.heappush(active, (starts[i][2], starts[i][1]))
            i += 1
        while active and active[0][1] < a:
            heapq.heappop(active)
        if active:
            k = active[0][0]
            if out and out[-1][1] == a - 1 and out[-1][2] == k:
                out[-1] = (out[-1][0], b - 1, k)
            else:
                out.append((a, b - 1, k))
    return out

def _float_code(v: int | float, single: bool) -> str:
    """A REAL/LREAL literal as Python: an overflowing literal is infinity, as in IEEE."""
    try:
        x = float(v)
    except OverflowError:
        x = math.inf if v > 0 else -math.inf
    if single:
        x = _f32(x)
    if x in (math.inf, -math.inf):
        return "_math.inf" if x > 0 else "(-_math.inf)"
    return repr(x)


def _from_native(e: A.Expr | None) -> bool:
    """A value read from a native block or function: Python code that may hand back doubles,
    so a store into a REAL rounds it like an arithmetic result."""
    if isinstance(e, A.Member):
        t = T.resolve(e.obj.ty) if e.obj.ty is not None else None
        return isinstance(t, T.FBType) and t.pou is not None and t.pou.native is not None
    if isinstance(e, A.Call) and e.target is not None and e.target.kind == "function":
        return e.target.callee.native is not None
    return False


_WRAPPED_KINDS = ("int", "bits", "time", "date", "tod", "dt")


def _stored_value(e: A.Expr) -> bool:
    """An expression whose value already lies in its type: a variable, a member, an element,
    a call of a function or a conversion, or a builtin that cannot leave its range."""
    return isinstance(e, _SIMPLE) or (isinstance(e, A.Call) and e.target is not None and (
        e.target.kind in ("function", "conv") or _in_range_builtin(e)))


def _in_range_builtin(e: A.Call) -> bool:
    """Builtins whose result never leaves its type's range when their inputs are stored values
    (so a store needs no wrap-around code)."""
    info = e.target
    if info.kind != "builtin":
        return False
    name = info.callee.name
    args = [x for _, x in info.inputs]
    if name in ("LEN", "FIND"):
        return all(getattr(T.resolve(x.ty), "length", 99999) <= 32767 for x in args)
    if name in ("MIN", "MAX", "LIMIT", "MOVE", "SEL"):
        vals = args[1:] if name == "SEL" else args
        t = T.base_of(e.ty) if e.ty is not None else None
        return all(isinstance(x, _SIMPLE) and x.ty is not None and T.base_of(x.ty) is t
                   for x in vals) and isinstance(args[0], _SIMPLE)
    return False


def kind_name(t: T.Type | None) -> str:
    if t is None:
        return "int?"
    r = T.resolve(t)
    if r is T.ANY_INT_LIT:
        return "int?"
    if isinstance(r, T.EnumType):
        return "enum:" + ",".join(f"{v}={r.spellings.get(k, k)}" for k, v in r.members.items())
    if r is T.REAL:
        return "real32"
    if isinstance(r, T.Subrange):
        return "int"
    return r.kind if r.name not in ("LTIME",) else "ltime"


def generate(project: Project, filename: str = "<plclab>") -> Compiled:
    return Codegen(project, filename).generate()


def _is_zero(e: A.Expr) -> bool:
    """The integer literal 0, which CODESYS compares a reference or an interface with."""
    return isinstance(e, A.Literal) and e.kind == "INT" and e.value == 0
