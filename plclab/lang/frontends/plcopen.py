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
from ..lexer import identifier_problem
from ..parsing import ParseAbort
from .il_lines import parse_il_body
from .plcopen_base import IGNORED, SECTIONS, Bad, local_name
from .plcopen_graphic import MAX_BOX_CHAIN, GraphicRead
from .plcopen_types import TypeRead
from .st import Parser, lower_alone

NS = "http://www.plcopen.org/xml/tc6_0201"
_NAMESPACES = (NS, "http://www.plcopen.org/xml/tc6_0200", "http://www.plcopen.org/xml/tc6.xsd")
_POU_KINDS = {"program": "PROGRAM", "functionBlock": "FUNCTION_BLOCK", "function": "FUNCTION"}
# Beremiz runtime blocks (its py_ext and logging plugins): no plclab equivalent, skipped (PLC0250)
BEREMIZ_ONLY = {"LOGGER", "PYTHON_EVAL", "PYTHON_POLL", "PYTHON_GEAR"}


class _Doctype(Exception):
    """The XML text has a <!DOCTYPE> or an <!ENTITY> declaration (refused)."""

    def __init__(self, line: int, col: int) -> None:
        super().__init__(line, col)
        self.line, self.col = line, col


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


class _Importer(TypeRead, GraphicRead):
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
        raise Bad

    def kids(self, el: ET.Element, name: str | None = None) -> list[ET.Element]:
        return [c for c in el if isinstance(c.tag, str) and (name is None or local_name(c.tag) == name)]

    def kid(self, el: ET.Element, name: str) -> ET.Element | None:
        for c in el:
            if isinstance(c.tag, str) and local_name(c.tag) == name:
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
        return f"<{local_name(el.tag)}>" + (f" (localId {lid}{where})" if lid is not None else "")

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
            raise Bad
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
        if local_name(root.tag) != "project" or ns not in _NAMESPACES:
            self.err("PLC0180", f"this is not a PLCopen XML project: the root element is "
                     f"<{local_name(root.tag)}> in namespace {ns or 'none'}, expected <project "
                     f"xmlns=\"{NS}\">", root)
            return self.out
        types = self.kid(root, "types")
        if types is not None:
            dts = self.kid(types, "dataTypes")
            for dt in self.kids(dts) if dts is not None else []:
                try:
                    self.data_type(dt)
                except Bad:
                    pass
            pous = self.kid(types, "pous")
            self.runtime_only -= {(pel.get("name") or "").upper()
                                  for pel in (self.kids(pous) if pous is not None else [])}
            for pel in self.kids(pous) if pous is not None else []:
                try:
                    self.pou(pel)
                except Bad:
                    pass
        inst = self.kid(root, "instances")
        cfgs = self.kid(inst, "configurations") if inst is not None else None
        for c in self.kids(cfgs) if cfgs is not None else []:
            try:
                self.configuration(c)
            except Bad:
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


    # -- POUs -------------------------------------------------------------------------------
    def pou(self, pel: ET.Element) -> None:
        if local_name(pel.tag) != "pou":
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
            decls = self.var_sections(iface, set(SECTIONS.values()) - {"VAR_GLOBAL"})
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
        langs = [k for k in self.kids(body) if local_name(k.tag) not in IGNORED]
        if not langs:
            return
        lang = langs[0]
        tag = local_name(lang.tag)
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

    # -- configurations -------------------------------------------------------------------------
    def configuration(self, c: ET.Element) -> None:
        name = self.ident(c.get("name"), c, "configuration name")
        cfg = A.Configuration(self.loc(c), name.upper(), [], [], [])
        for gv in self.kids(c, "globalVars"):
            cfg.globals.extend(self.var_sections(_Wrap(gv), {"VAR_GLOBAL"}))
        for res in self.kids(c, "resource"):
            try:
                rname = self.ident(res.get("name"), res, "resource name").upper()
            except Bad:
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
                except Bad:
                    pass
            for pi in self.kids(res, "pouInstance"):
                try:
                    cfg.instances.append(self.instance(pi, None))
                    cfg.instances[-1].resource = rname
                except Bad:
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
