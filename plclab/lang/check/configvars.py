"""Pass: VAR_CONFIG and VAR_ACCESS of a configuration (IEC 61131-3 ed.3 6.8.2, Table 62).

A VAR_CONFIG line names a variable inside a program instance by its path
(``[resource.]instance.member...``) and gives it the address its ``AT %I*`` left open, an
initial value, or both; a VAR_ACCESS line publishes a variable or a direct address under a name
of its own, read-only or read-write. Both are checked after the configuration is known (the
paths start at its program instances) and kept in the symbol table as
:class:`~.symbols.ConfigBinding` and :class:`~.symbols.AccessBinding`; the compiler syncs the
completed addresses and sets the initial values, the runtime resolves access names
(``plc["ABLE"]``). Codes: PLC0100 (unknown name in a path), PLC0101 (given twice), PLC0103
(type), PLC0116 (no members), PLC0120 (address).
"""

from __future__ import annotations

from ...errors import Location
from .. import ast as A
from .. import types as T
from .pass_api import Pass
from .symbols import AccessBinding, ConfigBinding, Scope, close_hint, instance_label

__all__ = ["ConfigVars"]

_AREAS = {"I": "an input", "Q": "an output", "M": "a memory"}


class ConfigVars(Pass):
    """Resolves and checks every VAR_CONFIG and VAR_ACCESS line."""

    def run(self, programs: list[tuple[str, A.Pou, str | None]]) -> None:
        self.instances = {inst: pou for inst, pou, _ in programs}
        seen: dict[tuple[str, tuple[str, ...], str], Location] = {}
        for cv in self.table.config_vars:
            b = self.config_var(cv)
            if b is None:
                continue
            key = (b.instance, b.via, b.decl.name)
            if key in seen:
                self.err("PLC0101", f"{cv.spelled} is configured twice (first at line "
                         f"{seen[key].line}); keep one line", cv.loc)
                continue
            seen[key] = cv.loc
            self.table.config_bindings.append(b)
        for c in self.table.configs:
            for inst in c.instances:
                if inst.call is not None and inst.key in self.instances:
                    self.connections(inst, self.instances[inst.key])
            for ap in c.access_paths:
                self.access_path(ap)
        for pou in self.table.pous.values():
            for ap in pou.access_paths:
                self.program_access_path(pou, ap)

    # -- VAR_ACCESS of a PROGRAM (ed.2 and ed.3 B.1.5.3, program_access_decls) ---------------
    def program_access_path(self, pou: A.Pou, ap: A.AccessPath) -> None:
        """``VAR_ACCESS ax : x : INT READ_WRITE; END_VAR`` inside a PROGRAM: ``Inst.ax`` is
        ``Inst.x`` (IEC and MATIEC; CODESYS and TIA Portal have no such section: PLC0321)."""
        if pou.kind != "PROGRAM":
            self.err("PLC0321", f"VAR_ACCESS belongs in a PROGRAM or a CONFIGURATION, not in a "
                     f"{pou.kind}; declare the access path in the program that holds the "
                     "instance", ap.loc)
            return
        d = self.cx.dialect(ap.loc)
        if d.name not in ("iec", "matiec"):
            self.err("PLC0321", f"VAR_ACCESS inside a PROGRAM is IEC 61131-3 (program_access_"
                     f"decls, MATIEC accepts it); the dialect '{d.name}' has none: declare "
                     "the access path in a CONFIGURATION's VAR_ACCESS, or choose "
                     "{dialect 'iec'} or {dialect 'matiec'}", ap.loc)
            return
        own = self.table.members(pou)
        taken = self.table.program_access.setdefault(pou.name, {})
        if ap.name in own or ap.name in taken:
            self.err("PLC0101", f"access path {ap.spelling} has the name of a variable or "
                     f"another access path of {pou.name}; choose another name", ap.loc)
            return
        if ap.path[-1].startswith("%"):
            self.err("PLC0100", f"{ap.spelled}: a program's access path names one of its "
                     "variables; publish a direct address in the CONFIGURATION's VAR_ACCESS",
                     ap.loc)
            return
        chain = self.walk(pou, ap.path, ap.spelled, ap.loc)
        if chain is None or not self.same_type(ap.type, chain[-1].ty, ap.spelled, ap.loc):
            return
        taken[ap.name] = AccessBinding(ap.name, ap.spelling or ap.name, ".".join(
            d.spelling or d.name for d in chain), chain[-1].ty, ap.read_only)

    # -- PROGRAM P1 : Prog(x := %IX1.1, y => g) ----------------------------------------------
    def connections(self, inst: A.ProgramInstance, pou: A.Pou) -> None:
        """The connections of a program instance are checked as a call of the program from
        the configuration: inputs take globals, direct addresses and constants; outputs and
        in-outs go to globals and direct addresses."""
        assert inst.call is not None
        old = self.cx.scope
        self.cx.scope = Scope({}, self.table.globals)
        self.cx.calls.call_fb(inst.call, pou, True, program=True)
        self.cx.scope = old
    # -- paths ----------------------------------------------------------------------------
    def strip_resource(self, parts: list[str]) -> list[str]:
        if len(parts) > 1 and f"{parts[0]}.{parts[1]}" in self.instances:  # ADR 0037
            return [f"{parts[0]}.{parts[1]}"] + parts[2:]
        return parts[1:] if len(parts) > 1 and parts[0] in self.table.resources else parts

    def walk(self, owner: A.Pou | T.Type, parts: list[str], spelled: str,
             loc: Location) -> list[A.VarDecl] | None:
        """The members ``parts`` name from ``owner`` on (the block instances passed, then the
        variable), or None when a name is missing (reported)."""
        chain: list[A.VarDecl] = []
        for i, part in enumerate(parts):
            members = self.table.members(owner)
            decl = members.get(part)
            if decl is None:
                name = owner.name if isinstance(owner, A.Pou | T.Type) else str(owner)
                self.err("PLC0100", f"{spelled}: {name} has no variable {part}"
                         + close_hint(part, members), loc)
                return None
            if i < len(parts) - 1:
                t = T.resolve(decl.ty) if decl.ty is not None else T.ANY
                if not isinstance(t, T.FBType | T.StructType):
                    self.err("PLC0116", f"{spelled}: {part} is {t}, which has no members", loc)
                    return None
                owner = t
            chain.append(decl)
        return chain or None

    def instance_var(self, parts: list[str], spelled: str, loc: Location
                     ) -> tuple[str, list[A.VarDecl]] | None:
        """``P1.fb1.x`` -> (instance, the declarations of fb1 and x); reported and None when it
        names nothing."""
        parts = self.strip_resource(parts)
        head = parts[0]
        pou = self.instances.get(head)
        if pou is None:
            self.err("PLC0100", f"{spelled}: {head} is not a program instance of the "
                     "configuration" + close_hint(head, self.instances) +
                     "; a path starts at a program instance, e.g. P1.x", loc)
            return None
        if len(parts) == 1:
            self.err("PLC0100", f"{spelled} names a program instance; name one of its "
                     f"variables, e.g. {spelled}.x", loc)
            return None
        chain = self.walk(pou, parts[1:], spelled, loc)
        return None if chain is None else (head, chain)

    def label(self, instance: str, chain: list[A.VarDecl]) -> str:
        """The path in the form the runtime and traces use (``Main.fb1.x``)."""
        return ".".join([instance_label(instance, self.instances[instance]),
                         *(d.spelling or d.name for d in chain)])

    def same_type(self, tref: A.TypeRef, want: T.Type, spelled: str, loc: Location) -> bool:
        ty = self.cx.decls.type_ref(tref)
        if ty is T.ANY or want is T.ANY or T.same_type(ty, want):
            return True
        self.err("PLC0103", f"{spelled} is {want}, not {ty}; write the variable's own type",
                 loc)
        return False

    def address_fits(self, address: str, ty: T.Type, loc: Location) -> None:
        """The address's own checks (size, range, type) as if declared ``AT address : ty``."""
        d = A.VarDecl(loc, "", A.NamedTypeRef(loc, "ANY"), None, address)
        d.ty = ty
        self.cx.decls.check_address(d)

    # -- VAR_CONFIG -------------------------------------------------------------------------
    def config_var(self, cv: A.ConfigVar) -> ConfigBinding | None:
        found = self.instance_var(cv.path, cv.spelled, cv.loc)
        if found is None:
            return None
        inst, chain = found
        decl = chain[-1]
        if not self.same_type(cv.type, decl.ty, cv.spelled, cv.loc):
            return None
        if cv.address is not None:
            declared = (decl.address or "").upper()
            if not declared.endswith("*"):
                self.err("PLC0120", f"{cv.spelled} is not declared with a wildcard address "
                         "(AT %I*, %Q* or %M*); VAR_CONFIG only completes such an address" +
                         (f" and this one is AT {declared}" if declared else ""), cv.loc)
                return None
            if declared[1] != cv.address[1]:
                self.err("PLC0120", f"{cv.spelled} is declared AT {declared}, "
                         f"{_AREAS[declared[1]]}; give it a %{declared[1]} address, not "
                         f"{cv.address}", cv.loc)
                return None
            self.address_fits(cv.address, decl.ty, cv.loc)
        if cv.init is not None:
            old, self.cx.scope = self.cx.scope, Scope()
            self.cx.decls.init_value(cv.init, decl.ty, cv.loc)
            self.cx.scope = old
        return ConfigBinding(self.label(inst, chain), inst, tuple(d.name for d in chain[:-1]),
                             decl, cv.address, cv.init)

    # -- VAR_ACCESS -------------------------------------------------------------------------
    def access_path(self, ap: A.AccessPath) -> None:
        if ap.name in self.table.globals or ap.name in self.instances or \
                ap.name in self.table.access_paths:
            self.err("PLC0101", f"access path {ap.spelling} has the name of a global variable, "
                     "a program instance or another access path; choose another name", ap.loc)
            return
        parts = self.strip_resource(ap.path)
        if parts[-1].startswith("%"):
            if len(parts) > 1:
                self.err("PLC0100", f"{ap.spelled}: a direct address follows only the resource "
                         "name, e.g. STATION_1.%IX1.1", ap.loc)
                return
            ty = self.cx.decls.type_ref(ap.type)
            self.address_fits(parts[0], ty, ap.loc)
            target = parts[0]
        elif parts[0] in self.table.globals:
            g = self.table.globals[parts[0]]
            chain = [g]
            if len(parts) > 1:
                more = self.walk(g.ty, parts[1:], ap.spelled, ap.loc)
                if more is None:
                    return
                chain += more
            if not self.same_type(ap.type, chain[-1].ty, ap.spelled, ap.loc):
                return
            ty, target = chain[-1].ty, ".".join(d.spelling or d.name for d in chain)
        else:
            found_i = self.instance_var(ap.path, ap.spelled, ap.loc)
            if found_i is None:
                return
            inst, chain = found_i
            if not self.same_type(ap.type, chain[-1].ty, ap.spelled, ap.loc):
                return
            ty, target = chain[-1].ty, self.label(inst, chain)
        self.table.access_paths[ap.name] = AccessBinding(ap.name, ap.spelling or ap.name,
                                                         target, ty, ap.read_only)
