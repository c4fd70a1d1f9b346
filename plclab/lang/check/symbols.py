"""The symbol table: every declaration of a project, and the questions asked about them.

A :class:`SymbolTable` is built once from the parsed files (:meth:`SymbolTable.collect`): the
TYPEs, the POUs (a user POU hides a library block of the same name), the global variables, the
enumeration values and the program instances. It answers *declaration* questions only, so it is
usable **before any body is checked** -- a lowering stage (IL, LD/FBD networks) may build one
and ask ``scope(pou).lookup(name)`` or ``members(pou)``. What it cannot know before the
checker's declarations pass has run is the resolved type of a declaration: ``VarDecl.ty`` (and
``types``) are filled by that pass; ``lookup`` still finds the declaration.

After checking, the :class:`~plclab.lang.check.checker.Project` carries the table
(``project.symbols``): the runtime, the simulator and the Modbus server ask it for program
variables and located variables instead of walking ``pou.decls`` themselves.

>>> from plclab.lang.frontends.st import parse_st
>>> f = parse_st("PROGRAM P VAR x AT %IX0.1 : BOOL; n : INT; END_VAR n := 1; END_PROGRAM")
>>> table = SymbolTable.collect([f])
>>> table.scope(table.pou("P")).lookup("N").decl.name
'N'
>>> [(v.path, v.address) for v in table.located_vars()]
[('P.x', '%IX0.1')]
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Any

from ...errors import Location
from ...suggest import suggest
from .. import ast as A
from .. import types as T
from ..limits import MAX_EXTENDS_DEPTH

Report = Callable[[str, str, Location | None, str], None]  # (code, message, where, severity)


@dataclass(eq=False)
class VarSym:
    """A variable a name refers to."""

    decl: A.VarDecl
    storage: str  # "self" (member of the POU instance), "local", "global", "resource"
    owner: A.Pou | None = None
    read_only: bool = False  # VAR_EXTERNAL CONSTANT: a global this POU may read, not write

    @property
    def ty(self) -> T.Type:
        return self.decl.ty


@dataclass(eq=False)
class EnumSym:
    """An enumeration value a name refers to."""

    type: T.EnumType
    value: int
    member: str


@dataclass(eq=False)
class ProgSym:
    """A program instance a name refers to."""

    pou: A.Pou
    instance: str


@dataclass(frozen=True, eq=False)
class LocatedVar:
    """A variable declared with an AT address, where it lives and how to name it."""

    path: str  # as a user writes it: "g" (a global) or "Main.x" (a program instance's variable)
    address: str  # upper-case, e.g. "%IX0.1" ("%I*" for a wildcard)
    decl: A.VarDecl
    pou: A.Pou | None = None  # the program, None for a global
    instance: str | None = None  # the program instance's name, None for a global
    via: tuple[str, ...] = ()  # the block instances between the program and the variable
    resource: str | None = None  # a global of this resource (ADR 0037)

    @property
    def wildcard(self) -> bool:
        """``AT %I*``: the address is given later (by a configuration)."""
        return self.address.endswith("*")


class Scope:
    """The names visible in one POU (or TEST): its own declarations, then the globals.

    ``VAR_EXTERNAL x`` names the global ``x`` (a :class:`VarSym` with storage ``"global"``); a
    FUNCTION's own name is its result variable (section ``RETURN``)."""

    def __init__(self, names: dict[str, Any] | None = None,
                 globals_: dict[str, A.VarDecl] | None = None) -> None:
        self.names: dict[str, Any] = names if names is not None else {}
        self.globals: dict[str, A.VarDecl] = globals_ if globals_ is not None else {}

    def local(self, name: str) -> Any:
        """The symbol declared in this scope itself, or None."""
        return self.names.get(name)

    def lookup(self, name: str) -> Any:
        """The symbol ``name`` refers to here: a local one, else a global variable, else None."""
        sym = self.names.get(name)
        if sym is not None:
            return sym
        g = self.globals.get(name)
        return VarSym(g, "global", None) if g is not None else None

    def declare(self, name: str, sym: Any) -> None:
        self.names[name] = sym

    def __iter__(self) -> Iterator[str]:
        return iter(self.names)

    def __contains__(self, name: object) -> bool:
        return name in self.names


