"""Loading: source files -> front ends -> checker -> compiler -> :class:`Plc`.

>>> import plclab
>>> plc = plclab.loads("PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM")
>>> plc.scan(3); plc["n"]
3
"""

from __future__ import annotations

import os
import re
from typing import Any

from .compile.cache import MemoryCache
from .errors import Diagnostic, PlcError
from .lang import ast as A
from .lang.dialect import DEFAULT, choose, using
from .lang.frontends import for_file
from .lang.frontends.st import parse_library
from .lang.lexer import cap_per_file
from .lang.library import ANNEX_F, ANNEX_F_BLOCKS, ANNEX_F_SHARED, SFC_LIBRARY, STDLIB_FILES
from .lang.lower import lower_pending
from .lang.sources import decode_source, read_sources  # noqa: F401 (their old home)
from .lang.walk import walk


def parse_sources(sources: list[tuple[str, str]], dialect: str | None = None,
                  ) -> tuple[list[A.SourceFile], list[Diagnostic]]:
    """Parse (text, filename) pairs plus the standard library; collect every diagnostic.

    Each file is read in its dialect: its ``{dialect 'NAME'}`` pragma, else ``dialect``, else
    the default (:mod:`plclab.lang.dialect`, ADR 0017).

    The order is the pipeline's: parse every file (each by the front end the registry picks for
    its suffix) -> every declaration known -> lower the pending IL bodies and LD/FBD networks
    of all files at once (:mod:`plclab.lang.lower`); the checker comes next. A project with an
    SFC chart also gets the SFC library (``SFC_STEP``, ``ACTION_CONTROL``)."""
    front_ends = [for_file(filename) for _, filename in sources]  # PLC3003 before any parsing
    files: list[A.SourceFile] = parse_library()
    diags: list[Diagnostic] = []
    for (text, filename), fe in zip(sources, front_ends, strict=True):
        try:
            name = choose(text, dialect, filename)
        except PlcError as exc:  # an unknown {dialect} pragma: report it, read the file anyway
            if exc.location is None:
                raise
            diags.append(exc.diagnostics[0])
            name = choose("", dialect, filename)
        with using(name):
            f, d = fe.parse(text, filename)
        f.dialect = None if name == DEFAULT else name  # None: the default (dumps unchanged)
        files.append(f)
        diags.extend(d)
    if any(b.kind == "SFC" for f in files for p in f.pous for b in p.pending):
        files[len(STDLIB_FILES):len(STDLIB_FILES)] = parse_library((SFC_LIBRARY,))
    own = files[-len(sources):] if sources else []
    add_annex_f(files, own, [text for text, _ in sources])
    keep_rtc(files, own)
    diags.extend(lower_pending(files))
    return files, diags


def add_annex_f(files: list[A.SourceFile], own: list[A.SourceFile],
                texts: list[str] | None = None) -> None:
    """Add the Annex F blocks (ADR 0029) when the project's own files declare one of them or
    one is in the ``matiec`` dialect; there PID and RAMP are the Annex's, else plclab's.
    ``texts``: the files' source texts; a type name is a word of them, so when none of them
    holds one of the names, the trees are not walked (a walk of a 50,000-line program: 0.1 s)."""
    matiec = any(f.dialect == "matiec" for f in own)
    wanted = ANNEX_F_BLOCKS if matiec else ANNEX_F_BLOCKS - ANNEX_F_SHARED
    if not matiec and texts is not None and not any(_ANNEX_F_WORD.search(t) for t in texts):
        return
    used = {n.name for f in own for n in walk(f) if isinstance(n, A.NamedTypeRef)}
    if not matiec and not used & wanted:
        return
    annex = parse_library((ANNEX_F,))[0]
    annex.pous = [p for p in annex.pous if p.name in wanted]
    for f in files[:len(STDLIB_FILES)]:  # the Annex's PID and RAMP replace plclab's
        f.pous = [p for p in f.pous if p.name not in wanted]
    files.insert(len(STDLIB_FILES), annex)


_ANNEX_F_WORD = re.compile(r"\b(?:" + "|".join(sorted(ANNEX_F_BLOCKS - ANNEX_F_SHARED)) + r")\b",
                           re.IGNORECASE)


RTC_DIALECTS = frozenset({"iec", "matiec"})
"""The dialects with the real-time clock block RTC (IEC 61131-3 ed.1 Table 35, MATIEC's
``lib/rtc.txt``); ed.2 dropped it and CODESYS and TIA Portal have none of that name (ADR 0037)."""


def keep_rtc(files: list[A.SourceFile], own: list[A.SourceFile]) -> None:
    """Keep the library's RTC only in a project with a file in an :data:`RTC_DIALECTS` dialect
    that names RTC and has no POU of that name: a user's own RTC wins, without a warning, and a
    CODESYS or S7 program meets RTC as an unknown type, as it would in its editor."""
    keep = (any(f.dialect in RTC_DIALECTS for f in own)
            and not any(p.name == "RTC" for f in own for p in f.pous)
            and any(isinstance(n, A.NamedTypeRef) and n.name == "RTC"
                    for f in own for n in walk(f)))
    if not keep:
        for f in files[:len(STDLIB_FILES)]:
            f.pous = [p for p in f.pous if p.name != "RTC"]


