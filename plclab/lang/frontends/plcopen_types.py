"""The data types and variables of the PLCopen XML reader: ``types/dataTypes``, type
references, initial values and the variable sections of an interface (a mixin of the importer
in :mod:`plclab.lang.frontends.plcopen`).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from .. import ast as A
from ..addresses import canonical
from ..datasize import NESTING_LIMIT
from ..dialect import current as current_dialect
from .plcopen_base import IGNORED, SECTIONS, Bad, local_name

_ELEMENTARY = {"BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT",
               "UINT", "UDINT", "ULINT", "REAL", "LREAL", "TIME", "LTIME", "DATE", "DT", "TOD",
               "LDATE", "LDT", "LTOD"}


class TypeRead:
    """Data types and variables (a mixin of the importer)."""

    # -- types ------------------------------------------------------------------------------
    def data_type(self, dt: ET.Element) -> None:
        name = self.ident(dt.get("name"), dt, "data type name")
        base = self.kid(dt, "baseType")
        if base is None:
            self.fail("PLC0183", f"data type {name} has no <baseType>", dt)
        tref = self.type_ref(base)
        init = None
        iv = self.kid(dt, "initialValue")
        if iv is not None:
            init = self.init_value(iv)
        self.out.types.append(A.TypeDecl(self.loc(dt), name.upper(), tref, init, name))

    def type_ref(self, holder: ET.Element) -> A.TypeRef:
        """The type inside ``<type>`` / ``<baseType>``; nested at most NESTING_LIMIT levels
        (arrays, structures, subranges in each other), like ST (PLC0124)."""
        depth = getattr(self, "_type_depth", 0)
        if depth >= NESTING_LIMIT:
            self.fail("PLC0124", f"this type is nested more than {NESTING_LIMIT} levels deep; "
                      "declare the inner levels as named data types with fewer levels", holder)
        self._type_depth = depth + 1
        try:
            return self._type_ref(holder)
        finally:
            self._type_depth = depth

    def _type_ref(self, holder: ET.Element) -> A.TypeRef:
        kids = [k for k in self.kids(holder) if local_name(k.tag) not in IGNORED]
        if not kids:
            self.fail("PLC0183", f"<{local_name(holder.tag)}> names no type", holder)
        t = kids[0]
        tag = local_name(t.tag)
        loc = self.loc(t)
        if tag.upper() in _ELEMENTARY and tag not in ("string", "wstring"):
            return A.NamedTypeRef(loc, tag.upper())
        if tag in ("string", "wstring"):
            length = t.get("length")
            ln = A.Literal(loc, int(length), "INT", None, length) if length and \
                length.isdigit() else None
            return A.StringTypeRef(loc, tag == "wstring", ln)
        if tag == "derived":
            name = self.ident(t.get("name"), t, "type name").upper()
            if name == "LOGLEVEL" and self.loglevel_used is None:
                self.loglevel_used = t
            return A.NamedTypeRef(loc, name)
        if tag == "array":
            ranges = []
            for d in self.kids(t, "dimension"):
                lo, hi = d.get("lower"), d.get("upper")
                ranges.append((self.expr(lo, d, "lower bound"), self.expr(hi, d, "upper bound")))
            bt = self.kid(t, "baseType")
            if bt is None or not ranges:
                self.fail("PLC0183", "<array> needs <dimension lower upper> and <baseType>", t)
            return A.ArrayTypeRef(loc, ranges, self.type_ref(bt))
        if tag == "enum":
            vals = self.kid(t, "values")
            members = []
            for v in self.kids(vals, "value") if vals is not None else []:
                vn = self.ident(v.get("name"), v, "enumeration value")
                ve = self.expr(v.get("value"), v, "value") if v.get("value") else None
                members.append((vn.upper(), ve, self.loc(v)))
            bt = self.kid(t, "baseType")
            return A.EnumTypeRef(loc, members, self.type_ref(bt) if bt is not None else None)
        if tag == "struct":
            return A.StructTypeRef(loc, [self.variable(v, "VAR") for v in self.kids(t, "variable")])
        if tag in ("subrangeSigned", "subrangeUnsigned"):
            rng = self.kid(t, "range")
            bt = self.kid(t, "baseType")
            if rng is None or bt is None:
                self.fail("PLC0183", f"<{tag}> needs <range lower upper> and <baseType>", t)
            return A.SubrangeTypeRef(loc, self.type_ref(bt), self.expr(rng.get("lower"), rng,
                                     "lower bound"), self.expr(rng.get("upper"), rng,
                                                               "upper bound"))
        self.fail("PLC0181", f"the type <{tag}> is not supported by plclab", t)
        raise AssertionError

    def init_value(self, iv: ET.Element, tref: A.TypeRef | None = None) -> A.Expr:
        kids = self.kids(iv)
        if not kids:
            self.fail("PLC0183", "<initialValue> is empty", iv)
        v = kids[0]
        tag = local_name(v.tag)
        if isinstance(tref, A.ArrayTypeRef):
            tref = tref.elem
        if tag == "simpleValue":
            value = v.get("value")
            if isinstance(tref, A.StringTypeRef) and value is not None and \
                    not re.match(r"^\s*(['\"]|W?STRING#)", value, re.I):
                # Beremiz writes a STRING's initial value unquoted (value="hello") and quotes
                # it when it generates ST: read it as the string it is (ADR 0053)
                value = _quote(value, tref.wide)
            return self.expr(value, v, "value")
        if tag == "arrayValue":
            items: list[tuple[A.Expr | None, A.Expr]] = []
            for item in self.kids(v, "value"):
                rep = item.get("repetitionValue")
                rep_e = A.Literal(self.loc(item), int(rep), "INT", None, rep) if rep and \
                    rep.isdigit() else None
                items.append((rep_e, self.init_value(item, tref)))
            return A.ArrayInit(self.loc(v), items)
        if tag == "structValue":
            fields = []
            for item in self.kids(v, "value"):
                m = self.ident(item.get("member"), item, "structure member")
                fields.append((m.upper(), self.init_value(item), self.loc(item)))
            return A.StructInit(self.loc(v), fields)
        self.fail("PLC0181", f"the initial value <{tag}> is not supported", v)
        raise AssertionError

    def variable(self, v: ET.Element, section: str, constant: bool = False,
                 retain: bool = False) -> A.VarDecl:
        name = self.ident(v.get("name"), v, "variable name")
        t = self.kid(v, "type")
        if t is None:
            self.fail("PLC0183", f"variable {name} has no <type>", v)
        tref = self.type_ref(t)
        iv = self.kid(v, "initialValue")
        init = self.init_value(iv, tref) if iv is not None else None
        addr = v.get("address")
        if addr is not None:
            addr = canonical(addr, current_dialect().hierarchical_words)
            if not re.match(r"^%[IQM][XBWDL]?[0-9]+(\.[0-9]+)*$|^%[IQM]\*$", addr):
                self.fail("PLC0183", f"variable {name}: {addr!r} is not a direct address such "
                          "as %IX0.0", v)
        return A.VarDecl(self.loc(v), name.upper(), tref, init, addr, section, constant, retain,
                         name)

    def var_sections(self, holder: ET.Element, allowed: set[str]) -> list[A.VarDecl]:
        out: list[A.VarDecl] = []
        for sec in self.kids(holder):
            tag = local_name(sec.tag)
            if tag in IGNORED or tag == "returnType":
                continue
            if tag not in SECTIONS or SECTIONS[tag] not in allowed:
                self.err("PLC0181", f"the variable section <{tag}> is not supported here", sec)
                continue
            constant = sec.get("constant") in ("true", "1")
            retain = sec.get("retain") in ("true", "1") or sec.get("persistent") in ("true", "1")
            for v in self.kids(sec, "variable"):
                if self.beremiz_instance(v):
                    continue
                try:
                    out.append(self.variable(v, SECTIONS[tag], constant, retain))
                except Bad:
                    pass
        return out

    def beremiz_instance(self, v: ET.Element) -> bool:
        """A variable whose type is a Beremiz runtime block: warned about and left out."""
        t = self.kid(v, "type")
        d = self.kid(t, "derived") if t is not None else None
        if d is None or (d.get("name") or "").upper() not in self.runtime_only:
            return False
        self.warn_beremiz(d.get("name") or "", v)
        self.dropped.add((v.get("name") or "").upper())
        return True


def _quote(text: str, wide: bool) -> str:
    """``hello`` -> ``'hello'`` (``"hello"`` for a WSTRING), with IEC escapes for ``$``, the
    quote and control characters, so the ST lexer reads back exactly ``text``."""
    q = '"' if wide else "'"
    out = []
    for ch in text:
        if ch in ("$", q):
            out.append("$" + ch)
        elif ch == "\n":
            out.append("$N")
        elif ch == "\t":
            out.append("$T")
        elif ch == "\r":
            out.append("$R")
        elif ord(ch) < 32:
            out.append(f"${ord(ch):02X}")
        else:
            out.append(ch)
    return q + "".join(out) + q

