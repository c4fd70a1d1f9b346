"""The one abstract syntax tree that every front end (ST, IL, LD, SFC, PLCopen XML) produces.

The checker annotates the tree in place, only through the fields declared below with
:func:`annotation` (``Expr.ty``, ``Name.sym``, ``Call.target``, ``Pou.return_decl``, ...; each says
which pass of :mod:`plclab.lang.check` sets it); the compiler reads those annotations and never
asks which language a POU came from. :mod:`plclab.lang.walk` knows the children of every node
class.
"""

from __future__ import annotations

import copy
import reprlib
from dataclasses import dataclass, field, fields
from typing import Any

from ..errors import Location


def annotation(default: Any = None) -> Any:
    """A field the checker fills in after parsing: not a constructor argument, not compared,
    not shown in ``repr``."""
    return field(default=default, init=False, compare=False, repr=False)

PARTIAL_WIDTHS = {"B": 8, "W": 16, "D": 32, "L": 64}  # x.%B1, x.%W0, ... (ed.3 Table 17)
PARTIAL_TYPES = {"B": "BYTE", "W": "WORD", "D": "DWORD", "L": "LWORD"}


def partial_access(field_name: str) -> tuple[str, int] | None:
    """The partial access a :class:`Member`'s ``field_name`` names: ("X", n) for the bit access
    ``x.n`` / ``x.%Xn`` (field ``%n``), ("B", n) for the byte ``x.%Bn`` (field ``%Bn``), "W",
    "D", "L" likewise; None for a member name or a dereference."""
    if not field_name.startswith("%"):
        return None
    if field_name[1:2] in PARTIAL_WIDTHS:
        return field_name[1], int(field_name[2:])
    return "X", int(field_name[1:])

# ---------------------------------------------------------------------------------------------
# Type expressions as written in source


@dataclass(eq=False, slots=True, repr=False)
class TypeRef:
    loc: Location


@dataclass(eq=False, slots=True, repr=False)
class NamedTypeRef(TypeRef):
    name: str
    # ``a : FB(k := 3);``: arguments for the block's FB_init (CODESYS; ADR 0052), None if none
    args: list[Arg] | None = None
    # check.declarations: (FB_init input, value) for each FB_init input after the two BOOLs
    bound: Any = annotation()


@dataclass(eq=False, slots=True, repr=False)
class StringTypeRef(TypeRef):
    wide: bool
    length: Expr | None = None


@dataclass(eq=False, slots=True, repr=False)
class ArrayTypeRef(TypeRef):
    ranges: list[tuple[Expr, Expr]]
    elem: TypeRef
    # ``ARRAY[*, *] OF T`` (ed.3 variable-length array): the number of ``*``, ranges empty
    star: int = 0


@dataclass(eq=False, slots=True, repr=False)
class SubrangeTypeRef(TypeRef):
    base: TypeRef
    lo: Expr
    hi: Expr


@dataclass(eq=False, slots=True, repr=False)
class EnumTypeRef(TypeRef):
    members: list[tuple[str, Expr | None, Location]]
    base: TypeRef | None = None
    spellings: dict[str, str] = field(default_factory=dict)  # RED -> Red, as written


@dataclass(eq=False, slots=True, repr=False)
class RefTypeRef(TypeRef):
    """``REF_TO T`` (IEC ed.3), ``POINTER TO T`` or ``REFERENCE TO T`` (CODESYS); ADR 0021."""

    kind: str  # REF_TO POINTER REFERENCE
    target: TypeRef


@dataclass(eq=False, slots=True, repr=False)
class StructTypeRef(TypeRef):
    fields: list[VarDecl]


# ---------------------------------------------------------------------------------------------
# Expressions


@dataclass(eq=False, slots=True, repr=False)
class Expr:
    loc: Location
    ty: Any = annotation()  # check.exprs: the expression's type (plclab.lang.types)
    is_target: bool = annotation(False)  # check.exprs.lvalue: written to, never a temporary


