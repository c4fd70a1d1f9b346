"""The course's glossary (``course/glossary.toml``): each term in English and in the Russian of
the source texts, a definition, the chapter that introduces it, and an index computed from the
chapters' text (term -> every chapter it appears in). ``plclab course build`` writes it as
``glossary.md``; the site makes it a page of the course. The Russian edition reuses the table.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from .model import Chapter, chapters, course_error, default_course_dir

_FENCE = re.compile(r"^```.*?^```", re.S | re.M)


@dataclass(frozen=True)
class Term:
    en: str
    ru: str
    definition: str
    chapter: int
    source: str            # "file.txt:line" in the source texts
    source_form: str       # the Russian word as that line writes it
    match: str             # regex finding the English term in a chapter's prose

    def found_in(self, text: str) -> bool:
        return re.search(self.match, prose(text)) is not None


def prose(text: str) -> str:
    """A chapter's text without its fenced code blocks (a term is taught in words)."""
    return _FENCE.sub("", text)


def glossary_path(course_dir: str | Path | None = None) -> Path:
    return Path(course_dir or default_course_dir()) / "glossary.toml"


def terms(course_dir: str | Path | None = None) -> list[Term]:
    """The glossary's terms in the order of the file; a bad row is a course error (PLC3020)."""
    path = glossary_path(course_dir)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise course_error(f"{path}: {e}") from None
    out = []
    for n, row in enumerate(data.get("term", []), 1):
        missing = {"en", "ru", "definition", "chapter", "source", "source_form"} - set(row)
        if missing:
            raise course_error(f"{path} term {n} ({row.get('en', '?')}): missing "
                               f"{', '.join(sorted(missing))}")
        match = row.get("match", r"(?i)\b" + re.escape(row["en"]) + r"s?\b")
        try:
            re.compile(match)
        except re.error as e:
            raise course_error(f"{path} term {row['en']}: match {match!r}: {e}") from None
        out.append(Term(row["en"], row["ru"], " ".join(row["definition"].split()),
                        int(row["chapter"]), row["source"], row["source_form"], match))
    return out


def index(ts: list[Term], chs: list[Chapter]) -> dict[str, list[Chapter]]:
    """English term -> the chapters whose prose uses it, in chapter order."""
    return {t.en: [c for c in chs if t.found_in(c.text)] for t in ts}


def glossary_markdown(ts: list[Term], chs: list[Chapter],
                      link: Callable[[Chapter], str] = lambda c: f"{c.slug}/chapter.md") -> str:
    """The glossary page: the terms A-Z with Russian and definition, then the index."""
    by_number = {c.number: c for c in chs}
    where = index(ts, chs)
    lines = ["# Glossary and index", "",
             "Each term with its Russian equivalent (the word the Russian source texts use), a "
             "short definition and the chapter that introduces it; the index below lists every "
             "chapter whose text uses the term.", "",
             "| term | по-русски | meaning | introduced in |", "|---|---|---|---|"]
    for t in sorted(ts, key=lambda t: t.en.lower()):
        c = by_number.get(t.chapter)
        intro = f"[{t.chapter}. {c.title}]({link(c)})" if c else str(t.chapter)
        lines.append(f"| **{t.en}** | {t.ru} | {t.definition} | {intro} |")
    lines += ["", "## Index", ""]
    for t in sorted(ts, key=lambda t: t.en.lower()):
        refs = ", ".join(f"[{c.number}]({link(c)})" for c in where[t.en]) or "-"
        lines.append(f"- **{t.en}** ({t.ru}): {refs}")
    return "\n".join(lines) + "\n"


def write_glossary(out: Path, course_dir: str | Path | None = None,
                   link: Callable[[Chapter], str] = lambda c: f"{c.slug}/chapter.md") -> Path:
    """Write ``glossary.md`` into *out* (the built course or the site's course folder)."""
    path = Path(out) / "glossary.md"
    path.write_text(glossary_markdown(terms(course_dir), chapters(course_dir), link),
                    encoding="utf-8")
    return path


def glossary_problems(course_dir: str | Path | None = None) -> list[str]:
    """What is wrong with the glossary (empty: nothing): a term twice, a chapter that does not
    exist, a term its introducing chapter never uses in its prose."""
    ts, chs = terms(course_dir), chapters(course_dir)
    by_number = {c.number: c for c in chs}
    out, seen = [], set()
    for t in ts:
        if t.en.lower() in seen:
            out.append(f"glossary: {t.en} twice")
        seen.add(t.en.lower())
        c = by_number.get(t.chapter)
        if c is None:
            out.append(f"glossary: {t.en} is introduced in chapter {t.chapter}, which does not "
                       "exist")
        elif not t.found_in(c.text):
            out.append(f"glossary: {t.en} is introduced in chapter {t.chapter} ({c.slug}), "
                       f"whose text never uses it (match {t.match!r})")
    return out
