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

SFC bodies are not exported here (the SFC front end owns them): :class:`PlcError` PLC4042.

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
from .unparse import expr as st_expr
from .unparse import unparse

NS = "http://www.plcopen.org/xml/tc6_0201"
XHTML = "http://www.w3.org/1999/xhtml"
_ELEMENTARY = {"BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT",
               "UINT", "UDINT", "ULINT", "REAL", "LREAL", "TIME", "LTIME", "DATE", "DT", "TOD",
               "LDATE", "LDT", "LTOD"}
_SECTIONS = {"VAR_INPUT": "inputVars", "VAR_OUTPUT": "outputVars", "VAR_IN_OUT": "inOutVars",
             "VAR": "localVars", "VAR_TEMP": "tempVars", "VAR_EXTERNAL": "externalVars"}
_KINDS = {"PROGRAM": "program", "FUNCTION_BLOCK": "functionBlock", "FUNCTION": "function"}
BLOCK_OF = {"AND": "AND", "OR": "OR", "XOR": "XOR", "+": "ADD", "-": "SUB", "*": "MUL",
            "/": "DIV", "MOD": "MOD", "**": "EXPT", "=": "EQ", "<>": "NE", "<": "LT",
            "<=": "LE", ">": "GT", ">=": "GE"}
_EXTENSIBLE = {"AND", "OR", "XOR", "ADD", "MUL"}
HIDDEN_PREFIX = "__"  # plclab's generated names; IEC forbids a double underscore
ROW = 60  # vertical distance between elements of a drawn network
COL = 140  # horizontal distance between the columns of a network


def export_plcopen(files: list[A.SourceFile], *, fbd: bool = False, name: str = "plclab",
                   sources: dict[str, str] | None = None) -> str:
    """The PLCopen XML text of the POUs, types and configurations of ``files`` (parsed and
    lowered, without the standard library). ``sources``: file name -> text, to copy IL bodies
    as written; without it they are written as the ST they lower to."""
    return _Exporter(fbd, sources or {}).project(files, name)


def _sub(parent: ET.Element, tag: str, **attrs: str) -> ET.Element:
    """A child element in the PLCopen namespace."""
    return ET.SubElement(parent, f"{{{NS}}}{tag}", attrs)


def visible(name: str) -> str:
    """A generated name (``__LD_T1``) made a legal IEC identifier (``LD_T1_h``)."""
    return name.lstrip("_") + "_h" if name.startswith(HIDDEN_PREFIX) else name


