"""What the checker's passes share: the symbol table, the diagnostics, where checking is now.

Each pass (:mod:`.declarations`, :mod:`.consts`, :mod:`.exprs`, :mod:`.calls`, :mod:`.stmts`,
:mod:`.program`) is a small object holding this context; a pass asks another one through it
(``self.cx.exprs.expr(e, None)``), so no pass needs to be one big class with all the others.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ...errors import Diagnostic, Location
from .. import ast as A
from ..dialect import Dialect, profile
from .symbols import Scope, SymbolTable

__all__ = ["CheckContext"]

if TYPE_CHECKING:  # the passes, created by checker.Checker
    from .calls import Calls
    from .consts import Constants
    from .declarations import Declarations
    from .exprs import Expressions
    from .oop import ObjectChecks
    from .program import ProgramChecks
    from .stmts import Statements


@dataclass(eq=False)
class CheckContext:
    table: SymbolTable
    diags: list[Diagnostic] = field(default_factory=list)
    # where checking is now
    scope: Scope = field(default_factory=Scope)  # the names visible now
    pou: A.Pou | None = None  # the POU whose body is being checked
    in_test: bool = False
    loop_depth: int = 0
    stmt_loc: Location | None = None  # the statement being checked (for PLC0191)
    # what the passes find for the compiler and the runtime
    const_values: dict[int, Any] = field(default_factory=dict)  # id(VarDecl) -> folded value
    image_needed: tuple[int, str, Location] | None = None  # (bytes, address, where)
    call_graph: dict[str, set[str]] = field(default_factory=dict)  # pou -> pous it calls
    call_sites: dict[tuple[str, str], Location] = field(default_factory=dict)  # first call
    dialects: dict[str, str] = field(default_factory=dict)  # file -> its dialect's name
    # the passes (set by the Checker)
    decls: Declarations = field(init=False)
    consts: Constants = field(init=False)
    exprs: Expressions = field(init=False)
    calls: Calls = field(init=False)
    stmts: Statements = field(init=False)
    program: ProgramChecks = field(init=False)
    oop: ObjectChecks = field(init=False)

    def dialect(self, loc: Location | None) -> Dialect:
        """The dialect of the file ``loc`` is in (ADR 0017)."""
        return profile(self.dialects.get(loc.file) if loc is not None else None)

    def err(self, code: str, msg: str, loc: Location | None) -> None:
        self.diags.append(Diagnostic(code, msg, loc))

    def warn(self, code: str, msg: str, loc: Location | None) -> None:
        self.diags.append(Diagnostic(code, msg, loc, "warning"))

    def report(self, code: str, msg: str, loc: Location | None, severity: str) -> None:
        """A diagnostic of the symbol table (:meth:`SymbolTable.collect`)."""
        self.diags.append(Diagnostic(code, msg, loc, severity))
