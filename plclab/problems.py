"""The catalogue of diagnostic codes: every code plclab can report, with what it means.

The entries live in ``problems.toml`` next to this module (title, explanation, and for codes a
student can cause a wrong example and its fix); this module reads it once, with ``tomllib``.
Codes are stable: a code is never reused for another problem. ``plclab explain CODE`` prints an
entry. PLC0xxx are compile-time diagnostics, PLC02xx warnings, PLC2xxx run-time faults,
PLC3xxx API/command-line misuse, PLC40xx simulation files, PLC50xx labs and the grader,
PLC9xxx configuration of I/O modules, Modbus and internal errors.

>>> PROBLEMS["PLC0100"][0]
'undeclared name'
>>> print(describe("PLC0013").splitlines()[0])
PLC0013: '=' used to assign
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

from .errors import PlcError

CATALOGUE_FILE = Path(__file__).with_name("problems.toml")
LANGUAGES = ("st", "il", "ld", "xml")


@dataclass(frozen=True, slots=True)
class Problem:
    """One entry of the catalogue (see the keys documented at the top of problems.toml)."""

    code: str
    title: str
    explanation: str
    language: str | None = None
    wrong: str | None = None
    fix: str | None = None
    scans: int | None = None
    run: str = "scan"  # "scan" | "test"
    example: str | None = None
    no_example: str | None = None
    reserved: bool = False
    reserved_why: str | None = None


_KEYS = set(Problem.__dataclass_fields__) - {"code"}


@cache
def catalogue() -> dict[str, Problem]:
    """Every entry of ``problems.toml``, by code, in file order."""
    with open(CATALOGUE_FILE, "rb") as fh:
        raw = tomllib.load(fh)
    out: dict[str, Problem] = {}
    for code, entry in raw.items():
        unknown = set(entry) - _KEYS
        if unknown:
            raise ValueError(f"problems.toml [{code}]: unknown keys {sorted(unknown)}")
        out[code] = Problem(code=code, **entry)
    return out


def _problems() -> dict[str, tuple[str, str]]:
    return {code: (p.title, p.explanation) for code, p in catalogue().items()}


def __getattr__(name: str) -> Any:
    # PROBLEMS is built on first use, so importing this module does not read the TOML
    if name == "PROBLEMS":
        value = _problems()
        globals()["PROBLEMS"] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


PROBLEMS: dict[str, tuple[str, str]]  # code -> (title, explanation); see __getattr__


def explain(code: str) -> str:
    """``CODE: title`` and the explanation, in the language chosen (:mod:`plclab.i18n`;
    English where it has no text); KeyError for an unknown code."""
    from .i18n import problem_text

    code = code.upper()
    if code not in catalogue():
        raise KeyError(code)
    p = catalogue()[code]
    return (f"{code}: {problem_text(code, 'title', p.title)}\n\n"
            f"{problem_text(code, 'explanation', p.explanation)}")


def _indent(text: str) -> str:
    return "\n".join(("    " + line) if line.strip() else "" for line in text.rstrip().split("\n"))


def describe(code: str) -> str:
    """The full entry as text: title, explanation, the wrong example and its fix (or the
    command or snippet for command-line and configuration codes). KeyError for an unknown code."""
    from .i18n import problem_text, tr

    p = catalogue()[code.upper()]
    parts = [explain(p.code)]
    if p.wrong is not None:
        if p.run == "test":
            how = tr(" (run its TEST blocks: plclab test FILE)")
        elif p.scans is not None:
            how = (tr(" (scan it {n} time: plclab run FILE --cycles {n})", n=p.scans)
                   if p.scans == 1 else
                   tr(" (scan it {n} times: plclab run FILE --cycles {n})", n=p.scans))
        else:
            how = ""
        lang = (p.language or "st").upper()
        parts.append(tr("Wrong ({lang}){how}:", lang=lang, how=how) + f"\n\n{_indent(p.wrong)}")
    if p.fix is not None:
        parts.append(tr("Fix:") + f"\n\n{_indent(p.fix)}")
    if p.example is not None:
        parts.append(tr("Example:") + f"\n\n{_indent(p.example)}")
    if p.no_example is not None:
        parts.append(tr("No example: {why}",
                        why=problem_text(p.code, "no_example", p.no_example)))
    if p.reserved:
        parts.append(tr("Reserved: {why}", why=problem_text(
            p.code, "reserved_why", p.reserved_why or "not raised yet")))
    return "\n\n".join(parts)


def listing() -> str:
    """One line per code: ``PLC0100  undeclared name``."""
    from .i18n import problem_text

    return "\n".join(f"{code}  {problem_text(code, 'title', p.title)}"
                     for code, p in sorted(catalogue().items()))


def close_codes(code: str, n: int = 3) -> list[str]:
    """Catalogued codes that look like ``code`` (a typo in a digit, a missing prefix)."""
    from .suggest import suggest

    digits = code.strip().upper().removeprefix("PLC")
    by_digits = {c.removeprefix("PLC"): c for c in catalogue()}
    if digits.isdigit() and len(digits) < 4:
        digits = digits.zfill(4)
    if digits in by_digits:  # "113" for PLC0113
        return [by_digits[digits]]
    return [by_digits[d] for d in suggest(digits, by_digits, n=n, cutoff=0.7)]


def explain_command(code: str | None, list_all: bool = False) -> int:
    """``plclab explain CODE`` / ``plclab explain --list``: print and return the exit status."""
    if list_all:
        print(listing())
        return 0
    if not code:
        raise PlcError("PLC3002", "give a code, e.g. plclab explain PLC0100, or --list for all "
                       "codes")
    try:
        print(describe(code.strip()))
    except KeyError:
        close = close_codes(code)
        hint = f"; did you mean {' or '.join(close)}?" if close else ""
        raise PlcError("PLC3002", f"{code} is not a plclab diagnostic code{hint} "
                       "(plclab explain --list lists them)") from None
    return 0
