"""Pass: calls -- functions, function block and program instances, standard functions and
conversions; binds arguments to parameters (PLC0106, PLC0107)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ...errors import Location
from .. import ast as A
from .. import types as T
from ..ast import expr_text
from ..builtins import BUILTINS, ED2_NAMES, Builtin, conversion
from ..lower import reference_to
from ..sizeof import sizeof, sizeof_type
from .pass_api import Pass
from .symbols import ProgSym, VarSym, close_hint
from .typing_rules import TYPING_RULES, Typing

_INPUTISH = ("VAR_INPUT", "VAR_IN_OUT")


@dataclass(eq=False)
class CallInfo:
    """A checked call: what is called and how its parameters bind (``Call.target``)."""

    kind: str  # "builtin" "conv" "function" "fb" "program" "method" "reference" "sizeof" "bound"
    callee: Any  # Builtin | (src, dst) | Pou
    inputs: list[tuple[Any, A.Expr]] = field(default_factory=list)  # (VarDecl|index, expr)
    outputs: list[tuple[Any, A.Expr, bool]] = field(default_factory=list)  # (VarDecl, target, neg)
    inouts: list[tuple[Any, A.Expr]] = field(default_factory=list)
    en: A.Expr | None = None  # EN := c (IEC 61131-3 ed.3 6.6.1.6): call only when TRUE
    eno: A.Expr | None = None  # ENO => ok: TRUE when the body ran
    pun: tuple[str, str] | None = None  # REF(x) read as another type of its size (PLC0291)


class Calls(Pass):
    """Checks calls, sets ``Call.target`` and records the call graph (for recursion)."""

    expected: T.Type | None = None  # the type the context of the call being checked expects

    def call(self, c: A.Call, statement: bool) -> T.Type:
        f = c.func
        if isinstance(f, A.Name):
            fname = f.name
            local = self.cx.exprs.lookup(fname)
            if isinstance(local, VarSym) and local.decl.section == "RETURN":
                local = None  # F(...) inside F is a (recursive) call, not the result variable
            if local is None and (fname.startswith("__") or fname in ("REF", "ADR")):
                # __ISVALIDREF, __QUERYINTERFACE, REF(), ADR() (ADR 0021)
                return self.cx.oop.reference_operator(c, fname)
            if local is None and fname == "SIZEOF" and "SIZEOF" not in self.table.pous and \
                    self.cx.dialect(c.loc).sizeof:
                return self.sizeof(c)
            if local is None and fname in ("LOWER_BOUND", "UPPER_BOUND") and \
                    fname not in self.table.pous:
                return self.bound(c, fname)
            if local is None and self._own_method(fname):
                # M(...) inside a block or its methods is THIS^.M(...) (CODESYS, ed.3 6.6.5)
                c.func = A.Member(f.loc, A.Name(f.loc, "THIS", "THIS^"), fname, f.text or fname)
                mt = self.cx.oop.method_call(c, statement)
                assert mt is not None
                return mt
            if local is None:
                pou = self.table.pous.get(fname)
                if pou is not None and pou.kind == "FUNCTION":
                    return self.call_function(c, pou)
                if pou is not None and pou.kind == "PROGRAM":
                    if not statement:
                        self.err("PLC0106", f"program {fname} is called as a statement, not in an "
                                 "expression", c.loc)
                    f.sym = ProgSym(pou, pou.name)
                    f.ty = self.table.types[pou.name]
                    return self.call_fb(c, pou, statement, program=True)
                if fname in BUILTINS or conversion(fname) is not None:
                    return self.call_builtin(c, fname, statement)
                if pou is not None and pou.kind == "FUNCTION_BLOCK":
                    self.err("PLC0106", f"{fname} is a function block type; declare an instance "
                             f"(e.g. my{fname.title()} : {fname};) and call the instance", c.loc)
                    self._args_only(c)
                    return T.ANY
                cands = [k for k, v in self.table.pous.items() if v.kind == "FUNCTION"] + list(
                    BUILTINS) + list(self.cx.scope)
                self.err("PLC0106", f"{fname} is not a function or function block instance" +
                         close_hint(fname, cands), c.loc)
                self._args_only(c)
                return T.ANY
        if isinstance(f, A.Member):  # inst.M(...): a METHOD (ADR 0021)
            mt = self.cx.oop.method_call(c, statement)
            if mt is not None:
                return mt
        ft = T.resolve(self.cx.exprs.expr(f, None))
        if isinstance(ft, T.FBType):
            if ft.pou.kind == "FUNCTION_BLOCK":
                if ft.pou.is_class:
                    self.err("PLC0341", f"{ft.pou.spelling or ft.pou.name} is a CLASS: it has "
                             "no body to call (IEC 61131-3 ed.3 6.6.5.2); call one of its "
                             "METHODs, e.g. inst.Method()", c.loc)
                    self._args_only(c)
                    return T.ANY
                return self.call_fb(c, ft.pou, statement)
            if ft.pou.kind == "PROGRAM":
                if not self.cx.in_test:
                    self.err("PLC0178", f"{ft.pou.name} is a PROGRAM: only a TEST block may "
                             "declare instances of a program; a POU calls the program by its "
                             f"name ({ft.pou.name}();)", c.loc)
                return self.call_fb(c, ft.pou, statement)
        if ft is not T.ANY:
            self.err("PLC0106", f"a value of type {ft} cannot be called", c.loc)
        self._args_only(c)
        return T.ANY

    def _var_array_arg(self, d: A.VarDecl, t: T.Type, a: A.Arg) -> bool:
        """Whether ``d`` is an ``ARRAY[*]`` in-out (checked here: True); the argument must be
        an array of as many dimensions and the same element type (ADR 0060)."""
        want = T.resolve(d.ty) if d.ty is not None else None
        if not isinstance(want, T.VarArrayType):
            return False
        if t is not T.ANY and not T.fits_var_array(t, want):
            self.err("PLC0107", f"VAR_IN_OUT {d.name} is {want}: pass an array of "
                     f"{want.ndims} dimension(s) of {want.elem}, not {t}", a.loc)
        return True

    def bound(self, c: A.Call, fname: str) -> T.Type:
        """``LOWER_BOUND(arr, dim)`` / ``UPPER_BOUND(arr, dim)``: a bound of dimension ``dim``
        (1 the first) of an array, a DINT (IEC 61131-3 ed.3 6.5.3; ADR 0060). Of an ``ARRAY[*]``
        it is read at run time; of an array with declared bounds it is a constant."""
        args = [a for a in c.args if a.value is not None]
        names = {a.name.upper() for a in args if a.name}
        if len(args) != 2 or any(a.output for a in args) or (
                names and names != {"ARR", "DIM"}):
            self.err("PLC0352", f"{fname} takes an array and a dimension number, e.g. "
                     f"{fname}(values, 1)", c.loc)
            self._args_only(c)
            return T.DINT
        if names:
            args.sort(key=lambda a: a.name.upper() != "ARR")
        arr, dim = args[0].value, args[1].value
        at = T.resolve(self.cx.exprs.expr(arr, None))
        self.cx.exprs.expr(dim, T.DINT)
        n = self.cx.consts.const_int(dim)
        if at is T.ANY:
            return T.DINT
        ndims = at.ndims if isinstance(at, T.VarArrayType) else len(at.dims) if isinstance(
            at, T.ArrayType) else 0
        if not ndims:
            self.err("PLC0352", f"{fname} needs an array, and {expr_text(arr)} is {at}", arr.loc)
            return T.DINT
        if n is None or not 1 <= n <= ndims:
            self.err("PLC0352", f"{fname}: the dimension must be a constant from 1 to {ndims} "
                     f"({expr_text(arr)} is {at})", dim.loc)
            return T.DINT
        static = None
        if isinstance(at, T.ArrayType):
            static = at.dims[n - 1][0 if fname == "LOWER_BOUND" else 1]
        c.target = CallInfo("bound", (fname == "UPPER_BOUND", n - 1, static), [(0, arr)])
        return T.DINT

    def sizeof(self, c: A.Call) -> T.Type:
        """``SIZEOF(x)`` of a variable or a type name: a constant of the smallest unsigned
        type that holds it (CODESYS, "Operator SIZEOF"; :mod:`plclab.lang.sizeof`)."""
        args = [a for a in c.args if a.value is not None]
        if len(args) != 1 or args[0].name or args[0].output:
            self.err("PLC0197", "SIZEOF takes one variable or data type, e.g. SIZEOF(buffer) "
                     "or SIZEOF(INT)", c.loc)
            self._args_only(c)
            return T.ANY
        x = args[0].value
        t: T.Type | None = None
        if isinstance(x, A.Name) and self.cx.exprs.lookup(x.name) is None:
            t = T.lookup_elementary(x.name) or self.table.types.get(x.name)
            if t is not None:
                x.ty = t
        if t is None:
            t = self.cx.exprs.expr(x, None)
        if t is T.ANY:
            return T.UDINT
        n = sizeof(t)
        if n is None:
            self.err("PLC0197", f"SIZEOF({expr_text(x)}): the size of {T.resolve(t).name} "
                     "(a function block instance, an interface or a reference) depends on the "
                     "target's code and pointers; plclab gives sizes of data types only", c.loc)
            return T.UDINT
        c.target = CallInfo("sizeof", n)
        return sizeof_type(n)

    def _own_method(self, name: str) -> bool:
        """Whether ``name`` is a METHOD (or ACTION) of the block or program whose body or
        method is being checked (an unqualified call of it is a call on THIS^), and ``THIS``
        is not hidden."""
        p = self.cx.pou
        block = p.owner if p is not None and p.kind == "METHOD" else p
        if block is None or block.kind not in ("FUNCTION_BLOCK", "PROGRAM"):
            return False
        this = self.cx.exprs.lookup("THIS")
        return isinstance(this, VarSym) and this.storage == "this" and \
            name in self.cx.oop.methods(block)

    def _args_only(self, c: A.Call) -> None:
        for a in c.args:
            if a.value is not None:
                self.cx.exprs.expr(a.value, None)

    def _bind(self, c: A.Call, params: list[A.VarDecl], who: str) -> tuple[list, list, list]:
        """Bind call arguments to formal parameters: named, or positional in order."""
        inputs, outputs, inouts = [], [], []
        positional_params = [d for d in params if d.section in _INPUTISH]
        by_name = {d.name: d for d in params}
        pos = 0
        seen: set[str] = set()
        for a in self.plain_args(c, params):
            if a.name is None:
                if pos >= len(positional_params):
                    self.err("PLC0107", f"too many arguments for {who} (it takes "
                             f"{len(positional_params)} input(s))", a.loc)
                    self.cx.exprs.expr(a.value, None)
                    continue
                d = positional_params[pos]
                pos += 1
            else:
                d = by_name.get(a.name)
                if d is None or d.section not in _INPUTISH + ("VAR_OUTPUT",):
                    names = [p.name for p in params if p.section in _INPUTISH + ("VAR_OUTPUT",)]
                    self.err("PLC0107", f"{who} has no parameter {a.name}" +
                             close_hint(a.name, names) + (
                                 "" if close_hint(a.name, names) else
                                 f" (parameters: {', '.join(names) or 'none'})"), a.loc)
                    if a.value is not None:
                        self.cx.exprs.expr(a.value, None)
                    continue
            if d.name in seen:
                self.err("PLC0107", f"parameter {d.name} is given twice", a.loc)
            seen.add(d.name)
            if a.output:
                if d.section != "VAR_OUTPUT":
                    self.err("PLC0107", f"{d.name} is an input of {who}; pass it with ':=' not "
                             "'=>'", a.loc)
                    continue
                if a.value is not None:
                    tt = self.cx.exprs.lvalue(a.value)
                    self.cx.exprs.check_assignable(d.ty, tt, a.value, a.loc)
                    outputs.append((d, a.value, a.negated))
                continue
            if d.section == "VAR_OUTPUT":
                self.err("PLC0107", f"{d.name} is an output of {who}; connect it with '=>' "
                         f"(e.g. {d.name} => myVar)", a.loc)
                self.cx.exprs.expr(a.value, None)
                continue
            if d.section == "VAR_IN_OUT":
                # VAR_IN_OUT CONSTANT takes any value of the type, a literal too (IEC 61131-3
                # ed.3 Table 13); the block cannot change it, so nothing is written back
                if d.constant:
                    vt = self.cx.exprs.expr(a.value, d.ty)
                    if not self._var_array_arg(d, vt, a):
                        self.cx.exprs.check_assignable(vt, d.ty, a.value, a.loc)
                    inouts.append((d, a.value))
                    continue
                tt = self.cx.exprs.lvalue(a.value)
                if self.cx.exprs.property_in(a.value) is not None:
                    self.err("PLC0107", f"VAR_IN_OUT {d.name} needs a variable, and "
                             f"{expr_text(a.value)} is a PROPERTY (a GET and a SET, not a "
                             "variable); copy it to a variable, pass that, and assign it back",
                             a.loc)
                elif self._var_array_arg(d, tt, a):
                    pass
                elif not T.same_type(tt, d.ty) and tt is not T.ANY and d.ty is not T.ANY and not (
                    isinstance(T.resolve(tt), T.StringType) and
                    isinstance(T.resolve(d.ty), T.StringType)
                ):
                    self.err("PLC0107", f"VAR_IN_OUT {d.name} needs a variable of type {d.ty} "
                             f"exactly, not {tt}", a.loc)
                inouts.append((d, a.value))
                continue
            dt = T.resolve(d.ty) if d.ty is not None else None
            if isinstance(dt, T.RefType) and dt.reference and a.value is not None:
                a.value = reference_to.ref_call(a.loc, a.value)  # a REFERENCE TO input binds
            vt = self.cx.exprs.expr(a.value, d.ty)
            self.cx.exprs.check_assignable(vt, d.ty, a.value, a.loc)
            inputs.append((d, a.value))
        for d in params:
            if d.section == "VAR_IN_OUT" and d.name not in seen:
                self.err("PLC0107", f"VAR_IN_OUT {d.name} of {who} must be connected on every "
                         "call", c.loc)
        return inputs, outputs, inouts

    def plain_args(self, c: A.Call, params: list[A.VarDecl] | None = None) -> list[A.Arg]:
        """The arguments without EN and ENO, unless the callee declares them itself."""
        own = {d.name for d in params or ()}
        return [a for a in c.args if not (a.name in ("EN", "ENO") and a.name not in own)]

    def en_eno(self, c: A.Call, info: CallInfo, params: list[A.VarDecl] | None = None) -> None:
        """Check the implicit EN input and ENO output of a call and record them on ``info``
        (IEC 61131-3 ed.3 6.6.1.6: with EN FALSE the body is not executed and ENO is FALSE)."""
        own = {d.name for d in params or ()}
        for a in c.args:
            if a.name not in ("EN", "ENO") or a.name in own:
                continue
            if a.name == "EN":
                if a.output or a.value is None:
                    self.err("PLC0177", "EN is an input: connect it with ':=' (EN := cond)",
                             a.loc)
                    continue
                t = self.cx.exprs.expr(a.value, T.BOOL)
                self.cx.exprs.check_assignable(t, T.BOOL, a.value, a.loc)
                info.en = a.value
            else:
                if not a.output:
                    self.err("PLC0177", "ENO is an output: connect it with '=>' (ENO => ok)",
                             a.loc)
                    if a.value is not None:
                        self.cx.exprs.expr(a.value, None)
                    continue
                if a.value is None:
                    continue
                t = self.cx.exprs.lvalue(a.value)
                self.cx.exprs.check_assignable(T.BOOL, t, a.value, a.loc)
                info.eno = a.value

    def params(self, pou: A.Pou) -> list[A.VarDecl]:
        """The declarations of a called POU, its parameters among them."""
        return list(self.table.members(pou).values())

    def _called(self, pou: A.Pou, loc: Location) -> None:
        """Remember that the POU being checked calls ``pou`` here (for recursion)."""
        if self.cx.pou is not None:
            self.cx.call_graph.setdefault(self.cx.pou.name, set()).add(pou.name)
            self.cx.call_sites.setdefault((self.cx.pou.name, pou.name), loc)

    def call_function(self, c: A.Call, pou: A.Pou) -> T.Type:
        self._called(pou, c.loc)
        params = self.params(pou)
        ins, outs, inouts = self._bind(c, params, f"function {pou.spelling or pou.name}")
        c.target = CallInfo("function", pou, ins, outs, inouts)
        self.en_eno(c, c.target, params)
        rd = pou.return_decl
        return rd.ty if rd is not None else T.VOID

    def call_fb(self, c: A.Call, pou: A.Pou, statement: bool, program: bool = False) -> T.Type:
        if not statement:
            self.err("PLC0106", f"a function block call is a statement: call {pou.name} on its "
                     "own line, then read its outputs (inst.Q)", c.loc)
        self._called(pou, c.loc)
        params = self.params(pou)
        ins, outs, inouts = self._bind(c, params, f"{pou.name}")
        c.target = CallInfo("program" if program else "fb", pou, ins, outs, inouts)
        self.en_eno(c, c.target, params)
        return T.VOID

    def call_builtin(self, c: A.Call, name: str, statement: bool) -> T.Type:
        expected, self.expected = self.expected, None  # this call's context, not its arguments'
        conv = conversion(name)
        args = self.plain_args(c)
        if conv is not None and name not in BUILTINS:
            if len(args) != 1 or args[0].output:
                self.err("PLC0107", f"{name} takes exactly one argument", c.loc)
                self._args_only(c)
                return conv[1]
            a = args[0]
            src, dst = conv
            # INT_TO_WORD(TRUNC(r)): TRUNC's context is INT (a call's only: a literal stays one)
            at = self.cx.exprs.expr(a.value, T.lookup_elementary(src) if isinstance(
                a.value, A.Call) and src not in (None, "__TRUNC__") else None)
            ra = T.base_of(at)
            if src not in (None, "__TRUNC__") and ra is not T.ANY:
                want = T.lookup_elementary(src)
                ok = T.can_widen(ra, want) or T.same_type(ra, want) or (
                    isinstance(ra, T.EnumType) and want.kind == "int")
                if not ok and ra.kind in ("int", "bits") and want.kind in ("int", "bits") \
                        and self.cx.dialect(a.loc).implicit_int_conversion:
                    sn = T.concrete(ra).name
                    self.warn("PLC0285", f"{sn} passed to {name}, which takes {src} (accepted "
                              f"as in CODESYS): it wraps to {src} first as {sn}_TO_{src} "
                              f"wraps; write {sn}_TO_{dst.name}(...) to convert directly", a.loc)
                    ok = True
                if not ok:
                    self.err("PLC0107", f"{name} expects {src}, but the argument is "
                             f"{T.concrete(ra)}" + (f"; use {T.concrete(ra).name}_TO_"
                                                    f"{dst.name}" if hasattr(dst, 'name') else ""),
                             a.loc)
            c.target = CallInfo("conv", (src, dst), [(0, a.value)])
            self.en_eno(c, c.target)
            return dst
        if name in ("MUL", "DIV") and len(args) == 2 and not any(a.output for a in args) and \
                isinstance(args[0].value, A.Name | A.Member | A.Index | A.Literal) and \
                T.base_of(self.cx.exprs.expr(args[0].value, None)) is T.TIME:
            name += "_TIME"  # MUL(t, 2), DIV(t, n): the overloaded TIME rows of ed.2 Table 30
        b: Builtin = BUILTINS[name]
        if name in ED2_NAMES and not self.cx.dialect(c.loc).ed2_time_names:
            self.err("PLC0320", f"{name} is the IEC 61131-3 ed.2 name (MATIEC, OSCAT) of "
                     f"{ED2_NAMES[name]}; write {ED2_NAMES[name]}(...), or choose "
                     "{dialect 'matiec'} for an ed.2 program", c.func.loc)
        if b.test_only and not self.cx.in_test:
            self.err("PLC0106", f"{name} is only available inside TEST ... END_TEST blocks",
                     c.loc)
        if b.statement_only and not statement:
            self.err("PLC0106", f"{name} is a statement, not a value", c.loc)
        vals: list[A.Expr] = []
        names = list(b.params)
        for a in args:
            if a.output:
                self.err("PLC0107", f"{name} has no outputs to connect with '=>'", a.loc)
                continue
            if a.name is not None:
                if a.name in names:
                    idx = names.index(a.name)
                elif b.variadic and a.name.startswith(names[-1][:-1]) and a.name[len(
                        names[-1]) - 1:].isdigit():
                    idx = int(a.name[len(names[-1]) - 1:]) - (1 if names[0].endswith("1") else 0)
                    idx = max(idx, 0)
                else:
                    self.err("PLC0107", f"{name} has no parameter {a.name} (parameters: "
                             f"{', '.join(names)})", a.loc)
                    continue
                while len(vals) <= idx:
                    vals.append(None)  # type: ignore[arg-type]
                vals[idx] = a.value
            else:
                vals.append(a.value)
        if any(v is None for v in vals) or len(vals) < b.min_args or (
            not b.variadic and len(vals) > len(b.params)
        ):
            self.err("PLC0107", f"{name} takes {'at least ' if b.variadic else ''}"
                     f"{b.min_args if b.variadic else len(b.params)} argument(s): "
                     f"{name}({', '.join(b.params)}{', ...' if b.variadic else ''})", c.loc)
            for v in vals:
                if v is not None:
                    self.cx.exprs.expr(v, None)
            return T.ANY
        c.target = CallInfo("builtin", b, list(enumerate(vals)))
        if not b.test_only:
            self.en_eno(c, c.target)
        return self.builtin_type(name, vals, c, expected)

    def builtin_type(self, name: str, vals: list[A.Expr], c: A.Call,
                     expected: T.Type | None = None) -> T.Type:
        """Type the arguments, then apply the function's typing rule (its ``Builtin.typing``,
        :mod:`.typing_rules`)."""
        spec = BUILTINS[name]
        ts = [self.cx.exprs.expr(v, None) for v in vals]
        bs = [T.base_of(t) for t in ts]
        if any(t is T.ANY for t in bs):
            return T.BOOL if spec.typing == "compare" else T.ANY
        return TYPING_RULES[spec.typing](Typing(self, spec, ts, bs, c, vals, expected))
