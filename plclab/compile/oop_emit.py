"""Code generation for the object-oriented extensions (ADR 0021).

A METHOD of block ``B`` is a Python method ``M_NAME(self, inputs..., in_outs...)`` of the
block's class ``P_B``; it returns like a FUNCTION (the result, then the outputs). A derived
block's class gets its base's variables (the symbol table's ``members``) and, after every
class is defined, each inherited method it does not override (``P_D.m_X = P_B.m_X``): a call
``obj.m_X(...)`` then dispatches on the instance's class, which is what a call through an
interface or ``THIS^`` needs. ``SUPER^.M()`` is the static call ``P_BASE.m_M(self, ...)``.
An interface variable holds the instance itself (a Python reference) or None; a call through
None is the runtime fault PLC9110 (:func:`plclab.runtime.rt_objects._iref`).

Only upper-cased ST identifiers reach the generated code; a method is ``m_`` + its upper-cased
name, in a namespace no variable can enter (a variable is always all upper case).
"""

from __future__ import annotations

import re
from typing import Any

from ..lang import ast as A
from ..lang import types as T
from ..lang.check import CallInfo, VarSym

Codegen = Any  # plclab.compile.codegen.Codegen, which imports this module
_IDENT = re.compile(r"^[A-Z_][A-Z0-9_]*$")


def ident(name: str) -> str:
    """The Python spelling of an ST name (as :func:`plclab.compile.codegen.ident`)."""
    up = name.upper()
    if not _IDENT.match(up):
        raise ValueError(f"not an identifier: {name!r}")
    return up


def method_name(m: A.Pou) -> str:
    return f"m_{ident(m.name)}"


def emit_methods(cg: Codegen, pou: A.Pou) -> None:
    """The methods of ``pou`` inside its class (the generator is at class level)."""
    outer = cg.pou
    for m in pou.methods:
        cg.pou = m
        params = [d for d in m.decls if d.section in ("VAR_INPUT", "VAR_IN_OUT")]
        cg.where_now = cg.where(m.loc)
        cg.emit(f"def {method_name(m)}(self" + "".join(f", v_{ident(d.name)}" for d in params)
                + "):")
        cg.ind += 1
        rd = m.return_decl
        if rd is not None and rd.ty is not T.VOID:
            cg.emit(f"v_{ident(m.name)} = {cg.default_code(rd.ty)}")
        for d in m.decls:
            if d.section in ("VAR", "VAR_TEMP", "VAR_OUTPUT"):
                cg.where_now = cg.where(d.loc)
                cg.emit_init(f"v_{ident(d.name)}", d)
        cg.function_body(m.body, [m.name] + [d.name for d in m.decls
                                            if d.section not in ("VAR_EXTERNAL", "VAR_INST")],
                         True)
        cg.emit(cg.function_return(m))
        cg.ind -= 1
    cg.pou = outer


def fb_init_inputs(cg: Codegen, pou: A.Pou) -> list[A.VarDecl]:
    """The inputs of the block's nearest FB_init after bInitRetains and bInCopyCode: what a
    declaration ``a : FB(k := 3)`` gives (CODESYS)."""
    for b in [pou, *cg.p.symbols.bases(pou)]:
        for m in b.methods:
            if m.name == "FB_INIT" and not m.action:
                return [x for x in m.decls if x.section == "VAR_INPUT"][2:]
    return []


def init_calls(cg: Codegen, pou: A.Pou) -> None:
    """In ``__init__``: the FB_init of the block's bases, then its own (CODESYS order), with
    bInitRetains TRUE except in a warm restart (``_INIT_RETAINS``) and bInCopyCode FALSE."""
    chain = [*reversed(cg.p.symbols.bases(pou)), pou]
    inits = [(b, m) for b in chain for m in b.methods if m.name == "FB_INIT" and not m.action]
    for b, m in inits:  # (not an ACTION called FB_init)
        extra = [x for x in m.decls if x.section == "VAR_INPUT"][2:]
        args = "".join(f", {cg.init_code(x.init, x.ty)}" for x in extra)
        if extra and m is inits[-1][1]:  # the nearest FB_init takes a : FB(k := 3)'s values
            args = f", *(_fbinit or ({args[2:]},))"
        cg.emit(f"P_{ident(b.name)}.m_FB_INIT(self, _INIT_RETAINS, False{args})")


def inherit_methods(cg: Codegen) -> None:
    """After every class: each block gets the methods of its bases it does not override,
    bases first (so a chain A <- B <- C copies A's method into B before C)."""
    table = cg.p.symbols
    blocks = [p for p in cg.p.pous.values() if p.kind == "FUNCTION_BLOCK" and not p.native]
    for p in sorted(blocks, key=lambda b: len(table.bases(b))):
        bases = table.bases(p)
        if not bases:
            continue
        own = {m.name for m in p.methods}
        base = bases[0]
        for name in sorted({m.name for b in bases for m in b.methods} - own):
            cg.emit(f"P_{ident(p.name)}.m_{ident(name)} = P_{ident(base.name)}.m_{ident(name)}")


