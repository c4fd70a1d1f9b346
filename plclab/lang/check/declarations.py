"""Pass: declarations -- named types, type expressions, variable declarations, addresses and
initial values (PLC0101, PLC0102, PLC0103, PLC0109, PLC0120, PLC0127)."""

from __future__ import annotations

from ...errors import Location
from .. import ast as A
from .. import types as T
from ..addresses import SIZE_BYTES
from .pass_api import Pass
from .symbols import EnumSym, Scope, VarSym, close_hint

MAX_IMAGE_BYTES = 65536  # the largest process image a Plc may have (image_size)


def split_address(addr: str) -> tuple[str, list[str]]:
    """``%IX1.2`` -> ("X", ["1", "2"]); ``%QW4`` -> ("W", ["4"]) (the lexer checked the form)."""
    sized = addr[2:3].isalpha()
    return (addr[2] if sized else "X"), addr[3 if sized else 2:].split(".")


class Declarations(Pass):
    """Resolves the types of TYPEs, globals, POU variables and TEST variables (``VarDecl.ty``)."""

    def run(self) -> None:
        """TYPEs first (global constants may size them), then the globals, then each POU's
        variables; no body is looked at."""
        table, consts = self.table, self.cx.consts
        for d in table.global_decls:  # global constants may size types declared before them
            if d.constant:
                consts.global_consts.setdefault(d.name, d)
        for name, td in table.type_decls.items():
            if isinstance(td.type, A.EnumTypeRef):
                for mname, _, _ in td.type.members:
                    consts.enum_index.setdefault(mname, name)
        for name in table.type_decls:
            self.named_type(name, table.type_decls[name].loc)
        for name, td in table.type_decls.items():
            if td.init is not None and name in table.types:
                self.init_value(td.init, table.types[name], td.loc)
        for p in table.pous.values():
            if p.kind != "FUNCTION":
                table.types.setdefault(p.name, T.block_type(p.name, p))
        per_resource = {id(d) for c in table.configs for ds in c.resource_globals.values()
                        for d in ds}
        for d in table.global_decls:
            self.decl_type(d)
            self.constant_value(d)
            if id(d) not in per_resource:
                table.declare_global(d, self.cx.report)
        for c in table.configs:  # after the configuration's: a name in both is reported
            for r, decls in c.resource_globals.items():
                table.declare_resource_globals(r, decls, self.cx.report)
        for d in table.global_decls:
            self.check_init(d, Scope())
        for p in table.pous.values():
            self.check_pou_decls(p)

    def named_type(self, name: str, loc: Location) -> T.Type:
        t = T.lookup_elementary(name)
        if t is not None:
            return t
        if name in self.table.types:
            return self.table.types[name]
        if name in self.table.type_decls:
            td = self.table.type_decls[name]
            if self.cx.consts.chain_too_deep("types, constants and enumeration values",
                                             "declare them with fewer levels", loc):
                return T.ANY
            if not self.cx.consts.enter(("type", name), td.spelling or name, td.loc):
                return T.ANY
            try:
                ty = self.type_ref(td.type, td.name)
            finally:
                self.cx.consts.leave()
            if isinstance(ty, T.Elementary | T.StringType | T.ArrayType | T.Subrange | T.FBType):
                ty = T.AliasType(name, ty) if not isinstance(ty, T.Subrange) else ty
            if td.init is not None and ty is not T.ANY:
                fresh = isinstance(ty, T.AliasType) or isinstance(
                    td.type, A.EnumTypeRef | A.SubrangeTypeRef)
                if not fresh:  # a new name for a type declared elsewhere keeps that one's default
                    ty = T.AliasType(name, ty)
                ty.init = td.init  # type: ignore[union-attr]
            self.table.types.setdefault(name, ty)
            return self.table.types[name]
        if name in self.table.pous and self.table.pous[name].kind != "FUNCTION":
            t2 = self.table.types.setdefault(name, T.block_type(name, self.table.pous[name]))
            return t2
        cands = list(T.ELEMENTARY) + list(self.table.type_decls) + [
            k for k, v in self.table.pous.items() if v.kind != "FUNCTION"] + ["STRING", "WSTRING"]
        self.err("PLC0102", f"unknown type {name}" + close_hint(name, cands), loc)
        return T.ANY

    def type_ref(self, r: A.TypeRef, name: str | None = None) -> T.Type:
        ok, self.var_array_ok = self.var_array_ok, False  # for the outermost type only
        if isinstance(r, A.ArrayTypeRef) and r.star:
            return self.var_array(r, ok)
        if isinstance(r, A.NamedTypeRef):
            return self.named_type(r.name, r.loc)
        if isinstance(r, A.RefTypeRef):  # REF_TO, POINTER TO (ADR 0021)
            return self.cx.oop.ref_type(r)
        if isinstance(r, A.StringTypeRef):
            n = 80
            if r.length is not None:
                v = self.cx.consts.const_int(r.length)
                if v is not None:
                    if v < 1 or v > 65535:
                        self.err("PLC0109", f"string length {v} is out of range 1..65535",
                                 r.length.loc)
                    else:
                        n = v
            return T.StringType(r.wide, n)
        if isinstance(r, A.ArrayTypeRef):
            dims = []
            known = True
            for lo_e, hi_e in r.ranges:
                lo, hi = self.cx.consts.const_int(lo_e), self.cx.consts.const_int(hi_e)
                if lo is None or hi is None:
                    lo, hi, known = 0, 0, False
                elif hi < lo:
                    self.err("PLC0109", f"array range {lo}..{hi} is empty; write the lower bound "
                             "first", lo_e.loc)
                    hi = lo
                dims.append((lo, hi))
            elem = self.type_ref(r.elem)
            if not known:  # reported: no follow-up errors about its elements
                return T.ANY
            at = T.ArrayType(dims, elem)
            if at.size > 10_000_000:
                self.err("PLC0109", f"array of {at.size} elements is too large for a PLC "
                         "(limit 10,000,000)", r.loc)
            return at
        if isinstance(r, A.SubrangeTypeRef):
            base = T.base_of(self.type_ref(r.base))
            lo, hi = self.cx.consts.const_int(r.lo), self.cx.consts.const_int(r.hi)
            if not isinstance(base, T.Elementary) or base.kind != "int":
                self.err("PLC0102", "a subrange needs an integer base type, e.g. INT(0..100)",
                         r.loc)
                return T.ANY
            if lo is None or hi is None:
                return base
            if hi < lo or not (T.fits(lo, base) and T.fits(hi, base)):
                self.err("PLC0109", f"subrange {lo}..{hi} does not fit {base.name} or is empty",
                         r.loc)
                return base
            return T.Subrange(base, lo, hi)
        if isinstance(r, A.EnumTypeRef):
            base = T.INT
            if r.base is not None:
                b = T.base_of(self.type_ref(r.base))
                if isinstance(b, T.Elementary) and b.kind in ("int", "bits"):
                    base = b
            et = T.EnumType(name or f"enum@{r.loc.line}", {}, base, dict(r.spellings))
            if name is not None:
                self.table.types.setdefault(name, et)  # its values may name each other
            syms: list[EnumSym] = []
            prev: EnumSym | None = None
            for mname, mval, mloc in r.members:
                if mname in et.members:
                    self.err("PLC0101", f"enumeration value {mname} appears twice", mloc)
                sym = EnumSym(et, 0, mname)
                et.members[mname] = 0
                self.cx.consts.enum_pending[id(sym)] = (mval, prev, mloc)
                self.table.enum_members.setdefault(mname, []).append(sym)
                syms.append(sym)
                prev = sym
            for sym in syms:  # in order: an implicit value is the one before plus 1
                self.cx.consts.enum_value(sym)
                et.members[sym.member] = sym.value
            return et
        if isinstance(r, A.StructTypeRef):
            st = T.StructType(name or f"struct@{r.loc.line}", {})
            if name is None:  # a STRUCT written in a VAR section: the compiler makes it a class
                # too, under a name no program can write (PLC0006 forbids '__')
                self.table.types[f"__STRUCT_{sum(k.startswith('__STRUCT_') for k in self.table.types)}"] = st
            for d in r.fields:
                self.decl_type(d)
                if d.name in st.fields:
                    self.err("PLC0101", f"field {d.name} appears twice in the structure", d.loc)
                st.fields[d.name] = d
            for d in r.fields:
                self.check_init(d, Scope())
            return st
        return T.ANY

    var_array_ok = False  # resolving the type of a VAR_IN_OUT of a FUNCTION, block or METHOD

    def var_array(self, r: A.ArrayTypeRef, ok: bool) -> T.Type:
        """``ARRAY[*, ...] OF T``: only as the type of a VAR_IN_OUT, where the argument gives
        the bounds (IEC 61131-3 ed.3 6.5.3; ADR 0060)."""
        elem = self.type_ref(r.elem)
        dialect = self.cx.dialect(r.loc)
        if not dialect.var_length_arrays:
            self.err("PLC0351", "ARRAY[*] (a variable-length array) is IEC 61131-3 ed.3; "
                     f"the dialect '{dialect.name}' follows ed.2, which has none: declare "
                     "the bounds (ARRAY[1..10] OF INT) or choose {dialect 'iec'} or "
                     "{dialect 'codesys'}", r.loc)
            return T.ANY
        if not ok:
            self.err("PLC0350", "ARRAY[*] (a variable-length array) is allowed only as the type "
                     "of a VAR_IN_OUT of a FUNCTION, FUNCTION_BLOCK or METHOD, whose argument "
                     "gives the bounds; declare the bounds here (ARRAY[1..10] OF INT)", r.loc)
            return T.ANY
        return T.ANY if elem is T.ANY else T.VarArrayType(r.star, elem)

    def decl_type(self, d: A.VarDecl) -> T.Type:
        if d.ty is None:
            d.ty = self.type_ref(d.type)
            if d.address:
                self.check_address(d)
        return d.ty

    def image_extent(self, addr: str, size_ch: str, byte_text: str, loc: Location) -> None:
        """Check that ``addr`` (split by :func:`split_address`) lies inside the largest
        process image (PLC0127) and remember the largest extent:
        :class:`~plclab.runtime.plc.Plc` compares it with its ``image_size``."""
        byte = int(byte_text) if len(byte_text) <= 9 else MAX_IMAGE_BYTES
        end = byte + SIZE_BYTES[size_ch]
        if end > MAX_IMAGE_BYTES:
            self.err("PLC0127", f"{addr[:30]} lies beyond the largest process image ({MAX_IMAGE_BYTES:,}"
                     " bytes, %..0 to %..65535); use a smaller address", loc)
        elif self.cx.image_needed is None or end > self.cx.image_needed[0]:
            self.cx.image_needed = (end, addr, loc)

    def check_address(self, d: A.VarDecl) -> None:
        addr = d.address or ""
        if addr.endswith("*"):
            return
        size_ch, parts = split_address(addr)
        bits = 1 if size_ch == "X" else 8 * SIZE_BYTES[size_ch]
        t0 = T.resolve(d.ty) if d.ty is not None else T.ANY
        if (size_ch == "X" and (t0.is_aggregate or isinstance(t0, T.StringType))
                and self.cx.dialect(d.loc).name == "matiec"):
            # MATIEC: a Beremiz extension (MQTT...) exchanges the whole value (ADR 0059)
            name = d.spelling or d.name
            self.warn("PLC0340", f"{name} AT {addr} is of the structured type {t0.name}, "
                      f"whose whole value a Beremiz extension (the one of IEC channel {parts[0]}) "
                      "exchanges; plclab's process image holds bits and words only, so "
                      f"{name} is kept "
                      "as an ordinary variable: set it from a TEST block or the watch table "
                      "to simulate the extension", d.loc)
            d.address = None
            return
        if size_ch == "X" and len(parts) != 2:
            self.err("PLC0120", f"bit address {addr} needs byte.bit, e.g. %IX0.3", d.loc)
            return
        if size_ch == "X" and (len(parts[1]) > 1 or int(parts[1]) > 7):
            self.err("PLC0120", f"bit number {parts[1][:12]} in {addr[:30]} is out of range 0..7",
                     d.loc)
            return
        if size_ch != "X" and len(parts) != 1:
            self.err("PLC0120", f"{addr}: only bit addresses (%IX, %QX, %MX) have a '.bit' part"
                     " (MATIEC and Beremiz write module.item: choose {dialect 'matiec'})",
                     d.loc)
            return
        self.image_extent(addr, size_ch, parts[0], d.loc)
        t = T.resolve(d.ty)
        if t is T.ANY:
            return
        tb = 1 if t is T.BOOL else getattr(T.base_of(t), "bits", 0)
        if isinstance(t, T.EnumType):
            tb = t.base.bits
        if tb != bits:
            need = {1: "BOOL", 8: "BYTE, SINT or USINT", 16: "WORD, INT or UINT",
                    32: "DWORD, DINT, UDINT, REAL or TIME", 64: "LWORD, LINT or LREAL"}[bits]
            self.err("PLC0120", f"{d.spelling or d.name} is {t.name} but {addr} holds "
                     f"{bits} bit(s); declare it as {need}", d.loc)

    def check_scope(self, p: A.Pou) -> None:
        """The POU's names in the symbol table: each VAR_EXTERNAL must match a VAR_GLOBAL of the
        same type; a FUNCTION's result variable gets its type."""
        for d in p.decls:
            if d.section != "VAR_EXTERNAL":
                continue
            g = self.table.globals.get(d.name)
            if g is None and any(d.name in r for r in self.table.resource_globals.values()):
                continue  # a resource's global: checked per resource (ProgramChecks, ADR 0037)
            if g is None:
                self.err("PLC0100", f"VAR_EXTERNAL {d.name} has no matching VAR_GLOBAL"
                         + close_hint(d.name, self.table.globals), d.loc)
            else:
                if d.ty is not None and not T.same_type(d.ty, g.ty) and g.ty is not T.ANY:
                    self.err("PLC0103", f"VAR_EXTERNAL {d.name} is {d.ty} but the global is "
                             f"{g.ty}", d.loc)
                g.used = True
        self.table.scope(p)  # builds p.return_decl for a FUNCTION
        if p.return_decl is not None and p.return_type is not None:
            p.return_decl.ty = self.type_ref(p.return_type)

    def check_pou_decls(self, p: A.Pou) -> None:
        seen: dict[str, A.VarDecl] = {}
        # constants of the POU may size its arrays: make them visible while types resolve
        self.cx.scope = Scope({d.name: VarSym(d, "self", p) for d in p.decls if d.constant})
        for d in p.decls:
            if d.name in seen:
                self.err("PLC0101", f"variable {d.name} is declared twice in {p.name} (first at "
                         f"line {seen[d.name].loc.line}); rename or remove one", d.loc)
            seen[d.name] = d
            if d.section == "VAR_EXTERNAL" and isinstance(d.type, A.NamedTypeRef) and \
                    d.type.name == "__ANY__":
                continue
            self.var_array_ok = d.section == "VAR_IN_OUT" and p.kind in (
                "FUNCTION", "FUNCTION_BLOCK", "METHOD")
            try:
                self.decl_type(d)
            finally:
                self.var_array_ok = False
            if d.name == p.name and p.kind == "FUNCTION":
                self.err("PLC0101", f"{d.name} is the function's own name (its result); choose "
                         "another variable name", d.loc)
            if d.address and p.kind != "PROGRAM" and not d.address.endswith("*"):
                self.err("PLC0120", f"{d.name}: located variables (AT {d.address}) belong in a "
                         "PROGRAM or VAR_GLOBAL, not in a function or function block", d.loc)
            self.constant_value(d)
        self.check_scope(p)
        self.cx.scope = self.table.scope(p)
        for d in p.decls:
            if d.section != "VAR_EXTERNAL":
                self.check_init(d, self.cx.scope)
        self.cx.scope = Scope()

    def fb_init_arguments(self) -> None:
        """``a : FB(k := 3);``: CODESYS passes the arguments to the block's FB_init, to its
        inputs after bInitRetains and bInCopyCode (CODESYS online help, "FB_init"); each
        argument is checked as an input of a call, in the scope of the declaration, and bound
        on the type reference (``NamedTypeRef.bound``) for the compiler. PLC0322 elsewhere, or
        for a block without such an FB_init."""
        table = self.table
        owners: list[tuple[A.VarDecl, Scope]] = [(d, Scope()) for d in table.global_decls]
        for p in [*table.pous.values(), *(m for q in table.pous.values() for m in q.methods)]:
            if any(isinstance(d.type, A.NamedTypeRef) and d.type.args is not None
                   for d in p.decls):
                scope = table.scope(p)
                owners += [(d, scope) for d in p.decls]
        for d, scope in owners:
            tref = d.type
            if isinstance(tref, A.NamedTypeRef) and tref.args is not None:
                old, self.cx.scope = self.cx.scope, scope
                try:
                    self.bind_fb_init(d, tref)
                finally:
                    self.cx.scope = old

    def bind_fb_init(self, d: A.VarDecl, tref: A.NamedTypeRef) -> None:
        assert tref.args is not None
        dialect = self.cx.dialect(d.loc)
        t = T.resolve(d.ty) if d.ty is not None else T.ANY
        init = None
        if isinstance(t, T.FBType) and t.pou is not None:
            init = next((m for b in [t.pou, *self.table.bases(t.pou)] for m in b.methods
                         if m.name == "FB_INIT" and not m.action), None)
        extra = [x for x in init.decls if x.section == "VAR_INPUT"][2:] if init else []
        if dialect.name != "codesys" or not extra:
            why = (f"the dialect '{dialect.name}' has no FB_init: choose {{dialect 'codesys'}}, "
                   "or give the block's inputs initial values, a : FB := (k := 3)"
                   if dialect.name != "codesys" else
                   f"{t} has no FB_init method with inputs after bInitRetains and bInCopyCode"
                   " to take them; to set the block's inputs write a : FB := (k := 3)")
            self.err("PLC0322", f"{d.spelling or d.name} : {tref.name}(...) passes arguments "
                     f"to the block's FB_init (a CODESYS extension); {why}", d.loc)
            for a in tref.args:
                if a.value is not None:
                    self.cx.exprs.expr(a.value, None)
            return
        bound: list[tuple[A.VarDecl, A.Expr]] = []
        by_name = {x.name: x for x in extra}
        for i, a in enumerate(tref.args):
            target = by_name.get(a.name) if a.name else (extra[i] if i < len(extra) else None)
            if target is None or a.output or a.value is None or any(
                    target is b for b, _ in bound):
                self.err("PLC0322", f"{tref.name}'s FB_init takes " + ", ".join(
                    f"{x.spelling or x.name} : {x.ty}" for x in extra) + ", each once; "
                    f"not {a.name or f'a value number {i + 1}'}", a.loc)
                continue
            at = self.cx.exprs.expr(a.value, target.ty)
            self.cx.exprs.check_assignable(at, target.ty, a.value, a.loc)
            bound.append((target, a.value))
        given = {id(x): v for x, v in bound}
        tref.bound = [(x, given.get(id(x))) for x in extra]  # in FB_init's order

    def constant_value(self, d: A.VarDecl) -> None:
        """A constant without a value: its type's default in iec and matiec (ed.2 2.4.2, ed.3
        6.5.1.3 make the value optional), PLC0109 where the vendor requires one."""
        if d.constant and d.init is None and d.section not in ("VAR_EXTERNAL", "VAR_IN_OUT") \
                and not self.cx.dialect(d.loc).constant_default:
            self.err("PLC0109", f"constant {d.name} needs a value: {d.name} : {d.ty} := ...; "
                     "(CODESYS and TIA Portal require one; IEC and MATIEC give it its type's "
                     "default: {dialect 'iec'} or {dialect 'matiec'})", d.loc)

    def check_init(self, d: A.VarDecl, scope: Scope) -> None:
        if d.init is None:
            return
        old = self.cx.scope
        self.cx.scope = scope
        self.init_value(d.init, d.ty, d.loc)
        if d.constant:
            self.cx.const_values[id(d)] = self.cx.consts.const_of(d, scope)
        self.cx.scope = old

    def init_value(self, e: A.Expr, ty: T.Type, loc: Location) -> None:
        ty = T.resolve(ty)
        if isinstance(e, A.ArrayInit):
            if not isinstance(ty, T.ArrayType):
                self.err("PLC0103", f"an array initial value [...] cannot initialise {ty}", e.loc)
                return
            count = 0
            for rep, val in e.items:
                n = 1
                if rep is not None:
                    n = self.cx.consts.const_int(rep) or 0
                if not (isinstance(val, A.Literal) and val.kind == "DEFAULT"):
                    self.init_value(val, ty.elem, loc)
                count += n
            e.ty = ty
            if count > ty.size:
                self.err("PLC0109", f"{count} initial values for an array of {ty.size} elements; "
                         "remove the extra values", e.loc)
            return
        if isinstance(e, A.StructInit):
            if not isinstance(ty, T.StructType | T.FBType):
                self.err("PLC0103", f"a structure initial value (...) cannot initialise {ty}",
                         e.loc)
                return
            fields = self.table.members(ty)
            for fname, fval, floc in e.fields:
                fd = fields.get(fname)
                if fd is None:
                    self.err("PLC0116", f"{ty.name} has no member {fname}" +
                             close_hint(fname, fields), floc)
                    continue
                self.init_value(fval, fd.ty, floc)
            e.ty = ty
            return
        t = self.cx.exprs.expr(e, ty)
        self.cx.exprs.check_assignable(t, ty, e, e.loc)
