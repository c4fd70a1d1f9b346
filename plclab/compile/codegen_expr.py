"""The code of expressions: coercion on store, names, members, indices, operators, calls and
conversions (a mixin of :class:`plclab.compile.codegen.Codegen`).
"""

from __future__ import annotations

import math

from ..errors import Location
from ..lang import ast as A
from ..lang import types as T
from ..lang.builtins import BUILTINS
from ..lang.check import CallInfo, EnumSym, ProgSym, VarSym
from ..lang.dialect import profile as dialect_profile
from ..lang.walk import UnhandledNode
from . import oop_emit
from .builtins_emit import EMITTERS, Emission, const_int
from .codegen_names import ident
from .real32 import f32 as _f32

SIMPLE_NODES = (A.Name, A.Member, A.Index, A.Literal)  # operands that need no temporary
_SIMPLE = SIMPLE_NODES


class ExprEmit:
    """Expressions and coercion (a mixin of Codegen)."""

    # -- coercion on store --------------------------------------------------------------------
    def coerce(self, code: str, src: T.Type | None, dst: T.Type | None, e: A.Expr | None) -> str:
        if dst is None or src is None:
            return code
        d = T.resolve(dst)
        s = T.resolve(src)
        if d is T.ANY or s is T.ANY:
            return code
        simple = isinstance(e, _SIMPLE) or (isinstance(e, A.Call) and e.target is not None and
                                            (e.target.kind in ("function", "conv") or
                                             _in_range_builtin(e)))
        if isinstance(d, T.Subrange):
            if isinstance(e, A.Literal) and isinstance(e.value, int):
                return code
            if isinstance(s, T.Subrange) and d.lo <= s.lo and s.hi <= d.hi:
                return code
            return f"_subr({code}, {d.lo}, {d.hi}, {self.where_now})"
        if isinstance(d, T.Elementary):
            k = d.kind
            if k in ("int", "bits", "time", "date", "tod", "dt"):
                if isinstance(e, A.Literal) and isinstance(e.value, int) and not isinstance(
                        e.value, bool):
                    return code
                sb = T.base_of(s)
                if s is T.BOOL or sb is T.BOOL:
                    return f"int({code})"
                if k == "time" and d is T.LTIME and sb is T.TIME:
                    return f"({code} * 1000000)" if simple else self.wrap(f"{code} * 1000000", d)
                if simple and (sb is d or (T.can_widen(sb, d) and sb.kind in ("int", "bits"))):
                    return code
                if isinstance(s, T.EnumType):
                    return code
                if sb.kind == "real":
                    return self.wrap(f"_round({code})", d)
                return self.wrap(code, d)
            if d is T.REAL:
                if isinstance(e, A.Literal) and isinstance(e.value, int | float) and not \
                        isinstance(e.value, bool):
                    return _float_code(e.value, single=True)
                if T.base_of(s) is T.REAL and simple and not _from_native(e):
                    return code
                if T.base_of(s).kind in ("int", "bits"):
                    return f"_i2r({code})"
                return f"_f32({code})"
            if d is T.LREAL:
                if isinstance(e, A.Literal) and isinstance(e.value, int | float):
                    return _float_code(e.value, single=False)
                if T.base_of(s) is T.REAL and e is not None:  # a REAL sum is a REAL value
                    return self.own_value(code, e)  # (ADR 0038): as REAL_TO_LREAL sees it
                if T.base_of(s).kind == "real":
                    return code
                return f"_fl({code})"
            return code
        if isinstance(d, T.StringType):
            if isinstance(s, T.StringType) and s.length <= d.length:
                return code
            return f"{code}[:{d.length}]"
        return code

    def own_value(self, code: str, e: A.Expr) -> str:
        """The value of ``e`` as its own type holds it, where it is used without a store: a
        conversion's argument, a CASE selector, an array index. Operators compute exactly (in
        a register), so ``s * s * s`` of SINTs may lie outside SINT; ``SINT_TO_INT`` then sees
        the SINT the hardware would hold, wrapped, and a REAL sum is rounded to single
        precision first (``REAL_TO_DINT(r + 1.0)``). A stored value, a literal, a call of a
        function or conversion and a value proven in range need nothing (ADR 0038)."""
        if e.ty is None:
            return code
        t = T.base_of(e.ty)
        if not isinstance(t, T.Elementary) or t is T.ANY_INT_LIT:
            return code
        if t.kind in _WRAPPED_KINDS and t.bits:
            if isinstance(e, A.Literal) or (_stored_value(e) and t.kind != "real"):
                return code
            r = self.interval(e)
            if r is not None and t.lo <= r[0] and r[1] <= t.hi:
                return code
            return self.wrap(code, t)
        if t is T.REAL and not (_stored_value(e) and not _from_native(e)) and \
                not isinstance(e, A.Literal):
            return f"_f32({code})"
        return code

    @staticmethod
    def wrap(code: str, t: T.Elementary) -> str:
        bits = t.bits
        mask = (1 << bits) - 1
        if t.signed:
            half = 1 << (bits - 1)
            return f"(((({code}) + {half}) & {mask}) - {half})"
        return f"(({code}) & {mask})"

    # -- expressions --------------------------------------------------------------------------
    def ex(self, e: A.Expr) -> str:
        """The Python code of ``e``. Long left chains (``a + b + c + ...``) are generated
        bottom-up with a loop (:meth:`chain`); every SPILL_LEVEL levels of nesting the code
        so far goes into a temporary (a line in ``self.pre``), so no generated line nests
        deeper than Python can parse. Targets of assignments are never moved."""
        made = self._memo.pop(id(e), None)
        if made is None:
            if isinstance(e, A.Binary) and isinstance(e.left, A.Binary):
                self.chain(e.left)
            made = self.ex_node(e)
        code, level = made
        if self._levels[-1] < level:
            self._levels[-1] = level
        return code

    def ex_node(self, e: A.Expr) -> tuple[str, int]:
        """(code, nesting since the last temporary) of one node."""
        self._levels.append(0)
        try:
            method = getattr(self, "e_" + type(e).__name__, None)
            if method is None:  # ArrayInit / StructInit go through init_code
                raise UnhandledNode("Codegen.ex_node", e)
            code = method(e)
        finally:
            level = self._levels.pop() + 1
        if level >= SPILL_LEVEL and not e.is_target:
            tmp = self.new_tmp()
            self.pre.append(f"{tmp} = {code}")
            return tmp, 0
        return code, level

    def chain(self, e: A.Expr) -> None:
        """Make the code of a long left spine of binary operators ahead, deepest first, so
        that each node finds its left operand made (no recursion along the chain)."""
        spine = []
        while isinstance(e, A.Binary) and id(e) not in self._memo:
            spine.append(e)
            e = e.left
        if len(spine) >= 8:
            for node in reversed(spine):
                self._memo[id(node)] = self.ex_node(node)

    def e_Literal(self, e: A.Literal) -> str:
        v = e.value
        k = e.kind
        if k == "BOOL" or (k == "INT" and e.ty is T.BOOL):  # TRUE, FALSE, and 0/1 as BOOL
            return "True" if v else "False"
        if k == "TIME":
            t = T.resolve(e.ty) if e.ty is not None else T.TIME
            if t is T.LTIME:
                return repr(int(v))
            q = abs(v) // 1_000_000
            return repr(-q if v < 0 else q)
        if k == "ENUM":
            return repr(e.enum_value or 0)
        if k == "REAL":
            return _float_code(v, single=T.resolve(e.ty) is T.REAL)
        if k == "INT" and e.ty is not None and T.resolve(e.ty).kind == "real":
            return _float_code(v, single=False)
        return repr(v)

    def e_Name(self, e: A.Name) -> str:
        sym = e.sym
        if isinstance(sym, VarSym):
            if sym.storage == "global":
                return f"_G.{ident(sym.decl.name)}"
            if sym.storage == "resource":  # the resource running this instance's (ADR 0037)
                return f"_R.{ident(sym.decl.name)}"
            if sym.storage == "self":
                code = f"self.{ident(sym.decl.name)}"
                return self.local_names.get(code, code)  # a local in a fast loop
            if sym.storage in ("this", "super"):  # THIS^, SUPER^ (ADR 0021)
                return "self"
            return f"v_{ident(sym.decl.name)}"
        if isinstance(sym, EnumSym):
            return repr(sym.value)
        if isinstance(sym, ProgSym):
            return f"_P.{ident(sym.instance)}"
        if isinstance(sym, A.Pou):  # a bare PROPERTY name in its own block: its GET
            return f"self.{oop_emit.method_name(sym)}()"
        return "None"

    def e_DirectAddr(self, e: A.DirectAddr) -> str:
        return self.addr_read(e.address)

    def e_Member(self, e: A.Member) -> str:
        if isinstance(e.sym, EnumSym):  # Color.Red (CODESYS)
            return repr(e.sym.value)
        if isinstance(e.sym, A.Pou):  # a PROPERTY's GET (ADR 0021)
            return oop_emit.property_call(self, e, None)
        if e.field_name == "^":  # r^ (ADR 0021)
            return f"{oop_emit.deref(self, e)}.get()"
        obj = self.ex(e.obj)
        part = A.partial_access(e.field_name)
        if part is not None and part[0] == "X":
            return f"({obj} >> {part[1]} & 1 != 0)"
        if part is not None:  # x.%B1: a byte of x (IEC 61131-3 ed.3 Table 17)
            width = A.PARTIAL_WIDTHS[part[0]]
            return f"({obj} >> {part[1] * width} & {(1 << width) - 1})"
        return f"{obj}.{ident(e.field_name)}"

    def e_Index(self, e: A.Index) -> str:
        obj = self.ex(e.obj)
        at = T.resolve(e.obj.ty)
        if isinstance(at, T.VarArrayType):  # ARRAY[*]: bounds of the argument (ADR 0060)
            ixs = "".join(f"{self.own_value(self.ex(ix), ix)}, " for ix in e.indices)
            return f"{obj}.data[_vla_ix({obj}, ({ixs}), {self.where(e.loc)})]"
        if not isinstance(at, T.ArrayType):
            return f"{obj}[0]"
        parts = []
        stride = 1
        strides = []
        for lo, hi in reversed(at.dims):
            strides.append(stride)
            stride *= hi - lo + 1
        strides.reverse()
        for ix, (lo, hi), st in zip(e.indices, at.dims, strides, strict=True):
            parts.append((self.index_code(ix, lo, hi), st))
        flat = " + ".join(p if st == 1 else f"({p}) * {st}" for p, st in parts)
        return f"{obj}[{flat}]"

    def index_code(self, ix: A.Expr, lo: int, hi: int) -> str:
        code = self.own_value(self.ex(ix), ix)
        c = const_int(ix)
        off = f" - {lo}" if lo > 0 else (f" + {-lo}" if lo < 0 else "")
        if c is not None:
            return str(c - lo)
        rng = self.interval(ix)
        if rng is not None and lo <= rng[0] and rng[1] <= hi:
            folded = self.folded_index(ix, lo)  # fastpaths.py
            if folded is not None:
                return folded
            return f"({code}){off}" if off else code
        w = self.where(ix.loc)
        if isinstance(ix, A.Name | A.Member):
            return f"({code}{off} if {lo} <= {code} <= {hi} else _oob({code}, {lo}, {hi}, {w}))"
        t = self.new_tmp()
        return f"({t}{off} if {lo} <= ({t} := {code}) <= {hi} else _oob({t}, {lo}, {hi}, {w}))"

    def interval(self, e: A.Expr) -> tuple[int, int] | None:
        """The range an integer expression surely lies in (literals, FOR variables with known
        bounds, + and - of those), or None: lets indexing skip its bounds check."""
        c = const_int(e)
        if c is not None:
            return (c, c)
        if isinstance(e, A.Name):
            return self.safe.get(self.e_Name(e))
        if isinstance(e, A.Binary) and e.op in ("+", "-"):
            a, b = self.interval(e.left), self.interval(e.right)
            if a is None or b is None:
                return None
            r = (a[0] + b[0], a[1] + b[1]) if e.op == "+" else (a[0] - b[1], a[1] - b[0])
            t = T.base_of(e.ty) if e.ty is not None else None
            if self.operand_width(e.loc) and isinstance(t, T.Elementary) and t.bits and \
                    t.kind in ("int", "bits") and not t.lo <= r[0] <= r[1] <= t.hi:
                return None  # S7 wraps the sum in the operands' width: no interval known
            return r
        return None

    def e_Unary(self, e: A.Unary) -> str:
        x = self.ex(e.operand)
        t = T.base_of(e.ty) if e.ty is not None else T.ANY
        if e.op == "NOT":
            if t is T.BOOL:
                return f"(not {x})"
            if isinstance(t, T.Elementary) and not t.signed:
                return f"({x} ^ {(1 << t.bits) - 1})"
            return f"(~{x})"
        return f"(-{x})"

    def e_Binary(self, e: A.Binary) -> str:
        op = e.op
        left, right = self.ex(e.left), self.ex(e.right)
        t = T.base_of(e.ty) if e.ty is not None else T.ANY
        lt = T.base_of(e.left.ty) if e.left.ty is not None else T.ANY
        rt = T.base_of(e.right.ty) if e.right.ty is not None else T.ANY
        if op in ("AND", "OR", "XOR"):
            return f"({left} {dict(AND='&', OR='|', XOR='^')[op]} {right})"
        if op in ("=", "<>", "<", "<=", ">", ">="):
            if lt is T.LREAL and rt is T.REAL:  # compared as LREAL: the REAL value (ADR 0038)
                right = self.own_value(right, e.right)
            elif rt is T.LREAL and lt is T.REAL:
                left = self.own_value(left, e.left)
            if lt is T.LTIME and rt is T.TIME:
                right = f"({right} * 1000000)"
            elif rt is T.LTIME and lt is T.TIME:
                left = f"({left} * 1000000)"
            if isinstance(lt, T.RefType | T.InterfaceType) and _is_zero(e.right):
                right = "None"  # CODESYS: IF itf <> 0 (ed.3 writes NULL; ADR 0059)
            elif isinstance(rt, T.RefType | T.InterfaceType) and _is_zero(e.left):
                left = "None"
            pyop = {"=": "==", "<>": "!="}.get(op, op)
            return f"({left} {pyop} {right})"
        if t is T.LREAL:  # a REAL operand of an LREAL operation is a REAL value (ADR 0038)
            if lt is T.REAL:
                left = self.own_value(left, e.left)
            if rt is T.REAL and op != "**":  # an exponent is not widened: it keeps its type
                right = self.own_value(right, e.right)
        if t.kind == "time" and t is T.LTIME:
            if lt is T.TIME:
                left = f"({left} * 1000000)"
            if rt is T.TIME:
                right = f"({right} * 1000000)"
        if op in ("/", "MOD"):
            fast = self.div_by_literal(e, left)  # fastpaths.py
            if fast is not None:
                return fast
        if op == "/":
            if t.kind in ("int", "bits") or (t.kind == "time" and rt.kind in ("int", "bits")):
                return f"_idiv({left}, {right})"
            if t.kind == "time":
                return f"_round(_rdiv({left}, {right}))"
            fast = self.real_division(e, left, right)  # fastpaths.py
            return fast if fast is not None else f"_rdiv({left}, {right})"
        if op == "MOD":
            return f"_imod({left}, {right})"
        if op == "-" and lt.kind == "date" and rt.kind == "date":  # seconds -> TIME in ms
            return f"(({left} - {right}) * 1000)"
        if op == "**":
            return f"_expt({left}, {right})"
        if op == "*" and t.kind == "time" and (lt.kind == "real" or rt.kind == "real"):
            return f"_round({left} * {right})"
        if op in ("+", "-", "*") and t.kind in ("int", "bits") and isinstance(t, T.Elementary) \
                and t is not T.ANY_INT_LIT and self.operand_width(e.loc):
            return self.wrap(f"{left} {op} {right}", t)  # S7: the operand type's width
        return f"({left} {op} {right})"

    def dialect_at(self, loc: Location | None):
        """The dialect of the file ``loc`` is in (ADR 0017)."""
        if not self.p.dialects:  # every file in the default dialect (the common case)
            return dialect_profile(None)
        return dialect_profile(self.p.dialects.get(loc.file) if loc is not None else None)

    def operand_width(self, loc: Location | None) -> bool:
        """Whether integer intermediates wrap to their type here (the S7 dialect, ADR 0017)
        instead of staying exact (CODESYS computes them in a register)."""
        return self.dialect_at(loc).operand_width

    def e_Call(self, e: A.Call) -> str:
        info: CallInfo | None = e.target
        if info is None:
            return "None"
        if info.en is not None or info.eno is not None:
            return self.enabled_call(e, info)
        return self.plain_call(e, info)

    def enabled_call(self, e: A.Call, info: CallInfo) -> str:
        """A function call with EN/ENO (IEC 61131-3 ed.3 6.6.1.6): EN is evaluated first; when
        it is FALSE the function is not called, the result is its type's default (as MATIEC)
        and ENO is FALSE; else ENO is TRUE."""
        en = self.new_tmp()
        self.pre.append(f"{en} = {self.ex(info.en) if info.en is not None else 'True'}")
        mark = len(self.pre)
        code = self.plain_call(e, info)
        inner = self.pre[mark:]
        del self.pre[mark:]
        if inner:  # the call's own statements (outputs, spilled temporaries) run only if EN
            self.pre.append(f"if {en}: " + "; ".join(inner))
        self.pre.extend(self.eno_false(info, en))
        if info.eno is not None:
            self.pre.append(self.store_code(info.eno, en))
        default = self.default_code(e.ty) if e.ty is not None and e.ty is not T.VOID \
            else "None"
        return f"({code} if {en} else {default})"

    def eno_false(self, info: CallInfo, en: str) -> list[str]:
        """``ENO => ok`` bound to a callee's own ENO output (declared, or the implicit one a
        body assigns, :mod:`plclab.lang.lower.implicit_eno`): FALSE when EN was FALSE and the
        body did not run (IEC 61131-3 ed.3 6.6.1.6)."""
        return [f"if not {en}: {self.store_code(tgt, 'False')}" for d, tgt, neg in info.outputs
                if getattr(d, "name", None) == "ENO" and not neg]

    def store_code(self, target: A.Expr, val: str) -> str:
        """One line storing ``val`` (a BOOL) into ``target`` (see :meth:`assign_to`)."""
        part = A.partial_access(target.field_name) if isinstance(target, A.Member) else None
        if part is not None:  # x.3 := v, x.%B1 := v (IEC 61131-3 ed.3 Table 17): x changes
            obj = self.ex(target.obj)
            kind, n = part
            if kind == "X":
                whole = f"(({obj}) | {1 << n}) if {val} else (({obj}) & ~{1 << n})"
            else:
                width = A.PARTIAL_WIDTHS[kind]
                mask, shift = (1 << width) - 1, n * width
                whole = f"(({obj}) & ~{mask << shift}) | ((({val}) & {mask}) << {shift})"
            return self.store_code(target.obj, whole)  # x.%W1.%B0 := v stores x.%W1
        if isinstance(target, A.DirectAddr):
            return self.addr_write(target.address, val)
        return f"{self.ex(target)} = {val}"

    def plain_call(self, e: A.Call, info: CallInfo) -> str:
        if info.kind == "conv":
            return self.conversion(info, e)
        if info.kind == "builtin":
            return self.builtin(info.callee.name, [x for _, x in info.inputs], e)
        if info.kind == "function":
            return self.user_function(info)
        if info.kind == "method":
            return oop_emit.method_call(self, e, info)
        if info.kind == "reference":
            return oop_emit.reference_operator(self, e, info)
        if info.kind == "sizeof":  # a constant the checker computed (plclab.lang.sizeof)
            return repr(int(info.callee))
        if info.kind == "bound":  # LOWER_BOUND / UPPER_BOUND (ADR 0060)
            upper, dim, static = info.callee
            if static is not None:
                return repr(static)
            return f"{self.ex(info.inputs[0][1])}.dims[{dim}][{int(upper)}]"
        return "None"

    def inout_code(self, d: A.VarDecl, e: A.Expr) -> str:
        """The value a VAR_IN_OUT receives: the variable itself, or for VAR_IN_OUT CONSTANT any
        value of the type, converted as an input would be."""
        want = T.resolve(d.ty)
        if isinstance(want, T.VarArrayType):  # an ARRAY[*] gets the array and its bounds
            at = T.resolve(e.ty)
            return f"_VLA({self.ex(e)}, {at.dims!r})" if isinstance(at, T.ArrayType) \
                else self.ex(e)
        return self.coerce(self.ex(e), e.ty, d.ty, e) if d.constant else self.ex(e)

    def user_function(self, info: CallInfo) -> str:
        pou: A.Pou = info.callee
        args = self.call_arguments(pou.decls, info)
        return self.call_with_results(f"F_{ident(pou.name)}({', '.join(args)})", pou.decls, info)

    def call_arguments(self, decls: list[A.VarDecl], info: CallInfo) -> list[str]:
        """The Python arguments of a FUNCTION or METHOD call: each VAR_INPUT (its initial value
        when not given) and VAR_IN_OUT, in declaration order."""
        given = {d.name: x for d, x in info.inputs}
        given_io = {d.name: x for d, x in info.inouts}
        args = []
        for d in decls:
            if d.section == "VAR_INPUT":
                x = given.get(d.name)
                if x is None:
                    args.append(self.init_code(d.init, d.ty))
                else:
                    code = self.coerce(self.ex(x), x.ty, d.ty, x)
                    if T.resolve(d.ty).is_aggregate:
                        code = self.copy_code(code, d.ty)
                    args.append(code)
            elif d.section == "VAR_IN_OUT":
                x = given_io.get(d.name)
                args.append(self.inout_code(d, x) if x is not None else "None")
        return args

    def call_with_results(self, call: str, decls: list[A.VarDecl], info: CallInfo) -> str:
        """``call`` (Python returning the result, then the VAR_OUTPUT and VAR_IN_OUT values) as
        an expression of its result; the outputs and in-outs go to their targets in ``pre``."""
        outs = [d for d in decls if d.section in ("VAR_OUTPUT", "VAR_IN_OUT")]
        if not outs:
            return call
        tmp = self.new_tmp("_f")
        self.pre.append(f"{tmp} = {call}")
        bound = {d.name: (tgt, neg) for d, tgt, neg in info.outputs}
        for d, x in info.inouts:
            if not T.resolve(d.ty).is_aggregate and not d.constant:
                bound[d.name] = (x, False)
        for i, d in enumerate(outs, start=1):
            if d.name in bound:
                tgt, neg = bound[d.name]
                v = f"{tmp}[{i}]"
                if neg:
                    v = f"(not {v})"
                lv = self.ex(tgt)
                self.pre.append(f"{lv} = {self.coerce(v, d.ty, tgt.ty, None)}")
        return f"{tmp}[0]"

    def conversion(self, info: CallInfo, e: A.Call) -> str:
        src_name, dst = info.callee
        x = info.inputs[0][1]
        code = self.own_value(self.ex(x), x)
        s = T.base_of(x.ty)
        d = T.resolve(dst)
        want = T.lookup_elementary(src_name) if src_name not in (None, "__TRUNC__") else None
        if want is not None and want.kind in ("int", "bits") and s.kind in ("int", "bits") and \
                s is not T.BOOL and not T.can_widen(s, want) and s is not want:
            code, s = self.wrap(code, want), want  # INT_TO_BYTE(d) of a DINT (PLC0285)
        if src_name == "__TRUNC__":
            return self.wrap(f"_trunc({code})", d) if d.kind in ("int", "bits") else code
        if isinstance(d, T.StringType):
            kind = ("bool" if s is T.BOOL else "real32" if s is T.REAL else
                    "real" if s.kind == "real" else "time" if s is T.TIME else
                    "ltime" if s is T.LTIME else "str" if isinstance(s, T.StringType) else "int")
            return f"_to_string({code}, {kind!r})"
        if isinstance(s, T.StringType):
            if d is T.BOOL:
                return f"_str_to_bool({code})"
            if d.kind == "real":
                return f"_str_to_real({code})" if d is T.LREAL else f"_f32(_str_to_real({code}))"
            if d.kind == "time":
                return f"_str_to_time({code})"
            return self.wrap(f"_str_to_int({code})", d)
        if s is T.DT and (d.kind in ("int", "bits", "real") or d is T.BOOL):
            # DT as a number counts seconds since 1970 (CODESYS "Conversion: DATE, DT, TOD",
            # Beckhoff "DT_TO conversions", MATIEC __time_to_int); plclab holds milliseconds
            code, s = f"({code} // 1000)", T.LINT
        elif d is T.DT and s.kind in ("int", "bits", "real"):
            whole = self.wrap(f"_round({code})", T.LINT) if s.kind == "real" else code
            return self.wrap(f"({whole} * 1000)", d)
        if d is T.BOOL:
            return f"({code} != 0)"
        if (s.kind == "time") != (d.kind == "time") and self.dialect_at(e.loc).time_in_seconds:
            return self.seconds_conversion(code, s, d)
        if d.kind == "real":
            if s.kind == "real":
                return f"_f32({code})" if d is T.REAL else code
            return f"_i2r({code})" if d is T.REAL else f"_fl({code})"
        if d.kind in ("int", "bits", "time", "date", "tod", "dt"):
            if s.kind == "real":
                return self.wrap(f"_round({code})", d)
            if s is T.LTIME and d is T.TIME:
                return self.wrap(f"_idiv({code}, 1000000)", d)
            if s is T.TIME and d is T.LTIME:
                return f"({code} * 1000000)"
            if s is T.BOOL:
                return f"int({code})"
            if s is T.DT and d is T.DATE:  # DT counts ms since 1970, DATE seconds
                return f"({code} // 86400000 * 86400)"
            if s is T.DT and d is T.TOD:  # ... TOD ms since midnight
                return f"({code} % 86400000)"
            if isinstance(s, T.Elementary) and s.kind in ("int", "bits", "time", "date", "tod",
                                                          "dt") and T.can_widen(s, d):
                return code
            return self.wrap(code, d)
        return code

    def seconds_conversion(self, code: str, s: T.Type, d: T.Type) -> str:
        """TIME <-> number in the MATIEC dialect: the number counts seconds (its
        ``__time_to_real`` is tv_sec + tv_nsec / 1e9, ``__time_to_int`` tv_sec; ``__int_to_time``
        and ``__real_to_time`` read seconds). TIME holds ms, LTIME ns."""
        if s.kind == "time":
            unit = 1_000 if s is T.TIME else 1_000_000_000
            if d.kind == "real":
                return f"_f32({code} / {unit})" if d is T.REAL else f"({code} / {unit})"
            return self.wrap(f"_idiv({code}, {unit})", d)  # whole seconds, toward zero
        unit = 1_000 if d is T.TIME else 1_000_000_000
        if s.kind == "real":
            return self.wrap(f"_round({code} * {unit})", d)
        return self.wrap(f"({code} * {unit})", d)

    def widen(self, code: str, src: T.Type | None, dst: T.Type | None,
              e: A.Expr | None = None) -> str:
        """An implicit widening inside an expression (MIN, SEL, GT...): an integer keeps its
        exact value but becomes a float for a REAL result, TIME becomes LTIME nanoseconds, and a
        REAL expression ``e`` widened to LREAL is its REAL value (ADR 0038, decision 4)."""
        if src is None or dst is None:
            return code
        s, d = T.base_of(src), T.base_of(dst)
        if s is d:
            return code
        if s is T.REAL and d is T.LREAL and e is not None:
            return self.own_value(code, e)
        if d.kind == "real" and s.kind in ("int", "bits") and s is not T.ANY_INT_LIT:
            return f"_fl({code})"
        if d is T.LTIME and s is T.TIME:
            return f"({code} * 1000000)"
        return code

    def builtin(self, name: str, args: list[A.Expr], e: A.Call) -> str:
        """A standard function call, by its emitter (``Builtin.emit``, :mod:`.builtins_emit`)."""
        spec = BUILTINS[name]
        t = T.base_of(e.ty) if e.ty is not None else T.ANY
        return EMITTERS[spec.emit](Emission(self, spec, [self.ex(a) for a in args], args, t, e))