@dataclass(eq=False, slots=True, repr=False)
class Literal(Expr):
    value: Any
    kind: str  # INT REAL BOOL STRING WSTRING TIME DATE TOD DT ENUM
    prefix: str | None = None  # INT#5 -> "INT"
    text: str = ""
    enum_value: int | None = annotation()  # check.exprs: the value of Color#Red (kind ENUM)


@dataclass(eq=False, slots=True, repr=False)
class Name(Expr):
    name: str
    text: str = ""  # as written (the name is upper-cased: identifiers are case-insensitive)
    sym: Any = annotation()  # check.exprs / check.calls: VarSym | EnumSym | ProgSym


@dataclass(eq=False, slots=True, repr=False)
class DirectAddr(Expr):
    address: str  # %IX0.0


@dataclass(eq=False, slots=True, repr=False)
class Member(Expr):
    obj: Expr
    field_name: str
    text: str = ""  # the member name as written
    # check.exprs: the member's VarDecl (block instances); check.oop: a PROPERTY's accessor
    # (a METHOD Pou). A field_name "^" is a dereference (r^), one "%3" a bit access (x.3).
    sym: Any = annotation()


@dataclass(eq=False, slots=True, repr=False)
class Index(Expr):
    obj: Expr
    indices: list[Expr]


@dataclass(eq=False, slots=True, repr=False)
class Unary(Expr):
    op: str  # "-", "+", "NOT"
    operand: Expr


@dataclass(eq=False, slots=True, repr=False)
class Binary(Expr):
    op: str  # + - * / MOD ** = <> < <= > >= AND OR XOR
    left: Expr
    right: Expr


@dataclass(eq=False, slots=True, repr=False)
class Arg:
    loc: Location
    name: str | None  # None for positional
    value: Expr | None  # None for an unconnected output `Q =>`
    output: bool = False  # `name => var`
    negated: bool = False  # `NOT Q => x`


@dataclass(eq=False, slots=True, repr=False)
class Call(Expr):
    func: Expr  # Name of a function / FB instance expression
    args: list[Arg]
    target: Any = annotation()  # check.calls: CallInfo, the callee and the bound arguments


@dataclass(eq=False, slots=True, repr=False)
class ArrayInit(Expr):
    """``[1, 2, 3(0)]`` for arrays; items are (repeat, value)."""

    items: list[tuple[Expr | None, Expr]]


@dataclass(eq=False, slots=True, repr=False)
class StructInit(Expr):
    """``(a := 1, b := 2)`` for structures."""

    fields: list[tuple[str, Expr, Location]]


# ---------------------------------------------------------------------------------------------
# Statements


@dataclass(eq=False, slots=True, repr=False)
class Stmt:
    loc: Location


@dataclass(eq=False, slots=True, repr=False)
class Assign(Stmt):
    target: Expr
    value: Expr
    op: str = ":="  # ":=", "S=" (set), "R=" (reset) -- used by LD coils


@dataclass(eq=False, slots=True, repr=False)
class CallStmt(Stmt):
    call: Call


@dataclass(eq=False, slots=True, repr=False)
class If(Stmt):
    branches: list[tuple[Expr, list[Stmt]]]
    orelse: list[Stmt] | None = None


@dataclass(eq=False, slots=True, repr=False)
class CaseBranch:
    loc: Location
    labels: list[Expr | tuple[Expr, Expr]]  # single values or (lo, hi) ranges
    body: list[Stmt]


@dataclass(eq=False, slots=True, repr=False)
class Case(Stmt):
    selector: Expr
    branches: list[CaseBranch]
    orelse: list[Stmt] | None = None


@dataclass(eq=False, slots=True, repr=False)
class For(Stmt):
    var: Name
    start: Expr
    end: Expr
    step: Expr | None
    body: list[Stmt]


@dataclass(eq=False, slots=True, repr=False)
class While(Stmt):
    cond: Expr
    body: list[Stmt]


@dataclass(eq=False, slots=True, repr=False)
class Repeat(Stmt):
    body: list[Stmt]
    cond: Expr


