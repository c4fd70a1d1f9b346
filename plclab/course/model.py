"""The course on disk: chapters, their code blocks, figure specifications and quizzes.

A chapter is a folder ``course/NN-slug/`` holding ``chapter.md`` (the text), ``examples/``
(complete programs the figures and quizzes use), ``figures.toml`` (what the build draws, from
real runs) and ``quiz.toml`` (the items and their keys). The format is explained in
``course/README.md`` and ``docs/adr/0018-course-format.md``.

Fenced code blocks in ``chapter.md`` carry their language and, for a deliberate mistake, the code
it must produce::

    ```st                      a complete program: compiled, TEST blocks run, scanned
    ```st error=PLC0013        must fail with exactly PLC0013
    ```il scans=5              scanned 5 times (default 10)
    ```text                    not a program (a formula, a table, terminal output)
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

from ..errors import PlcError

PROGRAM_LANGUAGES = {"st": ".st", "il": ".il", "ld": ".ld", "xml": ".xml"}
TEXT_LANGUAGES = {"text", "console"}
_FENCE = re.compile(r"^(`{3,})(.*)$")
_ATTR = re.compile(r"(\w+)=(\S+)")
_FIGURE_REF = re.compile(r"!\[[^\]]*\]\((figures/[^)\s]+)\)")
_LAB_REF = re.compile(r"\]\(\.\./\.\./labs/([\w-]+)/?[^)]*\)")


def default_course_dir() -> Path:
    """The ``course/`` folder: the student copy in an installed wheel (``plclab/courseware``),
    else the one of this checkout (beside the ``plclab`` package); ADR 0019."""
    from ..grade.courseware import courseware_root

    return courseware_root() / "course"


def course_error(message: str) -> PlcError:
    """A malformed course file (chapter, figure specification or quiz)."""
    return PlcError("PLC3020", message)


@dataclass(frozen=True)
class CodeBlock:
    """One fenced block of ``chapter.md``."""

    chapter: str
    index: int  # 1-based among the chapter's blocks
    line: int  # line of the opening fence
    language: str
    text: str
    attrs: dict[str, str] = field(default_factory=dict)

    @property
    def expected_code(self) -> str | None:
        return self.attrs.get("error")

    @property
    def is_program(self) -> bool:
        return self.language in PROGRAM_LANGUAGES

    @property
    def filename(self) -> str:
        """The file name diagnostics show: ``<chapter>/block3.st``."""
        return f"{self.chapter}/block{self.index}{PROGRAM_LANGUAGES.get(self.language, '.txt')}"

    @property
    def where(self) -> str:
        return f"course/{self.chapter}/chapter.md:{self.line}"


def code_blocks(text: str, chapter: str = "") -> list[CodeBlock]:
    """Every fenced block of a Markdown text; an unlabelled block or an unknown language is a
    course error (every block must say what it is)."""
    blocks: list[CodeBlock] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        m = _FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, info = m.group(1), m.group(2).strip()
        start = i + 1
        j = start
        while j < len(lines) and not lines[j].startswith(fence):
            j += 1
        if j == len(lines):
            raise course_error(f"course/{chapter}/chapter.md:{i + 1}: code block never closed")
        words = info.split()
        lang = words[0].lower() if words else ""
        if lang not in PROGRAM_LANGUAGES and lang not in TEXT_LANGUAGES:
            raise course_error(
                f"course/{chapter}/chapter.md:{i + 1}: a code block needs a language: one of "
                f"{', '.join(sorted(PROGRAM_LANGUAGES) + sorted(TEXT_LANGUAGES))} "
                f"(got {info!r})")
        attrs = dict(_ATTR.findall(" ".join(words[1:])))
        blocks.append(CodeBlock(chapter, len(blocks) + 1, i + 1, lang,
                                "\n".join(lines[start:j]) + "\n", attrs))
        i = j + 1
    return blocks


def _read_toml(path: Path) -> dict[str, Any]:
    if not path.exists():
        return {}
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as e:
        raise course_error(f"{path}: {e}") from None


@dataclass
class Chapter:
    """One chapter folder."""

    folder: Path

    @property
    def slug(self) -> str:
        return self.folder.name

    @property
    def number(self) -> int:
        return int(self.slug.split("-", 1)[0])

    @cached_property
    def text(self) -> str:
        return (self.folder / "chapter.md").read_text(encoding="utf-8")

    @property
    def title(self) -> str:
        for line in self.text.splitlines():
            if line.startswith("# "):
                return line[2:].strip()
        return self.slug

    @cached_property
    def blocks(self) -> list[CodeBlock]:
        return code_blocks(self.text, self.slug)

    @property
    def figure_refs(self) -> list[str]:
        """``figures/x.svg`` paths the text shows."""
        return _FIGURE_REF.findall(self.text)

    @property
    def lab_refs(self) -> list[str]:
        """Lab ids the text links (``../../labs/ID``)."""
        return sorted(set(_LAB_REF.findall(self.text)))

    @cached_property
    def figure_specs(self) -> list[dict[str, Any]]:
        return list(_read_toml(self.folder / "figures.toml").get("figure", []))

    @cached_property
    def quiz_data(self) -> dict[str, Any]:
        return _read_toml(self.folder / "quiz.toml")

    @property
    def examples(self) -> list[Path]:
        d = self.folder / "examples"
        return sorted(p for p in d.iterdir() if p.suffix in PROGRAM_LANGUAGES.values()) \
            if d.is_dir() else []

    def words(self) -> int:
        """Words of prose (code blocks not counted)."""
        prose = re.sub(r"^```.*?^```", "", self.text, flags=re.S | re.M)
        return len(re.findall(r"[A-Za-z0-9][\w'-]*", prose))


def chapters(course_dir: str | Path | None = None) -> list[Chapter]:
    """Every chapter folder (``NN-slug`` with a chapter.md), in number order."""
    root = Path(course_dir) if course_dir is not None else default_course_dir()
    if not root.is_dir():
        raise PlcError("PLC3003", f"{root}: no course folder; give --course DIR")
    found = [Chapter(p) for p in root.iterdir()
             if p.is_dir() and re.match(r"^\d\d-", p.name) and (p / "chapter.md").exists()]
    return sorted(found, key=lambda c: c.number)


def find_chapter(name: str | int, course_dir: str | Path | None = None) -> Chapter:
    """A chapter by number (``10``), by slug (``10-timers-counters``) or by a slug's words."""
    all_ = chapters(course_dir)
    key = str(name).strip().lower()
    for c in all_:
        if key in (c.slug, str(c.number), f"{c.number:02d}") or c.slug.split("-", 1)[1] == key:
            return c
    names = ", ".join(f"{c.number} ({c.slug})" for c in all_)
    raise PlcError("PLC3021", f"no chapter {name!r}; the chapters are: {names}")
