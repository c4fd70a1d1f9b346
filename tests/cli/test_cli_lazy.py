"""The lazy command line: a static table of commands, each module imported only when it runs.

``plclab check`` must not pay for the simulator, asyncio, the plotting and physics libraries or
the grader (issue 12); ``plclab --help`` and ``plclab CMD --help`` still show every command.
"""

from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from plclab import cli
from plclab.cli_registry import COMMAND_TABLE, REGISTRY

ROOT = Path(__file__).resolve().parents[2]

# What `plclab check` may not import (issue 12), and the packages of the other commands.
HEAVY = ["asyncio", "numpy", "matplotlib", "pymunk", "rerun", "pymodbus", "plants",
         "plclab.sim", "plclab.grade", "plclab.viz", "plclab.modbus", "plclab.trace"]


def modules_after(argv: list[str], cwd: Path) -> tuple[int, str, set[str]]:
    """Run ``plclab ARGV`` in a fresh interpreter: exit code, stdout, the modules it imported."""
    code = ("import json, sys\nfrom plclab.cli import main\n"
            "try:\n    rc = main(sys.argv[1:])\nexcept SystemExit as e:\n    rc = e.code\n"
            "print('@@' + json.dumps([rc, sorted(sys.modules)]))")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True,
                         cwd=cwd, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    text, _, tail = out.stdout.rpartition("@@")
    rc, modules = json.loads(tail)
    return rc, text, set(modules)


def loaded(modules: set[str], name: str) -> bool:
    return any(m == name or m.startswith(name + ".") for m in modules)


def test_check_imports_only_what_it_needs(tmp_path: Path) -> None:
    src = tmp_path / "p.st"
    src.write_text("PROGRAM P\nVAR x : INT; END_VAR\nx := y;\nEND_PROGRAM\n", encoding="utf-8")
    rc, out, modules = modules_after(["check", str(src)], tmp_path)
    assert rc == 1 and "PLC" in out and "1 error(s)" in out   # it really checked the file
    assert "plclab.lang.check" in modules
    assert [h for h in HEAVY if loaded(modules, h)] == []


def test_the_probe_sees_a_heavy_import(tmp_path: Path) -> None:
    # The same probe on a command that needs the simulator finds it: the check above can fail.
    rc, out, modules = modules_after(["sim", "--help"], tmp_path)
    assert rc == 0 and "--duration" in out
    assert loaded(modules, "plclab.sim") and not loaded(modules, "plclab.grade")


def test_help_lists_every_command_without_importing_them(tmp_path: Path) -> None:
    rc, out, modules = modules_after(["--help"], tmp_path)
    assert rc == 0
    for name, info in COMMAND_TABLE.items():
        assert name in out and info.help.split()[0] in out
    assert not {info.module for info in COMMAND_TABLE.values()} - {"plclab.cli"} & modules


@pytest.mark.parametrize("name", list(COMMAND_TABLE))
def test_each_command_help_shows_its_arguments(name: str, capsys: pytest.CaptureFixture) -> None:
    with pytest.raises(SystemExit) as e:
        cli.main([name, "--help"])
    assert e.value.code == 0
    out = capsys.readouterr().out
    assert out.startswith(f"usage: plclab {name}")
    parser = argparse_of(name)
    for action in parser._actions:  # every declared option or positional is in the help
        shown = action.option_strings[0] if action.option_strings else action.metavar or action.dest
        assert str(shown) in out


def argparse_of(name: str):
    """The command's own parser, built the way main() builds it."""
    top = cli.build_parser([name])
    sub = next(a for a in top._actions if a.dest == "command")
    return sub.choices[name]


def test_the_table_matches_the_registrations() -> None:
    for info in COMMAND_TABLE.values():
        importlib.import_module(info.module)
    assert set(REGISTRY) == set(COMMAND_TABLE)
    for name, reg in REGISTRY.items():
        assert reg.run.__module__ == COMMAND_TABLE[name].module, name
        given = getattr(reg.run, "_help_text", None)  # a help text in @command must agree
        assert given in (None, COMMAND_TABLE[name].help), name


def test_a_missing_command_module_is_a_plc_error(monkeypatch: pytest.MonkeyPatch,
                                                 capsys: pytest.CaptureFixture) -> None:
    from plclab.cli_registry import CommandInfo

    monkeypatch.setitem(COMMAND_TABLE, "gone", CommandInfo("a removed extra", "plclab.gone_x"))
    assert cli.main(["gone"]) == 1
    err = capsys.readouterr().err
    assert "PLC3005" in err and "plclab.gone_x" in err and "Traceback" not in err
