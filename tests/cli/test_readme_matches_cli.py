"""The README's command summary and lab count match the CLI's own registry and the labs
folder, so the docs cannot drift from the code (issue 37: "Docs made true and kept true")."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

from plclab.cli import build_parser
from plclab.cli_registry import COMMAND_TABLE

REPO = Path(__file__).resolve().parents[2]
README = (REPO / "README.md").read_text(encoding="utf-8")
NUMBERS = {w: i for i, w in enumerate(
    "zero one two three four five six seven eight nine ten eleven twelve thirteen fourteen "
    "fifteen sixteen seventeen eighteen nineteen twenty".split())}


def usage_block() -> list[str]:
    section = README.split("## Using it", 1)[1]
    block = section.split("```", 2)[1]
    return [ln for ln in block.splitlines() if ln.startswith("plclab ")]


def options(parser: argparse.ArgumentParser) -> set[str]:
    """Every option string of a parser and of its sub-parsers (``lab check``'s among ``lab``)."""
    found: set[str] = set()
    for action in parser._actions:  # noqa: SLF001 - argparse has no public walk
        found.update(s for s in action.option_strings)
        if isinstance(action, argparse._SubParsersAction):  # noqa: SLF001
            for sub in action.choices.values():
                found |= options(sub)
    return found


def command_parsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser("all")
    sub = next(a for a in parser._actions  # noqa: SLF001
               if isinstance(a, argparse._SubParsersAction))  # noqa: SLF001
    return dict(sub.choices)


def test_every_command_is_in_the_readme_summary():
    named = {ln.split()[1] for ln in usage_block()}
    missing = [c for c in COMMAND_TABLE if c not in named]
    assert not missing, f"README's 'Using it' block lacks: {missing}"
    top = {o for a in build_parser("all")._actions  # noqa: SLF001 - the global options
           for o in a.option_strings}
    unknown = named - set(COMMAND_TABLE) - top  # a global option (--version, --lang) may lead
    assert not unknown, f"README names commands the CLI does not have: {unknown}"


def test_every_option_in_the_readme_summary_exists():
    parsers = command_parsers()
    wrong = []
    for line in usage_block():
        name = line.split()[1]
        if name not in parsers:
            continue
        code = line.split("#", 1)[0]  # the comment may speak of other things
        known = options(parsers[name])
        wrong += [f"{name} {o}" for o in re.findall(r"(?<![\w-])(--?[a-z][\w-]*)", code)
                  if o not in known]
    assert not wrong, f"README shows options the commands do not take: {wrong}"


def test_the_readme_counts_the_labs_right():
    labs = [p for p in (REPO / "labs").iterdir() if (p / "lab.toml").exists()]
    m = re.search(r"^(\w+) labs live in `labs/`", README, re.M)
    assert m, "the README's Labs section no longer says how many labs there are"
    assert NUMBERS[m.group(1).lower()] == len(labs)


def test_the_checks_catch_drift():
    """The helpers above find a missing command and a made-up option (test the test)."""
    parsers = command_parsers()
    assert "--out" in options(parsers["lab"])  # lab check --out, one level down
    assert "--no-such-flag" not in options(parsers["grade"])
