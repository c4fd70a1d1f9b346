"""Structured Text front end: tokens -> :mod:`plclab.lang.ast`.

A recursive-descent parser that recovers at statement and declaration boundaries so that
one run reports every syntax error in a file.

IL bodies inside ST files are recognised here (:func:`plclab.lang.frontends.il_lines.is_il_body`) and
kept as pending data on the POU; :func:`parse` stops there, :func:`parse_st_collect` also runs
the lowering stage (:mod:`plclab.lang.lower`) on the file alone.

>>> f = parse_st("PROGRAM P VAR x : INT; END_VAR x := x + 1; END_PROGRAM", "p.st")
>>> f.pous[0].name, type(f.pous[0].body[0]).__name__
('P', 'Assign')
"""


from __future__ import annotations

import re
from functools import cache

from ...errors import Diagnostic, Location, PlcError
from ...suggest import suggest
from .. import ast as A
from ..dialect import current as current_dialect
from ..lexer import Lexer, Token, add_capped
from ..library import STDLIB_FILES, stdlib_filename, stdlib_text
from ..limits import compiler_guard
from ..lower import has_pending, lower_pending
from ..parsing import ParseAbort
from . import oop
from .il_lines import is_il_body, parse_il_body
from .sfc_text import is_sfc_body, parse_sfc_body
from .st_decl import DeclParse
from .st_expr import ExprParse
from .st_stmt import StmtParse
from .st_words import POU_START, SUGGEST, VAR_SECTIONS, found_token

_END_OF = {
    "IF": "END_IF", "CASE": "END_CASE", "FOR": "END_FOR", "WHILE": "END_WHILE",
    "REPEAT": "END_REPEAT", "PROGRAM": "END_PROGRAM", "FUNCTION": "END_FUNCTION",
    "FUNCTION_BLOCK": "END_FUNCTION_BLOCK", "TYPE": "END_TYPE", "STRUCT": "END_STRUCT",
    "TEST": "END_TEST",
}
_NATIVE_RE = re.compile(r"^native\s+'([A-Z][A-Z0-9_]*)'$")
_NATIVE_WORD = re.compile(r"^native\b", re.IGNORECASE)


