"""Fast paths of the code generator (issue 19, ``docs/adr/0024-generated-code-fast-paths.md``).

A mixin of :class:`plclab.compile.codegen.Codegen`: each method here either emits faster code
that keeps the plain path's behaviour exactly, or returns None/False so that the plain path
runs. ``tests/compile/test_fast_paths.py`` checks each one against the plain code on random
programs and values.

* **REAL stores** go through the PLC's float32 cell, ``_F32[0] = x; v = _F32[0]``, instead of a
  call of ``_f32`` (the cell rounds exactly as ``f32`` does).
* **MOD and integer ``/`` by a non-zero literal** are inline Python (``%`` and ``//`` on the
  magnitude, sign of the dividend) instead of two helper calls; the zero check is not needed.
* **Call-free FOR loops in a method**: the loop variable and the arrays the body only indexes
  are Python locals while the loop runs, written back in a ``finally`` (so a fault in the
  loop leaves the same state as the plain code).
* **Call-free WHILE and REPEAT loops** without inner loops charge the watchdog through a local
  counter, written back to the budget in a ``finally``.

"Call-free" means the body holds only the node classes in :data:`_PLAIN_NODES` and calls only
standard functions and conversions -- no method, no property, no dereference ``r^``, no
``THIS^``: nothing else can read or write the instance's variables while the loop runs, so the
locals cannot be seen stale.
"""

from __future__ import annotations

import re

from ..lang import ast as A
from ..lang import types as T
from ..lang.check import VarSym
from ..lang.walk import walk
from .builtins_emit import const_int

# False: the generator emits only the plain code (the property tests compare both).
ENABLED = True

# Node classes a call-free loop body may hold (anything else, e.g. a new node class, keeps the
# plain code: the check is a whitelist).
_PLAIN_NODES = (A.Assign, A.If, A.Case, A.For, A.While, A.Repeat, A.Exit, A.Continue, A.Empty,
                A.Name, A.Literal, A.Binary, A.Unary, A.Index, A.Member, A.Call, A.Arg)


