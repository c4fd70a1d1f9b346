"""Checking a document: the same pipeline as ``plclab check``, cached per text.

:func:`analyze` runs :func:`plclab.project.check_sources` (front end, lowering, checker,
beginner warnings) on one document and keeps what the editor features need: the diagnostics,
the parsed files and the :class:`~plclab.lsp.index.Index`. :class:`Workspace` keeps one
analysis per text hash (an unchanged document, or an edit undone, is never checked again; the
LRU is the compile cache's :class:`~plclab.compile.cache.MemoryCache`, and the block library
each analysis needs is parsed once a process, ADR 0057) and, per document, the last analysis
without syntax errors: while a student types a half line, hover and completion still know the
declarations.
"""

from __future__ import annotations

import hashlib
import time
from dataclasses import dataclass, field
from typing import Any

from ..compile.cache import MemoryCache
from ..errors import Diagnostic, Location, PlcError
from .index import Index, build

# the LSP languageId an editor sends -> the suffix whose front end reads the text
LANGUAGE_SUFFIX = {"st": ".st", "iec-st": ".st", "structured-text": ".st", "structuredtext": ".st",
                   "iec61131": ".st", "il": ".il", "iec-il": ".il", "ld": ".ld", "iec-ld": ".ld",
                   "xml": ".xml", "plcopen": ".xml", "plcopen-xml": ".xml"}


def filename_for(path: str, language_id: str | None = None) -> str:
    """The file name the front-end registry sees: the path when its suffix names a front end,
    else the path with the suffix of the editor's language (an ``untitled:`` buffer of IL:
    ``.il``; an unknown language: ``.st``)."""
    import os

    from ..lang.frontends.registry import suffixes

    ext = os.path.splitext(path)[1].lower()
    if ext and ext in suffixes():
        return path
    return path + LANGUAGE_SUFFIX.get((language_id or "").lower(), ".st")


@dataclass(eq=False)
class Analysis:
    """One checked text."""

    filename: str
    text: str
    digest: str
    diagnostics: list[Diagnostic]
    files: list[Any]  # every parsed SourceFile, the library's first
    index: Index
    syntax_ok: bool  # no error of the front end: declarations and bodies all read
    seconds: float = 0.0
    project: Any = None  # the checked project (None when there are errors)


def is_plc_document(text: str, filename: str) -> bool:
    """False for an XML file that is not PLCopen (an editor may send every ``.xml``: a Maven
    ``pom.xml`` gets no diagnostics from plclab)."""
    if not filename.lower().endswith(".xml"):
        return True
    head = text[:4000].lower()
    return "plcopen" in head or "<project" in head


def digest(filename: str, text: str, dialect: str | None) -> str:
    h = hashlib.sha256()
    for part in (filename, dialect or "", text):
        h.update(part.encode("utf-8", "surrogatepass"))
        h.update(b"\0")
    return h.hexdigest()


def analyze(text: str, filename: str, dialect: str | None = None, lint: bool = True
            ) -> Analysis:
    """Check *text* as the file *filename*; never raises for a mistake in the text."""
    from ..project import check_parsed, parse_sources

    start = time.perf_counter()
    if not is_plc_document(text, filename):
        return Analysis(filename, text, digest(filename, text, dialect), [], [],
                        Index(filename), True)
    files: list[Any] = []
    syntax_ok = True
    project = None
    sources = [(text, filename)]
    try:
        files, front = parse_sources(sources, dialect)
        syntax_ok = not any(d.severity == "error" for d in front)
        project, diags = check_parsed(files, front, sources, dialect, lint=lint)
    except PlcError as e:
        diags = list(e.diagnostics) or [Diagnostic(e.code, e.message, e.location)]
        syntax_ok = False
    own = files[-1] if files else None
    try:
        index = build(files, own, text)
    except Exception as exc:  # noqa: BLE001 - a gap of the index must not hide the diagnostics
        index = Index(filename)
        index.error = repr(exc)
    return Analysis(filename, text, digest(filename, text, dialect), diags, files, index,
                    syntax_ok, time.perf_counter() - start, project)


@dataclass(eq=False)
class Workspace:
    """The analyses of the open documents, cached by text hash (LRU of ``size``)."""

    size: int = 64
    dialect: str | None = None
    cache: MemoryCache = field(default=None)  # type: ignore[assignment] # made in __post_init__
    last_good: dict[str, Analysis] = field(default_factory=dict)  # uri -> analysis
    current: dict[str, Analysis] = field(default_factory=dict)  # uri -> analysis
    checks: int = 0  # how many times the pipeline ran (the cache's hits do not count)

    def __post_init__(self) -> None:
        if self.cache is None:
            self.cache = MemoryCache(self.size)  # the compile cache's LRU (ADR 0057)

    def update(self, uri: str, text: str, filename: str) -> Analysis:
        """The analysis of *text*: from the cache when this text was checked before."""
        key = digest(filename, text, self.dialect)
        a = self.cache.get(key)
        if a is None:
            a = analyze(text, filename, self.dialect)
            self.checks += 1
            self.cache.put(key, a)
        self.current[uri] = a
        if a.syntax_ok:
            self.last_good[uri] = a
        return a

    def for_features(self, uri: str) -> Analysis | None:
        """The analysis hover, completion and symbols use: the current one when it read without
        syntax errors, else the last one that did (the declarations before the half-typed line)."""
        a = self.current.get(uri)
        if a is not None and a.syntax_ok:
            return a
        return self.last_good.get(uri, a)

    def close(self, uri: str) -> None:
        self.current.pop(uri, None)
        self.last_good.pop(uri, None)


def location_in(d: Diagnostic, filename: str) -> Location | None:
    """Where a diagnostic of this document is (None: a diagnostic of another file or none)."""
    if d.location is None or d.location.file != filename:
        return None
    return d.location
