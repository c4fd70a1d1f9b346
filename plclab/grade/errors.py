"""Error codes of the labs and the autograder (PLC5001-PLC5099).

Every problem in a lab file is a :class:`~plclab.errors.PlcError` whose message names the key
and says what to write; every problem of a submission (no source, a language the lab does not
allow, a time or memory limit, a crash of the worker) becomes feedback with one of these codes.

>>> print(grade_error("PLC5002", "unknown key 'titel'"))
error PLC5002: unknown key 'titel'
"""

from __future__ import annotations

from collections.abc import Iterable

from plclab.errors import Location, PlcError
from plclab.problems import PROBLEMS as _PROBLEMS  # noqa: E402
from plclab.suggest import suggest

#: the lab and autograder codes (kept in the one catalogue, plclab/problems.py)
CODES: dict[str, tuple[str, str]] = {k: v for k, v in _PROBLEMS.items()
                                     if k.startswith("PLC50")}
"""Code -> (title, explanation)."""


def grade_error(code: str, message: str, location: Location | None = None) -> PlcError:
    """A :class:`PlcError` with a code from :data:`CODES`."""
    assert code in CODES, code
    return PlcError(code, message, location)


def did_you_mean(name: str, options: Iterable[str]) -> str:
    """`` Did you mean 'x'?`` or an empty string."""
    close = suggest(name, options)
    return f" Did you mean '{close[0]}'?" if close else ""


def explain(code: str) -> str:
    """``PLC5001: title`` and the explanation (KeyError for other codes)."""
    title, text = CODES[code.upper()]
    return f"{code.upper()}: {title}\n\n{text}"