class FastPaths:
    """Mixin: the fast paths. Uses the Codegen's ``emit``, ``ex``, ``new_tmp``, ``interval``,
    ``block``, ``locals``, ``has_self``, ``helper`` and ``jump_labels``."""

    # Python code of a member -> the local that stands for it inside a call-free loop
    local_names: dict[str, str]
    # the local counter charged by the loop being generated instead of _B.left, if any
    local_budget: str | None

    def init_fast_paths(self) -> None:
        self.fast = ENABLED
        self.local_names = {}
        self.local_budget = None

    # -- REAL store ---------------------------------------------------------------------------
    def real_store(self, target: A.Expr, raw: str, val: str) -> bool:
        """Emit ``target := raw`` rounded to REAL through the cell, when ``val`` (the plain
        store's value) is ``_f32(raw)`` and the target is a plain variable or member (its code
        has no temporaries, so nothing is reordered). False: the caller emits the plain store."""
        if not self.fast or val != f"_f32({raw})" or not _plain_target(target):
            return False
        lv = self.ex(target)
        self.emit(f"_F32[0] = {raw}")
        self.emit(f"{lv} = _F32[0]")
        return True

    # -- MOD and / by a literal ---------------------------------------------------------------
    def div_by_literal(self, e: A.Binary, left: str) -> str | None:
        """``left MOD c`` or ``left / c`` for an integer literal ``c`` != 0, inline; None when
        the plain helper call is needed. IEC (and C) truncate toward zero: the result has the
        dividend's sign and the magnitude of ``|left| op |c|``."""
        c = const_int(e.right)
        t = T.base_of(e.ty) if e.ty is not None else None
        lt = T.base_of(e.left.ty) if e.left.ty is not None else None
        if not self.fast or not c or t is None or lt is None or t.kind not in ("int", "bits") or \
                lt.kind not in ("int", "bits"):
            return None
        op = "%" if e.op == "MOD" else "//"
        b = abs(c)
        r = self.interval(e.left)
        if r is not None and r[0] >= 0:
            code = f"({left} {op} {b})"
        else:
            tmp = self.new_tmp()
            code = f"({tmp} {op} {b} if ({tmp} := {left}) >= 0 else -(-{tmp} {op} {b}))"
        return f"(-{code})" if op == "//" and c < 0 else code

    def real_division(self, e: A.Binary, left: str, right: str) -> str | None:
        """REAL ``a / b`` inline when ``a`` is a literal or a variable (evaluating it first or
        second makes no difference): the helper ``_rdiv`` is called only to fault when ``b``
        is zero. None: the plain ``_rdiv(a, b)``."""
        t = T.base_of(e.ty) if e.ty is not None else None
        if not self.fast or t is None or t.kind != "real" or \
                not isinstance(e.left, A.Literal | A.Name) or not self.call_free([e.right]):
            return None  # (a call in b could change a: keep the order a, b)
        b = self.new_tmp()
        return f"({left} / {b} if ({b} := {right}) != 0 else _rdiv({left}, {b}))"

    # -- string functions --------------------------------------------------------------------
    def string_inline(self, name: str, args: list[A.Expr], codes: list[str]) -> str | None:
        """FIND with a non-empty literal, LEFT, REPLACE and INSERT inline, when every argument
        is a pure read (:func:`_pure`: variables, literals, ``+ - *``, ``LEN``; evaluating one
        cannot fault, write anything or depend on the order). The expressions are those of the
        helpers in ``plclab.runtime.rt`` (``_find``, ``_left``, ``_replace``, ``_insert``);
        a slice end beyond the string is clipped by Python as the helpers' ``min`` does. None:
        the helper call (ADR 0034)."""
        if not self.fast or not all(_pure(a, c) for a, c in zip(args, codes, strict=True)):
            return None
        if name == "FIND":
            lit = args[1]
            if isinstance(lit, A.Literal) and isinstance(lit.value, str) and lit.value:
                return f"(_str_find({codes[0]}, {codes[1]}) + 1)"
            return None
        if name == "LEFT":
            return f"{codes[0]}[:{self._at_least(args[1], codes[1], 0)}]"
        if name == "REPLACE":  # IN1[:P-1] + IN2 + IN1[P-1+max(L,0):], P at least 1
            s1, s2 = codes[0], codes[1]
            n = self._at_least(args[2], codes[2], 0)
            p = const_int(args[3])
            if p is not None:
                head = max(p, 1) - 1
                tail = str(head) if n == "0" else f"{head} + {n}"
                return f"({s1}[:{head}] + {s2} + {s1}[{tail}:])"
            t, u = self.new_tmp(), self.new_tmp()
            head = f"({u} := ({t} - 1 if ({t} := {codes[3]}) > 1 else 0))"
            return f"({s1}[:{head}] + {s2} + {s1}[{u}{'' if n == '0' else f' + {n}'}:])"
        if name == "INSERT":  # IN1[:P] + IN2 + IN1[P:], P at least 0 (at most LEN: a slice)
            s1, s2 = codes[0], codes[1]
            p = self._at_least(args[2], codes[2], 0)
            if const_int(args[2]) is not None:
                return f"({s1}[:{p}] + {s2} + {s1}[{p}:])"
            u = self.new_tmp()
            return f"({s1}[:({u} := {p})] + {s2} + {s1}[{u}:])"
        return None

    def _at_least(self, e: A.Expr, code: str, lo: int) -> str:
        """The code of ``max(e, lo)`` for a pure integer ``e``: a literal folded, ``LEN(..)``
        (never negative) as it is when ``lo`` is 0, else a conditional with a temporary."""
        c = const_int(e)
        if c is not None:
            return str(max(c, lo))
        if lo == 0 and isinstance(e, A.Call) and isinstance(e.func, A.Name) and \
                e.func.name == "LEN":
            return code
        t = self.new_tmp()
        return f"({t} if ({t} := {code}) > {lo} else {lo})"

    # -- array index -------------------------------------------------------------------------
    def folded_index(self, ix: A.Expr, lo: int) -> str | None:
        """The flat offset of a checked-in-range index ``name + c`` (or ``name - c``) with the
        low bound folded into the constant: ``a[j + 1]`` of ``ARRAY[1..n]`` is ``a[j]``. None
        for any other index (the plain ``(code) - lo``)."""
        if not (self.fast and isinstance(ix, A.Binary) and ix.op in ("+", "-") and
                isinstance(ix.left, A.Name)):
            return None
        c = const_int(ix.right)
        if c is None:
            return None
        k = (c if ix.op == "+" else -c) - lo
        name = self.ex(ix.left)
        return name if k == 0 else f"{name} + {k}" if k > 0 else f"{name} - {-k}"

    # -- loops --------------------------------------------------------------------------------
    def call_free(self, nodes: list) -> bool:
        """Whether ``nodes`` (statements, expressions, None) hold only plain statements and
        expressions and call nothing but standard functions and conversions."""
        for s in nodes:
            if s is None:
                continue
            for n in walk(s):
                if not isinstance(n, _PLAIN_NODES):
                    return False
                if isinstance(n, A.Call) and (n.target is None or
                                              n.target.kind not in ("builtin", "conv")):
                    return False
                if isinstance(n, A.Name) and n.sym is not None and (
                        not isinstance(n.sym, VarSym) or n.sym.storage in ("this", "super")):
                    return False
                # a property runs user code; r^ reads or writes whatever r points at, maybe
                # a variable the loop holds in a local (ADR 0021)
                if isinstance(n, A.Member) and (n.field_name == "^" or isinstance(n.sym, A.Pou)):
                    return False
        return True

    def loop_var_guarded(self, s: A.For) -> bool:
        """Whether nothing can change the FOR variable behind the loop's back, so its range
        is a fact: the body never assigns it, never hands it to a call that could write it
        (VAR_IN_OUT, an output, REF/ADR) and, for a member of the instance, calls no user code
        and reaches no property or dereference at all (an action, a method, ``THIS^`` or a
        pointer may write a member). A local of a function or method must also never have
        its address taken anywhere in the POU. Only then may indexing and the MOD and ``/``
        fast paths trust the loop's bounds (ADR 0038)."""
        v = s.var
        if not (isinstance(v, A.Name) and isinstance(v.sym, VarSym)):
            return False
        decl = v.sym.decl
        local = v.sym.storage == "local"

        def is_var(x: A.Expr | None) -> bool:
            return isinstance(x, A.Name) and isinstance(x.sym, VarSym) and x.sym.decl is decl

        def mentions(x: A.Expr | None) -> bool:
            return x is not None and any(is_var(n) for n in walk(x))

        for st in s.body:
            for n in walk(st):
                if isinstance(n, A.Assign) and is_var(_stored_root(n.target)):
                    return False
                if isinstance(n, A.For) and is_var(n.var):
                    return False
                if isinstance(n, A.Arg) and n.output and is_var(_stored_root(n.value)):
                    return False
                if isinstance(n, A.Call):
                    kind = n.target.kind if n.target is not None else None
                    user = kind not in ("builtin", "conv")
                    if user and not local:
                        return False
                    if (user or _callee_name(n) in _ADDRESS_OF) and \
                            any(mentions(a.value) for a in n.args):
                        return False
                if not local and isinstance(n, A.Member) and (
                        n.field_name == "^" or isinstance(n.sym, A.Pou)):
                    return False
                if not local and isinstance(n, A.Name) and isinstance(n.sym, VarSym) and \
                        n.sym.storage in ("this", "super"):
                    return False
        if local and self.pou is not None:
            bodies = [self.pou.body, *(m.body for m in self.pou.methods)]
            for body in bodies:
                for st in body or []:
                    for n in walk(st):
                        if isinstance(n, A.Call) and _callee_name(n) in _ADDRESS_OF and \
                                any(mentions(a.value) for a in n.args):
                            return False
                        if isinstance(n, A.Assign) and n.op == "REF=" and mentions(n.value):
                            return False
        return True

    def local_for(self, s: A.For, plain) -> bool:
        """A call-free FOR in a method with its variable, the elementary variables and the
        arrays its body only indexes as Python locals; ``plain(s)`` emits the loop itself.
        Variables the loop stores to are written back in a ``finally``. False when not
        applicable."""
        v = s.var
        if not (self.fast and self.has_self and self.helper is None and self.jump_labels is None and
                isinstance(v, A.Name) and isinstance(v.sym, VarSym) and
                v.sym.storage == "self" and
                self.call_free([*s.body, s.start, s.end, s.step])):
            return False
        names, stored = _loop_members(s)
        if names is None:
            return False
        fresh = []  # (member code, local, written back)
        for n in [v, *names]:
            code = self.ex(n)
            if code.startswith("self.") and code not in self.local_names and \
                    code not in (c for c, _, _ in fresh):
                fresh.append((code, f"v_0L{self.new_tmp('')}", n is v or id(n.sym.decl) in stored))
        if not fresh or fresh[0][0] != f"self.{v.sym.decl.name.upper()}":
            return False  # the variable is already a local of an outer loop
        for code, local, _ in fresh:
            self.emit(f"{local} = {code}")
            self.local_names[code] = local
            self.locals.add(local)
        self.emit("try:")
        self.ind += 1
        plain(s)
        self.ind -= 1
        self.emit("finally:")
        self.ind += 1
        for code, local, back in fresh:
            if back:
                self.emit(f"{code} = {local}")
        self.ind -= 1
        for code, local, _ in fresh:
            del self.local_names[code]
            self.locals.discard(local)
        return True

    def local_watchdog(self, body: list[A.Stmt], cond: A.Expr, emit_loop) -> bool:
        """A call-free WHILE or REPEAT without inner loops: its passes are charged to a local
        counter (``emit_loop()`` emits the loop; :meth:`watchdog_lines` the charge)."""
        if not self.fast or self.local_budget is not None or self.helper is not None or \
                not self.call_free([*body, cond]) or \
                any(isinstance(x, A.For | A.While | A.Repeat) for x in A.walk_stmts(body)):
            return False
        w = self.local_budget = self.new_tmp()
        self.emit(f"{w} = _B.left")
        self.emit("try:")
        self.ind += 1
        try:
            emit_loop()
        finally:
            self.local_budget = None
        self.ind -= 1
        self.emit("finally:")
        self.ind += 1
        self.emit(f"_B.left = {w}")
        self.ind -= 1
        return True

    def watchdog_lines(self, where: int) -> list[str]:
        """The per-pass charge of a loop: the budget, or the loop's local counter."""
        w = self.local_budget
        if w is None:
            return ["_B.left -= 1", f"if _B.left < 0: _wd({where})"]
        return [f"{w} -= 1", f"if {w} < 0: _B.left = {w}; _wd({where})"]


