"""Dialects: what differs between strict IEC 61131-3, CODESYS, TIA Portal (S7) and MATIEC.

A file's dialect is, first found: its ``{dialect 'NAME'}`` pragma, the dialect the caller gives
(``plclab check --dialect``, ``plclab.load(..., dialect=...)``, ``dialect`` in ``lab.toml``), the
tool that wrote it (a PLCopen XML file from Beremiz or OpenPLC Editor is ``matiec``: its
``fileHeader``, or a ``beremiz.xml`` project file beside it; :func:`origin`), or
:data:`DEFAULT`. ADR 0017 says why the default is ``codesys``; the README's compliance list has the
table of differences.

>>> profile("s7").operand_width, profile("codesys").operand_width
(True, False)
>>> dialect_pragma("{dialect 'iec'}\\nPROGRAM P END_PROGRAM")
'iec'
"""

from __future__ import annotations

import os
import re
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

from ..errors import Location, PlcError

__all__ = ["Dialect", "PROFILES", "DEFAULT", "profile", "current", "using", "dialect_pragma",
           "choose", "explain_choice", "origin", "without_pragma"]


@dataclass(frozen=True)
class Dialect:
    """One profile: each field a point where the dialects differ."""

    name: str
    title: str
    type_semicolon_optional: bool  # `END_STRUCT END_TYPE` without `;` (CODESYS, TIA Portal)
    bit_arithmetic: bool  # BYTE/WORD/DWORD in arithmetic, FOR counters, indices: warn, not error
    qualified_enums: bool  # `Color.Red` as well as `Color#Red`
    nested_comments: bool  # `(* (* *) *)` is one comment (ed.3, CODESYS V3)
    operand_width: bool  # integer intermediates wrap to the operand type (S7), not exact
    # TIME <-> number conversions count seconds (MATIEC: TIME_TO_REAL(T#1500ms) = 1.5), not
    # milliseconds (CODESYS, TIA Portal: 1500.0)
    time_in_seconds: bool = False
    # a POU whose END_PROGRAM / END_FUNCTION_BLOCK / END_FUNCTION is missing at the end of the
    # file or before the next POU: the CODESYS editor shows none, so copied code has none
    # (PLC0280, a warning); elsewhere it is the syntax error PLC0010
    end_keyword_optional: bool = False
    # ``TIME()``: the milliseconds since the PLC started (CODESYS online help, *Functions*,
    # "TIME() function"); elsewhere PLC0106
    system_time: bool = False
    # ``%IW0.1``: a two-field address of a byte/word/double word is hierarchical (module 0,
    # item 1), read by its last field with PLC0175, as MATIEC and Beremiz write it; CODESYS
    # and S7 have no such form (PLC0120: a '.bit' part on a word)
    hierarchical_words: bool = False
    # ``i := r;``: a REAL or LREAL stored in an integer variable without a conversion compiles
    # with the warning PLC0283 and rounds as REAL_TO_INT does (CODESYS compiles it with a
    # message; ADR 0035); elsewhere it is PLC0118
    implicit_real_to_int: bool = False
    # ``i := d;`` / ``cnt := n;``: an integer or bit string stored in an integer or bit string
    # it does not widen to (DINT into INT, INT into BYTE, UINT into INT) compiles with the
    # warning PLC0285 and wraps as DINT_TO_INT does: CODESYS accepts such an implicit
    # conversion and only warns about the sign (C0195, C0196); elsewhere it is PLC0118
    implicit_int_conversion: bool = False
    # ``SIZEOF(x)``: the bytes of a variable or a type, a constant (CODESYS online help,
    # "Operator SIZEOF"; :mod:`plclab.lang.sizeof`); elsewhere PLC0106
    sizeof: bool = False
    # ``ACTIONS Pou ACTION A ... END_ACTION END_ACTIONS`` and ``ACTION Pou.A ... END_ACTION``:
    # actions of a PROGRAM or FUNCTION_BLOCK (CODESYS "Object: Action"; the text form of RuSTy
    # and blark), called ``inst.A(...)``, ``Prog.A()`` or ``A()`` inside; elsewhere PLC0198
    pou_actions: bool = False
    # ``REFERENCE TO T`` with ``r REF= x`` (CODESYS online help, "Reference";
    # :mod:`plclab.lang.lower.reference_to`); elsewhere PLC0239
    reference_to: bool = False
    # ``%IX0.0 := TRUE`` or an assignment to a variable AT %I: MATIEC compiles it (a located
    # input is a variable of the process image to its C code) and the next input read
    # overwrites the value: the warning PLC0284; elsewhere the error PLC0105 (ADR 0037)
    input_writes: bool = False
    # ``i := TRUNC(r) + 1`` with ``i : INT``: TRUNC (and ROUND) return ANY_INT typed by their
    # context, as IEC 61131-3 ed.2 Table 22 gives ``ANY_REAL -> ANY_INT`` and MATIEC infers
    # it (INT here, the conversion's source in ``INT_TO_WORD(TRUNC(r))``); DINT where the
    # context names no integer. CODESYS and TIA Portal: always DINT (ADR 0052)
    trunc_by_context: bool = False
    # ``MULTIME`` / ``DIVTIME``: the ed.2 names (Table 30) of MUL_TIME / DIV_TIME, which MATIEC
    # and OSCAT use; ed.3 and CODESYS know only MUL_TIME / DIV_TIME
    ed2_time_names: bool = False
    # ``VAR CONSTANT N : INT; END_VAR``: a constant without a value has its type's default
    # initial value (IEC 61131-3 ed.2 2.4.2, ed.3 6.5.1.3: the grammar makes the value optional;
    # MATIEC compiles it); CODESYS and TIA Portal require a value (PLC0109)
    constant_default: bool = False
    # the largest task PRIORITY: CODESYS 0..31; IEC 61131-3 bounds it by nothing but the
    # integer (0 the most urgent) and MATIEC takes any, e.g. PRIORITY := 90: 0..65535 (UINT)
    max_priority: int = 31
    # ``r := EXPT(n, 1.5) * 0.836;`` with ``r : REAL``: an expression that is LREAL only through
    # untyped real literals is stored in REAL with the warning PLC0290 (CODESYS types a literal
    # by its context; ADR 0051); elsewhere PLC0118 (IEC: an untyped real literal is LREAL)
    literal_context: bool = False
    # ``pt := REF(X); REAL_TO_DW := pt^;`` in a FUNCTION (OSCAT): REF of a local of the call,
    # kept in a local reference that does not outlive it, and a REF_TO DWORD to a REAL reading
    # its bits (PLC0291; ADR 0051); elsewhere PLC0240 and PLC0241 (IEC ed.3 6.4.4.10: no REF
    # of a temporary, a reference of its own type only)
    local_refs: bool = False
    reinterpret_refs: bool = False
    # ``VAR_IN_OUT a : ARRAY[*] OF INT`` with LOWER_BOUND / UPPER_BOUND: variable-length arrays
    # of IEC 61131-3 ed.3 (6.5.3), CODESYS V3 and TIA Portal (S7-1500); ed.2 and MATIEC have
    # none (PLC0351; ADR 0060)
    var_length_arrays: bool = True
    # ``inst.local := x`` / ``y := inst.local`` with ``local`` a VAR of the block: MATIEC checks
    # only that no output is assigned (stage3/lvalue_check.cc), so OpenPLC programs do it: the
    # warning PLC0353; elsewhere PLC0121 (only inputs and outputs are visible outside)
    fb_internal_access: bool = False


