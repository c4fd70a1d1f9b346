"""What the autograder does with untrusted names and files before anything else sees them.

* :func:`walk_submission` / :func:`read_source` read a submission without ever following a
  symbolic link (``O_NOFOLLOW``, ``lstat``), with a hard cap on the size of a file (checked with
  ``fstat`` before reading, then at most cap + 1 bytes are read: a 6 GB sparse file costs one
  system call), on the files of a submission and on the entries and depth of a folder.
* :func:`clean_text` makes a name printable (no control, format or surrogate characters);
  :func:`output_dirname` makes a student id a file name that collides with nothing;
  :func:`csv_cell` neutralises spreadsheet formulas (OWASP "CSV injection");
  :func:`md_text`, :func:`md_code` and :func:`md_fence` keep names out of the Markdown syntax.

>>> clean_text("eve\\n# A+\\x1b[2J")
'eve\\\\n# A+\\\\x1b[2J'
>>> csv_cell('=HYPERLINK("http://x","y")')
'\\'=HYPERLINK("http://x","y")'
>>> md_text("a*b*`c`")
'a\\\\*b\\\\*\\\\`c\\\\`'
>>> md_code("x`y")
'`` x`y ``'
"""

from __future__ import annotations

import hashlib
import os
import re
import stat
from dataclasses import dataclass
from pathlib import Path

from ..errors import printable
from .errors import grade_error

MAX_FILE_BYTES = 4 * 2**20
"""A source file larger than this is rejected (PLC5031) without being read."""
MAX_SUBMISSION_BYTES = 8 * 2**20
"""All source files of one submission together."""
MAX_SOURCE_FILES = 64
"""Source files in one submission (PLC5032)."""
MAX_ENTRIES = 2000
"""Entries (files and folders, sources or not) looked at in one submission folder."""
MAX_DEPTH = 8
"""Folder nesting inside a submission."""
MAX_NAME = 120
"""Characters kept of a name shown to people (student ids, file names)."""

RESERVED = {"grades.csv"}
"""Names in the output folder that belong to the class, not to a student."""
_SKIP = ("__MACOSX",)


@dataclass
class SourceFile:
    """One source file found in a submission: its path and its display name."""

    path: Path
    name: str


# ---------------------------------------------------------------------------- names


def clean_text(text: str, limit: int = MAX_NAME) -> str:
    """A printable, single-line form of an untrusted name: control, format (bidi) and
    unpaired surrogate characters become escapes, and it is cut to ``limit`` characters."""
    s = printable(str(text))
    return s if len(s) <= limit else s[:limit - 1] + "…"


def clean_file_name(name: str, limit: int = MAX_NAME) -> str:
    """:func:`clean_text` of a file name that keeps its extension when it is cut (the front
    end is chosen by the extension: ``very_long_name….st`` is still ST)."""
    s = clean_text(name, 10 * limit)
    if len(s) <= limit:
        return s
    stem, dot, ext = s.rpartition(".")
    if not dot or not stem or len(ext) > 8:
        return clean_text(name, limit)
    return s[:limit - len(ext) - 2] + "…." + ext


def output_dirname(student: str, taken: set[str]) -> str:
    """A folder name for a student's outputs: ASCII letters, digits, ``.``, ``_`` and ``-``,
    never hidden, never a class file (``grades.csv``) and unique in ``taken`` ignoring case
    (``taken`` is updated). A name that had to change gets a short hash of the original."""
    base = re.sub(r"[^A-Za-z0-9._-]+", "_", student).strip("._-")[:60] or "student"
    name = base
    if name != student or name.lower() in RESERVED or name.lower() in taken:
        digest = hashlib.sha256(student.encode("utf-8", "surrogatepass")).hexdigest()
        name = f"{base}-{digest[:8]}"
        n = 8
        while name.lower() in taken or name.lower() in RESERVED:
            n += 2
            name = f"{base}-{digest[:n]}"
    taken.add(name.lower())
    return name


_FORMULA = ("=", "+", "-", "@", "\t", "\r", "\n")


def csv_cell(text: str) -> str:
    """A text cell a spreadsheet never runs as a formula: a leading ``= + - @ TAB CR`` gets a
    ``'`` in front, as OWASP recommends (the csv module quotes the rest)."""
    s = str(text)
    return "'" + s if s.startswith(_FORMULA) else s


_MD_SPECIAL = re.compile(r"([\\`*_{}\[\]<>#|~!])")


def md_text(text: str) -> str:
    """Untrusted text as one line of plain Markdown: every character that could start
    emphasis, a code span, a link, HTML, a heading or a table cell is escaped."""
    return _MD_SPECIAL.sub(r"\\\1", clean_text(text, 10 * MAX_NAME))


_MD_INLINE = re.compile(r"([\\`*<>\[\]|])")


def md_line(text: str, limit: int = 4000) -> str:
    """Untrusted text inside a Markdown paragraph: one line, no code span, HTML, link,
    emphasis with ``*`` or table cell can start (lighter than :func:`md_text`, so identifiers
    like ``K1_OUT`` stay readable in a terminal)."""
    return _MD_INLINE.sub(r"\\\1", clean_text(text, limit))


def md_code(text: str) -> str:
    """Untrusted text as an inline code span that no backtick inside can close."""
    s = clean_text(text, 10 * MAX_NAME)
    longest = max((len(m) for m in re.findall(r"`+", s)), default=0)
    ticks = "`" * (longest + 1)
    return f"{ticks} {s} {ticks}" if longest else f"`{s}`"