# the code of a pure read: names, attribute paths, integer and string literals, + - * and
# parentheses, and the builtin len() (once the literals are taken out)
_STRING_LITERAL = re.compile(r"'(?:[^'\\]|\\.)*'" + r'|"(?:[^"\\]|\\.)*"')
_PURE_CODE = re.compile(r"[\w. ()+\-*]*")
_CALL = re.compile(r"[\w)\]]\s*\(")


def _pure(e: A.Expr, code: str) -> bool:
    """``code`` (of ``e``) only reads variables and computes with ``+ - *`` and LEN: it
    cannot fault, call user code or write anything (checked on the generated code itself,
    which is what runs)."""
    if isinstance(e, A.Literal):
        return isinstance(e.value, str | int) and not isinstance(e.value, bool)
    bare = re.sub(r"(?<![\w.])len\(", "(", _STRING_LITERAL.sub("0", code))
    return _PURE_CODE.fullmatch(bare) is not None and _CALL.search(bare) is None


def _plain_target(e: A.Expr) -> bool:
    """A variable or a member chain of variables (its code needs no temporaries); never a
    property (its SET is a call) nor a dereference."""
    while isinstance(e, A.Member) and not e.field_name.startswith("%"):
        if isinstance(e.sym, A.Pou) or e.field_name == "^":
            return False
        e = e.obj
    return isinstance(e, A.Name) and isinstance(e.sym, VarSym)


