"""The language layer: source text to one checked AST, with diagnostics.

The lowest layer of the PLC core (``docs/adr/0013-layers-and-lazy-cli.md``): it imports only the
standard library and :mod:`plclab.errors`, never the compiler, the runtime or anything above.
The front ends, one per language and sharing :mod:`~plclab.lang.lexer`, produce the node types of
:mod:`~plclab.lang.ast`; :mod:`~plclab.lang.check` resolves names and :mod:`~plclab.lang.types`
and reports diagnostics; :mod:`~plclab.lang.limits` holds the bounds every stage enforces. Most
callers want :mod:`plclab.project` (read, parse, check, compile).

The declared API is the modules in ``__all__``; importing this package imports none of them.
"""

__all__ = ["ast", "check", "lexer", "limits", "types"]
