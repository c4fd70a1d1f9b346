"""Reading source files the same way in every command: UTF-8 (a BOM is fine) or UTF-16 with a
BOM, one PlcError with a code for a missing file, a folder or another encoding.

Standard library and :mod:`plclab.errors` only, so ``plclab check`` can read and hash a file
before it imports a front end (the compile cache, ADR 0057).
"""

from __future__ import annotations

import os

from ..errors import Location, PlcError

__all__ = ["decode_source", "read_sources"]


def decode_source(raw: bytes, name: str) -> str:
    """The text of a source file, read the same way by every command: UTF-8 (a BOM is fine)
    or UTF-16 with a BOM. Anything else (Latin-1, Windows-1252) is PLC5052, naming the line
    and column of the first byte that is not UTF-8."""
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return raw.decode("utf-16")
        except UnicodeDecodeError:
            pass
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        before = raw[:e.start]
        line = before.count(b"\n") + 1
        col = e.start - (before.rfind(b"\n") + 1) + 1
        raise PlcError("PLC5052", f"{name} is not UTF-8 text (byte 0x{raw[e.start]:02X}: "
                       "Latin-1 or Windows-1252?); save it as UTF-8 (your editor's 'Save "
                       "with encoding' or 'Save as', UTF-8)", Location(name, line, col)
                       ) from None


def read_sources(paths: list[str | os.PathLike]) -> list[tuple[str, str]]:
    out = []
    for p in paths:
        p = str(p)
        try:
            with open(p, "rb") as fh:
                out.append((decode_source(fh.read(), p), p))
        except FileNotFoundError:
            raise PlcError("PLC3003", f"{p}: no such file; check the path") from None
        except IsADirectoryError:
            raise PlcError("PLC3003", f"{p} is a folder; give the source files in it") from None
    return out
