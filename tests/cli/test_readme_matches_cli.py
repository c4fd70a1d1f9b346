"""The README's commands, options and lab count match the CLI's own registry and the labs
folder, so the docs cannot drift from the code (issue 37: "Docs made true and kept true").

Every ``plclab ...`` command line the README and the user's docs show, in code blocks and in
inline code of the prose, is resolved against the argparse parser the way argparse would read it: the command, a
sub-command (``lab check``) or a word a positional takes from a fixed set (``site build``), and
every option, which must belong to the parser it is written for (an option of ``lab check`` shown
on ``lab list`` is wrong). Every "<number> labs" of the prose equals the number of labs.
"""

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
COUNT = re.compile(r"\b(\d+|" + "|".join(NUMBERS) + r")\s+labs\b", re.I)
OPTION = re.compile(r"(?<![\w-])(--?[A-Za-z][\w-]*)")
# `plclab` as a command: not part of a path, a module (plclab.sim) or a word (plclab-core.zip)
COMMAND_START = re.compile(r"(?<![\w./-])plclab(?= )")
PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9_.]*$")  # COMMAND, LAB, FILE...
ANYWHERE = ("--lang",)  # global options plclab/cli.py takes after the command too


def usage_block(text: str = README) -> list[str]:
    section = text.split("## Using it", 1)[1]
    block = section.split("```", 2)[1]
    return [ln for ln in block.splitlines() if ln.startswith("plclab ")]


def code_pieces(text: str) -> list[str]:
    """The code of a Markdown text: each line of a fenced block, each inline code span."""
    pieces: list[str] = []
    fenced = False
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
        elif fenced:
            pieces.append(line)
        else:
            pieces += re.findall(r"`([^`]+)`", line)
    return pieces


def command_lines(text: str) -> list[str]:
    """Every ``plclab ...`` command of a Markdown text, without its comment; the alternatives of
    a usage line (``lab list | show LAB | check LAB FILE...``) each as a command of its own."""
    out = []
    for piece in code_pieces(text):
        starts = [m.start() for m in COMMAND_START.finditer(piece)] + [len(piece)]
        for a, b in zip(starts, starts[1:], strict=False):
            line = re.split(r" #|&&|;", piece[a:b], maxsplit=1)[0].strip()
            first, *alternatives = line.split(" | ")
            out.append(first)
            words = first.split()
            head = next((w for w in words[1:] if not w.startswith("-")), "")
            out += [f"plclab {head} {alt}" for alt in alternatives]
    return out


def subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for a in parser._actions:  # noqa: SLF001 - argparse has no public walk
        if isinstance(a, argparse._SubParsersAction):  # noqa: SLF001
            return dict(a.choices)
    return {}


def word_choices(parser: argparse.ArgumentParser) -> list[str] | None:
    """The fixed words of the parser's first positional (``site build|serve``), if it has any."""
    for a in parser._actions:  # noqa: SLF001
        if not a.option_strings and not isinstance(a, argparse._SubParsersAction):  # noqa: SLF001
            return list(a.choices) if a.choices else None
    return None


def takes_value(parser: argparse.ArgumentParser, option: str) -> bool:
    action = parser._option_string_actions.get(option)  # noqa: SLF001
    return action is not None and action.nargs != 0


def problems(line: str, root: argparse.ArgumentParser) -> list[str]:
    """What is wrong with one command line against the parser *root* (empty when it holds)."""
    words = [w.strip("[](),.:;") if not w.endswith("...") else w.strip("[]")
             for w in line.split()[1:]]
    words = [w for w in words if w]
    wrong: list[str] = []
    parser, path, i, named = root, ["plclab"], 0, False
    while i < len(words):
        w = words[i]
        if OPTION.fullmatch(w) or "=" in w and w.startswith("--"):
            opt = w.split("=", 1)[0]
            owner = root if opt in ANYWHERE else parser
            if opt not in owner._option_string_actions:  # noqa: SLF001
                wrong.append(f"`{line}`: {' '.join(path)} has no option {opt}")
            elif "=" not in w and takes_value(owner, opt):
                i += 1  # its value
        elif PLACEHOLDER.match(w.rstrip(".")) and not named:
            named = True  # `plclab COMMAND --help`: any command
            parser = argparse.ArgumentParser(add_help=True)
        elif not named:
            named = True
            choices = subparsers(parser)
            if not re.fullmatch(r"[a-z][a-z-]*", w):
                break  # not a command line after all (`plclab --version / ...`)
            if w not in choices:
                wrong.append(f"`{line}`: plclab has no command {w!r}")
                break
            parser, path = choices[w], path + [w]
            sub = subparsers(parser)
            if sub and i + 1 < len(words) and not words[i + 1].startswith("-"):
                nxt = words[i + 1]
                if nxt in sub:
                    parser, path, i = sub[nxt], path + [nxt], i + 1
                elif not PLACEHOLDER.match(nxt.rstrip(".")):
                    wrong.append(f"`{line}`: plclab {w} has no sub-command {nxt!r}")
                    break
            elif (fixed := word_choices(parser)) and i + 1 < len(words) \
                    and re.fullmatch(r"[a-z][a-z-]*", words[i + 1]) \
                    and words[i + 1] not in fixed:
                wrong.append(f"`{line}`: plclab {w} takes {'|'.join(fixed)}, not "
                             f"{words[i + 1]!r}")
        i += 1
    return wrong


