"""Variable names as users type them on the command line or in a ``watch=`` list.

Used by the CLI and by the simulator, so it lives below both (``docs/adr/0013-layers-and-lazy-cli.md``).
"""

from __future__ import annotations

__all__ = ["split_names"]


def split_names(text: str) -> list[str]:
    """Split ``A,B[1,2],C`` at the commas that are not inside brackets.

    >>> split_names("A, B[1,2] ,C")
    ['A', 'B[1,2]', 'C']
    """
    out, depth, cur = [], 0, ""
    for ch in text:
        depth += ch == "["
        depth -= ch == "]"
        if ch == "," and depth == 0:
            out.append(cur)
            cur = ""
        else:
            cur += ch
    out.append(cur)
    return [n.strip() for n in out if n.strip()]
