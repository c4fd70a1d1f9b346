"""The LSP server on ``pygls`` 2 (stdio): :mod:`plclab.lsp.features` turned into LSP messages.

Only this module imports ``pygls`` and ``lsprotocol`` (the ``lsp`` extra). Documents are
synchronised incrementally; each version is checked once (:class:`~.documents.Workspace`
caches per text hash) and its diagnostics published with their code and a link to the code's
page of the site (``problems/PLCnnnn/``; the site's address from the client's
``initializationOptions.docsUrl`` or ``PLCLAB_DOCS_URL``, else ``plclab site serve``'s).
"""

from __future__ import annotations

import os
import re
from typing import Any

from lsprotocol import types as T
from pygls.lsp.server import LanguageServer
from pygls.uris import to_fs_path

from .. import __version__
from ..errors import Diagnostic, Location
from . import features as F
from . import index as I
from .documents import Workspace, filename_for, location_in

RUN_TEST = "plclab.runTest"
STATS = "plclab.stats"
DEFAULT_DOCS_URL = "http://127.0.0.1:8000/"  # `plclab site serve`

SYMBOL_KIND = {I.VARIABLE: T.SymbolKind.Variable, I.CONSTANT: T.SymbolKind.Constant,
               I.POU: T.SymbolKind.Module, I.METHOD: T.SymbolKind.Method,
               I.ACTION: T.SymbolKind.Function, I.STEP: T.SymbolKind.Event,
               I.TRANSITION: T.SymbolKind.Operator, I.TYPE: T.SymbolKind.Struct,
               I.FIELD: T.SymbolKind.Field, I.ENUM: T.SymbolKind.EnumMember,
               I.TEST: T.SymbolKind.Class, I.CONFIG: T.SymbolKind.Namespace}
COMPLETION_KIND = {I.VARIABLE: T.CompletionItemKind.Variable,
                   I.CONSTANT: T.CompletionItemKind.Constant,
                   I.POU: T.CompletionItemKind.Module, I.METHOD: T.CompletionItemKind.Method,
                   I.ACTION: T.CompletionItemKind.Function, I.STEP: T.CompletionItemKind.Event,
                   I.TRANSITION: T.CompletionItemKind.Operator,
                   I.TYPE: T.CompletionItemKind.Struct, I.FIELD: T.CompletionItemKind.Field,
                   I.ENUM: T.CompletionItemKind.EnumMember, I.TEST: T.CompletionItemKind.Class,
                   I.CONFIG: T.CompletionItemKind.Module,
                   "function": T.CompletionItemKind.Function,
                   "block": T.CompletionItemKind.Class, "keyword": T.CompletionItemKind.Keyword}


class PlcLanguageServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("plclab", __version__)
        self.docs = Workspace()
        self.docs_url = os.environ.get("PLCLAB_DOCS_URL", DEFAULT_DOCS_URL)
        self.results: dict[str, dict[str, Any]] = {}  # uri -> TEST title -> TestResult
        self.filenames: dict[str, str] = {}


server = PlcLanguageServer()


# ------------------------------------------------------------------------------ positions


def name_range(text: str, loc: Location | None, name: str) -> T.Range:
    """The range of *name* written at or after *loc* on its line (a POU's location is its
    keyword's; an XML element's, the tag's): the whole name, 0-based."""
    if loc is None or loc.line <= 0:
        return T.Range(T.Position(0, 0), T.Position(0, 0))
    s = F.line_text(text, loc.line)
    start = max(loc.col - 1, 0)
    m = re.compile(r"(?<![A-Za-z0-9_])" + re.escape(name) + r"(?![A-Za-z0-9_])", re.I) \
        .search(s, start) if name else None
    if m is not None:
        return T.Range(T.Position(loc.line - 1, m.start()), T.Position(loc.line - 1, m.end()))
    return T.Range(T.Position(loc.line - 1, start), T.Position(loc.line - 1, start))


def word_range(text: str, loc: Location) -> T.Range:
    """A diagnostic's range: the word (identifier, number) that starts at *loc*, else one
    character."""
    s = F.line_text(text, loc.line)
    a = min(max(loc.col - 1, 0), len(s))
    b = a
    while b < len(s) and (s[b].isalnum() or s[b] in "_#%."):
        b += 1
    if b == a:
        b = min(a + 1, len(s)) if s else a
    return T.Range(T.Position(loc.line - 1, a), T.Position(loc.line - 1, b))


def _lsp_diagnostic(text: str, filename: str, d: Diagnostic, docs_url: str) -> T.Diagnostic:
    where = location_in(d, filename)
    message = d.message
    if where is None or where.line <= 0:
        rng = T.Range(T.Position(0, 0), T.Position(0, 0))
        if d.location is not None and d.location.file != filename:
            message = f"{d.location}: {message}"
    else:
        rng = word_range(text, where)
    severity = (T.DiagnosticSeverity.Error if d.severity == "error"
                else T.DiagnosticSeverity.Warning)
    href = docs_url.rstrip("/") + f"/problems/{d.code}/"
    return T.Diagnostic(range=rng, message=message, severity=severity, code=d.code,
                        code_description=T.CodeDescription(href=href), source="plclab")