def check_sources(sources: list[tuple[str, str]], dialect: str | None = None, *,
                  lint: bool = False, io_table: Any = None):
    """Parse and check; return (project or None, diagnostics). Never raises for user errors.

    ``dialect``: of the files without a ``{dialect}`` pragma (ADR 0017). ``lint=True`` adds the
    beginner warnings (:mod:`plclab.lang.check.lint`, PLC0210..), with a lab's ``io_table``
    (rows with ``name`` and ``address``) also the addresses that contradict it."""
    files, diags = parse_sources(sources, dialect)
    return check_parsed(files, diags, sources, dialect, lint=lint, io_table=io_table)


def check_parsed(files: list[A.SourceFile], diags: list[Diagnostic],
                 sources: list[tuple[str, str]], dialect: str | None = None, *,
                 lint: bool = False, io_table: Any = None):
    """The checker's half of :func:`check_sources`, on the result of :func:`parse_sources`
    (the language server keeps the parsed files for its index)."""
    from .lang.check import Checker

    ck = Checker(files)
    project = ck.run()
    all_diags = diags + ck.diags
    if any(d.severity == "error" for d in diags):
        # a statement with a syntax error was dropped: skip the checker's follow-ups on its
        # line, and every warning (an unused variable may be used in the dropped statement)
        bad = {(d.location.file, d.location.line) for d in diags if d.location is not None}
        all_diags = diags + [d for d in ck.diags if d.severity == "error" and (
            d.location is None or (d.location.file, d.location.line) not in bad)]
    elif lint and not any(d.severity == "error" for d in ck.diags):
        from .lang.check.lint import lint as beginner_lint

        all_diags += beginner_lint(files, io_table)
    from .lang.beremiz_extensions import explain

    all_diags = explain(all_diags, sources, dialect)
    # errors before warnings, each in source order (the checks of a whole program, like the
    # data size, run last; a student must see them before the warnings)
    all_diags.sort(key=lambda d: (d.severity != "error",) + (
        (d.location.file, d.location.line, d.location.col) if d.location else ("", 0, 0)))
    has_err = any(d.severity == "error" for d in all_diags)
    return (None if has_err else project), cap_per_file(all_diags)


def compile_sources(sources: list[tuple[str, str]], filename: str = "<plclab>",
                    dialect: str | None = None, *, cache: bool = True):
    """Parse, check and compile; raise one PlcError carrying every diagnostic on error.
    ``dialect``: the dialect of files without a ``{dialect}`` pragma (ADR 0017).

    The same texts compiled again in this process come from the memory cache (ADR 0057): a
    copy of the first result whose lists a caller may change (``tests``), sharing the code
    objects and the checked project, which a :class:`Plc` only reads. ``cache=False`` (or
    ``PLCLAB_NO_CACHE=1``) compiles afresh."""
    from .compile import cache as compile_cache

    k = None
    if cache and not compile_cache.disabled() and sum(len(t) for t, _ in sources) <= \
            MEMORY_CACHE_CHARS:
        k = compile_cache.key("compiled", sources, dialect, {"filename": filename})
        hit = COMPILED.get(k)
        if hit is not None:
            return _fresh_copy(hit)
    from .compile.codegen import generate

    project, diags = check_sources(sources, dialect)
    if project is None:
        errors = [d for d in diags if d.severity == "error"]
        raise PlcError(errors[0].code, errors[0].message, errors[0].location, diagnostics=diags)
    compiled = generate(project, filename)
    compiled.diagnostics = diags  # type: ignore[attr-defined]
    if k is not None:
        COMPILED.put(k, compiled)
        return _fresh_copy(compiled)
    return compiled


MEMORY_CACHE_CHARS = 4_000_000
"""Sources longer than this (about 130,000 lines) are not kept in the memory cache."""


COMPILED = MemoryCache(size=16)
"""The memory cache of :func:`compile_sources` (key: :func:`plclab.compile.cache.key`)."""


def _fresh_copy(c):
    """A copy of a cached Compiled whose mutable lists and dicts are its own."""
    import copy

    out = copy.copy(c)
    out.tests = list(c.tests)
    out.located = list(c.located)
    out.natives = dict(c.natives)
    out.assert_texts = dict(c.assert_texts)
    out.diagnostics = list(getattr(c, "diagnostics", []))  # type: ignore[attr-defined]
    return out


def load(*paths: str | os.PathLike, dialect: str | None = None, **options: Any):
    """Load PLC source files into a ready-to-scan :class:`~plclab.runtime.plc.Plc`.

    ``dialect`` (``"codesys"`` by default; ``"iec"``, ``"s7"``, ``"matiec"``) is the dialect
    of files without a ``{dialect}`` pragma (ADR 0017); the other ``options`` go to
    :class:`Plc` (``cycle_time="10ms"``, ``watchdog=...``).
    """
    from .runtime.plc import Plc

    compiled = compile_sources(read_sources(list(paths)), dialect=dialect)
    return Plc(compiled, **options)


def loads(text: str, filename: str = "<string>.st", dialect: str | None = None,
          **options: Any):
    """Like :func:`load`, from a string."""
    from .runtime.plc import Plc

    return Plc(compile_sources([(text, filename)], dialect=dialect), **options)
