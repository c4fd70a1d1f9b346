"""The standard library's specification: one entry per standard function and block.

Every other place derives from these tables instead of keeping its own list of names:

* a :class:`Builtin` (a standard function of IEC 61131-3 2.5.1.5, or a TEST-block assertion)
  gives the signature (formal names, arity), the checker's typing rule (``typing``: a key of
  :data:`plclab.lang.check.calls.TYPING_RULES`), the compiler's emission (``emit``: a key of
  :data:`plclab.compile.builtins_emit.EMITTERS`) and the run-time helpers the emitted code calls
  (``natives``: names in :data:`plclab.runtime.rt.HELPERS`);
* a :class:`Block` (a standard or control function block) gives its library file, its native
  implementation (a key of :mod:`plclab.runtime.natives`), the pins a ladder rung's power flow
  enters and leaves by (:data:`POWER_PINS`) and its IL input operators (:data:`FB_INPUT_OPS`).

``tests/lang/test_standard_spec.py`` checks that every key names a rule, an emitter, a helper and a
library declaration that exist.

>>> BUILTINS["SQRT"].typing, BUILTINS["SQRT"].natives
('float', ('_sqrt',))
>>> POWER_PINS["CTU"], "PT" in FB_INPUT_OPS
(('CU', 'Q'), True)
"""

from __future__ import annotations

from dataclasses import dataclass

from . import types as T


@dataclass(frozen=True)
class Builtin:
    """A standard function (see the module text)."""

    name: str
    params: tuple[str, ...]  # formal names for named calls (IEC: IN, IN1, MN, ...)
    typing: str = ""  # the checker's typing rule
    emit: str = ""  # the compiler's emitter ("test" for the TEST-block statements)
    variadic: bool = False
    min_args: int = 1
    test_only: bool = False
    statement_only: bool = False
    natives: tuple[str, ...] = ()  # run-time helpers the emitted code calls
    operator: str = ""  # the Python operator of ADD, MUL and the comparisons
    args: tuple[str, ...] = ()  # the "signature" rule: argument kinds, STRING or INT
    needs: str = ""  # ... and how its message names them
    result: str = ""  # ... and the result: "IN" (the first argument's type) or a type name


@dataclass(frozen=True)
class Block:
    """A function block of plclab's library whose body is native Python."""

    name: str
    library: str  # stdlib.st or ctrllib.st
    power: tuple[str, str] | None = None  # LD: (BOOL input fed by the rung, output continuing)
    il_inputs: tuple[str, ...] = ()  # IL input operators (IEC 61131-3 Table 53: S1, PT, ...)


_B = Builtin
BUILTINS: dict[str, Builtin] = {}
_MATH = {"SQRT": "_sqrt", "LN": "_ln", "LOG": "_log", "EXP": "_exp", "SIN": "_sin",
         "COS": "_cos", "TAN": "_tan", "ASIN": "_asin", "ACOS": "_acos", "ATAN": "_math"}
_COMPARE = {"GT": ">", "GE": ">=", "EQ": "==", "LE": "<=", "LT": "<"}
_SHIFT = {"SHL": "_shl", "SHR": "_shr", "ROL": "_rol", "ROR": "_ror"}


def _add(*bs: Builtin) -> None:
    for b in bs:
        BUILTINS[b.name] = b


def _text(name: str, params: tuple[str, ...], native: str, args: tuple[str, ...], needs: str,
          result: str = "IN") -> Builtin:
    """A string function typed by its argument kinds."""
    return _B(name, params, "signature", "string_call", min_args=len(params), natives=(native,),
              args=args, needs=needs, result=result)


