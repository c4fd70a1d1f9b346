"""The code of POUs: defaults and initial values, the classes of structures, blocks, functions,
globals and programs, the process image access of located variables, TEST blocks (a mixin of
:class:`plclab.compile.codegen.Codegen`).
"""

from __future__ import annotations

from ..lang import ast as A
from ..lang import types as T
from ..lang.check import CallInfo
from . import oop_emit
from .codegen_names import ident, member_path, program_attr


class PouEmit:
    """POUs, classes, located variables, TEST blocks (a mixin of Codegen)."""

    # -- defaults and initial values ----------------------------------------------------------
    def default_code(self, ty: T.Type) -> str:
        declared = T.declared_init(ty)
        if declared is not None:  # TYPE LEVEL : (LOW, HIGH) := HIGH
            return self.init_code(declared, ty)
        t = T.resolve(ty)
        if isinstance(t, T.VarArrayType):  # an ARRAY[*] in-out: bound at each call
            return "None"
        if isinstance(t, T.ArrayType):
            d = self.default_code(t.elem)
            if T.resolve(t.elem).is_aggregate:
                return f"[{d} for _ in range({t.size})]"
            return f"[{d}] * {t.size}"
        if isinstance(t, T.StructType):
            return f"{self.struct_cls[id(t)]}()"
        if isinstance(t, T.FBType):
            if t.pou.native:
                return f"P_{ident(t.name)}(_CTX)"
            return f"P_{ident(t.name)}()"
        return repr(T.default_value(t))

    def init_code(self, e: A.Expr | None, ty: T.Type) -> str:
        if e is None:
            return self.default_code(ty)
        t = T.resolve(ty)
        if isinstance(e, A.ArrayInit) and isinstance(t, T.ArrayType):
            vals: list[str] = []
            for rep, val in e.items:
                n = 1 if rep is None else int(rep.value)
                if isinstance(val, A.Literal) and val.kind == "DEFAULT":
                    code = self.default_code(t.elem)
                else:
                    code = self.init_code(val, t.elem)
                vals.extend([code] * n)
            vals = vals[: t.size]
            if len(vals) < t.size:
                d = self.default_code(t.elem)
                if T.resolve(t.elem).is_aggregate:
                    return "[" + ", ".join(vals) + f"] + [{d} for _ in range({t.size - len(vals)})]"
                return "[" + ", ".join(vals) + f"] + [{d}] * {t.size - len(vals)}"
            return "[" + ", ".join(vals) + "]"
        if isinstance(e, A.StructInit):
            fields = t.fields if isinstance(t, T.StructType) else {
                d.name: d for d in t.pou.decls}
            kv = ", ".join(
                f"{ident(n)}={self.init_code(v, fields[n].ty)}" for n, v, _ in e.fields
                if n in fields
            )
            return f"_setattrs({self.default_code(t)}, {kv})" if kv else self.default_code(t)
        return self.coerce(self.ex(e), e.ty, ty, e)

    # -- classes ------------------------------------------------------------------------------
    def struct_class(self, name: str, st: T.StructType) -> None:
        cls = f"S_{ident(name)}"
        fields = list(st.fields.values())
        self.emit(f"class {cls}:")
        self.ind += 1
        self.emit("__slots__ = (" + "".join(f"{ident(d.name)!r}, " for d in fields) + ")")
        self.emit("def __init__(self):")
        self.ind += 1
        for d in fields:
            self.where_now = self.where(d.loc)
            self.emit_init(f"self.{ident(d.name)}", d)
        if not fields:
            self.emit("pass")
        self.ind -= 1
        self.emit(self.copier_line(fields))
        self.ind -= 1
        self.emit("")

    def copier_line(self, decls: list[A.VarDecl]) -> str:
        """``_copy = _copier(...)``: the class's copy method, made by one runtime helper from
        the names of its members grouped the way :meth:`copy_code` copies them (ADR 0034)."""
        groups: tuple[list[str], ...] = ([], [], [], [])
        for d in decls:
            t = T.resolve(d.ty)
            if isinstance(t, T.ArrayType):
                groups[3 if T.resolve(t.elem).is_aggregate else 2].append(ident(d.name))
            elif isinstance(t, T.StructType | T.FBType):
                groups[1].append(ident(d.name))
            else:
                groups[0].append(ident(d.name))
        return "_copy = _copier(" + ", ".join(
            "(" + "".join(f"{n!r}, " for n in g) + ")" for g in groups) + ")"

    def copy_code(self, code: str, ty: T.Type) -> str:
        t = T.resolve(ty)
        if isinstance(t, T.ArrayType):
            if T.resolve(t.elem).is_aggregate:
                return f"[_e._copy() for _e in {code}]"
            return f"list({code})"
        if isinstance(t, T.StructType | T.FBType):
            return f"{code}._copy()"
        return code

    def member_decls(self, pou: A.Pou) -> list[A.VarDecl]:
        """The instance variables of ``pou``, inherited ones (EXTENDS) first."""
        return [d for d in self.p.symbols.members(pou).values()
                if d.section not in ("VAR_TEMP", "VAR_EXTERNAL")]

    def block_class(self, pou: A.Pou) -> None:
        cls = f"P_{ident(pou.name)}"
        self.pou = pou
        members = self.member_decls(pou)
        self.where_now = self.where(pou.loc)
        self.emit(f"class {cls}:")
        self.ind += 1
        self.emit("__slots__ = (" + "".join(f"{ident(d.name)!r}, " for d in members) + ")")
        oop_emit.interfaces_line(self, pou)
        # _fbinit: the values of FB_init's further inputs (a : FB(3)), for a block that has them
        self.emit("def __init__(self, *_fbinit):" if oop_emit.fb_init_inputs(self, pou) else
                  "def __init__(self):")
        self.ind += 1
        self.forward_defaults(members, lambda d: f"self.{ident(d.name)}")
        for d in members:
            self.where_now = self.where(d.loc)
            self.emit_init(f"self.{ident(d.name)}", d)
        oop_emit.init_calls(self, pou)
        self.emit("pass")
        self.ind -= 1
        self.emit(self.copier_line(members))
        self.emit("def _body(self):")
        self.ind += 1
        self.where_now = self.where(pou.loc)
        temps = [d for d in pou.decls if d.section == "VAR_TEMP"]
        self.forward_defaults(temps, lambda d: f"v_{ident(d.name)}")
        for d in temps:
            self.emit_init(f"v_{ident(d.name)}", d)
        self.function_body(pou.body, [d.name for d in pou.decls if d.section == "VAR_TEMP"], True)
        self.emit("return")
        self.ind -= 1
        oop_emit.emit_methods(self, pou)
        self.ind -= 1
        self.emit("")
        self.pou = None

    def function(self, pou: A.Pou) -> None:
        self.pou = pou
        params = [d for d in pou.decls if d.section in ("VAR_INPUT", "VAR_IN_OUT")]
        self.where_now = self.where(pou.loc)
        self.emit(f"def F_{ident(pou.name)}(" + ", ".join(f"v_{ident(d.name)}" for d in params)
                  + "):")
        self.ind += 1
        rd = pou.return_decl
        if rd.ty is not T.VOID:
            self.emit(f"v_{ident(pou.name)} = {self.default_code(rd.ty)}")
        own = [d for d in pou.decls if d.section in ("VAR", "VAR_TEMP", "VAR_OUTPUT")]
        self.forward_defaults(own, lambda d: f"v_{ident(d.name)}")
        for d in own:
            self.where_now = self.where(d.loc)
            self.emit_init(f"v_{ident(d.name)}", d)
        self.function_body(pou.body, [pou.name] + [d.name for d in pou.decls
                                                    if d.section != "VAR_EXTERNAL"], False)
        self.emit(self.function_return(pou))
        self.ind -= 1
        self.emit("")
        self.pou = None

    def function_return(self, pou: A.Pou) -> str:
        rd = pou.return_decl
        res = f"v_{ident(pou.name)}" if rd.ty is not T.VOID else "None"
        outs = [d for d in pou.decls if d.section in ("VAR_OUTPUT", "VAR_IN_OUT")]
        if not outs:
            return f"return {res}"
        return "return (" + res + ", " + ", ".join(f"v_{ident(d.name)}" for d in outs) + ")"

    def globals_class(self) -> None:
        self.emit("class _Globals:")
        self.ind += 1
        gl = list(self.p.globals.values())
        self.emit("__slots__ = (" + "".join(f"{ident(d.name)!r}, " for d in gl) + ")")
        self.emit("def __init__(self):")
        self.ind += 1
        self.emit("global _G")  # a global's initial value may name the globals above it
        self.emit("_G = self")
        self.forward_defaults(gl, lambda d: f"self.{ident(d.name)}")
        for d in gl:
            self.where_now = self.where(d.loc)
            self.emit_init(f"self.{ident(d.name)}", d)
        for r in self.p.symbols.resource_globals:  # after the configuration's (ADR 0037)
            self.emit(f"global _RG_{ident(r)}")
            self.emit(f"_RG_{ident(r)} = _Res_{ident(r)}()")
        self.emit("pass")
        self.ind -= 2
        self.emit("")
        for r, gs in self.p.symbols.resource_globals.items():
            self.emit(f"class _Res_{ident(r)}:")
            self.ind += 1
            self.emit("__slots__ = (" + "".join(f"{ident(n)!r}, " for n in gs) + ")")
            self.emit("def __init__(self):")
            self.ind += 1
            for d in gs.values():
                self.where_now = self.where(d.loc)
                self.emit_init(f"self.{ident(d.name)}", d)
            self.emit("pass")
            self.ind -= 2
            self.emit("")
        if self.p.symbols.resource_globals:
            self.emit("_R = None")

    def connected_program(self, name: str, pou: A.Pou, info: CallInfo) -> str:
        """``PROGRAM P1 : Prog(x := %IX1.1, y => %QX0.0)``: a class of the instance whose body
        takes its inputs, runs the program, then hands its outputs on; its name."""
        cls = f"C_{program_attr(name)}"
        base = f"P_{ident(pou.name)}"
        self.emit(f"class {cls}({base}):")
        self.ind += 1
        self.emit("__slots__ = ()")
        self.emit("def _body(self):")
        self.ind += 1
        vals = [(ident(d.name), self.coerce(self.ex(e), e.ty, d.ty, e)) for d, e in info.inputs]
        vals += [(ident(d.name), self.ex(e)) for d, e in info.inouts]
        self.flush_pre()
        for n, v in vals:
            self.emit(f"self.{n} = {v}")
        self.emit(f"{base}._body(self)")
        for d, e in info.inouts:
            if not T.resolve(d.ty).is_aggregate:
                self.assign_to(e, f"self.{ident(d.name)}")
        for d, target, neg in info.outputs:
            v = f"self.{ident(d.name)}"
            self.assign_to(target, self.coerce(f"(not {v})" if neg else v, d.ty, target.ty,
                                               None))
        self.ind -= 2
        self.emit("")
        return cls

    def programs_class(self) -> None:
        connected = {i.key: i.call.target for c in self.p.symbols.configs for i in c.instances
                     if i.call is not None and isinstance(i.call.target, CallInfo)}
        classes = {n: self.connected_program(n, pou, connected[n])
                   for n, pou, _ in self.p.programs if n in connected}
        for n, pou, _ in self.p.programs:  # a resource's instance sets its globals first
            res = self.p.symbols.resource_of(n)
            if res is not None and self.p.symbols.resource_globals:
                base = classes.get(n, f"P_{ident(pou.name)}")
                classes[n] = cls = f"R_{program_attr(n)}"
                self.emit(f"class {cls}({base}):")
                self.ind += 1
                self.emit("__slots__ = ()")
                self.emit("def _body(self):")
                self.ind += 1
                self.emit("global _R")
                self.emit(f"_R = {f'_RG_{ident(res)}' if res in self.p.symbols.resource_globals else 'None'}")
                self.emit(f"{base}._body(self)")
                self.ind -= 2
                self.emit("")
        self.emit("class _Programs:")
        self.ind += 1
        names = [n for n, _, _ in self.p.programs]
        self.emit("__slots__ = (" + "".join(f"{program_attr(n)!r}, " for n in names) + ")")
        self.emit("def __init__(self):")
        self.ind += 1
        for n, pou, _ in self.p.programs:
            self.emit(f"self.{program_attr(n)} = {classes.get(n, f'P_{ident(pou.name)}')}()")
        for b in self.p.symbols.config_bindings:  # VAR_CONFIG initial values, after the POUs'
            if b.init is not None:
                self.emit_init(member_path(f"self.{program_attr(b.instance)}", b.via, b.decl),
                               b.decl, b.init)
        self.emit("pass")
        self.ind -= 2
        self.emit("")

    def sync_functions(self) -> None:
        """The copies between located variables and the process image (ADR 0056): the image
        is the one truth, a located variable an alias of its bytes. ``_sync_in`` (scan start)
        loads every located variable from its bytes (%I, and %Q and %M too, so that a direct
        address, an overlapping variable or a write from outside the program is seen) and
        remembers what it loaded; ``_sync_out`` (scan end) writes back only the %Q and %M
        variables the program changed, so an unchanged word does not wipe a bit written
        through ``%QX3.0``, then loads them all again, so that after a scan every variable
        shows its bytes; ``_sync_init`` (after a restart) writes every %Q and %M variable
        with its initial value."""
        ins: list[str] = []
        outs: list[str] = []
        reload: list[str] = []
        init: list[str] = []
        k = 0
        for v, path in self.located():
            area = v.address[1]
            rd = self.addr_read(v.address, v.decl.ty)
            if area == "I":
                ins.append(f"{path} = {rd}")
                continue
            write = self.addr_write(v.address, path, v.decl.ty)
            ins.append(f"{path} = _LOC[{k}] = {rd}")
            outs.append(f"if {path} != _LOC[{k}]: {write}")
            reload.append(f"{path} = {rd}")
            init.append(write)
            k += 1
        self.emit(f"_LOC = [None] * {k}")
        for name, body in (("_sync_in", ins), ("_sync_out", outs + reload), ("_sync_init", init)):
            self.emit(f"def {name}():")
            self.ind += 1
            for line in body:
                self.emit(line)
            self.emit("pass")
            self.ind -= 1
        self.emit("")

    def located(self):
        """(declaration, Python path) of every located variable with a concrete address."""
        for v in self.p.symbols.located_vars():
            if not v.wildcard:
                owner = (f"_RG_{ident(v.resource)}" if v.resource else "_G") \
                    if v.instance is None else f"_P.{program_attr(v.instance)}"
                yield v, member_path(owner, v.via, v.decl)

    # -- process image access -----------------------------------------------------------------
    @staticmethod
    def parse_addr(addr: str) -> tuple[str, str, int, int]:
        area = addr[1]
        size = addr[2] if addr[2].isalpha() else "X"
        rest = addr[3:] if addr[2].isalpha() else addr[2:]
        parts = rest.split(".")
        return area, size, int(parts[0]), int(parts[1]) if len(parts) > 1 else 0

    def addr_read(self, addr: str, ty: T.Type | None = None) -> str:
        area, size, byte, bit = self.parse_addr(addr)
        buf = f"_{area}"
        if size == "X":
            return f"({buf}[{byte}] >> {bit} & 1 != 0)"
        n = {"B": 1, "W": 2, "D": 4, "L": 8}[size]
        t = T.base_of(ty) if ty is not None else None
        if t is not None and t.kind == "real":
            fmt = ">f" if n == 4 else ">d"
            return f"_unpack_from({fmt!r}, {buf}, {byte})[0]"
        signed = bool(t is not None and getattr(t, "signed", False) and t.kind in ("int", "time"))
        if n == 1 and not signed:
            return f"{buf}[{byte}]"
        return f"int.from_bytes({buf}[{byte}:{byte + n}], 'big', signed={signed})"

    def addr_write(self, addr: str, value: str, ty: T.Type | None = None) -> str:
        area, size, byte, bit = self.parse_addr(addr)
        buf = f"_{area}"
        if size == "X":
            return (f"{buf}[{byte}] = ({buf}[{byte}] | {1 << bit}) if {value} else "
                    f"({buf}[{byte}] & {0xFF ^ (1 << bit)})")
        n = {"B": 1, "W": 2, "D": 4, "L": 8}[size]
        t = T.base_of(ty) if ty is not None else None
        if t is not None and t.kind == "real":
            fmt = ">f" if n == 4 else ">d"
            return f"_pack_into({fmt!r}, {buf}, {byte}, {value})"
        mask = (1 << (8 * n)) - 1
        return f"{buf}[{byte}:{byte + n}] = (({value}) & {mask}).to_bytes({n}, 'big')"

    # -- tests --------------------------------------------------------------------------------
    def test_function(self, i: int, t: A.TestBlock) -> None:
        fn = f"_test_{i}"
        self.tests.append((t.title, fn, t.loc))
        self.where_now = self.where(t.loc)
        self.emit(f"def {fn}():")
        self.ind += 1
        for d in t.decls:
            self.where_now = self.where(d.loc)
            self.emit_init(f"v_{ident(d.name)}", d)
        self.function_body(t.body, [d.name for d in t.decls], False)
        self.emit("return")
        self.ind -= 1
        self.emit("")