def md_fence(lines: list[str], info: str = "text") -> list[str]:
    """A fenced code block around ``lines`` whose fence is longer than any backtick run in
    them (so no line can close it and start Markdown of its own)."""
    longest = max((len(m) for ln in lines for m in re.findall(r"`{3,}", ln)), default=0)
    fence = "`" * max(3, longest + 1)
    return [fence + info, *lines, fence]


# ---------------------------------------------------------------------------- files


def _lstat(path: Path) -> os.stat_result:
    try:
        return os.lstat(path)
    except OSError as e:
        raise grade_error("PLC5033", f"{path.name}: cannot be read ({e.strerror}); submit "
                          "plain files") from None


def walk_submission(path: str | os.PathLike, exts: dict[str, str]) -> tuple[list[SourceFile],
                                                                             list[str]]:
    """The source files of a submission (a file or a folder) and the other files found.

    Never follows a symbolic link: a link anywhere is an error (PLC5030), as are special files
    (PLC5033), more than :data:`MAX_SOURCE_FILES` sources, :data:`MAX_ENTRIES` entries or
    :data:`MAX_DEPTH` levels (PLC5032). Display names are relative to the submission's parent
    and made printable (:func:`clean_text`)."""
    root = Path(path)
    st = _lstat(root)
    base = root.parent
    if stat.S_ISLNK(st.st_mode):
        raise _link_error(root.name)
    if stat.S_ISREG(st.st_mode):
        return [SourceFile(root, clean_file_name(root.name))], []
    if not stat.S_ISDIR(st.st_mode):
        raise _special_error(root.name)
    sources: list[SourceFile] = []
    ignored: list[str] = []
    seen = 0
    stack: list[tuple[Path, int]] = [(root, 0)]
    while stack:
        folder, depth = stack.pop()
        try:
            with os.scandir(folder) as it:
                entries = sorted(it, key=lambda e: e.name)
        except OSError as e:
            raise grade_error("PLC5033", f"{folder.name}: cannot be read ({e.strerror})") from None
        for e in entries:
            seen += 1
            if seen > MAX_ENTRIES:
                raise grade_error("PLC5032", f"{root.name}: more than {MAX_ENTRIES} files and "
                                  "folders; submit only your source files")
            if e.name.startswith(".") or e.name in _SKIP:
                continue
            rel = clean_file_name(Path(e.path).relative_to(base).as_posix(), 4 * MAX_NAME)
            if e.is_symlink():
                raise _link_error(rel)
            if e.is_dir(follow_symlinks=False):
                if depth + 1 >= MAX_DEPTH:
                    raise grade_error("PLC5032", f"{rel}: folders nested more than {MAX_DEPTH} "
                                      "deep; flatten the submission")
                stack.append((Path(e.path), depth + 1))
            elif not e.is_file(follow_symlinks=False):
                raise _special_error(rel)
            elif Path(e.name).suffix.lower() in exts:  # "..st" too (splitext: no extension)
                sources.append(SourceFile(Path(e.path), rel))
                if len(sources) > MAX_SOURCE_FILES:
                    raise grade_error("PLC5032", f"{root.name}: more than {MAX_SOURCE_FILES} "
                                      "source files; submit only the program's files")
            else:
                ignored.append(rel)
    sources.sort(key=lambda s: s.name)
    return sources, sorted(ignored)


def read_source(f: SourceFile, budget: int = MAX_FILE_BYTES) -> str:
    """The text of a source file: opened without following a link, its size checked before
    reading, at most ``min(cap, budget) + 1`` bytes read. UTF-8 (a BOM is fine) or UTF-16 with
    a BOM; anything else is PLC5052, as in every command."""
    cap = min(MAX_FILE_BYTES, budget)
    flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
    try:
        fd = os.open(f.path, flags)
    except OSError as e:
        if os.path.islink(f.path):
            raise _link_error(f.name) from None
        raise grade_error("PLC5033", f"{f.name}: cannot be read ({e.strerror})") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise _special_error(f.name)
        if st.st_size > cap:
            raise _size_error(f.name, st.st_size, cap)
        chunks, got = [], 0
        while got <= cap:
            b = os.read(fd, min(1 << 20, cap + 1 - got))
            if not b:
                break
            chunks.append(b)
            got += len(b)
        if got > cap:
            raise _size_error(f.name, got, cap)
    finally:
        os.close(fd)
    return decode_source(b"".join(chunks), f.name)


def decode_source(raw: bytes, name: str = "<source>") -> str:
    """Bytes of a source file as text, as every command reads them
    (:func:`plclab.project.decode_source`: UTF-8, UTF-16 with a BOM, else PLC5052)."""
    from plclab.project import decode_source as decode

    return decode(raw, name)


def read_sources(path: str | os.PathLike, exts: dict[str, str]
                 ) -> tuple[list[tuple[str, str]], list[str]]:
    """``([(text, display name)], ignored names)`` of a submission, with every cap applied."""
    files, ignored = walk_submission(path, exts)
    out: list[tuple[str, str]] = []
    left = MAX_SUBMISSION_BYTES
    for f in files:
        text = read_source(f, left)
        left -= len(text)
        out.append((text, f.name))
    return out, ignored


def _link_error(name: str):
    return grade_error("PLC5030", f"{name} is a symbolic link; links are never followed. "
                       "Submit the file itself, not a link to it")


def _special_error(name: str):
    return grade_error("PLC5033", f"{name} is not a plain file (a device, pipe or socket); "
                       "submit plain source files")


def _size_error(name: str, size: int, cap: int):
    return grade_error("PLC5031", f"{name} is {size / 2**20:.1f} MB; a source file may have "
                       f"at most {cap / 2**20:.0f} MB (a submission {MAX_SUBMISSION_BYTES / 2**20:.0f}"
                       " MB in all). Submit the program's text only")