_add(
    _B("ABS", ("IN",), "number_same", "abs"),
    _B("NEG", ("IN",), "number_same", "neg"),
    *(_B(n, ("IN",), "float", "math", natives=(fn,)) for n, fn in _MATH.items()),
    _B("TRUNC", ("IN",), "to_dint", "to_dint", natives=("_trunc",)),
    _B("ROUND", ("IN",), "to_dint", "to_dint", natives=("_round",)),
    _B("MOVE", ("IN",), "same", "move"),
    _B("EXPT", ("IN1", "IN2"), "expt", "expt", min_args=2, natives=("_expt",)),
    _B("ATAN2", ("Y", "X"), "atan2", "atan2", min_args=2, natives=("_math",)),
    _B("ADD", ("IN1", "IN2"), "arithmetic", "operator", variadic=True, min_args=2, operator="+"),
    _B("MUL", ("IN1", "IN2"), "arithmetic", "operator", variadic=True, min_args=2, operator="*"),
    _B("SUB", ("IN1", "IN2"), "arithmetic", "operator", min_args=2, operator="-"),
    _B("DIV", ("IN1", "IN2"), "arithmetic", "div", min_args=2, natives=("_idiv", "_rdiv")),
    _B("MOD", ("IN1", "IN2"), "arithmetic", "mod", min_args=2, natives=("_imod",)),
    # the bitwise Boolean functions of IEC 61131-3 ed.2 Table 24 / ed.3 Table 31 (items 21-24):
    # AND, OR, XOR are extensible; written as calls by Beremiz for every FBD/LD network
    *(_B(n, ("IN1", "IN2"), "bitwise", "bitwise", variadic=True, min_args=2, operator=op)
      for n, op in (("AND", "&"), ("OR", "|"), ("XOR", "^"))),
    _B("NOT", ("IN",), "bitwise", "not"),
    _B("MIN", ("IN1", "IN2"), "extremum", "extremum", variadic=True, min_args=1),
    _B("MAX", ("IN1", "IN2"), "extremum", "extremum", variadic=True, min_args=1),
    _B("LIMIT", ("MN", "IN", "MX"), "limit", "limit", min_args=3, natives=("_limit",)),
    _B("SEL", ("G", "IN0", "IN1"), "select", "select", min_args=3),
    _B("MUX", ("K", "IN0", "IN1"), "multiplex", "multiplex", variadic=True, min_args=2,
       natives=("_mux",)),
    *(_B(n, ("IN", "N"), "shift", "shift", min_args=2, natives=(fn,)) for n, fn in _SHIFT.items()),
    *(_B(n, ("IN1", "IN2"), "compare", "compare", variadic=True, min_args=2, operator=op)
      for n, op in _COMPARE.items()),
    _B("NE", ("IN1", "IN2"), "compare", "compare", min_args=2, operator="!="),
    _B("LEN", ("IN",), "signature", "len", args=("STRING",), needs="a STRING", result="INT"),
    _text("LEFT", ("IN", "L"), "_left", ("STRING", "INT"), "a STRING and a length"),
    _text("RIGHT", ("IN", "L"), "_right", ("STRING", "INT"), "a STRING and a length"),
    _text("MID", ("IN", "L", "P"), "_mid", ("STRING", "INT", "INT"),
          "a STRING, a length and a position"),
    _B("CONCAT", ("IN1", "IN2"), "concat", "concat", variadic=True, min_args=1),
    _text("INSERT", ("IN1", "IN2", "P"), "_insert", ("STRING", "STRING", "INT"),
          "two STRINGs and a position"),
    _text("DELETE", ("IN", "L", "P"), "_delete", ("STRING", "INT", "INT"),
          "a STRING, a length and a position"),
    _text("REPLACE", ("IN1", "IN2", "L", "P"), "_replace", ("STRING", "STRING", "INT", "INT"),
          "two STRINGs, a length and a position"),
    _text("FIND", ("IN1", "IN2"), "_find", ("STRING", "STRING"), "two STRINGs", result="INT"),
    # the assertions take an optional message last, as other ST test frameworks do
    *(_B(n, ("ACTUAL", "EXPECTED", "MSG"), "assert_compare", "test", min_args=2,
         test_only=True, statement_only=True, natives=("_assert_cmp",))
      for n in ("ASSERT_EQ", "ASSERT_NE")),
    *(_B(n, ("IN", "MSG"), "assert_bool", "test", test_only=True, statement_only=True,
         natives=("_assert_bool",)) for n in ("ASSERT_TRUE", "ASSERT_FALSE")),
    _B("ASSERT_NEAR", ("ACTUAL", "EXPECTED", "TOL", "MSG"), "assert_near", "test", min_args=3,
       test_only=True, statement_only=True, natives=("_assert_near",)),
    _B("ADVANCE_TIME", ("T",), "advance_time", "test", test_only=True, statement_only=True),
    # CODESYS's TIME(): the milliseconds since the PLC started, a TIME (CODESYS online help,
    # *Functions*, "TIME() function"); the other dialects have no such function (PLC0106)
    _B("TIME", (), "system_time", "system_time", min_args=0),
    # the functions of time data types, IEC 61131-3 ed.3 Table 37 (ed.2 Table 30): ``args`` the
    # argument types (NUM: any number), ``operator`` how the emitter combines them
    *(_B(n, ("IN1", "IN2"), "datetime", "datetime", min_args=2, args=args, result=res,
         operator=how, needs=" and ".join("a number" if a == "NUM" else f"a {a}" for a in args))
      for n, args, res, how in (
          ("ADD_TIME", ("TIME", "TIME"), "TIME", "+"),
          ("ADD_TOD_TIME", ("TOD", "TIME"), "TOD", "+"),
          ("ADD_DT_TIME", ("DT", "TIME"), "DT", "+"),
          ("SUB_TIME", ("TIME", "TIME"), "TIME", "-"),
          ("SUB_DATE_DATE", ("DATE", "DATE"), "TIME", "date-"),
          ("SUB_TOD_TIME", ("TOD", "TIME"), "TOD", "-"),
          ("SUB_TOD_TOD", ("TOD", "TOD"), "TIME", "-"),
          ("SUB_DT_TIME", ("DT", "TIME"), "DT", "-"),
          ("SUB_DT_DT", ("DT", "DT"), "TIME", "-"),
          ("MUL_TIME", ("TIME", "NUM"), "TIME", "*"),
          ("DIV_TIME", ("TIME", "NUM"), "TIME", "/"),
          # the ed.2 names (Table 30) of the two above: the matiec dialect only (PLC0320)
          ("MULTIME", ("TIME", "NUM"), "TIME", "*"),
          ("DIVTIME", ("TIME", "NUM"), "TIME", "/"),
          ("CONCAT_DATE_TOD", ("DATE", "TOD"), "DT", "date+tod"))),
)

