"""Front ends: source text (ST, IL, text LD, PLCopen XML) -> the one AST.

Each front end parses to :mod:`plclab.lang.ast` and leaves the bodies that need every
declaration first (IL, LD/FBD networks) as data on ``Pou.pending``; :mod:`plclab.lang.lower`
finishes them. :mod:`.registry` chooses the front end for a file.

Modules: :mod:`.st` (the ST parser, host of declarations), :mod:`.il_lines` (IL body lines),
:mod:`.il` (``.il`` files), :mod:`.ld` (text ladder), :mod:`.plcopen` (PLCopen XML).
"""

from __future__ import annotations

from .registry import BODY_KINDS, FRONT_ENDS, BodyKind, FrontEnd, for_file, suffixes

__all__ = ["BODY_KINDS", "FRONT_ENDS", "BodyKind", "FrontEnd", "for_file", "suffixes"]
