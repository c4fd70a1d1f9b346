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
from contextlib import contextmanager
from functools import cache

from ...errors import Diagnostic, Location, PlcError
from ...suggest import suggest
from .. import ast as A
from ..addresses import canonical, hierarchical
from ..datasize import NESTING_LIMIT
from ..dialect import current as current_dialect
from ..lexer import KEYWORDS, Lexer, Token, add_capped
from ..library import STDLIB_FILES, stdlib_filename, stdlib_text
from ..limits import MAX_BLOCK_NESTING, MAX_EXPR_NESTING, compiler_guard, too_deep_message
from ..lower import has_pending, lower_pending
from ..parsing import ParseAbort
from ..types import lookup_elementary
from . import oop
from .il_lines import is_il_body, parse_il_body
from .sfc_text import is_sfc_body, parse_sfc_body

# words worth suggesting in "did you mean": keywords plus those of later language extensions
SUGGEST = KEYWORDS | {"EXTENDS", "IMPLEMENTS", "METHOD", "END_METHOD", "INTERFACE",
                      "END_INTERFACE", "PROPERTY", "END_PROPERTY", "THIS", "SUPER"}

_END_OF = {
    "IF": "END_IF", "CASE": "END_CASE", "FOR": "END_FOR", "WHILE": "END_WHILE",
    "REPEAT": "END_REPEAT", "PROGRAM": "END_PROGRAM", "FUNCTION": "END_FUNCTION",
    "FUNCTION_BLOCK": "END_FUNCTION_BLOCK", "TYPE": "END_TYPE", "STRUCT": "END_STRUCT",
    "TEST": "END_TEST",
}
_VAR_SECTIONS = ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_GLOBAL", "VAR_EXTERNAL",
                 "VAR_TEMP")
_STMT_END = {"END_IF", "ELSIF", "ELSE", "END_CASE", "END_FOR", "END_WHILE", "UNTIL",
             "END_REPEAT", "END_PROGRAM", "END_FUNCTION", "END_FUNCTION_BLOCK", "END_TEST", "EOF"}
_POU_START = {"PROGRAM", "FUNCTION", "FUNCTION_BLOCK", "TYPE", "VAR_GLOBAL", "CONFIGURATION",
              "TEST", "VAR_CONFIG"}
# tokens where a declaration cannot continue: a new section, a new POU, the end of a body
_DECL_STOP = set(_VAR_SECTIONS) | _POU_START | _STMT_END | {"END_TYPE", "END_STRUCT",
                                                             "END_CONFIGURATION", "END_RESOURCE"}
_CMP = {"=": "=", "<>": "<>", "<": "<", "<=": "<=", ">": ">", ">=": ">="}
# binary operator token -> (precedence, AST operator); higher binds tighter
_BINARY = {
    "OR": (1, "OR"), "XOR": (2, "XOR"), "AND": (3, "AND"), "&": (3, "AND"),
    "=": (4, "="), "<>": (4, "<>"), "==": (4, "="), "!=": (4, "<>"),
    "<": (5, "<"), "<=": (5, "<="), ">": (5, ">"), ">=": (5, ">="),
    "+": (6, "+"), "-": (6, "-"), "*": (7, "*"), "/": (7, "/"), "MOD": (7, "MOD"),
    "**": (8, "**"),
}
_NATIVE_RE = re.compile(r"^native\s+'([A-Z][A-Z0-9_]*)'$")
_NATIVE_WORD = re.compile(r"^native\b", re.IGNORECASE)


_OPERATOR_FUNCTIONS = ("AND", "OR", "XOR", "MOD", "NOT")


class _TooDeep(ParseAbort):
    """Internal: nesting beyond the limits (PLC0190 is reported). Statements do not recover
    from it one by one (that would report every level again): the body is skipped."""


