"""The ``plclab`` command line.

Sub-commands: ``check``, ``test``, ``run`` (and more as the lab grows). User errors print as
``file:line:col: error PLCnnnn: message`` and never as a Python traceback.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable

from . import __version__
from .errors import PlcError

COMMANDS: dict[str, tuple[str, Callable[[argparse.ArgumentParser], None], Callable]] = {}


def command(name: str, help_text: str):
    def deco(fn):
        def add_args(p):
            for a in getattr(fn, "_args", []):
                p.add_argument(*a[0], **a[1])

        COMMANDS[name] = (help_text, add_args, fn)
        return fn

    return deco


def arg(*names, **kw):
    def deco(fn):
        fn._args = [(names, kw)] + getattr(fn, "_args", [])
        return fn

    return deco


def _print_diags(diags, out=None) -> tuple[int, int]:
    out = out or sys.stdout
    errors = warnings = 0
    for d in diags:
        print(str(d), file=out)
        if d.severity == "error":
            errors += 1
        else:
            warnings += 1
    return errors, warnings


@command("check", "check source files and print diagnostics (exit 1 on errors)")
@arg("files", nargs="+", metavar="FILE", help="source files (.st, .il, .ld, .xml)")
@arg("--no-warnings", action="store_true", help="print errors only")
def cmd_check(ns: argparse.Namespace) -> int:
    from .project import check_sources, read_sources

    _, diags = check_sources(read_sources(ns.files))
    if ns.no_warnings:
        diags = [d for d in diags if d.severity == "error"]
    errors, warnings = _print_diags(diags)
    print(f"{errors} error(s), {warnings} warning(s)")
    return 1 if errors else 0


@command("test", "run the TEST blocks of the given files")
@arg("files", nargs="+", metavar="FILE")
@arg("-k", dest="keyword", default=None, help="only tests whose name contains this text")
@arg("-v", "--verbose", action="store_true", help="print passing tests too")
def cmd_test(ns: argparse.Namespace) -> int:
    from .project import compile_sources, read_sources
    from .testing import run_compiled_tests

    compiled = compile_sources(read_sources(ns.files))
    for d in getattr(compiled, "diagnostics", []):
        print(str(d))
    if ns.keyword:
        compiled.tests = [t for t in compiled.tests if ns.keyword.lower() in t[0].lower()]
    results = run_compiled_tests(compiled)
    passed = sum(r.passed for r in results)
    failed = len(results) - passed
    for r in results:
        if not r.passed or ns.verbose:
            print(str(r))
    if not results:
        print("no TEST blocks found")
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 and results else 1


@command("run", "run programs for N scans and print variables")
@arg("files", nargs="+", metavar="FILE")
@arg("--cycles", type=int, required=True, help="number of scans to run")
@arg("--cycle-time", default="10ms", help="task period, e.g. 10ms (default)")
@arg("--set", action="append", default=[], metavar="NAME=VALUE",
     help="set a variable before the first scan (IEC literal, e.g. T#5s, TRUE, 16#FF)")
@arg("--print", dest="print_", default=None, metavar="NAME,...",
     help="variables to print after the run (default: every program variable)")
def cmd_run(ns: argparse.Namespace) -> int:
    from .project import load

    plc = load(*ns.files, cycle_time=ns.cycle_time)
    for item in ns.set:
        if "=" not in item:
            raise PlcError("PLC3002", f"--set {item}: write NAME=VALUE, e.g. --set Start=TRUE")
        name, _, value = item.partition("=")
        plc[name.strip()] = value.strip()
    if ns.cycles < 0:
        raise PlcError("PLC3002", "--cycles must be 0 or more")
    plc.scan(ns.cycles)
    names = split_names(ns.print_) if ns.print_ else plc.variables()
    for n in names:
        n = n.strip()
        if n:
            print(f"{n} = {plc.format(n)}")
    return 0


def split_names(text: str) -> list[str]:
    """Split ``A,B[1,2],C`` at the commas that are not inside brackets."""
    out, depth, cur = [], 0, ""
    for ch in text:
        depth += ch == "["
        depth -= ch == "]"
        if ch == "," and depth == 0:
            out.append(cur)
            cur = ""
        else:
            cur += ch
    out.append(cur)
    return [n.strip() for n in out if n.strip()]


# Modules that register more sub-commands with @command when imported. Each is optional: a
# module whose extra dependencies are missing still registers its commands, and reports the
# missing dependency only when the command runs.
COMMAND_MODULES = ["plclab.sim.commands", "plclab.viz.commands", "plclab.grade.commands",
                   "plclab.modbus.commands"]


def _load_command_modules() -> None:
    import importlib
    import importlib.util

    for mod in COMMAND_MODULES:
        if importlib.util.find_spec(mod.rsplit(".", 1)[0]) is None:
            continue
        try:
            importlib.import_module(mod)
        except ModuleNotFoundError as e:
            if e.name != mod:
                raise
    from .compile.commands import COMMAND as compile_command  # stdlib only; no cli import

    name, help_text, add_args, run = compile_command
    COMMANDS[name] = (help_text, add_args, run)


@command("explain", "explain a diagnostic code with an example and its fix, e.g. plclab "
         "explain PLC0113 (--list: every code)")
@arg("code", nargs="?", help="a code such as PLC0100")
@arg("--list", dest="list_all", action="store_true", help="list every code with its title")
def cmd_explain(ns: argparse.Namespace) -> int:
    from .problems import explain_command

    return explain_command(ns.code, ns.list_all)


def build_parser() -> argparse.ArgumentParser:
    _load_command_modules()
    p = argparse.ArgumentParser(prog="plclab", description="plclab: a virtual PLC lab for "
                                "IEC 61131-3 (ST, IL, LD) with physics plants and an autograder.")
    p.add_argument("--version", action="version", version=f"plclab {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    for name, (help_text, add_args, _) in COMMANDS.items():
        sp = sub.add_parser(name, help=help_text, description=help_text)
        add_args(sp)
    return p


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    ns = parser.parse_args(argv)
    if not ns.command:
        parser.print_help()
        return 2
    _, _, fn = COMMANDS[ns.command]
    try:
        return fn(ns)
    except PlcError as e:
        print(str(e), file=sys.stderr)
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
