"""The code of statements: assignments, calls, IF, CASE, loops, jumps, and the sizes rules that
keep deep blocks and large CASEs inside Python's limits (a mixin of
:class:`plclab.compile.codegen.Codegen`).
"""

from __future__ import annotations

import bisect
import heapq
import re
from dataclasses import dataclass, field

from ..errors import Location
from ..lang import ast as A
from ..lang import types as T
from ..lang.check import CallInfo, EnumSym, VarSym
from ..lang.walk import UnhandledNode
from . import oop_emit
from .codegen_expr import SIMPLE_NODES as _SIMPLE
from .codegen_names import ident, kind_name


class StmtEmit:
    """Statements (a mixin of Codegen)."""

    # -- statements ---------------------------------------------------------------------------
    def function_body(self, stmts: list[A.Stmt], local_names: list[str], has_self: bool) -> None:
        """The statements of a generated function whose ST locals are ``v_X`` Python locals."""
        self.locals = {f"v_{ident(n)}" for n in local_names}
        self.has_self = has_self
        self.block(stmts)
        self.locals = set()

    def block(self, stmts: list[A.Stmt]) -> None:
        if self.jump_labels is None and any(isinstance(s, A.Jump) for s in stmts):
            self.jump_block(stmts)
            return
        if stmts and (self.ind >= OUTLINE_INDENT or len(self.loops) >= OUTLINE_LOOPS):
            self.outline(stmts)
            return
        n = len(self.lines)
        for s in stmts:
            self.stmt(s)
        if len(self.lines) == n:
            self.emit("pass")

    def jump_block(self, stmts: list[A.Stmt]) -> None:
        """A body with jumps (IL) becomes a program-counter state machine: one ``if _pc <= k``
        block per label, in order, so falling through needs no code; a jump sets ``_pc`` and
        restarts the loop. Backward jumps are charged to the watchdog budget like loops."""
        segs: list[list[A.Stmt]] = [[]]
        labels: dict[str, int] = {}
        for s in stmts:
            if isinstance(s, A.Label):
                if segs[-1] or len(segs) > 1 or labels:
                    segs.append([])
                labels[s.name] = len(segs) - 1
            else:
                segs[-1].append(s)
        self.jump_labels = labels
        self.emit("_pc = 0")
        self.emit("while True:")
        self.ind += 1
        for k, seg in enumerate(segs):
            self.seg_index = k
            self.emit(f"if _pc <= {k}:")
            self.ind += 1
            n = len(self.lines)
            for s in seg:
                self.stmt(s)
            if len(self.lines) == n:
                self.emit("pass")
            self.ind -= 1
        self.emit("break")
        self.ind -= 1
        self.jump_labels = None

    def s_Label(self, s: A.Label) -> None:
        pass

    def s_Jump(self, s: A.Jump) -> None:
        labels = self.jump_labels or {}
        target = labels[s.label]
        if s.cond is not None:
            cond = self.ex(s.cond)
            self.flush_pre()
            self.emit(f"if {cond}:")
            self.ind += 1
        if target <= self.seg_index:  # backward: may loop, so it costs watchdog budget
            self._watchdog(s.loc)
        self.emit(f"_pc = {target}")
        self.emit("continue")
        if s.cond is not None:
            self.ind -= 1

    def stmt(self, s: A.Stmt) -> None:
        self.where_now = self.where(s.loc)
        m = getattr(self, "s_" + type(s).__name__, None)
        if m is None:
            raise UnhandledNode("Codegen.stmt", s)
        m(s)

    def s_Empty(self, s: A.Empty) -> None:
        pass

    def s_Assign(self, s: A.Assign) -> None:
        tt = s.target.ty
        if s.op in ("S=", "R="):
            val = self.ex(s.value)
            self.flush_pre()
            self.emit(f"if {val}:")
            self.ind += 1
            self.assign_to(s.target, "True" if s.op == "S=" else "False")
            self.ind -= 1
            return
        raw = self.ex(s.value)
        val = self.coerce(raw, s.value.ty, tt, s.value)
        if T.resolve(tt).is_aggregate and not isinstance(s.value, A.Call):
            val = self.copy_code(val, tt)
        self.flush_pre()
        if not self.real_store(s.target, raw, val):  # fast path (fastpaths.py)
            self.assign_to(s.target, val)

    def assign_to(self, target: A.Expr, val: str) -> None:
        if isinstance(target, A.Member) and isinstance(target.sym, A.Pou):  # a PROPERTY's SET
            code = oop_emit.property_call(self, target, val)
            self.flush_pre()
            self.emit(code)
            return
        if isinstance(target, A.Name) and isinstance(target.sym, A.Pou):  # bare PROPERTY: SET
            self.emit(f"self.{oop_emit.method_name(target.sym)}({val})")
            return
        if isinstance(target, A.Member) and target.field_name == "^":  # r^ := v (ADR 0021)
            code = oop_emit.deref(self, target)
            self.flush_pre()
            self.emit(f"{code}.set({val})")
            return
        if isinstance(target, A.Member) and target.field_name.startswith("%"):
            code = self.store_code(target, val)
            self.flush_pre()
            self.emit(code)
            return
        if isinstance(target, A.DirectAddr):
            self.emit(self.addr_write(target.address, val))
            return
        lv = self.ex(target)
        self.flush_pre()
        self.emit(f"{lv} = {val}")

    def s_CallStmt(self, s: A.CallStmt) -> None:
        c = s.call
        info: CallInfo | None = c.target
        if info is None:
            return
        if info.kind in ("fb", "program"):
            if info.en is None and info.eno is None:
                self.fb_call(c, info)
                return
            # EN/ENO (IEC 61131-3 ed.3 6.6.1.6): the body runs only when EN; ENO tells whether
            en = self.new_tmp()
            code = self.ex(info.en) if info.en is not None else "True"
            self.flush_pre()
            self.emit(f"{en} = {code}")
            self.emit(f"if {en}:")
            self.ind += 1
            self.fb_call(c, info)
            self.emit("pass")
            self.ind -= 1
            for code in self.eno_false(info, en):
                self.emit(code)
            if info.eno is not None:
                self.assign_to(info.eno, en)
            return
        if info.kind == "action":  # inst.A(...): the POU's inputs, its action, its outputs
            self.fb_call(c, info)
            return
        if info.kind == "builtin" and info.callee.statement_only:
            self.test_builtin(c, info)
            return
        code = self.ex(c)
        self.flush_pre()
        self.emit(code)

    def fb_call(self, c: A.Call, info: CallInfo) -> None:
        run = "_body()"
        if info.kind == "action":  # CODESYS action (ADR 0035): on the instance before the dot
            assert isinstance(c.func, A.Member)
            inst = self.ex(c.func.obj)
            run = f"{oop_emit.method_name(info.callee)}()"
        elif info.kind == "program":
            inst = f"_P.{ident(c.func.name)}"  # type: ignore[union-attr]
        elif oop_emit.is_super(c.func):  # SUPER^(): the base block's body on this instance
            self.flush_pre()
            self.emit(f"P_{ident(info.callee.name)}._body(self)")
            return
        else:
            inst = self.ex(c.func)
        fb = inst
        if not (info.inputs or info.outputs or info.inouts) and "[" not in inst:
            self.flush_pre()
            self.emit(f"{inst}.{run}")
            return
        if "." in inst or "[" in inst:
            fb = "_fb"
        vals = [(ident(d.name), self.coerce(self.ex(e), e.ty, d.ty, e)) for d, e in info.inputs]
        inouts = [(d, self.inout_code(d, e), e) for d, e in info.inouts]
        self.flush_pre()
        if fb != inst:
            self.emit(f"{fb} = {inst}")
        for n, v in vals:
            self.emit(f"{fb}.{n} = {v}")
        for d, code, _ in inouts:
            self.emit(f"{fb}.{ident(d.name)} = {code}")
        self.emit(f"{fb}.{run}")
        for d, _code, e in inouts:
            if not T.resolve(d.ty).is_aggregate and not d.constant:
                self.assign_to(e, f"{fb}.{ident(d.name)}")
        for d, target, neg in info.outputs:
            v = f"{fb}.{ident(d.name)}"
            if neg:
                v = f"(not {v})"
            self.assign_to(target, self.coerce(v, d.ty, target.ty, None))

    def test_builtin(self, c: A.Call, info: CallInfo) -> None:
        name = info.callee.name
        args = [self.ex(e) for _, e in info.inputs]
        self.flush_pre()
        w = self.where(c.loc)
        if name == "ADVANCE_TIME":
            e = info.inputs[0][1]
            scale = 1 if T.resolve(e.ty) is T.TIME else None
            if scale is None:
                self.emit(f"_CTX.advance_ns({args[0]})")
            else:
                self.emit(f"_CTX.advance_ns({args[0]} * 1000000)")
            return
        nargs = {"ASSERT_EQ": 2, "ASSERT_NE": 2, "ASSERT_NEAR": 3}.get(name, 1)
        texts = [A.expr_text(e) for _, e in info.inputs[:nargs]]
        msg = info.inputs[nargs][1] if len(info.inputs) > nargs else None
        self.assert_texts[w] = ", ".join(texts) + (
            f": {msg.value}" if isinstance(msg, A.Literal) else "")
        kinds = [kind_name(e.ty) for _, e in info.inputs]
        if name in ("ASSERT_EQ", "ASSERT_NE"):
            k = kinds[0] if kinds[0] != "int?" else kinds[1]
            self.emit(f"_assert_cmp({args[0]}, {args[1]}, {name == 'ASSERT_EQ'}, {w}, {k!r})")
        elif name in ("ASSERT_TRUE", "ASSERT_FALSE"):
            self.emit(f"_assert_bool({args[0]}, {name == 'ASSERT_TRUE'}, {w})")
        elif name == "ASSERT_NEAR":
            self.emit(f"_assert_near({args[0]}, {args[1]}, {args[2]}, {w})")

    def s_If(self, s: A.If) -> None:
        if len(s.branches) > MAX_ELIF:
            self.if_flag(s)
            return
        first = True
        depth = 0
        for cond, body in s.branches:
            code = self.ex(cond)
            if first:
                self.flush_pre()
                self.emit(f"if {code}:")
            elif self.pre:
                self.emit("else:")
                self.ind += 1
                depth += 1
                self.flush_pre()
                self.emit(f"if {code}:")
            else:
                self.emit(f"elif {code}:")
            first = False
            self.ind += 1
            self.block(body)
            self.ind -= 1
            self.where_now = self.where(s.loc)
        if s.orelse:
            self.emit("else:")
            self.ind += 1
            self.block(s.orelse)
            self.ind -= 1
        self.ind -= depth

    def if_flag(self, s: A.If) -> None:
        """A long IF/ELSIF chain without nesting: a flag says that no branch was taken yet
        (``elif`` nests in Python's tree, and thousands of them overflow its compiler)."""
        todo = self.new_tmp("_m")
        self.emit(f"{todo} = True")
        for i, (cond, body) in enumerate(s.branches):
            self.where_now = self.where(s.loc)
            if i:
                self.emit(f"if {todo}:")
                self.ind += 1
            code = self.ex(cond)
            self.flush_pre()
            self.emit(f"if {code}:")
            self.ind += 1
            self.emit(f"{todo} = False")
            self.block(body)
            self.ind -= 2 if i else 1
        if s.orelse:
            self.where_now = self.where(s.loc)
            self.emit(f"if {todo}:")
            self.ind += 1
            self.block(s.orelse)
            self.ind -= 1

    def s_Case(self, s: A.Case) -> None:
        sel = self.own_value(self.ex(s.selector), s.selector)
        self.flush_pre()
        tmp = self.new_tmp("_c")
        self.emit(f"{tmp} = {sel}")
        if sum(len(b.labels) for b in s.branches) > SMALL_CASE and self.case_table(s, tmp):
            return
        kw = "if"
        for b in s.branches:
            tests = []
            for lab in b.labels:
                if isinstance(lab, tuple):
                    tests.append(f"{self.ex(lab[0])} <= {tmp} <= {self.ex(lab[1])}")
                else:
                    tests.append(f"{tmp} == {self.ex(lab)}")
            self.emit(f"{kw} " + " or ".join(tests) + ":")
            kw = "elif"
            self.ind += 1
            self.block(b.body)
            self.ind -= 1
        if s.orelse:
            if kw == "if":
                self.block(s.orelse)
            else:
                self.emit("else:")
                self.ind += 1
                self.block(s.orelse)
                self.ind -= 1

    def _watchdog(self, loc: Location) -> None:
        for line in self.watchdog_lines(self.where(loc)):  # fastpaths.py
            self.emit(line)

    def s_While(self, s: A.While) -> None:
        if not self.local_watchdog(s.body, s.cond, lambda: self.plain_while(s)):
            self.plain_while(s)

    def plain_while(self, s: A.While) -> None:
        cond = self.ex(s.cond)
        if self.pre:
            pre, self.pre = self.pre, []
            self.emit("while True:")
            self.ind += 1
            self._watchdog(s.loc)
            for line in pre:
                self.emit(line)
            self.emit(f"if not {cond}: break")
        else:
            self.emit(f"while {cond}:")
            self.ind += 1
            self._watchdog(s.loc)
        self.loops.append(("while", None))
        self.block(s.body)
        self.loops.pop()
        self.ind -= 1

    def s_Repeat(self, s: A.Repeat) -> None:
        if not self.local_watchdog(s.body, s.cond, lambda: self.plain_repeat(s)):
            self.plain_repeat(s)

    def plain_repeat(self, s: A.Repeat) -> None:
        self.emit("while True:")
        self.ind += 1
        self._watchdog(s.loc)
        self.loops.append(("repeat", s.cond))
        self.block(s.body)
        self.loops.pop()
        self.where_now = self.where(s.cond.loc)
        cond = self.ex(s.cond)
        self.flush_pre()
        self.emit(f"if {cond}: break")
        self.ind -= 1

    def s_Exit(self, s: A.Exit) -> None:
        if self.helper is not None and not self.loops:  # the loop is outside this helper
            self.helper_return(EXIT)
            return
        self.emit("break")

    def s_Continue(self, s: A.Continue) -> None:
        if self.helper is not None and not self.loops:
            self.helper_return(CONTINUE)
            return
        kind, cond = self.loops[-1] if self.loops else ("while", None)
        if kind == "repeat" and cond is not None:
            c = self.ex(cond)
            self.flush_pre()
            self.emit(f"if {c}: break")
        self.emit("continue")

    def s_Return(self, s: A.Return) -> None:
        if self.helper is not None:
            self.helper_return(RETURN)
            return
        if self.pou is not None and self.pou.kind in ("FUNCTION", "METHOD"):
            self.emit(self.function_return(self.pou))
        else:
            self.emit("return")

    def s_For(self, s: A.For) -> None:
        if not self.local_for(s, self.plain_for):  # fastpaths.py
            self.plain_for(s)

    def plain_for(self, s: A.For) -> None:
        """FOR as the hardware runs it: ``v := v + step`` wraps at the variable's type limits.
        When the bounds and a literal step prove that the loop ends without wrapping, it is a
        plain Python ``range`` charged to the watchdog up front; otherwise ``_frange`` decides
        at run time (a ``range``, or a wrapping iterator that charges each pass)."""
        var = self.ex(s.var)
        start = self.coerce(self.ex(s.start), s.start.ty, s.var.ty, s.start)
        end = self.coerce(self.ex(s.end), s.end.ty, s.var.ty, s.end)
        self.flush_pre()
        w = self.where(s.loc)
        vt = T.base_of(s.var.ty)
        lo, hi = (vt.lo, vt.hi) if isinstance(vt, T.Elementary) and vt.bits else (None, None)
        step_v = None
        if s.step is None:
            step_v = 1
        elif isinstance(s.step, A.Literal) and isinstance(s.step.value, int):
            step_v = s.step.value
        has_exit = any(isinstance(x, A.Exit | A.Return) for x in A.walk_stmts(s.body))
        rng = self.new_tmp("_r")
        r_end = self._bound_range(s.end)
        proven = step_v is not None and step_v != 0 and (lo is None or r_end is not None and (
            r_end[1] + step_v <= hi if step_v > 0 else r_end[0] + step_v >= lo))
        if proven:
            stop = f"{end} + 1" if step_v > 0 else f"{end} - 1"
            if step_v == 1:
                self.emit(f"{rng} = range({start}, {stop})")
            else:
                self.emit(f"{rng} = range({start}, {stop}, {step_v})")
        else:
            step = self.ex(s.step) if s.step is not None else "1"
            self.flush_pre()
            budget = "None" if has_exit else "_B"
            self.emit(f"{rng} = _frange({start}, {end}, {step}, {lo}, {hi}, {w}, {budget})")
        if not has_exit:
            self.emit(f"_B.left -= len({rng})")
            self.emit(f"if _B.left < 0: _wd({w})")
        # a known range for the loop variable lets array indexing skip its bounds check
        r_start, r_end = self.interval(s.start), self.interval(s.end)
        saved = self.safe.get(var)
        if proven and r_start is not None and r_end is not None and self.loop_var_guarded(s):
            # inside the body the variable lies between start and end, whatever the step
            self.safe[var] = (min(r_start[0], r_end[0]), max(r_start[1], r_end[1]))
        else:
            self.safe.pop(var, None)
        self.emit(f"for {var} in {rng}:")
        self.ind += 1
        if has_exit:
            self._watchdog(s.loc)
        self.loops.append(("for", None))
        self.block(s.body)
        self.loops.pop()
        self.ind -= 1
        self.emit("else:")
        self.ind += 1
        if proven:
            self.emit(f"{var} = {rng}.start + len({rng}) * {rng}.step")
        else:
            self.emit(f"{var} = _fend({rng})")
        self.ind -= 1
        if saved is not None:
            self.safe[var] = saved
        else:
            self.safe.pop(var, None)

    # -- sizes: deep blocks, large CASEs ------------------------------------------------------
    # Python limits what it compiles: 100 levels of indentation, 20 nested loops, nesting of
    # its own syntax tree (each ``elif`` is one level deeper), 200 nested parentheses. The
    # generated code stays under those limits whatever the size of the ST program:
    # * a block nested deeper than OUTLINE_INDENT (or inside OUTLINE_LOOPS loops) becomes a
    #   module-level helper function ``_hN`` (see :meth:`outline`);
    # * a CASE with many labels dispatches through a table and a binary tree of ifs;
    # * a long IF/ELSIF chain uses a flag instead of nested ``elif``;
    # * an expression gets a temporary every SPILL_LEVEL levels of nesting (see :meth:`ex`).
    def outline(self, stmts: list[A.Stmt]) -> None:
        """Emit ``stmts`` as a helper function at module level, and its call here.

        The helper takes ``self`` (in a method) and the ``v_X`` locals its code uses, and
        returns ``(signal, *locals)``: the locals it may have changed, and whether the block
        ended normally or by EXIT, CONTINUE or RETURN of a loop or function outside it; the
        call site then does the same in its own context (which may be another helper)."""
        self.outline_code(lambda: self.block(stmts), stmts[0].loc)

    def outline_code(self, make, loc: Location, extra: tuple[str, ...] = ()) -> None:
        """Like :meth:`outline` for the code that ``make()`` emits; ``extra`` are temporaries
        it reads (passed in, not returned)."""
        name = self.new_tmp("_h")
        call_where = self.where_now
        outer = (self.lines, self.line_where, self.ind, self.loops, self.helper, self.pre)
        self.lines, self.line_where, self.ind, self.loops, self.pre = [], [], 1, [], []
        helper = self.helper = _Helper()
        self.where_now = self.where(loc)
        make()
        self.helper_return(NORMAL)
        lines, where = self.lines, self.line_where
        self.lines, self.line_where, self.ind, self.loops, self.helper, self.pre = outer
        used = sorted(self.locals & set(_LOCAL_NAME.findall("\n".join(lines))))
        params = (["self"] if self.has_self else []) + list(extra) + used
        tail = "".join(f", {v}" for v in used)
        lines = [line.replace(_LOCALS, tail) for line in lines]
        self.helpers.append(([f"def {name}({', '.join(params)}):"] + lines + [""],
                             [where[0] if where else call_where] + where + [0]))
        self.where_now = call_where
        sig = self.new_tmp("_s")
        self.emit(f"{sig}{tail} = {name}({', '.join(params)})")
        for signal, stmt in ((EXIT, A.Exit), (CONTINUE, A.Continue), (RETURN, A.Return)):
            if signal in helper.signals:
                self.emit(f"if {sig} == {signal}:")
                self.ind += 1
                self.stmt(stmt(self.locations[call_where] or Location()))
                self.ind -= 1
                self.where_now = call_where

    def helper_return(self, signal: int) -> None:
        """Leave the helper being generated with ``signal`` (the locals are filled in later)."""
        assert self.helper is not None
        self.helper.signals.add(signal)
        self.emit(f"return {signal}{_LOCALS}")

    def case_table(self, s: A.Case, sel: str) -> bool:
        """A large CASE: the branch number from a dict (single values) or a binary search
        (ranges), then a balanced tree of ``if`` on that number. False if a label is not a
        known constant (the checker reports that), so the plain if-chain is used."""
        singles: dict[int, int] = {}
        ranges: list[tuple[int, int, int]] = []
        for k, b in enumerate(s.branches):
            for lab in b.labels:
                if isinstance(lab, tuple):
                    lo, hi = self.label_const(lab[0]), self.label_const(lab[1])
                    if lo is None or hi is None:
                        return False
                    if lo <= hi:
                        ranges.append((lo, hi, k))
                else:
                    v = self.label_const(lab)
                    if v is None:
                        return False
                    singles.setdefault(v, k)
        segments = _segments(ranges)
        if segments:  # a value in an earlier branch's range is not the later single's
            starts = [lo for lo, _, _ in segments]
            for v, k in list(singles.items()):
                i = bisect.bisect_right(starts, v) - 1
                if i >= 0 and v <= segments[i][1] and segments[i][2] < k:
                    del singles[v]
        nb = len(s.branches)
        table = self.new_tmp("_CASE")
        self.tables.append(f"{table} = dict(zip({tuple(singles)!r}, {tuple(singles.values())!r}))")
        k = self.new_tmp("_k")
        if segments:
            rng = self.new_tmp("_CASE")
            self.tables.append(f"{rng} = ({tuple(x[0] for x in segments)!r}, "
                               f"{tuple(x[1] for x in segments)!r}, "
                               f"{tuple(x[2] for x in segments)!r})")
            self.emit(f"{k} = {table}.get({sel})")
            self.emit(f"if {k} is None: {k} = _case_range({sel}, {rng}, {nb})")
        else:
            self.emit(f"{k} = {table}.get({sel}, {nb})")
        bodies = [b.body for b in s.branches] + ([s.orelse] if s.orelse else [])
        self.case_tree(s, k, bodies, 0, len(bodies))
        return True

    def case_tree(self, s: A.Case, k: str, bodies: list[list[A.Stmt]], lo: int, hi: int,
                  top: bool = True) -> None:
        """Branches ``lo..hi-1``: halve the range until a few are left, then test each. Parts
        of CASE_CHUNK branches go into helper functions (Python compiles many medium-sized
        functions faster than one huge one)."""
        self.where_now = self.where(s.loc)
        if top and hi - lo <= CASE_CHUNK < len(bodies):
            self.outline_code(lambda: self.case_tree(s, k, bodies, lo, hi, False), s.loc, (k,))
            return
        if hi - lo <= MAX_ELIF:
            for i in range(lo, hi):
                self.emit(f"{'if' if i == lo else 'elif'} {k} == {i}:")
                self.ind += 1
                self.block(bodies[i])
                self.ind -= 1
                self.where_now = self.where(s.loc)
            return
        mid = (lo + hi) // 2
        self.emit(f"if {k} < {mid}:")
        self.ind += 1
        self.case_tree(s, k, bodies, lo, mid, top)
        self.ind -= 1
        self.emit("else:")
        self.ind += 1
        self.case_tree(s, k, bodies, mid, hi, top)
        self.ind -= 1

    def label_const(self, e: A.Expr) -> int | None:
        """The value of a CASE label: a literal, an enumeration value or a constant."""
        if isinstance(e, A.Unary) and e.op == "-":
            v = self.label_const(e.operand)
            return None if v is None else -v
        if isinstance(e, A.Literal):
            if e.kind == "ENUM":
                return e.enum_value
            v = e.value
        elif isinstance(e, A.Name) and isinstance(e.sym, EnumSym):
            v = e.sym.value
        elif isinstance(e, A.Name) and isinstance(e.sym, VarSym) and e.sym.decl.constant:
            v = self.p.const_values.get(id(e.sym.decl))
        else:
            return None
        return int(v) if isinstance(v, int) else None

    def _bound_range(self, e: A.Expr) -> tuple[int, int] | None:
        """The values a FOR bound can take: a known interval, or its type's range when it is
        a stored value (stored integers always lie in their type)."""
        r = self.interval(e)
        if r is not None:
            return r
        t = T.resolve(e.ty) if e.ty is not None else None
        if isinstance(e, _SIMPLE) and isinstance(t, T.Elementary | T.Subrange) and \
                t.kind == "int":
            return (t.lo, t.hi)
        return None