def _loop_members(s: A.For) -> tuple[list[A.Name] | None, set[int]]:
    """The instance variables a call-free FOR can hold in locals, one Name each: elementary
    ones, and arrays used only as ``a[...]`` (never whole: no copy, no assignment); and the
    ids of the declarations the loop stores to (write-back). (None, ...) when an output
    argument (``=>``) stores in a way this does not follow."""
    first: dict[int, A.Name] = {}
    uses: dict[int, int] = {}
    indexed: dict[int, int] = {}
    stored: set[int] = set()
    for st in s.body:
        for n in walk(st):
            if isinstance(n, A.Arg) and n.output:
                return None, stored
            if isinstance(n, A.Assign | A.For):
                root = _root(n.target if isinstance(n, A.Assign) else n.var)
                if isinstance(root, A.Name) and isinstance(root.sym, VarSym):
                    stored.add(id(root.sym.decl))
            elif isinstance(n, A.Name) and isinstance(n.sym, VarSym) and \
                    n.sym.storage == "self":
                key = id(n.sym.decl)
                uses[key] = uses.get(key, 0) + 1
                first.setdefault(key, n)
            elif isinstance(n, A.Index) and isinstance(n.obj, A.Name) and \
                    isinstance(n.obj.sym, VarSym):
                key = id(n.obj.sym.decl)
                indexed[key] = indexed.get(key, 0) + 1
    out = []
    for key, n in first.items():
        t = T.resolve(n.sym.decl.ty)
        if isinstance(t, T.ArrayType):
            if indexed.get(key, 0) == uses[key]:
                out.append(n)
        elif isinstance(t, T.Elementary | T.Subrange | T.StringType | T.EnumType):
            out.append(n)
    return out, stored


_ADDRESS_OF = ("REF", "ADR")


def _callee_name(c: A.Call) -> str:
    """The upper-case name a call is written with (``REF`` in ``REF(x)``), or ``""``."""
    return c.func.name.upper() if isinstance(c.func, A.Name) else ""


def _stored_root(e: A.Expr | None) -> A.Expr | None:
    """The variable a store into ``e`` changes: ``x`` of ``x``, ``x.m`` and ``x[i]``."""
    while isinstance(e, A.Member | A.Index):
        e = e.obj
    return e


def _root(e: A.Expr) -> A.Expr:
    while isinstance(e, A.Member):
        e = e.obj
    return e