class Parser(DeclParse, StmtParse, ExprParse):
    """``library=True`` only for plclab's own library files (see :mod:`plclab.runtime.natives`):
    there a ``{native 'NAME'}`` pragma binds a block to its registered implementation. In any
    other file the pragma is an error (PLC0131), so user text never selects Python code."""

    def __init__(self, text: str, file: str = "<input>", library: bool = False) -> None:
        lexer = Lexer(text, file)
        self._setup(lexer.tokens(), file, lexer.diagnostics, lexer.pragmas, library)
        self.il_default = file.lower().endswith(".il")  # a .il file: bodies are IL unless ST
        if not library:
            self._reject_native_pragmas(text)

    @classmethod
    def over_tokens(cls, tokens: list[Token], file: str,
                    diagnostics: list[Diagnostic]) -> Parser:
        """A parser over already-lexed ``tokens`` (one IL line, the inside of a ladder box),
        reporting into ``diagnostics``. Unless the tokens end with EOF, one is added just
        after the last token."""
        p = cls.__new__(cls)
        toks = list(tokens)
        if not toks or toks[-1].kind != "EOF":
            last = toks[-1] if toks else None
            toks.append(Token("EOF", None, "", last.line if last else 1,
                              last.col + len(last.text) if last else 1))
        p._setup(toks, file, diagnostics, [], False)
        p.il_default = False
        return p

    def _setup(self, toks: list[Token], file: str, diagnostics: list[Diagnostic],
               pragmas: list[tuple[int, str]], library: bool) -> None:
        self.toks: list[Token] = toks
        self.diagnostics: list[Diagnostic] = diagnostics
        self.pragmas = pragmas
        self.file = file
        self.library = library
        self.edge_inputs: list[tuple[str, bool, Location]] = []  # R_EDGE/F_EDGE of this POU
        self.i = 0
        self.depth = 0  # nesting of types and initial values (see nested())
        self.expr_depth = 0  # nesting of expr() calls
        self.block_depth = 0  # nesting of statement lists
        self.dialect = current_dialect()

    def _reject_native_pragmas(self, text: str) -> None:
        lines = text.splitlines()
        for line, body in self.pragmas:
            if _NATIVE_WORD.match(body):
                src = lines[line - 1] if 0 < line <= len(lines) else ""
                col = src.find("{") + 1 or 1
                self.diagnostics.append(Diagnostic(
                    "PLC0131", "the {native ...} pragma is reserved for plclab's own block "
                    "library; remove it and write the block's body in ST",
                    Location(self.file, line, col)))

    # -- token helpers ------------------------------------------------------------------------
    @property
    def tok(self) -> Token:
        return self.toks[self.i]

    def peek(self, k: int = 1) -> Token:
        j = min(self.i + k, len(self.toks) - 1)
        return self.toks[j]

    # the helpers below are the parser's inner loop: they index self.toks directly
    def loc(self, tok: Token | None = None) -> Location:
        t = self.toks[self.i] if tok is None else tok
        return Location(self.file, t.line, t.col)

    def advance(self) -> Token:
        i = self.i
        t = self.toks[i]
        if i < len(self.toks) - 1:
            self.i = i + 1
        return t

    def at(self, *kinds: str) -> bool:
        return self.toks[self.i].kind in kinds

    def accept(self, kind: str) -> Token | None:
        i = self.i
        t = self.toks[i]
        if t.kind == kind:
            if i < len(self.toks) - 1:
                self.i = i + 1
            return t
        return None

    def error(self, code: str, msg: str, tok: Token | None = None) -> None:
        add_capped(self.diagnostics, Diagnostic(code, msg, self.loc(tok)), self.file)

    def expect(self, kind: str, what: str | None = None) -> Token:
        i = self.i
        t = self.toks[i]
        if t.kind == kind:
            if i < len(self.toks) - 1:
                self.i = i + 1
            return t
        self.fail_expected(what or _describe(kind))
        raise AssertionError  # unreachable

    def fail_expected(self, what: str) -> None:
        t = self.tok
        found = found_token(t)
        if t.kind == "IDENT":
            close = suggest(t.value, SUGGEST, n=1, cutoff=0.75)
            if close:
                self.error("PLC0011", f"expected {what}, found '{t.text}'; did you mean the "
                           f"keyword {close[0]}?")
                raise ParseAbort
        if t.kind == "==":
            self.error("PLC0012", "'==' is not an ST operator; compare with '=' (and assign "
                       "with ':=')")
            raise ParseAbort
        self.error("PLC0010", f"expected {what}, found {found}")
        raise ParseAbort

    def ensure_progress(self, start: int) -> None:
        """Safety net of every recovery loop: if nothing was consumed since ``start``, report
        the token and skip it, so that no loop can run twice on the same token."""
        if self.i == start and not self.at("EOF"):
            self.error("PLC0010", f"unexpected {found_token(self.tok)} here; remove it or check the "
                       "structure around it")
            self.advance()

    def sync(self, stops: set[str]) -> None:
        """Skip tokens until after a ';' or before one of ``stops``."""
        while not self.at("EOF"):
            if self.tok.kind in stops:
                return
            if self.tok.kind == ";":
                self.advance()
                return
            self.advance()

    # -- file level ---------------------------------------------------------------------------
    def parse_file(self) -> A.SourceFile:
        out = A.SourceFile(self.file)
        actions: list[tuple[Token | None, A.Pou, A.Pou | None]] = []  # CODESYS POU actions
        while not self.at("EOF"):
            start = self.i
            try:
                k = self.tok.kind
                if k in ("PROGRAM", "FUNCTION", "FUNCTION_BLOCK"):
                    out.pous.append(self.pou())
                elif k == "TYPE":
                    out.types.extend(self.type_block())
                elif k == "VAR_GLOBAL":
                    loc = self.loc()
                    out.globals.append(A.GlobalVars(loc, self.var_section()))
                elif k == "CONFIGURATION":
                    out.configs.append(self.configuration())
                elif k == "VAR_CONFIG":  # CODESYS: a global variable list of its own
                    out.config_vars.extend(self.config_section())
                elif k == "TEST":
                    out.tests.append(self.test_block())
                elif oop.word(self, "INTERFACE"):  # object-oriented extensions (ADR 0021)
                    out.pous.append(oop.interface(self))
                elif oop.word(self, "CLASS") and self.peek().kind == "IDENT":
                    out.pous.append(oop.class_pou(self))  # ed.3 6.6.5.2 (ADR 0059)
                elif (oop.word(self, "ACTIONS") or oop.word(self, "ACTION")) and \
                        self.peek().kind == "IDENT":  # actions of a POU (ADR 0035)
                    if not self.dialect.pou_actions:
                        self.error("PLC0198", f"{self.tok.text} of a PROGRAM or FUNCTION_BLOCK "
                                   "is a CODESYS extension (IEC 61131-3 has actions only in "
                                   "SFC); choose {dialect 'codesys'} or call a FUNCTION_BLOCK "
                                   "or METHOD instead")
                        raise ParseAbort
                    before = out.pous[-1] if out.pous else None
                    found = oop.actions_block(self) if oop.word(self, "ACTIONS") else \
                        [oop.action(self)]
                    actions.extend((tok, act, before) for tok, act in found)
                else:
                    t = self.tok
                    close = (suggest(t.value, POU_START, n=1, cutoff=0.7)
                             if t.kind == "IDENT" else [])
                    hint = f"; did you mean {close[0]}?" if close else ""
                    code = "PLC0011" if close else "PLC0010"
                    self.error(code, f"expected PROGRAM, FUNCTION, FUNCTION_BLOCK, TYPE, "
                               f"VAR_GLOBAL, CONFIGURATION or TEST, found {found_token(t)}{hint}")
                    raise ParseAbort
            except (ParseAbort, RecursionError) as exc:
                if isinstance(exc, RecursionError):  # a safety net: the limits should prevent it
                    self.error("PLC0191", "this part of the program is too deeply nested to "
                               "parse; split it into smaller parts (FUNCTIONs, intermediate "
                               "variables)", self.toks[start])
                if self.i == start:
                    self.advance()
                while not self.at("EOF") and self.tok.kind not in POU_START:
                    self.advance()
        oop.attach_actions(self, out, actions)
        return out

    def _native_for(self, line: int) -> str | None:
        if not self.library:
            return None
        for pl, body in self.pragmas:
            if pl in (line - 1, line):
                m = _NATIVE_RE.match(body)
                if m:
                    return m.group(1)
        return None

    def pou(self) -> A.Pou:
        head = self.advance()
        kind = head.kind
        mods = oop.modifiers(self) if kind == "FUNCTION_BLOCK" else []
        name_tok = self.expect("IDENT", f"a name for the {kind}")
        ret = None
        if kind == "FUNCTION":
            if self.accept(":"):
                ret = self.type_ref()
        end_kw = _END_OF[kind]
        extends, implements = oop.header(self, kind) if kind == "FUNCTION_BLOCK" else ([], [])
        decls: list[A.VarDecl] = []
        access: list[A.AccessPath] = []
        while self.tok.kind in VAR_SECTIONS or self.at("VAR_ACCESS"):
            start = self.i
            try:
                if self.at("VAR_ACCESS"):  # a PROGRAM's access paths (ed.2 B.1.5.3, ed.3 B.1.5.3)
                    access.extend(self.access_section())
                else:
                    decls.extend(self.var_section())
            except ParseAbort:
                self.sync({"END_VAR", end_kw} | set(VAR_SECTIONS))
                self.accept("END_VAR")
                self.ensure_progress(start)
        pou = A.Pou(self.loc(head), kind, name_tok.value, decls, [], ret, name_tok.text,
                    native=self._native_for(head.line), extends=extends,
                    implements=implements, modifiers=mods)
        pou.access_paths = access
        if kind == "FUNCTION_BLOCK":  # METHODs before the body (ADR 0021)
            oop.members(self, pou, end_kw)
        body, language, pending = self.pou_body(end_kw)
        if kind == "FUNCTION_BLOCK":  # ... or after it
            oop.members(self, pou, end_kw)
        edges, self.edge_inputs = self.edge_inputs, []
        end_loc = self.loc()
        if not self.accept(end_kw):
            self.missing_end(end_kw, kind, name_tok)
        pou.body, pou.language, pou.end_loc = body, language, end_loc
        if pending is not None:  # IL: lowered once every file is parsed (types are known)
            pou.pending.append(pending)
        if edges:  # R_EDGE / F_EDGE inputs, lowered after the body they qualify
            pou.pending.append(A.PendingBody("EDGE", edges, self.loc(head)))
        return pou

    def missing_end(self, end_kw: str, kind: str, name_tok: Token) -> None:
        """No END_PROGRAM / END_FUNCTION_BLOCK / END_FUNCTION: a syntax error, except where
        the dialect's editor hides them (CODESYS: code copied from its editor has none) and the
        file ends or the next POU begins here; then the warning PLC0280."""
        if not (self.dialect.end_keyword_optional and (
                self.at("EOF") or self.tok.kind in POU_START)):
            self.fail_expected(f"{end_kw} to close {kind} {name_tok.text}")
        add_capped(self.diagnostics, Diagnostic(
            "PLC0280", f"{kind} {name_tok.text[:40]} has no {end_kw}; the CODESYS editor hides "
            f"it, a text file needs it: add {end_kw} before "
            + ("the end of the file" if self.at("EOF") else f"{self.tok.text[:20]}"),
            self.loc(), "warning"), self.file)

    def pou_body(self, end_kw: str) -> tuple[list[A.Stmt], str, A.PendingBody | None]:
        """(statements, language, pending body) of a POU body: ST, or IL when the body looks
        like IL (rule in :func:`plclab.lang.frontends.il.is_il_body`)."""
        if is_il_body(self, end_kw):
            return [], "IL", parse_il_body(self, end_kw)
        if is_sfc_body(self):  # textual SFC: a chart, lowered once every file is parsed
            return [], "SFC", parse_sfc_body(self, end_kw)
        return self.stmt_list({end_kw}), "ST", None

    def test_block(self) -> A.TestBlock:
        head = self.advance()
        if self.at("STRING", "WSTRING"):
            title = self.advance().value
        elif self.at("IDENT"):
            title = self.advance().text
        else:
            self.fail_expected("a test name in quotes, e.g. TEST 'TON fires at PT'")
            title = ""
        decls: list[A.VarDecl] = []
        while self.tok.kind in VAR_SECTIONS:
            decls.extend(self.var_section())
        body = self.stmt_list({"END_TEST"})
        if not self.accept("END_TEST"):
            self.fail_expected("END_TEST")
        return A.TestBlock(self.loc(head), str(title), decls, body)


