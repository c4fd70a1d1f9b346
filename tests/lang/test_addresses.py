"""One parser of direct addresses (issue 37): plclab.lang.addresses.parse_located, read by the
runtime, the simulator's wiring, the Modbus map, the lab's I/O table and Trace conditions."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from plclab.lang.addresses import SIZE_BYTES, Located, canonical, parse_located

ROOT = Path(__file__).resolve().parents[2]

GOOD = {
    "%IX0.0": Located("I", "X", 0, 0),
    "%qx1.7": Located("Q", "X", 1, 7),
    " %MW4 ": Located("M", "W", 4, None),
    "%ib3": Located("I", "B", 3, None),
    "%QD8": Located("Q", "D", 8, None),
    "%ML16": Located("M", "L", 16, None),
    "%I2.5": Located("I", "X", 2, 5),  # S7 writes a bit without X
    "%IX12": Located("I", "X", 12, None),  # a bit address without its bit: the caller says so
    "%IX0.9": Located("I", "X", 0, 9),  # bit range: the caller's code (PLC0120, PLC5004)
}
BAD = ["", "%", "IX0.0", "%AX0.0", "%IY0", "%IX", "%IX0.", "%IX.1", "%IX0.0.1", "%IW2.5.7.1",
       "%I X0.0", "%IX0,0", "%IX-1", "%IX0.0x", "x%IX0.0", "%IW1.2.3", "%IX1e3", "%IX٣.1",
       "%MW4;", "%QX0.0 AND TRUE"]


@pytest.mark.parametrize("text", sorted(GOOD))
def test_a_direct_address_is_read(text: str) -> None:
    assert parse_located(text) == GOOD[text]


@pytest.mark.parametrize("text", BAD)
def test_what_is_not_a_canonical_direct_address_is_refused(text: str) -> None:
    assert parse_located(text) is None


def test_the_parts_and_the_text() -> None:
    for loc in GOOD.values():
        assert parse_located(str(loc)) == loc  # str() is the canonical form, read back the same
        assert loc.nbytes == SIZE_BYTES[loc.size]
    assert str(parse_located("%qw2")) == "%QW2" and parse_located("%ML0").nbytes == 8


def test_iec_forms_become_canonical_first() -> None:
    # a flat bit number and a hierarchical address are not the canonical form...
    assert parse_located("%QX75") == Located("Q", "X", 75, None)
    assert parse_located("%IW2.5.7.1") is None
    # ...until canonical() rewrites them, as the front ends do
    assert parse_located(canonical("%QX75")) == Located("Q", "X", 9, 3)
    assert parse_located(canonical("%IW2.5.7.1")) == Located("I", "W", 1, None)


def test_the_users_read_addresses_as_the_shared_parser_does() -> None:
    from plclab.modbus.addressing import parse_address
    from plclab.sim.wiring import ADDRESS_RE
    from plclab.trace.expr import parse_condition

    for text, loc in GOOD.items():
        m = ADDRESS_RE.fullmatch(text.strip().upper())
        assert m and (m.group(1), m.group(2) or "X", int(m.group(3))) == (
            loc.area, loc.size, loc.byte)
        if loc.size != "X" or loc.bit is not None and loc.bit <= 7:
            area, size, byte, bit = parse_address(text.strip())
            assert (area, size, byte) == (loc.area, loc.size, loc.byte)
    for text in ("%IW2.5.7.1x", "%AX0.0", "%IX.1"):
        with pytest.raises(ValueError):
            parse_address(text)
    assert parse_condition("%ix0.1 and %QW4 > 3").names == {"%IX0.1", "%QW4"}


ALLOWED = {"plclab/lang/addresses.py", "plclab/lang/lexer.py", "plclab/viz/highlight.py",
           "plclab/lang/frontends/plcopen_types.py"}


def address_patterns(root: Path) -> list[str]:
    """Modules under ``root/plclab`` that spell an address pattern of their own (``[IQM]``)."""
    shape = re.compile(r"\[IQM\]")
    return [p.relative_to(root).as_posix() for p in sorted((root / "plclab").rglob("*.py"))
            if shape.search(p.read_text(encoding="utf-8"))]


def test_no_other_module_writes_its_own_address_pattern() -> None:
    # The source syntax of an address (hierarchical, %I*) is the lexer's and the highlighter's
    # token; the PLCopen reader checks the same token (plcopen_types.py, where it reads a
    # variable's address). Everything else reads the canonical form through
    # plclab.lang.addresses.
    found = address_patterns(ROOT)
    assert set(found) <= ALLOWED, sorted(set(found) - ALLOWED)
    assert "plclab/lang/addresses.py" in found


def test_the_pattern_check_would_catch_a_copy(tmp_path: Path) -> None:
    (tmp_path / "plclab" / "grade").mkdir(parents=True)
    (tmp_path / "plclab" / "grade" / "copy.py").write_text(
        'ADDR = re.compile(r"%([IQM])([XBWDL]?)(\\d+)")\n', encoding="utf-8")
    (tmp_path / "plclab" / "grade" / "fine.py").write_text("from x import LOCATED_RE\n",
                                                         encoding="utf-8")
    assert address_patterns(tmp_path) == ["plclab/grade/copy.py"]
