"""Pass: the object-oriented extensions (ADR 0021) -- EXTENDS and IMPLEMENTS, METHOD
declarations and bodies, method calls (``inst.M(...)``, ``THIS^.M()``, ``SUPER^.M()``, a call
through an interface) and assignments to interface variables.

Codes PLC0220-PLC0249. Inherited variables reach the other passes through the symbol table's
``bases()`` hook (:meth:`~.symbols.SymbolTable.bases`); this pass adds what only objects have.
"""

from __future__ import annotations

from typing import Any

from .. import ast as A
from .. import types as T
from ..ast import expr_text
from ..limits import MAX_EXTENDS_DEPTH
from ..walk import walk
from .calls import CallInfo
from .pass_api import Pass
from .symbols import VarSym, close_hint

_PARAMS = ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT")
# the methods the runtime calls itself (CODESYS), with their BOOL inputs
_BUILT_IN_METHODS = {"FB_INIT": ("BINITRETAINS", "BINCOPYCODE"), "FB_EXIT": ("BINCOPYCODE",),
                     "FB_REINIT": ()}


def _label(p: A.Pou) -> str:
    return p.spelling or p.name


def signature(m: A.Pou) -> list[tuple[str, str, str]]:
    """(section, name, type) of a method's parameters and its result, for override checks."""
    rt = m.return_decl.ty if m.return_decl is not None else None
    out = [(d.section, d.name, str(T.resolve(d.ty))) for d in m.decls if d.section in _PARAMS]
    return out + [("RETURN", "", str(T.resolve(rt)) if rt is not None else "VOID")]


