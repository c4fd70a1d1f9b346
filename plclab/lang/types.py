"""The IEC 61131-3 type system: elementary types, derived types, widening rules.

Run-time representation (what compiled code and the Python API see):

=================  ==========================================================
BOOL               ``bool``
integers, bits     ``int`` wrapped to the type's width on every store
REAL / LREAL       ``float`` (REAL rounded to IEEE single precision on store)
TIME               ``int`` milliseconds (signed 32 bit, as S7 TIME)
LTIME              ``int`` nanoseconds (signed 64 bit)
DATE, DT           ``int`` seconds since 1970-01-01 (DT: milliseconds)
TOD                ``int`` milliseconds since midnight
STRING / WSTRING   ``str`` truncated to the declared length (default 80)
enumerations       ``int`` (the member's value)
arrays             ``list`` (multi-dimensional arrays flattened, row-major)
structures, FBs    instances of generated classes
=================  ==========================================================

>>> INT.lo, INT.hi, can_widen(INT, DINT), can_widen(DINT, INT)
(-32768, 32767, True, False)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


class Type:
    name: str = "?"
    kind: str = "?"  # bool int bits real time date tod dt string enum array struct fb void any

    def __str__(self) -> str:
        return self.name

    @property
    def is_numeric(self) -> bool:
        return self.kind in ("int", "real")

    @property
    def is_aggregate(self) -> bool:
        return self.kind in ("array", "struct", "fb")


@dataclass(eq=False)
class Elementary(Type):
    name: str
    kind: str
    bits: int = 0
    signed: bool = False

    @property
    def lo(self) -> int:
        return -(1 << (self.bits - 1)) if self.signed else 0

    @property
    def hi(self) -> int:
        return (1 << (self.bits - 1)) - 1 if self.signed else (1 << self.bits) - 1

    def __repr__(self) -> str:
        return self.name


def _e(name, kind, bits=0, signed=False) -> Elementary:
    return Elementary(name, kind, bits, signed)


BOOL = _e("BOOL", "bool", 1)
SINT = _e("SINT", "int", 8, True)
INT = _e("INT", "int", 16, True)
DINT = _e("DINT", "int", 32, True)
LINT = _e("LINT", "int", 64, True)
USINT = _e("USINT", "int", 8)
UINT = _e("UINT", "int", 16)
UDINT = _e("UDINT", "int", 32)
ULINT = _e("ULINT", "int", 64)
BYTE = _e("BYTE", "bits", 8)
WORD = _e("WORD", "bits", 16)
DWORD = _e("DWORD", "bits", 32)
LWORD = _e("LWORD", "bits", 64)
REAL = _e("REAL", "real", 32, True)
LREAL = _e("LREAL", "real", 64, True)
TIME = _e("TIME", "time", 32, True)
LTIME = _e("LTIME", "time", 64, True)
DATE = _e("DATE", "date", 32)
TOD = _e("TOD", "tod", 32)
DT = _e("DT", "dt", 64)

ELEMENTARY: dict[str, Elementary] = {
    t.name: t
    for t in (BOOL, SINT, INT, DINT, LINT, USINT, UINT, UDINT, ULINT, BYTE, WORD, DWORD, LWORD,
              REAL, LREAL, TIME, LTIME, DATE, TOD, DT)
}
ALIASES = {"TIME_OF_DAY": "TOD", "DATE_AND_TIME": "DT", "LDATE": "DATE", "LTOD": "TOD",
           "LTIME_OF_DAY": "TOD", "LDT": "DT", "LDATE_AND_TIME": "DT", "CHAR": "BYTE",
           "WCHAR": "WORD"}


@dataclass(eq=False)
class StringType(Type):
    wide: bool = False
    length: int = 80

    @property
    def name(self) -> str:  # type: ignore[override]
        base = "WSTRING" if self.wide else "STRING"
        return base if self.length == 80 else f"{base}[{self.length}]"

    kind = "string"


STRING = StringType(False, 80)
WSTRING = StringType(True, 80)


@dataclass(eq=False)
class Subrange(Type):
    base: Elementary
    lo: int
    hi: int
    init: Any = None  # the TYPE's own initial value (an AST expression), if it declares one
    kind = "int"

    @property
    def name(self) -> str:  # type: ignore[override]
        return f"{self.base.name}({self.lo}..{self.hi})"

    @property
    def bits(self) -> int:
        return self.base.bits

    @property
    def signed(self) -> bool:
        return self.base.signed


@dataclass(eq=False)
class EnumType(Type):
    name: str
    members: dict[str, int] = field(default_factory=dict)
    base: Elementary = INT
    spellings: dict[str, str] = field(default_factory=dict)
    init: Any = None  # TYPE LEVEL : (LOW, HIGH) := HIGH: the expression HIGH
    kind = "enum"

    def member_name(self, value: int) -> str:
        """The member's name as the source wrote it."""
        for k, v in self.members.items():
            if v == value:
                return self.spellings.get(k, k)
        return str(value)


