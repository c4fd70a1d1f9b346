"""The lowering stage: pending bodies -> core AST statements.

Front ends parse to data (:class:`~plclab.lang.ast.PendingBody` on ``Pou.pending``); this stage
runs once every declaration of every file is known (parse all -> declarations known -> lower ->
check) and turns each pending body into ordinary statements and hidden declarations:

* ``"IL"``: instruction lists (:mod:`.il`);
* ``"NETWORK"``: LD and FBD networks, from the text ladder and from PLCopen graphics alike
  (:mod:`.network`);
* ``"SFC"``: sequential function charts, textual (:mod:`.sfc`);
* ``"EDGE"``: R_EDGE / F_EDGE inputs (:mod:`.edges`), after the body they qualify.

It is also the place where the object-oriented constructs will be lowered to
the core AST, so that the checker and the compiler keep seeing one language. The type questions
the lowering asks go through :class:`~.types.LoweringTypes` only.
"""

from __future__ import annotations

from collections.abc import Callable

from ...errors import Diagnostic
from .. import ast as A
from ..limits import compiler_guard
from .edges import lower_edges
from .il import lower_il
from .network import lower_network
from .sfc import lower_sfc
from .types import DeclarationTypes, LoweringTypes

LOWERINGS: dict[str, Callable[[A.Pou, list, LoweringTypes], list[Diagnostic]]] = {
    "IL": lower_il,
    "NETWORK": lower_network,
    "SFC": lower_sfc,
    "EDGE": lower_edges,
}


def has_pending(files: list[A.SourceFile]) -> bool:
    """Does any POU of ``files`` still hold a body to lower?"""
    return any(p.pending for f in files for p in f.pous)


def lower_pending(files: list[A.SourceFile],
                  library: tuple[A.SourceFile, ...] = ()) -> list[Diagnostic]:
    """Lower every pending body of ``files`` (in file and POU order) with every declaration
    known; return the diagnostics. ``library``: the standard library's declarations, when
    ``files`` do not hold them (see :class:`~.types.DeclarationTypes`)."""
    if not has_pending(files):
        return []
    types = DeclarationTypes(files, library)
    diags: list[Diagnostic] = []
    with compiler_guard():  # translations recurse once per nesting level (see limits)
        for f in files:
            for pou in f.pous:
                pending, pou.pending = pou.pending, []
                for body in pending:
                    diags.extend(LOWERINGS[body.kind](pou, body.payload, types))
    return diags


__all__ = ["LOWERINGS", "has_pending", "lower_pending", "LoweringTypes", "DeclarationTypes"]
