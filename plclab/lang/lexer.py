"""The lexer: source text -> tokens.

Identifiers and keywords are case-insensitive (IEC 61131-3 6.1.2): every identifier is
folded to upper case in ``Token.value`` while ``Token.text`` keeps the spelling.

>>> [t.kind for t in tokenize("x := 16#FF; (* c *)")]
['IDENT', ':=', 'INT', ';', 'EOF']
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ..durations import parse_duration
from ..errors import Diagnostic, Location
from .dialect import current as current_dialect

# CODESYS operators on interface references (ADR 0021): the only names with '__' a user writes
CODESYS_OPERATORS = frozenset({"__ISVALIDREF", "__QUERYINTERFACE"})
KEYWORDS = frozenset(
    """
    PROGRAM END_PROGRAM FUNCTION END_FUNCTION FUNCTION_BLOCK END_FUNCTION_BLOCK
    VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_GLOBAL VAR_EXTERNAL VAR_TEMP VAR_ACCESS VAR_CONFIG END_VAR
    CONSTANT RETAIN NON_RETAIN PERSISTENT AT
    TYPE END_TYPE STRUCT END_STRUCT ARRAY OF STRING WSTRING
    IF THEN ELSIF ELSE END_IF CASE END_CASE FOR TO BY DO END_FOR WHILE END_WHILE
    REPEAT UNTIL END_REPEAT EXIT CONTINUE RETURN
    AND OR XOR NOT MOD TRUE FALSE
    CONFIGURATION END_CONFIGURATION RESOURCE END_RESOURCE ON TASK WITH
    TEST END_TEST
    """.split()
)

# The tokens after which a TEST block may start: the start of a file and the end of a block.
_BLOCK_ENDS = frozenset({None, "END_PROGRAM", "END_FUNCTION", "END_FUNCTION_BLOCK", "END_TYPE",
                         "END_VAR", "END_CONFIGURATION", "END_TEST", ";"})
# ... and the unreserved words that end a block at the top level (ADR 0021, ADR 0035)
_WORD_ENDS = frozenset({"END_INTERFACE", "END_ACTION", "END_ACTIONS"})


def _test_as_name(toks: list[Token]) -> list[Token]:
    """``TEST`` opens a test block only where a block may start (first in the file or after the
    end of one) and when a title follows; anywhere else it is a name like any other, so that
    ``test : BOOL`` and ``IF test THEN`` mean what they say (``test`` is a common variable name
    in real code, and IEC 61131-3 has no TEST keyword)."""
    for i, t in enumerate(toks):
        if t.kind != "TEST":
            continue
        prev = toks[i - 1].kind if i else None
        if prev == "IDENT" and toks[i - 1].value in _WORD_ENDS:
            prev = None
        if prev not in _BLOCK_ENDS or toks[i + 1].kind not in ("STRING", "WSTRING", "IDENT"):
            toks[i] = Token("IDENT", t.value, t.text, t.line, t.col)
    return toks


# Typed-literal prefixes that introduce a time or date literal.
TIME_PREFIXES = {"T": "TIME", "TIME": "TIME", "LT": "LTIME", "LTIME": "LTIME"}
DATE_PREFIXES = {"D": "DATE", "DATE": "DATE", "LD": "LDATE", "LDATE": "LDATE"}
TOD_PREFIXES = {"TOD": "TOD", "TIME_OF_DAY": "TOD", "LTOD": "LTOD", "LTIME_OF_DAY": "LTOD"}
DT_PREFIXES = {"DT": "DT", "DATE_AND_TIME": "DT", "LDT": "LDT", "LDATE_AND_TIME": "LDT"}


@dataclass(slots=True)
class Token:
    kind: str  # IDENT, KEYWORD name, INT, REAL, STRING, WSTRING, TIME, DATE, TOD, DT, ADDR, op, EOF
    value: object
    text: str
    line: int
    col: int
    prefix: str | None = None  # type prefix of a typed literal: INT#5 -> "INT"

    def loc(self, file: str) -> Location:
        return Location(file, self.line, self.col)


_OPERATORS = [
    ":=", "=>", "<>", "<=", ">=", "**", "..", "==", "!=", "?=",
    "+", "-", "*", "/", "<", ">", "=", "(", ")", "[", "]", ",", ";", ":", ".", "&", "^", "#",
]
# IEC 61131-3 identifiers (and CODESYS's rules): a letter or '_' then letters, digits and '_',
# never two '_' in a row (CODESYS reserves '__' for its generated code, as plclab does) and not a
# lone '_'.
IDENTIFIER_RE = re.compile(r"(?!_$)(?!.*__)[A-Za-z_][A-Za-z0-9_]*\Z")


def identifier_problem(name: str) -> str | None:
    """Why ``name`` is not an IEC identifier, or None.

    >>> identifier_problem("Motor_1") is None
    True
    >>> identifier_problem("__import__")
    "'__import__' has two underscores in a row, which identifiers may not have; write '_import_'"
    """
    if IDENTIFIER_RE.match(name):
        return None
    if "__" in name and re.fullmatch(r"[A-Za-z0-9_]+", name):
        fixed = re.sub("_+", "_", name)
        return (f"'{name}' has two underscores in a row, which identifiers may not have; "
                f"write '{fixed}'")
    if name == "_":
        return "'_' alone is not an identifier; add a letter, e.g. '_x'"
    return f"{name!r} is not an identifier (a letter or '_', then letters, digits and '_')"


# Blanks before a token are consumed with it (one match a token, not two); a newline takes
# the next line's indentation along.
_TOKEN_RE = re.compile(
    r"""
    [ \t\r\f\v]*
    (?:
    (?P<ident>[A-Za-z_][A-Za-z0-9_]*(?![A-Za-z0-9_\#]))
  | (?P<op>:=|=>|<>|<=|>=|\*\*|\.\.|==|!=|\?=|[-+*<>=)\[\],;:.&^\#]|\((?!\*)|/(?![/*]))
  | (?P<nl>\n[ \t\r\f\v]*)
  | (?P<lcomment>//[^\n]*)
  | (?P<bcomment>\(\*)
  | (?P<ccomment>/\*)
  | (?P<pragma>\{)
  | (?P<typed>[A-Za-z_][A-Za-z0-9_]*\#)
  | (?P<based>(?:2|8|16)\#[0-9A-Fa-f_]+)
  | (?P<real>[0-9][0-9_]*\.[0-9][0-9_]*(?:[eE][+-]?[0-9]+)?|[0-9][0-9_]*[eE][+-]?[0-9]+)
  | (?P<int>[0-9][0-9_]*)
  | (?P<addr>%[IQM][XBWDL]?[0-9]+(?:\.[0-9]+)*|%[IQM]\*)
  | (?P<partial>%[XBWDLxbwdl][0-9]+)
  | (?P<sstring>')
  | (?P<dstring>")
    )
    """,
    re.VERBOSE,
)

# characters that can never start a token (a superset would be wrong, a subset only slower)
_NEVER_TOKEN = re.compile(r"[^\sA-Za-z0-9_%'\"{}()\[\]+\-*/<>=,;:.&^#!?]+")
_BLANKS = re.compile(r"[ \t]+")
_BLANKS_ANY = re.compile(r"[ \t\r\f\v]+")
MAX_DIGITS = 100  # an integer literal with more digits is an error (PLC0125)
_LTIME_MAX = (1 << 63) - 1  # ns
_DATE_MAX_S = (1 << 32) - 1  # DATE and DT: unsigned 32-bit seconds since 1970, as on S7/CODESYS
_ESCAPES = {"$": "$", "'": "'", '"': '"', "L": "\n", "N": "\n", "P": "\f", "R": "\r", "T": "\t"}


# At most this many diagnostics are kept per file; then one PLC0128 says there are more.
MAX_DIAGNOSTICS_PER_FILE = 100


def too_many_diagnostics(file: str, where: Location | None) -> Diagnostic:
    """The one diagnostic that replaces everything beyond the cap of a file (located at the
    first one left out)."""
    return Diagnostic("PLC0128", f"too many errors in {file}; only the first "
                      f"{MAX_DIAGNOSTICS_PER_FILE} are shown: fix these first", where)


def add_capped(diags: list[Diagnostic], d: Diagnostic, file: str) -> None:
    """Append ``d`` unless the file already has its cap of diagnostics."""
    if len(diags) < MAX_DIAGNOSTICS_PER_FILE:
        diags.append(d)
    elif len(diags) == MAX_DIAGNOSTICS_PER_FILE:
        diags.append(too_many_diagnostics(file, d.location))


def cap_per_file(diags: list[Diagnostic]) -> list[Diagnostic]:
    """Keep at most :data:`MAX_DIAGNOSTICS_PER_FILE` diagnostics of each file, errors before
    warnings, in their order; then one PLC0128 for each file that had more."""
    by_file: dict[str, list[Diagnostic]] = {}
    for d in diags:
        by_file.setdefault(d.location.file if d.location is not None else "", []).append(d)
    keep: set[int] = set()
    notes: list[Diagnostic] = []
    for f, ds in by_file.items():
        if len(ds) <= MAX_DIAGNOSTICS_PER_FILE:
            keep.update(id(d) for d in ds)
            continue
        ranked = [d for d in ds if d.severity == "error" and d.code != "PLC0128"]
        ranked += [d for d in ds if d.severity != "error"]
        shown = ranked[:MAX_DIAGNOSTICS_PER_FILE]
        keep.update(id(d) for d in shown)
        first_left_out = next(d for d in ds if id(d) not in keep)
        notes.append(too_many_diagnostics(f, first_left_out.location))
    return [d for d in diags if id(d) in keep] + notes


class Lexer:
    """Turns one source file into a token list, collecting diagnostics on the way."""

    def __init__(self, text: str, file: str = "<input>") -> None:
        self.text = text
        self.file = file
        self.diagnostics: list[Diagnostic] = []
        self.pragmas: list[tuple[int, str]] = []
        self.nested_comments = current_dialect().nested_comments

    def warn(self, code: str, msg: str, line: int, col: int) -> None:
        add_capped(self.diagnostics, Diagnostic(code, msg, Location(self.file, line, col),
                                                "warning"), self.file)

    def error(self, code: str, msg: str, line: int, col: int) -> None:
        add_capped(self.diagnostics, Diagnostic(code, msg, Location(self.file, line, col)),
                   self.file)

    def _bad_run(self, pos: int, line: int, col: int) -> int:
        """Report a run of characters that start no token (blanks between them included) as
        one diagnostic; return where the run ends."""
        text, n, match = self.text, len(self.text), _TOKEN_RE.match
        end, last = pos + 1, pos
        while end < n:
            m = _NEVER_TOKEN.match(text, end)  # fast path: many at once
            if m is not None:
                last, end = m.end() - 1, m.end()
                continue
            blank = _BLANKS.match(text, end)
            j = blank.end() if blank else end
            if j < n and text[j] not in " \t\r\f\v\n" and match(text, j) is None:
                end, last = j + 1, j
                continue
            break
        end = last + 1
        ch = text[pos]
        more = f" (and {end - pos - 1} more up to column {col + end - pos - 1})" \
            if end - pos > 1 else ""
        self.error("PLC0001", f"unexpected character {ch!r}{more}; remove it (ST uses only "
                   "ASCII letters, digits, operators and quotes outside comments and strings)",
                   line, col)
        return end

    def tokens(self) -> list[Token]:
        text, pos, line, line_start = self.text, 0, 1, 0
        out: list[Token] = []
        append = out.append
        n = len(text)
        match = _TOKEN_RE.match
        keywords = KEYWORDS
        while pos < n:
            m = match(text, pos)
            if m is None:  # skip the blanks, then a character that starts no token, or the end
                blank = _BLANKS_ANY.match(text, pos)
                if blank is not None:
                    pos = blank.end()
                    if pos >= n:
                        break
                    m = match(text, pos)
                if m is None:
                    pos = self._bad_run(pos, line, pos - line_start + 1)
                    continue
            kind = m.lastgroup
            end = m.end()
            s = m.group(kind)
            pos = end - len(s)  # where the token starts (after the blanks)
            col = pos - line_start + 1
            # the common tokens first
            if kind == "ident":
                up = s.upper()
                if ("__" in s or s == "_") and up not in CODESYS_OPERATORS:
                    self.error("PLC0006", identifier_problem(s) or "bad identifier", line, col)
                append(Token(up if up in keywords else "IDENT", up, s, line, col))
                pos = end
                continue
            if kind == "op":
                append(Token(s, s, s, line, col))
                pos = end
                continue
            if kind == "nl":
                line += 1
                line_start = pos + 1
                pos = end
                continue
            if kind == "lcomment":
                pos = end
                continue
            if kind in ("bcomment", "ccomment"):
                end_pos, line, line_start = self._skip_comment(pos, line, line_start, kind)
                pos = end_pos
                continue
            if kind == "pragma" and text.startswith("{{", pos):
                # MATIEC's inline C (Beremiz): {{ C code }} -- skipped, like any pragma
                end = text.find("}}", pos + 2)
                if end < 0:
                    self.error("PLC0002", "inline code '{{' is never closed with '}}'", line, col)
                    pos = n
                    continue
                self.warn("PLC0172", "MATIEC inline C code {{ ... }} is skipped: plclab does not "
                          "run C; write the logic in ST", line, col)
                body = text[pos + 2:end]
                nl = body.count("\n")
                if nl:
                    line += nl
                    line_start = pos + 2 + body.rfind("\n") + 1
                pos = end + 2
                continue
            if kind == "pragma":
                end = text.find("}", pos)
                if end < 0:
                    self.error("PLC0002", "pragma '{' is never closed with '}'", line, col)
                    pos = n
                    continue
                body = text[pos + 1:end]
                self.pragmas.append((line, body.strip()))
                nl = body.count("\n")
                if nl:
                    line += nl
                    line_start = pos + 1 + body.rfind("\n") + 1
                pos = end + 1
                continue
            if kind in ("sstring", "dstring"):
                tok, pos, ok = self._string(pos, line, col, kind == "dstring")
                if tok is not None:
                    append(tok)
                continue
            if kind == "typed":
                prefix = s[:-1].upper()
                tok, newpos = self._typed(prefix, end, line, col, s)
                if tok is not None:
                    append(tok)
                    pos = newpos
                    continue
                # Not a literal prefix: emit identifier and '#'
                append(Token("IDENT", prefix, s[:-1], line, col))
                append(Token("#", "#", "#", line, col + len(s) - 1))
                pos = end
                continue
            pos = end
            if kind == "int":
                append(Token("INT", self._int(s, s, line, col), s, line, col))
            elif kind == "based":
                base, digits = s.split("#", 1)
                append(self._based(int(base), digits, s, line, col))
            elif kind == "real":
                append(Token("REAL", self._real(s, s, line, col), s, line, col))
            elif kind == "addr":
                append(Token("ADDR", s.upper(), s, line, col))
            else:  # partial: w.%X15, w.%B1 (IEC ed.3 Table 17)
                append(Token("PARTIAL", s.upper(), s, line, col))
        append(Token("EOF", None, "", line, pos - line_start + 1))
        return _test_as_name(out)

    # -- pieces -------------------------------------------------------------------------
    def _skip_comment(self, pos: int, line: int, line_start: int, kind: str) -> tuple[int, int, int]:
        text = self.text
        start_line, start_col = line, pos - line_start + 1
        close = text.find(_EXP_END, pos) if text.startswith(_EXP_START, pos) else -1
        if close >= 0:
            # a CODESYS 2.3 export (.EXP, as OSCAT is published): the free text between
            # (*@KEY@:DESCRIPTION*) and (*@KEY@:END_DESCRIPTION*) is the POU's description
            seg = text[pos:close + len(_EXP_END)]
        elif kind == "ccomment":
            end = text.find("*/", pos + 2)
            if end < 0:
                self.error("PLC0002", "comment '/*' is never closed; add '*/'", start_line, start_col)
                return len(text), line, line_start
            seg = text[pos:end + 2]
        elif not self.nested_comments:  # ed.2, MATIEC, S7: the first '*)' ends the comment
            end = text.find("*)", pos + 2)
            if end < 0:
                self.error("PLC0002", "comment '(*' is never closed; add '*)'", start_line,
                           start_col)
                return len(text), line, line_start
            seg = text[pos:end + 2]
        else:
            depth, i = 0, pos
            n = len(text)
            while i < n:
                if text.startswith("(*", i):
                    depth += 1
                    i += 2
                elif text.startswith("*)", i):
                    depth -= 1
                    i += 2
                    if depth == 0:
                        break
                else:
                    i += 1
            if depth:
                self.error("PLC0002", "comment '(*' is never closed; add '*)' (comments nest, so "
                           "each '(*' needs its own '*)')", start_line, start_col)
                i = n
            seg = text[pos:i]
            end = i - 2
        nl = seg.count("\n")
        if nl:
            line += nl
            line_start = pos + seg.rfind("\n") + 1
        return pos + len(seg), line, line_start

    def _string(self, pos: int, line: int, col: int, wide: bool) -> tuple[Token | None, int, bool]:
        text, quote = self.text, self.text[pos]
        i, n, buf = pos + 1, len(self.text), []
        doubled = False
        while i < n:
            c = text[i]
            if c == quote and text[i + 1:i + 2] == quote:  # 'it''s' (SQL, Pascal): not ST
                if not doubled:  # one error a string
                    self.error("PLC0003", f"a doubled {quote}{quote} inside a string ends it in "
                               f"ST (CODESYS and TwinCAT too); write the quote as ${quote}, e.g. "
                               f"{quote}it${quote}s{quote}", line, col + i - pos)
                doubled = True
                buf.append(c)
                i += 2
                continue
            if c == quote:
                s = "".join(buf)
                kind = "WSTRING" if wide else "STRING"
                return Token(kind, s, text[pos:i + 1], line, col), i + 1, True
            if c == "\n":
                break
            if c == "$":
                nxt = text[i + 1:i + 2]
                if nxt.upper() in _ESCAPES:
                    buf.append(_ESCAPES[nxt.upper()])
                    i += 2
                    continue
                width = 4 if wide else 2
                hexs = text[i + 1:i + 1 + width]
                if len(hexs) == width and all(h in "0123456789abcdefABCDEF" for h in hexs):
                    buf.append(chr(int(hexs, 16)))
                    i += 1 + width
                    continue
                self.error("PLC0003", f"unknown escape '${nxt}' in string; use $$ for a dollar sign, "
                           "$' for a quote, $N/$L newline, $R, $T, $P or $hh", line, col + i - pos)
                i += 1
                continue
            buf.append(c)
            i += 1
        self.error("PLC0003", f"string is never closed; add the closing {quote} on the same line",
                   line, col)
        return None, i, False

    def _int(self, digits: str, text: str, line: int, col: int) -> int:
        """A decimal literal's value; more than :data:`MAX_DIGITS` digits is PLC0125 (and
        would exceed Python's int-from-text limit)."""
        clean = digits.replace("_", "")
        if len(clean) > MAX_DIGITS:
            self._too_long(text, len(clean), line, col)
            return 0
        return int(clean)

    def _too_long(self, text: str, n: int, line: int, col: int) -> None:
        self.error("PLC0125", f"'{text[:20]}...' has {n} digits; no integer type holds more "
                   "than 20 decimal digits (ULINT: 18446744073709551615)", line, col)

    def _real(self, digits: str, text: str, line: int, col: int) -> float:
        """A REAL literal's value; beyond LREAL's range is PLC0125 (it would become inf)."""
        v = float(digits.replace("_", ""))
        if math.isinf(v):
            shown = text if len(text) <= 24 else text[:20] + "..."
            self.error("PLC0125", f"{shown} is too large for LREAL (at most about 1.8E308); use "
                       "a smaller value", line, col)
            return 0.0
        return v

    def _based(self, base: int, digits: str, s: str, line: int, col: int, prefix=None) -> Token:
        clean = digits.replace("_", "")
        if len(clean) > MAX_DIGITS:
            self._too_long(s, len(clean), line, col)
            return Token("INT", 0, s, line, col, prefix)
        try:
            value = int(clean, base)
        except ValueError:
            self.error("PLC0004", f"'{s}' is not a valid base-{base} number", line, col)
            value = 0
        return Token("INT", value, s, line, col, prefix)

    def _typed(self, prefix: str, pos: int, line: int, col: int, head: str):
        """A literal with a type prefix: INT#5, T#5s, D#2024-01-31, BOOL#TRUE, Color#Red..."""
        text = self.text
        if prefix in TIME_PREFIXES:
            m = re.compile(r"[-+]?[0-9A-Za-z_.]+").match(text, pos)
            if not m:
                self.error("PLC0005", f"'{head}' must be followed by a duration such as T#1s500ms",
                           line, col)
                return Token("TIME", 0, head, line, col, TIME_PREFIXES[prefix]), pos
            s = m.group()
            ns = parse_duration(s, iec=True)
            if ns is not None and not (-_LTIME_MAX - 1 <= ns <= _LTIME_MAX):
                shown = head + (s if len(s) <= 30 else s[:26] + "...")
                self.error("PLC0126", f"'{shown}' is out of range: durations reach at most "
                           "about 106751 days (LTIME, 64 bits of ns) and TIME "
                           "24d20h31m23s647ms", line, col)
                ns = 0
            elif ns is None:
                self.error("PLC0005", f"'{head}{s[:30]}' is not a valid duration; write e.g. T#1h2m3s4ms, "
                           "T#2s_200ms or T#-5s (units d, h, m, s, ms, us, ns)", line, col)
                ns = 0
            return Token("TIME", ns, head + s, line, col, TIME_PREFIXES[prefix]), m.end()
        for table, kind, pattern in (
            (DATE_PREFIXES, "DATE", r"[0-9]{4}-[0-9]{1,2}-[0-9]{1,2}"),
            (TOD_PREFIXES, "TOD", r"[0-9]{1,2}:[0-9]{1,2}(?::[0-9]{1,2}(?:\.[0-9]+)?)?"),
            (DT_PREFIXES, "DT",
             r"[0-9]{4}-[0-9]{1,2}-[0-9]{1,2}-[0-9]{1,2}:[0-9]{1,2}(?::[0-9]{1,2}(?:\.[0-9]+)?)?"),
        ):
            if prefix in table:
                m = re.compile(pattern).match(text, pos)
                if not m:
                    examples = {"DATE": "D#2024-01-31", "TOD": "TOD#14:32:07.77",
                                "DT": "DT#2024-01-31-14:32:07"}
                    self.error("PLC0005", f"bad {kind} literal after '{head}'; write e.g. "
                               f"{examples[kind]}", line, col)
                    return Token(kind, 0, head, line, col, table[prefix]), pos
                s = m.group()
                try:
                    value = parse_datetime_literal(kind, s)
                except ValueError:
                    self.error("PLC0005", f"'{head}{s}' is not a valid calendar value", line, col)
                    value = 0
                if kind in ("DATE", "DT") and not _date_in_range(kind, value):
                    self.error("PLC0126", f"'{head}{s}' is out of range: {kind} holds "
                               "1970-01-01 to 2106-02-07 (32-bit seconds, as on the PLC)",
                               line, col)
                    value = 0
                return Token(kind, value, head + s, line, col, table[prefix]), m.end()
        # numeric or boolean or enum with a type prefix
        m = _TOKEN_RE.match(text, pos)
        if m and m.lastgroup in ("int", "real", "based"):
            s = m.group()
            if m.lastgroup == "int":
                tok = Token("INT", self._int(s, head + s, line, col), head + s, line, col,
                            prefix)
            elif m.lastgroup == "real":
                tok = Token("REAL", self._real(s, head + s, line, col), head + s, line, col,
                            prefix)
            else:
                b, d = s.split("#", 1)
                tok = self._based(int(b), d, head + s, line, col, prefix)
            return tok, m.end()
        if m and m.lastgroup == "op" and m.group() in "+-":
            m2 = _TOKEN_RE.match(text, m.end())
            if m2 and m2.lastgroup in ("int", "real"):
                s = m2.group()
                text = head + m.group() + s
                v = self._int(s, text, line, col) if m2.lastgroup == "int" else \
                    self._real(s, text, line, col)
                if m.group() == "-":
                    v = -v
                kind = "INT" if m2.lastgroup == "int" else "REAL"
                return Token(kind, v, head + m.group() + m2.group(), line, col, prefix), m2.end()
        if m and m.lastgroup == "ident":
            up = m.group().upper()
            if up in ("TRUE", "FALSE"):
                return Token("INT", 1 if up == "TRUE" else 0, head + m.group(), line, col,
                             prefix), m.end()
            # Enum#Value : a qualified enumeration value
            return Token("ENUMVAL", (prefix, up), head + m.group(), line, col, prefix), m.end()
        if m and m.lastgroup == "sstring" or (m and m.lastgroup == "dstring"):
            tok, newpos, ok = self._string(m.start(), line, col, m.lastgroup == "dstring")
            if tok is not None:
                tok.prefix = prefix
            return tok, newpos
        return None, pos


def _date_in_range(kind: str, value: int) -> bool:
    seconds = value if kind == "DATE" else value // 1000
    return 0 <= seconds <= _DATE_MAX_S


def parse_datetime_literal(kind: str, s: str) -> int:
    """DATE -> seconds since 1970-01-01; TOD -> ms since midnight; DT -> seconds since epoch
    (milliseconds kept as a fraction are dropped to whole ms for TOD only).

    >>> parse_datetime_literal("TOD", "14:32:07.77")
    52327770
    """
    import datetime as _dt

    if kind == "DATE":
        y, mo, d = (int(x) for x in s.split("-"))
        return int((_dt.date(y, mo, d) - _dt.date(1970, 1, 1)).total_seconds())
    if kind == "TOD":
        return _tod_ms(s)
    y, mo, d, rest = s.split("-", 3)
    day = _dt.date(int(y), int(mo), int(d))
    ms = _tod_ms(rest)
    return int((day - _dt.date(1970, 1, 1)).total_seconds()) * 1000 + ms


def _tod_ms(s: str) -> int:
    parts = s.split(":")
    h, m = int(parts[0]), int(parts[1])
    sec = float(parts[2]) if len(parts) > 2 else 0.0
    if not (0 <= h < 24 and 0 <= m < 60 and 0 <= sec < 60):
        raise ValueError(s)
    return h * 3_600_000 + m * 60_000 + round(sec * 1000)


_EXP_START, _EXP_END = "(*@KEY@:DESCRIPTION*)", "(*@KEY@:END_DESCRIPTION*)"


def tokenize(text: str, file: str = "<input>") -> list[Token]:
    """Tokenize ``text``; raises nothing, diagnostics are dropped (use :class:`Lexer`)."""
    return Lexer(text, file).tokens()
