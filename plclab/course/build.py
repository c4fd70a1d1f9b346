"""``plclab course build``: run every example, check every quiz key, regenerate every figure from
real runs, and write the readable course (chapters, examples, figures, an index) to a folder."""

from __future__ import annotations

import shutil
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import PlcError
from .blocks import check_chapter_code
from .figures import draw
from .glossary import glossary_path, write_glossary
from .model import Chapter, chapters
from .quiz import check_quiz


@dataclass
class ChapterReport:
    chapter: Chapter
    words: int = 0
    blocks: int = 0
    quiz_items: int = 0
    figures: list[tuple[Path, str]] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)


def build_chapter(chapter: Chapter, out_root: Path, figures: bool = True) -> ChapterReport:
    """Check and copy one chapter into ``out_root/<slug>/``, drawing its figures."""
    rep = ChapterReport(chapter, words=chapter.words())
    dest = out_root / chapter.slug
    dest.mkdir(parents=True, exist_ok=True)
    outcomes = check_chapter_code(chapter)
    rep.blocks = sum(1 for b in chapter.blocks if b.is_program)
    rep.problems += [str(o) for o in outcomes if not o.ok]
    n, problems = check_quiz(chapter)
    rep.quiz_items, rep.problems = n, rep.problems + problems
    drawn = set()
    if figures:
        for spec in chapter.figure_specs:
            try:
                path, note = draw(chapter, spec, dest / "figures")
            except PlcError as e:
                rep.problems.append(f"course/{chapter.slug}/figures.toml "
                                    f"{spec.get('file', '?')}: {e}")
                continue
            rep.figures.append((path, note))
            drawn.add(f"figures/{path.name}")
        missing = [r for r in chapter.figure_refs if r not in drawn]
        rep.problems += [f"course/{chapter.slug}/chapter.md shows {r}, which figures.toml does "
                         "not draw" for r in missing]
    (dest / "chapter.md").write_text(chapter.text, encoding="utf-8")
    for name in ("quiz.toml", "figures.toml"):
        if (chapter.folder / name).exists():
            shutil.copyfile(chapter.folder / name, dest / name)
    if (chapter.folder / "examples").is_dir():
        shutil.copytree(chapter.folder / "examples", dest / "examples", dirs_exist_ok=True)
    return rep


def index_text(reports: list[ChapterReport]) -> str:
    """The index of the built course: chapters with word, block, quiz and figure counts."""
    lines = ["# The plclab course (built)", "",
             "| chapter | words | programs | quiz items | figures | labs |",
             "|---|---:|---:|---:|---:|---|"]
    for r in reports:
        c = r.chapter
        labs = ", ".join(c.lab_refs) or "-"
        lines.append(f"| [{c.number}. {c.title}]({c.slug}/chapter.md) | {r.words} | {r.blocks} "
                     f"| {r.quiz_items} | {len(r.figures)} | {labs} |")
    tot = (sum(r.words for r in reports), sum(r.blocks for r in reports),
           sum(r.quiz_items for r in reports), sum(len(r.figures) for r in reports))
    lines.append(f"| **total** | {tot[0]} | {tot[1]} | {tot[2]} | {tot[3]} | |")
    lines += ["", "[Glossary and index](glossary.md): every term in English and Russian, and the "
              "chapters that use it."]
    return "\n".join(lines) + "\n"


def build(out: str | Path, course_dir: str | Path | None = None, only: list[Chapter] | None = None,
          figures: bool = True) -> list[ChapterReport]:
    """Build the course (or the chapters ``only``) into ``out``; returns one report a chapter."""
    out_root = Path(out)
    chs = only if only is not None else chapters(course_dir)
    if chs and out_root.resolve().is_relative_to(chs[0].folder.parent.resolve()):
        raise PlcError("PLC3002", f"--out {out}: the built course goes outside the course "
                       "sources; choose another folder")
    out_root.mkdir(parents=True, exist_ok=True)
    reports = [build_chapter(c, out_root, figures) for c in chs]
    (out_root / "README.md").write_text(index_text(reports), encoding="utf-8")
    if glossary_path(course_dir).exists():
        write_glossary(out_root, course_dir)
    return reports
