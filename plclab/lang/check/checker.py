"""The checker: runs the passes in order over the parsed files and returns a :class:`Project`.

1. :class:`~.symbols.SymbolTable` ``.collect`` -- every TYPE, POU and global by name;
2. :mod:`.declarations` (with :mod:`.consts`) -- types of TYPEs, globals and POU variables;
3. :mod:`.stmts` (with :mod:`.exprs` and :mod:`.calls`) -- every POU body;
4. :mod:`.program` -- recursion, the configuration and its tasks; :mod:`.configvars` -- its
   VAR_CONFIG and VAR_ACCESS;
5. :mod:`.stmts` -- the TEST blocks; :mod:`.program` -- data that contains itself or is too big.

The passes annotate the AST in place, only through the fields :mod:`plclab.lang.ast` declares
(``Expr.ty``, ``Name.sym``, ``Call.target``, ``Pou.return_decl``, ...). All errors of all files
are collected; :func:`check` raises one :class:`~plclab.errors.PlcError` carrying every
diagnostic.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ...errors import Diagnostic, Location, PlcError
from .. import ast as A
from .. import types as T
from ..limits import compiler_guard
from ..lower import implicit_eno, reference_to
from .calls import Calls
from .configvars import ConfigVars
from .consts import Constants
from .context import CheckContext
from .declarations import Declarations
from .exprs import Expressions
from .oop import ObjectChecks
from .program import ProgramChecks
from .stmts import Statements
from .symbols import SymbolTable


@dataclass(eq=False)
class Project:
    """A checked program: what the compiler and the runtime need."""

    files: list[A.SourceFile]
    types: dict[str, T.Type]
    pous: dict[str, A.Pou]
    globals: dict[str, A.VarDecl]
    programs: list[tuple[str, A.Pou, str | None]]  # (instance name, pou, task)
    tasks: list[A.TaskDecl]
    tests: list[A.TestBlock]
    diagnostics: list[Diagnostic]
    const_values: dict[int, Any] = field(default_factory=dict)  # id(VarDecl) -> value
    # the process image the addresses need: (bytes, the address that needs most, where)
    image_needed: tuple[int, str, Location] | None = None
    symbols: SymbolTable = field(default_factory=SymbolTable)  # declarations, by name
    dialects: dict[str, str] = field(default_factory=dict)  # file -> dialect (ADR 0017)


class Checker:
    """``Checker(files).run()`` -> :class:`Project`; the diagnostics are in ``.diags``."""

    def __init__(self, files: list[A.SourceFile]) -> None:
        self.files = files
        self.diags: list[Diagnostic] = []
        cx = self.cx = CheckContext(SymbolTable(), self.diags)
        cx.dialects = {f.file: f.dialect for f in files if f.dialect}
        cx.decls = Declarations(cx)
        cx.consts = Constants(cx)
        cx.exprs = Expressions(cx)
        cx.calls = Calls(cx)
        cx.stmts = Statements(cx)
        cx.program = ProgramChecks(cx)
        cx.oop = ObjectChecks(cx)
        self.config_vars = ConfigVars(cx)

    def run(self) -> Project:
        with compiler_guard():  # nesting recurses; the limits are checked (plclab.lang.limits)
            return self._run()

    def _run(self) -> Project:
        cx = self.cx
        implicit_eno.add(self.files)  # ENO := FALSE in a body declares the implicit output
        table = cx.table = SymbolTable.collect(self.files, cx.report, with_globals=False)
        reference_to.rewrite(self.files)  # REFERENCE TO: r is r^, r REF= x is r := REF(x)
        cx.decls.run()
        cx.oop.declarations()
        cx.decls.fb_init_arguments()  # a : FB(k := 3), once FB_init's inputs have types
        cx.oop.bodies()  # methods first: they use their block's variables (PLC0200)
        for p in table.pous.values():
            cx.stmts.check_pou_body(p)
        cx.program.check_recursion()
        programs, tasks = cx.program.configuration()
        self.config_vars.run(programs)
        tests = [t for f in self.files for t in f.tests]
        for t in tests:
            cx.stmts.check_test(t)
        cx.program.check_data(programs, tests)
        return Project(self.files, table.types, table.pous, table.globals, programs, tasks,
                       tests, self.diags, cx.const_values, cx.image_needed, table, cx.dialects)


def check(files: list[A.SourceFile]) -> Project:
    """Check parsed files; raise PlcError with every error, or return the project."""
    ck = Checker(files)
    project = ck.run()
    errors = [d for d in ck.diags if d.severity == "error"]
    if errors:
        raise PlcError(errors[0].code, errors[0].message, errors[0].location,
                       diagnostics=ck.diags)
    return project
