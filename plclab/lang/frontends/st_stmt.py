"""The statements of the ST parser: statement lists with recovery, assignments and calls, IF,
CASE, FOR, WHILE, REPEAT (a mixin of :class:`plclab.lang.frontends.st.Parser`).
"""

from __future__ import annotations

from ...suggest import suggest
from .. import ast as A
from ..lexer import Token
from ..limits import MAX_BLOCK_NESTING
from ..parsing import ParseAbort
from . import oop
from .st_words import POU_START, STMT_END, SUGGEST, TooDeep, found_token


class StmtParse:
    """Statements (a mixin of Parser)."""

    # -- statements ---------------------------------------------------------------------------
    def stmt_list(self, stops: set[str]) -> list[A.Stmt]:
        self.block_depth += 1
        try:
            if self.block_depth > MAX_BLOCK_NESTING + 1:  # + 1: the POU body itself
                self._too_deep("blocks", MAX_BLOCK_NESTING)
            out: list[A.Stmt] = []
            stop = stops | STMT_END
            while self.tok.kind not in stop:
                if self.tok.kind in POU_START and self.tok.kind != "TYPE" or oop.ends_body(self):
                    break
                self._guarded_statement(out, stop)
            return out
        except TooDeep:
            if self.block_depth > 1:
                raise
            while not self.at("EOF") and self.tok.kind not in stops | POU_START:
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
        except TooDeep:
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
                   f"found {found_token(t)}")
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