class _Exporter:
    def __init__(self, fbd: bool, sources: dict[str, str]) -> None:
        self.fbd = fbd
        self.sources = sources

    # -- the project --------------------------------------------------------------------------
    def project(self, files: list[A.SourceFile], name: str) -> str:
        ET.register_namespace("xhtml", XHTML)
        ET.register_namespace("", NS)
        root = ET.Element(f"{{{NS}}}project")
        _sub(root, "fileHeader", companyName="plclab", productName=name, productVersion="1",
             creationDateTime="2026-01-01T00:00:00")
        ch = _sub(root, "contentHeader", name=name)
        ci = _sub(ch, "coordinateInfo")
        for lang in ("fbd", "ld", "sfc"):
            _sub(_sub(ci, lang), "scaling", x="0", y="0")
        _USER_INPUTS.clear()
        _USER_INPUTS.update({p.name: [d.spelling or d.name for d in p.decls
                                      if d.section == "VAR_INPUT"]
                             for f in files for p in f.pous if p.kind == "FUNCTION"})
        types = _sub(root, "types")
        dts = _sub(types, "dataTypes")
        pous = _sub(types, "pous")
        for f in files:
            for t in f.types:
                dt = _sub(dts, "dataType", name=t.spelling or t.name)
                self.type_ref(_sub(dt, "baseType"), t.type)
                if t.init is not None:
                    self.init_value(_sub(dt, "initialValue"), t.init)
            for p in f.pous:
                self.pou(pous, p, f.file)
        configs = _sub(_sub(root, "instances"), "configurations")
        loose = [d for f in files for g in f.globals for d in g.decls]
        for f in files:
            for c in f.configs:
                self.configuration(configs, c, loose)
                loose = []
        if loose:  # globals outside a configuration: PLCopen keeps globals in one
            self.configuration(configs, A.Configuration(Location("", 0, 0), "config", [], [], []),
                               loose)
        ET.indent(root, "  ")
        return "<?xml version='1.0' encoding='utf-8'?>\n" + ET.tostring(root, "unicode") + "\n"

    def configuration(self, parent: ET.Element, c: A.Configuration,
                      extra: list[A.VarDecl]) -> None:
        cel = _sub(parent, "configuration", name=c.name)
        res = _sub(cel, "resource", name="resource1")
        for t in c.tasks:
            attrs = {"name": t.name, "priority": st_expr(t.priority) if t.priority else "0"}
            if t.interval is not None:
                attrs["interval"] = st_expr(t.interval)
            task = _sub(res, "task", **attrs)
            for pi in c.instances:
                if pi.task == t.name:
                    _sub(task, "pouInstance", name=pi.name, typeName=pi.program)
        for pi in c.instances:
            if pi.task is None:
                _sub(res, "pouInstance", name=pi.name, typeName=pi.program)
        decls = list(c.globals) + extra
        for constant in (False, True):
            group = [d for d in decls if d.constant == constant]
            if group:
                gv = _sub(cel, "globalVars", **({"constant": "true"} if constant else {}))
                for d in group:
                    self.variable(gv, d)

    # -- types and variables --------------------------------------------------------------------
    def type_ref(self, holder: ET.Element, t: A.TypeRef) -> None:
        if isinstance(t, A.NamedTypeRef):
            if t.name in _ELEMENTARY:
                _sub(holder, t.name)
            elif t.name in ("STRING", "WSTRING"):
                _sub(holder, t.name.lower())
            else:
                _sub(holder, "derived", name=t.name)
        elif isinstance(t, A.StringTypeRef):
            attrs = {"length": st_expr(t.length)} if t.length is not None else {}
            _sub(holder, "wstring" if t.wide else "string", **attrs)
        elif isinstance(t, A.ArrayTypeRef):
            arr = _sub(holder, "array")
            for lo, hi in t.ranges:
                _sub(arr, "dimension", lower=st_expr(lo), upper=st_expr(hi))
            self.type_ref(_sub(arr, "baseType"), t.elem)
        elif isinstance(t, A.SubrangeTypeRef):
            sr = _sub(holder, "subrangeSigned")
            _sub(sr, "range", lower=st_expr(t.lo), upper=st_expr(t.hi))
            self.type_ref(_sub(sr, "baseType"), t.base)
        elif isinstance(t, A.EnumTypeRef):
            en = _sub(holder, "enum")
            vals = _sub(en, "values")
            for n, v, _ in t.members:
                attrs = {"name": t.spellings.get(n, n)}
                if v is not None:
                    attrs["value"] = st_expr(v)
                _sub(vals, "value", **attrs)
            if t.base is not None:
                self.type_ref(_sub(en, "baseType"), t.base)
        elif isinstance(t, A.StructTypeRef):
            st = _sub(holder, "struct")
            for d in t.fields:
                self.variable(st, d)
        else:
            raise PlcError("PLC4043", f"the type {type(t).__name__} has no PLCopen form",
                           t.loc)

    def init_value(self, holder: ET.Element, e: A.Expr) -> None:
        if isinstance(e, A.ArrayInit):
            arr = _sub(holder, "arrayValue")
            for rep, v in e.items:
                item = _sub(arr, "value", **({"repetitionValue": st_expr(rep)} if rep else {}))
                self.init_value(item, v)
        elif isinstance(e, A.StructInit):
            sv = _sub(holder, "structValue")
            for member, v, _ in e.fields:
                self.init_value(_sub(sv, "value", member=member), v)
        else:
            _sub(holder, "simpleValue", value=st_expr(e))

    def variable(self, parent: ET.Element, d: A.VarDecl) -> None:
        attrs = {"name": visible(d.name) if d.name.startswith(HIDDEN_PREFIX) else
                 d.spelling or d.name}
        if d.address:
            attrs["address"] = d.address
        v = _sub(parent, "variable", **attrs)
        self.type_ref(_sub(v, "type"), d.type)
        if d.init is not None:
            self.init_value(_sub(v, "initialValue"), d.init)

    # -- POUs ---------------------------------------------------------------------------------
    def pou(self, parent: ET.Element, p: A.Pou, file: str) -> None:
        if p.language == "SFC":
            raise PlcError("PLC4042", f"{p.spelling or p.name} has an SFC body; plclab's "
                           "PLCopen export writes ST, IL, LD (as ST) and FBD bodies only: "
                           "write the chart's logic in ST to export it", p.loc)
        pel = _sub(parent, "pou", name=p.spelling or p.name, pouType=_KINDS[p.kind])
        iface = _sub(pel, "interface")
        if p.return_type is not None:
            self.type_ref(_sub(iface, "returnType"), p.return_type)
        il = self.il_text(p, file) if p.language == "IL" else None
        net = self.network(p, file) if p.language in ("LD", "FBD") else None
        groups: dict[tuple[str, bool, bool], list[A.VarDecl]] = {}
        for d in p.decls:
            if net is not None and d.name.startswith(HIDDEN_PREFIX):
                continue  # the lowering's own variables: the network is written, not its ST
            groups.setdefault((d.section, d.constant, d.retain), []).append(d)
        for (section, constant, retain), decls in groups.items():
            attrs = {}
            if constant:
                attrs["constant"] = "true"
            if retain:
                attrs["retain"] = "true"
            sec = _sub(iface, _SECTIONS.get(section, "localVars"), **attrs)
            for d in decls:
                self.variable(sec, d)
        body = _sub(pel, "body")
        if il is not None:
            _text_body(_sub(body, "IL"), il)
        elif net is not None:
            _NetworkWriter(_sub(body, p.language), net[0], net[1]).write()
        elif self.fbd and fbd_exportable(p.body, fb_types := _fb_types(p)):
            _FbdWriter(_sub(body, "FBD"), fb_types).statements(p.body)
        else:
            _text_body(_sub(body, "ST"), _hide(unparse(p.body) if p.body else ""))

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
                if elems and all(e.kind in _WRITABLE for e in elems):
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