@dataclass(eq=False)
class ArrayType(Type):
    dims: list[tuple[int, int]]
    elem: Type
    kind = "array"

    @property
    def name(self) -> str:  # type: ignore[override]
        r = ", ".join(f"{lo}..{hi}" for lo, hi in self.dims)
        return f"ARRAY[{r}] OF {self.elem.name}"

    @property
    def size(self) -> int:
        n = 1
        for lo, hi in self.dims:
            n *= hi - lo + 1
        return n


@dataclass(eq=False)
class VarArrayType(Type):
    """``ARRAY[*, ...] OF elem`` of a VAR_IN_OUT (IEC 61131-3 ed.3 6.5.3): the bounds are the
    argument's, known at run time only (``LOWER_BOUND``, ``UPPER_BOUND``; ADR 0060)."""

    ndims: int
    elem: Type
    kind = "array"

    @property
    def name(self) -> str:  # type: ignore[override]
        return f"ARRAY[{', '.join('*' * self.ndims)}] OF {self.elem.name}"


def fits_var_array(src: Type, dst: Type) -> bool:
    """Whether a variable of type ``src`` can be passed for the variable-length array ``dst``:
    an array of as many dimensions, elements of the same type."""
    s, d = resolve(src), resolve(dst)
    if not isinstance(d, VarArrayType):
        return False
    ndims = len(s.dims) if isinstance(s, ArrayType) else s.ndims if isinstance(
        s, VarArrayType) else -1
    return ndims == d.ndims and same_type(s.elem, d.elem)


@dataclass(eq=False)
class StructType(Type):
    name: str
    fields: dict[str, Any] = field(default_factory=dict)  # name -> VarDecl (with .ty)
    kind = "struct"
    pyname: str = ""


@dataclass(eq=False)
class FBType(Type):
    """The type of a function block instance (also used for PROGRAM instances)."""

    name: str
    pou: Any = None  # ast.Pou
    kind = "fb"


@dataclass(eq=False)
class InterfaceType(Type):
    """A reference to an instance whose block implements the INTERFACE ``pou`` (ADR 0021): a
    value (copied as a reference, never the instance), unassigned (None) by default."""

    name: str
    pou: Any = None  # ast.Pou of kind INTERFACE
    kind = "interface"


@dataclass(eq=False)
class RefType(Type):
    """``REF_TO target`` / ``POINTER TO target`` (ADR 0021): a reference to a variable, NULL
    (None) by default; ``target`` ANY for NULL itself."""

    target: Type
    pointer: bool = False
    reference: bool = False  # CODESYS REFERENCE TO: used without ^ (lower.reference_to)
    kind = "ref"

    @property
    def name(self) -> str:  # type: ignore[override]
        if self.target is ANY:
            return "NULL"
        word = "POINTER TO" if self.pointer else "REFERENCE TO" if self.reference else "REF_TO"
        return f"{word} {self.target}"


def block_type(name: str, pou: Any) -> Type:
    """The type a FUNCTION_BLOCK, PROGRAM or INTERFACE name stands for."""
    return InterfaceType(name, pou) if pou.kind == "INTERFACE" else FBType(name, pou)


