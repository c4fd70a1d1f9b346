"""Reading TOML files for wiring tables and scenarios, with line numbers for rows and keys.

``tomllib`` gives no positions, so the lines of the rows of an array (``[[wiring]]`` tables or an
inline ``wiring = [ {...}, ... ]`` array) are found by scanning the text. When the scan fails
the callers fall back to naming the row index.
"""

from __future__ import annotations

import os
import re
import tomllib
from typing import Any

from .errors import sim_error


def read_toml(path: str | os.PathLike, what: str) -> tuple[dict[str, Any], str, str]:
    """``(data, text, filename)`` of a TOML file; PLC4001 when it cannot be read."""
    filename = os.fspath(path)
    try:
        with open(filename, encoding="utf-8-sig") as fh:
            text = fh.read()
    except FileNotFoundError:
        raise sim_error("PLC4001", f"{filename}: no such {what} file; check the path") from None
    except IsADirectoryError:
        raise sim_error("PLC4001", f"{filename} is a folder, not a {what} file") from None
    except UnicodeDecodeError:
        raise sim_error("PLC4001", f"{filename} is not UTF-8 text; save it as UTF-8") from None
    return parse_toml(text, filename, what), text, filename


def parse_toml(text: str, filename: str, what: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        m = re.search(r"\(at line (\d+), column (\d+)\)", str(e))
        line, col = (int(m.group(1)), int(m.group(2))) if m else (0, 0)
        msg = re.sub(r"\s*\(at line \d+, column \d+\)", "", str(e))
        raise sim_error("PLC4001", f"this {what} file is not valid TOML: {msg}", filename, line,
                        col) from None


def row_spans(text: str, key: str) -> list[tuple[int, int]]:
    """1-based ``(first_line, last_line)`` of each row of the array ``key``."""
    lines = text.splitlines()
    header = re.compile(r"^\s*\[\[\s*" + re.escape(key) + r"\s*\]\]")
    any_header = re.compile(r"^\s*\[")
    starts = [i for i, ln in enumerate(lines) if header.match(ln)]
    if starts:
        spans = []
        for n, s in enumerate(starts):
            end = len(lines) - 1
            for j in range(s + 1, len(lines)):
                if any_header.match(lines[j]) or (n + 1 < len(starts) and j == starts[n + 1]):
                    end = j - 1
                    break
            spans.append((s + 1, end + 1))
        return spans
    m = re.search(r"^\s*" + re.escape(key) + r"\s*=\s*\[", text, re.MULTILINE)
    if not m:
        return []
    spans: list[tuple[int, int]] = []
    pos = m.end()
    depth_sq, depth_br = 1, 0
    line = text.count("\n", 0, pos) + 1
    start_line = 0
    i, n = pos, len(text)
    while i < n and depth_sq > 0:
        ch = text[i]
        if ch == "\n":
            line += 1
        elif ch == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        elif ch in "\"'":
            q3 = text[i:i + 3]
            if q3 in ('"""', "'''"):
                j = text.find(q3, i + 3)
                j = n if j < 0 else j + 3
            else:
                j = i + 1
                while j < n and text[j] != ch and text[j] != "\n":
                    j += 2 if (ch == '"' and text[j] == "\\") else 1
                j += 1
            line += text.count("\n", i, j)
            i = j
            continue
        elif ch == "[":
            depth_sq += 1
        elif ch == "]":
            depth_sq -= 1
        elif ch == "{":
            if depth_br == 0 and depth_sq == 1:
                start_line = line
            depth_br += 1
        elif ch == "}":
            depth_br -= 1
            if depth_br == 0 and depth_sq == 1:
                spans.append((start_line, line))
        i += 1
    return spans


def key_position(text: str, span: tuple[int, int] | None, key: str) -> tuple[int, int]:
    """``(line, col)`` of ``key =`` inside a row span, or the span's first line."""
    if span is None:
        return 0, 0
    lines = text.splitlines()
    pat = re.compile(r"(?:^|[\s{,])(" + re.escape(key) + r"|\"" + re.escape(key) + r"\")\s*=")
    for ln in range(span[0], min(span[1], len(lines)) + 1):
        m = pat.search(lines[ln - 1])
        if m:
            return ln, m.start(1) + 1
    return span[0], 1


def row_reporter(what: str, index: int, file: str | None, text: str | None,
                 span: tuple[int, int] | None, diags: list):
    """``(loc, bad)`` for one row of a TOML table: ``loc(key)`` is where the row (or one of its
    keys) stands in the file, ``bad(code, key, msg)`` records a diagnostic there."""
    from plclab.errors import Diagnostic, Location

    def loc(key: str | None = None) -> Location | None:
        if file is None:
            return None
        if text is not None and span is not None:
            if key is None:
                return Location(file, span[0], 1)
            ln, col = key_position(text, span, key)
            return Location(file, ln, col)
        return Location(file)

    def bad(code: str, key: str | None, msg: str) -> None:
        where = f"{what} {index}" + (f", key '{key}'" if key else "")
        diags.append(Diagnostic(code, f"{where}: {msg}", loc(key)))

    return loc, bad
