"""Variable names as users type them on the command line or in a ``watch=`` list.

Used by the CLI and by the simulator, so it lives below both (``docs/adr/0013-layers-and-lazy-cli.md``).
"""

from __future__ import annotations

__all__ = ["split_names", "split_outside_brackets"]


def split_outside_brackets(text: str, sep: str) -> list[str]:
    """Split ``text`` at each ``sep`` that is not inside ``[...]`` (parts kept as written).

    >>> split_outside_brackets("P.arr[1.5].x", ".")
    ['P', 'arr[1.5]', 'x']
    """
    out, depth, cur = [], 0, ""
    for ch in text:
        depth += (ch == "[") - (ch == "]")
        if ch == sep and depth == 0:
            out.append(cur)
            cur = ""
        else:
            cur += ch
    out.append(cur)
    return out


def split_names(text: str) -> list[str]:
    """Split ``A,B[1,2],C`` at the commas that are not inside brackets.

    >>> split_names("A, B[1,2] ,C")
    ['A', 'B[1,2]', 'C']
    """
    return [n.strip() for n in split_outside_brackets(text, ",") if n.strip()]
