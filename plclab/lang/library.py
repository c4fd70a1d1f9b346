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


@cache
def stdlib_text(name: str) -> str:
    """The text of one of :data:`STDLIB_FILES`."""
    return (Path(__file__).parent.parent / "runtime" / name).read_text(encoding="utf-8")


def stdlib_filename(name: str) -> str:
    """The file name diagnostics and locations use for a library file."""
    return f"<plclab>/{name}"


__all__ = ["STDLIB_FILES", "SFC_LIBRARY", "stdlib_text", "stdlib_filename"]
