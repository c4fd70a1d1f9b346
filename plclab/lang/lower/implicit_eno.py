"""The implicit ENO output written in a POU's body: ``ENO := FALSE; RETURN;``.

IEC 61131-3 (ed.2 2.5.1.2, ed.3 6.6.1.6, Annex F's WEIGH) gives every function and function
block an implicit BOOL output ENO, TRUE when the body starts; the body may assign it to report
that its result is not valid. MATIEC compiles such bodies, and CODESYS too. Before the checker
sees the files, a FUNCTION or FUNCTION_BLOCK whose body names ENO without declaring it gets the
declaration ``VAR_OUTPUT ENO : BOOL := TRUE; END_VAR`` and the first statement ``ENO := TRUE;``
(a block's outputs keep their values between calls). A caller's ``ENO => ok`` then binds that
output, and with ``EN := FALSE`` the body does not run and ``ok`` is FALSE
(:mod:`plclab.compile.codegen`, ``Codegen.eno_false``). ADR 0052.
"""

from __future__ import annotations

from .. import ast as A
from ..walk import walk

__all__ = ["add"]


def _names_eno(body: list[A.Stmt]) -> bool:
    return any(isinstance(n, A.Name) and n.name == "ENO" for s in body for n in walk(s))


def add(files: list[A.SourceFile]) -> None:
    """Declare the implicit ENO of each FUNCTION and FUNCTION_BLOCK whose body names it."""
    for f in files:
        for p in f.pous:
            if p.kind not in ("FUNCTION", "FUNCTION_BLOCK") or p.native or \
                    any(d.name == "ENO" for d in p.decls) or not _names_eno(p.body):
                continue
            loc = p.body[0].loc if p.body else p.loc
            p.decls.append(A.VarDecl(loc, "ENO", A.NamedTypeRef(loc, "BOOL"),
                                     A.Literal(loc, True, "BOOL", None, "TRUE"), None,
                                     "VAR_OUTPUT", False, False, "ENO"))
            p.body.insert(0, A.Assign(loc, A.Name(loc, "ENO", "ENO"),
                                      A.Literal(loc, True, "BOOL", None, "TRUE")))
