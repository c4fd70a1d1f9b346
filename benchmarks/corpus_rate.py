"""Acceptance rate of plclab on a corpus of real-world files (issue 23's measure).

Run ``python benchmarks/corpus_rate.py DIR [DIR ...]``: every ``.st`` and ``.xml`` file under
each DIR is checked on its own, in the dialect its ``{dialect}`` pragma names, else the one a
``DIALECT`` file in its folder (or a parent, up to DIR) names, else the default. A file that
checks without errors and holds a program is then loaded and scanned 100 times (10 ms apart).
The table gives, per DIR: files, accepted, accepted and ran 100 scans without a fault, the
rate, and the most frequent first error codes with one example each, which is what to work on
next. ``--list`` also prints each file's outcome. Files under a ``_excluded`` folder (invalid on
purpose, or needing a vendor library or another file) are not counted.

The corpus itself is not in the repository unless its licence allows it (MIT, BSD, Apache,
LGPL with attribution; see ``tests/corpus/`` where such files are kept with their source).
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import plclab  # noqa: E402
from plclab.errors import PlcError  # noqa: E402
from plclab.project import check_sources  # noqa: E402
from plclab.runtime.plc import Plc  # noqa: E402

SCANS = 100
EXCLUDED = "_excluded"  # files not valid or not self-contained, kept aside with the reason


@dataclass
class Outcome:
    path: Path
    status: str  # "ran", "accepted" (no program to run), "rejected", "fault", "unreadable"
    code: str = ""
    message: str = ""


def dialect_for(path: Path, root: Path) -> str | None:
    """The dialect of the nearest ``DIALECT`` file, or ``dialect`` key of a ``SOURCE.toml``
    (the committed corpus, ``tests/corpus/``), from the file's folder up to ``root``."""
    import tomllib

    for folder in [path.parent, *path.parent.parents]:
        marker = folder / "DIALECT"
        if marker.is_file():
            return marker.read_text().strip() or None
        source = folder / "SOURCE.toml"
        if source.is_file():
            return tomllib.loads(source.read_text(encoding="utf-8")).get("dialect") or None
        if folder == root:
            break
    return None


def context_for(path: Path, root: Path) -> list[Path]:
    """The files a corpus file is read together with: the ``[context]`` entry of the nearest
    ``SOURCE.toml`` (a file -> other files of its folder, e.g. the objects of one TwinCAT
    project that a POU uses, which its IDE compiles together), else none."""
    import tomllib

    for folder in [path.parent, *path.parent.parents]:
        source = folder / "SOURCE.toml"
        if source.is_file():
            meta = tomllib.loads(source.read_text(encoding="utf-8"))
            rel = str(path.relative_to(folder).as_posix())
            return [folder / other for other in meta.get("context", {}).get(rel, [])]
        if folder == root:
            break
    return []


def read_text(path: Path) -> str | None:
    raw = path.read_bytes()
    for encoding in ("utf-8-sig", "latin-1"):
        try:
            return raw.decode(encoding)
        except UnicodeDecodeError:
            continue
    return None


def judge(path: Path, root: Path) -> Outcome:
    text = read_text(path)
    if text is None:
        return Outcome(path, "unreadable")
    dialect = dialect_for(path, root)
    sources = [(read_text(c) or "", c.name) for c in context_for(path, root)]
    sources.append((text, path.name))
    try:
        project, diags = check_sources(sources, dialect)
    except PlcError as exc:  # a file the front ends refuse as a whole
        return Outcome(path, "rejected", exc.code, str(exc).splitlines()[0])
    errors = [d for d in diags if d.severity == "error"]
    if errors or project is None:
        first = errors[0] if errors else None
        return Outcome(path, "rejected", first.code if first else "?",
                       first.message if first else "no project")
    if not project.programs:
        return Outcome(path, "accepted")
    try:
        plc = Plc(plclab.compile_sources(sources, dialect=dialect))
        plc.scan(SCANS)
    except PlcError as exc:
        return Outcome(path, "fault", exc.code, str(exc).splitlines()[0])
    return Outcome(path, "ran")


def corpus_files(root: Path) -> list[Path]:
    """Every ``.st`` and ``.xml`` file under ``root`` outside ``_excluded`` folders, sorted."""
    return sorted(p for p in root.rglob("*") if p.suffix.lower() in (".st", ".xml")
                  and EXCLUDED not in p.relative_to(root).parts)


def measure(root: Path) -> list[Outcome]:
    return [judge(p, root) for p in corpus_files(root)]


def report(root: Path, outcomes: list[Outcome], listing: bool) -> None:
    n = len(outcomes)
    by = Counter(o.status for o in outcomes)
    ok = by["ran"] + by["accepted"]
    print(f"{root}: {n} files, {ok} accepted ({by['ran']} ran {SCANS} scans), "
          f"{by['rejected']} rejected, {by['fault']} faulted, {by['unreadable']} unreadable; "
          f"acceptance {ok / n:.0%}" if n else f"{root}: no files")
    codes = Counter(o.code for o in outcomes if o.status in ("rejected", "fault"))
    for code, count in codes.most_common(8):
        example = next(o for o in outcomes if o.code == code)
        print(f"  {count:4d} x {code}  e.g. {example.path.relative_to(root)}: "
              f"{example.message[:100]}")
    if listing:
        for o in outcomes:
            print(f"  {o.status:9s} {o.code:8s} {o.path.relative_to(root)}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="+", type=Path)
    ap.add_argument("--list", action="store_true", help="print each file's outcome")
    args = ap.parse_args(argv)
    total = accepted = 0
    for d in args.dirs:
        outcomes = measure(d)
        report(d, outcomes, args.list)
        total += len(outcomes)
        accepted += sum(o.status in ("ran", "accepted") for o in outcomes)
    if total:
        print(f"acceptance rate: {accepted / total:.2f} ({accepted}/{total})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