SPILL_LEVEL = 12  # expression nesting between temporaries (Python allows 200 parentheses)


def _float_code(v: int | float, single: bool) -> str:
    """A REAL/LREAL literal as Python: an overflowing literal is infinity, as in IEEE."""
    try:
        x = float(v)
    except OverflowError:
        x = math.inf if v > 0 else -math.inf
    if single:
        x = _f32(x)
    if x in (math.inf, -math.inf):
        return "_math.inf" if x > 0 else "(-_math.inf)"
    return repr(x)


def _from_native(e: A.Expr | None) -> bool:
    """A value read from a native block or function: Python code that may hand back doubles,
    so a store into a REAL rounds it like an arithmetic result."""
    if isinstance(e, A.Member):
        t = T.resolve(e.obj.ty) if e.obj.ty is not None else None
        return isinstance(t, T.FBType) and t.pou is not None and t.pou.native is not None
    if isinstance(e, A.Call) and e.target is not None and e.target.kind == "function":
        return e.target.callee.native is not None
    return False


_WRAPPED_KINDS = ("int", "bits", "time", "date", "tod", "dt")


def _stored_value(e: A.Expr) -> bool:
    """An expression whose value already lies in its type: a variable, a member, an element,
    a call of a function or a conversion, or a builtin that cannot leave its range."""
    return isinstance(e, _SIMPLE) or (isinstance(e, A.Call) and e.target is not None and (
        e.target.kind in ("function", "conv") or _in_range_builtin(e)))


def _in_range_builtin(e: A.Call) -> bool:
    """Builtins whose result never leaves its type's range when their inputs are stored values
    (so a store needs no wrap-around code)."""
    info = e.target
    if info.kind != "builtin":
        return False
    name = info.callee.name
    args = [x for _, x in info.inputs]
    if name in ("LEN", "FIND"):
        return all(getattr(T.resolve(x.ty), "length", 99999) <= 32767 for x in args)
    if name in ("MIN", "MAX", "LIMIT", "MOVE", "SEL"):
        vals = args[1:] if name == "SEL" else args
        t = T.base_of(e.ty) if e.ty is not None else None
        return all(isinstance(x, _SIMPLE) and x.ty is not None and T.base_of(x.ty) is t
                   for x in vals) and isinstance(args[0], _SIMPLE)
    return False


def _is_zero(e: A.Expr) -> bool:
    """The integer literal 0, which CODESYS compares a reference or an interface with."""
    return isinstance(e, A.Literal) and e.kind == "INT" and e.value == 0
