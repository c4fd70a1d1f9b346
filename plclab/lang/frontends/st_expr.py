"""The expressions of the ST parser: operator chains by precedence, unary operators, primaries,
postfix selectors and call arguments (a mixin of :class:`plclab.lang.frontends.st.Parser`).
"""

from __future__ import annotations

from .. import ast as A
from ..lexer import Token
from ..limits import MAX_EXPR_NESTING, too_deep_message
from ..types import lookup_elementary
from . import oop
from .st_words import TooDeep

_CMP = {"=": "=", "<>": "<>", "<": "<", "<=": "<=", ">": ">", ">=": ">="}
# binary operator token -> (precedence, AST operator); higher binds tighter
_BINARY = {
    "OR": (1, "OR"), "XOR": (2, "XOR"), "AND": (3, "AND"), "&": (3, "AND"),
    "=": (4, "="), "<>": (4, "<>"), "==": (4, "="), "!=": (4, "<>"),
    "<": (5, "<"), "<=": (5, "<="), ">": (5, ">"), ">=": (5, ">="),
    "+": (6, "+"), "-": (6, "-"), "*": (7, "*"), "/": (7, "/"), "MOD": (7, "MOD"),
    "**": (8, "**"),
}


_OPERATOR_FUNCTIONS = ("AND", "OR", "XOR", "MOD", "NOT")


class ExprParse:
    """Expressions (a mixin of Parser)."""

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
        raise TooDeep

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

