"""Error codes of the simulation layer (wiring tables, scenarios, the simulation, traces).

Every problem a user can cause here is a :class:`plclab.errors.PlcError` with one of these codes,
a message that says what to do and, for files, the ``file:line`` of the offending row (TOML
parsers give no positions, so the line is found from the row's text; when that fails the
message still names the row index and the key).

>>> str(sim_error("PLC4002", "no such signal", "w.toml", 3))
'w.toml:3:1: error PLC4002: no such signal'
"""

from __future__ import annotations

from collections.abc import Iterable

from plclab.errors import Diagnostic, Location, PlcError
from plclab.problems import PROBLEMS as _PROBLEMS  # noqa: E402
from plclab.suggest import suggest

#: the simulation layer's codes (kept in the one catalogue, plclab/problems.py)
CODES: dict[str, tuple[str, str]] = {k: v for k, v in _PROBLEMS.items()
                                     if k.startswith("PLC40")}
"""Code -> (title, explanation) for every code this package raises (PLC40xx)."""


def sim_error(code: str, message: str, file: str | None = None, line: int = 0,
              col: int = 1) -> PlcError:
    """A :class:`PlcError` with an optional ``file:line`` location."""
    loc = Location(str(file), line, col if line else 0) if file else None
    return PlcError(code, message, loc)


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """`` Did you mean 'X'?`` (with a leading space) or an empty string."""
    choices = list(choices)
    close = suggest(word, choices, n=2)
    if not close:
        close = [c for c in choices if c.lower() == str(word).lower()]
    if not close:
        return ""
    return " Did you mean " + " or ".join(repr(c) for c in close) + "?"


def raise_all(diags: list[Diagnostic]) -> None:
    """Raise one PlcError carrying every diagnostic (the first one is the headline)."""
    if not diags:
        return
    first = diags[0]
    raise PlcError(first.code, first.message, first.location, diagnostics=list(diags))
