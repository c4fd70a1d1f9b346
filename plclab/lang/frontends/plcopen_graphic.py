"""The LD and FBD bodies of the PLCopen XML reader: elements, connections, blocks and their
pins read into the networks of :mod:`plclab.lang.lower.network` (a mixin of the importer in
:mod:`plclab.lang.frontends.plcopen`).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from ...errors import Diagnostic
from .. import ast as A
from ..lexer import identifier_problem
from ..lower.network import Elem, plan_feedback
from .plcopen_base import IGNORED, Bad, local_name

MAX_BOX_CHAIN = 100  # function boxes feeding each other directly in one LD/FBD network


class GraphicRead:
    """LD and FBD networks (a mixin of the importer)."""

    def graphic_body(self, pou: A.Pou, lang: ET.Element) -> None:
        tag = local_name(lang.tag)
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
            k = local_name(el.tag)
            try:
                if k in IGNORED:
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
            except Bad:
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


def _num(s: str | None) -> float:
    """A coordinate; a malformed one counts as 0 (positions only order and draw elements)."""
    try:
        return float(s or 0)
    except ValueError:
        return 0.0

