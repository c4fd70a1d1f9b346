"""The playground editor's Python side: highlighting, diagnostics as you type, hover and
completion. It runs in the page's worker under Pyodide (and in CPython for tests).

The highlighting is the course's: the Pygments lexers of :mod:`plclab.viz.highlight` (the site
ships Pygments' lexer core in its zip), with Pygments' short CSS classes, so the editor and the
course pages colour a program alike. Diagnostics, hover and completion are the language
server's feature functions (:mod:`plclab.lsp.documents`, :mod:`plclab.lsp.features`), not the
pygls server: the page gets what an editor with ``plclab lsp`` gets (docs/adr/0064).

Lines and columns are 1-based; every function returns plain data and never raises for a
mistake in the text.

>>> spans = highlight("x := 1; (* note *)", "st")
>>> [c for c, v in spans[0] if v == "(*"]
['cm']
>>> lint("PROGRAM P\\nVAR x : INT; END_VAR\\nx := 1 +;\\nEND_PROGRAM\\n", "st")[0]["code"]
'PLC0010'
"""

from __future__ import annotations

import re
from typing import Any

LANGUAGE_SUFFIX = {"st": ".st", "il": ".il", "ld": ".ld"}
URI = "playground"
_IDENT = re.compile(r"[A-Za-z0-9_]")
_workspace: Any = None


def filename(language: str) -> str:
    return "playground" + LANGUAGE_SUFFIX.get(language, ".st")


def _lexer(language: str) -> Any:
    from plclab.viz.highlight import IecIlLexer, IecLdLexer, IecStLexer

    return {"il": IecIlLexer, "ld": IecLdLexer}.get(language, IecStLexer)()


def css_class(token: Any) -> str:
    """Pygments' short class of a token type (its parent's when it has none of its own), as
    the HTML formatter of the course pages writes it."""
    from pygments.token import STANDARD_TYPES

    while token not in STANDARD_TYPES:
        token = token.parent
    return STANDARD_TYPES[token]


def highlight(text: str, language: str = "st") -> list[list[tuple[str, str]]]:
    """The text as lines of (css class, text) pieces; joined, each line is the text's line."""
    lines: list[list[tuple[str, str]]] = [[]]
    for _, token, value in _lexer(language).get_tokens_unprocessed(text):
        cls = css_class(token)
        parts = value.split("\n")
        for k, part in enumerate(parts):
            if k:
                lines.append([])
            if part:
                lines[-1].append((cls, part))
    return lines


def _analysis(text: str, language: str, line: int = 0) -> Any:
    """The language server's analysis of the text; with ``line`` the one hover and completion
    use: the text's own when it reads, else the text without the half-typed ``line`` (the
    declarations around it), else the last text that read. (The last text that read alone is
    not enough: in the page it may be another program, the one before a paste.)"""
    global _workspace
    from plclab.lsp.documents import Workspace

    if _workspace is None:
        _workspace = Workspace(size=16)
    a = _workspace.update(URI, text, filename(language))
    if not line or a.syntax_ok:
        return a
    lines = text.split("\n")
    if 0 < line <= len(lines):
        lines[line - 1] = ""
        probe = _workspace.update(URI + "-without-line", "\n".join(lines), filename(language))
        if probe.syntax_ok:
            return probe
    return _workspace.for_features(URI)


def word_end(text: str, line: int, col: int) -> int:
    """The column after the word (or the one character) at (line, col): what is underlined."""
    lines = text.split("\n")
    s = lines[line - 1] if 0 < line <= len(lines) else ""
    i = max(col - 1, 0)
    j = i
    while j < len(s) and _IDENT.match(s[j]):
        j += 1
    return max(j, min(i + 1, len(s))) + 1


def lint(text: str, language: str = "st") -> list[dict[str, Any]]:
    """What ``plclab check`` reports (the language server's diagnostics), each with the range
    the editor underlines: ``line``, ``col``, ``end`` (the column after it; 0 = no place)."""
    from plclab.i18n import message
    from plclab.lsp.documents import location_in

    a = _analysis(text, language)
    out = []
    for d in a.diagnostics:
        loc = location_in(d, a.filename)
        line, col = (loc.line, max(loc.col, 1)) if loc is not None and loc.line > 0 else (0, 0)
        out.append({"code": d.code, "message": message(d.code, d.message),
                    "severity": d.severity, "line": line, "col": col if line else 0,
                    "end": word_end(text, line, col) if line else 0})
    out.sort(key=lambda d: (d["severity"] != "error", d["line"], d["col"]))
    return out


def hover(text: str, language: str, line: int, col: int) -> str:
    """The language server's hover at (line, col) as Markdown ('' when there is none): a
    variable's type and declaration, a standard function's or block's signature and doc."""
    from plclab.lsp import features as F

    a = _analysis(text, language, line)
    if a is None:
        return ""
    if a.text != text:  # the last text that read: positions may have moved, so ask by name
        w = F.word_at(text, line, col)
        if w is None or not w.text:
            return ""
        return _hover_by_name(a, w.text) or ""
    return F.hover(a, line, col) or ""


def _hover_by_name(a: Any, name: str) -> str | None:
    for n, row in enumerate(a.text.split("\n"), 1):
        m = re.search(rf"\b{re.escape(name)}\b", row, re.IGNORECASE)
        if m:
            from plclab.lsp import features as F

            found = F.hover(a, n, m.start() + 1)
            if found:
                return found
    return None


def complete(text: str, language: str, line: int, col: int) -> list[dict[str, str]]:
    """The language server's completion at (line, col): members after ``.`` (FB outputs,
    STRUCT fields, methods, step flags), else declared names, standard functions and blocks
    and keywords, narrowed to those that start with the word typed so far."""
    from plclab.lsp import features as F

    a = _analysis(text, language, line)
    if a is None:
        return []
    w = F.word_at(text, line, col, before_only=True)
    prefix = (w.text if w is not None else "").upper()
    out = [{"label": c.label, "kind": c.kind, "detail": c.detail, "doc": c.doc,
            "from": w.start if w is not None else col}
           for c in F.completions(a, text, line, col) if c.label.upper().startswith(prefix)]
    return out[:200]
