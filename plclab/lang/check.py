"""The checker: names, types, constants and the diagnostics that teach.

It annotates the AST in place (``expr.ty``, ``name.sym``, ``call.target``, ``call.bound``) and
returns a :class:`Project` that the compiler turns into Python. All errors of all files are
collected; :func:`check` raises one :class:`~plclab.errors.PlcError` carrying every diagnostic.
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass, field
from typing import Any

from ..errors import Diagnostic, Location, PlcError
from . import ast as A
from . import datasize
from . import types as T
from .builtins import BUILTINS, Builtin, conversion
from .datasize import DataSizes
from .limits import (
    MAX_BLOCK_NESTING,
    MAX_EXPR_NESTING,
    MAX_INTERVAL_NS,
    MIN_INTERVAL_NS,
    compiler_guard,
    nesting_violation,
    too_deep_message,
)

_INPUTISH = ("VAR_INPUT", "VAR_IN_OUT")
MAX_IMAGE_BYTES = 65536  # the largest process image a Plc may have (image_size)
_MAX_PRIORITY = 31  # task priorities 0..31 (CODESYS)
_REAL_MAX = 3.4028234663852886e38  # the largest finite IEEE single
_CHAIN_LIMIT = 64  # named types / constants defined through each other, at most this deep
_CONST_BITS = 128  # constant folding stops beyond this (no IEC integer has more than 64)
_ADDR_SIZES = {"X": 1, "B": 8, "W": 16, "D": 32, "L": 64}


# ---------------------------------------------------------------------------------------------
# Symbols


@dataclass(eq=False)
class VarSym:
    decl: A.VarDecl
    storage: str  # "self" (member of the POU instance), "local", "global"
    owner: A.Pou | None = None

    @property
    def ty(self) -> T.Type:
        return self.decl.ty


@dataclass(eq=False)
class EnumSym:
    type: T.EnumType
    value: int
    member: str


@dataclass(eq=False)
class ProgSym:
    pou: A.Pou
    instance: str


@dataclass(eq=False)
class CallInfo:
    """A checked call: what is called and how its parameters bind."""

    kind: str  # "builtin" "conv" "function" "fb" "program"
    callee: Any  # Builtin | (src, dst) | Pou
    inputs: list[tuple[Any, A.Expr]] = field(default_factory=list)  # (VarDecl|index, expr)
    outputs: list[tuple[Any, A.Expr, bool]] = field(default_factory=list)  # (VarDecl, target, neg)
    inouts: list[tuple[Any, A.Expr]] = field(default_factory=list)


@dataclass(eq=False)
class Project:
    files: list[A.SourceFile]
    types: dict[str, T.Type]
    pous: dict[str, A.Pou]
    globals: dict[str, A.VarDecl]
    programs: list[tuple[str, A.Pou, str | None]]  # (instance name, pou, task)
    tasks: list[A.TaskDecl]
    tests: list[A.TestBlock]
    diagnostics: list[Diagnostic]
    const_values: dict[int, Any] = field(default_factory=dict)  # id(VarDecl) -> value
    # the process image the addresses need: (bytes, the address that needs most, where)
    image_needed: tuple[int, str, Location] | None = None


class Checker:
    def __init__(self, files: list[A.SourceFile]) -> None:
        self.files = files
        self.diags: list[Diagnostic] = []
        self.types: dict[str, T.Type] = {}
        self.type_decls: dict[str, A.TypeDecl] = {}
        self.pous: dict[str, A.Pou] = {}
        self.globals: dict[str, A.VarDecl] = {}
        self.enum_members: dict[str, list[EnumSym]] = {}
        self.consts: dict[int, Any] = {}
        # what is being evaluated or resolved right now (constants, types, enumeration values):
        # meeting one of them again is a cycle (PLC0122)
        self._chain: list[tuple[Any, str, Location | None]] = []
        self._chain_keys: set[Any] = set()
        self._cycles_seen: set[frozenset] = set()
        self._too_deep = False
        self._const_memo: dict[int, Any] = {}  # id(VarDecl) -> folded value
        self._broken: set[int] = set()  # constants whose value has a reported error
        self._broken_hits = 0  # uses of such constants (their users need no second error)
        self._global_consts: dict[str, A.VarDecl] = {}  # visible to TYPEs before globals are
        self._enum_index: dict[str, str] = {}  # member name -> TYPE not yet resolved
        self._enum_pending: dict[int, tuple[A.Expr | None, EnumSym | None, Location]] = {}
        self.calls: dict[str, set[str]] = {}  # pou -> pous it calls (for recursion)
        self.image_needed: tuple[int, str, Location] | None = None  # (bytes, address, where)
        self.call_sites: dict[tuple[str, str], Location] = {}  # (caller, callee) -> 1st call
        self.pou: A.Pou | None = None
        self.scope: dict[str, Any] = {}
        self.in_test = False
        self.loop_depth = 0
        self.for_vars: list[A.VarDecl] = []
        self.stmt_loc: Location | None = None  # the statement being checked (for PLC0191)

    # -- reporting ----------------------------------------------------------------------------
    def err(self, code: str, msg: str, loc: Location | None) -> None:
        self.diags.append(Diagnostic(code, msg, loc))

    def warn(self, code: str, msg: str, loc: Location | None) -> None:
        self.diags.append(Diagnostic(code, msg, loc, "warning"))

    # -- cycles among constants, enumeration values and types ---------------------------------
    def _enter(self, key: Any, label: str, loc: Location | None) -> bool:
        """Start evaluating ``key``; False (and PLC0122 once) if it is already under way."""
        if key in self._chain_keys:
            i = next(k for k, (ck, _, _) in enumerate(self._chain) if ck == key)
            cyc = self._chain[i:]
            ident = frozenset(ck for ck, _, _ in cyc)
            if ident not in self._cycles_seen:
                self._cycles_seen.add(ident)
                names = " -> ".join([lab for _, lab, _ in cyc] + [label])
                structs = [ck[1] for ck, _, _ in cyc if isinstance(ck, tuple) and
                           isinstance(self.type_decls[ck[1]].type, A.StructTypeRef)]
                if structs:
                    self.err("PLC0123", f"structure {structs[0]} contains itself ({names}): it "
                             "would be infinitely large; remove the field that closes the "
                             "circle", cyc[0][2])
                else:
                    self.err("PLC0122", f"{names}: these are defined in terms of each other; "
                             "give one of them a value that does not depend on the others",
                             cyc[0][2])
            return False
        self._chain.append((key, label, loc))
        self._chain_keys.add(key)
        return True

    def _chain_too_deep(self, what: str, remedy: str, loc: Location | None) -> bool:
        """True when the definitions under way are :data:`_CHAIN_LIMIT` deep (PLC0124, once)."""
        if len(self._chain) < _CHAIN_LIMIT:
            return False
        if not self._too_deep:
            self._too_deep = True
            path = " -> ".join(lab for _, lab, _ in self._chain[:4])
            self.err("PLC0124", f"{what} are defined in terms of each other more than "
                     f"{_CHAIN_LIMIT} levels deep ({path} -> ...); {remedy}", loc)
        return True

    def _leave(self) -> None:
        key, _, _ = self._chain.pop()
        self._chain_keys.discard(key)

    # -- driver -------------------------------------------------------------------------------
    def run(self) -> Project:
        with compiler_guard():  # nesting recurses; the limits are checked (plclab.lang.limits)
            return self._run()

    def _run(self) -> Project:
        for f in self.files:
            for td in f.types:
                self._declare("type", td.name, td.loc, self.type_decls, td)
            for p in f.pous:
                if p.name in self.type_decls:
                    self.err("PLC0101", f"{p.spelling or p.name} is declared twice (as a type "
                             "and as a POU); rename one of them", p.loc)
                prev = self.pous.get(p.name)
                if prev is not None and prev.loc.file.startswith("<plclab>/"):
                    # a user POU may take the name of a library block: it hides that block
                    self.warn("PLC0205", f"{p.spelling or p.name} hides the library block of the "
                              "same name; rename it to keep using the library one", p.loc)
                    self.pous[p.name] = p
                    continue
                self._declare("POU", p.name, p.loc, self.pous, p)
        configs = [c for f in self.files for c in f.configs]
        gdecls = [d for f in self.files for g in f.globals for d in g.decls]
        gdecls += [d for c in configs for d in c.globals]
        for d in gdecls:  # global constants may size types declared before them
            if d.constant:
                self._global_consts.setdefault(d.name, d)
        for name, td in self.type_decls.items():
            if isinstance(td.type, A.EnumTypeRef):
                for mname, _, _ in td.type.members:
                    self._enum_index.setdefault(mname, name)
        for name in self.type_decls:
            self.named_type(name, self.type_decls[name].loc)
        for p in self.pous.values():
            if p.kind != "FUNCTION":
                self.types.setdefault(p.name, T.FBType(p.name, p))
        # globals
        for d in gdecls:
            d.section = "VAR_GLOBAL"
            self.decl_type(d)
            self._declare("global variable", d.name, d.loc, self.globals, d)
        for d in gdecls:
            self.check_init(d, {})
        for p in self.pous.values():
            self.check_pou_decls(p)
        for p in self.pous.values():
            self.check_pou_body(p)
        self.check_recursion()
        programs, tasks = self.configuration(configs)
        tests = [t for f in self.files for t in f.tests]
        for t in tests:
            self.check_test(t)
        self.check_data(programs, tests)
        return Project(self.files, self.types, self.pous, self.globals, programs, tasks, tests,
                       self.diags, self.consts, self.image_needed)

    def _declare(self, what: str, name: str, loc: Location, table: dict, item: Any) -> None:
        if name in table:
            prev = table[name]
            self.err("PLC0101", f"{what} {name} is declared twice (first at {prev.loc}); rename "
                     "or remove one", loc)
            return
        table[name] = item

    def configuration(self, configs: list[A.Configuration]):
        tasks: list[A.TaskDecl] = []
        programs: list[tuple[str, A.Pou, str | None]] = []
        if configs:
            for c in configs:
                tasks.extend(c.tasks)
                tnames = {t.name for t in c.tasks}
                for t in c.tasks:
                    self.check_task(t)
                for inst in c.instances:
                    p = self.pous.get(inst.program)
                    if p is None or p.kind != "PROGRAM":
                        self.err("PLC0100", f"PROGRAM {inst.program} is not declared" +
                                 self._suggest(inst.program, [k for k, v in self.pous.items()
                                                              if v.kind == "PROGRAM"]), inst.loc)
                        continue
                    if inst.task and inst.task not in tnames:
                        self.err("PLC0100", f"task {inst.task} is not declared in the "
                                 "configuration" + self._suggest(inst.task, tnames), inst.loc)
                    programs.append((inst.name, p, inst.task))
        else:
            for p in self.pous.values():
                if p.kind == "PROGRAM":
                    programs.append((p.name, p, None))
        return programs, tasks

    def check_task(self, t: A.TaskDecl) -> None:
        """INTERVAL a TIME constant > 0, PRIORITY an integer constant 0..31 (PLC0129); both are
        replaced by their folded literal, which is what the runtime reads."""
        if t.interval is not None:
            e = t.interval
            ty = T.resolve(self.expr(e, None))
            v = self.const_value(e) if ty.kind == "time" else None
            if ty.kind != "time" or not isinstance(v, int):
                self.err("PLC0129", f"the INTERVAL of task {t.name} must be a TIME constant, "
                         "e.g. INTERVAL := T#10ms", e.loc)
            elif ty is not T.LTIME and v % 1_000_000 and v < 1_000_000:
                self.err("PLC0129", f"the INTERVAL of task {t.name} is less than 1 ms, which a "
                         "TIME (whole milliseconds) cannot hold; write LTIME#500us or more than "
                         "T#1ms", e.loc)
            elif not MIN_INTERVAL_NS <= v <= MAX_INTERVAL_NS:
                self.err("PLC0129", f"the INTERVAL of task {t.name} is {v / 1e6:g} ms; it must "
                         "lie between 0.1 ms (LTIME#100us) and 1 day, e.g. INTERVAL := T#10ms",
                         e.loc)
            else:
                t.interval = A.Literal(e.loc, v if ty is T.LTIME else v // 1_000_000 * 1_000_000,
                                       "TIME", None, getattr(e, "text", ""))
                t.interval.ty = ty
        if t.priority is not None:
            e = t.priority
            ty = T.resolve(self.expr(e, None))
            v = self.const_value(e)
            if ty.kind != "int" or isinstance(v, bool) or not isinstance(v, int) or \
                    not 0 <= v <= _MAX_PRIORITY:
                self.err("PLC0129", f"the PRIORITY of task {t.name} must be an integer constant "
                         f"0..{_MAX_PRIORITY} (0 is the most urgent)", e.loc)
            else:
                t.priority = A.Literal(e.loc, v, "INT", None, str(v))
                t.priority.ty = ty

    # -- types --------------------------------------------------------------------------------
    def named_type(self, name: str, loc: Location) -> T.Type:
        t = T.lookup_elementary(name)
        if t is not None:
            return t
        if name in self.types:
            return self.types[name]
        if name in self.type_decls:
            td = self.type_decls[name]
            if self._chain_too_deep("types, constants and enumeration values",
                                    "declare them with fewer levels", loc):
                return T.ANY
            if not self._enter(("type", name), td.spelling or name, td.loc):
                return T.ANY
            try:
                ty = self.type_ref(td.type, td.name)
            finally:
                self._leave()
            if isinstance(ty, T.Elementary | T.StringType | T.ArrayType | T.Subrange | T.FBType):
                ty = T.AliasType(name, ty) if not isinstance(ty, T.Subrange) else ty
            self.types.setdefault(name, ty)
            return self.types[name]
        if name in self.pous and self.pous[name].kind != "FUNCTION":
            t2 = self.types.setdefault(name, T.FBType(name, self.pous[name]))
            return t2
        cands = list(T.ELEMENTARY) + list(self.type_decls) + [
            k for k, v in self.pous.items() if v.kind != "FUNCTION"] + ["STRING", "WSTRING"]
        self.err("PLC0102", f"unknown type {name}" + self._suggest(name, cands), loc)
        return T.ANY

    def type_ref(self, r: A.TypeRef, name: str | None = None) -> T.Type:
        if isinstance(r, A.NamedTypeRef):
            return self.named_type(r.name, r.loc)
        if isinstance(r, A.StringTypeRef):
            n = 80
            if r.length is not None:
                v = self.const_int(r.length)
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
                lo, hi = self.const_int(lo_e), self.const_int(hi_e)
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
            lo, hi = self.const_int(r.lo), self.const_int(r.hi)
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
                self.types.setdefault(name, et)  # its values may name each other
            syms: list[EnumSym] = []
            prev: EnumSym | None = None
            for mname, mval, mloc in r.members:
                if mname in et.members:
                    self.err("PLC0101", f"enumeration value {mname} appears twice", mloc)
                sym = EnumSym(et, 0, mname)
                et.members[mname] = 0
                self._enum_pending[id(sym)] = (mval, prev, mloc)
                self.enum_members.setdefault(mname, []).append(sym)
                syms.append(sym)
                prev = sym
            for sym in syms:  # in order: an implicit value is the one before plus 1
                self._enum_value(sym)
                et.members[sym.member] = sym.value
            return et
        if isinstance(r, A.StructTypeRef):
            st = T.StructType(name or f"struct@{r.loc.line}", {})
            for d in r.fields:
                self.decl_type(d)
                if d.name in st.fields:
                    self.err("PLC0101", f"field {d.name} appears twice in the structure", d.loc)
                st.fields[d.name] = d
            for d in r.fields:
                self.check_init(d, {})
            return st
        return T.ANY

    def decl_type(self, d: A.VarDecl) -> T.Type:
        if d.ty is None:
            d.ty = self.type_ref(d.type)
            if d.address:
                self.check_address(d)
        return d.ty

    def image_extent(self, addr: str, size_ch: str, byte_text: str, loc: Location) -> None:
        """Check that ``addr`` (split by :func:`_split_address`) lies inside the largest
        process image (PLC0127) and remember the largest extent:
        :class:`~plclab.runtime.plc.Plc` compares it with its ``image_size``."""
        byte = int(byte_text) if len(byte_text) <= 9 else MAX_IMAGE_BYTES
        end = byte + max(1, _ADDR_SIZES[size_ch] // 8)
        if end > MAX_IMAGE_BYTES:
            self.err("PLC0127", f"{addr[:30]} lies beyond the largest process image ({MAX_IMAGE_BYTES:,}"
                     " bytes, %..0 to %..65535); use a smaller address", loc)
        elif self.image_needed is None or end > self.image_needed[0]:
            self.image_needed = (end, addr, loc)

    def check_address(self, d: A.VarDecl) -> None:
        addr = d.address or ""
        if addr.endswith("*"):
            return
        size_ch, parts = _split_address(addr)
        bits = _ADDR_SIZES[size_ch]
        if size_ch == "X" and len(parts) != 2:
            self.err("PLC0120", f"bit address {addr} needs byte.bit, e.g. %IX0.3", d.loc)
            return
        if size_ch == "X" and (len(parts[1]) > 1 or int(parts[1]) > 7):
            self.err("PLC0120", f"bit number {parts[1][:12]} in {addr[:30]} is out of range 0..7",
                     d.loc)
            return
        if size_ch != "X" and len(parts) != 1:
            self.err("PLC0120", f"{addr}: only bit addresses (%IX, %QX, %MX) have a '.bit' part",
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

    def _enum_value(self, sym: EnumSym) -> int | None:
        """The value of an enumeration member, evaluated on first use (values may refer to
        constants and to other members; a circle among them is PLC0122)."""
        walked: list[EnumSym] = []  # implicit values, from ``sym`` back to an explicit one
        s: EnumSym | None = sym
        while s is not None and id(s) in self._enum_pending and \
                self._enum_pending[id(s)][0] is None:
            walked.append(s)
            s = self._enum_pending[id(s)][1]
        entered = 0
        try:
            for w in walked:
                if not self._enter(id(w), f"{w.type.name}.{w.member}",
                                   self._enum_pending[id(w)][2]):
                    return None
                entered += 1
            if s is None:
                base: int | None = -1
            elif id(s) not in self._enum_pending:
                base = s.value
            else:  # an explicit value still to evaluate
                expr, _, loc = self._enum_pending[id(s)]
                if not self._enter(id(s), f"{s.type.name}.{s.member}", loc):
                    return None
                try:
                    base = self.const_int(expr)
                finally:
                    self._leave()
                self._enum_pending.pop(id(s), None)
                s.value = base if base is not None else 0
                s.type.members[s.member] = s.value
        finally:
            for _ in range(entered):
                self._leave()
        if base is None:
            return None
        for k, w in enumerate(reversed(walked)):
            w.value = base + k + 1
            w.type.members[w.member] = w.value
            self._enum_pending.pop(id(w), None)
        return sym.value

    def _const_of(self, d: A.VarDecl, scope: dict[str, Any]) -> Any:
        """The folded value of constant ``d`` (evaluated once, in its own ``scope``)."""
        key = id(d)
        if key in self._const_memo:
            if key in self._broken:
                self._broken_hits += 1
            return self._const_memo[key]
        if self._chain_too_deep("constants", "give some of them literal values", d.loc):
            self._broken_hits += 1
            return None
        if not self._enter(key, d.spelling or d.name, d.loc):
            self._broken_hits += 1
            return None
        old, before = self.scope, (len(self.diags), self._broken_hits)
        self.scope = scope
        try:
            v = self.const_value(d.init) if d.init is not None else None
        finally:
            self.scope = old
            self._leave()
        if (len(self.diags), self._broken_hits) != before:
            self._broken.add(key)  # its error is reported: users of it need no second one
        self._const_memo[key] = v
        return v

    # -- constants ----------------------------------------------------------------------------
    def const_value(self, e: A.Expr) -> Any:
        """Evaluate a constant expression (literals, constants, arithmetic); None if not."""
        if isinstance(e, A.Literal):
            if e.kind == "ENUM":
                return None
            if e.kind == "TIME":
                return e.value
            return e.value
        if isinstance(e, A.Name):
            sym = self.scope.get(e.name)
            d, scope = None, self.scope
            if isinstance(sym, VarSym):
                d = sym.decl
                scope = {} if sym.storage == "global" else self.scope
            else:
                d, scope = self.globals.get(e.name) or self._global_consts.get(e.name), {}
            if d is not None and d.constant and d.init is not None:
                d.used = True
                return self._const_of(d, scope)
            if e.name not in self.enum_members and e.name in self._enum_index:
                tname = self._enum_index.pop(e.name)  # declared later: resolve it now
                self.named_type(tname, e.loc)
            if e.name in self.enum_members and len(self.enum_members[e.name]) == 1:
                return self._enum_value(self.enum_members[e.name][0])
            return None
        if isinstance(e, A.Unary):
            v = self.const_value(e.operand)
            if v is None:
                return None
            if e.op == "-":
                return -v
            if e.op == "NOT" and isinstance(v, bool):
                return not v
            return None
        if isinstance(e, A.Binary):
            a, b = self.const_value(e.left), self.const_value(e.right)
            if a is None or b is None or isinstance(a, str) or isinstance(b, str):
                return None
            try:
                match e.op:
                    case "+":
                        r = a + b
                    case "-":
                        r = a - b
                    case "*":
                        r = a * b
                    case "/":
                        if isinstance(a, int) and isinstance(b, int):
                            q = abs(a) // abs(b)
                            r = q if (a >= 0) == (b >= 0) else -q
                        else:
                            r = a / b
                    case "MOD":
                        r = a - b * (abs(a) // abs(b)) * (1 if (a >= 0) == (b >= 0) else -1) \
                            if isinstance(a, int) and isinstance(b, int) else math.fmod(a, b)
                    case _:
                        return None
            except (ZeroDivisionError, ValueError):
                self.err("PLC2001", "division by zero in a constant expression", e.loc)
                return None
            except OverflowError:
                r = math.inf
            return self._bounded(r, e)
        return None

    def _bounded(self, v: Any, e: A.Expr) -> Any:
        """A folded value no IEC type can hold (integers beyond 128 bits, floats beyond LREAL)
        is PLC0125, so that folding never builds huge numbers."""
        if isinstance(v, bool):
            return v
        if isinstance(v, int) and v.bit_length() > _CONST_BITS:
            self.err("PLC0125", f"this constant expression is larger than any integer type "
                     f"(more than {_CONST_BITS} bits); use smaller values", e.loc)
            return None
        if isinstance(v, float) and not math.isfinite(v):
            self.err("PLC0125", "this constant expression overflows LREAL (beyond "
                     "1.8E308); use smaller values", e.loc)
            return None
        return v

    def const_int(self, e: A.Expr) -> int | None:
        before = (len(self.diags), self._broken_hits)
        v = self.const_value(e)
        if (len(self.diags), self._broken_hits) != before:  # explained (a cycle, an overflow)
            return v if isinstance(v, int) and not isinstance(v, bool) else None
        if isinstance(v, bool) or not isinstance(v, int):
            self.err("PLC0109", "a constant integer expression is needed here (a literal or a "
                     "VAR CONSTANT)", e.loc)
            return None
        return v

    # -- POUs ---------------------------------------------------------------------------------
    def pou_scope(self, p: A.Pou) -> dict[str, Any]:
        scope: dict[str, Any] = {}
        storage_local = p.kind == "FUNCTION"
        for d in p.decls:
            if d.section == "VAR_EXTERNAL":
                g = self.globals.get(d.name)
                if g is None:
                    self.err("PLC0100", f"VAR_EXTERNAL {d.name} has no matching VAR_GLOBAL"
                             + self._suggest(d.name, self.globals), d.loc)
                    scope[d.name] = VarSym(d, "global", p)
                else:
                    if d.ty is not None and not T.same_type(d.ty, g.ty) and g.ty is not T.ANY:
                        self.err("PLC0103", f"VAR_EXTERNAL {d.name} is {d.ty} but the global is "
                                 f"{g.ty}", d.loc)
                    g.used = True
                    scope[d.name] = VarSym(g, "global", p)
                continue
            st = "local" if (storage_local or d.section == "VAR_TEMP") else "self"
            scope[d.name] = VarSym(d, st, p)
        if p.kind == "FUNCTION":
            rt = self.type_ref(p.return_type) if p.return_type else T.VOID
            rd = A.VarDecl(p.loc, p.name, p.return_type or A.NamedTypeRef(p.loc, "VOID"),
                           section="RETURN", spelling=p.spelling)
            rd.ty = rt
            rd.used = True
            scope[p.name] = VarSym(rd, "local", p)
            p.return_decl = rd  # type: ignore[attr-defined]
        return scope

    def check_pou_decls(self, p: A.Pou) -> None:
        seen: dict[str, A.VarDecl] = {}
        # constants of the POU may size its arrays: make them visible while types resolve
        self.scope = {d.name: VarSym(d, "self", p) for d in p.decls if d.constant}
        for d in p.decls:
            if d.name in seen:
                self.err("PLC0101", f"variable {d.name} is declared twice in {p.name} (first at "
                         f"line {seen[d.name].loc.line}); rename or remove one", d.loc)
            seen[d.name] = d
            if d.section == "VAR_EXTERNAL" and isinstance(d.type, A.NamedTypeRef) and \
                    d.type.name == "__ANY__":
                continue
            self.decl_type(d)
            if d.name == p.name and p.kind == "FUNCTION":
                self.err("PLC0101", f"{d.name} is the function's own name (its result); choose "
                         "another variable name", d.loc)
            if d.address and p.kind != "PROGRAM" and not d.address.endswith("*"):
                self.err("PLC0120", f"{d.name}: located variables (AT {d.address}) belong in a "
                         "PROGRAM or VAR_GLOBAL, not in a function or function block", d.loc)
            if d.constant and d.init is None:
                self.err("PLC0109", f"constant {d.name} needs a value: {d.name} : "
                         f"{d.ty} := ...;", d.loc)
        p.scope = self.pou_scope(p)  # type: ignore[attr-defined]
        self.scope = p.scope  # type: ignore[attr-defined]
        for d in p.decls:
            if d.section != "VAR_EXTERNAL":
                self.check_init(d, p.scope)  # type: ignore[attr-defined]
        self.scope = {}

    def check_init(self, d: A.VarDecl, scope: dict) -> None:
        if d.init is None:
            return
        old = self.scope
        self.scope = scope
        self.init_value(d.init, d.ty, d.loc)
        if d.constant:
            self.consts[id(d)] = self._const_of(d, scope)
        self.scope = old

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
                    n = self.const_int(rep) or 0
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
            fields = ty.fields if isinstance(ty, T.StructType) else {
                d.name: d for d in ty.pou.decls}
            for fname, fval, floc in e.fields:
                fd = fields.get(fname)
                if fd is None:
                    self.err("PLC0116", f"{ty.name} has no member {fname}" +
                             self._suggest(fname, fields), floc)
                    continue
                self.init_value(fval, fd.ty, floc)
            e.ty = ty
            return
        t = self.expr(e, ty)
        self.check_assignable(t, ty, e, e.loc)

    def check_pou_body(self, p: A.Pou) -> None:
        self.pou = p
        self.scope = p.scope  # type: ignore[attr-defined]
        self.calls.setdefault(p.name, set())
        self.checked_body(p.body, p.loc)
        self.check_labels(p.body)
        if p.kind == "FUNCTION" and p.native is None and p.return_type is not None:
            assigned = any(
                isinstance(s, A.Assign) and isinstance(s.target, A.Name) and s.target.name == p.name
                for s in A.walk_stmts(p.body)
            )
            if not assigned:
                self.warn("PLC0119", f"function {p.spelling or p.name} never assigns its result; "
                          f"add  {p.spelling or p.name} := ...;  (it returns the default value)",
                          p.loc)
        if p.native is None:
            for d in p.decls:
                if d.section in ("VAR", "VAR_TEMP") and not d.used and not d.address:
                    self.warn("PLC0200", f"variable {d.spelling or d.name} is declared but never "
                              "used; remove it or use it", d.loc)
        self.pou = None
        self.scope = {}

    def check_labels(self, body: list[A.Stmt]) -> None:
        """Jumps and labels (IL): labels unique, targets known, both at the top of the body."""
        labels: dict[str, A.Label] = {}
        for s in body:
            if isinstance(s, A.Label):
                if s.name in labels:
                    self.err("PLC0101", f"label {s.name} is defined twice (first at line "
                             f"{labels[s.name].loc.line}); rename one of them", s.loc)
                labels.setdefault(s.name, s)
        top = {id(s) for s in body}
        for s in A.walk_stmts(body):
            if isinstance(s, A.Label | A.Jump) and id(s) not in top:
                self.err("PLC0145", "jumps and labels must be at the top level of the body, "
                         "not inside IF, CASE or a loop", s.loc)
            elif isinstance(s, A.Jump) and s.label not in labels:
                self.err("PLC0145", f"jump to unknown label {s.label}" +
                         (self._suggest(s.label, labels) or
                          (f" (labels: {', '.join(labels)})" if labels else
                           "; define it with  " + s.label + ":  at the start of a line")), s.loc)

    def check_test(self, t: A.TestBlock) -> None:
        self.in_test = True
        scope: dict[str, Any] = {}
        for d in t.decls:
            self.decl_type(d)
            if d.name in scope:
                self.err("PLC0101", f"variable {d.name} is declared twice in the test", d.loc)
            scope[d.name] = VarSym(d, "local", None)
        self.scope = scope
        for d in t.decls:
            self.check_init(d, scope)
        self.checked_body(t.body, t.loc)
        self.scope = {}
        self.in_test = False

    def check_recursion(self) -> None:
        """PLC0110 at the call that closes each circle of calls, naming it (F -> G -> F).
        Iterative depth-first walk: long call chains are fine."""
        state: dict[str, int] = {}
        for root in list(self.calls):
            if root in state:
                continue
            state[root] = 1
            path = [root]
            stack = [iter(sorted(self.calls.get(root, ())))]
            while stack:
                m = next(stack[-1], None)
                if m is None:
                    stack.pop()
                    state[path.pop()] = 2
                    continue
                if state.get(m) == 1:
                    n = path[-1]
                    cyc = path[path.index(m):] + [m]
                    names = [self.pous[x].spelling or x for x in cyc]
                    if len(names) > 9:
                        names = names[:4] + [f"({len(names) - 8} more)"] + names[-4:]
                    where = self.call_sites.get((n, m), self.pous[m].loc)
                    self.err("PLC0110", "recursion is not allowed in IEC 61131-3 (a PLC has no "
                             f"dynamic stack): {' -> '.join(names)}; this call closes the "
                             "circle: rewrite it as a loop", where)
                elif m not in state:
                    state[m] = 1
                    path.append(m)
                    stack.append(iter(sorted(self.calls.get(m, ()))))

    # -- data: containment cycles, nesting, size ----------------------------------------------
    def check_data(self, programs: list, tests: list[A.TestBlock]) -> None:
        """Blocks and structures must not contain themselves; every POU's and TEST's data and
        the program's whole data must stay within :data:`datasize.DATA_LIMIT` bytes and
        :data:`datasize.NESTING_LIMIT` levels (PLC0123, PLC0124)."""
        ds = DataSizes()
        for p in self.pous.values():
            if p.kind != "FUNCTION":
                ds.ensure(p)
        for t in list(self.types.values()):
            if isinstance(T.resolve(t), T.StructType):
                ds.ensure(T.resolve(t))
        seen: set[frozenset] = set()
        for closing, text, ring in ds.cycles:
            key = frozenset(id(c) for c in ring)
            if key not in seen:
                seen.add(key)
                self.err("PLC0123", f"{text}: {datasize.container_name(ring[0])} contains an "
                         "instance of itself, which would be infinitely large; remove "
                         f"{closing.spelling or closing.name} or pass the block as VAR_IN_OUT",
                         closing.loc)
        if seen:
            return  # sizes are meaningless until the circle is gone
        scopes: list[tuple[str, list[A.VarDecl], Location]] = [
            (f"{p.kind} {p.spelling or p.name}", datasize.members(p), p.loc)
            for p in self.pous.values() if not p.loc.file.startswith("<plclab>/")]
        scopes += [(f"TEST '{t.title}'", t.decls, t.loc) for t in tests]
        for what, decls, loc in scopes:
            if self._data_fits(ds, what, decls, loc, None):
                continue
            return
        top = list(self.globals.values())
        total, depth, _ = ds.decls_cost(top)
        big, big_bytes, owner = None, -1, None
        for d in top:
            b, _ = ds.type_cost(d.ty)
            if b > big_bytes:
                big, big_bytes, owner = d, b, None
        for inst, p, _ in programs:
            b, dep = ds.type_cost(self.types.get(p.name))
            total += b
            if b > big_bytes:
                big, big_bytes, owner = ds.biggest.get(id(p)), b, inst
        if total > datasize.DATA_LIMIT and big is not None:
            self.err("PLC0124", f"the program's data takes {total:,} bytes, more than the limit "
                     f"of {datasize.DATA_LIMIT:,} (16 MiB); the largest part: "
                     f"{ds.chain(big, owner)}. Use smaller arrays", big.loc)

    def _data_fits(self, ds: DataSizes, what: str, decls: list[A.VarDecl], loc: Location,
                   owner: str | None) -> bool:
        size, depth, big = ds.decls_cost(decls)
        if big is None:
            return True
        name = what.split(" ", 1)[1].strip("'")
        if depth > datasize.NESTING_LIMIT:
            self.err("PLC0124", f"the data of {what} nests {depth} levels deep (arrays, "
                     f"structures and instances inside each other; the limit is "
                     f"{datasize.NESTING_LIMIT}): {ds.chain(big, name)}", big.loc)
            return False
        if size > datasize.DATA_LIMIT:
            self.err("PLC0124", f"the data of {what} takes {size:,} bytes, more than the limit "
                     f"of {datasize.DATA_LIMIT:,} (16 MiB): {ds.chain(big, name)}; use smaller "
                     "arrays", big.loc)
            return False
        return True

    # -- statements ---------------------------------------------------------------------------
    def checked_body(self, stmts: list[A.Stmt], loc: Location) -> None:
        """Check a POU or TEST body whose nesting is within the limits (else PLC0190: the
        checker and the compiler recurse once per nesting level)."""
        bad = nesting_violation(stmts)
        if bad is not None:
            what, where = bad
            limit = MAX_BLOCK_NESTING if what == "blocks" else MAX_EXPR_NESTING
            self.err("PLC0190", too_deep_message(what, limit), where or loc)
            return
        self.stmt_loc = loc
        try:
            self.body(stmts)
        except RecursionError:  # a safety net: the limits above should prevent it
            self.loop_depth = 0
            self.err("PLC0191", "this part of the program is too large or too deeply nested to "
                     "check; split it into smaller parts (FUNCTIONs, intermediate variables)",
                     self.stmt_loc)

    def body(self, stmts: list[A.Stmt]) -> None:
        returned = None
        for s in stmts:
            if isinstance(s, A.Label):  # a jump may land here: reachable again
                returned = None
            if returned is not None and not isinstance(s, A.Empty):
                self.warn("PLC0201", "this code is never executed: it follows a RETURN at line "
                          f"{returned.loc.line}; remove it or make the RETURN conditional", s.loc)
                returned = None
            self.stmt(s)
            if isinstance(s, A.Return | A.Exit | A.Continue):
                returned = s

    def stmt(self, s: A.Stmt) -> None:
        self.stmt_loc = s.loc
        if isinstance(s, A.Assign):
            tt = self.lvalue(s.target)
            vt = self.expr(s.value, tt)
            if s.op == ":=":
                self.check_assignable(vt, tt, s.value, s.loc)
            else:
                self.cond_type(vt, s.value, "a set/reset coil")
        elif isinstance(s, A.CallStmt):
            self.call(s.call, statement=True)
        elif isinstance(s, A.If):
            for cond, body in s.branches:
                self.cond_type(self.expr(cond, T.BOOL), cond, "IF")
                self.body(body)
            if s.orelse is not None:
                self.body(s.orelse)
        elif isinstance(s, A.Case):
            self.case(s)
        elif isinstance(s, A.For):
            self.for_stmt(s)
        elif isinstance(s, A.While):
            self.cond_type(self.expr(s.cond, T.BOOL), s.cond, "WHILE")
            self.loop_body(s.body)
        elif isinstance(s, A.Repeat):
            self.loop_body(s.body)
            self.cond_type(self.expr(s.cond, T.BOOL), s.cond, "UNTIL")
        elif isinstance(s, A.Exit | A.Continue):
            if self.loop_depth == 0:
                kw = "EXIT" if isinstance(s, A.Exit) else "CONTINUE"
                self.err("PLC0114", f"{kw} is only allowed inside FOR, WHILE or REPEAT", s.loc)
        elif isinstance(s, A.Jump):
            if s.cond is not None:
                self.cond_type(self.expr(s.cond, T.BOOL), s.cond, "jump")

    def loop_body(self, body: list[A.Stmt]) -> None:
        self.loop_depth += 1
        self.body(body)
        self.loop_depth -= 1

    def cond_type(self, t: T.Type, e: A.Expr, where: str) -> None:
        t = T.resolve(t)
        if t is not T.BOOL and t is not T.ANY:
            hint = ""
            if isinstance(e, A.Binary) and e.op in ("AND", "OR") or t.kind in ("int", "bits"):
                hint = " (compare it, e.g. x <> 0, or check the operator precedence: AND/OR " \
                       "bind weaker than comparisons)"
            self.err("PLC0108", f"the {where} condition must be BOOL, not {t}{hint}", e.loc)

    def case(self, s: A.Case) -> None:
        st = T.resolve(self.expr(s.selector, None))
        if st is not T.ANY and st.kind not in ("int", "bits", "enum"):
            self.err("PLC0115", f"CASE needs an integer or enumeration selector, not {st}",
                     s.selector.loc)
        seen: dict[Any, Location] = {}
        for b in s.branches:
            for lab in b.labels:
                los = [lab] if not isinstance(lab, tuple) else list(lab)
                vals = []
                for le in los:
                    lt = self.expr(le, st)
                    v = self.label_value(le)
                    if v is None:
                        self.err("PLC0115", "a CASE label must be a constant (a literal, a "
                                 "constant or an enumeration value)", le.loc)
                    elif not T.can_widen(lt, st) and T.common_type(lt, st) is None:
                        self.err("PLC0115", f"CASE label of type {lt} does not match the "
                                 f"selector type {st}", le.loc)
                    vals.append(v)
                if None in vals:
                    continue
                keys = [vals[0]] if len(vals) == 1 else [("range", vals[0], vals[1])]
                for k in keys:
                    if k in seen:
                        self.err("PLC0115", f"CASE label {k} appears twice (first at line "
                                 f"{seen[k].line})", b.loc)
                    seen[k] = b.loc
            self.body(b.body)
        if s.orelse is not None:
            self.body(s.orelse)

    def label_value(self, e: A.Expr) -> Any:
        if isinstance(e, A.Literal) and e.kind == "ENUM":
            return getattr(e, "enum_value", None)
        if isinstance(e, A.Name) and isinstance(e.sym, EnumSym):
            return e.sym.value
        return self.const_value(e)

    def for_stmt(self, s: A.For) -> None:
        vt = self.lvalue(s.var)
        sym = s.var.sym
        if T.resolve(vt).kind not in ("int", "any"):
            self.err("PLC0113", f"the FOR variable must be an integer, not {vt}", s.var.loc)
        for e in (s.start, s.end) + ((s.step,) if s.step else ()):
            et = self.expr(e, vt)
            if T.resolve(et).kind not in ("int", "any"):
                self.err("PLC0113", f"FOR bounds and step must be integers, not {et}", e.loc)
        if s.step is not None:
            v = self.const_value(s.step)
            if v == 0:
                self.err("PLC0113", "FOR step BY 0 never ends; use a step other than 0",
                         s.step.loc)
        if isinstance(sym, VarSym):
            for inner in A.walk_stmts(s.body):
                if isinstance(inner, A.Assign) and isinstance(inner.target, A.Name) and \
                        inner.target.name == s.var.name:
                    self.err("PLC0113", f"do not assign the FOR variable {s.var.name} inside the "
                             "loop; use a WHILE loop or EXIT instead", inner.loc)
        self.loop_body(s.body)

    # -- assignability ------------------------------------------------------------------------
    def check_assignable(self, src: T.Type, dst: T.Type, e: A.Expr, loc: Location) -> None:
        if src is T.ANY or dst is T.ANY:
            return
        rs, rd = T.resolve(src), T.resolve(dst)
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
        hint = ""
        if rs.kind in ("int", "real", "bits", "time", "bool") and rd.kind in (
            "int", "real", "bits", "time", "bool"
        ):
            sn, dn = T.base_of(T.concrete(rs)).name, T.base_of(rd).name
            hint = f"; convert explicitly with {sn}_TO_{dn}(...)"
        self.err("PLC0118" if hint else "PLC0103",
                 f"cannot assign {T.concrete(rs)} to {rd} without a conversion{hint}", loc)

    # -- expressions --------------------------------------------------------------------------
    def lookup(self, name: str) -> Any:
        sym = self.scope.get(name)
        if sym is not None:
            return sym
        g = self.globals.get(name)
        if g is not None:
            return VarSym(g, "global", None)
        return None

    def lvalue(self, e: A.Expr) -> T.Type:
        t = self.expr(e, None, write=True)
        e.is_target = True  # type: ignore[attr-defined]  # never moved into a temporary
        if isinstance(e, A.Member) and e.field_name.startswith("%"):
            e.obj.is_target = True  # type: ignore[attr-defined]  # x.3 := ... assigns x
        root = e
        while isinstance(root, A.Member | A.Index):
            root = root.obj
        if isinstance(e, A.Name):
            sym = e.sym
            if isinstance(sym, VarSym):
                d = sym.decl
                if d.constant:
                    self.err("PLC0105", f"{d.spelling or d.name} is a constant and cannot be "
                             "changed", e.loc)
                elif d.address and d.address.startswith("%I"):
                    self.err("PLC0105", f"{d.spelling or d.name} is a physical input ({d.address}); "
                             "a program can read an input but not write it", e.loc)
                elif d.section == "VAR_INPUT" and self.pou is not None and \
                        self.pou.kind == "FUNCTION_BLOCK":
                    self.warn("PLC0203", f"{d.name} is an input of {self.pou.name}: the caller "
                              "overwrites it on every call; copy it to a local variable", e.loc)
            elif isinstance(sym, EnumSym):
                self.err("PLC0105", f"{e.name} is an enumeration value, not a variable", e.loc)
            elif isinstance(sym, ProgSym):
                self.err("PLC0105", f"{e.name} is a program; assign its variables instead",
                         e.loc)
        elif isinstance(e, A.DirectAddr):
            if e.address.startswith("%I"):
                self.err("PLC0105", f"{e.address} is a physical input; a program cannot write it",
                         e.loc)
        elif not isinstance(e, A.Name | A.Member | A.Index):
            self.err("PLC0105", "the left side of ':=' must be a variable, an element or a "
                     "member", e.loc)
        return t

    def expr(self, e: A.Expr, expected: T.Type | None, write: bool = False) -> T.Type:
        t = self._expr(e, expected, write)
        e.ty = t
        return t

    def _expr(self, e: A.Expr, expected: T.Type | None, write: bool) -> T.Type:
        if isinstance(e, A.Literal):
            return self.literal(e, expected)
        if isinstance(e, A.Name):
            return self.name(e, expected)
        if isinstance(e, A.DirectAddr):
            return self.direct(e)
        if isinstance(e, A.Member):
            return self.member(e, write)
        if isinstance(e, A.Index):
            return self.index(e)
        if isinstance(e, A.Unary):
            return self.unary(e, expected)
        if isinstance(e, A.Binary):
            return self.binary(e, expected)
        if isinstance(e, A.Call):
            return self.call(e, statement=False)
        if isinstance(e, A.ArrayInit | A.StructInit):
            self.err("PLC0103", "an aggregate initial value is only allowed in a declaration",
                     e.loc)
            return T.ANY
        return T.ANY

    def literal(self, e: A.Literal, expected: T.Type | None) -> T.Type:
        k = e.kind
        if k == "BOOL":
            return T.BOOL
        if k in ("INT", "REAL") and e.prefix:
            t = self.named_type(e.prefix, e.loc)
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
            e.tyname = t.name  # type: ignore[attr-defined]
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
            t = T.resolve(self.named_type(tname, e.loc))
            if isinstance(t, T.EnumType):
                if member not in t.members:
                    self.err("PLC0116", f"{tname} has no value {member}" +
                             self._suggest(member, t.members), e.loc)
                    return T.ANY
                e.enum_value = t.members[member]  # type: ignore[attr-defined]
                return t
            if t is not T.ANY:
                self.err("PLC0102", f"{tname} is not an enumeration type", e.loc)
            return T.ANY
        return T.ANY

    def name(self, e: A.Name, expected: T.Type | None) -> T.Type:
        sym = self.lookup(e.name)
        if sym is not None:
            e.sym = sym
            sym.decl.used = True
            return sym.decl.ty if sym.decl.ty is not None else T.ANY
        members = self.enum_members.get(e.name)
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
        p = self.pous.get(e.name)
        if p is not None and p.kind == "PROGRAM":
            e.sym = ProgSym(p, p.name)
            return self.types[p.name]
        if p is not None and p.kind == "FUNCTION_BLOCK":
            self.err("PLC0100", f"{e.name} is a function block type; declare an instance "
                     f"(inst : {e.name};) and use the instance", e.loc)
            return T.ANY
        cands = list(self.scope) + list(self.globals) + list(self.enum_members)
        self.err("PLC0100", f"{e.text or e.name} is not declared" + self._suggest(e.name, cands) +
                 ("" if self._suggest(e.name, cands) else "; declare it in a VAR section"),
                 e.loc)
        # declare it to avoid repeated errors
        d = A.VarDecl(e.loc, e.name, A.NamedTypeRef(e.loc, "ANY"))
        d.ty = T.ANY
        d.used = True
        sym2 = VarSym(d, "local", None)
        self.scope[e.name] = sym2
        e.sym = sym2
        return T.ANY

    def direct(self, e: A.DirectAddr) -> T.Type:
        a = e.address
        size, parts = _split_address(a)
        if size == "X" and (len(parts) != 2 or len(parts[1]) > 1 or int(parts[1]) > 7):
            self.err("PLC0120", f"bit address {a[:30]} needs byte.bit with bit 0..7, e.g. %IX0.3",
                     e.loc)
        elif size != "X" and len(parts) != 1:
            self.err("PLC0120", f"{a[:30]}: only bit addresses (%IX, %QX, %MX) have a '.bit' part",
                     e.loc)
        else:
            self.image_extent(a, size, parts[0], e.loc)
        return {"X": T.BOOL, "B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}[size]

    def member(self, e: A.Member, write: bool) -> T.Type:
        ot = T.resolve(self.expr(e.obj, None))
        f = e.field_name
        if ot is T.ANY:
            return T.ANY
        if f.startswith("%"):
            bit = int(f[1:])
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
                         self._suggest(f, ot.fields), e.loc)
                return T.ANY
            return d.ty
        if isinstance(ot, T.FBType):
            pou = ot.pou
            d = next((d for d in pou.decls if d.name == f), None)
            if d is None:
                names = [d.name for d in pou.decls]
                self.err("PLC0116", f"{pou.kind.replace('_', ' ').lower()} {pou.name} has no "
                         f"member {f}" + self._suggest(f, names), e.loc)
                return T.ANY
            e.sym = d
            if pou.kind == "FUNCTION_BLOCK" and not self.in_test:
                if d.section in ("VAR", "VAR_TEMP"):
                    self.err("PLC0121", f"{f} is internal to {pou.name}; only its inputs and "
                             "outputs are visible outside", e.loc)
                elif write and d.section == "VAR_OUTPUT":
                    self.err("PLC0105", f"{f} is an output of {pou.name}; only the block itself "
                             "writes it", e.loc)
            return d.ty
        self.err("PLC0116", f"{ot} has no members; '.{f}' needs a structure or a function block "
                 "instance", e.loc)
        return T.ANY

    def index(self, e: A.Index) -> T.Type:
        ot = T.resolve(self.expr(e.obj, None))
        for ix in e.indices:
            it = T.resolve(self.expr(ix, T.DINT))
            if it is not T.ANY and it.kind not in ("int", "enum") and it is not T.ANY_INT_LIT:
                self.err("PLC0117", f"an array index must be an integer, not {it}", ix.loc)
        if ot is T.ANY:
            return T.ANY
        if isinstance(ot, T.StringType):
            self.err("PLC0117", "strings are not indexed with [...]; use MID(s, 1, position)",
                     e.loc)
            return T.ANY
        if not isinstance(ot, T.ArrayType):
            self.err("PLC0117", f"{ot} is not an array and cannot be indexed", e.loc)
            return T.ANY
        if len(e.indices) != len(ot.dims):
            self.err("PLC0117", f"{ot} has {len(ot.dims)} dimension(s) but {len(e.indices)} "
                     "index(es) were given", e.loc)
            return ot.elem
        for ix, (lo, hi) in zip(e.indices, ot.dims, strict=True):
            v = self.const_value(ix) if isinstance(ix, A.Literal | A.Unary) else None
            if isinstance(v, int) and not lo <= v <= hi:
                self.err("PLC0112", f"index {v} is outside the array bounds {lo}..{hi}", ix.loc)
        return ot.elem

    def unary(self, e: A.Unary, expected: T.Type | None) -> T.Type:
        t = self.expr(e.operand, expected)
        rt = T.base_of(t)
        if rt is T.ANY:
            return T.ANY
        if e.op == "NOT":
            if rt is T.BOOL or rt.kind == "bits" or rt.kind == "int":
                return t
            self.err("PLC0104", f"NOT needs BOOL or a bit string, not {t}", e.loc)
            return T.ANY
        if rt.kind in ("int", "real", "time"):
            if isinstance(rt, T.Elementary) and rt.kind == "int" and not rt.signed:
                self.warn("PLC0204", f"negating an unsigned {rt.name} wraps around", e.loc)
            return t
        self.err("PLC0104", f"unary '-' needs a number or a TIME, not {t}", e.loc)
        return T.ANY

    def binary(self, e: A.Binary, expected: T.Type | None) -> T.Type:
        """A chain ``a + b + c + ...`` is a left-deep tree: walk its left spine with a loop
        (expected types flow down, result types up), so its length costs no recursion."""
        spine = [(e, expected)]
        while isinstance(spine[-1][0].left, A.Binary):
            node, exp = spine[-1]
            spine.append((node.left, _left_expected(node, exp)))
        bottom, exp = spine[-1]
        lt = self.expr(bottom.left, _left_expected(bottom, exp))
        for node, exp in reversed(spine):
            lt = self.binary_node(node, exp, lt)
            node.ty = lt
        return lt

    def binary_node(self, e: A.Binary, expected: T.Type | None, lt: T.Type) -> T.Type:
        """The type of ``e`` whose left operand (of type ``lt``) is checked already."""
        op = e.op
        if op in ("AND", "OR", "XOR"):
            rt = self.expr(e.right, lt if lt not in (T.ANY_INT_LIT,) else expected)
        else:
            sub_exp = expected if op in ("+", "-", "*", "/", "MOD") else None
            rt = self.expr(e.right, lt if T.resolve(lt).kind in ("enum",) else sub_exp)
            if T.resolve(rt).kind == "enum" and isinstance(e.left, A.Name) and \
                    isinstance(e.left.sym, EnumSym):
                lt = self.expr(e.left, rt)
        a, b = T.base_of(lt), T.base_of(rt)
        if a is T.ANY or b is T.ANY:
            return T.BOOL if op in ("=", "<>", "<", "<=", ">", ">=") else T.ANY
        if op in ("AND", "OR", "XOR"):
            if a is T.BOOL and b is T.BOOL:
                return T.BOOL
            if a.kind in ("bits", "int") and b.kind in ("bits", "int"):
                c = T.common_type(a, b)
                if c is not None:
                    return c
            self.err("PLC0104", f"{op} needs two BOOLs or two bit strings, not {a} and {b}" +
                     (" (comparisons bind tighter than AND/OR: add parentheses, e.g. "
                      "(a AND b) = c)" if T.BOOL in (a, b) else ""), e.loc)
            return T.ANY
        if op in ("=", "<>", "<", "<=", ">", ">="):
            if isinstance(a, T.EnumType) or isinstance(b, T.EnumType):
                if a is not b:
                    self.err("PLC0104", f"cannot compare {a} with {b}", e.loc)
                return T.BOOL
            c = T.common_type(a, b)
            if c is None:
                self.err("PLC0104", f"cannot compare {T.concrete(a)} with {T.concrete(b)}" +
                         _conv_hint(a, b), e.loc)
            return T.BOOL
        # arithmetic
        ka, kb = a.kind, b.kind
        if ka in ("time", "tod", "dt", "date") or kb in ("time", "tod", "dt", "date"):
            return self.time_arith(e, a, b)
        if op == "**":
            if ka in ("int", "real") and kb in ("int", "real"):
                if ka == "real" and a is not T.ANY_REAL_LIT:
                    return a
                return T.LREAL if a in (T.DINT, T.LINT, T.UDINT, T.ULINT) else T.REAL
            self.err("PLC0104", f"'**' needs numbers, not {a} and {b}", e.loc)
            return T.ANY
        if op == "MOD":
            if ka in ("int", "bits") and kb in ("int", "bits"):
                c = T.common_type(a, b)
                if c is not None:
                    return c
            self.err("PLC0104", f"MOD needs integers, not {T.concrete(a)} and {T.concrete(b)}",
                     e.loc)
            return T.ANY
        if ka in ("int", "real", "bits") and kb in ("int", "real", "bits"):
            c = T.common_type(a, b)
            if c is not None and c.kind != "bits":
                return c
            if c is not None and c.kind == "bits":
                self.err("PLC0104", f"arithmetic '{op}' is not defined on bit strings ({c}); "
                         f"convert to an integer first, e.g. {c.name}_TO_UINT(...)", e.loc)
                return T.ANY
        if isinstance(a, T.StringType) and op == "+":
            self.err("PLC0104", "strings are joined with CONCAT(a, b), not '+'", e.loc)
            return T.ANY
        self.err("PLC0104", f"operator '{op}' cannot combine {T.concrete(a)} and "
                 f"{T.concrete(b)}" + _conv_hint(a, b), e.loc)
        return T.ANY

    def time_arith(self, e: A.Binary, a: T.Type, b: T.Type) -> T.Type:
        op, ka, kb = e.op, a.kind, b.kind
        if ka == "time" and kb == "time" and op in ("+", "-"):
            return T.LTIME if T.LTIME in (a, b) else T.TIME
        if ka == "time" and kb in ("int", "real") and op in ("*", "/"):
            return a
        if kb == "time" and ka in ("int", "real") and op == "*":
            return b
        if ka in ("tod", "dt") and kb == "time" and op in ("+", "-"):
            return a
        if ka == kb and ka in ("tod", "dt", "date") and op == "-":
            return T.TIME
        self.err("PLC0104", f"operator '{op}' cannot combine {T.concrete(a)} and "
                 f"{T.concrete(b)} (TIME + TIME, TIME * number, TOD + TIME and DT - DT are "
                 "defined)", e.loc)
        return T.ANY

    # -- calls --------------------------------------------------------------------------------
    def call(self, c: A.Call, statement: bool) -> T.Type:
        f = c.func
        if isinstance(f, A.Name):
            fname = f.name
            local = self.lookup(fname)
            if isinstance(local, VarSym) and local.decl.section == "RETURN":
                local = None  # F(...) inside F is a (recursive) call, not the result variable
            if local is None:
                pou = self.pous.get(fname)
                if pou is not None and pou.kind == "FUNCTION":
                    return self.call_function(c, pou)
                if pou is not None and pou.kind == "PROGRAM":
                    if not statement:
                        self.err("PLC0106", f"program {fname} is called as a statement, not in an "
                                 "expression", c.loc)
                    f.sym = ProgSym(pou, pou.name)
                    f.ty = self.types[pou.name]
                    return self.call_fb(c, pou, statement, program=True)
                if fname in BUILTINS or conversion(fname) is not None:
                    return self.call_builtin(c, fname, statement)
                if pou is not None and pou.kind == "FUNCTION_BLOCK":
                    self.err("PLC0106", f"{fname} is a function block type; declare an instance "
                             f"(e.g. my{fname.title()} : {fname};) and call the instance", c.loc)
                    self._args_only(c)
                    return T.ANY
                cands = [k for k, v in self.pous.items() if v.kind == "FUNCTION"] + list(
                    BUILTINS) + list(self.scope)
                self.err("PLC0106", f"{fname} is not a function or function block instance" +
                         self._suggest(fname, cands), c.loc)
                self._args_only(c)
                return T.ANY
        ft = T.resolve(self.expr(f, None))
        if isinstance(ft, T.FBType):
            if ft.pou.kind == "FUNCTION_BLOCK":
                return self.call_fb(c, ft.pou, statement)
        if ft is not T.ANY:
            self.err("PLC0106", f"a value of type {ft} cannot be called", c.loc)
        self._args_only(c)
        return T.ANY

    def _args_only(self, c: A.Call) -> None:
        for a in c.args:
            if a.value is not None:
                self.expr(a.value, None)

    def _bind(self, c: A.Call, params: list[A.VarDecl], who: str) -> tuple[list, list, list]:
        """Bind call arguments to formal parameters: named, or positional in order."""
        inputs, outputs, inouts = [], [], []
        positional_params = [d for d in params if d.section in _INPUTISH]
        by_name = {d.name: d for d in params}
        pos = 0
        seen: set[str] = set()
        for a in c.args:
            if a.name is None:
                if pos >= len(positional_params):
                    self.err("PLC0107", f"too many arguments for {who} (it takes "
                             f"{len(positional_params)} input(s))", a.loc)
                    self.expr(a.value, None)
                    continue
                d = positional_params[pos]
                pos += 1
            else:
                d = by_name.get(a.name)
                if d is None or d.section not in _INPUTISH + ("VAR_OUTPUT",):
                    names = [p.name for p in params if p.section in _INPUTISH + ("VAR_OUTPUT",)]
                    self.err("PLC0107", f"{who} has no parameter {a.name}" +
                             self._suggest(a.name, names) + (
                                 "" if self._suggest(a.name, names) else
                                 f" (parameters: {', '.join(names) or 'none'})"), a.loc)
                    if a.value is not None:
                        self.expr(a.value, None)
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
                    tt = self.lvalue(a.value)
                    self.check_assignable(d.ty, tt, a.value, a.loc)
                    outputs.append((d, a.value, a.negated))
                continue
            if d.section == "VAR_OUTPUT":
                self.err("PLC0107", f"{d.name} is an output of {who}; connect it with '=>' "
                         f"(e.g. {d.name} => myVar)", a.loc)
                self.expr(a.value, None)
                continue
            if d.section == "VAR_IN_OUT":
                tt = self.lvalue(a.value)
                if not T.same_type(tt, d.ty) and tt is not T.ANY and d.ty is not T.ANY and not (
                    isinstance(T.resolve(tt), T.StringType) and
                    isinstance(T.resolve(d.ty), T.StringType)
                ):
                    self.err("PLC0107", f"VAR_IN_OUT {d.name} needs a variable of type {d.ty} "
                             f"exactly, not {tt}", a.loc)
                inouts.append((d, a.value))
                continue
            vt = self.expr(a.value, d.ty)
            self.check_assignable(vt, d.ty, a.value, a.loc)
            inputs.append((d, a.value))
        for d in params:
            if d.section == "VAR_IN_OUT" and d.name not in seen:
                self.err("PLC0107", f"VAR_IN_OUT {d.name} of {who} must be connected on every "
                         "call", c.loc)
        return inputs, outputs, inouts

    def _called(self, pou: A.Pou, loc: Location) -> None:
        """Remember that the POU being checked calls ``pou`` here (for recursion)."""
        if self.pou is not None:
            self.calls.setdefault(self.pou.name, set()).add(pou.name)
            self.call_sites.setdefault((self.pou.name, pou.name), loc)

    def call_function(self, c: A.Call, pou: A.Pou) -> T.Type:
        self._called(pou, c.loc)
        ins, outs, inouts = self._bind(c, pou.decls, f"function {pou.spelling or pou.name}")
        c.target = CallInfo("function", pou, ins, outs, inouts)
        rd = getattr(pou, "return_decl", None)
        return rd.ty if rd is not None else T.VOID

    def call_fb(self, c: A.Call, pou: A.Pou, statement: bool, program: bool = False) -> T.Type:
        if not statement:
            self.err("PLC0106", f"a function block call is a statement: call {pou.name} on its "
                     "own line, then read its outputs (inst.Q)", c.loc)
        self._called(pou, c.loc)
        ins, outs, inouts = self._bind(c, pou.decls, f"{pou.name}")
        c.target = CallInfo("program" if program else "fb", pou, ins, outs, inouts)
        return T.VOID

    def call_builtin(self, c: A.Call, name: str, statement: bool) -> T.Type:
        conv = conversion(name)
        if conv is not None and name not in BUILTINS:
            if len(c.args) != 1 or c.args[0].output:
                self.err("PLC0107", f"{name} takes exactly one argument", c.loc)
                self._args_only(c)
                return conv[1]
            a = c.args[0]
            at = self.expr(a.value, None)
            src, dst = conv
            ra = T.base_of(at)
            if src not in (None, "__TRUNC__") and ra is not T.ANY:
                want = T.lookup_elementary(src)
                ok = T.can_widen(ra, want) or T.same_type(ra, want) or (
                    isinstance(ra, T.EnumType) and want.kind == "int")
                if not ok:
                    self.err("PLC0107", f"{name} expects {src}, but the argument is "
                             f"{T.concrete(ra)}" + (f"; use {T.concrete(ra).name}_TO_"
                                                    f"{dst.name}" if hasattr(dst, 'name') else ""),
                             a.loc)
            c.target = CallInfo("conv", (src, dst), [(0, a.value)])
            return dst
        b: Builtin = BUILTINS[name]
        if b.test_only and not self.in_test:
            self.err("PLC0106", f"{name} is only available inside TEST ... END_TEST blocks",
                     c.loc)
        if b.statement_only and not statement:
            self.err("PLC0106", f"{name} is a statement, not a value", c.loc)
        vals: list[A.Expr] = []
        names = list(b.params)
        for a in c.args:
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
                    self.expr(v, None)
            return T.ANY
        c.target = CallInfo("builtin", b, list(enumerate(vals)))
        return self.builtin_type(name, vals, c)

    def builtin_type(self, name: str, vals: list[A.Expr], c: A.Call) -> T.Type:
        ts = [self.expr(v, None) for v in vals]
        bs = [T.base_of(t) for t in ts]
        if any(t is T.ANY for t in bs):
            return T.BOOL if name in ("GT", "GE", "EQ", "LE", "LT", "NE") else T.ANY

        def need(ok: bool, what: str) -> None:
            if not ok:
                self.err("PLC0107", f"{name} needs {what}, not " +
                         ", ".join(str(T.concrete(b)) for b in bs), c.loc)

        def common(items: list[T.Type]) -> T.Type:
            cur = items[0]
            for x in items[1:]:
                nxt = T.common_type(cur, x)
                if nxt is None:
                    self.err("PLC0107", f"{name}: the arguments {T.concrete(cur)} and "
                             f"{T.concrete(x)} have no common type", c.loc)
                    return T.ANY
                cur = nxt
            return cur

        if name in ("ABS", "NEG"):
            need(bs[0].kind in ("int", "real"), "a number")
            return ts[0]
        if name in ("SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN"):
            need(bs[0].kind in ("int", "real"), "a number")
            return ts[0] if bs[0].kind == "real" and bs[0] is not T.ANY_REAL_LIT else (
                T.LREAL if bs[0] is T.ANY_REAL_LIT or getattr(bs[0], "bits", 0) > 16 else T.REAL)
        if name == "ATAN2":
            return common(bs) if all(b.kind == "real" for b in bs) else T.LREAL
        if name in ("TRUNC", "ROUND"):
            need(bs[0].kind == "real", "a REAL or LREAL")
            return T.DINT  # as CODESYS: TRUNC and ROUND give DINT
        if name == "MOVE":
            return ts[0]
        if name == "EXPT":
            need(bs[0].kind in ("int", "real") and bs[1].kind in ("int", "real"), "numbers")
            return ts[0] if bs[0].kind == "real" and bs[0] is not T.ANY_REAL_LIT else T.LREAL
        if name in ("ADD", "MUL", "SUB", "DIV", "MOD", "MIN", "MAX"):
            t = common(bs)
            if name in ("MIN", "MAX"):
                return t
            need(t is T.ANY or t.kind in ("int", "real", "time"), "numbers")
            return t
        if name == "LIMIT":
            return common(bs)
        if name == "SEL":
            need(bs[0] is T.BOOL, "a BOOL selector G first")
            return common(bs[1:])
        if name == "MUX":
            need(bs[0].kind == "int", "an integer selector K first")
            return common(bs[1:])
        if name in ("SHL", "SHR", "ROL", "ROR"):
            need(bs[0].kind in ("bits", "int") and bs[1].kind == "int",
                 "a bit string and a shift count")
            return ts[0] if bs[0] is not T.ANY_INT_LIT else T.DWORD
        if name in ("GT", "GE", "EQ", "LE", "LT", "NE"):
            common(bs)
            return T.BOOL
        strs = [isinstance(b, T.StringType) for b in bs]
        if name == "LEN":
            need(strs[0], "a STRING")
            return T.INT
        if name in ("LEFT", "RIGHT"):
            need(strs[0] and bs[1].kind == "int", "a STRING and a length")
            return ts[0]
        if name == "MID":
            need(strs[0] and bs[1].kind == "int" and bs[2].kind == "int",
                 "a STRING, a length and a position")
            return ts[0]
        if name == "CONCAT":
            need(all(strs), "STRINGs")
            wide = any(getattr(b, "wide", False) for b in bs)
            return T.StringType(wide, 80 if not wide else 80)
        if name == "INSERT":
            need(strs[0] and strs[1] and bs[2].kind == "int", "two STRINGs and a position")
            return ts[0]
        if name == "DELETE":
            need(strs[0] and bs[1].kind == "int" and bs[2].kind == "int",
                 "a STRING, a length and a position")
            return ts[0]
        if name == "REPLACE":
            need(strs[0] and strs[1] and bs[2].kind == "int" and bs[3].kind == "int",
                 "two STRINGs, a length and a position")
            return ts[0]
        if name == "FIND":
            need(strs[0] and strs[1], "two STRINGs")
            return T.INT
        if name in ("ASSERT_EQ", "ASSERT_NE"):
            if T.common_type(bs[0], bs[1]) is None and not (
                isinstance(bs[0], T.EnumType) and bs[0] is bs[1]
            ):
                self.err("PLC0107", f"{name} compares values of one type, not {T.concrete(bs[0])} "
                         f"and {T.concrete(bs[1])}", c.loc)
            return T.VOID
        if name in ("ASSERT_TRUE", "ASSERT_FALSE"):
            need(bs[0] is T.BOOL, "a BOOL")
            return T.VOID
        if name == "ASSERT_NEAR":
            need(all(b.kind in ("int", "real", "time") for b in bs), "numbers")
            return T.VOID
        if name == "ADVANCE_TIME":
            need(bs[0].kind == "time", "a TIME, e.g. ADVANCE_TIME(T#100ms)")
            return T.VOID
        return T.ANY

    # -- suggestions --------------------------------------------------------------------------
    @staticmethod
    def _suggest(name: str, candidates) -> str:
        close = difflib.get_close_matches(name.upper(), [str(c).upper() for c in candidates],
                                          n=1, cutoff=0.7)
        return f"; did you mean {close[0]}?" if close else ""


def _split_address(addr: str) -> tuple[str, list[str]]:
    """``%IX1.2`` -> ("X", ["1", "2"]); ``%QW4`` -> ("W", ["4"]) (the lexer checked the form)."""
    sized = addr[2:3].isalpha()
    return (addr[2] if sized else "X"), addr[3 if sized else 2:].split(".")


def _left_expected(e: A.Binary, expected: T.Type | None) -> T.Type | None:
    """The type expected of the left operand of ``e`` when ``e`` is expected to be ``expected``."""
    if e.op in ("AND", "OR", "XOR") or e.op in ("+", "-", "*", "/", "MOD"):
        return expected
    return None


def _range_text(t: T.Type) -> str:
    t = T.resolve(t)
    if isinstance(t, T.Subrange):
        return f"{t.lo}..{t.hi}"
    if isinstance(t, T.Elementary):
        return f"{t.lo}..{t.hi}"
    return str(t)


def _conv_hint(a: T.Type, b: T.Type) -> str:
    a, b = T.concrete(a), T.concrete(b)
    if a.kind in ("int", "real", "bits") and b.kind in ("int", "real", "bits"):
        return f"; convert one side, e.g. {a.name}_TO_{b.name}(...)"
    return ""


def check(files: list[A.SourceFile]) -> Project:
    """Check parsed files; raise PlcError with every error, or return the project."""
    ck = Checker(files)
    project = ck.run()
    errors = [d for d in ck.diags if d.severity == "error"]
    if errors:
        raise PlcError(errors[0].code, errors[0].message, errors[0].location,
                       diagnostics=ck.diags)
    return project
