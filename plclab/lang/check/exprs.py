"""Pass: expressions -- names, literals, members, indices, operators, and whether a value may
be assigned where it goes (PLC0100, PLC0103-PLC0105, PLC0111, PLC0116-PLC0118, PLC0121)."""

from __future__ import annotations

from typing import Any

from ...errors import Location
from .. import ast as A
from .. import types as T
from ..walk import NodeVisitor, walk
from .declarations import split_address
from .exprs_operators import OperatorChecks
from .pass_api import Pass
from .symbols import EnumSym, ProgSym, VarSym, close_hint

_REAL_MAX = 3.4028234663852886e38  # the largest finite IEEE single
def _lreal_from_literals(e: A.Expr) -> bool:
    """``EXPT(BFT, 1.5) * 0.836``: the expression is LREAL only through untyped real literals
    (no LREAL variable, typed literal ``LREAL#``, conversion or user function returning LREAL),
    so CODESYS, which types a literal by its context, computes it as REAL."""
    seen = False
    for n in walk(e):
        if isinstance(n, A.Literal) and n.kind == "REAL" and n.prefix is None:
            seen = True
            continue
        if not isinstance(n, A.Expr) or n.ty is None or T.base_of(n.ty) is not T.LREAL:
            continue
        if isinstance(n, A.Literal):
            return False
        elif isinstance(n, A.Call):
            if n.target is None or n.target.kind != "builtin":
                return False
        elif not isinstance(n, A.Binary | A.Unary):
            return False
    return seen