class Parser:
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
        found = _found(t)
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
            self.error("PLC0010", f"unexpected {_found(self.tok)} here; remove it or check the "
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
                    close = (suggest(t.value, _POU_START, n=1, cutoff=0.7)
                             if t.kind == "IDENT" else [])
                    hint = f"; did you mean {close[0]}?" if close else ""
                    code = "PLC0011" if close else "PLC0010"
                    self.error(code, f"expected PROGRAM, FUNCTION, FUNCTION_BLOCK, TYPE, "
                               f"VAR_GLOBAL, CONFIGURATION or TEST, found {_found(t)}{hint}")
                    raise ParseAbort
            except (ParseAbort, RecursionError) as exc:
                if isinstance(exc, RecursionError):  # a safety net: the limits should prevent it
                    self.error("PLC0191", "this part of the program is too deeply nested to "
                               "parse; split it into smaller parts (FUNCTIONs, intermediate "
                               "variables)", self.toks[start])
                if self.i == start:
                    self.advance()
                while not self.at("EOF") and self.tok.kind not in _POU_START:
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
        while self.tok.kind in _VAR_SECTIONS or self.at("VAR_ACCESS"):
            start = self.i
            try:
                if self.at("VAR_ACCESS"):  # a PROGRAM's access paths (ed.2 B.1.5.3, ed.3 B.1.5.3)
                    access.extend(self.access_section())
                else:
                    decls.extend(self.var_section())
            except ParseAbort:
                self.sync({"END_VAR", end_kw} | set(_VAR_SECTIONS))
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
                self.at("EOF") or self.tok.kind in _POU_START)):
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
        while self.tok.kind in _VAR_SECTIONS:
            decls.extend(self.var_section())
        body = self.stmt_list({"END_TEST"})
        if not self.accept("END_TEST"):
            self.fail_expected("END_TEST")
        return A.TestBlock(self.loc(head), str(title), decls, body)

    def configuration(self) -> A.Configuration:
        head = self.advance()
        name = self.expect("IDENT", "a configuration name").value
        cfg = A.Configuration(self.loc(head), name, [], [], [])
        while not self.at("END_CONFIGURATION", "EOF"):
            if self.at("VAR_GLOBAL"):
                cfg.globals.extend(self.var_section())
            elif self.at("VAR_CONFIG"):
                cfg.config_vars.extend(self.config_section())
            elif self.at("VAR_ACCESS"):
                cfg.access_paths.extend(self.access_section())
            elif self.accept("RESOURCE"):
                res = str(self.expect("IDENT", "a resource name").value)
                cfg.resources.append(res)
                if self.accept("ON"):
                    self.expect("IDENT", "a processor type")
                while not self.at("END_RESOURCE", "EOF"):
                    if self.at("VAR_GLOBAL"):
                        cfg.resource_globals.setdefault(res, []).extend(self.var_section())
                    elif self.at("TASK"):
                        cfg.tasks.append(self.task_decl())
                        cfg.tasks[-1].resource = res
                    elif self.at("PROGRAM"):
                        cfg.instances.append(self.program_instance())
                        cfg.instances[-1].resource = res
                    else:
                        self.fail_expected("TASK, PROGRAM or END_RESOURCE")
                self.expect("END_RESOURCE")
                self.accept(";")
            elif self.at("TASK"):
                cfg.tasks.append(self.task_decl())
            elif self.at("PROGRAM"):
                cfg.instances.append(self.program_instance())
            else:
                self.fail_expected("RESOURCE, TASK, PROGRAM, VAR_GLOBAL, VAR_CONFIG, VAR_ACCESS "
                                   "or END_CONFIGURATION")
        self.expect("END_CONFIGURATION")
        cfg.settle_resources()
        return cfg

    def instance_path(self, what: str) -> tuple[list[Token], Token | None]:
        """``STATION_1.P1.FB1.C2`` (names) or ``STATION_1.%IX1.1`` (names, then an address)."""
        parts = [self.expect("IDENT", what)]
        while self.accept("."):
            if self.at("ADDR"):
                return parts, self.advance()
            parts.append(self.expect("IDENT", "a name after '.'"))
        return parts, None

    def config_section(self) -> list[A.ConfigVar]:
        """``VAR_CONFIG path [AT %addr] : type [:= value]; ... END_VAR``."""
        self.advance()
        out: list[A.ConfigVar] = []
        while not self.at("END_VAR", "EOF") and self.tok.kind not in _DECL_STOP:
            start = self.i
            try:
                parts, _ = self.instance_path("an instance path such as Main.fb1.x")
                address = None
                if self.accept("AT"):
                    address = self.address(self.expect("ADDR", "a direct address such as "
                                                       "%IX0.0"))
                self.expect(":", "':' and the variable's type")
                tref = self.type_ref()
                init = self.initializer() if self.accept(":=") else None
                if not self.accept(";"):
                    self.fail_expected("';' after the VAR_CONFIG line")
                out.append(A.ConfigVar(self.loc(parts[0]), [p.value for p in parts],
                                       ".".join(p.text for p in parts), address, tref, init))
            except ParseAbort:
                self.sync({"END_VAR"} | _DECL_STOP)
                self.ensure_progress(start)
        self.expect("END_VAR")
        return out

    def access_section(self) -> list[A.AccessPath]:
        """``VAR_ACCESS name : path : type [READ_ONLY | READ_WRITE]; ... END_VAR``."""
        self.advance()
        out: list[A.AccessPath] = []
        while not self.at("END_VAR", "EOF") and self.tok.kind not in _DECL_STOP:
            start = self.i
            try:
                name = self.expect("IDENT", "the access path's name")
                self.expect(":", "':' and the path it names")
                parts, addr = self.instance_path("a variable path such as P1.x")
                path = [p.value for p in parts] + ([canonical(addr.value)] if addr else [])
                spelled = ".".join([p.text for p in parts] + ([addr.text] if addr else []))
                self.expect(":", "':' and the type")
                tref = self.type_ref()
                read_only = True
                if self.at("IDENT") and self.tok.value in ("READ_ONLY", "READ_WRITE"):
                    read_only = self.advance().value == "READ_ONLY"
                if not self.accept(";"):
                    self.fail_expected("';' after the VAR_ACCESS line")
                out.append(A.AccessPath(self.loc(name), name.value, name.text, path, spelled,
                                        tref, read_only))
            except ParseAbort:
                self.sync({"END_VAR"} | _DECL_STOP)
                self.ensure_progress(start)
        self.expect("END_VAR")
        return out

    def task_decl(self) -> A.TaskDecl:
        head = self.advance()
        name = self.expect("IDENT", "a task name").value
        task = A.TaskDecl(self.loc(head), name, None, None)
        self.expect("(")
        while not self.at(")"):
            key = self.expect("IDENT", "INTERVAL, PRIORITY or SINGLE").value
            self.expect(":=")
            val = self.expr()
            if key == "INTERVAL":
                task.interval = val
            elif key == "PRIORITY":
                task.priority = val
            elif key == "SINGLE":
                task.single = val
            else:
                self.error("PLC0010", f"unknown task property {key}; use INTERVAL, PRIORITY "
                           "or SINGLE")
            if not self.accept(","):
                break
        self.expect(")")
        self.expect(";")
        return task

    def program_instance(self) -> A.ProgramInstance:
        head = self.advance()
        name = self.expect("IDENT", "a program instance name").value
        task = None
        if self.accept("WITH"):
            task = self.expect("IDENT", "a task name").value
        self.expect(":")
        prog_tok = self.expect("IDENT", "a program type name")
        call = None
        if self.at("("):  # connections (ed.3 Figure 21): inputs from, outputs to, the outside
            loc = self.loc()
            self.advance()
            args = self.call_args()
            call = A.Call(loc, A.Name(self.loc(prog_tok), prog_tok.value, prog_tok.text), args)
        self.expect(";")
        return A.ProgramInstance(self.loc(head), name, task, prog_tok.value, call)

    # -- declarations -------------------------------------------------------------------------
    def var_section(self) -> list[A.VarDecl]:
        sec_tok = self.advance()
        section = sec_tok.kind
        constant = retain = False
        while self.at("CONSTANT", "RETAIN", "NON_RETAIN", "PERSISTENT") or (
                oop.word(self, *oop.ACCESS) and self.peek().kind == "IDENT"):
            # ed.3 Annex A var_decls: VAR [CONSTANT] [PUBLIC|PRIVATE|PROTECTED|INTERNAL]; the
            # access specifier of a class's variables is read and not enforced (ADR 0059)
            k = self.advance().kind
            constant |= k == "CONSTANT"
            retain |= k in ("RETAIN", "PERSISTENT")
        out: list[A.VarDecl] = []
        while not self.at("END_VAR"):
            if self.tok.kind in _DECL_STOP:
                # a section or POU starts before this one is closed: report it and let the
                # caller go on from here (never loop on the same token)
                self.error("PLC0010", f"expected END_VAR to close the {section} section opened "
                           f"at line {sec_tok.line}, found {_found(self.tok)}; add END_VAR "
                           "before it")
                raise ParseAbort
            start = self.i
            try:
                out.extend(self.var_decl(section, constant, retain))
            except ParseAbort:
                self.sync({"END_VAR"} | _DECL_STOP)
                self.ensure_progress(start)
        self.expect("END_VAR")
        return out

    def var_decl(self, section: str, constant: bool, retain: bool) -> list[A.VarDecl]:
        if self.at("AT"):  # unnamed: AT %IX1.1 : BOOL; (IEC 61131-3 ed.3 Table 16)
            at = self.tok
            names = [Token("IDENT", "", "", at.line, at.col)]
        else:
            names = [self.expect("IDENT", "a variable name")]
            while self.accept(","):
                names.append(self.expect("IDENT", "a variable name"))
        address = None
        if self.accept("AT"):
            address = self.address(self.expect("ADDR", "a direct address such as %IX0.0"))
            if not names[0].value:  # the unnamed variable is called by its address
                text = address.replace("%", "").replace(".", "_")
                names = [Token("IDENT", f"AT_{text}", address, names[0].line, names[0].col)]
        if self.at(":="):
            self.error("PLC0010", "a declaration needs a type before the initial value: "
                       "write  name : TYPE := value;")
            raise ParseAbort
        self.expect(":", "':' and a type")
        tref = self.type_ref()
        if self.at("IDENT") and self.tok.value in ("R_EDGE", "F_EDGE"):
            self.edge_qualifier(section, tref, names)
        init = None
        if self.accept(":="):
            init = self.initializer()
        if not self.accept(";"):
            self.fail_expected("';' after the declaration")
        return [
            A.VarDecl(self.loc(n), n.value, tref, init, address, section, constant, retain, n.text)
            for n in names
        ]

    def edge_qualifier(self, section: str, tref: A.TypeRef, names: list[Token]) -> None:
        """``x : BOOL R_EDGE;`` (IEC 61131-3 ed.3 6.5.2.2): recorded for the lowering stage
        (:mod:`plclab.lang.lower.edges`); only a BOOL VAR_INPUT may carry it (PLC0179)."""
        qualifier = self.advance()
        if section != "VAR_INPUT" or not (isinstance(tref, A.NamedTypeRef)
                                          and tref.name == "BOOL"):
            self.error("PLC0179", f"{qualifier.value} qualifies a BOOL input only: declare "
                       f"it as  name : BOOL {qualifier.value};  in VAR_INPUT", qualifier)
            return
        self.edge_inputs.extend((n.value, qualifier.value == "R_EDGE", self.loc(n))
                                for n in names)

    def address(self, t: Token) -> str:
        """A direct address in its canonical form (:mod:`plclab.lang.addresses`); a
        hierarchical one is read by its last field, with a warning."""
        words = self.dialect.hierarchical_words
        address = canonical(t.value, words)
        if t.value != address and hierarchical(t.value, words):
            add_capped(self.diagnostics, Diagnostic(
                "PLC0175", f"{t.text[:40]} is hierarchical; plclab's process image is flat, so "
                f"it is read as {address} (the leading fields name hardware a simulated PLC "
                "does not have); write the flat address to say so", self.loc(t), "warning"),
                self.file)
        return address

    def initializer(self) -> A.Expr:
        if self.at("["):
            with self.nested("initial value"):
                return self.array_init()
        if self.at("(") and self.peek().kind == "IDENT" and self.peek(2).kind == ":=":
            with self.nested("initial value"):
                return self.struct_init()
        return self.expr()

    def array_init(self) -> A.ArrayInit:
        start = self.advance()
        items: list[tuple[A.Expr | None, A.Expr]] = []
        while not self.at("]"):
            if self.at("INT") and self.peek().kind == "(":
                rep = A.Literal(self.loc(), self.advance().value, "INT")
                self.advance()
                val = self.initializer() if not self.at(")") else None
                self.expect(")")
                items.append((rep, val if val is not None else A.Literal(rep.loc, None, "DEFAULT")))
            else:
                items.append((None, self.initializer()))
            if not self.accept(","):
                break
        self.expect("]", "']' to close the array initial value")
        return A.ArrayInit(self.loc(start), items)

    def struct_init(self) -> A.StructInit:
        start = self.advance()
        fields = []
        while not self.at(")"):
            n = self.expect("IDENT", "a field name")
            self.expect(":=")
            fields.append((n.value, self.initializer(), self.loc(n)))
            if not self.accept(","):
                break
        self.expect(")")
        return A.StructInit(self.loc(start), fields)

    def type_block(self) -> list[A.TypeDecl]:
        self.advance()
        out = []
        while not self.at("END_TYPE"):
            if self.at("EOF") or self.tok.kind in _POU_START:
                self.fail_expected("END_TYPE")
            start = self.i
            try:
                n = self.expect("IDENT", "a type name")
                self.expect(":")
                tref = self.type_ref(allow_decl=True)
                init = None
                if self.accept(":="):
                    init = self.initializer()
                self.type_end()
                out.append(A.TypeDecl(self.loc(n), n.value, tref, init, n.text))
            except ParseAbort:
                self.sync({"END_TYPE"} | _POU_START)
                self.ensure_progress(start)
        self.expect("END_TYPE")
        return out

    def type_end(self) -> None:
        """The ``;`` after a type declaration; CODESYS and TIA Portal let a declaration that
        ends with END_STRUCT (or the last one, before END_TYPE) go without it."""
        if self.accept(";"):
            return
        prev = self.toks[self.i - 1] if self.i else None
        if self.dialect.type_semicolon_optional and (
                self.at("END_TYPE") or (prev is not None and prev.kind == "END_STRUCT")):
            return
        if prev is not None and prev.kind == "END_STRUCT" or self.at("END_TYPE"):
            self.error("PLC0171", f"';' missing after this type declaration: the dialect "
                       f"'{self.dialect.name}' needs it (CODESYS and S7 do not); add ';' or "
                       "choose {dialect 'codesys'}")
            raise ParseAbort
        self.expect(";")

    def type_ref(self, allow_decl: bool = True) -> A.TypeRef:
        with self.nested("type"):
            return self._type_ref(allow_decl)

    @contextmanager
    def nested(self, what: str):
        """Count nesting of types and initial values written inside each other; beyond
        :data:`NESTING_LIMIT` levels report PLC0124 and give up the declaration."""
        if self.depth >= NESTING_LIMIT:
            self.error("PLC0124", f"this {what} is nested more than {NESTING_LIMIT} levels "
                       "deep; declare the inner levels as named TYPEs with fewer levels")
            raise ParseAbort
        self.depth += 1
        try:
            yield
        finally:
            self.depth -= 1

    def _type_ref(self, allow_decl: bool = True) -> A.TypeRef:
        t = self.tok
        loc = self.loc()
        ref = oop.ref_type(self)  # REF_TO T, POINTER TO T, REFERENCE TO T (ADR 0021)
        if ref is not None:
            return ref
        if t.kind in ("STRING", "WSTRING"):
            self.advance()
            length = None
            if self.accept("[") or self.accept("("):
                length = self.expr()
                if not (self.accept("]") or self.accept(")")):
                    self.fail_expected("']' after the string length")
            return A.StringTypeRef(loc, t.kind == "WSTRING", length)
        if t.kind == "ARRAY":
            self.advance()
            self.expect("[", "'[' and the index ranges, e.g. ARRAY[1..10] OF INT")
            if self.at("*"):  # ARRAY[*, *] OF T: variable length (IEC 61131-3 ed.3 6.5.3)
                star = 0
                while self.accept("*"):
                    star += 1
                    if not self.accept(","):
                        break
                self.expect("]", "']' after the '*' of each dimension, e.g. ARRAY[*, *] OF INT")
                self.expect("OF", "OF and the element type")
                return A.ArrayTypeRef(loc, [], self.type_ref(), star)
            ranges = []
            while True:
                lo = self.expr()
                self.expect("..", "'..' between the lower and upper bound")
                hi = self.expr()
                ranges.append((lo, hi))
                if not self.accept(","):
                    break
            self.expect("]")
            self.expect("OF", "OF and the element type")
            return A.ArrayTypeRef(loc, ranges, self.type_ref())
        if t.kind == "STRUCT":
            self.advance()
            fields: list[A.VarDecl] = []
            while not self.at("END_STRUCT"):
                if self.at("EOF", "END_TYPE"):
                    self.fail_expected("END_STRUCT")
                fields.extend(self.var_decl("STRUCT", False, False))
            self.expect("END_STRUCT")
            return A.StructTypeRef(loc, fields)
        if t.kind == "(":
            self.advance()
            members = []
            spellings: dict[str, str] = {}
            while True:
                n = self.expect("IDENT", "an enumeration value name")
                val = None
                if self.accept(":="):
                    val = self.expr()
                members.append((n.value, val, self.loc(n)))
                spellings[n.value] = n.text
                if not self.accept(","):
                    break
            self.expect(")", "')' to close the enumeration")
            base = None
            if self.at("IDENT") and not self.at(";"):
                base = A.NamedTypeRef(self.loc(), self.advance().value)
            return A.EnumTypeRef(loc, members, base, spellings)
        if t.kind == "IDENT":
            self.advance()
            base = A.NamedTypeRef(loc, t.value)
            if self.at("(") and self._fb_init_args(t.value):
                # a : FB(k := 3): the arguments of the block's FB_init (CODESYS; ADR 0052)
                self.advance()
                base.args = self.call_args()
                return base
            if self.at("(") and self.peek().kind != "IDENT" or (
                self.at("(") and self.peek(2).kind == ".."
            ):
                self.advance()
                lo = self.expr()
                self.expect("..", "'..' in the subrange")
                hi = self.expr()
                self.expect(")")
                return A.SubrangeTypeRef(loc, base, lo, hi)
            if self.at("(") and self.peek().kind == "IDENT":
                # typed enumeration: INT (A, B)  -- rare; treat as enum with base
                enum = self.type_ref()
                assert isinstance(enum, A.EnumTypeRef)
                enum.base = base
                return enum
            return base
        self.fail_expected("a type name")
        raise AssertionError

    # -- statements ---------------------------------------------------------------------------
    def stmt_list(self, stops: set[str]) -> list[A.Stmt]:
        self.block_depth += 1
        try:
            if self.block_depth > MAX_BLOCK_NESTING + 1:  # + 1: the POU body itself
                self._too_deep("blocks", MAX_BLOCK_NESTING)
            out: list[A.Stmt] = []
            stop = stops | _STMT_END
            while self.tok.kind not in stop:
                if self.tok.kind in _POU_START and self.tok.kind != "TYPE" or oop.ends_body(self):
                    break
                self._guarded_statement(out, stop)
            return out
        except _TooDeep:
            if self.block_depth > 1:
                raise
            while not self.at("EOF") and self.tok.kind not in stops | _POU_START:
                self.advance()
            return []
        finally:
            self.block_depth -= 1

    def _guarded_statement(self, out: list[A.Stmt], stop: set[str]) -> None:
        """Parse one statement into ``out``; after a syntax error skip to a safe point."""
        start = self.i
        try:
            s = self.statement()
            if s is not None:
                out.append(s)
        except _TooDeep:
            raise
        except ParseAbort:
            if self.i == start:
                self.advance()
            self.sync(stop)

    def statement(self) -> A.Stmt | None:
        t = self.tok
        k = t.kind
        loc = self.loc()
        if k == ";":
            self.advance()
            return A.Empty(loc)
        if k == "IF":
            return self.if_stmt()
        if k == "CASE":
            return self.case_stmt()
        if k == "FOR":
            return self.for_stmt()
        if k == "WHILE":
            self.advance()
            cond = self.condition("WHILE")
            self.expect("DO", "DO after the WHILE condition")
            body = self.stmt_list({"END_WHILE"})
            self.end("END_WHILE", "WHILE", t)
            return A.While(loc, cond, body)
        if k == "REPEAT":
            self.advance()
            body = self.stmt_list({"UNTIL"})
            self.expect("UNTIL", "UNTIL and a condition to end the REPEAT loop")
            cond = self.condition("UNTIL")
            self.end("END_REPEAT", "REPEAT", t)
            return A.Repeat(loc, body, cond)
        if k in ("EXIT", "CONTINUE", "RETURN"):
            self.advance()
            self.semicolon()
            return {"EXIT": A.Exit, "CONTINUE": A.Continue, "RETURN": A.Return}[k](loc)
        if k in ("IDENT", "ADDR"):
            target = self.postfix(self.primary())
            if self.accept(":="):
                value = self.expr()
                self.semicolon()
                return A.Assign(loc, target, value)
            if self.at("?="):  # ed.3 assignment attempt: the instance if it implements the
                self.advance()   # interface, else NULL: __QUERYINTERFACE (ADR 0059)
                value = self.expr()
                self.semicolon()
                return A.CallStmt(loc, A.Call(loc, A.Name(loc, "__QUERYINTERFACE", "?="),
                                              [A.Arg(value.loc, None, value),
                                               A.Arg(target.loc, None, target)]))
            if self.tok.kind == "IDENT" and self.tok.value == "REF" and self.peek().kind == "=":
                self.advance()  # r REF= x; binds a REFERENCE TO (CODESYS; lower.reference_to)
                self.advance()
                value = self.expr()
                self.semicolon()
                return A.Assign(loc, target, value, op="REF=")
            if isinstance(target, A.Call):
                self.semicolon()
                return A.CallStmt(loc, target)
            if self.at("="):
                self.error("PLC0013", "'=' compares; to assign a value write ':=' "
                           f"(e.g. {t.text} := ...;)")
                raise ParseAbort
            if self.at("=="):
                self.error("PLC0012", "'==' is not an ST operator; assign with ':='")
                raise ParseAbort
            if self.at(":") and isinstance(target, A.Name):  # HasError: State <> OK;
                self.error("PLC0231", f"':' declares, it does not assign; write "
                           f"{t.text} := ...; (with ':=')")
                raise ParseAbort
            if t.kind == "IDENT" and isinstance(target, A.Name):
                close = suggest(t.value, SUGGEST, n=1, cutoff=0.75)
                if close:
                    self.error("PLC0011", f"'{t.text}' is not a keyword or a statement; did you "
                               f"mean {close[0]}?", t)
                    # read it as the keyword it resembles, so the structure around recovers
                    self.i -= 1
                    self.toks[self.i] = Token(close[0], close[0], t.text, t.line, t.col)
                    return None
            self.fail_expected("':=' or '(' after the name (a statement is an assignment or a "
                               "call)")
        if k.startswith("END_") or k in ("ELSE", "ELSIF", "UNTIL", "THEN", "DO"):
            self.error("PLC0010", f"unexpected {t.text}: there is no open statement it could "
                       "close here; check the structure above")
            raise ParseAbort
        self.fail_expected("a statement")
        return None

    def semicolon(self) -> None:
        if not self.accept(";"):
            self.fail_expected("';' at the end of the statement")

    def end(self, kw: str, opener: str, open_tok: Token) -> None:
        if self.accept(kw):
            self.accept(";")
            return
        t = self.tok
        if t.kind == "IDENT":
            close = suggest(t.value, [kw], n=1, cutoff=0.6)
            if close:
                self.error("PLC0011", f"'{t.text}' is misspelled; did you mean {kw}?")
                self.advance()
                self.accept(";")
                return
        self.error("PLC0010", f"expected {kw} to close the {opener} at line {open_tok.line}, "
                   f"found {_found(t)}")
        raise ParseAbort

    def condition(self, where: str) -> A.Expr:
        cond = self.expr()
        if self.at(":="):
            self.error("PLC0014", f"':=' assigns; in a {where} condition compare with '='")
            self.advance()
            self.expr()
        return cond

    def if_stmt(self) -> A.If:
        t = self.advance()
        branches = []
        cond = self.condition("IF")
        self.expect("THEN", "THEN after the IF condition")
        branches.append((cond, self.stmt_list({"ELSIF", "ELSE", "END_IF"})))
        orelse = None
        while True:
            if self.accept("ELSIF"):
                c = self.condition("ELSIF")
                self.expect("THEN", "THEN after the ELSIF condition")
                branches.append((c, self.stmt_list({"ELSIF", "ELSE", "END_IF"})))
            elif self.at("IDENT") and self.tok.value in ("ELSEIF", "ELIF", "ELSE_IF"):
                self.error("PLC0011", f"'{self.tok.text}' is not ST; did you mean ELSIF?")
                self.advance()
                c = self.condition("ELSIF")
                self.expect("THEN")
                branches.append((c, self.stmt_list({"ELSIF", "ELSE", "END_IF"})))
            elif self.accept("ELSE"):
                orelse = self.stmt_list({"END_IF"})
            else:
                break
        self.end("END_IF", "IF", t)
        return A.If(self.loc(t), branches, orelse)

    def case_stmt(self) -> A.Case:
        t = self.advance()
        sel = self.expr()
        self.expect("OF", "OF after the CASE selector")
        branches: list[A.CaseBranch] = []
        orelse = None
        while not self.at("END_CASE", "EOF"):
            if self.accept("ELSE"):
                orelse = self.stmt_list({"END_CASE"})
                break
            loc = self.loc()
            labels: list = []
            while True:
                lo = self.case_label()
                if self.accept(".."):
                    labels.append((lo, self.case_label()))
                else:
                    labels.append(lo)
                if not self.accept(","):
                    break
            self.expect(":", "':' after the CASE label(s)")
            body = self.case_body()
            branches.append(A.CaseBranch(loc, labels, body))
        self.end("END_CASE", "CASE", t)
        return A.Case(self.loc(t), sel, branches, orelse)

    def case_label(self) -> A.Expr:
        return self.unary()

    def case_body(self) -> list[A.Stmt]:
        out: list[A.Stmt] = []
        while not self.at("END_CASE", "ELSE", "EOF"):
            # a new label starts: literal/name followed by ':' ',' or '..'
            if self._at_case_label():
                break
            self._guarded_statement(out, {"END_CASE", "ELSE"})
        return out

    def _at_case_label(self) -> bool:
        j = self.i
        toks = self.toks
        if toks[j].kind == "-":
            j += 1
        if toks[j].kind in ("INT", "ENUMVAL"):
            return toks[j + 1].kind in (":", ",", "..")
        if toks[j].kind == "IDENT":
            nk = toks[j + 1].kind
            if nk == ":" or nk == ",":
                return True
            if nk == "..":
                return True
            # Color.Red: a CODESYS-qualified enumeration value (no statement starts `a.b :`)
            if nk == "." and toks[j + 2].kind == "IDENT" and toks[j + 3].kind in (":", ",", ".."):
                return True
        return False

    def for_stmt(self) -> A.For:
        t = self.advance()
        vt = self.expect("IDENT", "the loop variable")
        var = A.Name(self.loc(vt), vt.value)
        if not self.accept(":="):
            self.fail_expected("':=' and the start value (FOR i := 1 TO 10 DO)")
        start = self.expr()
        self.expect("TO", "TO and the end value")
        end = self.expr()
        step = None
        if self.accept("BY"):
            step = self.expr()
        self.expect("DO", "DO after the FOR range")
        body = self.stmt_list({"END_FOR"})
        self.end("END_FOR", "FOR", t)
        return A.For(self.loc(t), var, start, end, step, body)

    # -- expressions (IEC 61131-3 precedence, lowest first) -----------------------------------
    # Operator chains are parsed with loops (an explicit operand/operator stack, precedence
    # climbing), so a 10,000-term sum costs no recursion; only nesting (parentheses, calls,
    # indices) recurses, counted in expr() and limited to MAX_EXPR_NESTING (PLC0190).
    def expr(self) -> A.Expr:
        self.expr_depth += 1
        try:
            if self.expr_depth > MAX_EXPR_NESTING:
                self._too_deep("expressions", MAX_EXPR_NESTING)
            return self._operator_chain()
        finally:
            self.expr_depth -= 1

    def _operator_chain(self) -> A.Expr:
        """Operands joined by binary operators, left-associative at each precedence level."""
        operands = [self.unary()]
        ops: list[tuple[int, str, Token]] = []
        while self.tok.kind in _BINARY:
            t = self.advance()
            prec, op = _BINARY[t.kind]
            if t.kind == "==":
                self.error("PLC0012", "'==' is not an ST operator; compare with '='", t)
            elif t.kind == "!=":
                self.error("PLC0012", "'!=' is not an ST operator; write '<>'", t)
            while ops and ops[-1][0] >= prec:
                self._reduce(operands, ops)
            ops.append((prec, op, t))
            operands.append(self.unary())
        while ops:
            self._reduce(operands, ops)
        return operands[0]

    def _reduce(self, operands: list[A.Expr], ops: list[tuple[int, str, Token]]) -> None:
        _, op, t = ops.pop()
        right = operands.pop()
        operands[-1] = A.Binary(self.loc(t), op, operands[-1], right)

    def _too_deep(self, what: str, limit: int) -> None:
        self.error("PLC0190", too_deep_message(what, limit))
        raise _TooDeep

    def unary(self) -> A.Expr:
        """Prefix operators (a loop, not recursion: NOT NOT NOT x is fine), then the operand."""
        prefix: list[Token] = []
        while self.tok.kind in ("-", "+", "NOT") and not self._named_not_call():
            prefix.append(self.advance())
            if self.expr_depth + len(prefix) > MAX_EXPR_NESTING:
                self._too_deep("expressions", MAX_EXPR_NESTING)
        operand = self.postfix(self.primary())
        for t in reversed(prefix):
            operand = self._apply_unary(t, operand)
        return operand

    def _named_not_call(self) -> bool:
        """``NOT(IN := x)``: the function NOT with a formal argument, not the operator."""
        return (self.tok.kind == "NOT" and self.peek().kind == "(" and
                self.peek(2).kind == "IDENT" and self.peek(3).kind == ":=")

    def _apply_unary(self, t: Token, operand: A.Expr) -> A.Expr:
        if t.kind == "-" and isinstance(operand, A.Literal) and operand.kind in ("INT", "REAL",
                                                                                 "TIME"):
            operand.value = -operand.value
            operand.loc = self.loc(t)
            operand.text = "-" + operand.text
            return operand
        if t.kind == "+":
            return operand
        return A.Unary(self.loc(t), t.kind, operand)

    def primary(self) -> A.Expr:
        t = self.tok
        loc = self.loc()
        k = t.kind
        if k == "INT":
            self.advance()
            if t.prefix == "BOOL":
                return A.Literal(loc, bool(t.value), "BOOL", None, t.text)
            return A.Literal(loc, t.value, "INT", t.prefix, t.text)
        if k == "REAL":
            self.advance()
            return A.Literal(loc, t.value, "REAL", t.prefix, t.text)
        if k in ("TRUE", "FALSE"):
            self.advance()
            return A.Literal(loc, k == "TRUE", "BOOL", None, t.text)
        if k in ("STRING", "WSTRING", "TIME", "DATE", "TOD", "DT"):
            self.advance()
            return A.Literal(loc, t.value, k, t.prefix, t.text)
        if k == "ENUMVAL":
            self.advance()
            return A.Literal(loc, t.value, "ENUM", t.prefix, t.text)
        if k == "ADDR":
            self.advance()
            return A.DirectAddr(loc, self.address(t) if not t.value.endswith("*") else t.value)
        if k == "IDENT":
            this = oop.this_or_super(self)  # THIS^ / SUPER^ (ADR 0021)
            if this is not None:
                return this
            self.advance()
            return A.Name(loc, t.value, t.text)
        if k == "(":
            self.advance()
            e = self.expr()
            self.expect(")", "')' to close the parenthesis")
            return e
        if k in _OPERATOR_FUNCTIONS and self.peek().kind == "(":
            # a standard function named like an operator, called: AND(a, b, c), MOD(a, 3)
            # (IEC 61131-3 ed.3 Table 31; Beremiz writes FBD/LD networks this way)
            self.advance()
            return A.Name(loc, k, t.text)
        if k in ("NOT",):
            return self.unary()
        self.fail_expected("an expression")
        raise AssertionError

    def postfix(self, e: A.Expr) -> A.Expr:
        """``.member``, ``[index]`` and ``(arguments)`` after an operand, in a loop; each one
        nests the operand one level deeper for the checker and the compiler."""
        chain = 0
        while True:
            if self.toks[self.i].kind not in (".", "[", "(", "^"):  # the usual case, quickly
                return e
            if self.at(".", "[", "("):
                chain += 1
                if self.expr_depth + chain > MAX_EXPR_NESTING:
                    self._too_deep("expressions", MAX_EXPR_NESTING)
            if self.at("."):
                dot = self.advance()
                if self.at("INT"):  # bit access x.3
                    bit = self.advance()
                    e = A.Member(self.loc(dot), e, f"%{bit.value}")
                    continue
                if self.at("PARTIAL"):  # x.%X3 is x.3, x.%B1 a byte of x (IEC ed.3 Table 17)
                    part = self.advance()
                    kind, n = part.value[1], int(part.value[2:])
                    field = f"%{n}" if kind == "X" else f"%{kind}{n}"
                    e = A.Member(self.loc(dot), e, field, field)
                    continue
                n = self.expect("IDENT", "a member name after '.'")
                e = A.Member(self.loc(n), e, n.value, n.text)
            elif self.at("["):
                b = self.advance()
                idx = [self.expr()]
                while self.accept(","):
                    idx.append(self.expr())
                self.expect("]", "']' to close the index")
                e = A.Index(self.loc(b), e, idx)
            elif self.at("("):
                p = self.advance()
                e = A.Call(e.loc if e.loc else self.loc(p), e, self.call_args())
            elif self.at("^"):  # r^: the variable a reference points to (ADR 0021)
                e = A.Member(self.loc(self.advance()), e, "^", "^")
            else:
                return e

    def _fb_init_args(self, name: str) -> bool:
        """After ``name (``: arguments of an FB_init (``FB(k := 3)``, ``FB(inst)``), not a
        subrange (``INT (1..5)``) nor a typed enumeration (``INT (A, B)``), which take an
        elementary base type."""
        if lookup_elementary(name) is not None or self.peek(2).kind == "..":
            return False
        nxt, after = self.peek().kind, self.peek(2).kind
        return nxt == ")" or (nxt == "IDENT" and after in (":=", ",", ")")) or (
            nxt in ("INT", "REAL", "-") and after != ".." and self.peek(3).kind != "..")

    def call_args(self) -> list[A.Arg]:
        args: list[A.Arg] = []
        while not self.at(")"):
            loc = self.loc()
            negated = False
            if self.at("NOT") and self.peek().kind == "IDENT" and self.peek(2).kind == "=>":
                self.advance()
                negated = True
            if self.at("IDENT") and self.peek().kind in (":=", "=>"):
                name = self.advance().value
                op = self.advance().kind
                if op == "=>":
                    val = None if self.at(",", ")") else self.expr()
                    args.append(A.Arg(loc, name, val, True, negated))
                else:
                    args.append(A.Arg(loc, name, self.expr()))
            else:
                args.append(A.Arg(loc, None, self.expr()))
            if not self.accept(","):
                break
        self.expect(")", "')' to close the argument list")
        return args


def _describe(kind: str) -> str:
    return {"IDENT": "a name", "INT": "an integer", "EOF": "the end of the file"}.get(
        kind, f"'{kind}'" if not kind.isalpha() else kind
    )


def _found(t: Token) -> str:
    if t.kind == "EOF":
        return "the end of the file"
    return f"'{t.text}'"


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