@dataclass(eq=False)
class AliasType(Type):
    name: str
    target: Type | None = None
    init: Any = None  # TYPE Speed : INT := 50: the expression 50


def declared_init(t: Type) -> Any:
    """The initial value a TYPE declaration gives its type (``TYPE LEVEL : (LOW, HIGH) := HIGH``,
    IEC 61131-3 ed.3 6.4.4.1), from the nearest alias that declares one; None when the IEC
    default applies."""
    while True:
        init = getattr(t, "init", None)
        if init is not None or not isinstance(t, AliasType) or t.target is None:
            return init
        t = t.target


@dataclass(eq=False)
class _Special(Type):
    name: str
    kind: str


VOID = _Special("VOID", "void")
ANY = _Special("ANY", "any")  # unknown after an error: compatible with everything
# Untyped literal kinds: an integer literal adapts to the type it meets
ANY_INT_LIT = _Special("ANY_INT", "int")
ANY_REAL_LIT = _Special("ANY_REAL", "real")


def resolve(t: Type) -> Type:
    while isinstance(t, AliasType) and t.target is not None:
        t = t.target
    return t


# IEC 61131-3 3rd edition, implicit (widening) conversions (Figure 11 / Table 11 analog).
_WIDEN: dict[str, set[str]] = {
    "SINT": {"INT", "DINT", "LINT", "REAL", "LREAL"},
    "INT": {"DINT", "LINT", "REAL", "LREAL"},
    "DINT": {"LINT", "LREAL"},
    "LINT": set(),
    "USINT": {"UINT", "UDINT", "ULINT", "INT", "DINT", "LINT", "REAL", "LREAL"},
    "UINT": {"UDINT", "ULINT", "DINT", "LINT", "REAL", "LREAL"},
    "UDINT": {"ULINT", "LINT", "LREAL"},
    "ULINT": set(),
    "BOOL": {"BYTE", "WORD", "DWORD", "LWORD"},
    "BYTE": {"WORD", "DWORD", "LWORD"},
    "WORD": {"DWORD", "LWORD"},
    "DWORD": {"LWORD"},
    "LWORD": set(),
    "REAL": {"LREAL"},
    "LREAL": set(),
    "TIME": {"LTIME"},
    "LTIME": set(),
    "DATE": set(),
    "TOD": set(),
    "DT": set(),
}
# Lenient extras that CODESYS and TIA accept silently (DINT -> REAL loses precision but is
# accepted by both): kept separate so the checker can warn instead of erroring.
_LENIENT: dict[str, set[str]] = {
    "DINT": {"REAL"},
    "UDINT": {"REAL"},
    "LINT": {"REAL"},
}


def base_of(t: Type) -> Type:
    t = resolve(t)
    if isinstance(t, Subrange):
        return t.base
    return t


def can_widen(src: Type, dst: Type) -> bool:
    """True if a value of ``src`` may be stored in ``dst`` without an explicit conversion."""
    src, dst = resolve(src), resolve(dst)
    if src is ANY or dst is ANY:
        return True
    if src is dst:
        return True
    if isinstance(src, Subrange):
        src = src.base  # a subrange value is a value of its base type, and widens like it
        if src is dst:
            return True
    if isinstance(dst, Subrange):
        return base_of(src) is dst.base or can_widen(src, dst.base)
    if src is ANY_INT_LIT:
        return dst.kind in ("int", "bits", "real")
    if src is ANY_REAL_LIT:
        return dst.kind == "real"
    if isinstance(src, StringType) and isinstance(dst, StringType):
        return src.wide == dst.wide
    if isinstance(src, Elementary) and isinstance(dst, Elementary):
        return dst.name in _WIDEN.get(src.name, set()) or dst.name in _LENIENT.get(src.name, set())
    if isinstance(src, ArrayType) and isinstance(dst, ArrayType):
        return [hi - lo for lo, hi in src.dims] == [hi - lo for lo, hi in dst.dims] and (
            same_type(src.elem, dst.elem)
        )
    return False