class Expressions(OperatorChecks, Pass, NodeVisitor):
    """Types every expression (``Expr.ty``) and resolves names (``Name.sym``)."""

    def check_assignable(self, src: T.Type, dst: T.Type, e: A.Expr, loc: Location) -> None:
        if src is T.ANY or dst is T.ANY:
            return
        rs, rd = T.resolve(src), T.resolve(dst)
        if isinstance(rs, T.VarArrayType) or isinstance(rd, T.VarArrayType):
            self.err("PLC0352", f"cannot assign {rs} to {rd}: a variable-length array is copied "
                     "element by element, FOR i := LOWER_BOUND(a, 1) TO UPPER_BOUND(a, 1)", loc)
            return
        if isinstance(rd, T.InterfaceType):  # an instance or interface reference (ADR 0021)
            self.cx.oop.interface_assign(rs, rd, loc)
            return
        if isinstance(rd, T.RefType) or isinstance(rs, T.RefType):  # REF_TO (ADR 0021)
            if self.reinterpreted_ref(rs, rd, e, loc):
                return
            self.cx.oop.ref_assign(rs, rd, loc)
            return
        if rd is T.BOOL and isinstance(e, A.Literal) and e.kind == "INT" and e.prefix is None \
                and e.value in (0, 1):
            e.ty = T.BOOL  # 0 and 1 are BOOL literals (IEC 61131-3 ed.2 2.2.1, ed.3 Table 5)
            return
        if isinstance(rd, T.FBType):
            self.err("PLC0103", f"cannot assign to a function block instance of {rd.name}; "
                     "call it or assign its members", loc)
            return
        if isinstance(e, A.Literal) and e.kind == "INT" and src in (T.ANY_INT_LIT,) or (
            isinstance(e, A.Literal) and e.kind == "INT" and e.prefix is None
        ):
            if rd.kind in ("int", "bits"):
                if not T.fits(e.value, rd):
                    self.err("PLC0111", f"{e.value} does not fit in {rd.name} "
                             f"({_range_text(rd)}); use a larger type", e.loc)
                return
        if isinstance(rs, T.EnumType) or isinstance(rd, T.EnumType):
            if rs is rd:
                return
            self.err("PLC0103", f"cannot assign {rs} to {rd}: enumerations only take their own "
                     "values", loc)
            return
        if T.base_of(rd) is T.REAL and isinstance(e, A.Literal) and e.prefix is None and \
                e.kind in ("REAL", "INT") and abs(e.value) > _REAL_MAX:
            self.err("PLC0111", f"{e.text} does not fit in REAL (at most about 3.4E38); use "
                     "LREAL", e.loc)
            return
        if T.can_widen(rs, rd):
            if T.base_of(rs).name in ("DINT", "UDINT", "LINT") and T.base_of(rd) is T.REAL:
                self.warn("PLC0202", f"{rs} to REAL may lose precision (REAL has 24 bits of "
                          "mantissa); use LREAL or an explicit conversion", loc)
            if isinstance(rd, T.Subrange) and isinstance(e, A.Literal) and e.kind == "INT" and \
                    not T.fits(e.value, rd):
                self.err("PLC0111", f"{e.value} is outside the subrange {rd.lo}..{rd.hi}", e.loc)
            return
        if isinstance(rs, T.StringType) and isinstance(rd, T.StringType) and rs.wide != rd.wide:
            self.err("PLC0103", "STRING and WSTRING do not mix; convert with STRING_TO_WSTRING",
                     loc)
            return
        if rs.kind == "real" and rd.kind == "int" and not isinstance(rd, T.Subrange) and \
                self.cx.dialect(loc).implicit_real_to_int:
            sn, dn = T.base_of(T.concrete(rs)).name, T.base_of(rd).name
            self.warn("PLC0283", f"{sn} stored in {dn} without a conversion (accepted as in "
                      f"CODESYS): it is rounded as {sn}_TO_{dn} rounds (2.5 -> 3, -2.5 -> -3); "
                      f"write {sn}_TO_{dn}(...) to say so, or TRUNC(...) to drop the fraction",
                      loc)
            return
        if T.base_of(rs) is T.LREAL and T.base_of(rd) is T.REAL and \
                self.cx.dialect(loc).literal_context and _lreal_from_literals(e):
            self.warn("PLC0290", "a real literal here is REAL, as CODESYS types a literal by "
                      "the variable it goes to (accepted as in CODESYS); IEC 61131-3 reads "
                      "an untyped real literal as LREAL, so a strict compiler refuses LREAL "
                      "stored in REAL: write REAL#1.5 or LREAL_TO_REAL(...) to be portable",
                      loc)
            return
        if rs.kind in ("int", "bits") and rd.kind in ("int", "bits") and not isinstance(
                rd, T.Subrange) and self.cx.dialect(loc).implicit_int_conversion:
            sn, dn = T.base_of(T.concrete(rs)).name, T.base_of(rd).name
            self.warn("PLC0285", f"{sn} stored in {dn} without a conversion (accepted as in "
                      f"CODESYS): it wraps as {sn}_TO_{dn} wraps (a value outside {dn} "
                      f"changes, a sign may flip); write {sn}_TO_{dn}(...) to say so", loc)
            return
        hint = ""
        if rs.kind in ("int", "real", "bits", "time", "bool") and rd.kind in (
            "int", "real", "bits", "time", "bool"
        ):
            sn, dn = T.base_of(T.concrete(rs)).name, T.base_of(rd).name
            hint = f"; convert explicitly with {sn}_TO_{dn}(...)"
        self.err("PLC0118" if hint else "PLC0103",
                 f"cannot assign {T.concrete(rs)} to {rd} without a conversion{hint}", loc)

    def partial(self, e: A.Member, ot: T.Type, kind: str, n: int) -> T.Type:
        """``x.%B1``, ``x.%W0``, ``x.%D1``, ``x.%L0``: a byte, word, double or long word of a bit
        string (IEC 61131-3 ed.3 Table 17, item 1b), numbered from the least significant."""
        pt = T.lookup_elementary(A.PARTIAL_TYPES[kind])
        width = A.PARTIAL_WIDTHS[kind]
        bt = T.base_of(ot)
        if bt.kind != "bits" or not isinstance(bt, T.Elementary) or bt is T.BOOL:
            self.err("PLC0176", f"partial access .%{kind}{n} needs a bit string (WORD, DWORD, "
                     f"LWORD), not {ot}" + (f"; convert first, e.g. {bt.name}_TO_DWORD(x)"
                                           f".%{kind}{n}" if bt.kind == "int" else ""), e.loc)
        elif (n + 1) * width > bt.bits:
            count = bt.bits // width
            self.err("PLC0176", f"{bt.name} has no {pt.name} {n}: " + (
                f"its {pt.name}s are .%{kind}0 to .%{kind}{count - 1}" if count > 1 else
                f"it is one {pt.name}, .%{kind}0" if count else
                f"it is smaller than a {pt.name}"), e.loc)
        return pt


    def reinterpreted_ref(self, rs: T.Type, rd: T.Type, e: A.Expr, loc: Location) -> bool:
        """``pt := REF(x)`` with ``pt : REF_TO DWORD`` and ``x : REAL`` (OSCAT ``REAL_TO_DW``):
        in the codesys dialect, a reference to another elementary number or bit string of
        the same size reads and writes ``x``'s bits (PLC0291); elsewhere PLC0241."""
        if not (isinstance(rs, T.RefType) and isinstance(rd, T.RefType) and
                isinstance(e, A.Call) and e.target is not None and
                e.target.kind == "reference" and e.target.callee in ("REF", "ADR")):
            return False
        a, b = T.resolve(rs.target), T.resolve(rd.target)
        kinds = ("int", "bits", "real")
        if not (isinstance(a, T.Elementary) and isinstance(b, T.Elementary) and a is not b and
                a.kind in kinds and b.kind in kinds and a is not T.BOOL and b is not T.BOOL and
                a.bits == b.bits and self.cx.dialect(loc).reinterpret_refs):
            return False
        self.warn("PLC0291", f"a REF_TO {b.name} to a {a.name} reads and writes its bits as "
                  f"{b.name} (accepted as in CODESYS; IEEE 754, little-endian); IEC 61131-3 "
                  f"refuses a reference of another type: convert the value, or keep the "
                  f"bits in a {b.name} variable", loc)
        e.target.pun = (a.name, b.name)
        return True

    def lookup(self, name: str) -> Any:
        sym = self.cx.scope.local(name)
        if sym is not None:
            return sym
        g = self.table.globals.get(name)
        if g is not None:
            return VarSym(g, "global", None)
        return None

    def own_property(self, e: A.Name, write: bool) -> T.Type | None:
        """A bare PROPERTY name inside its own block (its body, methods and accessors), as
        CODESYS allows: ``Speed := Speed + 1.0`` means ``THIS^.Speed := THIS^.Speed + 1.0``.
        ``e.sym`` := the accessor; None when ``e`` names no property of the block."""
        this = self.cx.scope.local("THIS")
        if not isinstance(this, VarSym) or this.storage != "this":
            return None
        block = self.cx.oop._block_of(self.cx.pou)
        if block is None or block.kind != "FUNCTION_BLOCK":
            return None
        m = A.Member(e.loc, A.Name(e.loc, "THIS"), e.name, e.text)
        m.obj.sym = this
        pt = self.cx.oop.property_access(m, block, write)
        if pt is None:
            return None
        e.sym = m.sym
        return pt

    @staticmethod
    def property_in(e: A.Expr) -> A.Expr | None:
        """The PROPERTY access in the path ``e`` (``m.Speed``, ``Speed``, ``m.Pos.x``), or
        None: a property is a pair of calls, not a variable, so nothing can point at it."""
        while True:
            if isinstance(e, A.Name | A.Member) and isinstance(e.sym, A.Pou):
                return e
            if not isinstance(e, A.Member | A.Index):
                return None
            e = e.obj

    def lvalue(self, e: A.Expr) -> T.Type:
        t = self.expr(e, None, write=True)
        e.is_target = True  # never moved into a temporary
        if isinstance(e, A.Member) and e.field_name.startswith("%"):
            e.obj.is_target = True  # x.3 := ... assigns x
        root = e
        while isinstance(root, A.Member | A.Index):
            root = root.obj
        if isinstance(root, A.Name) and root is not e and isinstance(root.sym, VarSym) and (
                root.sym.decl.constant or root.sym.read_only):  # LIMITS[1] := ..., P.x := ...
            self.err("PLC0105", f"{root.sym.decl.spelling or root.name} is a constant and "
                     "cannot be changed", e.loc)
        if isinstance(e, A.Name):
            sym = e.sym
            if isinstance(sym, VarSym):
                d = sym.decl
                if d.constant or sym.read_only:
                    self.err("PLC0105", f"{d.spelling or d.name} is a constant and cannot be "
                             "changed" + (" (it is declared VAR_EXTERNAL CONSTANT here)"
                                          if sym.read_only and not d.constant else ""), e.loc)
                elif d.address and d.address.startswith("%I"):
                    self.input_write(f"{d.spelling or d.name} is a physical input ({d.address})",
                                     e.loc)
                elif d.section == "VAR_INPUT" and self.cx.pou is not None and \
                        self.cx.pou.kind == "FUNCTION_BLOCK":
                    self.warn("PLC0203", f"{d.name} is an input of {self.cx.pou.name}: the caller "
                              "overwrites it on every call; copy it to a local variable", e.loc)
            elif isinstance(sym, EnumSym):
                self.err("PLC0105", f"{e.name} is an enumeration value, not a variable", e.loc)
            elif isinstance(sym, ProgSym):
                self.err("PLC0105", f"{e.name} is a program; assign its variables instead",
                         e.loc)
        elif isinstance(e, A.DirectAddr):
            if e.address.startswith("%I"):
                self.input_write(f"{e.address} is a physical input", e.loc)
        elif not isinstance(e, A.Name | A.Member | A.Index):
            self.err("PLC0105", "the left side of ':=' must be a variable, an element or a "
                     "member", e.loc)
        return t

    def input_write(self, what: str, loc: Location) -> None:
        """A write to a physical input: PLC0105, or in a dialect with ``input_writes``
        (matiec) the warning PLC0284, the next input read overwriting the value (ADR 0037)."""
        if self.cx.dialect(loc).input_writes:
            self.warn("PLC0284", f"{what}: MATIEC lets a program write it, but the next scan's "
                      "input read overwrites the value; write a memory variable (%M or "
                      "unlocated) unless an extension publishes the input", loc)
        else:
            self.err("PLC0105", f"{what}; a program can read an input but not write it", loc)

    def expr(self, e: A.Expr, expected: T.Type | None, write: bool = False) -> T.Type:
        t = self.visit(e, expected, write)
        e.ty = t
        return t

    # one visit_<Class> per expression class (an unknown class raises UnhandledNode)
    def visit_Literal(self, e: A.Literal, expected: T.Type | None, write: bool) -> T.Type:
        return self.literal(e, expected)

    def visit_Name(self, e: A.Name, expected: T.Type | None, write: bool) -> T.Type:
        return self.name(e, expected, write)

    def visit_DirectAddr(self, e: A.DirectAddr, expected: T.Type | None, write: bool) -> T.Type:
        return self.direct(e)

    def visit_Member(self, e: A.Member, expected: T.Type | None, write: bool) -> T.Type:
        return self.member(e, write)

    def visit_Index(self, e: A.Index, expected: T.Type | None, write: bool) -> T.Type:
        return self.index(e)

    def visit_Unary(self, e: A.Unary, expected: T.Type | None, write: bool) -> T.Type:
        return self.unary(e, expected)

    def visit_Binary(self, e: A.Binary, expected: T.Type | None, write: bool) -> T.Type:
        return self.binary(e, expected)

    def visit_Call(self, e: A.Call, expected: T.Type | None, write: bool) -> T.Type:
        calls = self.cx.calls
        outer, calls.expected = calls.expected, expected  # TRUNC is typed by its context
        try:
            return calls.call(e, statement=False)
        finally:
            calls.expected = outer

    def visit_ArrayInit(self, e: A.Expr, expected: T.Type | None, write: bool) -> T.Type:
        self.err("PLC0103", "an aggregate initial value is only allowed in a declaration",
                 e.loc)
        return T.ANY

    visit_StructInit = visit_ArrayInit

    def literal(self, e: A.Literal, expected: T.Type | None) -> T.Type:
        k = e.kind
        if k == "BOOL":
            return T.BOOL
        if k in ("INT", "REAL") and e.prefix:
            t = self.cx.decls.named_type(e.prefix, e.loc)
            rt = T.resolve(t)
            if k == "INT" and rt.kind in ("int", "bits"):
                if not T.fits(e.value, rt):
                    self.err("PLC0111", f"{e.text} does not fit in {rt.name} ({_range_text(rt)})",
                             e.loc)
                return t
            if rt is T.BOOL and k == "INT" and e.value in (0, 1):
                e.kind, e.value = "BOOL", bool(e.value)
                return T.BOOL
            if rt.kind == "real":
                e.kind, e.value = "REAL", float(e.value)
                if rt is T.REAL and abs(e.value) > _REAL_MAX:
                    self.err("PLC0111", f"{e.text} does not fit in REAL (at most about "
                             "3.4E38); use LREAL", e.loc)
                return t
            if isinstance(rt, T.EnumType):
                return rt
            self.err("PLC0111", f"{e.text} is not a valid {t} literal", e.loc)
            return t
        if k == "INT":
            return T.ANY_INT_LIT
        if k == "REAL":
            return T.ANY_REAL_LIT
        if k in ("STRING", "WSTRING"):
            return T.StringType(k == "WSTRING", max(len(e.value), 1))
        if k == "TIME":
            t = T.LTIME if e.prefix == "LTIME" else T.TIME
            if expected is not None and T.resolve(expected) is T.LTIME:
                t = T.LTIME
            ms = abs(e.value) // 1_000_000 * (-1 if e.value < 0 else 1)
            if t is T.TIME and not (T.TIME.lo <= ms <= T.TIME.hi):
                self.err("PLC0126", f"{e.text} is out of TIME's range (T#-24d20h31m23s648ms.."
                         "T#24d20h31m23s647ms, 32 bits of ms); use LTIME# for longer durations",
                         e.loc)
            return t
        if k in ("DATE", "TOD", "DT"):
            return {"DATE": T.DATE, "TOD": T.TOD, "DT": T.DT}[k]
        if k == "ENUM":
            tname, member = e.value
            t = T.resolve(self.cx.decls.named_type(tname, e.loc))
            if isinstance(t, T.EnumType):
                if member not in t.members:
                    self.err("PLC0116", f"{tname} has no value {member}" +
                             close_hint(member, t.members), e.loc)
                    return T.ANY
                e.enum_value = t.members[member]
                return t
            if t is not T.ANY:
                self.err("PLC0102", f"{tname} is not an enumeration type", e.loc)
            return T.ANY
        return T.ANY

    def name(self, e: A.Name, expected: T.Type | None, write: bool = False) -> T.Type:
        sym = self.lookup(e.name)
        if sym is None or (isinstance(sym, VarSym) and sym.storage == "global"):
            pt = self.own_property(e, write)  # a member shadows a global, as a variable does
            if pt is not None:
                return pt
        if sym is not None:
            e.sym = sym
            sym.decl.used = True
            return sym.decl.ty if sym.decl.ty is not None else T.ANY
        members = self.table.enum_members.get(e.name)
        if members:
            rexp = T.resolve(expected) if expected is not None else None
            for m in members:
                if m.type is rexp:
                    e.sym = m
                    return m.type
            if len(members) == 1:
                e.sym = members[0]
                return members[0].type
            self.err("PLC0100", f"{e.name} is a value of several enumerations ("
                     + ", ".join(m.type.name for m in members) + "); qualify it, e.g. "
                     f"{members[0].type.name}#{e.name}", e.loc)
            return T.ANY
        p = self.table.pous.get(e.name)
        if p is not None and p.kind == "PROGRAM":
            e.sym = ProgSym(p, p.name)
            return self.table.types[p.name]
        if p is not None and p.kind == "FUNCTION_BLOCK":
            self.err("PLC0100", f"{e.name} is a function block type; declare an instance "
                     f"(inst : {e.name};) and use the instance", e.loc)
            return T.ANY
        if e.name == "NULL":  # the reference to nothing (IEC ed.3, ADR 0021)
            return T.RefType(T.ANY)
        cands = list(self.cx.scope) + list(self.table.globals) + list(self.table.enum_members)
        rexp = T.resolve(expected) if expected is not None else None
        if isinstance(rexp, T.EnumType):  # l : LEVEL := PURPLE
            values = [rexp.spellings.get(k, k) for k in rexp.members]
            self.err("PLC0100", f"{e.text or e.name} is not a value of {rexp.name}; its values "
                     f"are {', '.join(values)}" + close_hint(e.name, list(rexp.members)), e.loc)
        elif e.name in ("THIS", "SUPER") and (e.text or "").endswith("^"):
            self.err("PLC0100", f"{e.text} exists only inside a FUNCTION_BLOCK or CLASS and its "
                     "METHODs (IEC 61131-3 ed.3 6.6.5); a FUNCTION or PROGRAM has no instance "
                     "of its own: pass the instance as an input", e.loc)
        else:
            self.err("PLC0100", f"{e.text or e.name} is not declared" + close_hint(e.name, cands)
                     + ("" if close_hint(e.name, cands) else "; declare it in a VAR section"),
                     e.loc)
        # declare it to avoid repeated errors
        d = A.VarDecl(e.loc, e.name, A.NamedTypeRef(e.loc, "ANY"))
        d.ty = T.ANY
        d.used = True
        sym2 = VarSym(d, "local", None)
        self.cx.scope.declare(e.name, sym2)
        e.sym = sym2
        return T.ANY

    def direct(self, e: A.DirectAddr) -> T.Type:
        a = e.address
        size, parts = split_address(a)
        if size == "X" and (len(parts) != 2 or len(parts[1]) > 1 or int(parts[1]) > 7):
            self.err("PLC0120", f"bit address {a[:30]} needs byte.bit with bit 0..7, e.g. %IX0.3",
                     e.loc)
        elif size != "X" and len(parts) != 1:
            self.err("PLC0120", f"{a[:30]}: only bit addresses (%IX, %QX, %MX) have a '.bit' part",
                     e.loc)
        else:
            self.cx.decls.image_extent(a, size, parts[0], e.loc)
        return {"X": T.BOOL, "B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}[size]

    def member(self, e: A.Member, write: bool) -> T.Type:
        if e.field_name == "^":  # r^ (ADR 0021)
            return self.cx.oop.deref(e)
        qualified = self.qualified_enum(e, write)
        if qualified is not None:
            return qualified
        ot = T.resolve(self.expr(e.obj, None))
        f = e.field_name
        if ot is T.ANY:
            return T.ANY
        part = A.partial_access(f)
        if part is not None and part[0] != "X":
            return self.partial(e, ot, *part)
        if part is not None:
            bit = part[1]
            bt = T.base_of(ot)
            if bt.kind not in ("bits", "int") or not isinstance(bt, T.Elementary):
                self.err("PLC0116", f"bit access .{bit} needs a BYTE/WORD/DWORD/LWORD or integer, "
                         f"not {ot}", e.loc)
            elif bit >= bt.bits:
                self.err("PLC0116", f"bit {bit} does not exist in {bt.name} (0..{bt.bits - 1})",
                         e.loc)
            return T.BOOL
        if isinstance(ot, T.StructType):
            d = ot.fields.get(f)
            if d is None:
                self.err("PLC0116", f"structure {ot.name} has no member {f}" +
                         close_hint(f, ot.fields), e.loc)
                return T.ANY
            return d.ty
        if isinstance(ot, T.FBType | T.InterfaceType):  # a PROPERTY (ADR 0021)
            pt = self.cx.oop.property_access(e, ot.pou, write)
            if pt is not None:
                return pt
        if isinstance(ot, T.FBType):
            pou = ot.pou
            members = self.table.members(pou)
            d = members.get(f)
            if d is None and self.cx.oop.method_without_call(e, pou):
                return T.ANY
            if d is None:
                names = list(members)
                self.err("PLC0116", f"{pou.kind.replace('_', ' ').lower()} {pou.name} has no "
                         f"member {f}" + close_hint(f, names), e.loc)
                return T.ANY
            e.sym = d
            inside = isinstance(e.obj, A.Name) and isinstance(e.obj.sym, VarSym) and \
                e.obj.sym.storage in ("this", "super")  # THIS^.x, SUPER^.x (ADR 0021)
            if pou.kind == "FUNCTION_BLOCK" and not self.cx.in_test and not inside:
                if d.section == "VAR" and self.cx.dialect(e.loc).fb_internal_access:
                    self.warn("PLC0353", f"{f} is internal to {pou.name}: MATIEC lets a program "
                              "read and write it from outside, IEC 61131-3 shows only a block's "
                              f"inputs and outputs; make {f} a VAR_INPUT or VAR_OUTPUT of "
                              f"{pou.name} to be portable", e.loc)
                elif d.section in ("VAR", "VAR_TEMP"):
                    self.err("PLC0121", f"{f} is internal to {pou.name}; only its inputs and "
                             "outputs are visible outside", e.loc)
                elif write and d.section == "VAR_OUTPUT":
                    self.err("PLC0105", f"{f} is an output of {pou.name}; only the block itself "
                             "writes it", e.loc)
            return d.ty
        self.err("PLC0116", f"{ot} has no members; '.{f}' needs a structure or a function block "
                 "instance", e.loc)
        return T.ANY

    def qualified_enum(self, e: A.Member, write: bool) -> T.Type | None:
        """``Color.Red``: a CODESYS qualified enumeration value (IEC writes ``Color#Red``);
        None when ``e`` is not one."""
        obj = e.obj
        if not isinstance(obj, A.Name) or self.lookup(obj.name) is not None:
            return None
        et = self.table.types.get(obj.name)
        if not isinstance(et, T.EnumType):
            return None
        sym = next((m for m in self.table.enum_members.get(e.field_name, ())
                    if m.type is et), None)
        spelled = f"{obj.text or obj.name}.{e.text or e.field_name}"
        if sym is None:
            self.err("PLC0102", f"{obj.name} has no value {e.field_name}" +
                     close_hint(e.field_name, list(et.members)), e.loc)
            return T.ANY
        if write:
            self.err("PLC0103", f"{spelled} is a constant; assign it to a variable instead",
                     e.loc)
        dialect = self.cx.dialect(e.loc)
        if not dialect.qualified_enums:
            self.err("PLC0174", f"{spelled}: the dialect '{dialect.name}' writes a qualified "
                     f"enumeration value as {obj.text or obj.name}#{e.text or e.field_name}",
                     e.loc)
        e.sym = sym
        e.ty = et
        return et

    def bits_accepted(self, t: T.Type, what: str, loc: Location) -> bool:
        """A bit string (BYTE, WORD, DWORD, LWORD) used as a number: the dialects that accept it
        (CODESYS, S7) get a teaching warning PLC0173; the caller reports the error otherwise."""
        b = T.base_of(t)
        if b.kind != "bits" or b is T.BOOL or not self.cx.dialect(loc).bit_arithmetic:
            return False
        self.warn("PLC0173", f"{what} on {T.concrete(b).name}, a bit string: accepted as in "
                  "CODESYS, but IEC 61131-3 keeps bit strings for bit patterns; an unsigned "
                  f"integer (USINT, UINT, UDINT) says what you mean", loc)
        return True

    def index(self, e: A.Index) -> T.Type:
        ot = T.resolve(self.expr(e.obj, None))
        for ix in e.indices:
            it = T.resolve(self.expr(ix, T.DINT))
            if it is not T.ANY and it.kind not in ("int", "enum") and it is not T.ANY_INT_LIT \
                    and not self.bits_accepted(it, "an array index", ix.loc):
                self.err("PLC0117", f"an array index must be an integer, not {it}", ix.loc)
        if ot is T.ANY:
            return T.ANY
        if isinstance(ot, T.StringType):
            self.err("PLC0117", "strings are not indexed with [...]; use MID(s, 1, position)",
                     e.loc)
            return T.ANY
        if isinstance(ot, T.VarArrayType):  # ARRAY[*]: bounds checked at run time (ADR 0060)
            if len(e.indices) != ot.ndims:
                self.err("PLC0117", f"{ot} has {ot.ndims} dimension(s) but {len(e.indices)} "
                         "index(es) were given", e.loc)
            return ot.elem
        if not isinstance(ot, T.ArrayType):
            self.err("PLC0117", f"{ot} is not an array and cannot be indexed", e.loc)
            return T.ANY
        if len(e.indices) != len(ot.dims):
            self.err("PLC0117", f"{ot} has {len(ot.dims)} dimension(s) but {len(e.indices)} "
                     "index(es) were given", e.loc)
            return ot.elem
        for ix, (lo, hi) in zip(e.indices, ot.dims, strict=True):
            v = self.cx.consts.const_value(ix) if isinstance(ix, A.Literal | A.Unary) else None
            if isinstance(v, int) and not lo <= v <= hi:
                self.err("PLC0112", f"index {v} is outside the array bounds {lo}..{hi}", ix.loc)
        return ot.elem


def _range_text(t: T.Type) -> str:
    t = T.resolve(t)
    if isinstance(t, T.Subrange):
        return f"{t.lo}..{t.hi}"
    if isinstance(t, T.Elementary):
        return f"{t.lo}..{t.hi}"
    return str(t)
