"""``plclab lsp``: a Language Server Protocol server for ST, IL, text LD and PLCopen XML.

The editor features are plain functions over the front ends and the checker of
:mod:`plclab.lang` (:mod:`.documents`, :mod:`.index`, :mod:`.features`, :mod:`.stdlib_docs`);
:mod:`.server` alone imports ``pygls`` (the ``lsp`` extra) and turns them into LSP messages.
Importing this package imports neither (docs/adr/0054-language-server.md).

Layer ``lsp``: above the core and its front door (:mod:`plclab.project`, :mod:`plclab.testing`);
nothing imports it but the command line.
"""

__all__ = ["documents", "features", "index", "stdlib_docs"]