def _describe(kind: str) -> str:
    return {"IDENT": "a name", "INT": "an integer", "EOF": "the end of the file"}.get(
        kind, f"'{kind}'" if not kind.isalpha() else kind
    )



def parse(text: str, file: str = "<input>",
          library: bool = False) -> tuple[A.SourceFile, list[Diagnostic]]:
    """Parse ST source (IL bodies included) to the tree and its diagnostics; IL bodies stay
    pending (``Pou.pending``) for the lowering stage. ``library`` is for plclab's own library
    files only (see :class:`Parser`)."""
    with compiler_guard():
        p = Parser(text, file, library)
        out = p.parse_file()
    return out, p.diagnostics


def parse_st(text: str, file: str = "<input>") -> A.SourceFile:
    """Parse ST source; raise :class:`PlcError` with every syntax diagnostic if any."""
    out, diags = parse_st_collect(text, file)
    if diags:
        raise PlcError(diags[0].code, diags[0].message, diags[0].location, diagnostics=diags)
    return out


def parse_st_collect(text: str, file: str = "<input>",
                     library: bool = False) -> tuple[A.SourceFile, list[Diagnostic]]:
    """Parse ST source and lower its IL bodies (the file alone, with the standard library's
    declarations); return the tree plus the diagnostics (no exception)."""
    out, diags = parse(text, file, library)
    return out, diags + lower_alone(out)


