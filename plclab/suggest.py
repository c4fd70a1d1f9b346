"""One "did you mean" for every message that proposes a close name.

>>> suggest("countr", ["Counter", "x"], ignore_case=True)
['Counter']
>>> did_you_mean("PMUP", ["LS1", "PUMP"])
" Did you mean 'PUMP'?"
"""

from __future__ import annotations

from collections.abc import Iterable


def suggest(word: object, candidates: Iterable[object], n: int = 1, cutoff: float = 0.6,
            ignore_case: bool = False) -> list[str]:
    """The candidates closest to ``word``, best first (at most ``n``, similarity >= ``cutoff``).

    With ``ignore_case`` both sides are compared upper-cased and the candidates are returned in
    their own spelling.
    """
    import difflib  # only when a name is not found: keeps `plclab check` start-up short

    cands = [str(c) for c in candidates]
    if not ignore_case:
        return difflib.get_close_matches(str(word), cands, n=n, cutoff=cutoff)
    spelled: dict[str, str] = {}
    for c in cands:
        spelled.setdefault(c.upper(), c)
    close = difflib.get_close_matches(str(word).upper(), list(spelled), n=n, cutoff=cutoff)
    return [spelled[c] for c in close]


def did_you_mean(word: object, candidates: Iterable[object], n: int = 1,
                 cutoff: float = 0.6) -> str:
    """`` Did you mean 'A' or 'B'?`` (with a leading space) or an empty string."""
    close = suggest(word, candidates, n=n, cutoff=cutoff)
    return (" Did you mean " + " or ".join(repr(c) for c in close) + "?") if close else ""