def close_hint(name: str, candidates) -> str:
    """``"; did you mean X?"`` for the candidate closest to ``name``, or ``""``."""
    close = suggest(name.upper(), [str(c).upper() for c in candidates], cutoff=0.7)
    return f"; did you mean {close[0]}?" if close else ""


def result_decl(p: A.Pou) -> A.VarDecl:
    """The variable named after a FUNCTION or METHOD that holds its result (section
    ``RETURN``; VOID without a return type), made on first use."""
    if p.return_decl is None:
        rd = A.VarDecl(p.loc, p.name, p.return_type or A.NamedTypeRef(p.loc, "VOID"),
                       section="RETURN", spelling=p.spelling)
        rd.used = True
        if p.return_type is None:
            rd.ty = T.VOID
        p.return_decl = rd
    return p.return_decl


def instance_label(instance: str, pou: A.Pou) -> str:
    """How a program instance is named in paths: the POU as written when the instance is the
    POU itself (no configuration), else the instance name."""
    return (pou.spelling or pou.name) if instance == pou.name else instance


@dataclass(eq=False)
class ConfigBinding:
    """A VAR_CONFIG line the checker resolved: which variable of which program instance it
    addresses, the address it completes and the initial value it gives."""

    path: str  # as a user writes it, e.g. "P1.fb1.sensor"
    instance: str  # the program instance
    via: tuple[str, ...]  # the member names between the instance and the variable
    decl: A.VarDecl
    address: str | None
    init: A.Expr | None


@dataclass(eq=False)
class AccessBinding:
    """A VAR_ACCESS name the checker resolved: the path (or direct address) it stands for."""

    name: str
    spelling: str
    target: str  # a variable path ("P1.x", "g.member") or a direct address ("%IX1.1")
    type: T.Type
    read_only: bool