@dataclass(eq=False, slots=True, repr=False)
class Exit(Stmt):
    pass


@dataclass(eq=False, slots=True, repr=False)
class Continue(Stmt):
    pass


@dataclass(eq=False, slots=True, repr=False)
class Return(Stmt):
    pass


@dataclass(eq=False, slots=True, repr=False)
class Empty(Stmt):
    pass


@dataclass(eq=False, slots=True, repr=False)
class Label(Stmt):
    """A jump target (IL labels; compiled as a state machine)."""

    name: str


@dataclass(eq=False, slots=True, repr=False)
class Jump(Stmt):
    label: str
    cond: Expr | None = None


# ---------------------------------------------------------------------------------------------
# Declarations


@dataclass(eq=False, slots=True, repr=False)
class VarDecl:
    loc: Location
    name: str  # upper-case
    type: TypeRef
    init: Expr | None = None
    address: str | None = None  # "%IX0.0"
    section: str = "VAR"  # VAR VAR_INPUT VAR_OUTPUT VAR_IN_OUT VAR_GLOBAL VAR_EXTERNAL VAR_TEMP
    constant: bool = False
    retain: bool = False
    spelling: str = ""  # the name as written
    used: bool = False  # set by the checker (check.exprs, check.declarations): for PLC0200
    ty: Any = annotation()  # check.declarations: the resolved type


@dataclass(eq=False, slots=True, repr=False)
class Pou:
    loc: Location
    kind: str  # PROGRAM FUNCTION FUNCTION_BLOCK
    name: str
    decls: list[VarDecl]
    body: list[Stmt]
    return_type: TypeRef | None = None
    spelling: str = ""
    language: str = "ST"
    native: str | None = None  # library blocks only: key in plclab.runtime.natives
    end_loc: Location | None = None
    # bodies parsed but not yet in core statements; plclab.lang.lower empties the list
    pending: list[PendingBody] = field(default_factory=list, compare=False, repr=False)
    # text ladder only: the drawn networks (plclab.lang.frontends.ld.Network), for drawings
    networks: list[Any] = field(default_factory=list, compare=False, repr=False)
    # an SFC body only: the chart it was lowered from (plclab.lang.lower.sfc.Chart), for the
    # trace's SFC lane, the feedback and the drawing (ADR 0023)
    sfc: Any = field(default=None, compare=False, repr=False)

    # object-oriented extensions (plclab.lang.frontends.oop, ADR 0021): a FUNCTION_BLOCK's
    # base (one) or an INTERFACE's bases (several), the interfaces it implements, its METHODs
    # (Pou of kind METHOD), and ABSTRACT FINAL PUBLIC PRIVATE PROTECTED INTERNAL as written
    extends: list[str] = field(default_factory=list)
    implements: list[str] = field(default_factory=list)
    methods: list[Pou] = field(default_factory=list)
    modifiers: list[str] = field(default_factory=list)
    owner: Pou | None = field(default=None, compare=False, repr=False)  # a METHOD's block
    # a CODESYS action of a PROGRAM or FUNCTION_BLOCK (kind METHOD, no declarations of its
    # own: it runs on its POU's data, and a call passes the POU's inputs and outputs; ADR 0035)
    action: bool = False
    # a PROGRAM's VAR_ACCESS (IEC 61131-3 ed.2 and ed.3 B.1.5.3, program_access_decls): names
    # under which it publishes its own variables, ``path`` relative to the program
    access_paths: list[AccessPath] = field(default_factory=list)
    # an ed.3 CLASS (6.6.5.2): a FUNCTION_BLOCK without a body and without inputs or outputs
    # (ADR 0059); kind stays FUNCTION_BLOCK, so every pass treats it as one
    is_class: bool = False

    # check.symbols (SymbolTable.scope) / check.declarations: a FUNCTION's result variable
    return_decl: VarDecl | None = annotation()