_WRITABLE = {"left", "contact", "coil", "fb", "func", "cmp", "invar", "outvar", "inoutvar",
             "conn", "jump", "label", "return"}


class _NetworkWriter:
    """An LD or FBD network (text ladder or PLCopen) written back as PLCopen elements: power
    rails, contacts and coils with their kinds, boxes with named pins (a text box's rung
    enters its first BOOL input), parameters as in-variables, results as out-variables."""

    def __init__(self, holder: ET.Element, elems: list, pous: dict[str, A.Pou]) -> None:
        self.holder = holder
        self.elems = {e.id: e for e in elems}
        self.pous = pous
        self.next_id = max((e.id for e in elems), default=0) + 2
        self.power_out: dict[int, str] = {}  # box -> the pin its power flow continues from
        self.rail = self.fresh()  # the one left power rail

    def lid(self, i: int) -> str:
        return str(i + 1)

    def fresh(self) -> str:
        self.next_id += 1
        return str(self.next_id)

    def pos(self, e) -> tuple[int, int]:
        g = e.geom
        if isinstance(g, tuple) and len(g) == 3:  # text: (line, first col, last col)
            return g[1] * 10, g[0] * 40
        if isinstance(g, tuple) and len(g) >= 2:
            return int(g[0]), int(g[1])
        return 0, 0

    def place(self, el: ET.Element, x: int, y: int) -> None:
        _sub(el, "position", x=str(x), y=str(y))

    def refs(self, refs: list) -> list[tuple[str, str | None]]:
        """(localId, pin) of each source, through junctions (``conn``) to what feeds them."""
        out: list[tuple[str, str | None]] = []
        stack = list(reversed(refs))
        seen: set[int] = set()
        while stack:
            i, pin = stack.pop()
            if i < 0 or self.elems[i].kind == "left":
                out.append((self.rail, None))
                continue
            e = self.elems[i]
            if e.kind == "conn":
                if i not in seen:
                    seen.add(i)
                    stack.extend(reversed(e.inputs.get("", [])))
                continue
            if e.kind in ("fb", "func", "cmp"):
                pin = pin or self.power_out.get(i) or "OUT"
            else:
                pin = None
            out.append((self.lid(i), pin))
        return out

    def connect(self, parent: ET.Element, refs: list) -> ET.Element:
        cpi = _sub(parent, "connectionPointIn")
        for ref, pin in self.refs(refs):
            _connect(cpi, ref, pin)
        return cpi

    def box_pins(self, e) -> tuple[str, str]:
        """(power input, power output) of a text ladder box."""
        from .builtins import BLOCKS

        if e.kind != "fb":
            return "EN", "ENO"
        b = BLOCKS.get(e.type_name)
        if b is not None and b.power:
            return b.power
        pou = self.pous.get(e.type_name)
        if pou is None:
            from .frontends.st import parse_library

            pou = next((q for f in parse_library() for q in f.pous if q.name == e.type_name),
                       None)
        bools = [(d.section, d.spelling or d.name) for d in (pou.decls if pou else [])
                 if isinstance(d.type, A.NamedTypeRef) and d.type.name == "BOOL"]
        ins = [n for s, n in bools if s == "VAR_INPUT"]
        outs = [n for s, n in bools if s == "VAR_OUTPUT"]
        return (ins[0].upper(), outs[0].upper()) if ins and outs else ("EN", "ENO")

    def write(self) -> None:
        for e in self.elems.values():
            if e.kind in ("fb", "func", "cmp"):
                self.power_out[e.id] = self.box_pins(e)[1] if "" in e.inputs else ""
        coils = []
        if self.holder.tag.endswith("LD"):
            el = _sub(self.holder, "leftPowerRail", localId=self.rail)
            self.place(el, 0, 0)
            _sub(el, "connectionPointOut", formalParameter="")
        for e in sorted(self.elems.values(), key=lambda e: e.order):
            x, y = self.pos(e)
            k = e.kind
            if k == "left":
                continue
            elif k in ("contact", "coil"):
                attrs = {"localId": self.lid(e.id)}
                if e.mode == "/":
                    attrs["negated"] = "true"
                elif e.mode in ("P", "N"):
                    attrs["edge"] = "rising" if e.mode == "P" else "falling"
                elif e.mode in ("S", "R"):
                    attrs["storage"] = "set" if e.mode == "S" else "reset"
                el = _sub(self.holder, k, **attrs)
                self.place(el, x, y)
                self.connect(el, e.inputs.get("", []))
                _sub(el, "connectionPointOut")
                _sub(el, "variable").text = _hide(st_expr(e.var))
                if k == "coil":
                    coils.append(e)
            elif k in ("invar", "outvar", "inoutvar"):
                tag = {"invar": "inVariable", "outvar": "outVariable"}.get(k, "inOutVariable")
                el = _sub(self.holder, tag, localId=self.lid(e.id))
                self.place(el, x, y)
                if k != "invar":
                    self.connect(el, e.inputs.get("", []))
                if k != "outvar":
                    _sub(el, "connectionPointOut")
                _sub(el, "expression").text = _hide(st_expr(e.var))
            elif k in ("jump", "label", "return"):
                el = _sub(self.holder, k, localId=self.lid(e.id),
                          **({"label": e.label} if k != "return" else {}))
                self.place(el, x, y)
                if k != "label":
                    self.connect(el, e.inputs.get("", []))
            elif k in ("fb", "func", "cmp"):
                self.box(e, x, y)
        if coils:
            right = _sub(self.holder, "rightPowerRail", localId=self.fresh())
            self.place(right, 800, 0)
            for c in coils:
                _connect(_sub(right, "connectionPointIn"), self.lid(c.id), None)

    def box(self, e, x: int, y: int) -> None:
        """A function block, function or comparison box with its pins."""
        power_in, power_out = self.box_pins(e)
        inputs: list[tuple[str, list | str]] = []  # pin -> refs, or a localId of a new variable
        if "" in e.inputs:
            inputs.append((power_in, e.inputs[""]))
        for pin, refs in e.inputs.items():
            if pin:
                inputs.append((pin, refs))
        outputs: list[tuple[str, A.Expr]] = []
        if e.kind == "fb":
            for a in e.args:
                if a.output and a.value is not None:
                    outputs.append(((a.name or "").upper(), a.value))
                elif not a.output and a.value is not None:
                    inputs.append(((a.name or "").upper(), self.variable(a.value, x - 60, y)))
        else:
            names = call_pins(A.Call(e.loc, A.Name(e.loc, "GT" if e.kind == "cmp" else
                                                   e.type_name), e.args)) or \
                [f"IN{i + 1}" for i in range(len(e.args))]
            for pin, a in zip(names, e.args, strict=False):
                inputs.append((pin, self.variable(a.value, x - 60, y)))
        attrs = {"localId": self.lid(e.id), "typeName": e.type_name}
        if e.instance is not None:
            attrs["instanceName"] = _hide(st_expr(e.instance))
        if e.kind == "cmp":  # power AND (a <op> b): the comparison, then an AND
            attrs["localId"] = self.fresh()
        el = _sub(self.holder, "block", **attrs)
        self.place(el, x, y)
        iv = _sub(el, "inputVariables")
        for pin, src in inputs:
            if e.kind == "cmp" and pin == "EN":
                continue
            v = _sub(iv, "variable", formalParameter=pin, **(
                {"negated": "true"} if pin in e.neg_in else {}), **(
                {"edge": "rising" if e.edge_in[pin] == "P" else "falling"}
                if pin in e.edge_in else {}))
            if isinstance(src, str):
                _connect(_sub(v, "connectionPointIn"), src, None)
            else:
                self.connect(v, src)
        _sub(el, "inOutVariables")
        ov = _sub(el, "outputVariables")
        outs = list(e.outs) or ([power_out] if "" in e.inputs and e.kind == "fb" else []) + \
            ([] if e.kind == "fb" else ["ENO", "OUT"] if e.kind == "func" else ["OUT"])
        for pin, _ in outputs:
            if pin not in outs:
                outs.append(pin)
        for pin in outs:
            _sub(_sub(ov, "variable", formalParameter=pin, **(
                {"negated": "true"} if pin in e.neg_out else {})), "connectionPointOut")
        for pin, target in outputs:
            self.out_variable(target, el.get("localId") or "", pin, x + 120, y)
        for t in e.targets:
            self.out_variable(t, el.get("localId") or "", "OUT", x + 120, y)
        if e.kind == "cmp":
            self.power_out[e.id] = "OUT"
            and_el = _sub(self.holder, "block", localId=self.lid(e.id), typeName="AND")
            self.place(and_el, x + 60, y)
            ai = _sub(and_el, "inputVariables")
            self.connect(_sub(ai, "variable", formalParameter="IN1"), e.inputs.get("", []))
            _connect(_sub(_sub(ai, "variable", formalParameter="IN2"), "connectionPointIn"),
                     el.get("localId") or "", "OUT")
            _sub(and_el, "inOutVariables")
            _sub(_sub(_sub(and_el, "outputVariables"), "variable", formalParameter="OUT"),
                 "connectionPointOut")

    def variable(self, value: A.Expr, x: int, y: int) -> str:
        el = _sub(self.holder, "inVariable", localId=self.fresh())
        self.place(el, x, y)
        _sub(el, "connectionPointOut")
        _sub(el, "expression").text = _hide(st_expr(value))
        return el.get("localId") or ""

    def out_variable(self, target: A.Expr, ref: str, pin: str, x: int, y: int) -> None:
        el = _sub(self.holder, "outVariable", localId=self.fresh())
        self.place(el, x, y)
        _connect(_sub(el, "connectionPointIn"), ref, pin)
        _sub(el, "expression").text = _hide(st_expr(target))


