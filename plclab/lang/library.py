"""The source text of plclab's own block library (standard and control function blocks).

The files live next to their native implementations in ``plclab/runtime``; this module only
reads them, so that the front ends and :mod:`plclab.project` share one list without importing
each other.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

STDLIB_FILES = ("stdlib.st", "ctrllib.st")
"""The library files, parsed (with ``library=True``) before every project's own files."""

SFC_LIBRARY = "sfclib.st"
"""What lowered SFC charts use (``SFC_STEP``, ``ACTION_CONTROL``): added to a project only when
it holds a chart, so that other programs compile no more code than before."""


ANNEX_F = "annexf.st"
"""The analog blocks of IEC 61131-3 ed.2 Annex F (INTEGRAL, DERIVATIVE, HYSTERESIS, PID, RAMP),
as Beremiz and OpenPLC ship them: added to a project that declares one of them, or that has a
file in the ``matiec`` dialect (ADR 0029)."""

ANNEX_F_BLOCKS = frozenset({"INTEGRAL", "DERIVATIVE", "HYSTERESIS", "PID", "RAMP"})
ANNEX_F_SHARED = frozenset({"PID", "RAMP"})
"""Names plclab's own control library (CODESYS-style blocks) uses too: a project in the
``matiec`` dialect gets the Annex F blocks under these names, every other project plclab's."""


@cache
def stdlib_text(name: str) -> str:
    """The text of one of :data:`STDLIB_FILES`."""
    return (Path(__file__).parent.parent / "runtime" / name).read_text(encoding="utf-8")


def stdlib_filename(name: str) -> str:
    """The file name diagnostics and locations use for a library file."""
    return f"<plclab>/{name}"


__all__ = ["STDLIB_FILES", "SFC_LIBRARY", "ANNEX_F", "ANNEX_F_BLOCKS", "ANNEX_F_SHARED",
           "stdlib_text", "stdlib_filename"]
