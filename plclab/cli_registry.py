"""The commands of the ``plclab`` command line: a static table, and the registry of their code.

:data:`COMMAND_TABLE` names every sub-command, its one-line help and the module that implements
it. ``plclab --help`` is built from the table alone, so listing the commands imports none of
them; :mod:`plclab.cli` imports a command's module only when that command runs or its own
``--help`` is asked for. Importing the module registers the command's function and arguments
with :func:`command` and :func:`arg` into :data:`REGISTRY`.

This module imports only the standard library, so a command module of any layer may use the
decorators without importing :mod:`plclab.cli` (see ``docs/adr/0013-layers-and-lazy-cli.md``).
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import NamedTuple

__all__ = ["COMMAND_TABLE", "REGISTRY", "CommandInfo", "Registered", "arg", "command"]


class CommandInfo(NamedTuple):
    """A row of the static table: the help line and the module that registers the command."""

    help: str
    module: str


class Registered(NamedTuple):
    """A command whose module has been imported: help, argument builder, function."""

    help: str
    add_args: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]


# In the order `plclab --help` lists them. A test imports every module and checks that each
# registers exactly its rows, so the table cannot drift from the code.
COMMAND_TABLE: dict[str, CommandInfo] = {
    "check": CommandInfo("check source files and print diagnostics (exit 1 on errors)",
                         "plclab.cli"),
    "test": CommandInfo("run the TEST blocks of the given files", "plclab.cli"),
    "run": CommandInfo("run programs for N scans and print variables", "plclab.cli"),
    "explain": CommandInfo("explain a diagnostic code with an example and its fix, e.g. plclab "
                           "explain PLC0113 (--list: every code)", "plclab.cli"),
    "compile": CommandInfo("show the generated Python, the lowered ST or the AST of a program",
                           "plclab.compile.commands"),
    "sim": CommandInfo("simulate PLC programs driving a plant; print a summary, save the trace",
                       "plclab.sim.commands"),
    "plants": CommandInfo("list the plants and their signals (plclab plants NAME for details)",
                          "plclab.sim.commands"),
    "view": CommandInfo("open a saved trace in the rerun viewer, or export it (--rrd, --png, ...)",
                        "plclab.viz.commands"),
    "figures": CommandInfo("draw the timing diagrams of TP/TON/TOF/TONR/CTU/CTD/CTUD from real "
                           "runs", "plclab.viz.commands"),
    "grade": CommandInfo("grade a folder of submissions against a lab (Gradescope JSON, feedback, "
                         "CSV)", "plclab.grade.commands"),
    "grade-bundle": CommandInfo("build a Gradescope autograder zip of a lab (setup.sh, "
                                "run_autograder, hidden scenarios: instructors only)",
                                "plclab.grade.commands"),
    "lab": CommandInfo("labs: list, show LAB, get LAB [DIR], check LAB FILE..., new ID",
                       "plclab.grade.commands"),
    "panel": CommandInfo("an operator panel in the browser: signals, buttons, alarms with "
                         "acknowledgement, recipes, users (plclab.scada)", "plclab.scada.commands"),
    "serve": CommandInfo("run programs in real time behind a Modbus TCP server",
                         "plclab.modbus.commands"),
    "opcua": CommandInfo("run programs in real time behind an OPC UA server (tags with quality, "
                         "subscriptions, alarms; read-only unless configured)",
                         "plclab.opcua.commands"),
    "plant-serve": CommandInfo("run a plant in real time as a Modbus TCP server (remote I/O)",
                               "plclab.modbus.commands"),
    "render": CommandInfo("draw a program: LD/FBD networks, SFC charts, ST/IL listings as SVG or "
                          "PNG, with values from a trace (--at TRACE --time T)",
                          "plclab.viz.diagram_commands"),
    "export": CommandInfo("write programs as PLCopen XML for OpenPLC Editor and Beremiz "
                          "(--fbd: networks where the body allows)", "plclab.viz.diagram_commands"),
    "course": CommandInfo("the course: build (run examples, draw figures) [--out DIR], list, "
                          "check", "plclab.course.commands"),
    "quiz": CommandInfo("take a chapter's quiz in the terminal (plclab quiz 10); --check "
                        "validates every key; export OUT --format gift|qti writes the pool for "
                        "Moodle or Canvas", "plclab.course.commands"),
    "lsp": CommandInfo("a language server for editors (LSP over stdio): diagnostics, hover, "
                       "completion, outline, run a TEST", "plclab.lsp.commands"),
    "site": CommandInfo("the web site: build [--out DIR] (course, labs, codes, reference, "
                        "playground) or serve it on 127.0.0.1", "plclab.site.commands"),
}

REGISTRY: dict[str, Registered] = {}


def command(name: str, help_text: str | None = None, *,
            add_args: Callable[[argparse.ArgumentParser], None] | None = None):
    """Register the decorated ``fn(namespace) -> exit code`` as ``plclab NAME``.

    The help line comes from :data:`COMMAND_TABLE`; *help_text* is only for a command that is
    not in the table yet (it is added, with the function's module). *add_args* builds the
    command's parser by hand; by default the :func:`arg` decorators below ``@command`` do.
    """

    def deco(fn: Callable[[argparse.Namespace], int]):
        def from_decorators(p: argparse.ArgumentParser) -> None:
            for names, kw in getattr(fn, "_args", []):
                p.add_argument(*names, **kw)

        if name not in COMMAND_TABLE:
            COMMAND_TABLE[name] = CommandInfo(help_text or "", fn.__module__)
        REGISTRY[name] = Registered(COMMAND_TABLE[name].help, add_args or from_decorators, fn)
        fn._help_text = help_text  # checked against the table by tests/cli/test_cli_lazy.py
        return fn

    return deco


def arg(*names: str, **kw):
    """One ``argparse`` argument of the command below; decorators read top to bottom."""

    def deco(fn):
        fn._args = [(names, kw)] + getattr(fn, "_args", [])
        return fn

    return deco