def _hide(text: str) -> str:
    """Generated names made legal identifiers in a body text."""
    return re.sub(r"\b__([A-Za-z0-9_]+)", lambda m: m.group(1) + "_h", text)


def _text_body(holder: ET.Element, text: str) -> None:
    p = ET.SubElement(holder, f"{{{XHTML}}}p")
    p.text = text


def _fb_types(p: A.Pou) -> dict[str, str]:
    """Instance name -> function block type, for the declared instances of ``p``."""
    return {d.name: d.type.name for d in p.decls if isinstance(d.type, A.NamedTypeRef)}


def fbd_exportable(body: list[A.Stmt], fb_types: dict[str, str]) -> bool:
    """True when every statement is an assignment or a call of a declared function block
    instance with named parameters (with expressions a network can draw)."""
    return bool(body) and all(
        (isinstance(s, A.Assign) and _drawable(s.value)) or _conditional(s) or
        (isinstance(s, A.CallStmt) and isinstance(s.call.func, A.Name) and
         s.call.func.name in fb_types and
         all(a.name is not None and (a.value is None or _drawable(a.value)) for a in s.call.args))
        for s in body)


def _conditional(s: A.Stmt) -> bool:
    """``IF c THEN x := e; ... END_IF`` (one branch, assignments not writing what ``c`` reads):
    drawn as MOVE blocks enabled by ``c``."""
    if not (isinstance(s, A.If) and len(s.branches) == 1 and not s.orelse):
        return False
    cond, body = s.branches[0]
    read = {n.name for n in _names(cond)}
    return _drawable(cond) and bool(body) and all(
        isinstance(a, A.Assign) and a.op == ":=" and _drawable(a.value) and
        not ({n.name for n in _names(a.target)} & read) for a in body)


