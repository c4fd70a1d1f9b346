"""The compiler: a checked :class:`~plclab.lang.check.Project` -> Python source -> code object.

Design rules (DESIGN.md, principle 2):

* every POU becomes a plain Python class or function; a scan calls ``_body()`` methods;
* user text reaches the generated code only as upper-cased identifiers (``[A-Z0-9_]``, which
  can never be a Python keyword or builtin) or as ``repr()`` literals;
* each generated line remembers the source location it came from, so a runtime fault can be
  reported at ``file:line:col`` of the ST source.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..errors import Location, PlcError
from ..lang import ast as A
from ..lang import types as T
from ..lang.check import Project, VarSym
from ..lang.limits import compiler_guard
from ..lang.walk import walk
from . import oop_emit
from .codegen_expr import ExprEmit
from .codegen_names import ident, kind_name, member_path, program_attr
from .codegen_pou import PouEmit
from .codegen_stmt import OutlinedBlock as _Helper
from .codegen_stmt import StmtEmit
from .fastpaths import FastPaths
from .pycompile import compile_lines


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


class Codegen(PouEmit, StmtEmit, ExprEmit, FastPaths):
    """The generator: the emission and the driver here; POUs (:mod:`.codegen_pou`), statements
    (:mod:`.codegen_stmt`) and expressions (:mod:`.codegen_expr`) in its mixins."""

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


def generate(project: Project, filename: str = "<plclab>") -> Compiled:
    return Codegen(project, filename).generate()


__all__ = ["Codegen", "Compiled", "generate", "ident", "kind_name", "member_path",
           "program_attr"]  # the names other modules import from here