PROFILES: dict[str, Dialect] = {d.name: d for d in (
    Dialect("iec", "IEC 61131-3 ed.3, strict", False, False, False, True, False,
            hierarchical_words=True, trunc_by_context=True, constant_default=True,
            max_priority=65535),
    Dialect("codesys", "CODESYS V3 (the textbook's examples)", True, True, True, True, False,
            end_keyword_optional=True, system_time=True, implicit_real_to_int=True,
            implicit_int_conversion=True, literal_context=True,
            local_refs=True, reinterpret_refs=True,
            sizeof=True, pou_actions=True, reference_to=True),
    Dialect("s7", "Siemens TIA Portal SCL (S7-1200/1500)", True, True, False, False, True),
    Dialect("matiec", "MATIEC / Beremiz (IEC ed.2)", False, False, False, False, False, True,
            hierarchical_words=True, input_writes=True, trunc_by_context=True,
            ed2_time_names=True, constant_default=True, max_priority=65535,
            var_length_arrays=False, fb_internal_access=True),
)}
DEFAULT = "codesys"

_CURRENT: ContextVar[str] = ContextVar("plclab_dialect", default=DEFAULT)
_PRAGMA = re.compile(r"\{\s*dialect\s+'?([A-Za-z0-9_]+)'?\s*\}", re.IGNORECASE)