def same_type(a: Type, b: Type) -> bool:
    a, b = resolve(a), resolve(b)
    if a is b:
        return True
    if isinstance(a, StringType) and isinstance(b, StringType):
        return a.wide == b.wide
    if isinstance(a, ArrayType) and isinstance(b, ArrayType):
        return a.dims == b.dims and same_type(a.elem, b.elem)
    if isinstance(a, VarArrayType) and isinstance(b, VarArrayType):
        return a.ndims == b.ndims and same_type(a.elem, b.elem)
    if isinstance(a, RefType) and isinstance(b, RefType):  # POINTER TO POINTER TO INT: by
        return same_type(a.target, b.target)  # structure, as anonymous types have no name
    return False


def common_type(a: Type, b: Type) -> Type | None:
    """The type both operands widen to (for arithmetic and comparison), or None."""
    a, b = base_of(a), base_of(b)
    if a is ANY or b is ANY:
        return ANY
    if a is b:
        return a
    if a in (ANY_INT_LIT, ANY_REAL_LIT) and b in (ANY_INT_LIT, ANY_REAL_LIT):
        return ANY_REAL_LIT if ANY_REAL_LIT in (a, b) else ANY_INT_LIT
    if a is ANY_INT_LIT and b.kind in ("int", "bits", "real", "enum"):
        return b
    if b is ANY_INT_LIT and a.kind in ("int", "bits", "real", "enum"):
        return a
    if a is ANY_REAL_LIT and b.kind == "real":
        return b
    if b is ANY_REAL_LIT and a.kind == "real":
        return a
    if a is ANY_REAL_LIT and b.kind == "int":
        return LREAL if b.bits > 16 else REAL
    if b is ANY_REAL_LIT and a.kind == "int":
        return LREAL if a.bits > 16 else REAL
    if can_widen(a, b):
        return b
    if can_widen(b, a):
        return a
    if isinstance(a, StringType) and isinstance(b, StringType) and a.wide == b.wide:
        return a if a.length >= b.length else b
    # mixed signed/unsigned integers: the smallest signed type holding both
    if a.kind == "int" and b.kind == "int" and isinstance(a, Elementary) and isinstance(
        b, Elementary
    ):
        bits = max(a.bits if a.signed else a.bits * 2, b.bits if b.signed else b.bits * 2)
        for t in (SINT, INT, DINT, LINT):
            if t.bits >= bits:
                return t
        return LINT
    if a.kind == "bits" and b.kind == "bits":
        return a if a.bits >= b.bits else b
    return None


def concrete(t: Type) -> Type:
    """Give an untyped literal type its default: ANY_INT -> DINT (or LINT), ANY_REAL -> LREAL."""
    if t is ANY_INT_LIT:
        return DINT
    if t is ANY_REAL_LIT:
        return LREAL
    return t


def fits(value: int, t: Type) -> bool:
    t = resolve(t)
    if isinstance(t, Subrange):
        return t.lo <= value <= t.hi
    if isinstance(t, Elementary) and t.kind in ("int", "bits"):
        return t.lo <= value <= t.hi
    return True


def int_type_for(value: int) -> Elementary:
    for t in (SINT, INT, DINT, LINT):
        if t.lo <= value <= t.hi:
            return t
    return ULINT


def lookup_elementary(name: str) -> Type | None:
    name = ALIASES.get(name, name)
    if name in ELEMENTARY:
        return ELEMENTARY[name]
    if name == "STRING":
        return STRING
    if name == "WSTRING":
        return WSTRING
    return None


def default_value(t: Type) -> Any:
    """The IEC default initial value of a scalar type (aggregates handled by the compiler)."""
    t = resolve(t)
    if t is BOOL:
        return False
    if isinstance(t, StringType):
        return ""
    if t.kind == "real":
        return 0.0
    if isinstance(t, Subrange):
        return t.lo if t.lo > 0 else (0 if t.lo <= 0 <= t.hi else t.hi)
    if isinstance(t, EnumType):
        return next(iter(t.members.values()), 0)
    if isinstance(t, InterfaceType | RefType):
        return None
    return 0
