"""``plclab compile FILE... --emit python|st|ast [-o OUT]``: what the compiler makes of a program.

* ``python``: the generated Python module (one class per program and function block, one
  function per FUNCTION; plclab's library blocks that are written in ST appear too).
* ``st``: the checked core AST printed back as ST, so IL bodies and ladder networks show the ST
  they were lowered to (:mod:`plclab.lang.unparse`).
* ``ast``: an indented dump of the same AST (:mod:`plclab.lang.dump`).

Diagnostics go to standard error, the emitted text to standard output or to ``OUT``. The command
registers itself with :mod:`plclab.cli_registry` (standard library only), so this module imports
nothing from the command line.
"""

from __future__ import annotations

import argparse
import sys

from ..cli_registry import command
from ..errors import Diagnostic, PlcError

EMITS = ("python", "st", "ast")
LIBRARY_PREFIX = "<plclab>/"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("files", nargs="+", metavar="FILE", help="source files (.st, .il, .ld, .xml)")
    p.add_argument("--emit", choices=EMITS, default="python",
                   help="python: the generated code; st: the core AST as ST (IL and LD lowered); "
                   "ast: an indented dump of the AST")
    p.add_argument("--dialect", default=None, choices=("iec", "codesys", "s7", "matiec"),
                   help="dialect of files without a {dialect} pragma (default codesys)")
    p.add_argument("-o", "--output", metavar="OUT", default=None,
                   help="write to this file instead of standard output")


def emit(sources: list[tuple[str, str]], kind: str,
         dialect: str | None = None) -> tuple[str, list[Diagnostic]]:
    """The text ``--emit kind`` prints for (text, filename) sources, and the warnings; PlcError
    with every diagnostic when the program has errors."""
    from ..project import check_sources

    if kind not in EMITS:
        raise PlcError("PLC3002", f"--emit {kind}: choose one of {', '.join(EMITS)}")
    project, diags = check_sources(sources, dialect)
    if project is None:
        errors = [d for d in diags if d.severity == "error"]
        raise PlcError(errors[0].code, errors[0].message, errors[0].location, diagnostics=diags)
    if kind == "python":
        from .codegen import generate

        return generate(project, "<plclab>").source, diags
    files = [f for f in project.files if not f.file.startswith(LIBRARY_PREFIX)]
    if kind == "st":
        from ..lang.unparse import unparse

        return "\n".join(f"(* {f.file} *)\n{unparse(f)}" for f in files), diags
    from ..lang.dump import dump

    return "\n".join(dump(f) for f in files) + "\n", diags


@command("compile", add_args=add_arguments)
def run(ns: argparse.Namespace) -> int:
    """The ``compile`` sub-command."""
    from ..project import read_sources

    text, warnings = emit(read_sources(ns.files), ns.emit, getattr(ns, "dialect", None))
    for d in warnings:
        print(str(d), file=sys.stderr)
    if ns.output is None:
        sys.stdout.write(text)
        return 0
    try:
        with open(ns.output, "w", encoding="utf-8") as fh:
            fh.write(text)
    except OSError as e:
        raise PlcError("PLC3014", f"cannot write {ns.output}: {e.strerror or e}; check the "
                       "folder exists and is writable") from None
    return 0

