"""plclab programs -> PLCopen XML (TC6 v2.01), the format OpenPLC Editor and Beremiz open.

What is written (ADR 0022):

* data types (``dataTypes``), POU interfaces with every variable section, initial values and
  addresses, configurations with their tasks, program instances and global variables;
* **ST** bodies as ST text; **IL** bodies as their IL text (copied from the source file);
  **LD** and **FBD** networks (text ladder or PLCopen) as PLCopen networks: rails, contacts
  and coils of every kind, boxes with named pins (a text box's rung at its first BOOL input),
  parameters as in-variables; any other body as the ST it lowers to;
* with ``fbd=True``, every body made only of assignments and function block calls as an
  **FBD** network: one network a statement, operators as standard blocks (``AND``, ``ADD``,
  ``GT``...), ``NOT`` of a variable as a negated pin, set/reset assignments as ``MOVE`` with
  ``EN``, an ``executionOrderId`` on every element (the order of the statements).

**SFC** bodies as ``<SFC>`` charts with their ``<actions>`` and ``<transitions>``
(:mod:`.plcopen_sfc_export`); what a chart cannot carry is :class:`PlcError` PLC4042.

>>> from plclab.project import parse_sources
>>> files, _ = parse_sources([("PROGRAM P VAR a, b : BOOL; END_VAR b := NOT a; END_PROGRAM",
...                            "p.st")])
>>> xml = export_plcopen(files[-1:], fbd=True)
>>> 'typeName="NOT"' in xml and '<expression>b</expression>' in xml and '<FBD>' in xml
True
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from ..errors import Location, PlcError
from . import ast as A
from .plcopen_elements import HIDDEN_PREFIX, NS, XHTML, hide, sub, text_body, visible
from .plcopen_fbd_export import FbdWriter, fb_types_of, fbd_exportable
from .plcopen_ld_export import WRITABLE, NetworkWriter
from .plcopen_sfc_export import SfcWriter, chart_names, source_chart
from .unparse import expr as st_expr
from .unparse import unparse

_ELEMENTARY = {"BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT",
               "UINT", "UDINT", "ULINT", "REAL", "LREAL", "TIME", "LTIME", "DATE", "DT", "TOD",
               "LDATE", "LDT", "LTOD"}
_SECTIONS = {"VAR_INPUT": "inputVars", "VAR_OUTPUT": "outputVars", "VAR_IN_OUT": "inOutVars",
             "VAR": "localVars", "VAR_TEMP": "tempVars", "VAR_EXTERNAL": "externalVars"}
_KINDS = {"PROGRAM": "program", "FUNCTION_BLOCK": "functionBlock", "FUNCTION": "function"}

def export_plcopen(files: list[A.SourceFile], *, fbd: bool = False, name: str = "plclab",
                   sources: dict[str, str] | None = None) -> str:
    """The PLCopen XML text of the POUs, types and configurations of ``files`` (parsed and
    lowered, without the standard library). ``sources``: file name -> text, to copy IL bodies
    as written; without it they are written as the ST they lower to."""
    return _Exporter(fbd, sources or {}).project(files, name)


class _Exporter:
    def __init__(self, fbd: bool, sources: dict[str, str]) -> None:
        self.fbd = fbd
        self.sources = sources
        self.user_inputs: dict[str, list[str]] = {}  # the project's FUNCTIONs: input names

    # -- the project --------------------------------------------------------------------------
    def project(self, files: list[A.SourceFile], name: str) -> str:
        ET.register_namespace("xhtml", XHTML)
        ET.register_namespace("", NS)
        root = ET.Element(f"{{{NS}}}project")
        sub(root, "fileHeader", companyName="plclab", productName=name, productVersion="1",
             creationDateTime="2026-01-01T00:00:00")
        ch = sub(root, "contentHeader", name=name)
        ci = sub(ch, "coordinateInfo")
        for lang in ("fbd", "ld", "sfc"):
            sub(sub(ci, lang), "scaling", x="0", y="0")
        self.user_inputs = {p.name: [d.spelling or d.name for d in p.decls
                                     if d.section == "VAR_INPUT"]
                            for f in files for p in f.pous if p.kind == "FUNCTION"}
        types = sub(root, "types")
        dts = sub(types, "dataTypes")
        pous = sub(types, "pous")
        for f in files:
            for t in f.types:
                dt = sub(dts, "dataType", name=t.spelling or t.name)
                self.type_ref(sub(dt, "baseType"), t.type)
                if t.init is not None:
                    self.init_value(sub(dt, "initialValue"), t.init)
            for p in f.pous:
                self.pou(pous, p, f.file)
        configs = sub(sub(root, "instances"), "configurations")
        loose = [d for f in files for g in f.globals for d in g.decls]
        for f in files:
            for c in f.configs:
                self.configuration(configs, c, loose)
                loose = []
        if loose:  # globals outside a configuration: PLCopen keeps globals in one, which then
            # runs every PROGRAM under its own name, as plclab does without a configuration
            where = Location("", 0, 0)
            programs = [A.ProgramInstance(where, p.spelling or p.name, None, p.spelling or p.name)
                        for f in files for p in f.pous if p.kind == "PROGRAM"]
            self.configuration(configs, A.Configuration(where, "config", [], [], programs), loose)
        ET.indent(root, "  ")
        return "<?xml version='1.0' encoding='utf-8'?>\n" + ET.tostring(root, "unicode") + "\n"

    def configuration(self, parent: ET.Element, c: A.Configuration,
                      extra: list[A.VarDecl]) -> None:
        cel = sub(parent, "configuration", name=c.name)
        # one resource (resource1), or each of two or more with its own globals (ADR 0037)
        scoped = any(x.resource for x in [*c.tasks, *c.instances]) or c.resource_globals
        for r in (c.resources if scoped else [None]):
            res = sub(cel, "resource", name=r or "resource1")
            for t in c.tasks:
                if t.resource != r:
                    continue
                attrs = {"name": t.name, "priority": st_expr(t.priority) if t.priority else "0"}
                if t.interval is not None:
                    attrs["interval"] = st_expr(t.interval)
                task = sub(res, "task", **attrs)
                for pi in c.instances:
                    if pi.task == t.name and pi.resource == r:
                        sub(task, "pouInstance", name=pi.name, typeName=pi.program)
            for pi in c.instances:
                if pi.task is None and pi.resource == r:
                    sub(res, "pouInstance", name=pi.name, typeName=pi.program)
            for constant in (False, True):
                group = [d for d in c.resource_globals.get(r or "", []) if d.constant == constant]
                if group:
                    gv = sub(res, "globalVars", **({"constant": "true"} if constant else {}))
                    for d in group:
                        self.variable(gv, d)
        decls = list(c.globals) + extra
        for constant in (False, True):
            group = [d for d in decls if d.constant == constant]
            if group:
                gv = sub(cel, "globalVars", **({"constant": "true"} if constant else {}))
                for d in group:
                    self.variable(gv, d)

    # -- types and variables --------------------------------------------------------------------
    def type_ref(self, holder: ET.Element, t: A.TypeRef) -> None:
        if isinstance(t, A.NamedTypeRef):
            if t.name in _ELEMENTARY:
                sub(holder, t.name)
            elif t.name in ("STRING", "WSTRING"):
                sub(holder, t.name.lower())
            else:
                sub(holder, "derived", name=t.name)
        elif isinstance(t, A.StringTypeRef):
            attrs = {"length": st_expr(t.length)} if t.length is not None else {}
            sub(holder, "wstring" if t.wide else "string", **attrs)
        elif isinstance(t, A.ArrayTypeRef):
            arr = sub(holder, "array")
            for lo, hi in t.ranges:
                sub(arr, "dimension", lower=st_expr(lo), upper=st_expr(hi))
            self.type_ref(sub(arr, "baseType"), t.elem)
        elif isinstance(t, A.SubrangeTypeRef):
            sr = sub(holder, "subrangeSigned")
            sub(sr, "range", lower=st_expr(t.lo), upper=st_expr(t.hi))
            self.type_ref(sub(sr, "baseType"), t.base)
        elif isinstance(t, A.EnumTypeRef):
            en = sub(holder, "enum")
            vals = sub(en, "values")
            for n, v, _ in t.members:
                attrs = {"name": t.spellings.get(n, n)}
                if v is not None:
                    attrs["value"] = st_expr(v)
                sub(vals, "value", **attrs)
            if t.base is not None:
                self.type_ref(sub(en, "baseType"), t.base)
        elif isinstance(t, A.StructTypeRef):
            st = sub(holder, "struct")
            for d in t.fields:
                self.variable(st, d)
        else:
            raise PlcError("PLC4043", f"the type {type(t).__name__} has no PLCopen form",
                           t.loc)

    def init_value(self, holder: ET.Element, e: A.Expr) -> None:
        if isinstance(e, A.ArrayInit):
            arr = sub(holder, "arrayValue")
            for rep, v in e.items:
                item = sub(arr, "value", **({"repetitionValue": st_expr(rep)} if rep else {}))
                self.init_value(item, v)
        elif isinstance(e, A.StructInit):
            sv = sub(holder, "structValue")
            for member, v, _ in e.fields:
                self.init_value(sub(sv, "value", member=member), v)
        else:
            sub(holder, "simpleValue", value=st_expr(e))

    def variable(self, parent: ET.Element, d: A.VarDecl) -> None:
        attrs = {"name": visible(d.name) if d.name.startswith(HIDDEN_PREFIX) else
                 d.spelling or d.name}
        if d.address:
            attrs["address"] = d.address
        v = sub(parent, "variable", **attrs)
        self.type_ref(sub(v, "type"), d.type)
        if d.init is not None:
            self.init_value(sub(v, "initialValue"), d.init)

    # -- POUs ---------------------------------------------------------------------------------
    def pou(self, parent: ET.Element, p: A.Pou, file: str) -> None:
        if p.kind not in _KINDS or p.methods or p.extends or p.implements:
            raise PlcError("PLC4043", f"{p.spelling or p.name} uses the object-oriented "
                           "extensions (INTERFACE, METHOD, EXTENDS, IMPLEMENTS), which PLCopen XML "
                           "TC6 v2.01 cannot express; export a program without them, or keep "
                           "the ST file", p.loc)
        chart = source_chart(p, file, self.sources) if p.language == "SFC" else None
        if p.language == "SFC" and chart is None:
            raise PlcError("PLC4042", f"{p.spelling or p.name} has an SFC body whose chart is "
                           "not known here; export it from its source file", p.loc)
        pel = sub(parent, "pou", name=p.spelling or p.name, pouType=_KINDS[p.kind])
        iface = sub(pel, "interface")
        if p.return_type is not None:
            self.type_ref(sub(iface, "returnType"), p.return_type)
        il = self.il_text(p, file) if p.language == "IL" else None
        net = self.network(p, file) if p.language in ("LD", "FBD") else None
        groups: dict[tuple[str, bool, bool], list[A.VarDecl]] = {}
        lowered = chart_names(chart) if chart is not None else set()
        for d in p.decls:
            if (net is not None or chart is not None) and d.name.startswith(HIDDEN_PREFIX) \
                    or d.name in lowered:
                continue  # the lowering's own variables: the network/chart is written, not its ST
            groups.setdefault((d.section, d.constant, d.retain), []).append(d)
        for (section, constant, retain), decls in groups.items():
            attrs = {}
            if constant:
                attrs["constant"] = "true"
            if retain:
                attrs["retain"] = "true"
            sec = sub(iface, _SECTIONS.get(section, "localVars"), **attrs)
            for d in decls:
                self.variable(sec, d)
        if chart is not None:  # SFC: <actions>, <transitions> and the chart (ADR 0022)
            SfcWriter(p, chart, file, self.sources).write(pel)
            return
        body = sub(pel, "body")
        if il is not None:
            text_body(sub(body, "IL"), il)
        elif net is not None:
            NetworkWriter(sub(body, p.language), net[0], net[1], self.user_inputs).write()
        elif self.fbd and fbd_exportable(p.body, fb_types := fb_types_of(p), self.user_inputs):
            FbdWriter(sub(body, "FBD"), fb_types, self.user_inputs).statements(p.body)
        else:
            text_body(sub(body, "ST"), hide(unparse(p.body) if p.body else ""))

    def network(self, p: A.Pou, file: str) -> tuple[list, dict[str, A.Pou]] | None:
        """The network elements of ``p`` as its front end read them (before lowering) and the
        POUs of its file, when the source is known and every element can be written."""
        from .frontends.registry import for_file

        text = self.sources.get(file)
        if text is None:
            return None
        src, diags = for_file(file).parse(text, file)
        if any(d.severity == "error" for d in diags):
            return None
        for q in src.pous:
            if q.name == p.name:
                elems = [e for b in q.pending if b.kind == "NETWORK" for e in b.payload]
                if elems and all(e.kind in WRITABLE for e in elems):
                    return elems, {x.name: x for x in src.pous}
        return None

    def il_text(self, p: A.Pou, file: str) -> str | None:
        """The IL lines of ``p`` as written: after its last END_VAR, before its END_ line."""
        text = self.sources.get(file)
        if text is not None and file.lower().endswith(".xml"):
            return _xml_il_text(text, file, p.name)
        if text is None or p.end_loc is None:
            return None
        lines = text.split("\n")[p.loc.line - 1:p.end_loc.line - 1]
        start = max((i for i, ln in enumerate(lines)
                     if re.search(r"\bEND_VAR\b", ln.split("(*")[0], re.IGNORECASE)), default=0)
        return "\n".join(lines[start + 1:]).strip("\n") + "\n"


def _xml_il_text(text: str, file: str, name: str) -> str | None:
    """The IL text of POU ``name`` in a PLCopen XML source."""
    return xml_body_text(text, file, name, "IL")


def xml_body_text(text: str, file: str, name: str, lang: str) -> str | None:
    """The text of the ``lang`` (ST or IL) body of POU ``name`` in a PLCopen XML source."""
    from .frontends.plcopen import parse_xml_safely

    for pou in parse_xml_safely(text, file).iter(f"{{{NS}}}pou"):
        if (pou.get("name") or "").upper() == name.upper():
            body = pou.find(f"{{{NS}}}body/{{{NS}}}{lang}")
            return "".join(body.itertext()) if body is not None else None
    return None


__all__ = ["export_plcopen", "fbd_exportable", "visible", "xml_body_text", "NS"]
