"""The language server driven end to end by pytest-lsp: ``plclab lsp`` runs as a subprocess
and the test talks LSP to it over stdio, as an editor does."""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import pytest

pytest.importorskip("pytest_lsp")

import pytest_lsp  # noqa: E402
from lsprotocol import types as T  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities  # noqa: E402

DOCS = Path(__file__).parent / "docs"
DOCS_URL = "https://plclab.example.org/site/"
LANGUAGE_ID = {".st": "iec-st", ".il": "iec-il", ".ld": "iec-ld", ".xml": "xml"}


@pytest_lsp.fixture(config=ClientServerConfig(
    server_command=[sys.executable, "-m", "plclab", "lsp", "--stdio"]))
async def client(lsp_client: LanguageClient):
    lsp_client.lens_refreshes = []  # the server asks the editor to redraw the lenses

    @lsp_client.feature(T.WORKSPACE_CODE_LENS_REFRESH)
    def _refresh(params: None) -> None:
        lsp_client.lens_refreshes.append(params)

    await lsp_client.initialize_session(T.InitializeParams(
        capabilities=client_capabilities("visual-studio-code"),
        initialization_options={"docsUrl": DOCS_URL}))
    yield
    await lsp_client.shutdown_session()


class Doc:
    """A document opened in the server: its URI, its text, and edits as an editor sends them."""

    def __init__(self, client: LanguageClient, uri: str, text: str, language: str) -> None:
        self.client, self.uri, self.text, self.language = client, uri, text, language
        self.version = 1

    def line_of(self, needle: str, nth: int = 0) -> int:
        """0-based line of the *nth* line containing *needle*."""
        hits = [i for i, s in enumerate(self.text.splitlines()) if needle in s]
        return hits[nth]

    def pos(self, needle: str, offset: int = 0, nth: int = 0) -> T.Position:
        """The position of *needle* (+ offset characters) in the *nth* line that holds it."""
        line = self.line_of(needle, nth)
        return T.Position(line, self.text.splitlines()[line].index(needle) + offset)

    async def diagnostics(self) -> list[T.Diagnostic]:
        """The next diagnostics published for this document (start waiting before the request
        that causes them: ``asyncio.ensure_future(doc.diagnostics())``)."""
        async def wait() -> list[T.Diagnostic]:
            while True:
                p = await self.client.wait_for_notification(T.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
                if p.uri == self.uri:
                    return p.diagnostics

        return await asyncio.wait_for(wait(), 60)

    async def replace(self, old: str, new: str) -> list[T.Diagnostic]:
        """An incremental edit: *old* (its first occurrence) becomes *new*; the diagnostics."""
        i = self.text.index(old)
        before = self.text[:i]
        line = before.count("\n")
        col = i - (before.rfind("\n") + 1)
        end_text = before + old
        end = T.Position(end_text.count("\n"), len(end_text) - (end_text.rfind("\n") + 1))
        self.text = before + new + self.text[i + len(old):]
        self.version += 1
        waiter = asyncio.ensure_future(self.diagnostics())
        await asyncio.sleep(0)
        self.client.text_document_did_change(T.DidChangeTextDocumentParams(
            text_document=T.VersionedTextDocumentIdentifier(uri=self.uri, version=self.version),
            content_changes=[T.TextDocumentContentChangePartial(
                range=T.Range(T.Position(line, col), end), text=new)]))
        return await waiter

    def ident(self) -> T.TextDocumentIdentifier:
        return T.TextDocumentIdentifier(uri=self.uri)


@pytest.fixture
def open_doc(client: LanguageClient, tmp_path: Path):
    """``await open_doc("demo.st")``: open a test document (never written to disk: the server
    reads the editor's text) and wait for its first diagnostics."""

    async def opener(name: str, text: str | None = None) -> tuple[Doc, list[T.Diagnostic]]:
        text = (DOCS / name).read_text(encoding="utf-8") if text is None else text
        uri = (tmp_path / name).as_uri()
        doc = Doc(client, uri, text, LANGUAGE_ID[Path(name).suffix])
        waiter = asyncio.ensure_future(doc.diagnostics())
        await asyncio.sleep(0)
        client.text_document_did_open(T.DidOpenTextDocumentParams(T.TextDocumentItem(
            uri=uri, language_id=doc.language, version=1, text=text)))
        return doc, await waiter

    return opener