def _names(e: A.Expr) -> list[A.Name]:
    out, stack = [], [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Name):
            out.append(x)
        for v in vars(x).values():
            if isinstance(v, A.Expr):
                stack.append(v)
            elif isinstance(v, list):
                stack += [i.value if isinstance(i, A.Arg) else i for i in v
                          if isinstance(i, A.Expr | A.Arg) and
                          (not isinstance(i, A.Arg) or i.value is not None)]
    return out


_USER_INPUTS: dict[str, list[str]] = {}  # user FUNCTION name -> its input names (per export)


def call_pins(e: A.Call) -> list[str] | None:
    """The pin of each argument of a function call drawn as a block, or None when they are
    not known (positional arguments of an unknown function)."""
    from .builtins import BUILTINS, conversion

    names = [a.name for a in e.args]
    if all(names):
        return [n.upper() for n in names if n]
    fname = e.func.name if isinstance(e.func, A.Name) else ""
    if fname in _USER_INPUTS:
        params = [n.upper() for n in _USER_INPUTS[fname]]
    elif fname in BUILTINS:
        b = BUILTINS[fname]
        params = list(b.params)
        if b.variadic:
            params += [f"IN{i + 1}" for i in range(len(params), len(e.args))]
    elif conversion(fname) is not None:
        params = ["IN"]
    else:
        return None
    if len(params) < len(e.args):
        return None
    return [a.name.upper() if a.name else params[i] for i, a in enumerate(e.args)]