# BCD conversions, IEC 61131-3 ed.3 Table 22 (items 1-2: ``WORD_BCD_TO_UINT``,
# ``UINT_TO_BCD_WORD``) and the ed.2 / CODESYS names ``BCD_TO_INT``, ``INT_TO_BCD`` (the BCD
# width follows the integer's: SINT/USINT BYTE, INT/UINT WORD, ...). Invalid digits: see the
# helpers ``_bcd_to_int`` and ``_int_to_bcd`` (the target's maximum; all ones).
_WIDTH = {8: "BYTE", 16: "WORD", 32: "DWORD", 64: "LWORD"}
_INTS = ("SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT")
_add(
    *(_B(f"BCD_TO_{n}", ("IN",), "signature", "bcd", natives=("_bcd_to_int",), args=("BITS",),
         needs="a bit string (BYTE, WORD, DWORD, LWORD) holding BCD digits", result=n)
      for n in _INTS),
    *(_B(f"{n}_TO_BCD", ("IN",), "signature", "bcd", natives=("_int_to_bcd",), args=("INT",),
         needs="an integer", result=_WIDTH[T.ELEMENTARY[n].bits]) for n in _INTS),
    *(_B(f"{w}_BCD_TO_{n}", ("IN",), "signature", "bcd", natives=("_bcd_to_int",),
         args=("BITS",), needs="a bit string holding BCD digits", result=n)
      for w, n in (("BYTE", "USINT"), ("WORD", "UINT"), ("DWORD", "UDINT"), ("LWORD", "ULINT"))),
    *(_B(f"{n}_TO_BCD_{w}", ("IN",), "signature", "bcd", natives=("_int_to_bcd",),
         args=("INT",), needs="an integer", result=w)
      for w, n in (("BYTE", "USINT"), ("WORD", "UINT"), ("DWORD", "UDINT"), ("LWORD", "ULINT"))),
)

_STD, _CTRL = "stdlib.st", "ctrllib.st"
BLOCKS: dict[str, Block] = {b.name: b for b in (
    # IEC 61131-3 2.5.2.3: bistables, edge detection, counters, timers (TONR: plclab's own);
    # il_inputs: the FB input operators of IEC 61131-3 ed.2 Table 53 (S, R, LD also name IL ops)
    Block("SR", _STD, ("S1", "Q1"), ("S1", "R")),
    Block("RS", _STD, ("S", "Q1"), ("S", "R1")),
    Block("R_TRIG", _STD, ("CLK", "Q"), ("CLK",)),
    Block("F_TRIG", _STD, ("CLK", "Q"), ("CLK",)),
    Block("CTU", _STD, ("CU", "Q"), ("CU", "R", "PV")),
    Block("CTD", _STD, ("CD", "Q"), ("CD", "LD", "PV")),
    Block("CTUD", _STD, ("CU", "QU"), ("CU", "CD", "R", "LD", "PV")),
    Block("TP", _STD, ("IN", "Q"), ("IN", "PT")),
    Block("TON", _STD, ("IN", "Q"), ("IN", "PT")),
    Block("TOF", _STD, ("IN", "Q"), ("IN", "PT")),
    Block("TONR", _STD, ("IN", "Q"), ("IN", "PT")),
    # the typed counters of IEC 61131-3 ed.3 Table 45 (CV and PV of the named type)
    *(Block(f"{base}_{t}", _STD, power, ops) for base, power, ops in (
        ("CTU", ("CU", "Q"), ("CU", "R", "PV")), ("CTD", ("CD", "Q"), ("CD", "LD", "PV")),
        ("CTUD", ("CU", "QU"), ("CU", "CD", "R", "LD", "PV")))
      for t in ("INT", "DINT", "LINT", "UDINT", "ULINT")),
    # the real-time clock of IEC 61131-3 ed.1 Table 35 (MATIEC lib/rtc.txt; ADR 0037: only in
    # the iec and matiec dialects, see plclab.project.keep_rtc)
    Block("RTC", _STD, ("IN", "Q"), ("IN",)),
    # control blocks (a ladder box takes its first BOOL input and output)
    *(Block(n, _CTRL) for n in ("PID", "PID_INC", "HYST", "AI_SCALE", "AO_SCALE", "DEBOUNCE",
                                "BLINKER", "RAMP", "PT1", "MOVING_AVG", "LIMIT_ALARM")),
)}

# derived: the power-flow pins of a ladder box, the IL input operators
POWER_PINS: dict[str, tuple[str, str]] = {b.name: b.power for b in BLOCKS.values() if b.power}
FB_INPUT_OPS: tuple[str, ...] = tuple(dict.fromkeys(op for b in BLOCKS.values()
                                                    for op in b.il_inputs))

# the ed.2 name of a function -> its ed.3 name, known only where ``Dialect.ed2_time_names``
ED2_NAMES: dict[str, str] = {"MULTIME": "MUL_TIME", "DIVTIME": "DIV_TIME"}

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
