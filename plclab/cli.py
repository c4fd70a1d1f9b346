"""The ``plclab`` command line.

Sub-commands: ``check``, ``test``, ``run``, ``explain`` here, and those of the simulator, the
viewers, the grader and the Modbus server in their packages' ``commands`` modules. The list of
commands is the static :data:`~plclab.cli_registry.COMMAND_TABLE`; a command's module is
imported only when that command runs (or its ``--help`` is asked for), so ``plclab check`` does
not import the simulator, asyncio or a plotting library. User errors print as
``file:line:col: error PLCnnnn: message`` and never as a Python traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from . import __version__
from .cli_registry import COMMAND_TABLE, REGISTRY, Registered, arg, command
from .errors import PlcError, printable
from .i18n import normalize, tr, unknown_language
from .names import split_names

DIALECTS = ("iec", "codesys", "s7", "matiec")  # plclab.lang.dialect.PROFILES (not imported here)

__all__ = ["COMMANDS", "build_parser", "load_command", "main", "split_names"]

COMMANDS = REGISTRY  # the commands registered so far (name -> Registered); kept for old callers


def _print_diags(diags, out=None) -> tuple[int, int]:
    out = out or sys.stdout
    errors = warnings = 0
    for d in diags:
        print(d.render(), file=out)
        if d.severity == "error":
            errors += 1
        else:
            warnings += 1
    return errors, warnings


@command("check")
@arg("files", nargs="+", metavar="FILE", help="source files (.st, .il, .ld, .xml)")
@arg("--no-warnings", action="store_true", help="print errors only")
@arg("--dialect", default=None, choices=DIALECTS,
     help="dialect of files without a {dialect} pragma (default codesys; ADR 0017)")
@arg("--no-lint", action="store_true", help="without the beginner warnings (PLC0210-PLC0216)")
@arg("--lab", default=None, metavar="LAB", help="also compare the addresses with the I/O "
     "table of this lab")
@arg("-v", "--verbose", action="store_true", help="also say in which dialect each file is read "
     "and why (its pragma, --dialect, the tool that wrote it, or the default)")
@arg("--explain-dialect", action="store_true", help="list the dialect rules that fired: "
     "each leniency with its warning code and location, and what a strict iec compiler says "
     "there (what is not portable)")
@arg("--no-cache", action="store_true", help="check again even when these files were checked "
     "before (the compile cache, ADR 0057; PLCLAB_NO_CACHE=1 turns it off everywhere)")
def cmd_check(ns: argparse.Namespace) -> int:
    from .lang.sources import read_sources

    if not (ns.explain_dialect or ns.lab or ns.verbose):
        # the plain check: its diagnostics come from the compile cache when these texts were
        # checked before; the front end is imported only on a miss
        diags = cached_check(read_sources(ns.files), ns.dialect, lint=not ns.no_lint,
                             use_cache=not ns.no_cache)
        return _report_check(ns, diags)
    from .project import check_sources

    if ns.explain_dialect:
        from .lang.explain_dialect import report

        text, _ = report(read_sources(ns.files), ns.dialect, check_sources)
        print(text)
    io_table = None
    if ns.lab:
        from .grade.lab import load_lab

        io_table = load_lab(ns.lab).io
    sources = read_sources(ns.files)
    if ns.verbose:
        from .lang.dialect import explain_choice

        for text, filename in sources:
            try:
                name, why = explain_choice(text, ns.dialect, filename)
            except PlcError as e:
                name, why = "?", e.message
            print(tr("{file}: dialect {name} ({why})", file=printable(filename), name=name,
                     why=why))
    _, diags = check_sources(sources, ns.dialect, lint=not ns.no_lint, io_table=io_table)
    return _report_check(ns, diags)


def _report_check(ns: argparse.Namespace, diags) -> int:
    if ns.no_warnings:
        diags = [d for d in diags if d.severity == "error"]
    errors, warnings = _print_diags(diags)
    print(tr("{errors} error(s), {warnings} warning(s)", errors=errors, warnings=warnings))
    return 1 if errors else 0


def cached_check(sources: list[tuple[str, str]], dialect: str | None = None, *,
                 lint: bool = True, use_cache: bool = True) -> list:
    """The diagnostics of :func:`plclab.project.check_sources` for (text, filename) sources,
    from the disk cache when the same texts were checked before with the same plclab, dialect
    and options (ADR 0057); a miss checks and stores them. ``use_cache=False``: check only."""
    from .compile import cache
    from .errors import Diagnostic, Location

    k = None
    if use_cache and not cache.disabled():
        k = cache.key("check", sources, dialect, {"lint": lint})
        stored = cache.load_entry(k)
        if isinstance(stored, list) and all(_stored_diagnostic(x) for x in stored):
            return [Diagnostic(code, message, None if file is None else
                               Location(file, line, col), severity)
                    for code, message, severity, file, line, col in stored]
    from .project import check_sources

    _, diags = check_sources(sources, dialect, lint=lint)
    if k is not None:
        cache.store_entry(k, [[d.code, d.message, d.severity] + (
            [d.location.file, d.location.line, d.location.col] if d.location is not None
            else [None, 0, 0]) for d in diags])
    return diags


def _stored_diagnostic(x: object) -> bool:
    """``x`` is a diagnostic as :func:`cached_check` stores it (anything else: check again)."""
    return (isinstance(x, list) and len(x) == 6 and isinstance(x[0], str)
            and isinstance(x[1], str) and x[2] in ("error", "warning")
            and (x[3] is None or isinstance(x[3], str))
            and all(type(v) is int for v in x[4:]))


@command("test")
@arg("files", nargs="+", metavar="FILE")
@arg("-k", dest="keyword", default=None, help="only tests whose name contains this text")
@arg("-v", "--verbose", action="store_true", help="print passing tests too")
@arg("--dialect", default=None, choices=DIALECTS,
     help="dialect of files without a {dialect} pragma (default codesys; ADR 0017)")
def cmd_test(ns: argparse.Namespace) -> int:
    from .project import compile_sources, read_sources
    from .testing import run_compiled_tests

    compiled = compile_sources(read_sources(ns.files), dialect=ns.dialect)
    for d in getattr(compiled, "diagnostics", []):
        print(d.render())
    if ns.keyword:
        compiled.tests = [t for t in compiled.tests if ns.keyword.lower() in t[0].lower()]
    results = run_compiled_tests(compiled)
    passed = sum(r.passed for r in results)
    failed = len(results) - passed
    for r in results:
        if not r.passed or ns.verbose:
            print(r.render())
    if not results:
        print(tr("no TEST blocks found"))
    print(tr("{passed} passed, {failed} failed", passed=passed, failed=failed))
    return 0 if failed == 0 and results else 1


@command("run")
@arg("files", nargs="+", metavar="FILE")
@arg("--cycles", type=int, required=True, help="number of scans to run")
@arg("--cycle-time", default="10ms", help="task period, e.g. 10ms (default)")
@arg("--set", action="append", default=[], metavar="NAME=VALUE",
     help="set a variable before the first scan (IEC literal, e.g. T#5s, TRUE, 16#FF)")
@arg("--print", dest="print_", default=None, metavar="NAME,...",
     help="variables to print after the run (default: every program variable)")
@arg("--watch", default=None, metavar="FILE",
     help="a watch table (TOML: rows, formats, trigger, modify/force): print its samples")
@arg("--dialect", default=None, choices=DIALECTS,
     help="dialect of files without a {dialect} pragma (default codesys; ADR 0017)")
@arg("--image-size", type=int, default=None, metavar="BYTES",
     help="bytes of each process image area, 8 to 65536 (default: sized from the program's "
     "addresses, at least 1024)")
def cmd_run(ns: argparse.Namespace) -> int:
    from .project import load

    plc = load(*ns.files, dialect=ns.dialect, cycle_time=ns.cycle_time,
               image_size=ns.image_size)
    for item in ns.set:
        if "=" not in item:
            raise PlcError("PLC3002", f"--set {item}: write NAME=VALUE, e.g. --set Start=TRUE")
        name, _, value = item.partition("=")
        plc[name.strip()] = value.strip()
    if ns.cycles < 0:
        raise PlcError("PLC3002", "--cycles must be 0 or more")
    table = None
    if ns.watch:
        from .process.watch import WatchTable

        table = WatchTable.load(ns.watch)
        table.attach(plc)
    plc.scan(ns.cycles)
    if table is not None:
        print(table.report())
        if not ns.print_:
            return 0
    names = split_names(ns.print_) if ns.print_ else plc.variables()
    for n in names:
        n = n.strip()
        if n:
            print(f"{printable(n)} = {printable(plc.format(n))}")
    return 0


@command("explain")
@arg("code", nargs="?", help="a code such as PLC0100")
@arg("--list", dest="list_all", action="store_true", help="list every code with its title")
def cmd_explain(ns: argparse.Namespace) -> int:
    from .problems import explain_command

    status = explain_command(ns.code, ns.list_all)
    if ns.code and not ns.list_all:
        from .course.links import chapters_teaching

        for line in chapters_teaching(ns.code.strip().upper()):
            print(line)
    return status


def load_command(name: str) -> Registered:
    """Import the module of command *name* (from the static table) and return its registration."""
    module = COMMAND_TABLE[name].module
    if name not in REGISTRY:
        try:
            importlib.import_module(module)
        except ModuleNotFoundError as e:
            if not e.name or not (module == e.name or module.startswith(e.name + ".")):
                raise
            raise PlcError("PLC3005", f"plclab {name}: this installation has no {module}; "
                           "reinstall plclab (pip install -e .)") from None
    return REGISTRY[name]


def chosen_command(argv: list[str]) -> str | None:
    """The sub-command named in *argv*: the first word that is not an option (the top-level
    options, ``-h`` and ``--version``, take no value)."""
    for a in argv:
        if not a.startswith("-"):
            return a
    return None


def build_parser(load: str | list[str] | tuple[str, ...] = (),
                 only: bool = False) -> argparse.ArgumentParser:
    """The argument parser: every command of the table with its help line; the arguments only
    of the commands named in *load* (``"all"`` for every command, which imports them all).
    ``only=True``: the commands of *load* alone (``main`` when the first argument is a known
    command: the other sub-parsers would cost start-up time and never be used)."""
    p = argparse.ArgumentParser(prog="plclab", description="plclab: a virtual PLC lab for "
                                "IEC 61131-3 (ST, IL, LD) with physics plants and an autograder.")
    p.add_argument("--version", action="version", version=f"plclab {__version__}")
    p.add_argument("--lang", metavar="LANG", help="the language of messages: en or ru (default: "
                   "PLCLAB_LANG, else the locale, else en); also after the command")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    for name, info in COMMAND_TABLE.items():
        if only and name not in load:
            continue
        sp = sub.add_parser(name, help=info.help, description=info.help)
        if load == "all" or name in load:
            load_command(name).add_args(sp)
    return p


def _tolerant_streams() -> None:
    """A terminal that cannot show a character (an ASCII or cp1252 console, PYTHONIOENCODING)
    gets it as a backslash escape, never a UnicodeEncodeError (ADR 0041)."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None and getattr(stream, "errors", "") == "strict":
            try:
                reconfigure(errors="backslashreplace")
            except (ValueError, OSError):  # pragma: no cover - a closed or odd stream
                pass