def profile(name: str | None = None) -> Dialect:
    """The profile called ``name`` (the current one for None); PLC0170 for an unknown name."""
    key = (name or _CURRENT.get()).lower()
    d = PROFILES.get(key)
    if d is None:
        raise PlcError("PLC0170", f"unknown dialect '{name}'; choose one of "
                       f"{', '.join(PROFILES)}")
    return d


def current() -> Dialect:
    """The dialect of the file being read (see :func:`using`)."""
    return PROFILES[_CURRENT.get()]


@contextmanager
def using(name: str):
    """Read (lex and parse) a file in the dialect ``name``."""
    token = _CURRENT.set(profile(name).name)
    try:
        yield
    finally:
        _CURRENT.reset(token)


def without_pragma(text: str) -> str:
    """``text`` with its ``{dialect}`` pragmas blanked (same lines and columns)."""
    return _PRAGMA.sub(lambda m: " " * len(m.group(0)), text)


def dialect_pragma(text: str) -> str | None:
    """The name in a file's ``{dialect 'NAME'}`` pragma, or None."""
    m = _PRAGMA.search(text)
    return m.group(1).lower() if m else None


_HEADER = re.compile(r"<fileHeader\b[^>]*>", re.IGNORECASE)
_ATTR = re.compile(r"""\b(companyName|productName)\s*=\s*["']([^"']*)["']""", re.IGNORECASE)
# PLCopen editor defaults: Beremiz's and OpenPLC Editor's new project ("Unknown", "Unnamed")
_MATIEC_WRITERS = ("beremiz", "openplc", "plcopeneditor")


def origin(text: str, file: str = "<input>") -> tuple[str, str] | None:
    """The dialect of a PLCopen XML file from the tool that wrote it, with the reason, or None.

    Beremiz and OpenPLC Editor compile with MATIEC, so their files are read as ``matiec``
    (``%QD0.2``, ed.2 rules). Their ``fileHeader`` names Beremiz, OpenPLC or the editor's
    defaults (company "Unknown", product "Unnamed"); a Beremiz project also has a
    ``beremiz.xml`` beside its ``plc.xml``.

    >>> origin('<project><fileHeader companyName="Beremiz" productName="Beremiz"/></project>')
    ('matiec', 'its PLCopen fileHeader names Beremiz')
    >>> origin('<fileHeader companyName="CODESYS" productName="CODESYS"/>') is None
    True
    """
    if not file.lower().endswith(".xml") and not text.lstrip().startswith("<"):
        return None
    head = _HEADER.search(text[:4096])
    if head:
        attrs = {k.lower(): v.strip() for k, v in _ATTR.findall(head.group(0))}
        values = " ".join(attrs.values()).lower()
        for w in _MATIEC_WRITERS:
            if w in values:
                who = next(v for v in attrs.values() if w in v.lower())
                return "matiec", f"its PLCopen fileHeader names {who}"
        if attrs.get("companyname") == "Unknown" and attrs.get("productname") == "Unnamed":
            return "matiec", ("its PLCopen fileHeader has the Beremiz / OpenPLC Editor defaults "
                              "(Unknown, Unnamed)")
    folder = os.path.dirname(file)
    if file.lower().endswith(".xml") and folder and os.path.isfile(
            os.path.join(folder, "beremiz.xml")):
        return "matiec", "a Beremiz project file (beremiz.xml) lies beside it"
    return None


def explain_choice(text: str, given: str | None, file: str = "<input>") -> tuple[str, str]:
    """A file's dialect and why: its pragma, else ``given``, else the tool that wrote it
    (:func:`origin`), else :data:`DEFAULT` (PLC0170 if a pragma or ``given`` is unknown)."""
    named = dialect_pragma(text)
    if not named and not given:
        return origin(text, file) or (DEFAULT, "the default, ADR 0017")
    why = "its {dialect} pragma" if named else "chosen by the caller (--dialect or the lab)"
    try:
        return profile(named or given).name, why
    except PlcError as exc:
        where = None
        if named:
            line = text[:_PRAGMA.search(text).start()].count("\n") + 1
            where = Location(file, line, 1)
        raise PlcError(exc.code, exc.message, where) from None


def choose(text: str, given: str | None, file: str = "<input>") -> str:
    """A file's dialect (:func:`explain_choice` without the reason)."""
    return explain_choice(text, given, file)[0]