@dataclass(eq=False)
class SymbolTable:
    """Every declaration of a project (see the module text)."""

    type_decls: dict[str, A.TypeDecl] = field(default_factory=dict)
    pous: dict[str, A.Pou] = field(default_factory=dict)
    globals: dict[str, A.VarDecl] = field(default_factory=dict)
    global_decls: list[A.VarDecl] = field(default_factory=list)  # all, duplicates included
    configs: list[A.Configuration] = field(default_factory=list)
    types: dict[str, T.Type] = field(default_factory=dict)  # resolved by the checker
    enum_members: dict[str, list[EnumSym]] = field(default_factory=dict)  # by the checker
    config_vars: list[A.ConfigVar] = field(default_factory=list)  # VAR_CONFIG lines, all files
    resources: set[str] = field(default_factory=set)  # the configurations' resource names
    config_bindings: list[ConfigBinding] = field(default_factory=list)  # by the checker
    access_paths: dict[str, AccessBinding] = field(default_factory=dict)  # by the checker
    # a PROGRAM's own VAR_ACCESS, by program (POU) name and access name (check.configvars)
    program_access: dict[str, dict[str, AccessBinding]] = field(default_factory=dict)
    # the VAR_GLOBAL of each resource of a configuration with two or more (ADR 0037), by
    # resource and name; their declarations are in global_decls too (for their types)
    resource_globals: dict[str, dict[str, A.VarDecl]] = field(default_factory=dict)
    # the VAR_EXTERNALs that name a resource's global, by POU: checked per resource
    resource_externals: dict[str, list[A.VarDecl]] = field(default_factory=dict)
    _scopes: dict[int, Scope] = field(default_factory=dict)
    _programs: list[tuple[str, A.Pou, str | None]] | None = None

    # -- building -----------------------------------------------------------------------------
    @classmethod
    def collect(cls, files: list[A.SourceFile], report: Report | None = None,
                with_globals: bool = True) -> SymbolTable:
        """The TYPEs, POUs and global variables of ``files`` (no body is looked at);
        ``report(code, message, where, severity)`` hears about names declared twice (the first
        declaration wins). The checker passes ``with_globals=False`` and enters the globals
        itself (:meth:`declare_global`) once the TYPEs are resolved, which must not see them."""
        say = report or (lambda *_: None)
        table = cls()
        for f in files:
            for td in f.types:
                table._declare("type", td.name, td.loc, table.type_decls, td, say)
            for p in f.pous:
                if p.name in table.type_decls:
                    say("PLC0101", f"{p.spelling or p.name} is declared twice (as a type and as "
                        "a POU); rename one of them", p.loc, "error")
                prev = table.pous.get(p.name)
                if prev is not None and prev.loc.file.startswith("<plclab>/"):
                    # a user POU may take the name of a library block: it hides that block
                    say("PLC0205", f"{p.spelling or p.name} hides the library block of the "
                        "same name; rename it to keep using the library one", p.loc, "warning")
                    table.pous[p.name] = p
                    continue
                table._declare("POU", p.name, p.loc, table.pous, p, say)
        table.configs = [c for f in files for c in f.configs]
        table.config_vars = [v for c in table.configs for v in c.config_vars] + [
            v for f in files for v in f.config_vars]
        table.resources = {r for c in table.configs for r in c.resources}
        table.global_decls = [d for f in files for g in f.globals for d in g.decls]
        table.global_decls += [d for c in table.configs for d in c.globals]
        for d in table.global_decls:
            d.section = "VAR_GLOBAL"
            if with_globals:
                table.declare_global(d, say)
        for c in table.configs:
            for r, decls in c.resource_globals.items():
                for d in decls:
                    d.section = "VAR_GLOBAL"
                table.global_decls += decls
                if with_globals:
                    table.declare_resource_globals(r, decls, say)
        return table

    def declare_resource_globals(self, resource: str, decls: list[A.VarDecl],
                                 report: Report | None = None) -> None:
        """Enter the VAR_GLOBAL of one resource (ADR 0037): a name twice in the resource, or
        also a global of the configuration, is reported (PLC0101); two resources may each have
        one of a name."""
        say = report or (lambda *_: None)
        own = self.resource_globals.setdefault(resource, {})
        for d in decls:
            g = self.globals.get(d.name)
            if g is not None:
                say("PLC0101", f"global variable {d.name} of resource {resource} is also a global "
                    f"of the configuration (at {g.loc}); rename one of them", d.loc, "error")
                continue
            self._declare("global variable", d.name, d.loc, own, d, say)

    def is_resource_global(self, d: A.VarDecl) -> bool:
        """Whether ``d`` is a VAR_GLOBAL of a resource (not of the configuration)."""
        return any(r.get(d.name) is d for r in self.resource_globals.values())

    @staticmethod
    def resource_of(instance: str) -> str | None:
        """The resource a program instance runs in, ``RESOURCEA.INSTANCE0`` -> ``RESOURCEA``
        (ADR 0037); None where its configuration has one resource or none."""
        head, dot, _ = instance.partition(".")
        return head.upper() if dot else None

    def declare_global(self, d: A.VarDecl, report: Report | None = None) -> None:
        """Enter global variable ``d``; a second one of the same name is reported, not entered."""
        self._declare("global variable", d.name, d.loc, self.globals, d,
                      report or (lambda *_: None))

    @staticmethod
    def _declare(what: str, name: str, loc: Location, table: dict, item: Any,
                 say: Report) -> None:
        if name in table:
            say("PLC0101", f"{what} {name} is declared twice (first at {table[name].loc}); "
                "rename or remove one", loc, "error")
            return
        table[name] = item

    # -- questions ----------------------------------------------------------------------------
    def pou(self, name: str) -> A.Pou | None:
        """The POU called ``name`` (upper-case), or None."""
        return self.pous.get(name)

    def bases(self, pou: A.Pou) -> list[A.Pou]:
        """The blocks ``pou`` inherits from (FUNCTION_BLOCK ... EXTENDS, ADR 0021), nearest
        first; an unknown base or a cycle ends the chain (:mod:`.oop` reports them). A chain
        longer than ``MAX_EXTENDS_DEPTH`` is cut one block beyond it (PLC0310 is reported):
        a chain of 1,500 blocks must not cost 1,500 squared."""
        key = (id(pou), len(self.pous))
        cache = self.__dict__.setdefault("_bases_cache", {})
        hit = cache.get(key)
        if hit is not None:
            return list(hit)
        out: list[A.Pou] = []
        seen = {id(pou)}  # identity, not equality: linear in the chain (issue 30)
        p = pou
        while p.kind == "FUNCTION_BLOCK" and p.extends and len(out) <= MAX_EXTENDS_DEPTH:
            b = self.pous.get(p.extends[0])
            if b is None or b.kind != "FUNCTION_BLOCK" or id(b) in seen:
                break
            out.append(b)
            seen.add(id(b))
            p = b
        cache[key] = tuple(out)
        return out

    def interfaces(self, p: A.Pou) -> list[A.Pou]:
        """Every INTERFACE ``p`` (a block or an interface) is, through IMPLEMENTS, EXTENDS of
        interfaces and its base blocks; ``p`` itself first when it is an interface."""
        out: list[A.Pou] = []
        todo = [p] if p.kind == "INTERFACE" else []
        for b in [p, *self.bases(p)] if p.kind == "FUNCTION_BLOCK" else []:
            todo += [i for n in b.implements if (i := self.pous.get(n)) is not None]
        while todo:
            i = todo.pop(0)
            if i.kind != "INTERFACE" or i in out:
                continue
            out.append(i)
            todo += [b for n in i.extends if (b := self.pous.get(n)) is not None]
        return out

    def members(self, owner: A.Pou | T.Type) -> dict[str, A.VarDecl]:
        """The declared members of a POU, a block or structure type, by name: inherited ones
        first (:meth:`bases`), then its own, in declaration order; the first of a name wins."""
        t = T.resolve(owner) if isinstance(owner, T.Type) else owner
        if isinstance(t, T.StructType):
            return dict(t.fields)
        pou = t.pou if isinstance(t, T.FBType) else t
        out: dict[str, A.VarDecl] = {}
        if not isinstance(pou, A.Pou):
            return out
        for p in [*reversed(self.bases(pou)), pou]:
            for d in p.decls:
                out.setdefault(d.name, d)
        return out

    def scope(self, pou: A.Pou) -> Scope:
        """The names visible inside ``pou`` (built on first use, from declarations only)."""
        sc = self._scopes.get(id(pou))
        if sc is None:
            sc = self._scopes[id(pou)] = self._build_scope(pou)
        return sc

    def _build_scope(self, p: A.Pou) -> Scope:
        if p.kind == "METHOD" and p.owner is not None:
            return self._method_scope(p, p.owner)
        names: dict[str, Any] = {}
        storage_local = p.kind == "FUNCTION"
        for d in [d for b in reversed(self.bases(p)) for d in b.decls] + p.decls:
            if d.section == "VAR_EXTERNAL":
                g = self.globals.get(d.name)
                if g is None and any(d.name in r for r in self.resource_globals.values()):
                    # a resource's global: which one depends on the resource the instance runs
                    # in (ADR 0037); typed by this declaration, checked per resource
                    if d.ty is None:
                        d.ty = next(r[d.name].ty for r in self.resource_globals.values()
                                    if d.name in r)
                    names[d.name] = VarSym(d, "resource", p, read_only=d.constant)
                    self.resource_externals.setdefault(p.name, []).append(d)
                    continue
                names[d.name] = VarSym(g if g is not None else d, "global", p,
                                       read_only=d.constant)
                continue
            st = "local" if (storage_local or d.section == "VAR_TEMP") else "self"
            names[d.name] = VarSym(d, st, p)
        if p.kind == "FUNCTION":
            names[p.name] = VarSym(result_decl(p), "local", p)
        if p.kind == "FUNCTION_BLOCK" or (p.kind == "PROGRAM" and p.methods):
            self._this_super(names, p)  # a PROGRAM's actions are called on THIS (ADR 0035)
        return Scope(names, self.globals)

    # -- object-oriented extensions (ADR 0021) ------------------------------------------------
    def _method_scope(self, m: A.Pou, owner: A.Pou) -> Scope:
        """A METHOD sees its block's variables (inherited ones included) as instance data,
        its VAR_INST as hidden instance variables ``METHOD__NAME`` of the block, its own
        parameters and locals, its result, ``THIS^`` and ``SUPER^``."""
        names: dict[str, Any] = dict(self.scope(owner).names)
        names = {k: v for k, v in names.items()
                 if not (isinstance(v, VarSym) and v.storage == "local")}
        owned = self.members(owner)
        for d in m.decls:
            if d.section == "VAR_INST":
                inst = owned.get(A.method_inst_name(owner.name, m.name, d.name))
                names[d.name] = VarSym(inst if inst is not None else d, "self", owner)
            else:
                names[d.name] = VarSym(d, "local", m)
        names[m.name] = VarSym(result_decl(m), "local", m)
        if m.name.endswith("__GET"):  # a PROPERTY's GET: its result has the property's name
            names[m.name[:-5]] = names[m.name]
        return Scope(names, self.globals)

    def _this_super(self, names: dict[str, Any], fb: A.Pou) -> None:
        """``THIS`` (the instance, as its own block type) and ``SUPER`` (as its base type; ANY
        without a base, which :mod:`.oop` reports)."""
        for name, storage, of in (("THIS", "this", fb), ("SUPER", "super",
                                                          (self.bases(fb) or [None])[0])):
            if name in names:  # a variable of that name hides it
                continue
            d = A.VarDecl(fb.loc, name, A.NamedTypeRef(fb.loc, of.name if of else "ANY"),
                          section="VAR", spelling=name)
            d.used = True
            d.ty = self.types.setdefault(of.name, T.FBType(of.name, of)) if of else T.ANY
            names[name] = VarSym(d, storage, fb)

    def set_programs(self, programs: list[tuple[str, A.Pou, str | None]]) -> None:
        """The program instances, as the checker validated them against the configuration."""
        self._programs = programs

    def programs(self) -> list[tuple[str, A.Pou, str | None]]:
        """``(instance, pou, task)`` of every program that runs: the configuration's instances
        (unknown programs left out), or every PROGRAM when there is no configuration."""
        if self._programs is not None:
            return self._programs
        if self.configs:
            return [x for c in self.configs for x in self.instances(c)]
        return [(p.name, p, None) for p in self.pous.values() if p.kind == "PROGRAM"]

    def instances(self, config: A.Configuration,
                  report: Report | None = None) -> list[tuple[str, A.Pou, str | None]]:
        """``(instance, pou, task)`` of the program instances of one configuration; an unknown
        program (left out) or task is reported (PLC0100)."""
        say = report or (lambda *_: None)
        out = []
        for inst in config.instances:
            # a task of the instance's own resource (ADR 0037: two may have tasks of one name)
            tnames = {t.name for t in config.tasks if t.resource == inst.resource}
            p = self.pous.get(inst.program)
            if p is None or p.kind != "PROGRAM":
                say("PLC0100", f"PROGRAM {inst.program} is not declared" + close_hint(
                    inst.program, [k for k, v in self.pous.items() if v.kind == "PROGRAM"]),
                    inst.loc, "error")
                continue
            if inst.task and inst.task not in tnames:
                say("PLC0100", f"task {inst.task} is not declared in the configuration" +
                    close_hint(inst.task, tnames), inst.loc, "error")
            # with two or more resources an instance is named RESOURCE.INSTANCE (ADR 0037)
            task = f"{inst.resource}.{inst.task}" if inst.resource and inst.task else inst.task
            out.append((inst.key, p, task))
        return out

    def programs_declaring(self, name: str) -> list[tuple[str, A.Pou]]:
        """``(instance, pou)`` of the program instances that declare a variable ``name``
        (upper-case)."""
        return [(inst, pou) for inst, pou, _ in self.programs() if name in self.members(pou)]

    def located_vars(self) -> list[LocatedVar]:
        """Every variable with an AT address: the globals, then each program instance's own
        variables (its VAR_EXTERNALs are the globals already listed), wildcards included."""
        out = [LocatedVar(d.spelling or d.name, d.address.upper(), d)
               for d in self.globals.values() if d.address]
        out += [LocatedVar(f"{r}.{d.spelling or d.name}", d.address.upper(), d, resource=r)
                for r, gs in self.resource_globals.items() for d in gs.values() if d.address]
        configured = {(b.instance, b.via, b.decl.name): b for b in self.config_bindings
                      if b.address}
        for inst, pou, _ in self.programs():
            label = instance_label(inst, pou)
            for d in self.members(pou).values():
                if d.address and d.section != "VAR_EXTERNAL":
                    b = configured.pop((inst, (), d.name), None)
                    address = b.address if b is not None else d.address.upper()
                    out.append(LocatedVar(f"{label}.{d.spelling or d.name}", address, d, pou,
                                          inst))
        programs = {inst: pou for inst, pou, _ in self.programs()}
        out += [LocatedVar(b.path, b.address, b.decl, programs.get(b.instance), b.instance,
                           b.via) for b in configured.values() if b.address]
        return out
