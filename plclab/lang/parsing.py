"""What every text front end shares: the exception that abandons the current item.

A parser that has recorded a diagnostic raises :class:`ParseAbort`; the nearest recovery point
(a statement, a declaration, an IL line, a ladder box, an XML attribute) catches it and goes on,
so that one run reports every syntax error of a file.
"""

from __future__ import annotations


class ParseAbort(Exception):
    """Abandon the current statement, declaration or item: a diagnostic was recorded."""


__all__ = ["ParseAbort"]
