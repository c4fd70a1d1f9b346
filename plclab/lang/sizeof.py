"""``SIZEOF(x)``: the bytes a variable or a data type takes, as CODESYS lays it out.

CODESYS (online help, "Operator SIZEOF"; Beckhoff InfoSys, "SIZEOF"): an extension of IEC
61131-3 giving "the number of bytes required by the variable x", as a constant whose type is the
smallest unsigned type that holds it (USINT below 256, UINT below 65536, UDINT, then ULINT);
``SIZEOF(ARRAY[0..4] OF INT)`` is 10. Elementary types take their width (BOOL one byte),
STRING(n) n + 1 bytes and WSTRING(n) 2(n + 1), an enumeration its base type, an array its
elements. A structure is laid out with natural alignment, the default of CODESYS targets: each
member at an offset that is a multiple of its own alignment (its width, at most 8; a string's
character; an array's element; a structure's largest member), the whole rounded up to the
largest alignment. Function block instances, interfaces and references hold code pointers
whose size depends on the target, so plclab gives no size for them (None).

>>> from plclab.lang import types as T
>>> sizeof(T.ArrayType([(0, 4)], T.INT)), sizeof(T.StringType(False, 80)), sizeof(T.LREAL)
(10, 81, 8)
>>> sizeof_type(300).name, sizeof_type(10).name
('UINT', 'USINT')
"""

from __future__ import annotations

from . import types as T


def _layout(t: T.Type) -> tuple[int, int] | None:
    """(size, alignment) of ``t`` in bytes, or None when the target decides it."""
    t = T.resolve(t)
    if isinstance(t, T.StringType):
        ch = 2 if t.wide else 1
        return (t.length + 1) * ch, ch
    if isinstance(t, T.EnumType):
        return _layout(t.base)
    if isinstance(t, T.Subrange):
        return _layout(T.base_of(t))
    if isinstance(t, T.ArrayType):
        inner = _layout(t.elem)
        return None if inner is None else (inner[0] * t.size, inner[1])
    if isinstance(t, T.StructType):
        offset, align = 0, 1
        for d in t.fields.values():
            m = _layout(d.ty)
            if m is None:
                return None
            offset = -(-offset // m[1]) * m[1] + m[0]
            align = max(align, m[1])
        return -(-offset // align) * align, align
    if isinstance(t, T.Elementary) and t.kind != "special" and t.bits:
        n = max(1, t.bits // 8)
        return n, min(n, 8)
    return None


def sizeof(t: T.Type) -> int | None:
    """The bytes of a variable of type ``t`` (None: not given for this type)."""
    lay = _layout(t)
    return None if lay is None else lay[0]


def sizeof_type(n: int) -> T.Elementary:
    """The type of the constant ``SIZEOF`` gives for ``n`` bytes."""
    for t in (T.USINT, T.UINT, T.UDINT):
        if n <= t.hi:
            return t
    return T.ULINT
