"""Signatures of the standard functions (IEC 61131-3 2.5.1.5) as the checker sees them.

Each entry maps a function name to a typing rule. The compiler turns calls into inline Python
or calls of :mod:`plclab.runtime.stdfuncs`.
"""

from __future__ import annotations

from dataclasses import dataclass

from . import types as T


@dataclass(frozen=True)
class Builtin:
    name: str
    params: tuple[str, ...]  # formal names for named calls (IEC: IN, IN1, MN, ...)
    variadic: bool = False
    min_args: int = 1
    test_only: bool = False
    statement_only: bool = False


_NUM_1 = ("IN",)
_B = Builtin
BUILTINS: dict[str, Builtin] = {}


def _add(*bs: Builtin) -> None:
    for b in bs:
        BUILTINS[b.name] = b


_add(
    *(_B(n, ("IN",)) for n in ("ABS", "SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN",
                               "ACOS", "ATAN", "TRUNC", "MOVE", "ROUND", "NEG")),
    _B("EXPT", ("IN1", "IN2"), min_args=2),
    _B("ATAN2", ("Y", "X"), min_args=2),
    _B("ADD", ("IN1", "IN2"), variadic=True, min_args=2),
    _B("MUL", ("IN1", "IN2"), variadic=True, min_args=2),
    _B("SUB", ("IN1", "IN2"), min_args=2),
    _B("DIV", ("IN1", "IN2"), min_args=2),
    _B("MOD", ("IN1", "IN2"), min_args=2),
    _B("MIN", ("IN1", "IN2"), variadic=True, min_args=1),
    _B("MAX", ("IN1", "IN2"), variadic=True, min_args=1),
    _B("LIMIT", ("MN", "IN", "MX"), min_args=3),
    _B("SEL", ("G", "IN0", "IN1"), min_args=3),
    _B("MUX", ("K", "IN0", "IN1"), variadic=True, min_args=2),
    *(_B(n, ("IN", "N"), min_args=2) for n in ("SHL", "SHR", "ROL", "ROR")),
    *(_B(n, ("IN1", "IN2"), variadic=True, min_args=2) for n in ("GT", "GE", "EQ", "LE", "LT")),
    _B("NE", ("IN1", "IN2"), min_args=2),
    _B("LEN", ("IN",)),
    _B("LEFT", ("IN", "L"), min_args=2),
    _B("RIGHT", ("IN", "L"), min_args=2),
    _B("MID", ("IN", "L", "P"), min_args=3),
    _B("CONCAT", ("IN1", "IN2"), variadic=True, min_args=1),
    _B("INSERT", ("IN1", "IN2", "P"), min_args=3),
    _B("DELETE", ("IN", "L", "P"), min_args=3),
    _B("REPLACE", ("IN1", "IN2", "L", "P"), min_args=4),
    _B("FIND", ("IN1", "IN2"), min_args=2),
    _B("ASSERT_EQ", ("ACTUAL", "EXPECTED"), min_args=2, test_only=True, statement_only=True),
    _B("ASSERT_NE", ("ACTUAL", "EXPECTED"), min_args=2, test_only=True, statement_only=True),
    _B("ASSERT_TRUE", ("IN",), test_only=True, statement_only=True),
    _B("ASSERT_FALSE", ("IN",), test_only=True, statement_only=True),
    _B("ASSERT_NEAR", ("ACTUAL", "EXPECTED", "TOL"), min_args=3, test_only=True,
       statement_only=True),
    _B("ADVANCE_TIME", ("T",), test_only=True, statement_only=True),
)

CONVERTIBLE = [n for n in T.ELEMENTARY] + ["STRING", "WSTRING"]


def conversion(name: str) -> tuple[str | None, T.Type] | None:
    """Parse ``INT_TO_REAL`` / ``TO_REAL`` / ``TRUNC_INT`` into (source name or None, target)."""
    if name.startswith("TRUNC_"):
        tgt = T.lookup_elementary(name[6:])
        return ("__TRUNC__", tgt) if tgt is not None else None
    if name.startswith("TO_"):
        tgt = T.lookup_elementary(name[3:])
        return (None, tgt) if tgt is not None else None
    if "_TO_" in name:
        src, _, dst = name.partition("_TO_")
        src = T.ALIASES.get(src, src)
        s = T.lookup_elementary(src)
        d = T.lookup_elementary(dst)
        if s is not None and d is not None:
            return (s.name if not isinstance(s, T.StringType) else src, d)
    return None


def is_builtin(name: str) -> bool:
    return name in BUILTINS or conversion(name) is not None
