"""PLCopen XML ``<SFC>`` bodies (TC6 XML v2.01, as OpenPLC Editor and Beremiz write them) -> the
same :class:`~plclab.lang.lower.sfc_chart.Chart` as the textual SFC front end.

The graphical chart is a graph of elements joined by ``connectionPointIn/connection
refLocalId``: ``step`` (``initialStep="true"``), ``transition`` (``priority``, a ``condition``),
``selectionDivergence``/``selectionConvergence`` (alternative branches),
``simultaneousDivergence``/``simultaneousConvergence`` (parallel branches), ``jumpStep``
(``targetName``: a step to activate), ``macroStep`` (a chart in its ``body``, expanded in place)
and ``actionBlock`` (wired to a step; ``action`` with ``qualifier``, ``duration``,
``indicator`` and a ``reference`` or an ``inline`` body). The reader walks the graph: a
transition's preceding steps are found by going back through divergences and simultaneous
convergences, a step's preceding transitions through selection convergences and simultaneous
divergences (what Beremiz's ``PLCGenerator`` does before it writes the textual chart).

Conditions: ``inline`` ST (an expression) or IL; ``reference`` to a ``<transitions>`` entry
of the POU whose body is ST (``:= cond;`` as Beremiz writes it, a bare expression as CODESYS
does, or statements assigning the transition's name), IL, LD or FBD (a coil or output
variable named after the transition); or ``connectionPointIn`` wired to LD/FBD elements in the
SFC body itself. Actions: ``<actions>`` entries in any body language, inline ST/IL bodies
(named ``<STEP>_INLINE<n>``, Beremiz's convention), or a BOOL variable (a Boolean action).

Transitions that share a preceding step are tried left to right (``position x``) unless they
carry a ``priority`` (docs/adr/0023-plcopen-sfc-and-step-trace.md). Codes: PLC0184-PLC0189.
Only :func:`read_sfc_pou` is called from :mod:`.plcopen`; the body readers of the importer
are reused for every embedded body.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from typing import Any

from ...errors import Diagnostic, Location
from .. import ast as A
from ..lower.sfc_chart import Action, Assoc, Chart, Step, Transition
from ..parsing import ParseAbort

_Importer = Any  # plcopen's importer: loc, err, fail, kid, kids, ident, describe, expr, ...

_BARS = ("selectionDivergence", "selectionConvergence", "simultaneousDivergence",
         "simultaneousConvergence")
_STEPLIKE = ("step", "macroStep", "jumpStep")
_GRAPHIC = ("leftPowerRail", "rightPowerRail", "contact", "coil", "block", "inVariable",
            "outVariable", "inOutVariable", "connector", "continuation")
_SKIPPED = ("documentation", "addData", "comment")
MAX_MACRO_DEPTH = 8  # macro steps nested in macro steps


class _Stop(Exception):
    """Abandon the chart (a diagnostic was recorded). The importer's own errors (bad names,
    unparsable text) abandon the whole POU the same way."""


def read_sfc_pou(imp: _Importer, pou: A.Pou, pel: ET.Element) -> None:
    """Read the ``<SFC>`` body of the POU element ``pel`` (with its ``<actions>`` and
    ``<transitions>``) into ``pou.pending`` as a chart; diagnostics go to ``imp.diags``."""
    body = imp.kid(pel, "body")
    lang = imp.kid(body, "SFC") if body is not None else None
    if lang is None:
        return
    pou.language = "SFC"
    try:
        chart = _SfcReader(imp, pou, pel).read(lang)
    except _Stop:
        return
    if pou.kind == "FUNCTION":
        imp.err("PLC0010", "a FUNCTION keeps nothing from one call to the next, so it cannot hold "
                "an SFC chart; make the POU a functionBlock or a program", lang)
        return
    pou.pending.append(A.PendingBody("SFC", [chart], imp.loc(lang)))


class _SfcReader:
    def __init__(self, imp: _Importer, pou: A.Pou, pel: ET.Element) -> None:
        self.imp, self.pou = imp, pou
        self.actions = self._named(pel, "actions", "action")
        self.transitions = self._named(pel, "transitions", "transition")
        self.chart: Chart | None = None
        self.inline_count = 0
        self.used_actions: set[str] = set()
        self.x_of: dict[int, float] = {}
        self.referenced_names: set[str] = set()
        self.hidden_count = 0

    # -- helpers ----------------------------------------------------------------------------
    def hidden(self) -> str:
        """A generated name for a condition without a name of its own (``__SFC_C<n>``: never
        built from the file's text, which is untrusted)."""
        self.hidden_count += 1
        return f"__SFC_C{self.hidden_count}"

    def err(self, code: str, msg: str, el: ET.Element | None) -> None:
        self.imp.err(code, msg, el)

    def fail(self, code: str, msg: str, el: ET.Element | None) -> None:
        self.err(code, msg, el)
        raise _Stop

    def loc(self, el: ET.Element) -> Location:
        return self.imp.loc(el)

    def _named(self, pel: ET.Element, group: str, item: str) -> dict[str, ET.Element]:
        holder = self.imp.kid(pel, group)
        out: dict[str, ET.Element] = {}
        for el in self.imp.kids(holder, item) if holder is not None else []:
            name = el.get("name") or ""
            if name:
                out[name.upper()] = el
        return out

    def ident(self, name: str | None, el: ET.Element, what: str) -> tuple[str, str]:
        """(canonical, as written) of a name; PLC0183 when it is not an identifier."""
        text = self.imp.ident(name, el, what)
        return text.upper(), text

    def refs(self, el: ET.Element) -> list[tuple[str, ET.Element]]:
        """The localIds wired into ``el`` (all its connectionPointIn)."""
        out = []
        for cpi in self.imp.kids(el, "connectionPointIn"):
            for c in self.imp.kids(cpi, "connection"):
                rid = c.get("refLocalId")
                if rid is None:
                    self.fail("PLC0182", "<connection> without refLocalId", c)
                out.append((rid, c))
        return out

    # -- the chart --------------------------------------------------------------------------
    def read(self, lang: ET.Element) -> Chart:
        chart = Chart(self.loc(lang))
        self.chart = chart
        self.graph(lang, chart, prefix_depth=0)
        # rivals (transitions sharing a step) are tried left to right unless they have a
        # priority; the sort is stable, so elements at the same x keep document order
        chart.transitions.sort(key=lambda t: self.x_of[id(t)])
        return chart

    def graph(self, lang: ET.Element, chart: Chart, prefix_depth: int) -> tuple[str, str]:
        """Read one SFC graph (the body or a macro step's body) into ``chart``; return the
        names of its entry and exit steps (for macro steps)."""
        els: dict[str, ET.Element] = {}
        order: list[ET.Element] = []
        graphics: list[ET.Element] = []
        for el in self.imp.kids(lang):
            k = _tag(el)
            if k in _SKIPPED:
                continue
            lid = el.get("localId")
            if k in _GRAPHIC:
                graphics.append(el)
            elif k not in _STEPLIKE + _BARS + ("transition", "actionBlock"):
                self.fail("PLC0189", f"{self.imp.describe(el)} is not an SFC element plclab "
                          "reads (steps, transitions, divergences, convergences, jump steps, "
                          "macro steps, action blocks, and LD/FBD elements wired to conditions)",
                          el)
            if lid is None:
                if k in _GRAPHIC and k in ("leftPowerRail", "rightPowerRail"):
                    continue
                self.fail("PLC0184", f"{self.imp.describe(el)} has no localId; every SFC element "
                          "needs one to be connected", el)
            if lid in els:
                self.fail("PLC0182", f"localId {lid} is used twice", el)
            els[lid] = el
            order.append(el)
        names: dict[str, str] = {}  # localId of a step, macro step -> name of its (exit) step
        entries: dict[str, str] = {}  # localId of a step, macro step, jump -> name to activate
        steps_here: list[Step] = []
        for el in order:
            k = _tag(el)
            if k == "step":
                name, text = self.ident(el.get("name"), el, "step name")
                initial = el.get("initialStep") in ("true", "1")
                if initial and prefix_depth:
                    initial = False  # a macro step's entry is activated by the macro step
                step = Step(self.loc(el), name, text, initial=initial)
                chart.steps.append(step)
                steps_here.append(step)
                names[el.get("localId", "")] = name
                entries[el.get("localId", "")] = name
            elif k == "jumpStep":
                name, text = self.ident(el.get("targetName"), el, "target of the jump step")
                entries[el.get("localId", "")] = name
            elif k == "macroStep":
                if prefix_depth >= MAX_MACRO_DEPTH:
                    self.fail("PLC0188", f"macro steps nested more than {MAX_MACRO_DEPTH} deep",
                              el)
                body = self.imp.kid(el, "body")
                inner = self.imp.kid(body, "SFC") if body is not None else None
                if inner is None:
                    self.fail("PLC0188", f"macro step {el.get('name') or ''} has no <body><SFC>; "
                              "draw the steps it stands for inside it", el)
                entry, exit_ = self.graph(inner, chart, prefix_depth + 1)
                entries[el.get("localId", "")] = entry
                names[el.get("localId", "")] = exit_
        mine: dict[int, Transition] = {}  # id(transition element) -> its transition
        for el in order:
            if _tag(el) == "transition":
                tr = self.transition(el, els, names, graphics)
                mine[id(el)] = tr
                chart.transitions.append(tr)
                self.x_of[id(tr)] = _x(self.imp, el)
        for el in order:
            k = _tag(el)
            if k in _STEPLIKE:
                for tr_el in self.preceding_transitions(el, els):
                    tr = mine[id(tr_el)]
                    name = entries[el.get("localId", "")]
                    tr.targets.append((name, self.loc(el)))
                    tr.spelling.setdefault(name, el.get("name") or el.get("targetName") or name)
            elif k == "actionBlock":
                self.action_block(el, els, chart)
        for el in order:
            if _tag(el) == "transition" and not mine[id(el)].targets:
                self.fail("PLC0184", f"{self.imp.describe(el)} leads to no step; connect its "
                          "output to a step, a jump step or a divergence", el)
        if not steps_here:
            self.fail("PLC0188" if prefix_depth else "PLC0152",
                      "this SFC body has no step; draw at least an initial step", lang)
        return self.entry_exit(steps_here, chart, order, names)

    def entry_exit(self, steps: list[Step], chart: Chart, order, names) -> tuple[str, str]:
        """A macro step body's entry step (no transition leads to it, or the one marked
        initial) and exit step (no transition leaves it)."""
        here = {s.name for s in steps}
        targeted = {n for t in chart.transitions for n, _ in t.targets}
        left = {n for t in chart.transitions for n, _ in t.sources}
        marked = [el.get("name", "").upper() for el in order
                  if _tag(el) == "step" and el.get("initialStep") in ("true", "1")]
        entry = next((n for n in marked if n in here), None) or \
            next((s.name for s in steps if s.name not in targeted), steps[0].name)
        exit_ = next((s.name for s in reversed(steps) if s.name not in left), steps[-1].name)
        return entry, exit_

    # -- wiring -----------------------------------------------------------------------------
    def walk_back(self, el: ET.Element, els: dict[str, ET.Element], through: tuple[str, ...],
                  want: tuple[str, ...], what: str) -> list[ET.Element]:
        """Elements of kind ``want`` reached going back from ``el`` through ``through`` bars."""
        found: list[ET.Element] = []
        seen: set[int] = set()
        todo = [el]
        while todo:
            cur = todo.pop()
            for rid, c in self.refs(cur):
                src = els.get(rid)
                if src is None:
                    self.fail("PLC0182", f"{self.imp.describe(cur)} is connected to localId {rid}, "
                              "which does not exist in this SFC body", c)
                if id(src) in seen:
                    continue
                seen.add(id(src))
                k = _tag(src)
                if k in want:
                    found.append(src)
                elif k in through:
                    todo.append(src)
                else:
                    self.fail("PLC0184", f"{self.imp.describe(cur)} is connected to "
                              f"{self.imp.describe(src)}; {what}", c)
        return found

    def preceding_transitions(self, el: ET.Element, els) -> list[ET.Element]:
        return self.walk_back(el, els, ("selectionConvergence", "simultaneousDivergence"),
                              ("transition",), "steps follow transitions: put a transition "
                              "between two steps")

    def transition(self, el: ET.Element, els, names: dict[str, str], graphics) -> Transition:
        srcs = self.walk_back(el, els, ("selectionDivergence", "simultaneousConvergence"),
                              ("step", "macroStep"), "a transition follows steps: put a step "
                              "between two transitions")
        if not srcs:
            self.fail("PLC0184", f"{self.imp.describe(el)} has no preceding step; connect its "
                      "input to a step or a divergence", el)
        loc = self.loc(el)
        sources = [(names[s.get("localId", "")], self.loc(s)) for s in srcs]
        prio = el.get("priority")
        priority = int(prio) if prio and prio.isdigit() else None
        tr = Transition(loc, None, sources, [], priority,
                        spelling={n: n for n, _ in sources})
        for s in srcs:
            if _tag(s) == "step":
                tr.spelling[names[s.get("localId", "")]] = s.get("name", "")
        self.condition(el, tr, els, graphics)
        return tr

    # -- conditions -------------------------------------------------------------------------
    def condition(self, el: ET.Element, tr: Transition, els, graphics) -> None:
        cond = self.imp.kid(el, "condition")
        if cond is None:
            self.fail("PLC0186", f"{self.imp.describe(el)} has no <condition>; give it an inline "
                      "condition (e.g. TRUE) or a reference to a transition", el)
        kid = next((k for k in self.imp.kids(cond) if _tag(k) not in _SKIPPED), None)
        kind = _tag(kid) if kid is not None else ""
        if kind == "inline" or kind in ("ST", "IL"):
            body = kid if kind != "inline" else next(
                (k for k in self.imp.kids(kid) if _tag(k) not in _SKIPPED), None)
            if body is None or _tag(body) not in ("ST", "IL"):
                self.fail("PLC0189", f"{self.imp.describe(el)}: an inline condition is ST or IL "
                          "text; draw an LD or FBD condition wired to the transition instead",
                          kid)
            if _tag(body) == "ST":
                tr.cond = self.st_expr(body)
            else:
                tr.name = self.hidden()
                tr.il = self.il(body)
        elif kind == "reference":
            self.referenced(el, tr, kid)
        elif kind == "connectionPointIn":
            self.wired(el, tr, kid, graphics)
        elif kind == "connection":
            # TC6 v2.00 (Beremiz before 2012, its tests/linux/test_master_DS401GUI) puts the
            # <connection>s in <condition> itself; v2.01 wraps them in <connectionPointIn>
            cpi = ET.Element(cond.tag[: -len("condition")] + "connectionPointIn")
            cpi.extend(k for k in self.imp.kids(cond) if _tag(k) == "connection")
            self.imp.starts[id(cpi)] = self.imp.starts.get(id(cond), (0, 0))
            self.wired(el, tr, cpi, graphics)
        else:
            self.fail("PLC0186", f"{self.imp.describe(el)} has an empty <condition>; write an "
                      "inline condition, a reference or wire LD/FBD elements to it", cond)

    def st_expr(self, holder: ET.Element) -> A.Expr:
        """The ST text of ``holder`` as one expression (``:= e;`` and ``e;`` accepted)."""
        text = "".join(next((d for d in holder.iter() if (d.text or "").strip()), holder)
                       .itertext())
        p = self.imp.text_parser(None, holder)
        n = len(self.imp.diags)
        try:
            p.accept(":=")
            e = p.expr()
            p.accept(";")
            if not p.at("EOF"):
                p.fail_expected("the end of the transition condition")
        except ParseAbort:
            e = None
        self.imp.diags.extend(p.diagnostics)
        if e is None or len(self.imp.diags) > n:
            raise _Stop
        if not text.strip():
            self.fail("PLC0186", "the transition condition is empty", holder)
        return e

    def il(self, holder: ET.Element) -> list:
        tmp = A.Pou(self.pou.loc, self.pou.kind, self.pou.name, [], [])
        n = len(self.imp.diags)
        self.imp.il_body(tmp, holder)
        if len(self.imp.diags) > n:
            raise _Stop
        return tmp.pending[0].payload if tmp.pending else []

    def referenced(self, el: ET.Element, tr: Transition, ref: ET.Element) -> None:
        name, text = self.ident(ref.get("name"), ref, "name of the referenced transition")
        tel = self.transitions.get(name)
        if tel is None:
            have = ", ".join(sorted(t.get("name", "") for t in self.transitions.values())) \
                or "none"
            self.fail("PLC0185", f"{self.imp.describe(el)} refers to transition {text}, which "
                      f"is not in the POU's <transitions> (it has: {have}); add it or use an "
                      "inline condition", ref)
        again = name in self.referenced_names  # a second use of the same transition body
        self.referenced_names.add(name)
        tr.name, tr.text = name, text
        body = self.imp.kid(tel, "body")
        lang = next((k for k in self.imp.kids(body) if _tag(k) not in _SKIPPED), None) \
            if body is not None else None
        if lang is None:
            self.fail("PLC0186", f"transition {text} has no body", tel)
        k = _tag(lang)
        if k == "ST":
            self.st_transition(tr, lang, text)
        elif k == "IL":
            tr.il = self.il(lang)
        elif k in ("LD", "FBD"):
            tr.pending = self.network(lang, name, text)
        else:
            self.fail("PLC0189", f"transition {text}: a <{k}> body is not supported (ST, IL, LD "
                      "or FBD)", lang)
        if tr.cond is not None:  # a plain condition: anonymous, like Beremiz writes it
            tr.name, tr.text = None, ""
        elif again:  # the name is declared by its first use: this one copies it
            hidden = self.hidden()
            tr.name, tr.text = hidden, hidden
            if tr.body is not None or tr.pending:
                tr.body = (tr.body or []) + [A.Assign(tr.loc, A.Name(tr.loc, hidden, text=hidden),
                                                      A.Name(tr.loc, name, text=text))]

    def st_transition(self, tr: Transition, lang: ET.Element, text: str) -> None:
        """``:= cond;`` (Beremiz), a bare expression (CODESYS) or statements assigning the
        transition's name."""
        raw = "".join(next((d for d in lang.iter() if (d.text or "").strip()), lang).itertext())
        probe = self.imp.text_parser(raw, lang)
        as_expr = False
        try:
            probe.accept(":=")
            probe.expr()
            probe.accept(";")
            as_expr = probe.at("EOF") and not probe.diagnostics
        except ParseAbort:
            as_expr = False
        if as_expr:
            tr.cond = self.st_expr(lang)
            return
        tmp = A.Pou(self.pou.loc, self.pou.kind, self.pou.name, [], [])
        n = len(self.imp.diags)
        self.imp.st_body(tmp, lang)
        if len(self.imp.diags) > n:
            raise _Stop
        tr.body = tmp.body

    def network(self, lang: ET.Element, name: str, text: str) -> list[A.PendingBody]:
        """An LD or FBD body of a transition: it must write the transition's name with a coil
        or an output variable (as Beremiz requires)."""
        writes = [k for k in lang.iter() if _tag(k) in ("coil", "outVariable")
                  and "".join(k.itertext()).strip().upper() == name]
        if not writes:
            self.fail("PLC0186", f"the {_tag(lang)} body of transition {text} never writes "
                      f"{text}; end the network in a coil or output variable named {text}", lang)
        return self.sub_pending(lang)

    def sub_pending(self, lang: ET.Element) -> list[A.PendingBody]:
        tmp = A.Pou(self.pou.loc, self.pou.kind, self.pou.name, [], [])
        n = len(self.imp.diags)
        self.imp.body_readers()[_tag(lang)](tmp, lang)
        if len(self.imp.diags) > n:
            raise _Stop
        return tmp.pending

    def wired(self, el: ET.Element, tr: Transition, cpi: ET.Element, graphics) -> None:
        """LD or FBD elements of the SFC body wired into the transition's condition: a network
        of its own, ending in an output variable that writes the hidden condition."""
        hidden = self.hidden()
        by_id = {g.get("localId"): g for g in graphics}
        todo, seen, mine = [cpi], set(), []
        while todo:  # the LD/FBD elements this condition reads, and nothing else
            for c in todo.pop().iter():
                g = by_id.get(c.get("refLocalId")) if _tag(c) == "connection" else None
                if g is not None and id(g) not in seen:
                    seen.add(id(g))
                    mine.append(g)
                    todo.append(g)
        # the condition's own elements say whether it is LD or FBD (not the rest of the body)
        tag = "LD" if any(_tag(g) in ("contact", "coil", "leftPowerRail") for g in mine) \
            else "FBD"
        net = ET.Element(tag)
        net.extend(mine)
        if tag == "LD":
            net.extend(g for g in graphics if _tag(g) == "leftPowerRail" and id(g) not in seen)
        out = ET.SubElement(net, "outVariable", {"localId": f"{hidden}-out"})
        out.append(cpi)
        expr = ET.SubElement(out, "expression")
        expr.text = "TRUE"
        self.imp.starts[id(net)] = self.imp.starts.get(id(el), (0, 0))
        self.imp.starts[id(out)] = self.imp.starts.get(id(el), (0, 0))
        pend = self.sub_pending(net)
        for body in pend:
            for e in body.payload if body.kind == "NETWORK" else []:
                if e.kind == "outvar" and e.loc == self.loc(el) and \
                        isinstance(e.var, A.Literal):
                    e.var = A.Name(e.loc, hidden, text=hidden)
        tr.name, tr.text = hidden, hidden
        tr.pending = pend

    # -- actions ----------------------------------------------------------------------------
    def action_block(self, el: ET.Element, els, chart: Chart) -> None:
        src = self.walk_back(el, els, (), ("step", "macroStep"),
                             "an action block is wired to a step")
        if len(src) != 1 or _tag(src[0]) != "step":
            self.fail("PLC0184", f"{self.imp.describe(el)} must be wired to exactly one step", el)
        sname = (src[0].get("name") or "").upper()
        step = next(s for s in chart.steps if s.name == sname)
        for a in self.imp.kids(el, "action"):
            step.assocs.append(self.association(a, step, chart))

    def association(self, a: ET.Element, step: Step, chart: Chart) -> Assoc:
        ref = self.imp.kid(a, "reference")
        inline = self.imp.kid(a, "inline")
        if ref is not None:
            name, text = self.ident(ref.get("name"), ref, "action name")
            if name in self.actions and name not in self.used_actions:
                self.used_actions.add(name)
                chart.actions.append(self.declared_action(name, text, self.actions[name]))
        elif inline is not None:
            self.inline_count += 1
            text = f"{step.text}_INLINE{self.inline_count}"
            name = text.upper()
            body = next((k for k in self.imp.kids(inline) if _tag(k) not in _SKIPPED), None)
            if body is None or _tag(body) not in ("ST", "IL"):
                self.fail("PLC0189", "an inline action is ST or IL text; put a graphical body in "
                          "the POU's <actions> and refer to it", inline)
            chart.actions.append(self.action_from(name, text, body, a))
        else:
            self.fail("PLC0184", f"{self.imp.describe(a)} names no action: give it a "
                      "<reference name=...> or an <inline> body", a)
        assoc = Assoc(self.loc(a), name, text, (a.get("qualifier") or "N").upper())
        duration = a.get("duration")
        if duration:
            assoc.time = self.imp.expr(_duration(duration), a, "action duration")
        return assoc

    def declared_action(self, name: str, text: str, ael: ET.Element) -> Action:
        body = self.imp.kid(ael, "body")
        lang = next((k for k in self.imp.kids(body) if _tag(k) not in _SKIPPED), None) \
            if body is not None else None
        if lang is None:
            return Action(self.loc(ael), name, text)
        if _tag(lang) == "SFC":
            self.fail("PLC0189", f"action {text} holds an SFC chart; plclab does not nest charts "
                      "in actions: write the action in ST, IL, LD or FBD", lang)
        return self.action_from(name, text, lang, ael)

    def action_from(self, name: str, text: str, lang: ET.Element, el: ET.Element) -> Action:
        if _tag(lang) not in self.imp.body_readers():
            self.fail("PLC0189", f"action {text}: a <{_tag(lang)}> body is not supported", lang)
        act = Action(self.loc(el), name, text)
        if _tag(lang) == "ST":
            tmp = A.Pou(self.pou.loc, self.pou.kind, self.pou.name, [], [])
            n = len(self.imp.diags)
            self.imp.st_body(tmp, lang)
            if len(self.imp.diags) > n:
                raise _Stop
            act.body = tmp.body
        elif _tag(lang) == "IL":
            act.il = self.il(lang)
        else:
            act.pending = self.sub_pending(lang)
        return act


def _duration(s: str) -> str:
    """``PT1M30S`` (ISO 8601, written by some editors) -> ``T#90000ms``; IEC literals pass."""
    m = re.fullmatch(r"PT(?:([\d.]+)H)?(?:([\d.]+)M)?(?:([\d.]+)S)?", s.strip())
    if not m or not any(m.groups()):
        return s
    h, mi, sec = (float(x) if x else 0.0 for x in m.groups())
    return f"T#{round(((h * 60 + mi) * 60 + sec) * 1000)}ms"


def _x(imp: _Importer, el: ET.Element) -> float:
    pos = imp.kid(el, "position")
    try:
        return float(pos.get("x", 0) or 0) if pos is not None else 0.0
    except ValueError:
        return 0.0


def _tag(el: ET.Element) -> str:
    t = el.tag
    return t.split("}", 1)[1] if isinstance(t, str) and t.startswith("{") else str(t)


__all__ = ["read_sfc_pou", "Diagnostic"]
