"""No module is longer than a newcomer reads in one sitting (issue 37, ADR 0061).

A module of plclab or of the plants over :data:`LIMIT` lines fails, unless it is listed in
:data:`EXCEPTIONS` with the reason. An exception that no longer holds (the file is gone or is
short enough now) fails too, so the list only shrinks. Split a long module along its concepts,
with names that say what is inside (``grade/lab_spec.py``, ``lab_reader.py``), not into parts.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ("plclab", "plants")
LIMIT = 700

# none left (issue 37): a module listed here needs a reason, and the list only shrinks
EXCEPTIONS: dict[str, str] = {}


def line_counts(root: Path = ROOT, folders: tuple[str, ...] = FOLDERS) -> dict[str, int]:
    """Lines of every ``.py`` file under *folders* of *root*, by path relative to *root*."""
    out = {}
    for folder in folders:
        for path in sorted((root / folder).rglob("*.py")):
            if "__pycache__" in path.parts:
                continue
            with path.open("rb") as f:
                out[path.relative_to(root).as_posix()] = sum(1 for _ in f)
    return out


def too_long(counts: dict[str, int], limit: int, exceptions: dict[str, str]) -> list[str]:
    """Modules over *limit* lines that are not in *exceptions*, as sentences."""
    return [f"{p}: {n} lines (at most {limit}); split it along its concepts"
            for p, n in sorted(counts.items()) if n > limit and p not in exceptions]


def stale(counts: dict[str, int], limit: int, exceptions: dict[str, str]) -> list[str]:
    """Exceptions that no longer hold: the file is gone or within the limit."""
    return [f"{p}: " + ("no such module" if p not in counts else f"{counts[p]} lines now")
            + "; remove it from EXCEPTIONS" for p in sorted(exceptions)
            if counts.get(p, 0) <= limit]


def test_no_module_is_over_the_limit() -> None:
    bad = too_long(line_counts(), LIMIT, EXCEPTIONS)
    assert not bad, "\n".join(bad)


def test_every_exception_still_holds_and_has_a_reason() -> None:
    assert not stale(line_counts(), LIMIT, EXCEPTIONS), stale(line_counts(), LIMIT, EXCEPTIONS)
    assert all(len(reason.split()) >= 4 and "TODO" not in reason
               for reason in EXCEPTIONS.values())


def test_the_check_catches_a_long_module_and_a_stale_exception(tmp_path: Path) -> None:
    pkg = tmp_path / "plclab" / "sub"
    pkg.mkdir(parents=True)
    (pkg / "long.py").write_text("x = 1\n" * 701, encoding="utf-8")
    (pkg / "edge.py").write_text("x = 1\n" * 700, encoding="utf-8")
    (pkg / "listed.py").write_text("x = 1\n" * 900, encoding="utf-8")
    (pkg / "no_newline.py").write_text("x = 1\n" * 700 + "y = 2", encoding="utf-8")
    counts = line_counts(tmp_path, ("plclab",))
    assert counts["plclab/sub/edge.py"] == 700 and counts["plclab/sub/no_newline.py"] == 701
    listed = {"plclab/sub/listed.py": "a reason", "plclab/sub/edge.py": "short now",
              "plclab/gone.py": "removed"}
    assert too_long(counts, 700, listed) == [
        "plclab/sub/long.py: 701 lines (at most 700); split it along its concepts",
        "plclab/sub/no_newline.py: 701 lines (at most 700); split it along its concepts"]
    assert stale(counts, 700, listed) == [
        "plclab/gone.py: no such module; remove it from EXCEPTIONS",
        "plclab/sub/edge.py: 700 lines now; remove it from EXCEPTIONS"]
