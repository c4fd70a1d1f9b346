"""Direct addresses: the IEC 61131-3 forms, and the one canonical form the rest of plclab reads.

plclab has one flat process image per area (%I, %Q, %M), addressed S7-style by byte and bit.
IEC 61131-3 (ed.3 6.5.5, Table 16) writes the same places in more ways; :func:`canonical` turns
each into the S7 form once, where a front end reads it, so the checker, the compiler, the
runtime, the simulator and the Modbus server keep reading one form:

* ``%IX1.2``, ``%I1.2``: byte 1, bit 2 (as S7; unchanged, the size X added);
* ``%QX75``, ``%Q75``: IEC's flat bit number 75 = byte 9, bit 3;
* ``%IW2.5.7.1`` (hierarchical, three fields or more: bus, rack, module, channel): the leading
  fields name hardware a simulated PLC does not have; the last field is the item (here
  ``%IW1``), and the front end warns (PLC0175). A hierarchical bit address keeps its last two
  fields as byte.bit. (``%MW1.2``, two fields, stays an error, a bit part on a word, except in
  the dialects that write it as module.item: MATIEC/Beremiz and strict IEC, ADR 0031.)

Anything else (a bit number above 7, an oversized number) is left as written for the checker's
PLC0120 and PLC0127.

>>> canonical("%QX75"), canonical("%Q75"), canonical("%ix1.2"), canonical("%MW4")
('%QX9.3', '%QX9.3', '%IX1.2', '%MW4')
>>> canonical("%IW2.5.7.1"), hierarchical("%IW2.5.7.1")
('%IW1', True)

Everything after the front ends reads the canonical form with :func:`parse_located` (one parser
for the runtime's process image, the simulator's wiring, the Modbus map, the lab's I/O table and
the Trace's conditions):

>>> parse_located("%qx1.2"), parse_located("%MW4").nbytes, parse_located("%IX1.2.3")
(Located(area='Q', size='X', byte=1, bit=2), 2, None)
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = ["ADDRESS_RE", "LOCATED", "LOCATED_RE", "SIZE_BYTES", "Located", "canonical",
           "hierarchical", "parse_located"]

ADDRESS_RE = re.compile(r"%([IQM])([XBWDL]?)([0-9]+(?:\.[0-9]+)*)")
_MAX_DIGITS = 9  # longer numbers are left for the checker (PLC0127)


def hierarchical(text: str, words: bool = False) -> bool:
    """Three fields or more (``%IW2.5.7.1``, ``%IX0.1.2``); with ``words`` (the dialects
    whose ``hierarchical_words`` is set) also two on a byte/word address (``%IW0.1``)."""
    m = ADDRESS_RE.fullmatch(text.strip().upper())
    if m is None:
        return False
    dots = m.group(3).count(".")
    return dots >= 2 or (words and dots == 1 and m.group(2) not in ("", "X"))


def canonical(text: str, words: bool = False) -> str:
    """The S7 form of an IEC direct address (see the module text); ``text`` upper-cased and
    otherwise unchanged when it is not an address this module rewrites. ``words``: a two-field
    byte/word address is hierarchical too (MATIEC, Beremiz: ``%IW0.1`` -> ``%IW1``).

    >>> canonical("%IW0.1"), canonical("%IW0.1", words=True), canonical("%IX0.1", words=True)
    ('%IW0.1', '%IW1', '%IX0.1')
    """
    up = text.strip().upper()
    m = ADDRESS_RE.fullmatch(up)
    if m is None:
        return up
    area, size, fields = m.group(1), m.group(2) or "X", m.group(3).split(".")
    if any(len(f) > _MAX_DIGITS for f in fields):
        return up
    if size == "X" and len(fields) == 1:  # a flat bit number
        n = int(fields[0])
        return f"%{area}X{n // 8}.{n % 8}"
    if len(fields) < 3 and (size == "X" or len(fields) == 1 or not words):
        # byte.bit, a byte/word number (%MW1.2 stays unless ``words``: PLC0120 explains it)
        return f"%{area}{size}{'.'.join(fields)}"
    if size == "X":
        return f"%{area}X{int(fields[-2])}.{fields[-1]}"
    return f"%{area}{size}{int(fields[-1])}"


# -- the canonical form, read by everything after the front ends ----------------------------------
LOCATED = r"%([IQM])([XBWDL]?)([0-9]+)(?:\.([0-9]+))?"
"""The canonical (S7) form of a direct address as a pattern, upper case: area, size (empty for a
bit), byte, bit. :data:`LOCATED_RE` matches it; :func:`parse_located` reads it."""
LOCATED_RE = re.compile(LOCATED)
SIZE_BYTES = {"X": 1, "B": 1, "W": 2, "D": 4, "L": 8}
"""Bytes of the process image an address of each size covers (a bit address: its byte)."""


@dataclass(frozen=True)
class Located:
    """A direct address in the canonical form: ``%QX1.2`` is ``Located("Q", "X", 1, 2)``."""

    area: str  # I, Q or M
    size: str  # X (bit), B, W, D or L
    byte: int
    bit: int | None  # None for B, W, D, L (and for a bit address written without its bit)

    @property
    def nbytes(self) -> int:
        """Bytes of the process image it covers."""
        return SIZE_BYTES[self.size]

    def __str__(self) -> str:
        return f"%{self.area}{self.size}{self.byte}" + ("" if self.bit is None else f".{self.bit}")


def parse_located(text: str) -> Located | None:
    """The parts of a direct address in the canonical form (any case, blanks around ignored), or
    None when ``text`` is not one. IEC's other forms (``%QX75``, ``%IW2.5.7.1``) are not
    rewritten here: :func:`canonical` does that where a front end reads them. The bit range
    (0..7), a bit address without its bit and the size against a type are for the caller to
    report, each with its own code and words.

    >>> str(parse_located(" %ib3 ")), parse_located("%IX0.9").bit, parse_located("IX0.0")
    ('%IB3', 9, None)
    """
    m = LOCATED_RE.fullmatch(text.strip().upper())
    if m is None:
        return None
    return Located(m.group(1), m.group(2) or "X", int(m.group(3)),
                   None if m.group(4) is None else int(m.group(4)))