def take_lang(argv: list[str]) -> tuple[str | None, list[str]]:
    """``--lang X`` / ``--lang=X`` anywhere before a ``--`` (a global option: ``plclab --lang ru
    check f.st`` and ``plclab explain PLC0113 --lang ru`` alike): its value and the rest."""
    lang, rest, i = None, [], 0
    while i < len(argv):
        a = argv[i]
        if a == "--":
            rest += argv[i:]
            break
        if a == "--lang":
            if i + 1 >= len(argv):
                raise PlcError("PLC9300", "--lang needs a language: --lang en or --lang ru")
            lang, i = argv[i + 1], i + 2
            continue
        if a.startswith("--lang="):
            lang = a.partition("=")[2]
        else:
            rest.append(a)
        i += 1
    if lang is not None and normalize(lang) is None:
        raise PlcError("PLC9300", unknown_language(lang))
    return lang, rest


def localize_parser(p: argparse.ArgumentParser) -> None:
    """The help texts of ``p`` and of its sub-commands in the language chosen."""
    from .i18n import SOURCE, language, tr

    if language() == SOURCE:
        return
    import argparse as ap

    if p.description:
        p.description = tr(p.description)
    for action in p._actions:
        if action.help and action.help != ap.SUPPRESS:
            action.help = tr(action.help)
        if isinstance(action, ap._SubParsersAction):
            for choice in action._choices_actions:
                if choice.help:
                    choice.help = tr(choice.help)
            for sp in dict.fromkeys(action.choices.values()):
                localize_parser(sp)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    _tolerant_streams()
    from . import i18n

    before, gettext = i18n.chosen(), argparse._
    try:
        return _main(argv)
    finally:  # main() called again in one process (tests, a notebook) starts afresh
        i18n.set_language(before)
        argparse._ = gettext


def _main(argv: list[str]) -> int:
    try:
        lang, argv = take_lang(argv)
        if lang is not None:
            from .i18n import set_language

            set_language(lang)
        name = chosen_command(argv)
        known = name in COMMAND_TABLE
        # `plclab check f.st`: only the parser of `check`; `plclab -h check` lists them all
        from .i18n import SOURCE, language

        if language() != SOURCE:  # argparse's own words: "usage: ", "options", "-h" ...
            argparse._ = tr  # looked up when a parser is made and when help is printed
        parser = build_parser([name] if known else [], only=known and argv[0] == name)
        localize_parser(parser)
        ns = parser.parse_args(argv)
        if not ns.command:
            parser.print_help()
            return 2
        return REGISTRY[ns.command].run(ns)
    except PlcError as e:
        print(e.render(), file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # `plclab plants | head`
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