def _drawable(e: A.Expr) -> bool:
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Binary):
            if x.op not in BLOCK_OF:
                return False
            stack += [x.left, x.right]
        elif isinstance(x, A.Unary):
            stack.append(x.operand)
        elif isinstance(x, A.Call):
            if not isinstance(x.func, A.Name) or any(a.output for a in x.args) or \
                    call_pins(x) is None:
                return False
            stack += [a.value for a in x.args if a.value is not None]
        elif not isinstance(x, A.Name | A.Literal | A.Member | A.DirectAddr | A.Index):
            return False
    return True


class _FbdWriter:
    """One FBD network a statement, drawn right to left from the assigned variable."""

    def __init__(self, holder: ET.Element, fb_types: dict[str, str]) -> None:
        self.holder = holder
        self.fb_types = fb_types
        self.next_id = 0
        self.order = 0
        self.y = 20

    def new_id(self) -> str:
        self.next_id += 1
        return str(self.next_id)

    def element(self, tag: str, x: float, y: float, **attrs: str) -> ET.Element:
        self.order += 1
        el = _sub(self.holder, tag, localId=self.new_id(), executionOrderId=str(self.order),
                  height="30", width="100", **attrs)
        _sub(el, "position", x=str(int(x)), y=str(int(y)))
        return el

    def statements(self, body: list[A.Stmt]) -> None:
        for s in body:
            top = self.y
            if isinstance(s, A.Assign):
                self.assign(s)
            elif isinstance(s, A.If):
                self.conditional(s)
            else:
                self.fb_call(s)  # type: ignore[arg-type]
            self.y = max(self.y, top + ROW) + ROW // 2

    # values -> (localId, output pin or None); negated leaves are reported for pin negation
    def value(self, e: A.Expr, x: float, y: float) -> tuple[str, str | None]:
        if isinstance(e, A.Binary) and e.op in BLOCK_OF:
            kind = BLOCK_OF[e.op]
            ops = _flatten(e, e.op) if kind in _EXTENSIBLE else [e.left, e.right]
            return self.block(kind, ops, x, y), "OUT"
        if isinstance(e, A.Unary) and e.op == "NOT":
            return self.block("NOT", [e.operand], x, y), "OUT"
        if isinstance(e, A.Unary) and e.op == "-":
            return self.block("NEG", [e.operand], x, y), "OUT"
        if isinstance(e, A.Call):
            return self.block(st_expr(e.func), [a.value for a in e.args], x, y,
                              call_pins(e)), "OUT"
        el = self.element("inVariable", x, y, negated="false")
        _sub(el, "connectionPointOut")
        _sub(el, "expression").text = _hide(st_expr(e))
        return el.get("localId") or "", None

    def block(self, kind: str, operands: list, x: float, y: float,
              pins: list[str] | None = None) -> str:
        names = pins or ([f"IN{i + 1}" for i in range(len(operands))] if kind not in ("NOT", "NEG")
                         else ["IN"])
        wired = []
        for i, (pin, op) in enumerate(zip(names, operands, strict=True)):
            negated = isinstance(op, A.Unary) and op.op == "NOT" and not isinstance(
                op.operand, A.Binary | A.Unary | A.Call) and kind != "NOT"
            src = self.value(op.operand if negated else op, x - COL, y + i * ROW)
            self.y = max(self.y, y + i * ROW)
            wired.append((pin, src, negated))
        el = self.element("block", x, y, typeName=kind)
        ins = _sub(el, "inputVariables")
        for pin, (ref, out), negated in wired:
            v = _sub(ins, "variable", formalParameter=pin, **(
                {"negated": "true"} if negated else {}))
            _connect(_sub(v, "connectionPointIn"), ref, out)
        _sub(el, "inOutVariables")
        outs = _sub(el, "outputVariables")
        _sub(_sub(outs, "variable", formalParameter="OUT"), "connectionPointOut")
        return el.get("localId") or ""

    def assign(self, s: A.Assign) -> None:
        x = 200 + COL * _depth(s.value)
        top = self.y
        if s.op in ("S=", "R="):  # set/reset: MOVE TRUE/FALSE enabled by the condition
            cond = self.value(s.value, x - COL, self.y)
            lit = self.value(A.Literal(s.loc, s.op == "S=", "BOOL", None,
                                       "TRUE" if s.op == "S=" else "FALSE"), x - COL,
                             self.y + ROW)
            el = self.element("block", x, self.y, typeName="MOVE")
            ins = _sub(el, "inputVariables")
            _connect(_sub(_sub(ins, "variable", formalParameter="EN"), "connectionPointIn"),
                     *cond)
            _connect(_sub(_sub(ins, "variable", formalParameter="IN"), "connectionPointIn"),
                     *lit)
            _sub(el, "inOutVariables")
            outs = _sub(el, "outputVariables")
            for pin in ("ENO", "OUT"):
                _sub(_sub(outs, "variable", formalParameter=pin), "connectionPointOut")
            src: tuple[str, str | None] = (el.get("localId") or "", "OUT")
            self.y += ROW
        else:
            src = self.value(s.value, x - COL, self.y)
        self.out_variable(s.target, src, x + 40, top)

    def conditional(self, s: A.If) -> None:
        """One MOVE a assignment, each enabled by the shared condition."""
        cond_e, body = s.branches[0]
        cond = self.value(cond_e, 200, self.y)
        for a in body:
            x = 200 + COL * (_depth(a.value) + 1)
            top = self.y
            val = self.value(a.value, x - COL, self.y)
            el = self.element("block", x, top, typeName="MOVE")
            ins = _sub(el, "inputVariables")
            _connect(_sub(_sub(ins, "variable", formalParameter="EN"), "connectionPointIn"),
                     *cond)
            _connect(_sub(_sub(ins, "variable", formalParameter="IN"), "connectionPointIn"),
                     *val)
            _sub(el, "inOutVariables")
            outs = _sub(el, "outputVariables")
            for pin in ("ENO", "OUT"):
                _sub(_sub(outs, "variable", formalParameter=pin), "connectionPointOut")
            self.out_variable(a.target, (el.get("localId") or "", "OUT"), x + COL, top)
            self.y = max(self.y, top) + ROW

    def out_variable(self, target: A.Expr, src: tuple[str, str | None], x: float,
                     y: float) -> None:
        el = self.element("outVariable", x, y, negated="false")
        _connect(_sub(el, "connectionPointIn"), *src)
        _sub(el, "expression").text = _hide(st_expr(target))

    def fb_call(self, s: A.CallStmt) -> None:
        call = s.call
        ins = [a for a in call.args if not a.output]
        outs = [a for a in call.args if a.output and a.value is not None]
        x = 200 + COL * max((_depth(a.value) for a in ins if a.value is not None), default=0)
        y = self.y
        wired = [(a.name or "", self.value(a.value, x - COL, y + i * ROW))
                 for i, a in enumerate(ins) if a.value is not None]
        type_name = self.fb_types[call.func.name]  # type: ignore[attr-defined]
        el = self.element("block", x, y, typeName=type_name,
                          instanceName=_hide(st_expr(call.func)))
        iv = _sub(el, "inputVariables")
        for pin, (ref, out) in wired:
            _connect(_sub(_sub(iv, "variable", formalParameter=pin), "connectionPointIn"),
                     ref, out)
        _sub(el, "inOutVariables")
        ov = _sub(el, "outputVariables")
        for a in outs:
            _sub(_sub(ov, "variable", formalParameter=a.name or "",
                      **({"negated": "true"} if a.negated else {})), "connectionPointOut")
        bid = el.get("localId") or ""
        for i, a in enumerate(outs):
            self.out_variable(a.value, (bid, a.name), x + COL, y + i * ROW)
        self.y = max(self.y, y + ROW * max(len(ins), len(outs), 1))


def _connect(cpi: ET.Element, ref: str, pin: str | None) -> None:
    _sub(cpi, "connection", refLocalId=ref, **({"formalParameter": pin} if pin else {}))


def _flatten(e: A.Expr, op: str) -> list[A.Expr]:
    """``a AND b AND c`` -> [a, b, c] (an extensible block with three inputs)."""
    out: list[A.Expr] = []
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Binary) and x.op == op:
            stack += [x.right, x.left]
        else:
            out.append(x)
    return out


def _depth(e: A.Expr) -> int:
    """How many block columns the drawing of ``e`` needs."""
    if isinstance(e, A.Binary):
        return 1 + max(_depth(x) for x in _flatten(e, e.op))
    if isinstance(e, A.Unary):
        return (1 + _depth(e.operand)) if isinstance(e.operand, A.Binary | A.Unary | A.Call) \
            else 1
    if isinstance(e, A.Call):
        return 1 + max((_depth(a.value) for a in e.args if a.value is not None), default=0)
    return 1


__all__ = ["export_plcopen", "fbd_exportable", "visible", "xml_body_text", "NS"]