def parse_library(names: tuple[str, ...] = STDLIB_FILES) -> list[A.SourceFile]:
    """plclab's block library, a fresh copy (a project's checker annotates its own copy);
    ``names``: which library files (default: those every project gets).

    Parsed once a process and dialect; each call unpickles a copy of that first parse (3 times
    faster than parsing, and 10 times faster than ``copy.deepcopy``). The pickle never leaves
    the process and holds only trees parsed from plclab's own files (ADR 0057)."""
    import pickle

    blob = _library_blobs.get((names, _CURRENT_DIALECT()))
    if blob is None:
        files = []
        for name in names:
            f, d = parse(stdlib_text(name), stdlib_filename(name), library=True)
            assert not d, d
            files.append(f)
        _library_blobs[(names, _CURRENT_DIALECT())] = pickle.dumps(
            files, protocol=pickle.HIGHEST_PROTOCOL)
        return files
    with compiler_guard():
        return pickle.loads(blob)


_library_blobs: dict[tuple[tuple[str, ...], str], bytes] = {}
"""The library files parsed, pickled: (names, dialect) -> the pickle (see parse_library)."""


def _CURRENT_DIALECT() -> str:  # noqa: N802 - reads like the constant it is for one parse
    return current_dialect().name


@cache
def library_declarations() -> tuple[A.SourceFile, ...]:
    """The block library parsed once, read-only: the declarations that a file lowered on its
    own needs (the pins of TON, the outputs of CTU...)."""
    return tuple(parse_library())


def lower_alone(*files: A.SourceFile) -> list[Diagnostic]:
    """Lower the pending bodies of ``files`` parsed without a project (the standalone entry
    points ``parse_*_collect``); a project lowers all its files at once instead."""
    if not has_pending(list(files)):
        return []
    return lower_pending(list(files), library_declarations())
