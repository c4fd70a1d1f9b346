"""The API a checker pass is written against: :class:`Pass`, its context and the two ways to report.

A pass module imports this and :mod:`.symbols`, never :mod:`.context` at run time: the context
names the passes it holds (for type checkers only), the passes name the context only through
``Pass.cx``, so the passes and the context do not import each other.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...errors import Location
from .symbols import SymbolTable

if TYPE_CHECKING:
    from .context import CheckContext

__all__ = ["Pass"]


class Pass:
    """A checker pass: its context, the symbol table, and the two ways to report."""

    def __init__(self, cx: CheckContext) -> None:
        self.cx = cx

    @property
    def table(self) -> SymbolTable:
        return self.cx.table

    def err(self, code: str, msg: str, loc: Location | None) -> None:
        self.cx.err(code, msg, loc)

    def warn(self, code: str, msg: str, loc: Location | None) -> None:
        self.cx.warn(code, msg, loc)
