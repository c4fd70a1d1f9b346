"""plclab on the STruC++ validation suite (issue 33's measure).

Run ``python benchmarks/strucpp_suite.py DIR`` with DIR the suite's ``tests/st-validation``
folder (or the STruC++ checkout holding it). The suite is not in this repository: bring it with
``git clone https://github.com/Autonomy-Logic/STruCpp``.

The suite's convention (its ``README.md`` and ``tests/integration/st-validation.test.ts``): in
each category folder, a source ``NAME.st`` (programs, functions, blocks, types) is paired with
``test_NAME.st`` holding ``TEST 'title' ... END_TEST`` blocks with ``ASSERT_*`` calls; a pair
passes when no assertion fails. plclab reads the pair as a user would: ``plclab test NAME.st
test_NAME.st``, default options (each file in its ``{dialect}`` pragma's dialect, else the
default). A pair that does not compile fails every TEST block in it, counted under its first
error code. The table gives the passing TEST blocks out of all of them, then the failures
grouped by cause (code and the start of the message), most tests first, which is what to work on
next. ``--list`` also prints each failing test. A cause that vendor documentation rules out
(ADR 0059: no vendor documents ``TIME_TO_US``/``TIME_TO_S`` or ``''`` in a string; IEC's CTUD
counts on rising edges) is marked ``[by design]``: 362 of 374 is the ceiling without inventing
them.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections import Counter, defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from plclab.errors import PlcError  # noqa: E402
from plclab.project import compile_sources, read_sources  # noqa: E402
from plclab.testing import run_compiled_tests  # noqa: E402

TEST_RE = re.compile(r"^\s*TEST\s+'((?:[^']|'')*)'", re.MULTILINE | re.IGNORECASE)
# causes that plclab refuses on purpose, and why (ADR 0059)
BY_DESIGN = {
    "TIME_TO_US": "a STruC++ runtime helper no vendor documents",
    "TIME_TO_S ": "a STruC++ runtime helper no vendor documents",
    "doubled": "no vendor documents '' in a string; CODESYS and TwinCAT write $'",
    "in cv_init": "IEC's CTUD counts on the rising edge of CD, the test expects the falling one",
}
NUMBER_RE = re.compile(r"\b\d+(\.\d+)?\b|'[^']*'|\"[^\"]*\"")


def suite_dir(root: Path) -> Path:
    for cand in (root, root / "tests" / "st-validation", root / "st-validation"):
        if any(cand.glob("*/test_*.st")):
            return cand
    raise SystemExit(f"{root}: no */test_*.st files; give the suite's tests/st-validation folder")


def pairs(root: Path) -> list[tuple[Path, Path]]:
    out = []
    for test in sorted(root.rglob("test_*.st")):
        source = test.with_name(test.name[len("test_"):])
        if source.exists():
            out.append((source, test))
    return out


def cause(code: str, message: str) -> str:
    """A failure's group: its code and the first words of its message, numbers and names out."""
    words = NUMBER_RE.sub("_", message.splitlines()[0] if message else "")
    return f"{code or '?'} {words[:70]}"


def run_pair(source: Path, test: Path) -> list[tuple[str, bool, str, str]]:
    """(title, passed, cause, detail) of every TEST block of the pair."""
    titles = [t.replace("''", "'") for t in TEST_RE.findall(test.read_text(encoding="utf-8"))]
    try:
        compiled = compile_sources(read_sources([source, test]))
    except PlcError as exc:
        detail = f"{exc.location}: {exc.code} {exc.message}"
        why = "compile " + cause(exc.code, exc.message)
        return [(t, False, why, detail) for t in titles]
    out = []
    for r in run_compiled_tests(compiled):
        why = "" if r.passed else ("assert " if r.code == "PLC2060" else "fault ") + cause(
            r.code, r.message)
        out.append((r.title, r.passed, why, "" if r.passed else str(r)))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dir", type=Path, help="STruC++'s tests/st-validation (or the checkout)")
    ap.add_argument("--list", action="store_true", help="print every failing test")
    args = ap.parse_args(argv)
    root = suite_dir(args.dir)
    total = passed = 0
    causes: Counter[str] = Counter()
    examples: dict[str, str] = {}
    by_pair: dict[str, list[str]] = defaultdict(list)
    for source, test in pairs(root):
        name = str(test.relative_to(root))
        for title, ok, why, detail in run_pair(source, test):
            total += 1
            passed += ok
            if not ok:
                causes[why] += 1
                examples.setdefault(why, detail)
                by_pair[name].append(f"  {title}: {detail}")
    print(f"STruC++ st-validation: {passed}/{total} TEST blocks pass "
          f"({100 * passed / max(total, 1):.1f} %)")
    for why, n in causes.most_common():
        note = next((f"  [by design: {v}]" for k, v in BY_DESIGN.items() if k in why), "")
        print(f"{n:4d}  {why}{note}\n      e.g. {examples[why][:160]}")
    if args.list:
        for name, lines in by_pair.items():
            print(name)
            print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
