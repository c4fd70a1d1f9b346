"""LD and FBD networks (the text ladder's or a PLCopen file's, as the front end read them)
written back as PLCopen elements for ``plclab export``. ADR 0022."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from . import ast as A
from .plcopen_elements import call_pins, connect, hide, sub
from .unparse import expr as st_expr

WRITABLE = {"left", "contact", "coil", "fb", "func", "cmp", "invar", "outvar", "inoutvar",
             "conn", "jump", "label", "return"}


class NetworkWriter:
    """An LD or FBD network (text ladder or PLCopen) written back as PLCopen elements: power
    rails, contacts and coils with their kinds, boxes with named pins (a text box's rung
    enters its first BOOL input), parameters as in-variables, results as out-variables."""

    def __init__(self, holder: ET.Element, elems: list, pous: dict[str, A.Pou],
                 user_inputs: dict[str, list[str]]) -> None:
        self.holder = holder
        self.user_inputs = user_inputs
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
        sub(el, "position", x=str(x), y=str(y))

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
        cpi = sub(parent, "connectionPointIn")
        for ref, pin in self.refs(refs):
            connect(cpi, ref, pin)
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
            el = sub(self.holder, "leftPowerRail", localId=self.rail)
            self.place(el, 0, 0)
            sub(el, "connectionPointOut", formalParameter="")
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
                el = sub(self.holder, k, **attrs)
                self.place(el, x, y)
                self.connect(el, e.inputs.get("", []))
                sub(el, "connectionPointOut")
                sub(el, "variable").text = hide(st_expr(e.var))
                if k == "coil":
                    coils.append(e)
            elif k in ("invar", "outvar", "inoutvar"):
                tag = {"invar": "inVariable", "outvar": "outVariable"}.get(k, "inOutVariable")
                el = sub(self.holder, tag, localId=self.lid(e.id))
                self.place(el, x, y)
                if k != "invar":
                    self.connect(el, e.inputs.get("", []))
                if k != "outvar":
                    sub(el, "connectionPointOut")
                sub(el, "expression").text = hide(st_expr(e.var))
            elif k in ("jump", "label", "return"):
                el = sub(self.holder, k, localId=self.lid(e.id),
                          **({"label": e.label} if k != "return" else {}))
                self.place(el, x, y)
                if k != "label":
                    self.connect(el, e.inputs.get("", []))
            elif k in ("fb", "func", "cmp"):
                self.box(e, x, y)
        if coils:
            right = sub(self.holder, "rightPowerRail", localId=self.fresh())
            self.place(right, 800, 0)
            for c in coils:
                connect(sub(right, "connectionPointIn"), self.lid(c.id), None)

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
                                                   e.type_name), e.args),
                              self.user_inputs) or \
                [f"IN{i + 1}" for i in range(len(e.args))]
            for pin, a in zip(names, e.args, strict=False):
                inputs.append((pin, self.variable(a.value, x - 60, y)))
        attrs = {"localId": self.lid(e.id), "typeName": e.type_name}
        if e.instance is not None:
            attrs["instanceName"] = hide(st_expr(e.instance))
        if e.kind == "cmp":  # power AND (a <op> b): the comparison, then an AND
            attrs["localId"] = self.fresh()
        el = sub(self.holder, "block", **attrs)
        self.place(el, x, y)
        iv = sub(el, "inputVariables")
        for pin, src in inputs:
            if e.kind == "cmp" and pin == "EN":
                continue
            v = sub(iv, "variable", formalParameter=pin, **(
                {"negated": "true"} if pin in e.neg_in else {}), **(
                {"edge": "rising" if e.edge_in[pin] == "P" else "falling"}
                if pin in e.edge_in else {}))
            if isinstance(src, str):
                connect(sub(v, "connectionPointIn"), src, None)
            else:
                self.connect(v, src)
        sub(el, "inOutVariables")
        ov = sub(el, "outputVariables")
        outs = list(e.outs) or ([power_out] if "" in e.inputs and e.kind == "fb" else []) + \
            ([] if e.kind == "fb" else ["ENO", "OUT"] if e.kind == "func" else ["OUT"])
        for pin, _ in outputs:
            if pin not in outs:
                outs.append(pin)
        for pin in outs:
            sub(sub(ov, "variable", formalParameter=pin, **(
                {"negated": "true"} if pin in e.neg_out else {})), "connectionPointOut")
        for pin, target in outputs:
            self.out_variable(target, el.get("localId") or "", pin, x + 120, y)
        for t in e.targets:
            self.out_variable(t, el.get("localId") or "", "OUT", x + 120, y)
        if e.kind == "cmp":
            self.power_out[e.id] = "OUT"
            and_el = sub(self.holder, "block", localId=self.lid(e.id), typeName="AND")
            self.place(and_el, x + 60, y)
            ai = sub(and_el, "inputVariables")
            self.connect(sub(ai, "variable", formalParameter="IN1"), e.inputs.get("", []))
            connect(sub(sub(ai, "variable", formalParameter="IN2"), "connectionPointIn"),
                     el.get("localId") or "", "OUT")
            sub(and_el, "inOutVariables")
            sub(sub(sub(and_el, "outputVariables"), "variable", formalParameter="OUT"),
                 "connectionPointOut")

    def variable(self, value: A.Expr, x: int, y: int) -> str:
        el = sub(self.holder, "inVariable", localId=self.fresh())
        self.place(el, x, y)
        sub(el, "connectionPointOut")
        sub(el, "expression").text = hide(st_expr(value))
        return el.get("localId") or ""

    def out_variable(self, target: A.Expr, ref: str, pin: str, x: int, y: int) -> None:
        el = sub(self.holder, "outVariable", localId=self.fresh())
        self.place(el, x, y)
        connect(sub(el, "connectionPointIn"), ref, pin)
        sub(el, "expression").text = hide(st_expr(target))