def _failure_diagnostic(text: str, r: Any) -> T.Diagnostic:
    loc = r.failure_location or r.location
    rng = word_range(text, loc) if loc and loc.line > 0 else T.Range(T.Position(0, 0),
                                                                        T.Position(0, 0))
    return T.Diagnostic(range=rng, message=f"TEST '{r.title}' failed: {r.message}",
                        severity=T.DiagnosticSeverity.Error, code=r.code or None,
                        source="plclab test")


# ------------------------------------------------------------------------------ documents


def _filename(ls: PlcLanguageServer, uri: str, language_id: str | None) -> str:
    if uri not in ls.filenames:
        path = to_fs_path(uri) if uri.startswith("file:") else uri
        ls.filenames[uri] = filename_for(path or uri, language_id)
    return ls.filenames[uri]


def _publish(ls: PlcLanguageServer, uri: str, version: int | None = None) -> None:
    doc = ls.workspace.get_text_document(uri)
    filename = _filename(ls, uri, doc.language_id)
    try:
        a = ls.docs.update(uri, doc.source, filename)
    except Exception as exc:  # noqa: BLE001 - a bug of plclab: say so, keep serving
        ls.window_log_message(T.LogMessageParams(T.MessageType.Error,
                                                 f"plclab could not check {uri}: {exc!r}"))
        return
    if a.index.error:
        ls.window_log_message(T.LogMessageParams(T.MessageType.Error,
                                                 f"plclab could not index {uri}: {a.index.error}"))
    diags = [_lsp_diagnostic(doc.source, filename, d, ls.docs_url) for d in a.diagnostics]
    for r in ls.results.get(uri, {}).values():
        if not r.passed and getattr(r, "digest", None) == a.digest:
            diags.append(_failure_diagnostic(doc.source, r))
    ls.text_document_publish_diagnostics(
        T.PublishDiagnosticsParams(uri=uri, diagnostics=diags, version=version))


def _analysis(ls: PlcLanguageServer, uri: str):
    doc = ls.workspace.get_text_document(uri)
    a = ls.docs.for_features(uri)
    if a is None or uri not in ls.docs.current:
        ls.docs.update(uri, doc.source, _filename(ls, uri, doc.language_id))
        a = ls.docs.for_features(uri)
    return doc, a


@server.feature(T.INITIALIZE)
def initialize(ls: PlcLanguageServer, params: T.InitializeParams) -> None:
    opts = params.initialization_options
    if isinstance(opts, dict):
        if isinstance(opts.get("docsUrl"), str):
            ls.docs_url = opts["docsUrl"]
        if opts.get("dialect") in ("iec", "codesys", "s7", "matiec"):
            ls.docs.dialect = opts["dialect"]


@server.feature(T.TEXT_DOCUMENT_DID_OPEN)
def did_open(ls: PlcLanguageServer, params: T.DidOpenTextDocumentParams) -> None:
    ls.filenames.pop(params.text_document.uri, None)
    _publish(ls, params.text_document.uri, params.text_document.version)


@server.feature(T.TEXT_DOCUMENT_DID_CHANGE)
def did_change(ls: PlcLanguageServer, params: T.DidChangeTextDocumentParams) -> None:
    _publish(ls, params.text_document.uri, params.text_document.version)


@server.feature(T.TEXT_DOCUMENT_DID_SAVE)
def did_save(ls: PlcLanguageServer, params: T.DidSaveTextDocumentParams) -> None:
    _publish(ls, params.text_document.uri)


@server.feature(T.TEXT_DOCUMENT_DID_CLOSE)
def did_close(ls: PlcLanguageServer, params: T.DidCloseTextDocumentParams) -> None:
    uri = params.text_document.uri
    ls.docs.close(uri)
    ls.filenames.pop(uri, None)
    ls.text_document_publish_diagnostics(T.PublishDiagnosticsParams(uri=uri, diagnostics=[]))


# ------------------------------------------------------------------------------ features


@server.feature(T.TEXT_DOCUMENT_HOVER)
def hover(ls: PlcLanguageServer, params: T.HoverParams) -> T.Hover | None:
    doc, a = _analysis(ls, params.text_document.uri)
    if a is None:
        return None
    line, col = params.position.line + 1, params.position.character + 1
    text = F.hover(a, line, col, ls.results.get(params.text_document.uri))
    if text is None:
        return None
    return T.Hover(contents=T.MarkupContent(kind=T.MarkupKind.Markdown, value=text))


@server.feature(T.TEXT_DOCUMENT_DEFINITION)
def definition(ls: PlcLanguageServer, params: T.DefinitionParams) -> T.Location | None:
    doc, a = _analysis(ls, params.text_document.uri)
    if a is None:
        return None
    t = F.resolve(a, params.position.line + 1, params.position.character + 1)
    if t is None or t.loc is None or t.loc.file != a.index.file:
        return None
    return T.Location(uri=params.text_document.uri, range=name_range(a.text, t.loc, t.name))


