"""``plclab course build|list|check`` and ``plclab quiz CHAPTER`` / ``plclab quiz --check``."""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from ..cli_registry import arg, command
from ..errors import PlcError


@command("course")
@arg("action", choices=["build", "list", "check"], metavar="ACTION",
     help="build: run, draw and write the course; list: the chapters; check: run the code only")
@arg("chapters", nargs="*", metavar="CHAPTER", help="chapter numbers or slugs (default: all)")
@arg("--out", help="where the built course goes (default: a folder in the temp directory)")
@arg("--course", help="the course sources (default: course/ of this checkout)")
def cmd_course(ns: argparse.Namespace) -> int:
    from .blocks import check_chapter_code
    from .build import build
    from .model import chapters, find_chapter

    chs = [find_chapter(c, ns.course) for c in ns.chapters] or chapters(ns.course)
    if ns.action == "list":
        for c in chs:
            print(f"{c.number:>3}  {c.title}  ({c.slug}; labs: {', '.join(c.lab_refs) or '-'})")
        return 0
    if ns.action == "check":
        bad = 0
        for c in chs:
            for o in check_chapter_code(c):
                bad += not o.ok
                print(o)
        print(f"{bad} problem(s)")
        return 1 if bad else 0
    out = Path(ns.out) if ns.out else Path(tempfile.gettempdir()) / "plclab-course"
    reports = build(out, ns.course, chs)
    problems = [p for r in reports for p in r.problems]
    for r in reports:
        print(f"{r.chapter.slug}: {r.words} words, {r.blocks} programs, {r.quiz_items} quiz items,"
              f" {len(r.figures)} figures")
        for path, note in r.figures:
            print(f"    {path} ({note})")
    for p in problems:
        print(f"FAIL {p}", file=sys.stderr)
    print(f"course written to {out / 'README.md'}")
    return 1 if problems else 0


@command("quiz")
@arg("words", nargs="*", metavar="CHAPTER | export OUT [CHAPTER ...]",
     help="a chapter number or slug to take its quiz (plclab quiz 10); or export OUT: write the "
     "quiz pool (all chapters, or those named) for Moodle (--format gift) or Canvas and other "
     "QTI 1.2 importers (--format qti, a .zip)")
@arg("--check", action="store_true",
     help="validate every answer key (numbers recomputed, program outputs re-run)")
@arg("--format", dest="fmt", nargs="+", default=["gift"], metavar="gift|qti",
     help="quiz export: Moodle GIFT text (default) or an IMS QTI 1.2 package (.zip); OUT and "
     "the chapters may follow it: plclab quiz export --format qti OUT.zip")
@arg("--course", help="the course sources (default: course/ of this checkout)")
def cmd_quiz(ns: argparse.Namespace) -> int:
    from .model import chapters, find_chapter
    from .quiz import ask, check_quiz

    # --format takes what follows it too, so that "export --format qti OUT" parses like
    # "export OUT --format qti" (argparse stops a positional list at the first option)
    fmt, *after = ns.fmt
    words = list(ns.words) + after
    if words[:1] == ["export"]:
        from .quiz_export import write_export

        if len(words) < 2:
            raise PlcError("PLC3080", "quiz export needs a place to write: plclab quiz export "
                           "OUT.gift (or --format qti OUT.zip), optionally followed by chapters")
        chs = [find_chapter(c, ns.course) for c in words[2:]] or chapters(ns.course)
        path, n = write_export(chs, fmt, words[1], ns.course)
        print(f"{n} quiz items of {len(chs)} chapter(s) written to {path} ({fmt})")
        return 0
    if after or fmt != "gift":
        raise PlcError("PLC3002", "--format belongs to plclab quiz export OUT --format gift|qti")
    if len(words) > 1:
        raise PlcError("PLC3002", f"give one chapter, not {len(words)}: plclab quiz 10 (or "
                       "plclab quiz export OUT 10 11 to export several)")
    chapter = words[0] if words else None
    if ns.check:
        chs = [find_chapter(chapter, ns.course)] if chapter else chapters(ns.course)
        total, problems = 0, []
        for c in chs:
            n, p = check_quiz(c)
            total += n
            problems += p
            print(f"{c.slug}: {n} items, {'ok' if not p else f'{len(p)} problem(s)'}")
        for p in problems:
            print(f"FAIL {p}")
        print(f"{total} items checked, {len(problems)} problem(s)")
        return 1 if problems else 0
    if not chapter:
        raise PlcError("PLC3002", "give a chapter, e.g. plclab quiz 10 (plclab course list "
                       "lists them), --check to validate the keys, or export OUT to write the "
                       "pool for Moodle or Canvas")
    right, total = ask(find_chapter(chapter, ns.course))
    return 0 if right == total else 1
