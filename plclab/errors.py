"""Errors and diagnostics.

Every error a user can cause is a :class:`PlcError` with a stable code (``PLCnnnn``),
a message that says what to do, and a location where there is one.

>>> e = PlcError("PLC0001", "unexpected character '@'", Location("a.st", 3, 7))
>>> str(e)
"a.st:3:7: error PLC0001: unexpected character '@'"
"""

from __future__ import annotations

import unicodedata
from dataclasses import dataclass

_UNPRINTABLE = ("Cc", "Cf", "Cs", "Zl", "Zp", "Co", "Cn")


def printable(text: str) -> str:
    r"""``text`` safe to show on a terminal or in a one-line report: control characters
    (newline, carriage return, escape sequences), bidi and other format characters, line
    separators and lone surrogates become visible escapes, so a student's string cannot erase
    a line, colour the terminal or fake a test summary. The one function every such text
    goes through (messages, ASSERT texts, printed values; the grader's names too).

    >>> printable("ok\x1b[2K\rPASS\n2 passed")
    'ok\\x1b[2K\\rPASS\\n2 passed'
    >>> printable("caf\u00e9 \ud800")
    'café \\ud800'
    """
    if text.isprintable():
        return text
    out = []
    for ch in text:
        if unicodedata.category(ch) in _UNPRINTABLE:
            out.append(ch.encode("unicode_escape", "backslashreplace").decode("ascii"))
        else:
            out.append(ch)
    return "".join(out)


@dataclass(slots=True, unsafe_hash=True)
class Location:
    """A place in a source file (1-based line and column). Treat it as immutable (it is
    hashed); it is not declared ``frozen`` because the parser makes one for nearly every node
    and a frozen dataclass is three times slower to construct (ADR 0034)."""

    file: str = "<input>"
    line: int = 0
    col: int = 0

    def __str__(self) -> str:
        file = printable(self.file)  # a file name is the user's text too
        if self.line <= 0:
            return file
        return f"{file}:{self.line}:{self.col}"


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One message of the checker: an error or a warning."""

    code: str
    message: str
    location: Location | None = None
    severity: str = "error"  # "error" | "warning"

    def __str__(self) -> str:
        where = f"{self.location}: " if self.location else ""
        return f"{where}{self.severity} {self.code}: {printable(self.message)}"

    def render(self) -> str:
        """The diagnostic in the language chosen (``--lang``, ``PLCLAB_LANG``, the locale:
        :mod:`plclab.i18n`); ``str()`` stays English, the form tools and logs parse."""
        from .i18n import SOURCE, language, message, severity

        if language() == SOURCE:
            return str(self)
        where = f"{self.location}: " if self.location else ""
        return (f"{where}{severity(self.severity)} {self.code}: "
                f"{printable(message(self.code, self.message))}")


class PlcError(Exception):
    """An error a user can cause: bad source, a runtime fault, a bad lab file...

    ``diagnostics`` holds every diagnostic when a whole file was checked (all errors
    are reported, not only the first).
    """

    def __init__(
        self,
        code: str,
        message: str,
        location: Location | None = None,
        diagnostics: list[Diagnostic] | None = None,
    ) -> None:
        self.code = code
        self.message = message
        self.location = location
        self.diagnostics = diagnostics or [Diagnostic(code, message, location)]
        super().__init__(str(self))

    def __str__(self) -> str:
        if len(self.diagnostics) > 1:
            return "\n".join(str(d) for d in self.diagnostics)
        where = f"{self.location}: " if self.location else ""
        return f"{where}error {self.code}: {printable(self.message)}"

    def render(self) -> str:
        """The error in the language chosen (see :meth:`Diagnostic.render`)."""
        from .i18n import SOURCE, language, message, severity

        if language() == SOURCE:
            return str(self)
        if len(self.diagnostics) > 1:
            return "\n".join(d.render() for d in self.diagnostics)
        where = f"{self.location}: " if self.location else ""
        return (f"{where}{severity('error')} {self.code}: "
                f"{printable(message(self.code, self.message))}")


class PlcRuntimeFault(PlcError):
    """A fault raised while the PLC scans (watchdog, division by zero, index out of range)."""
