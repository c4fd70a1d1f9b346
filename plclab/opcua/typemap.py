"""IEC 61131-3 types as OPC UA built-in types, and values from one to the other (ADR 0055).

The PLC keeps TIME in milliseconds, LTIME in nanoseconds, DATE in seconds and DT in
milliseconds since 1970, TOD in milliseconds after midnight (:mod:`plclab.runtime`). OPC UA
shows TIME, LTIME and TOD as ``Duration`` (a Double of milliseconds, the type OPC UA itself
uses for intervals), DATE and DT as ``DateTime``.

>>> kind_of("INT"), kind_of("REAL"), kind_of("TIME")
('Int16', 'Float', 'Duration')
"""

from __future__ import annotations

import datetime as _dt
import math
from typing import Any

from plclab.lang import types as T

# IEC elementary type -> OPC UA built-in type name (a ua.VariantType, or Duration/DateTime)
KINDS: dict[str, str] = {
    "BOOL": "Boolean",
    "SINT": "SByte", "INT": "Int16", "DINT": "Int32", "LINT": "Int64",
    "USINT": "Byte", "UINT": "UInt16", "UDINT": "UInt32", "ULINT": "UInt64",
    "BYTE": "Byte", "WORD": "UInt16", "DWORD": "UInt32", "LWORD": "UInt64",
    "REAL": "Float", "LREAL": "Double",
    "TIME": "Duration", "LTIME": "Duration", "TOD": "Duration",
    "DATE": "DateTime", "DT": "DateTime",
}
# milliseconds of one unit of the PLC's representation
_TIME_SCALE = {"TIME": 1.0, "LTIME": 1e-6, "TOD": 1.0}
_EPOCH = _dt.datetime(1970, 1, 1, tzinfo=_dt.UTC)


def elementary_name(ty: Any) -> str | None:
    """The elementary IEC name behind ``ty`` (aliases, subranges and enums resolved), or None
    for a string, an aggregate or a reference."""
    r = T.resolve(ty)
    if isinstance(r, T.Subrange):
        r = r.base
    if isinstance(r, T.EnumType):
        r = r.base
    if isinstance(r, T.Elementary) and r.name in KINDS:
        return r.name
    return None


def kind_of(ty: Any) -> str | None:
    """The OPC UA type name of a scalar IEC type (``"Int16"``, ``"String"``), or None."""
    if isinstance(ty, str):
        ty = T.lookup_elementary(ty) or ty
        if isinstance(ty, str):
            return None
    r = T.resolve(ty)
    if isinstance(r, T.StringType):
        return "String"
    name = elementary_name(r)
    return KINDS.get(name) if name else None


def variant_type(kind: str):
    """The asyncua ``ua.VariantType`` of an OPC UA type name (Duration is a Double)."""
    from asyncua import ua

    return ua.VariantType.Double if kind == "Duration" else getattr(ua.VariantType, kind)


def data_type_id(kind: str):
    """The NodeId of the OPC UA DataType (Duration: i=290, a subtype of Double)."""
    from asyncua import ua

    return ua.NodeId(getattr(ua.ObjectIds, kind))


def to_ua(value: Any, ty: Any) -> Any:
    """A PLC value as the Python value asyncua sends for the OPC UA type of ``ty``."""
    name = elementary_name(ty)
    if name is None:
        return str(value) if isinstance(value, str) else value
    if name in _TIME_SCALE:
        return float(value) * _TIME_SCALE[name]
    if name == "DATE":
        return _EPOCH + _dt.timedelta(seconds=int(value))
    if name == "DT":
        return _EPOCH + _dt.timedelta(milliseconds=int(value))
    if name in ("REAL", "LREAL"):
        return float(value)
    if name == "BOOL":
        return bool(value)
    return int(value)


def from_ua(value: Any, ty: Any) -> Any:
    """A value a client wrote, as the PLC keeps it for ``ty``; ValueError when it does not fit
    (out of range, not finite, the wrong kind)."""
    r = T.resolve(ty)
    if isinstance(r, T.StringType):
        if not isinstance(value, str):
            raise ValueError("a string")
        if len(value) > r.length:
            raise ValueError(f"at most {r.length} characters")
        return value
    name = elementary_name(r)
    if name is None:
        raise ValueError("a value this server cannot write")
    if name == "BOOL":
        if not isinstance(value, bool):
            raise ValueError("TRUE or FALSE")
        return value
    if isinstance(value, bool):
        raise ValueError(f"a number, not {value}")
    if name in _TIME_SCALE:
        if not isinstance(value, int | float) or not math.isfinite(value):
            raise ValueError("a finite duration in milliseconds")
        return int(round(value / _TIME_SCALE[name]))
    if name in ("DATE", "DT"):
        if not isinstance(value, _dt.datetime):
            raise ValueError("a DateTime")
        if value.tzinfo is None:
            value = value.replace(tzinfo=_dt.UTC)
        ms = int((value - _EPOCH).total_seconds() * 1000)
        return ms // 1000 if name == "DATE" else ms
    if name in ("REAL", "LREAL"):
        if not isinstance(value, int | float) or not math.isfinite(value):
            raise ValueError("a finite number")
        return float(value)
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if not isinstance(value, int):
        raise ValueError("a whole number")
    lo, hi = _limits(r)
    if not lo <= value <= hi:
        raise ValueError(f"a whole number from {lo} to {hi}")
    return value


def _limits(r: Any) -> tuple[int, int]:
    if isinstance(r, T.Subrange):
        return r.lo, r.hi
    if isinstance(r, T.EnumType):
        return min(r.members.values()), max(r.members.values())
    return r.lo, r.hi