@dataclass(eq=False, slots=True, repr=False)
class PendingBody:
    """A body a front end parsed into data that :mod:`plclab.lang.lower` turns into core
    statements once every declaration is known. ``kind`` is ``"IL"`` (``payload``: a list of
    :class:`plclab.lang.lower.il.Instr`) or ``"NETWORK"`` (an LD or FBD network: a list of
    :class:`plclab.lang.lower.network.Elem`)."""

    kind: str
    payload: list[Any]
    loc: Location


@dataclass(eq=False, slots=True, repr=False)
class TypeDecl:
    loc: Location
    name: str
    type: TypeRef
    init: Expr | None = None
    spelling: str = ""


@dataclass(eq=False, slots=True, repr=False)
class GlobalVars:
    loc: Location
    decls: list[VarDecl]


@dataclass(eq=False, slots=True, repr=False)
class TaskDecl:
    loc: Location
    name: str
    interval: Expr | None
    priority: Expr | None
    single: Expr | None = None
    resource: str | None = None  # upper-case; set where a configuration has two or more


@dataclass(eq=False, slots=True, repr=False)
class ProgramInstance:
    loc: Location
    name: str
    task: str | None
    program: str
    # PROGRAM P1 : Prog(x := %IX1.1, y => g): the connections, as a call of the program
    call: Call | None = None
    resource: str | None = None  # upper-case; set where a configuration has two or more

    @property
    def key(self) -> str:
        """How the project names the instance: ``RESOURCE.NAME`` in a configuration of two or
        more resources (ADR 0037), else its name."""
        return f"{self.resource}.{self.name}" if self.resource else self.name


@dataclass(eq=False, slots=True, repr=False)
class ConfigVar:
    """One line of VAR_CONFIG (IEC 61131-3 ed.3 6.8.2, Table 62): a variable deep inside a
    program instance given the address its ``AT %I*`` left open and/or an initial value,
    ``STATION_1.P1.FB1.C2 AT %QB25 : BYTE := 7;``."""

    loc: Location
    path: list[str]  # upper-case parts: [resource.]instance.member...
    spelled: str  # the path as written
    address: str | None
    type: TypeRef
    init: Expr | None = None


@dataclass(eq=False, slots=True, repr=False)
class AccessPath:
    """One line of VAR_ACCESS (IEC 61131-3 ed.3 6.8.2): a name under which a configuration
    publishes a variable or a direct address to other systems, read-only or read-write,
    ``ABLE : STATION_1.%IX1.1 : BOOL READ_ONLY;``."""

    loc: Location
    name: str
    spelling: str
    path: list[str]  # upper-case parts; a direct address is its last part
    spelled: str
    type: TypeRef
    read_only: bool = True


@dataclass(eq=False, slots=True, repr=False)
class Configuration:
    loc: Location
    name: str
    globals: list[VarDecl]
    tasks: list[TaskDecl]
    instances: list[ProgramInstance]
    resources: list[str] = field(default_factory=list)  # upper-case resource names
    config_vars: list[ConfigVar] = field(default_factory=list)
    access_paths: list[AccessPath] = field(default_factory=list)
    # the VAR_GLOBAL of each resource (upper-case name), where there are two or more resources
    # (IEC 61131-3 ed.3 6.8: visible to that resource's programs only; ADR 0037)
    resource_globals: dict[str, list[VarDecl]] = field(default_factory=dict)

    def settle_resources(self) -> None:
        """After parsing: with one resource (or none) its globals are the configuration's and
        its instances and tasks are named as before; with two or more, each keeps its own."""
        if len(self.resources) > 1:
            return
        for decls in self.resource_globals.values():
            self.globals.extend(decls)
        self.resource_globals = {}
        for x in [*self.tasks, *self.instances]:
            x.resource = None


@dataclass(eq=False, slots=True, repr=False)
class TestBlock:
    loc: Location
    title: str
    decls: list[VarDecl]
    body: list[Stmt]


