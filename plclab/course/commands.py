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
@arg("chapter", nargs="?", metavar="CHAPTER", help="chapter number or slug, e.g. 10")
@arg("--check", action="store_true",
     help="validate every answer key (numbers recomputed, program outputs re-run)")
@arg("--course", help="the course sources (default: course/ of this checkout)")
def cmd_quiz(ns: argparse.Namespace) -> int:
    from .model import chapters, find_chapter
    from .quiz import ask, check_quiz

    if ns.check:
        chs = [find_chapter(ns.chapter, ns.course)] if ns.chapter else chapters(ns.course)
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
    if not ns.chapter:
        raise PlcError("PLC3002", "give a chapter, e.g. plclab quiz 10 (plclab course list "
                       "lists them), or --check to validate the keys")
    right, total = ask(find_chapter(ns.chapter, ns.course))
    return 0 if right == total else 1
