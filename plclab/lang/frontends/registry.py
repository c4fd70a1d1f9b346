"""Which front end reads which source: the one place that chooses a language.

A file goes to the front end registered for its suffix (:func:`for_file`); a body embedded in
another file (a POU body in an ST file, a ``<body>`` in PLCopen XML) is read by the front end
registered for its body kind (:data:`BODY_KINDS`). Every front end parses to the one AST and
leaves IL bodies and LD/FBD networks pending (``Pou.pending``) for :mod:`plclab.lang.lower`.

>>> for_file("tank.ld").name
'LD'
>>> ", ".join(suffixes())
'.st, .iecst, .txt, .il, .ld, .xml'
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass

from ...errors import Diagnostic, PlcError
from .. import ast as A
from . import il, ld, st

ParseFn = Callable[[str, str], tuple[A.SourceFile, list[Diagnostic]]]


def _plcopen_parse(text: str, file: str) -> tuple[A.SourceFile, list[Diagnostic]]:
    """PLCopen XML, its module (and the XML parser) imported on first use: start-up of
    commands on ST files stays short (issue 19)."""
    from . import plcopen

    return plcopen.parse(text, file)


@dataclass(frozen=True)
class FrontEnd:
    """A source language: ``parse(text, file) -> (SourceFile, diagnostics)``, bodies pending."""

    name: str
    title: str
    suffixes: tuple[str, ...]
    parse: ParseFn  # (text, file) -> (tree with pending bodies, diagnostics)


FRONT_ENDS: tuple[FrontEnd, ...] = (
    # "" (no suffix) reads as ST too; ST files may hold IL POUs (recognised by their first line)
    FrontEnd("ST", "Structured Text (IL bodies recognised)", (".st", ".iecst", ".txt", ""), st.parse),
    FrontEnd("IL", "Instruction List", (".il",), il.parse),
    FrontEnd("LD", "Ladder Diagram as text", (".ld",), ld.parse),
    FrontEnd("PLCopen", "PLCopen XML (ST, IL, LD, FBD bodies)", (".xml",), _plcopen_parse),
)

@dataclass(frozen=True)
class BodyKind:
    """A body embedded in a POU: the front end that reads it, the function doing so, and the
    kind of pending body it leaves for :data:`plclab.lang.lower.LOWERINGS` (``None``: the
    body is core statements at once)."""

    kind: str
    front_end: str
    reader: str  # plclab.lang.frontends.<module>.<function or Class.method>
    pending: str | None


BODY_KINDS: dict[str, BodyKind] = {b.kind: b for b in (
    BodyKind("ST", "ST", "st.Parser.stmt_list", None),
    BodyKind("IL", "IL", "il_lines.parse_il_body", "IL"),
    BodyKind("LD", "LD", "ld._TextLadder.parse", "NETWORK"),  # text rungs; PLCopen <LD> too
    BodyKind("FBD", "PLCopen", "plcopen._Importer.graphic", "NETWORK"),
)}
"""Embedded body kinds (the ``<body>`` languages of PLCopen, the bodies of ST/IL/LD files)."""


_BY_SUFFIX = {s: fe for fe in FRONT_ENDS for s in fe.suffixes}


def suffixes() -> list[str]:
    """Every file suffix a front end reads (``""``, a file without one, is left out)."""
    return [s for fe in FRONT_ENDS for s in fe.suffixes if s]


def for_file(path: str) -> FrontEnd:
    """The front end for ``path`` by its suffix; PLC3003 when no front end reads it."""
    ext = os.path.splitext(path)[1].lower()
    fe = _BY_SUFFIX.get(ext)
    if fe is None:
        raise PlcError("PLC3003", f"{path}: unknown source type '{ext}'; plclab reads "
                       f"{_listing()} files")
    return fe


def _listing() -> str:
    """``.st, .il, .ld and PLCopen .xml`` from the registry (the main suffix of each)."""
    names = [("PLCopen " if fe.name == "PLCopen" else "") + fe.suffixes[0] for fe in FRONT_ENDS]
    return ", ".join(names[:-1]) + " and " + names[-1]


__all__ = ["FrontEnd", "BodyKind", "FRONT_ENDS", "BODY_KINDS", "for_file", "suffixes"]
