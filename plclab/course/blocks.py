"""Run the code of a chapter: every program block compiles, its TEST blocks pass and its programs
scan without a fault, or it is a marked mistake that produces exactly the code it names."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..errors import PlcError
from .model import PROGRAM_LANGUAGES, Chapter, CodeBlock

DEFAULT_SCANS = 10


@dataclass
class BlockOutcome:
    """What running one block (or example file) gave."""

    where: str
    ok: bool
    message: str
    codes: tuple[str, ...] = ()

    def __str__(self) -> str:
        return f"{'ok  ' if self.ok else 'FAIL'} {self.where}: {self.message}"


def _produced_codes(text: str, filename: str, scans: int) -> tuple[tuple[str, ...], str]:
    """(codes produced, summary): compile errors, else failed TESTs' or a scan's fault code,
    else the warnings (the beginner lint included). An empty tuple means the program is clean."""
    from ..project import check_sources, compile_sources
    from ..runtime.plc import Plc
    from ..testing import run_compiled_tests

    # with the beginner lint (PLC0210..), so that a chapter can show a lint warning as a mistake
    project, diags = check_sources([(text, filename)], lint=True)
    errors = [d for d in diags if d.severity == "error"]
    if project is None:
        return tuple(d.code for d in errors), str(errors[0])
    compiled = compile_sources([(text, filename)])
    failed = [r for r in run_compiled_tests(compiled) if not r.passed]
    if failed:
        return tuple(r.code or "TEST" for r in failed), str(failed[0])
    try:
        plc = Plc(compiled)
        if plc.project.programs:
            plc.scan(scans)
    except PlcError as e:  # a run-time fault (PLC2xxx) or the watchdog
        return (e.code,), str(e)
    warnings = [d for d in diags if d.severity != "error"]
    return tuple(d.code for d in warnings), (str(warnings[0]) if warnings else "")


def run_block(block: CodeBlock) -> BlockOutcome:
    """Run one block of a chapter and say whether it behaves as the chapter claims."""
    if not block.is_program:
        return BlockOutcome(block.where, True, f"{block.language} (not run)")
    scans = int(block.attrs.get("scans", DEFAULT_SCANS))
    codes, summary = _produced_codes(block.text, block.filename, scans)
    expected = block.expected_code
    if expected is None:
        bad = [c for c in codes if not c.startswith("PLC02")]  # warnings are allowed
        if bad:
            return BlockOutcome(block.where, False, f"should run cleanly but gave {summary}",
                                codes)
        return BlockOutcome(block.where, True, "runs" + (f" (warnings {', '.join(codes)})"
                                                           if codes else ""), codes)
    if codes[:1] == (expected,):
        return BlockOutcome(block.where, True, f"fails as marked with {expected}", codes)
    got = summary or "no diagnostic at all"
    return BlockOutcome(block.where, False, f"marked error={expected} but gave {got}", codes)


def run_example(path: Path, chapter: str = "") -> BlockOutcome:
    """An example file of a chapter: compiles, its TESTs pass, its programs scan cleanly."""
    codes, summary = _produced_codes(path.read_text(encoding="utf-8"), str(path),
                                     DEFAULT_SCANS)
    where = f"course/{chapter}/examples/{path.name}" if chapter else str(path)
    bad = [c for c in codes if not c.startswith("PLC02")]
    if bad:
        return BlockOutcome(where, False, f"should run cleanly but gave {summary}", codes)
    return BlockOutcome(where, True, "runs", codes)


def check_chapter_code(chapter: Chapter) -> list[BlockOutcome]:
    """Every block and example file of a chapter, in order."""
    out = [run_block(b) for b in chapter.blocks]
    out += [run_example(p, chapter.slug) for p in chapter.examples
            if p.suffix in PROGRAM_LANGUAGES.values()]
    return out


def codes_taught(chapters: list[Chapter]) -> dict[str, list[Chapter]]:
    """Diagnostic code -> the chapters that show it as a marked mistake."""
    out: dict[str, list[Chapter]] = {}
    for c in chapters:
        for b in c.blocks:
            if b.expected_code and c not in out.setdefault(b.expected_code, []):
                out[b.expected_code].append(c)
    return out