def interfaces_line(cg: Codegen, pou: A.Pou) -> None:
    """The class attribute naming every interface the block implements (for
    ``__QUERYINTERFACE``); none for a block without interfaces."""
    names = sorted(ident(i.name) for i in cg.p.symbols.interfaces(pou))
    if names:
        cg.emit(f"_itf = {tuple(names)!r}")


def reference_operator(cg: Codegen, e: A.Call, info: CallInfo) -> str:
    """``REF(x)``, ``ADR(x)``, ``__ISVALIDREF(x)`` and ``__QUERYINTERFACE(x, y)``."""
    if info.callee in ("REF", "ADR"):
        code = ref_code(cg, info.inputs[0][1])
        if info.pun is not None:  # REF_TO DWORD := REF(real): the bits (PLC0291)
            return f"_RefPun({code}, {info.pun[0]!r}, {info.pun[1]!r})"
        return code
    if info.callee == "__ISVALIDREF":
        return f"({cg.ex(info.inputs[0][1])} is not None)"
    src, dst = info.inputs[0][1], info.inputs[1][1]
    want = ident(T.resolve(dst.ty).name)
    tmp = cg.new_tmp("_t")
    cg.pre.append(f"{tmp} = _qi({cg.ex(src)}, {want!r})")
    cg.pre.append(f"{cg.ex(dst)} = {tmp}")
    return f"({tmp} is not None)"


def property_call(cg: Codegen, e: A.Member, value: str | None) -> str:
    """``obj.P`` read (``value`` None: the GET accessor) or written (the SET accessor)."""
    m: A.Pou = e.sym
    obj = "self" if is_super(e.obj) else cg.ex(e.obj)
    if is_super(e.obj):
        base = T.resolve(e.obj.ty).pou
        return f"P_{ident(base.name)}.{method_name(m)}(self{'' if value is None else ', ' + value})"
    if isinstance(T.resolve(e.obj.ty), T.InterfaceType):
        obj = f"_iref({obj}, {m.name[:-5]!r}, {cg.where_now})"
    return f"{obj}.{method_name(m)}({'' if value is None else value})"


def ref_code(cg: Codegen, x: A.Expr) -> str:
    """A reference to the variable ``x``: the object that holds it and its key (an attribute
    name or a list index); the checker let only instance, program and global data through."""
    code = cg.ex(x)
    if code.isidentifier():  # a local of this call (PLC0240 keeps it inside the call)
        setter = cg.new_tmp("_rs")
        cg.pre.extend([f"def {setter}(_v):", f"    nonlocal {code}", f"    {code} = _v"])
        return f"_RefCell(lambda: {code}, {setter})"
    if code.endswith("]"):  # obj[flat index]: split at the bracket that matches the last one
        depth = 0
        for i in range(len(code) - 1, -1, -1):
            depth += {"]": 1, "[": -1}.get(code[i], 0)
            if depth == 0:
                return f"_RefItem({code[:i]}, {code[i + 1:-1]})"
    obj, _, attr = code.rpartition(".")
    return f"_RefAttr({obj}, {attr!r})"


def deref(cg: Codegen, e: A.Member) -> str:
    """The reference ``e.obj`` checked for NULL (PLC9111)."""
    return f"_deref({cg.ex(e.obj)}, {cg.where_now})"


def is_super(e: A.Expr) -> bool:
    return isinstance(e, A.Name) and isinstance(e.sym, VarSym) and e.sym.storage == "super"


def method_call(cg: Codegen, e: A.Call, info: CallInfo) -> str:
    """``obj.M(args)`` as a Python expression (the outputs are stored by ``cg.pre`` lines)."""
    m: A.Pou = info.callee
    f = e.func
    assert isinstance(f, A.Member)
    obj_t = T.resolve(f.obj.ty)
    args = cg.call_arguments(m.decls, info)
    if is_super(f.obj):
        base = obj_t.pou  # SUPER^'s type is the base block
        call = f"P_{ident(base.name)}.{method_name(m)}(self{''.join(', ' + a for a in args)})"
    else:
        obj = cg.ex(f.obj)
        if isinstance(obj_t, T.InterfaceType):
            obj = f"_iref({obj}, {repr(ident(m.name))}, {cg.where_now})"
        call = f"{obj}.{method_name(m)}({', '.join(args)})"
    return cg.call_with_results(call, m.decls, info)