def lab_count_problems(text: str, labs: int) -> list[str]:
    """Every "<number> labs" of the prose of *text* that is not *labs*."""
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    prose = re.sub(r"`[^`]*`", "", prose)
    return [f"the README says {m.group(0)!r}; there are {labs}"
            for m in COUNT.finditer(prose)
            if _number(m.group(1)) != labs]


def _number(word: str) -> int:
    return int(word) if word.isdigit() else NUMBERS[word.lower()]


def number_of_labs() -> int:
    return sum(1 for p in (REPO / "labs").iterdir() if (p / "lab.toml").is_file())


# ------------------------------------------------------------------------------ the tests


def test_every_command_is_in_the_readme_summary():
    named = {ln.split()[1] for ln in usage_block()}
    missing = [c for c in COMMAND_TABLE if c not in named]
    assert not missing, f"README's 'Using it' block lacks: {missing}"


def test_every_command_and_option_the_readme_shows_exists():
    root = build_parser("all")
    lines = command_lines(README)
    assert len(lines) > len(COMMAND_TABLE)  # the summary and the prose were both read
    wrong = [p for line in lines for p in problems(line, root)]
    assert not wrong, "the README shows what the CLI does not take:\n" + "\n".join(wrong)


def user_docs() -> list[Path]:
    """The Markdown pages a user reads besides the README: docs/ (not the ADRs, which record
    decisions as they were taken, old command names included), the course, the labs' and the
    plants' READMEs, CONTRIBUTING."""
    pages = [p for p in (REPO / "docs").rglob("*.md") if "adr" not in p.parts]
    pages += list((REPO / "course").rglob("*.md")) + list((REPO / "labs").glob("*/README*.md"))
    return sorted(pages) + [REPO / "plants" / "README.md", REPO / "CONTRIBUTING.md"]


def test_every_command_and_option_the_docs_show_exists():
    root = build_parser("all")
    pages = user_docs()
    assert len(pages) > 30 and all(p.is_file() for p in pages)
    wrong = [f"{page.relative_to(REPO)}: {p}" for page in pages
             for line in command_lines(page.read_text(encoding="utf-8"))
             for p in problems(line, root)]
    assert not wrong, "the docs show what the CLI does not take:\n" + "\n".join(wrong)


def test_the_readme_counts_the_labs_right():
    assert re.search(r"^(\w+) labs live in `labs/`", README, re.M), \
        "the README's Labs section no longer says how many labs there are"
    wrong = lab_count_problems(README, number_of_labs())
    assert not wrong, "\n".join(wrong)


def test_the_checks_catch_drift():
    """A planted README with a made-up command, sub-command, word and option, an option of
    another sub-command and a wrong count is caught line by line (test the test)."""
    planted = "\n".join([
        "## Using it", "", "```",
        "plclab check FILE... [--no-cache]        # fine: check takes --no-cache",
        "plclab chek FILE                         # no such command",
        "plclab lab list [--out DIR] | check LAB FILE... [--out DIR] | grok ID",
        "plclab site build [--out DIR] | deploy",
        "plclab --lang ru check --no-such-flag F",
        "plclab explain PLC0113 --lang ru; plclab explain PLC0113 --version",
        "plclab --version / plclab COMMAND --help",
        "```", "",
        "Run `plclab lab check LAB my.st --png why.png`, or `plclab compile F --emitt st`;",
        "the module `plclab.sim` and `plclab/runtime/rt.py` are no commands.",
        "Eight labs live in `labs/`; the first two labs are short; 17 labs in all.",
    ])
    root = build_parser("all")
    found = [p for line in command_lines(planted) for p in problems(line, root)]
    assert found == [
        "`plclab chek FILE`: plclab has no command 'chek'",
        "`plclab lab list [--out DIR]`: plclab lab list has no option --out",
        "`plclab lab grok ID`: plclab lab has no sub-command 'grok'",
        "`plclab site deploy`: plclab site takes build|serve, not 'deploy'",
        "`plclab --lang ru check --no-such-flag F`: plclab check has no option --no-such-flag",
        "`plclab explain PLC0113 --version`: plclab explain has no option --version",
        "`plclab compile F --emitt st`: plclab compile has no option --emitt",
    ]
    assert lab_count_problems(planted, 17) == [
        "the README says 'Eight labs'; there are 17", "the README says 'two labs'; there are 17"]
    assert usage_block(planted)[0].startswith("plclab check FILE")