def _symbol(text: str, e: I.Entry) -> T.DocumentSymbol:
    sel = name_range(text, e.loc, e.name if e.kind not in (I.TEST, I.TRANSITION) else "")
    end_line = (e.end_line or (e.loc.line if e.loc else 1)) - 1
    full = T.Range(T.Position(sel.start.line, 0), T.Position(max(end_line, sel.start.line),
                                                             len(F.line_text(text, end_line + 1))))
    if sel.start.line == full.end.line and sel.end.character > full.end.character:
        full = T.Range(full.start, sel.end)
    return T.DocumentSymbol(name=e.name or "?", kind=SYMBOL_KIND.get(e.kind, T.SymbolKind.Variable),
                            range=full, selection_range=sel, detail=e.detail,
                            children=[_symbol(text, c) for c in e.children] or None)


@server.feature(T.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
def document_symbol(ls: PlcLanguageServer, params: T.DocumentSymbolParams
                    ) -> list[T.DocumentSymbol]:
    doc, a = _analysis(ls, params.text_document.uri)
    if a is None:
        return []
    return [_symbol(a.text, e) for e in a.index.top]


@server.feature(T.TEXT_DOCUMENT_COMPLETION,
                T.CompletionOptions(trigger_characters=["."]))
def completion(ls: PlcLanguageServer, params: T.CompletionParams) -> T.CompletionList:
    doc, a = _analysis(ls, params.text_document.uri)
    if a is None:
        return T.CompletionList(is_incomplete=False, items=[])
    items = []
    for c in F.completions(a, doc.source, params.position.line + 1,
                           params.position.character + 1):
        items.append(T.CompletionItem(
            label=c.label, kind=COMPLETION_KIND.get(c.kind, T.CompletionItemKind.Text),
            detail=c.detail or None,
            documentation=T.MarkupContent(kind=T.MarkupKind.Markdown, value=c.doc)
            if c.doc else None))
    return T.CompletionList(is_incomplete=False, items=items)


@server.feature(T.TEXT_DOCUMENT_CODE_LENS)
def code_lens(ls: PlcLanguageServer, params: T.CodeLensParams) -> list[T.CodeLens]:
    doc, a = _analysis(ls, params.text_document.uri)
    if a is None:
        return []
    uri = params.text_document.uri
    out = []
    for title, loc in F.test_lenses(a):
        r = ls.results.get(uri, {}).get(title)
        label = "▶ Run TEST"
        if r is not None:
            label += "  (last run: passed)" if r.passed else "  (last run: FAILED)"
        line = loc.line - 1
        out.append(T.CodeLens(range=T.Range(T.Position(line, 0), T.Position(line, 0)),
                              command=T.Command(title=label, command=RUN_TEST,
                                                arguments=[uri, title])))
    return out


@server.command(RUN_TEST)
def run_test(ls: PlcLanguageServer, *args: Any) -> dict[str, Any]:
    """Run one TEST of a document; publish the result (a message, the lens, a diagnostic at
    the failed assertion) and return it."""
    if len(args) == 1 and isinstance(args[0], list):  # pygls passes the arguments as a list
        args = tuple(args[0])
    if len(args) != 2 or not all(isinstance(x, str) for x in args):
        return {"error": "plclab.runTest takes two arguments: the document's URI and the "
                         "TEST's title"}
    uri, title = args
    doc = ls.workspace.get_text_document(uri)
    filename = _filename(ls, uri, doc.language_id)
    a = ls.docs.update(uri, doc.source, filename)
    r = F.run_test(doc.source, filename, title, ls.docs.dialect)
    r.digest = a.digest  # the failure diagnostic stays while the text stays the same
    ls.results.setdefault(uri, {})[title] = r
    state = "passed" if r.passed else f"FAILED: {r.message}"
    ls.window_show_message(T.ShowMessageParams(
        type=T.MessageType.Info if r.passed else T.MessageType.Error,
        message=f"TEST '{title}' {state}"))
    _publish(ls, uri)
    lens = ls.client_capabilities.workspace and ls.client_capabilities.workspace.code_lens
    if lens is not None and lens.refresh_support:
        ls.workspace_code_lens_refresh(None)
    where = r.failure_location
    return {"title": title, "passed": r.passed, "message": r.message, "code": r.code,
            "line": where.line if where and where.file == filename else None}


@server.command(STATS)
def stats(ls: PlcLanguageServer, *args: Any) -> dict[str, Any]:
    """How often the pipeline ran and what the cache holds (the tests and the benchmark)."""
    return {"checks": ls.docs.checks, "cached": len(ls.docs.cache),
            "last_ms": {uri: round(a.seconds * 1000, 1) for uri, a in ls.docs.current.items()}}


def main() -> None:
    server.start_io()
