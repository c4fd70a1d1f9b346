"""``plclab check --explain-dialect FILE``: what in a file is not portable IEC 61131-3.

Each file is checked twice: in the dialect it is read in (its ``{dialect}`` pragma, the option,
the tool that wrote it, or the default; ADR 0017), and as strict ``iec`` (the pragma set
aside). Every place where the strict reading has an error the file's own dialect does not is a
dialect rule that fired: the report names the rule's warning code where the dialect gives one
(PLC0173, PLC0283, PLC0285, PLC0290, ...), its location, and what a strict IEC compiler says
there, so a student porting CODESYS code sees what another compiler will refuse (ADR 0051).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..errors import Diagnostic, Location, PlcError, printable
from .dialect import DEFAULT, explain_choice, without_pragma

__all__ = ["DialectRule", "dialect_rules", "report"]

# warnings that say "accepted as the dialect does, not as IEC": the leniency codes
LENIENCY = frozenset({"PLC0173", "PLC0175", "PLC0280", "PLC0283", "PLC0284", "PLC0285",
                      "PLC0290", "PLC0291", "PLC0292", "PLC0340"})


@dataclass
class DialectRule:
    location: Location | None
    dialect: str
    code: str  # the dialect's warning code, or "" when it accepts the text silently
    message: str  # the dialect's warning
    strict: list[Diagnostic]  # what the iec dialect says at the same place


def _key(d: Diagnostic) -> tuple[str, int]:
    return (d.location.file, d.location.line) if d.location is not None else ("", 0)


def dialect_rules(sources: list[tuple[str, str]], given: str | None, check_sources: Callable,
                  ) -> tuple[dict[str, tuple[str, str]], list[DialectRule]]:
    """(file -> (dialect, why), the rules that fired), in source order. ``check_sources`` is
    :func:`plclab.project.check_sources` (passed in: the language layer imports no upper one)."""
    chosen: dict[str, tuple[str, str]] = {}
    for text, filename in sources:
        try:
            chosen[filename] = explain_choice(text, given, filename)
        except PlcError as exc:  # an unknown pragma: PLC0170 in the check
            chosen[filename] = (DEFAULT, exc.message)
    _, own = check_sources(sources, given, lint=False)
    strict_sources = [(without_pragma(text), f) for text, f in sources]
    _, strict = check_sources(strict_sources, "iec", lint=False)
    own_errors = {_key(d) for d in own if d.severity == "error"}
    strict_at: dict[tuple[str, int], list[Diagnostic]] = {}
    for d in strict:
        if d.severity == "error" and _key(d) not in own_errors:
            strict_at.setdefault(_key(d), []).append(d)
    rules: list[DialectRule] = []
    seen: set[tuple[str, int]] = set()
    for d in own:
        if d.code in LENIENCY and d.location is not None:
            k = _key(d)
            rules.append(DialectRule(d.location, chosen.get(d.location.file, (DEFAULT, ""))[0],
                                     d.code, d.message, strict_at.get(k, [])))
            seen.add(k)
    for k, ds in strict_at.items():
        if k not in seen:  # accepted silently by the dialect (a form of its syntax)
            loc = ds[0].location
            rules.append(DialectRule(loc, chosen.get(k[0], (DEFAULT, ""))[0], "", "", ds))
    rules.sort(key=lambda r: (r.location.file, r.location.line, r.location.col)
               if r.location else ("", 0, 0))
    return chosen, rules


def report(sources: list[tuple[str, str]], given: str | None,
           check_sources: Callable) -> tuple[str, int]:
    """The text ``plclab check --explain-dialect`` prints, and the number of rules that fired."""
    chosen, rules = dialect_rules(sources, given, check_sources)
    lines = [f"{printable(f)}: dialect {name} ({why})" for f, (name, why) in chosen.items()]
    for r in rules:
        head = f"{r.location}: " if r.location else ""
        if r.code:
            lines.append(f"{head}{r.code} ({r.dialect}) {printable(r.message)}")
        else:
            lines.append(f"{head}accepted by {r.dialect} without a warning")
        if r.strict:
            for s in r.strict:
                lines.append(f"    iec: {s.code} {printable(s.message)}")
        else:
            lines.append("    iec: accepted here too (the warning is advice)")
    n = len(rules)
    portable = [f for f, (name, _) in chosen.items() if name == "iec"]
    lines.append(f"{n} dialect rule(s) fired" + (
        "; the files read as iec are strict already" if portable and len(portable) == len(
            chosen) else ""))
    return "\n".join(lines), n