# limits of the generated code (see "-- sizes" in Codegen)
OUTLINE_INDENT = 40  # Python allows 100 levels of indentation
OUTLINE_LOOPS = 12  # ... and 20 nested loops
MAX_ELIF = 8  # ... and a few hundred elif (they nest in its syntax tree)
CASE_CHUNK = 128  # branches of a large CASE per helper function
SMALL_CASE = 16  # up to this many labels a CASE is an if/elif chain (fastest when small)
SPILL_LEVEL = 12  # expression nesting between temporaries (Python allows 200 parentheses)
NORMAL, EXIT, CONTINUE, RETURN = 0, 1, 2, 3  # how an outlined block ended
_LOCALS = "\x00"  # placeholder for the locals a helper returns (repr() never writes a NUL)
_LOCAL_NAME = re.compile(r"\bv_[A-Z0-9_]+\b")


@dataclass
class OutlinedBlock:
    """An outlined block being generated: the signals its code may return."""

    signals: set[int] = field(default_factory=set)


_Helper = OutlinedBlock


def _segments(ranges: list[tuple[int, int, int]]) -> list[tuple[int, int, int]]:
    """Disjoint sorted (lo, hi, branch) from CASE ranges (lo, hi, branch) that may overlap;
    where they do, the first branch wins, as in the if-chain.

    >>> _segments([(1, 10, 0), (5, 20, 1)])
    [(1, 10, 0), (11, 20, 1)]
    """
    points = sorted({lo for lo, _, _ in ranges} | {hi + 1 for _, hi, _ in ranges})
    starts = sorted(ranges)
    active: list[tuple[int, int]] = []  # heap of (branch, hi)
    out: list[tuple[int, int, int]] = []
    i = 0
    for a, b in zip(points, points[1:], strict=False):
        while i < len(starts) and starts[i][0] <= a:
            heapq.heappush(active, (starts[i][2], starts[i][1]))
            i += 1
        while active and active[0][1] < a:
            heapq.heappop(active)
        if active:
            k = active[0][0]
            if out and out[-1][1] == a - 1 and out[-1][2] == k:
                out[-1] = (out[-1][0], b - 1, k)
            else:
                out.append((a, b - 1, k))
    return out
