"""Known crashes and hangs found by the fuzzers and the escape suite, as minimal reproducers.

Each entry names the area of issue 11 whose fix it waits for. ``test_fuzz.py`` runs every
reproducer as an ``xfail(strict=False)`` test (it passes for real once the fix is merged) and
the fuzz campaigns only fail on a failure signature that matches no entry here.
"""

from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Known:
    id: str
    area: str  # which engineer's part of issue 11 fixes it
    pattern: str  # regular expression on the fuzz failure signature
    name: str  # file name of the reproducer (its extension picks the front end)
    text: str  # the minimal reproducer
    reason: str


KNOWN: list[Known] = []


def match(sig: str) -> Known | None:
    """The known issue a fuzz failure signature belongs to, if any."""
    for k in KNOWN:
        if re.fullmatch(k.pattern, sig):
            return k
    return None


# escape-suite case ids (tests/security/payloads.py) that fail for a known reason
ESCAPES: dict[str, str] = {}


def match_escape(case_id: str) -> Known | None:
    """The known issue an escape-suite case waits for, if any."""
    kid = ESCAPES.get(case_id)
    return next((k for k in KNOWN if k.id == kid), None) if kid else None
