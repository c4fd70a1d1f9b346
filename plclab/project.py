"""Loading: source files -> front ends -> checker -> compiler -> :class:`Plc`.

>>> import plclab
>>> plc = plclab.loads("PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM")
>>> plc.scan(3); plc["n"]
3
"""

from __future__ import annotations

import os
from functools import cache
from pathlib import Path
from typing import Any

from .errors import Diagnostic, PlcError
from .lang import ast as A
from .lang.lexer import cap_per_file

STDLIB_FILES = ("stdlib.st", "ctrllib.st")


@cache
def _stdlib_text(name: str) -> str:
    return (Path(__file__).parent / "runtime" / name).read_text(encoding="utf-8")


def _frontend(path: str):
    """The parser for a file, by extension: ``f(text, filename, defer=False) -> (file, diags)``.
    ``.st`` files may hold IL POUs too (recognised by their first line)."""
    ext = os.path.splitext(path)[1].lower()
    if ext in (".st", ".iecst", ".txt", ""):
        from .lang.st_parser import parse_st_collect

        return parse_st_collect
    if ext == ".il":
        from .lang.il_parser import parse_il_collect

        return parse_il_collect
    if ext == ".ld":
        from .lang.ld_parser import parse_ld_collect

        return parse_ld_collect
    if ext == ".xml":
        from .lang.plcopen import parse_plcopen_collect

        return parse_plcopen_collect
    raise PlcError("PLC3003", f"{path}: unknown source type '{ext}'; plclab reads .st, .il, .ld "
                   "and PLCopen .xml files")


def parse_sources(sources: list[tuple[str, str]]) -> tuple[list[A.SourceFile], list[Diagnostic]]:
    """Parse (text, filename) pairs plus the standard library; collect every diagnostic."""
    files: list[A.SourceFile] = []
    diags: list[Diagnostic] = []
    for name in STDLIB_FILES:
        from .lang.st_parser import parse_st_collect

        f, d = parse_st_collect(_stdlib_text(name), f"<plclab>/{name}", library=True)
        assert not d, d
        files.append(f)
    for text, filename in sources:
        f, d = _frontend(filename)(text, filename, defer=True)
        files.append(f)
        diags.extend(d)
    if any(hasattr(p, "_lower") for f in files for p in f.pous):
        # IL bodies and ladder networks are translated once every declaration is known
        from .lang.il_parser import lower_pending

        diags.extend(lower_pending(files))
    return files, diags


def check_sources(sources: list[tuple[str, str]]):
    """Parse and check; return (project or None, diagnostics). Never raises for user errors."""
    from .lang.check import Checker

    files, diags = parse_sources(sources)
    ck = Checker(files)
    project = ck.run()
    all_diags = diags + ck.diags
    if any(d.severity == "error" for d in diags):
        # a statement with a syntax error was dropped: skip the checker's follow-ups on its line
        bad = {(d.location.file, d.location.line) for d in diags if d.location is not None}
        all_diags = diags + [d for d in ck.diags if d.location is None or
                             (d.location.file, d.location.line) not in bad]
    # errors before warnings, each in source order (the checks of a whole program, like the
    # data size, run last; a student must see them before the warnings)
    all_diags.sort(key=lambda d: (d.severity != "error",) + (
        (d.location.file, d.location.line, d.location.col) if d.location else ("", 0, 0)))
    has_err = any(d.severity == "error" for d in all_diags)
    return (None if has_err else project), cap_per_file(all_diags)


def compile_sources(sources: list[tuple[str, str]], filename: str = "<plclab>"):
    """Parse, check and compile; raise one PlcError carrying every diagnostic on error."""
    from .compile.codegen import generate

    project, diags = check_sources(sources)
    if project is None:
        errors = [d for d in diags if d.severity == "error"]
        raise PlcError(errors[0].code, errors[0].message, errors[0].location, diagnostics=diags)
    compiled = generate(project, filename)
    compiled.diagnostics = diags  # type: ignore[attr-defined]
    return compiled


def read_sources(paths: list[str | os.PathLike]) -> list[tuple[str, str]]:
    out = []
    for p in paths:
        p = str(p)
        try:
            with open(p, encoding="utf-8-sig") as fh:
                out.append((fh.read(), p))
        except FileNotFoundError:
            raise PlcError("PLC3003", f"{p}: no such file; check the path") from None
        except IsADirectoryError:
            raise PlcError("PLC3003", f"{p} is a folder; give the source files in it") from None
        except UnicodeDecodeError:
            raise PlcError("PLC3003", f"{p} is not UTF-8 text; save it as UTF-8") from None
    return out


def load(*paths: str | os.PathLike, **options: Any):
    """Load PLC source files into a ready-to-scan :class:`~plclab.runtime.plc.Plc`.

    ``options`` go to :class:`Plc` (``cycle_time="10ms"``, ``watchdog=...``).
    """
    from .runtime.plc import Plc

    compiled = compile_sources(read_sources(list(paths)))
    return Plc(compiled, **options)


def loads(text: str, filename: str = "<string>.st", **options: Any):
    """Like :func:`load`, from a string."""
    from .runtime.plc import Plc

    return Plc(compile_sources([(text, filename)]), **options)