class ObjectChecks(Pass):
    """Declarations (after :mod:`.declarations`), method bodies (after the POU bodies), and
    the two hooks the other passes call: :meth:`method_call` and :meth:`interface_assign`."""

    # -- questions ----------------------------------------------------------------------------
    def interfaces_of(self, p: A.Pou) -> list[A.Pou]:
        return self.table.interfaces(p)

    def methods(self, p: A.Pou) -> dict[str, A.Pou]:
        """The methods callable on ``p`` by name: its own, then inherited (a block's bases, an
        interface's bases); the nearest definition wins. Built once per block (a call looks
        its method up here: 4,000 ACTIONs must not rebuild the table 4,000 times); the dict
        is shared, never change it."""
        chain = [p, *self.table.bases(p)] if p.kind == "FUNCTION_BLOCK" else (
            [p] if p.kind == "PROGRAM" else self.interfaces_of(p))  # a PROGRAM's actions
        key = tuple((id(q), len(q.methods)) for q in chain)
        cache = self.__dict__.setdefault("_methods_cache", {})
        out = cache.get(key)
        if out is None:
            out = {}
            for q in chain:
                for m in q.methods:
                    out.setdefault(m.name, m)
            cache[key] = out
        return out

    def _block_of(self, p: A.Pou | None) -> A.Pou | None:
        return p.owner if p is not None and p.kind == "METHOD" else p

    # -- declarations -------------------------------------------------------------------------
    def declarations(self) -> None:
        for p in list(self.table.pous.values()):
            if p.kind in ("FUNCTION_BLOCK", "INTERFACE"):
                self.check_header(p)
            if p.kind in ("FUNCTION_BLOCK", "INTERFACE", "PROGRAM"):
                for m in p.methods:
                    self.method_decls(m)
        for p in list(self.table.pous.values()):
            if p.kind == "FUNCTION_BLOCK":
                self.check_overrides(p)
                self.check_implements(p)
        for p in self.table.pous.values():
            for d in p.decls:
                self.check_not_abstract(d)
        for d in self.table.globals.values():
            self.check_not_abstract(d)

    def check_header(self, p: A.Pou) -> None:
        want = "FUNCTION_BLOCK" if p.kind == "FUNCTION_BLOCK" else "INTERFACE"
        if p.kind == "FUNCTION_BLOCK" and len(p.extends) > 1:
            self.err("PLC0220", f"{_label(p)} EXTENDS {len(p.extends)} blocks; a FUNCTION_BLOCK "
                     "has one base (implement several INTERFACEs instead)", p.loc)
        for n in p.extends:
            b = self.table.pous.get(n)
            if b is None or b.kind != want:
                cands = [k for k, v in self.table.pous.items() if v.kind == want]
                self.err("PLC0220", f"{_label(p)} EXTENDS {n}, which is not a {want}" +
                         close_hint(n, cands), p.loc)
            elif p.is_class and not b.is_class:  # ed.3 6.6.5.2: class_decl EXTENDS a class
                self.err("PLC0341", f"CLASS {_label(p)} EXTENDS {_label(b)}, a FUNCTION_BLOCK: "
                         "a CLASS extends only a CLASS (IEC 61131-3 ed.3); make "
                         f"{_label(p)} a FUNCTION_BLOCK, or {_label(b)} a CLASS", p.loc)
            elif "FINAL" in b.modifiers:
                self.err("PLC0224", f"{_label(b)} is FINAL: no block may extend it; remove FINAL "
                         f"from {_label(b)} or do not extend it", p.loc)
        if p.kind == "FUNCTION_BLOCK" and p.extends and p.extends[0] in self.table.pous:
            chain = self.table.bases(p)
            last = chain[-1] if chain else p
            after = self.table.pous.get(last.extends[0]) if last.extends else None
            if after is not None and any(after is q for q in (p, *chain)):
                self.err("PLC0232", f"{_label(p)} inherits from itself (EXTENDS goes round in a "
                         "circle); remove one EXTENDS", p.loc)
            elif len(chain) > MAX_EXTENDS_DEPTH and (
                    len(self.table.bases(chain[0])) <= MAX_EXTENDS_DEPTH  # where it crosses
                    or not self.__dict__.get("_deep_reported")):  # (a long ring: once)
                self.__dict__["_deep_reported"] = True
                self.err("PLC0310", f"{_label(p)} has more than {MAX_EXTENDS_DEPTH} levels of "
                         f"EXTENDS above it (through {_label(chain[-1])}); "
                         f"plclab allows {MAX_EXTENDS_DEPTH}: merge some of the blocks, or use "
                         "an instance of a block instead of inheriting from it", p.loc)
        for n in p.implements:
            i = self.table.pous.get(n)
            if i is None or i.kind != "INTERFACE":
                cands = [k for k, v in self.table.pous.items() if v.kind == "INTERFACE"]
                self.err("PLC0220", f"{_label(p)} IMPLEMENTS {n}, which is not an INTERFACE" +
                         close_hint(n, cands), p.loc)
        inherited = {n for b in self.table.bases(p) for n in (d.name for d in b.decls)}
        for d in p.decls:
            if d.name in inherited:
                self.err("PLC0235", f"{d.spelling or d.name} is declared again in {_label(p)}, "
                         "which inherits it already; remove this declaration or rename it",
                         d.loc)
        self.check_duplicates(p)

    def check_duplicates(self, p: A.Pou) -> None:
        """Two methods or actions of one name, or one named like a variable (PLC0235)."""
        seen: set[str] = set()
        for m in p.methods:
            if m.name in seen:
                what = "ACTION" if m.action else "METHOD"
                self.err("PLC0235", f"{_label(p)} declares {what} {_label(m)} twice; rename or "
                         "remove one", m.loc)
            seen.add(m.name)
            if m.name.removesuffix("__GET").removesuffix("__SET") in self.table.members(p):
                self.err("PLC0235", f"{_label(m)} has the name of a variable of {_label(p)} "
                         "(names do not depend on case); rename one of them", m.loc)

    def method_decls(self, m: A.Pou) -> None:
        """Type a method's declarations and its result (the declarations pass sees POUs only)."""
        self.cx.decls.check_pou_decls(m)
        self.table.scope(m)  # creates the result variable
        rd = m.return_decl
        if rd is not None and rd.ty is None:
            rd.ty = self.cx.decls.type_ref(rd.type)
        want = _BUILT_IN_METHODS.get(m.name)
        if want is not None and m.owner is not None and m.owner.kind == "FUNCTION_BLOCK":
            got = [(d.section, d.name, str(T.resolve(d.ty))) for d in m.decls
                   if d.section in _PARAMS]
            if m.name == "FB_INIT":  # more inputs: given where an instance is declared, a :
                got = got[:2] + [g for g in got[2:] if g[0] != "VAR_INPUT"]  # FB(k := 3)
            if got != [("VAR_INPUT", n, "BOOL") for n in want]:
                ins = ", ".join(f"{n} : BOOL" for n in want) or "none"
                self.err("PLC0237", f"{m.name} is called by the runtime with fixed inputs "
                         f"({ins}); declare exactly those" + (
                             " first, then any inputs an instance's declaration gives"
                             if m.name == "FB_INIT" else "") + ", no outputs or in-outs", m.loc)

    def check_overrides(self, p: A.Pou) -> None:
        bases = self.table.bases(p)
        inherited: dict[str, A.Pou] = {}
        for b in bases:
            for m in b.methods:
                inherited.setdefault(m.name, m)
        for m in p.methods:
            base = inherited.get(m.name)
            if base is None:
                if "OVERRIDE" in m.modifiers and not any(  # IEC 61131-3 ed.3: it overrides
                        im.name == m.name for i in self.interfaces_of(p) for im in i.methods):
                    where = (f"the blocks {_label(p)} extends" if bases else
                             f"{_label(p)}, which extends no block")
                    self.err("PLC0245", f"METHOD {_label(m)} is declared OVERRIDE, but no "
                             f"method of that name exists in {where}; remove OVERRIDE or "
                             "check the name", m.loc)
                continue
            if "FINAL" in base.modifiers:
                self.err("PLC0224", f"METHOD {_label(m)} overrides a FINAL method of "
                         f"{_label(base.owner)}; rename it or remove FINAL there", m.loc)
            elif signature(m) != signature(base):
                self.err("PLC0228", f"METHOD {_label(m)} overrides the one of "
                         f"{_label(base.owner)} with other parameters or another result; "
                         "declare the same inputs, outputs and result type", m.loc)

    def check_implements(self, p: A.Pou) -> None:
        have = self.methods(p)
        abstract = "ABSTRACT" in p.modifiers
        for m in have.values():
            if "ABSTRACT" in m.modifiers and not abstract:
                self.err("PLC0221", f"{_label(p)} is not ABSTRACT but its METHOD {_label(m)} "
                         f"(from {_label(m.owner)}) is: implement it in {_label(p)} or declare "
                         f"FUNCTION_BLOCK ABSTRACT {_label(p)}", p.loc)
        for i in self.interfaces_of(p):
            for im in i.methods:
                m = have.get(im.name)
                if m is None:
                    if not abstract:
                        self.err("PLC0221", f"{_label(p)} implements {_label(i)} but has no "
                                 f"METHOD {_label(im)}; add it (with the same parameters)",
                                 p.loc)
                elif signature(m) != signature(im):
                    self.err("PLC0228", f"METHOD {_label(m)} of {_label(p)} does not match "
                             f"{_label(i)}.{_label(im)}: declare the same inputs, outputs and "
                             "result type", m.loc)

    def check_not_abstract(self, d: A.VarDecl) -> None:
        t = T.resolve(d.ty) if d.ty is not None else None
        while isinstance(t, T.ArrayType):
            t = T.resolve(t.elem)
        if isinstance(t, T.FBType) and "ABSTRACT" in t.pou.modifiers:
            self.err("PLC0225", f"{_label(t.pou)} is ABSTRACT: declare an instance of a block "
                     f"that EXTENDS it, or an interface variable", d.loc)

    # -- bodies -------------------------------------------------------------------------------
    def bodies(self) -> None:
        for p in list(self.table.pous.values()):
            if p.kind == "PROGRAM":  # its actions (ADR 0035)
                self.check_duplicates(p)
                for m in p.methods:
                    self.cx.stmts.check_pou_body(m)
            if p.kind != "FUNCTION_BLOCK":
                continue
            for q in [p, *p.methods]:
                self.check_super(p, q)
            for m in p.methods:
                self.cx.stmts.check_pou_body(m)

    def check_super(self, fb: A.Pou, q: A.Pou) -> None:
        if self.table.bases(fb):
            return
        for s in q.body:
            for x in walk(s):
                if isinstance(x, A.Name) and x.name == "SUPER" and x.text.endswith("^"):
                    self.err("PLC0227", f"SUPER^ needs a base block, and {_label(fb)} EXTENDS "
                             "none; add EXTENDS Base or call THIS^ instead", x.loc)
                    return

    # -- hooks for the other passes -----------------------------------------------------------
    def method_call(self, c: A.Call, statement: bool) -> T.Type | None:
        """The type of ``obj.M(...)`` when ``M`` is a method of ``obj``'s block or interface;
        None when the call is something else (the caller goes on)."""
        f = c.func
        assert isinstance(f, A.Member)
        obj = f.obj
        if isinstance(obj, A.Name) and self.cx.exprs.lookup(obj.name) is None:
            p = self.table.pous.get(obj.name)
            if p is not None and p.kind in ("FUNCTION_BLOCK", "INTERFACE") and \
                    f.field_name in self.methods(p):
                self.err("PLC0229", f"{obj.text or obj.name} is a type, not an instance: call "
                         f"the method on a variable of that type (e.g. myVar.{f.text or f.field_name}"
                         "())", c.loc)
                self.cx.calls._args_only(c)
                return T.ANY
        n = len(self.cx.diags)
        ot = T.resolve(self.cx.exprs.expr(obj, None))
        pou = ot.pou if isinstance(ot, T.FBType | T.InterfaceType) else None
        if ot is T.ANY and len(self.cx.diags) > n:  # obj itself is wrong (unknown name...):
            self.cx.calls._args_only(c)  # keep its error; typed again it would say nothing
            return T.ANY
        if pou is None or pou.kind not in ("FUNCTION_BLOCK", "INTERFACE", "PROGRAM"):
            del self.cx.diags[n:]  # the caller types the expression again and reports
            return None
        m = self.methods(pou).get(f.field_name)
        if m is None and pou.kind == "PROGRAM":
            del self.cx.diags[n:]
            return None
        if m is None:
            if f.field_name in self.table.members(pou):
                del self.cx.diags[n:]
                return None
            self.err("PLC0222", f"{_label(pou)} has no METHOD {f.text or f.field_name}" +
                     close_hint(f.field_name, [*self.methods(pou), *self.table.members(pou)]),
                     f.loc)
            self.cx.calls._args_only(c)
            return T.ANY
        self.check_access(m, f)
        if m.action:
            return self.action_call(c, m, statement)
        params = [d for d in m.decls if d.section != "VAR_INST"]
        ins, outs, inouts = self.cx.calls._bind(c, params, f"method {_label(m)}")
        c.target = CallInfo("method", m, ins, outs, inouts)
        f.sym = m
        f.ty = T.VOID
        rd = m.return_decl
        return rd.ty if rd is not None and rd.ty is not None else T.VOID

    def action_call(self, c: A.Call, m: A.Pou, statement: bool) -> T.Type:
        """``inst.A(...)`` / ``Prog.A(...)``: an action runs on its POU's data; the arguments
        set the POU's inputs and read its outputs as a call of the POU does (CODESYS "Object:
        Action", calling an action)."""
        f = c.func
        assert isinstance(f, A.Member) and m.owner is not None
        if not statement:
            self.err("PLC0198", f"ACTION {_label(m)} has no value: call it as a statement "
                     f"({expr_text(f)}();) and read the outputs of {_label(m.owner)}", c.loc)
        params = self.cx.calls.params(m.owner)
        ins, outs, inouts = self.cx.calls._bind(c, params, f"action {_label(m)}")
        c.target = CallInfo("action", m, ins, outs, inouts)
        f.sym = m
        f.ty = T.VOID
        return T.VOID

    def check_access(self, m: A.Pou, f: A.Member) -> None:
        mods = set(m.modifiers)
        if not mods & {"PRIVATE", "PROTECTED"} or self.cx.in_test:
            return
        caller = self._block_of(self.cx.pou)
        owner = m.owner
        ok = caller is owner if "PRIVATE" in mods else (
            caller is not None and owner is not None and
            (caller is owner or owner in self.table.bases(caller)))
        if not ok:
            which = "PRIVATE" if "PRIVATE" in mods else "PROTECTED"
            where = "its own block" if which == "PRIVATE" else "its block and blocks that extend it"
            self.err("PLC0223", f"METHOD {_label(m)} of {_label(owner)} is {which}: only {where} "
                     "may call it; call a PUBLIC method instead", f.loc)

    def property_access(self, e: A.Member, pou: A.Pou, write: bool) -> T.Type | None:
        """The type of ``obj.P`` when ``P`` is a PROPERTY of ``pou`` (``e.sym`` := the accessor
        the access calls); None when ``P`` is something else."""
        if e.field_name in self.table.members(pou):
            return None
        have = self.methods(pou)
        get, put = have.get(e.field_name + "__GET"), have.get(e.field_name + "__SET")
        if get is None and put is None:
            return None
        acc = put if write else get
        if acc is None:
            self.err("PLC0233", f"PROPERTY {e.text or e.field_name} of {_label(pou)} has no "
                     f"{'SET' if write else 'GET'}: it can only be "
                     f"{'read' if write else 'written'}; add {'SET' if write else 'GET'} ... "
                     f"END_{'SET' if write else 'GET'} to the property", e.loc)
            return T.ANY
        self.check_access(acc, e)
        e.sym = acc
        if write:
            return acc.decls[0].ty
        rd = acc.return_decl
        return rd.ty if rd is not None and rd.ty is not None else T.ANY

    def method_without_call(self, e: A.Member, pou: A.Pou) -> bool:
        """``inst.M`` where ``M`` is a METHOD: reported (PLC0242) with the call to write; the
        article writes ``IF NOT Pump2.HasError THEN`` (003_9d92dccf8dc4ed13.txt line 219)."""
        m = self.methods(pou).get(e.field_name)
        if m is None:
            return False
        self.err("PLC0242", f"{e.text or e.field_name} is a METHOD of {_label(pou)}: call it "
                 f"with parentheses, {expr_text(e)}()", e.loc)
        return True

    def reference_operator(self, c: A.Call, name: str) -> T.Type:
        """``REF(x)`` / ``ADR(x)`` (a reference to the variable x), ``__ISVALIDREF(r)`` (TRUE
        when the interface or reference r refers to something) and ``__QUERYINTERFACE(itf,
        other)`` (``other`` := the same instance when its block also implements ``other``'s
        interface; TRUE when it did), as IEC ed.3 and CODESYS have them."""
        args = [a for a in c.args if a.value is not None]
        want = {"__ISVALIDREF": 1, "__QUERYINTERFACE": 2, "REF": 1, "ADR": 1}.get(name)
        if want is None or len(args) != want or any(a.name or a.output for a in args):
            self.err("PLC0236", f"{name} is not a function here; write REF(x), ADR(x), "
                     "__ISVALIDREF(r) or __QUERYINTERFACE(itf, itfOther) with positional "
                     "arguments", c.loc)
            self.cx.calls._args_only(c)
            return T.ANY
        if name in ("REF", "ADR"):
            return self.ref_of(c, name, args[0].value)
        types = []
        for i, a in enumerate(args):
            t = T.resolve(self.cx.exprs.lvalue(a.value) if i == 1 else
                          self.cx.exprs.expr(a.value, None))
            types.append(t)
            ok = isinstance(t, T.InterfaceType) or (name == "__ISVALIDREF" and
                                                    isinstance(t, T.RefType))
            if not ok and t is not T.ANY:
                if getattr(c.func, "text", "") == "?=":  # dst ?= src (ed.3, ADR 0059)
                    self.err("PLC0236", f"?= (an assignment attempt) works on interface "
                             f"variables, not {t}; declare both sides with an INTERFACE type "
                             "(or assign with :=)", a.loc)
                    continue
                self.err("PLC0236", f"{name} takes interface variables"
                         f"{' or references' if name == '__ISVALIDREF' else ''}, not {t}; "
                         "declare the variable with an INTERFACE type", a.loc)
        c.target = CallInfo("reference", name, [(i, a.value) for i, a in enumerate(args)])
        return T.BOOL

    # -- references: REF_TO, POINTER TO, REF(), ADR(), ^, NULL --------------------------------
    def ref_type(self, r: A.RefTypeRef) -> T.Type:
        if r.kind == "REFERENCE" and not self.cx.dialect(r.loc).reference_to:
            self.err("PLC0239", "REFERENCE TO is a CODESYS type (choose {dialect 'codesys'}); "
                     "in IEC 61131-3 declare REF_TO T, assign r := REF(x); and write r^ where "
                     "the variable is meant", r.loc)
            return T.ANY
        return T.RefType(self.cx.decls.type_ref(r.target), pointer=r.kind == "POINTER",
                         reference=r.kind == "REFERENCE")

    def ref_of(self, c: A.Call, name: str, x: A.Expr) -> T.Type:
        t = self.cx.exprs.expr(x, None)
        x.is_target = True  # a variable, never a temporary
        if self.cx.exprs.property_in(x) is not None:
            self.err("PLC0240", f"{name}({expr_text(x)}): a PROPERTY is a GET and a SET, not a "
                     f"variable, so nothing can point at it; point at the variable it reads",
                     x.loc)
            return T.ANY
        root = x
        while isinstance(root, A.Member | A.Index):
            if isinstance(root, A.Member) and root.field_name.startswith("%"):
                self.err("PLC0240", f"{name} cannot point at a single bit or a part of a "
                         "variable (.%B1); point at the whole variable", x.loc)
                return T.ANY
            root = root.obj
        if isinstance(root, A.Name) and isinstance(root.sym, VarSym) and root is x and (
                root.sym.storage == "local" or root.sym.decl.section in ("VAR_TEMP", "RETURN")) \
                and root.sym.decl.section != "RETURN" and root.sym.storage == "local" and \
                self.cx.dialect(x.loc).local_refs:
            # allowed if the reference cannot outlive the call: check_local_refs decides
            self.__dict__.setdefault("local_refs", []).append((c, x, name))
        elif isinstance(root, A.Name) and isinstance(root.sym, VarSym) and root is x and (
                root.sym.storage == "local" or root.sym.decl.section in ("VAR_TEMP", "RETURN")):
            self.err("PLC0240", f"{name}({expr_text(x)}): the variable lives only during one "
                     "call (a local of a FUNCTION, METHOD or TEST, or a VAR_TEMP); point at a "
                     "variable of a block, a program or a global", x.loc)
            return T.ANY
        if not isinstance(root, A.Name):
            self.err("PLC0240", f"{name} needs a variable, e.g. {name}(x) or {name}(arr[i])",
                     x.loc)
            return T.ANY
        c.target = CallInfo("reference", name, [(0, x)])
        return T.RefType(t, pointer=name == "ADR")

    def check_local_refs(self, body: list[A.Stmt]) -> None:
        """REF(x) of a local of a FUNCTION, METHOD or TEST (OSCAT ``REAL_TO_DW``: ``pt :=
        REF(X); REAL_TO_DW := pt^;``) is allowed when the reference cannot outlive the call: it
        goes straight into a local reference variable of the same call, and that variable is
        only dereferenced (``pt^``), compared or assigned, never stored or passed anywhere
        (an output, a global, a VAR_IN_OUT, a member of a block, the result). Else PLC0240."""
        pending = self.__dict__.pop("local_refs", [])
        if not pending:
            return
        from ..walk import CHILDREN

        calls = {id(c) for c, _, _ in pending}
        parent: dict[int, Any] = {}
        holders: set[str] = set()
        stored: set[int] = set()
        for n in (n for st in body for n in walk(st)):
            for ch in CHILDREN[type(n)](n):
                parent[id(ch)] = n
            if isinstance(n, A.Assign) and id(n.value) in calls and isinstance(
                    n.target, A.Name) and isinstance(n.target.sym, VarSym) and \
                    n.target.sym.storage == "local" and n.target.sym.decl.section in (
                        "VAR", "VAR_TEMP"):
                stored.add(id(n.value))
                holders.add(n.target.sym.decl.name)
        for c, x, name in pending:
            if id(c) in stored:
                self.warn("PLC0292", f"{name}({expr_text(x)}) points at a local of this call "
                          "(accepted as in CODESYS: the reference is only used inside the "
                          "call); IEC 61131-3 ed.3 refuses REF of a temporary variable: copy "
                          "the value, or make the variable one of a block or a global", x.loc)
            else:
                self.err("PLC0240", f"{name}({expr_text(x)}): the variable lives only during "
                         "one call (a local of a FUNCTION, METHOD or TEST, or a VAR_TEMP); "
                         "store the reference in a local REF_TO variable of the same call and "
                         "only dereference it, or point at a variable of a block, a program "
                         "or a global", x.loc)
        for n in (n for st in body for n in walk(st)):
            if not (isinstance(n, A.Name) and isinstance(n.sym, VarSym) and
                    n.sym.storage == "local" and n.sym.decl.name in holders):
                continue
            up = parent.get(id(n))
            if isinstance(up, A.Assign) and up.target is n or \
                    isinstance(up, A.Member) and up.field_name == "^" or \
                    isinstance(up, A.Binary) and up.op in ("=", "<>"):
                continue
            if isinstance(up, A.Arg):
                call = parent.get(id(up))
                if isinstance(call, A.Call) and isinstance(call.func, A.Name) and \
                        call.func.name == "__ISVALIDREF":
                    continue
            self.err("PLC0240", f"{n.text or n.name} holds a reference to a local of this "
                     "call, which ends with the call; here it could be kept beyond it (stored "
                     "or passed on): copy the value (x := " + (n.text or n.name) + "^) instead",
                     n.loc)

    def deref(self, e: A.Member) -> T.Type:
        t = T.resolve(self.cx.exprs.expr(e.obj, None))
        if isinstance(t, T.RefType) and t.target is not T.ANY:
            return t.target
        if t is not T.ANY:
            self.err("PLC0238", f"'^' follows a reference (REF_TO or POINTER TO), and "
                     f"{expr_text(e.obj)} is {t}", e.loc)
        return T.ANY

    def ref_compare(self, e: A.Binary, a: T.Type, b: T.Type) -> T.Type:
        if e.op in ("=", "<>"):
            return T.BOOL
        self.err("PLC0238", f"'{e.op}' on a reference: plclab has no pointer arithmetic (a "
                 "variable has no numeric address here); compare references with = or <>, "
                 "index an ARRAY instead of moving a pointer", e.loc)
        return T.ANY

    def ref_assign(self, rs: T.Type, rd: T.Type, loc) -> None:
        if isinstance(rs, T.RefType) and isinstance(rd, T.RefType) and (
                rs.target is T.ANY or T.same_type(rs.target, rd.target) or
                T.resolve(rs.target) is T.resolve(rd.target)):
            return
        self.err("PLC0241", f"cannot assign {rs} to {rd}: a reference takes REF(x) of a "
                 "variable of its target type, another such reference, or NULL", loc)

    def interface_assign(self, rs: T.Type, rd: T.InterfaceType, loc) -> None:
        """Check storing a value of type ``rs`` in an interface variable of type ``rd``."""
        if isinstance(rs, T.FBType | T.InterfaceType) and rs.pou is not None and \
                rd.pou in self.interfaces_of(rs.pou):
            return
        what = f"{rs}" if not isinstance(rs, T.FBType) else f"an instance of {rs.name}"
        self.err("PLC0226", f"cannot assign {what} to the interface {rd.name}: only an instance "
                 f"of a block that IMPLEMENTS {rd.name} (or an interface that EXTENDS it) fits; "
                 f"add IMPLEMENTS {rd.name} to the block", loc)
