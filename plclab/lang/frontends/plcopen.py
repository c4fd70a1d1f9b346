"""PLCopen XML (TC6 XML v2.01) importer: projects exported by OpenPLC Editor, Beremiz or CODESYS
-> the shared AST.

What is read:

* ``types/dataTypes``: enumerations, structures, arrays, subranges, aliases (``derived``);
* ``types/pous``: programs, function blocks and functions with their interface
  (``inputVars`` ``outputVars`` ``inOutVars`` ``localVars`` ``tempVars`` ``externalVars``,
  ``constant``/``retain``, addresses, initial values) and a body in
  **ST** or **IL** (text, parsed by the ST and IL front ends, errors located in the XML file),
  **LD** (``leftPowerRail``, ``rightPowerRail``, ``contact``, ``coil``, ``block``,
  ``inVariable``, ``outVariable``, ``inOutVariable``, ``connector``/``continuation``,
  ``jump``, ``label``, ``return``, joined by ``connection refLocalId``) or **FBD** (the same
  without rails, contacts and coils); block pins may be ``negated`` or edge-triggered, pin
  names are read in any case; ``comment`` and ``addData`` are skipped;
* ``instances/configurations``: global variables, resources, tasks and program instances.

Beremiz runtime blocks (``LOGGER``, ``python_eval``...) are left out with the warning
``PLC0250``. Anything else (SFC bodies, actions, action blocks...) is reported as ``PLC0181``
naming the element, its ``localId`` and position. Locations are ``file.xml:line:col`` of the
XML element (or of the line inside an ST/IL body). The execution order of a network is
:func:`plclab.lang.lower.network.execution_order` (ADR 0022).

>>> f, diags = parse_plcopen_collect('''<project xmlns="http://www.plcopen.org/xml/tc6_0201">
... <types><pous><pou name="P" pouType="program"><interface><localVars>
...   <variable name="a"><type><BOOL/></type></variable></localVars></interface>
...   <body><ST><![CDATA[a := NOT a;]]></ST></body></pou></pous></types></project>''', "p.xml")
>>> diags, f.pous[0].name, type(f.pous[0].body[0]).__name__
([], 'P', 'Assign')
>>> parse_plcopen_collect("<oops>", "bad.xml")[1][0].code
'PLC0180'
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
import xml.parsers.expat as expat

from ...errors import Diagnostic, Location, PlcError
from .. import ast as A
from ..addresses import canonical
from ..datasize import NESTING_LIMIT
from ..dialect import current as current_dialect
from ..lexer import identifier_problem
from ..lower.network import Elem, plan_feedback
from ..parsing import ParseAbort
from .il_lines import parse_il_body
from .st import Parser, lower_alone

NS = "http://www.plcopen.org/xml/tc6_0201"
_NAMESPACES = (NS, "http://www.plcopen.org/xml/tc6_0200", "http://www.plcopen.org/xml/tc6.xsd")
_ELEMENTARY = {"BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT",
               "UINT", "UDINT", "ULINT", "REAL", "LREAL", "TIME", "LTIME", "DATE", "DT", "TOD",
               "LDATE", "LDT", "LTOD"}
_SECTIONS = {"inputVars": "VAR_INPUT", "outputVars": "VAR_OUTPUT", "inOutVars": "VAR_IN_OUT",
             "localVars": "VAR", "tempVars": "VAR_TEMP", "externalVars": "VAR_EXTERNAL",
             "globalVars": "VAR_GLOBAL"}
_POU_KINDS = {"program": "PROGRAM", "functionBlock": "FUNCTION_BLOCK", "function": "FUNCTION"}
_IGNORED = {"documentation", "addData", "comment"}
# Beremiz runtime blocks (its py_ext and logging plugins): no plclab equivalent, skipped (PLC0250)
BEREMIZ_ONLY = {"LOGGER", "PYTHON_EVAL", "PYTHON_POLL", "PYTHON_GEAR"}
MAX_BOX_CHAIN = 100  # function boxes feeding each other directly in one LD/FBD network


class _Bad(Exception):
    """Abandon the current item (a diagnostic was recorded)."""


class _Doctype(Exception):
    """The XML text has a <!DOCTYPE> or an <!ENTITY> declaration (refused)."""

    def __init__(self, line: int, col: int) -> None:
        super().__init__(line, col)
        self.line, self.col = line, col


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def parse_xml_positions(text: str) -> tuple[ET.Element, dict[int, tuple[int, int]],
                                             dict[int, tuple[int, int]]]:
    """Parse XML keeping, for each element, where its start tag and its first text are
    (1-based line and column). Raises :class:`expat.ExpatError` on malformed XML and
    :class:`_Doctype` on a document type declaration: PLCopen files need none, and refusing it
    shuts out entity expansion ("billion laughs") and external entities."""
    p = expat.ParserCreate(encoding="utf-8", namespace_separator="}")
    p.buffer_text = False
    tb = ET.TreeBuilder()
    starts: dict[int, tuple[int, int]] = {}
    texts: dict[int, tuple[int, int]] = {}
    stack: list[ET.Element] = []

    def fix(tag: str) -> str:
        return "{" + tag if "}" in tag else tag

    def start(tag, attrs):
        el = tb.start(fix(tag), attrs)
        starts[id(el)] = (p.CurrentLineNumber, p.CurrentColumnNumber + 1)
        stack.append(el)

    def end(tag):
        tb.end(fix(tag))
        stack.pop()

    def data(s):
        if stack and id(stack[-1]) not in texts:
            texts[id(stack[-1])] = (p.CurrentLineNumber, p.CurrentColumnNumber + 1)
        tb.data(s)

    def doctype(name, *_):
        raise _Doctype(p.CurrentLineNumber, p.CurrentColumnNumber + 1)

    p.StartDoctypeDeclHandler = doctype  # no DTD: no entity expansion, no external files
    p.EntityDeclHandler = doctype
    p.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    p.StartElementHandler = start
    p.EndElementHandler = end
    p.CharacterDataHandler = data
    p.Parse(text.encode("utf-8"), True)
    return tb.close(), starts, texts


def parse_xml_safely(text: str | bytes, file: str = "<input>.xml") -> ET.Element:
    """Parse XML text refusing DOCTYPE and ENTITY declarations; any problem is a
    :class:`PlcError` PLC0180."""
    if isinstance(text, bytes):
        text = text.decode("utf-8", errors="replace")
    try:
        return parse_xml_positions(text)[0]
    except expat.ExpatError as exc:
        raise PlcError("PLC0180", f"not well-formed XML: {exc}; fix the file or export it again",
                       Location(file, exc.lineno, exc.offset + 1)) from None
    except _Doctype as exc:
        raise PlcError("PLC0180", _DOCTYPE_MSG, Location(file, exc.line, exc.col)) from None


_DOCTYPE_MSG = ("the file has a <!DOCTYPE> or <!ENTITY> declaration; PLCopen XML needs none and "
                "plclab refuses them (entities could expand without bound or read other files): "
                "remove the declaration or export the project again")


class _Importer:
    def __init__(self, text: str, file: str) -> None:
        self.text = text
        self.file = file
        self.diags: list[Diagnostic] = []
        self.out = A.SourceFile(file)
        # the Beremiz runtime blocks this file does not declare itself (a project may define its
        # own LOGGER: Beremiz's tests/logging does, with C inside; then it is the user's POU)
        self.runtime_only = set(BEREMIZ_ONLY)
        self.dropped: set[str] = set()  # the current POU's runtime-block instances left out
        self.loglevel_used: ET.Element | None = None  # where the file first names LOGLEVEL

    # -- helpers ----------------------------------------------------------------------------
    def loc(self, el: ET.Element) -> Location:
        line, col = self.starts.get(id(el), (0, 0))
        return Location(self.file, line, col)

    def err(self, code: str, msg: str, el: ET.Element | None) -> None:
        self.diags.append(Diagnostic(code, msg, self.loc(el) if el is not None else
                                     Location(self.file, 1, 1)))

    def fail(self, code: str, msg: str, el: ET.Element | None) -> None:
        self.err(code, msg, el)
        raise _Bad

    def kids(self, el: ET.Element, name: str | None = None) -> list[ET.Element]:
        return [c for c in el if isinstance(c.tag, str) and (name is None or _local(c.tag) == name)]

    def kid(self, el: ET.Element, name: str) -> ET.Element | None:
        for c in el:
            if isinstance(c.tag, str) and _local(c.tag) == name:
                return c
        return None

    def ident(self, name: str | None, el: ET.Element, what: str) -> str:
        problem = identifier_problem(name) if name else "it is empty"
        if problem:
            self.fail("PLC0183", f"the {what} is not a valid IEC identifier: {problem}", el)
        return name  # type: ignore[return-value]

    def describe(self, el: ET.Element) -> str:
        """``<block> (localId 4 at x=90 y=30)``: how a message names a graphical element."""
        lid = el.get("localId")
        pos = self.kid(el, "position")
        where = f" at x={pos.get('x')} y={pos.get('y')}" if pos is not None and \
            pos.get("x") is not None else ""
        return f"<{_local(el.tag)}>" + (f" (localId {lid}{where})" if lid is not None else "")

    def text_parser(self, text: str | None, el: ET.Element):
        """An ST parser over ``text`` placed where it stands in the XML file; ``None``: the text
        of ``el`` (of its first descendant holding text, e.g. ``<xhtml:p>`` in ``<ST>``)."""
        if text is None:
            holder = next((d for d in el.iter() if (d.text or "").strip()), el)
            text = "".join(holder.itertext())
            line, col = self.texts.get(id(holder), self.starts.get(id(el), (1, 1)))
        elif id(el) in self.texts and (el.text or "").strip() == text.strip():
            text = el.text or ""
            line, col = self.texts[id(el)]
        else:  # an attribute value: located at its element
            line, col = self.starts.get(id(el), (1, 1))
        return _placed(Parser(text, self.file), line, col)

    def expr(self, text: str | None, el: ET.Element, what: str) -> A.Expr:
        if text is None or not text.strip():
            self.fail("PLC0183", f"{self.describe(el)} has no {what}", el)
        p = self.text_parser(text or "", el)
        n = len(self.diags)
        try:
            e = p.expr()
            if not p.at("EOF"):
                p.fail_expected(f"the end of the {what}")
        except ParseAbort:
            e = None
        if p.diagnostics:
            self.diags.extend(p.diagnostics)
        if e is None or len(self.diags) > n:
            raise _Bad
        return e

    # -- driver -----------------------------------------------------------------------------
    def run(self) -> A.SourceFile:
        try:
            root, self.starts, self.texts = parse_xml_positions(self.text)
        except expat.ExpatError as exc:
            self.diags.append(Diagnostic("PLC0180", f"not well-formed XML: {exc}; fix the file "
                                         "or export it again", Location(self.file, exc.lineno,
                                                                        exc.offset + 1)))
            return self.out
        except _Doctype as exc:
            self.diags.append(Diagnostic("PLC0180", _DOCTYPE_MSG,
                                         Location(self.file, exc.line, exc.col)))
            return self.out
        ns = root.tag[1:].split("}")[0] if root.tag.startswith("{") else ""
        if _local(root.tag) != "project" or ns not in _NAMESPACES:
            self.err("PLC0180", f"this is not a PLCopen XML project: the root element is "
                     f"<{_local(root.tag)}> in namespace {ns or 'none'}, expected <project "
                     f"xmlns=\"{NS}\">", root)
            return self.out
        types = self.kid(root, "types")
        if types is not None:
            dts = self.kid(types, "dataTypes")
            for dt in self.kids(dts) if dts is not None else []:
                try:
                    self.data_type(dt)
                except _Bad:
                    pass
            pous = self.kid(types, "pous")
            self.runtime_only -= {(pel.get("name") or "").upper()
                                  for pel in (self.kids(pous) if pous is not None else [])}
            for pel in self.kids(pous) if pous is not None else []:
                try:
                    self.pou(pel)
                except _Bad:
                    pass
        inst = self.kid(root, "instances")
        cfgs = self.kid(inst, "configurations") if inst is not None else None
        for c in self.kids(cfgs) if cfgs is not None else []:
            try:
                self.configuration(c)
            except _Bad:
                pass
        self.beremiz_loglevel()
        return self.out

    def beremiz_loglevel(self) -> None:
        """Beremiz's runtime library declares ``TYPE LOGLEVEL : (CRITICAL, WARNING, INFO, DEBUG)
        := INFO; END_TYPE`` (its NativeLib.xml, beside LOGGER) and projects use it without
        declaring it (``lvl : LOGLEVEL := INFO`` wired to a LOGGER's LEVEL, Beremiz's
        tests/projects/c_runtime). A project that names it and does not declare it gets that
        declaration: plain IEC, it runs; the LOGGER itself is still left out (PLC0250)."""
        if self.loglevel_used is None or any(t.name == "LOGLEVEL" for t in self.out.types):
            return
        loc = self.loc(self.loglevel_used)
        members = [(m, None, loc) for m in ("CRITICAL", "WARNING", "INFO", "DEBUG")]
        self.out.types.append(A.TypeDecl(loc, "LOGLEVEL", A.EnumTypeRef(loc, members),
                                         A.Name(loc, "INFO", "INFO"), "LOGLEVEL"))

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
        kids = [k for k in self.kids(holder) if _local(k.tag) not in _IGNORED]
        if not kids:
            self.fail("PLC0183", f"<{_local(holder.tag)}> names no type", holder)
        t = kids[0]
        tag = _local(t.tag)
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
        tag = _local(v.tag)
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
            tag = _local(sec.tag)
            if tag in _IGNORED or tag == "returnType":
                continue
            if tag not in _SECTIONS or _SECTIONS[tag] not in allowed:
                self.err("PLC0181", f"the variable section <{tag}> is not supported here", sec)
                continue
            constant = sec.get("constant") in ("true", "1")
            retain = sec.get("retain") in ("true", "1") or sec.get("persistent") in ("true", "1")
            for v in self.kids(sec, "variable"):
                if self.beremiz_instance(v):
                    continue
                try:
                    out.append(self.variable(v, _SECTIONS[tag], constant, retain))
                except _Bad:
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

    # -- POUs -------------------------------------------------------------------------------
    def pou(self, pel: ET.Element) -> None:
        if _local(pel.tag) != "pou":
            return
        name = self.ident(pel.get("name"), pel, "POU name")
        kind = _POU_KINDS.get(pel.get("pouType", ""))
        if kind is None:
            self.fail("PLC0183", f"POU {name}: pouType {pel.get('pouType')!r} must be program, "
                      "functionBlock or function", pel)
        decls: list[A.VarDecl] = []
        ret = None
        self.dropped = set()
        iface = self.kid(pel, "interface")
        if iface is not None:
            decls = self.var_sections(iface, set(_SECTIONS.values()) - {"VAR_GLOBAL"})
            rt = self.kid(iface, "returnType")
            if rt is not None:
                ret = self.type_ref(rt)
        if kind == "FUNCTION" and ret is None:
            self.fail("PLC0183", f"function {name} has no <returnType>", pel)
        pou = A.Pou(self.loc(pel), kind, name.upper(), decls, [], ret, name)
        self.out.pous.append(pou)
        body = self.kid(pel, "body")
        if body is not None and self.kid(body, "SFC") is not None:  # ADR 0023
            from .plcopen_sfc import read_sfc_pou  # the chart, its actions and transitions

            return read_sfc_pou(self, pou, pel)
        for extra in ("actions", "transitions"):
            el = self.kid(pel, extra)
            if el is not None and self.kids(el):
                self.err("PLC0181", f"POU {name}: <{extra}> (SFC) are not supported", el)
        body = self.kid(pel, "body")
        if body is None:
            return
        langs = [k for k in self.kids(body) if _local(k.tag) not in _IGNORED]
        if not langs:
            return
        lang = langs[0]
        tag = _local(lang.tag)
        reader = self.body_readers().get(tag)
        if reader is not None:
            reader(pou, lang)
        else:
            self.err("PLC0181", f"POU {name}: a <{tag}> body is not supported (plclab imports ST, "
                     "IL, LD and FBD bodies)", lang)

    def body_readers(self):
        """The body languages of a PLCopen POU: element name -> reader(pou, element)."""
        return {"ST": self.st_body, "IL": self.il_body, "LD": self.graphic_body,
                "FBD": self.graphic_body}

    def st_body(self, pou: A.Pou, lang: ET.Element) -> None:
        p = self.text_parser(None, lang)
        pou.body = p.stmt_list(set())
        if not p.at("EOF"):
            p.error("PLC0010", f"unexpected '{p.tok.text}' in the ST body of {pou.spelling}")
        self.diags.extend(p.diagnostics)
        if self.dropped:
            pou.body = self.drop_runtime_calls(pou.body)

    def drop_runtime_calls(self, body: list[A.Stmt]) -> list[A.Stmt]:
        """Calls of a left-out Beremiz runtime instance in an ST body (``LOGGER0(TRIG := ...,
        LEVEL := CRITICAL);``, Beremiz's tests/projects/modbus_test_tcp) go with it: each
        becomes an empty statement, with the warning PLC0250 at the call."""
        out: list[A.Stmt] = []
        for s in body:
            if (isinstance(s, A.CallStmt) and isinstance(s.call.func, A.Name)
                    and s.call.func.name in self.dropped):
                self.diags.append(Diagnostic(
                    "PLC0250", f"the call of {s.call.func.text or s.call.func.name} (a Beremiz "
                    "runtime block, not available in plclab) is left out", s.loc, "warning"))
                out.append(A.Empty(s.loc))
                continue
            if isinstance(s, A.If):
                s.branches = [(c, self.drop_runtime_calls(b)) for c, b in s.branches]
            elif isinstance(s, A.Case):
                for br in s.branches:
                    br.body = self.drop_runtime_calls(br.body)
            elif isinstance(s, A.For | A.While | A.Repeat):
                s.body = self.drop_runtime_calls(s.body)
            if isinstance(s, A.If | A.Case) and s.orelse is not None:
                s.orelse = self.drop_runtime_calls(s.orelse)
            out.append(s)
        return out

    def il_body(self, pou: A.Pou, lang: ET.Element) -> None:
        p = self.text_parser(None, lang)
        pending = parse_il_body(p, "EOF")
        if not p.at("EOF"):
            p.error("PLC0146", f"unexpected '{p.tok.text}' in the IL body of {pou.spelling}")
        self.diags.extend(p.diagnostics)
        pou.language = "IL"
        pou.pending.append(pending)

    def graphic_body(self, pou: A.Pou, lang: ET.Element) -> None:
        tag = _local(lang.tag)
        pou.language = tag
        elems = self.graphic(lang, tag)
        if elems is not None:
            pou.pending.append(A.PendingBody("NETWORK", elems, self.loc(lang)))

    # -- LD and FBD -------------------------------------------------------------------------
    def refs(self, cpi: ET.Element | None) -> list[tuple[str, str, ET.Element]]:
        if cpi is None:
            return []
        out = []
        for c in self.kids(cpi, "connection"):
            rid = c.get("refLocalId")
            if rid is None:
                self.err("PLC0182", "<connection> without refLocalId", c)
                continue
            out.append((rid, c.get("formalParameter") or "", c))
        return out

    def graphic(self, lang: ET.Element, tag: str) -> list[Elem] | None:
        elems: list[Elem] = []
        by_id: dict[str, Elem] = {}
        pending: list[tuple[Elem, str, list[tuple[str, str, ET.Element]]]] = []
        connectors: dict[str, Elem] = {}
        continuations: list[tuple[Elem, str, ET.Element]] = []
        rights: list[ET.Element] = []
        skipped: set[str] = set()  # localIds of Beremiz-only blocks and what they feed
        ok = True

        def new(kind: str, el: ET.Element) -> Elem:
            pos = self.kid(el, "position")
            x = _num(pos.get("x")) if pos is not None else 0.0
            y = _num(pos.get("y")) if pos is not None else 0.0
            e = Elem(len(elems), kind, self.loc(el), text=self.describe(el), geom=(x, y))
            eo = el.get("executionOrderId")
            given = int(eo) if eo and eo.isdigit() and int(eo) > 0 else 0
            e.explicit_order = given > 0
            e.order = (given, y, 0 if kind == "label" else 1, x)
            elems.append(e)
            lid = el.get("localId")
            if lid is not None:
                if lid in by_id:
                    self.err("PLC0182", f"localId {lid} is used twice", el)
                by_id[lid] = e
            return e

        for el in self.kids(lang):
            k = _local(el.tag)
            try:
                if k in _IGNORED:
                    continue
                if k == "leftPowerRail":
                    new("left", el)
                elif k == "rightPowerRail":
                    rights.append(el)
                elif k in ("contact", "coil"):
                    if tag != "LD":
                        self.fail("PLC0181", f"{self.describe(el)} belongs in an LD body, not "
                                  "FBD", el)
                    e = new(k, el)
                    v = self.kid(el, "variable")
                    e.var = self.expr(v.text if v is not None else None, v if v is not None
                                      else el, "variable")
                    neg = el.get("negated") in ("true", "1")
                    edge = el.get("edge", "none")
                    storage = el.get("storage", "none")
                    e.mode = "P" if edge == "rising" else "N" if edge == "falling" else \
                        "S" if storage == "set" else "R" if storage == "reset" else \
                        "/" if neg else ""
                    if k == "contact" and e.mode in ("S", "R"):
                        self.fail("PLC0183", f"{self.describe(el)}: a contact has no storage",
                                  el)
                    e.text = f"{'[' if k == 'contact' else '('}{e.mode or ' '}" \
                             f"{']' if k == 'contact' else ')'} {v.text.strip() if v is not None else ''}"
                    pending.append((e, "", self.refs(self.kid(el, "connectionPointIn"))))
                elif k == "block":
                    if (el.get("typeName") or "").upper() in self.runtime_only:
                        skipped.add(el.get("localId") or "")
                        self.warn_beremiz(el.get("typeName") or "", el)
                        continue
                    self.block(el, new, pending)
                elif k in ("inVariable", "outVariable", "inOutVariable"):
                    e = new({"inVariable": "invar", "outVariable": "outvar"}.get(k, "inoutvar"),
                            el)
                    x = self.kid(el, "expression")
                    e.var = self.expr(x.text if x is not None else None,
                                      x if x is not None else el, "expression")
                    self.variable_pins(el, e, k)
                    if k != "inVariable":
                        refs = self.refs(self.kid(el, "connectionPointIn"))
                        if not refs:
                            self.unconnected(el, k, x)
                            if k == "outVariable":
                                elems.pop()  # nothing reads it: it is left out
                                by_id.pop(el.get("localId"), None)
                                continue
                            e.kind = "invar"  # still read by what it feeds, never written
                        else:
                            pending.append((e, "", refs))
                elif k in ("jump", "label", "return"):
                    if tag not in ("FBD", "LD"):
                        self.fail("PLC0181", f"{self.describe(el)} belongs in an LD or FBD body",
                                  el)
                    e = new(k, el)
                    if k != "return":
                        e.label = self.ident(el.get("label"), el, f"{k} label").upper()
                    if k != "label":
                        pending.append((e, "", self.refs(self.kid(el, "connectionPointIn"))))
                elif k == "connector":
                    e = new("conn", el)
                    connectors[(el.get("name") or "").upper()] = e
                    pending.append((e, "", self.refs(self.kid(el, "connectionPointIn"))))
                elif k == "continuation":
                    e = new("conn", el)
                    continuations.append((e, (el.get("name") or "").upper(), el))
                else:
                    self.fail("PLC0181", f"{self.describe(el)} is not supported in an {tag} body "
                              "(plclab reads rails, contacts, coils, blocks, in/out variables, "
                              "connectors and comments)", el)
            except _Bad:
                ok = False
        for e, name, el in continuations:
            c = connectors.get(name)
            if c is None:
                self.err("PLC0182", f"continuation {name!r} has no connector of that name", el)
                ok = False
            else:
                e.inputs[""] = [(c.id, "")]
        dead = self.dead_elements(pending, skipped, by_id)
        for e, pin, refs in pending:
            out = []
            if e.id in dead:
                continue
            for rid, fp, cel in refs:
                src = by_id.get(rid)
                if src is None:
                    self.err("PLC0182", f"{e.text} is connected to localId {rid}, which does not "
                             "exist", cel)
                    ok = False
                    continue
                out.append((src.id, "" if src.kind in ("left", "contact", "coil", "invar",
                                                       "inoutvar", "conn") else fp.upper()))
            e.inputs.setdefault(pin, []).extend(out)
        if dead:
            keep = [e for e in elems if e.id not in dead]
            renum = {e.id: k for k, e in enumerate(keep)}
            for e in keep:
                e.id = renum[e.id]
                e.inputs = {p: [(renum[i], o) for i, o in refs] for p, refs in e.inputs.items()}
            elems = keep
        for el in rights:
            for rid, _, cel in self.refs_all(el):
                if rid not in by_id and rid not in skipped:
                    self.err("PLC0182", f"the right power rail is connected to localId {rid}, "
                             "which does not exist", cel)
                    ok = False
        if ok:
            stuck = plan_feedback(elems)[1]
            if stuck is not None:
                self.diags.append(Diagnostic(
                    "PLC0330", f"the {tag} network of this POU has a feedback loop through "
                    f"{stuck.text} that nothing holds: a wire fed back must leave a function "
                    "block output, a BOOL box, or an output whose value an output variable "
                    "also receives (the feedback variable); wire that output to a variable "
                    "too", stuck.loc))
                ok = False
        if ok and _box_depth(elems) > MAX_BOX_CHAIN:
            self.err("PLC0181", f"the {tag} network of this POU chains more than {MAX_BOX_CHAIN} "
                     "function boxes, each feeding the next; store an intermediate result in a "
                     "variable (an outVariable, then an inVariable) to split the chain", lang)
            ok = False
        return elems if ok else None

    def unconnected(self, el: ET.Element, k: str, x: ET.Element | None) -> None:
        """An output (or in-out) variable with nothing wired into it: no assignment (writing
        FALSE or 0 every scan would be a silent miscompile; Beremiz generates nothing)."""
        what = (x.text or "").strip() if x is not None else "?"
        self.diags.append(Diagnostic(
            "PLC0331", f"{self.describe(el)} writes {what} but nothing is wired into it; it is "
            "left out (no assignment): connect its input or delete it", self.loc(el),
            "warning"))

    def dead_elements(self, pending, skipped: set[str], by_id: dict[str, Elem]) -> set[int]:
        """The elements wired (directly or through others) to a skipped Beremiz-only block:
        they are left out too; their localIds join ``skipped``."""
        lid_of = {e.id: lid for lid, e in by_id.items()}
        dead: set[int] = set()
        changed = bool(skipped)
        while changed:
            changed = False
            for e, _, refs in pending:
                if e.id not in dead and any(rid in skipped for rid, _, _ in refs):
                    dead.add(e.id)
                    skipped.add(lid_of.get(e.id, ""))
                    changed = True
        return dead

    def warn_beremiz(self, type_name: str, el: ET.Element) -> None:
        """A Beremiz runtime block (LOGGER, python_eval...): skipped with a warning."""
        self.diags.append(Diagnostic(
            "PLC0250", f"{type_name} in {self.describe(el)} is a Beremiz runtime block, not "
            "available in plclab; it is left out (with whatever it alone feeds) and the rest of "
            "the project runs", self.loc(el), "warning"))

    def variable_pins(self, el: ET.Element, e: Elem, k: str) -> None:
        """``negated`` on an in/out variable: the value read is inverted (inVariable), the
        value written is inverted (outVariable); ``edge`` on them is not IEC and is refused."""
        neg_in = el.get("negatedIn", el.get("negated")) in ("true", "1")
        neg_out = el.get("negatedOut", el.get("negated") if k != "inOutVariable" else None) \
            in ("true", "1")
        if k == "inVariable" and neg_out:
            e.var = A.Unary(e.loc, "NOT", e.var)
        elif k != "inVariable" and neg_in:
            e.neg_in.add("")
        if k == "inOutVariable" and neg_out:
            e.neg_out.add("")
        for attr in ("edge", "edgeIn", "edgeOut"):
            if el.get(attr, "none") not in ("none", ""):
                self.fail("PLC0183", f"{self.describe(el)}: {attr}={el.get(attr)!r} on a "
                          "variable is not part of IEC FBD; put the edge on a block input or "
                          "use R_TRIG/F_TRIG", el)

    def refs_all(self, el: ET.Element):
        out = []
        for cpi in self.kids(el, "connectionPointIn"):
            out.extend(self.refs(cpi))
        return out

    def block(self, el: ET.Element, new, pending) -> None:
        tname = self.ident(el.get("typeName"), el, "block type").upper()
        inst = el.get("instanceName")
        e = new("fb" if inst else "func", el)
        e.type_name = tname
        e.text = f"[{tname}{' ' + inst if inst else ''}] " + self.describe(el)
        if inst:
            e.instance = self.expr(inst, el, "instance name")
        seen: set[str] = set()
        for group in ("inputVariables", "inOutVariables"):
            holder = self.kid(el, group)
            for v in self.kids(holder, "variable") if holder is not None else []:
                pin = self.pin_name(v, el, seen)
                if group == "inOutVariables":
                    e.inout_pins.add(pin)
                edge = v.get("edge", "none")
                if edge in ("rising", "falling"):
                    e.edge_in[pin] = "P" if edge == "rising" else "N"
                elif edge not in ("none", ""):
                    self.fail("PLC0183", f"{self.describe(el)}: input {pin} has edge={edge!r}; "
                              "use rising, falling or none", v)
                if v.get("negated") in ("true", "1"):
                    e.neg_in.add(pin)
                pending.append((e, pin, self.refs(self.kid(v, "connectionPointIn"))))
        outs = self.kid(el, "outputVariables")
        out_pins = []
        for v in self.kids(outs, "variable") if outs is not None else []:
            if not inst and not (v.get("formalParameter") or "").strip() and "OUT" not in out_pins:
                # a function's result pin without a name: TC6 v2.00 files (Beremiz 2008, its
                # tests/linux/test_master_DS401GUI) write formalParameter="" where v2.01 has OUT
                pin = "OUT"
            else:
                pin = self.pin_name(v, el, set())
            out_pins.append(pin)
            if v.get("negated") in ("true", "1"):
                e.neg_out.add(pin)
        e.out_pin = next((p for p in out_pins if p != "ENO"), "OUT")
        e.outs = out_pins

    def pin_name(self, v: ET.Element, el: ET.Element, seen: set[str]) -> str:
        """A block pin's formal parameter, upper case (pin names are case-insensitive)."""
        pin = (v.get("formalParameter") or "").upper()
        if not pin or identifier_problem(pin):
            self.fail("PLC0183", f"{self.describe(el)}: a pin has formalParameter "
                      f"{v.get('formalParameter')!r}; every pin needs the name of a parameter "
                      "of the block", v)
        if pin in seen:
            self.fail("PLC0183", f"{self.describe(el)}: the pin {pin} appears twice", v)
        seen.add(pin)
        return pin

    # -- configurations -------------------------------------------------------------------------
    def configuration(self, c: ET.Element) -> None:
        name = self.ident(c.get("name"), c, "configuration name")
        cfg = A.Configuration(self.loc(c), name.upper(), [], [], [])
        for gv in self.kids(c, "globalVars"):
            cfg.globals.extend(self.var_sections(_Wrap(gv), {"VAR_GLOBAL"}))
        for res in self.kids(c, "resource"):
            try:
                rname = self.ident(res.get("name"), res, "resource name").upper()
            except _Bad:
                rname = f"RESOURCE{len(cfg.resources) + 1}"
            cfg.resources.append(rname)
            for gv in self.kids(res, "globalVars"):
                cfg.resource_globals.setdefault(rname, []).extend(
                    self.var_sections(_Wrap(gv), {"VAR_GLOBAL"}))
            for t in self.kids(res, "task"):
                try:
                    tname = self.ident(t.get("name"), t, "task name").upper()
                    interval = t.get("interval")
                    iv = None
                    if interval:
                        iv = self.expr(_iso_duration(interval), t, "task interval")
                    pr = t.get("priority")
                    pe = self.expr(pr, t, "task priority") if pr else None
                    cfg.tasks.append(A.TaskDecl(self.loc(t), tname, iv, pe, resource=rname))
                    for pi in self.kids(t, "pouInstance"):
                        cfg.instances.append(self.instance(pi, tname))
                        cfg.instances[-1].resource = rname
                except _Bad:
                    pass
            for pi in self.kids(res, "pouInstance"):
                try:
                    cfg.instances.append(self.instance(pi, None))
                    cfg.instances[-1].resource = rname
                except _Bad:
                    pass
        cfg.settle_resources()
        self.out.configs.append(cfg)

    def instance(self, pi: ET.Element, task: str | None) -> A.ProgramInstance:
        n = self.ident(pi.get("name"), pi, "program instance name")
        # TC6 v2.01 names the program with typeName, v2.00 (Beremiz before 2012) with type
        t = self.ident(pi.get("typeName", pi.get("type")), pi, "program type")
        return A.ProgramInstance(self.loc(pi), n.upper(), task, t.upper())


def _placed(p, line: int, col: int):
    """Move the tokens and diagnostics of a parser over a snippet to where the snippet stands
    in the XML file (line and column of its first character). Shifting costs the snippet's
    length only; padding the text with ``line`` newlines made an import quadratic."""
    if line <= 1 and col <= 1:
        return p
    for t in p.toks:
        if t.line == 1:
            t.col += col - 1
        t.line += line - 1
    p.diagnostics[:] = [_shift(d, line, col) for d in p.diagnostics]
    p.pragmas[:] = [(ln + line - 1, body) for ln, body in p.pragmas]
    return p


def _shift(d: Diagnostic, line: int, col: int) -> Diagnostic:
    loc = d.location
    if loc is None or loc.line <= 0:
        return d
    c = loc.col + col - 1 if loc.line == 1 else loc.col
    return Diagnostic(d.code, d.message, Location(loc.file, loc.line + line - 1, c), d.severity)


class _Wrap:
    """Makes one ``<globalVars>`` element look like an interface holding it."""

    def __init__(self, el: ET.Element) -> None:
        self.el = el

    def __iter__(self):
        return iter([self.el])


def _box_depth(elems: list[Elem]) -> int:
    """The longest chain of function boxes feeding each other (connectors pass through;
    other elements start a new chain). Iterative; an element met again while its chain is
    being measured (a feedback loop, ADR 0053) counts as the start of a chain."""
    depth: dict[int, int] = {}
    for root in elems:
        stack = [(root.id, False)]
        while stack:
            i, done = stack.pop()
            if i in depth and depth[i] >= 0:
                continue
            e = elems[i]
            if not done:
                depth[i] = -1
                stack.append((i, True))
                stack.extend((j, False) for j in _feeds(e) if j not in depth)
                continue
            up = max((depth[j] for j in _feeds(e)), default=0)
            depth[i] = up + 1 if e.kind == "func" else up if e.kind == "conn" else 0
    return max(depth.values(), default=0)


def _feeds(e: Elem, elems: list[Elem] | None = None):
    """The ids of the elements wired into ``e``. With ``elems``: not those that are in-out
    variables (reading one reads the variable: a loop through one is not a feedback loop)."""
    return (i for refs in e.inputs.values() for i, _ in refs
            if i >= 0 and (elems is None or elems[i].kind != "inoutvar"))


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


def _num(s: str | None) -> float:
    """A coordinate; a malformed one counts as 0 (positions only order and draw elements)."""
    try:
        return float(s or 0)
    except ValueError:
        return 0.0


def _iso_duration(s: str) -> str:
    """``PT0.02S`` (ISO 8601, some exporters) -> ``T#20ms``; ``00:00:00.050000`` (an
    ``xsd:time``, what TC6 v2.00 files of Beremiz before its v2.01 format hold, e.g. its
    tests/linux/test_master) -> ``T#50ms``; IEC literals pass through."""
    num = r"([0-9]+(?:\.[0-9]+)?)"
    m = re.match(rf"^PT(?:{num}H)?(?:{num}M)?(?:{num}S)?$", s.strip()) or \
        re.match(r"^([0-9]{1,2}):([0-9]{2}):([0-9]{2}(?:\.[0-9]+)?)$", s.strip())
    if not m:
        return s
    h, mi, sec = (float(x) if x else 0.0 for x in m.groups())
    ms = round(((h * 60 + mi) * 60 + sec) * 1000)
    return f"T#{ms}ms"


def parse(text: str, file: str = "<input>.xml") -> tuple[A.SourceFile, list[Diagnostic]]:
    """Import a PLCopen XML project; IL bodies and LD/FBD networks stay pending."""
    imp = _Importer(text, file)
    return imp.run(), imp.diags


def parse_plcopen_collect(text: str, file: str = "<input>.xml") -> tuple[A.SourceFile,
                                                                         list[Diagnostic]]:
    """Import a PLCopen XML project and lower it (the file alone); return the tree and the
    diagnostics (no exception)."""
    out, diags = parse(text, file)
    return out, diags + lower_alone(out)


def parse_plcopen(text: str, file: str = "<input>.xml") -> A.SourceFile:
    """Import a PLCopen XML project; raise :class:`PlcError` on any error."""
    out, diags = parse_plcopen_collect(text, file)
    errors = [d for d in diags if d.severity == "error"]
    if errors:
        raise PlcError(errors[0].code, errors[0].message, errors[0].location, diagnostics=diags)
    return out


__all__ = ["parse", "parse_plcopen", "parse_plcopen_collect", "parse_xml_safely",
           "parse_xml_positions", "MAX_BOX_CHAIN", "NS"]
