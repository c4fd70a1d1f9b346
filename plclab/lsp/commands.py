"""``plclab lsp``: the language server's command (registered lazily, ADR 0013)."""

from __future__ import annotations

import argparse

from ..cli_registry import arg, command
from ..errors import PlcError


@command("lsp")
@arg("--stdio", action="store_true", help="talk LSP over stdin/stdout (the default and only "
     "transport; editors pass it)")
def cmd_lsp(ns: argparse.Namespace) -> int:
    try:
        from .server import main
    except ModuleNotFoundError as e:
        if e.name and e.name.split(".")[0] in ("pygls", "lsprotocol", "cattrs", "attrs"):
            raise PlcError("PLC7001", "plclab lsp needs pygls 2: pip install 'plclab[lsp]' "
                           "(or pip install 'pygls>=2')") from None
        raise
    main()
    return 0