@dataclass(eq=False, slots=True, repr=False)
class SourceFile:
    file: str
    types: list[TypeDecl] = field(default_factory=list)
    pous: list[Pou] = field(default_factory=list)
    globals: list[GlobalVars] = field(default_factory=list)
    configs: list[Configuration] = field(default_factory=list)
    config_vars: list[ConfigVar] = field(default_factory=list)  # a CODESYS top-level VAR_CONFIG
    tests: list[TestBlock] = field(default_factory=list)
    dialect: str | None = None  # the file's dialect (plclab.lang.dialect); None: the default


def method_inst_name(block: str, method: str, var: str) -> str:
    """The hidden instance variable of a METHOD's ``VAR_INST`` variable (ADR 0021; ``__``
    cannot be written in an ST name, so it cannot clash with a user variable; the block's name
    keeps an override's variable apart from its base's)."""
    return f"{block}__{method}__{var}"


def child_bodies(s: Stmt) -> list[list[Stmt]]:
    """The statement lists directly inside ``s`` (IF branches and ELSE, CASE branches and
    ELSE, loop bodies); empty for a simple statement."""
    if isinstance(s, If):
        return [body for _, body in s.branches] + ([s.orelse] if s.orelse else [])
    if isinstance(s, Case):
        return [b.body for b in s.branches] + ([s.orelse] if s.orelse else [])
    if isinstance(s, For | While | Repeat):
        return [s.body]
    return []


def walk_stmts(stmts: list[Stmt]):
    """Yield every statement of a body, nested ones included (pre-order).

    A loop over an explicit stack, not recursion: bodies may be nested thousands deep."""
    stack = [iter(stmts)]
    while stack:
        s = next(stack[-1], None)
        if s is None:
            stack.pop()
            continue
        yield s
        bodies = child_bodies(s)
        if bodies:
            stack.append(x for body in bodies for x in body)


def copy_expr(e: Expr) -> Expr:
    """A deep copy of an expression; the left spine of an operator chain (``a + b + c ...``,
    IL's current result after 10,000 lines) is copied with a loop, not recursion."""
    spine: list[Binary] = []
    while isinstance(e, Binary):
        spine.append(e)
        e = e.left
    out = copy.deepcopy(e)
    for node in reversed(spine):
        top = copy.copy(node)
        top.left, top.right = out, copy.deepcopy(node.right)
        out = top
    return out


def expr_text(e: Expr | None) -> str:
    """A short readable rendering of an expression, for messages (``t.Q``, ``a + 1``)."""
    if e is None:
        return "?"
    if isinstance(e, Literal):
        return e.text or repr(e.value)
    if isinstance(e, Name):
        return e.text or e.name
    if isinstance(e, Member) and e.field_name == "^":
        return f"{expr_text(e.obj)}^"
    if isinstance(e, Member):
        f = e.text or e.field_name
        return f"{expr_text(e.obj)}.{f[1:] if f.startswith('%') else f}"
    if isinstance(e, Index):
        return f"{expr_text(e.obj)}[{', '.join(expr_text(i) for i in e.indices)}]"
    if isinstance(e, DirectAddr):
        return e.address
    if isinstance(e, Unary):
        return f"NOT {expr_text(e.operand)}" if e.op == "NOT" else f"-{expr_text(e.operand)}"
    if isinstance(e, Binary):
        return f"{expr_text(e.left)} {e.op} {expr_text(e.right)}"
    if isinstance(e, Call):
        return f"{expr_text(e.func)}(...)"
    return "?"


@reprlib.recursive_repr()
def _node_repr(self: Any) -> str:
    """The repr a dataclass would make (its fields with ``repr=True``): one function for
    every node class instead of one compiled for each class at import (ADR 0034)."""
    shown = ", ".join(f"{f.name}={getattr(self, f.name)!r}" for f in fields(self) if f.repr)
    return f"{type(self).__qualname__}({shown})"


for _cls in list(globals().values()):
    if isinstance(_cls, type) and _cls.__module__ == __name__ and \
            "__dataclass_fields__" in _cls.__dict__ and "__repr__" not in _cls.__dict__:
        _cls.__repr__ = _node_repr
del _cls
