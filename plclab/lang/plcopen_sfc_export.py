"""SFC charts -> PLCopen XML ``<SFC>`` bodies (TC6 v2.01), as Beremiz and OpenPLC Editor write
them and as :mod:`plclab.lang.frontends.plcopen_sfc` reads them back (ADR 0022, ADR 0023).

What a chart becomes:

* a ``step`` per step (``initialStep="true"`` for the initial one), with an ``actionBlock``
  wired to it holding its associations (``qualifier``, ``duration``, a ``reference`` to a
  declared action or to a BOOL variable: a Boolean action);
* a ``transition`` per transition, with ``priority`` when the text gives one; a condition
  ``:= e;`` without a name is an ``inline`` ST condition, any other condition (a named one, ST
  statements, IL lines) is an entry of the POU's ``<transitions>`` the transition refers to;
* a ``selectionDivergence`` under a step several transitions leave, a
  ``selectionConvergence`` over a step several transitions lead to, a
  ``simultaneousConvergence`` over a transition leaving several steps and a
  ``simultaneousDivergence`` under a transition activating several steps;
* a ``jumpStep`` where a transition leads back (to a step drawn above it);
* the declared actions as ``<actions>`` of the POU, with ST or IL bodies.

Layout: steps in rows, a row further down each time a transition leads forward, the branches of
a divergence left to right in the order the text declares them: the importer tries rival
transitions left to right, so the drawing keeps the chart's precedence.

Not exported (:class:`PlcError` PLC4042): LD or FBD bodies of actions and transitions (they only
come from PLCopen files), and IL bodies when the source text is not known or is XML.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from ..errors import PlcError
from . import ast as A
from .lower.sfc_chart import Chart, Step, Transition
from .plcopen_elements import hide, sub, text_body, visible
from .unparse import expr as st_expr
from .unparse import unparse

COLUMN, ROW = 260, 150  # the grid of steps
STEP_W, STEP_H = 60, 30
BRANCH = 70  # horizontal distance between the branches of a divergence


def source_chart(p: A.Pou, file: str, sources: dict[str, str]) -> Chart | None:
    """The chart of ``p`` as its front end read it (before lowering), when the source is known;
    else the chart kept by the lowering (``Pou.sfc``)."""
    from .frontends.registry import for_file

    text = sources.get(file)
    if text is not None:
        src, diags = for_file(file).parse(text, file)
        if not any(d.severity == "error" for d in diags):
            for q in src.pous:
                if q.name == p.name:
                    for b in q.pending:
                        if b.kind == "SFC":
                            return b.payload[0]
    return p.sfc


def chart_names(chart: Chart) -> set[str]:
    """Names the lowering declares for a chart (steps, actions, named transitions): the
    importer declares them again, so the interface leaves them out."""
    return ({s.name for s in chart.steps} | {a.name for a in chart.actions}
            | {t.name for t in chart.transitions if t.name})


class SfcWriter:
    """Writes one chart: ``<actions>``, ``<transitions>`` and ``<body><SFC>`` of a POU."""

    def __init__(self, p: A.Pou, chart: Chart, file: str, sources: dict[str, str]) -> None:
        self.p, self.chart = p, chart
        self.text = sources.get(file) if not file.lower().endswith(".xml") else None
        self.ids = 0
        self.steps = {s.name: s for s in chart.steps}

    def lid(self) -> str:
        self.ids += 1
        return str(self.ids)

    # -- the POU's parts ----------------------------------------------------------------------
    def write(self, pel: ET.Element) -> None:
        if self.chart.actions:
            holder = sub(pel, "actions")
            for a in self.chart.actions:
                ael = sub(holder, "action", name=a.text or a.name)
                self.body(sub(ael, "body"), a.body, a.il, bool(a.pending), a.loc, "END_ACTION",
                          f"action {a.text}")
        named = [t for t in self.chart.transitions if t.name]
        if named:
            holder = sub(pel, "transitions")
            for t in named:
                tel = sub(holder, "transition", name=visible(t.text or t.name or ""))
                body = t.body
                if t.cond is not None:  # the name stays a variable: assign it
                    body = [A.Assign(t.loc, A.Name(t.loc, t.name or "", text=t.text), t.cond)]
                self.body(sub(tel, "body"), body or [], t.il, bool(t.pending), t.loc,
                          "END_TRANSITION", f"transition {t.text}")
        self.graph(sub(sub(pel, "body"), "SFC"))

    def body(self, holder: ET.Element, stmts: list[A.Stmt], il, drawn: bool, loc,
             end: str, what: str) -> None:
        if drawn:
            raise PlcError("PLC4042", f"{what} of {self.p.spelling or self.p.name} is an LD or "
                           "FBD network in a PLCopen chart; plclab exports chart bodies in ST or "
                           "IL only: keep the original XML file, or rewrite the body in ST", loc)
        if il is not None:
            text_body(sub(holder, "IL"), self.il_text(loc, end, what))
        else:
            text_body(sub(holder, "ST"), hide(unparse(stmts) if stmts else ""))

    def il_text(self, loc, end: str, what: str) -> str:
        """The IL lines of an action or transition as written in the textual SFC source."""
        seg = None
        if self.text is not None:
            lines = self.text.split("\n")
            rest = "\n".join([lines[loc.line - 1][max(loc.col - 1, 0):]] + lines[loc.line:])
            head = r"\bTO\b\s*(?:\([^)]*\)|[A-Za-z_]\w*)\s*:(?!=)" if end == "END_TRANSITION" \
                else r"^\s*[A-Za-z_]\w*\s*:"
            m = re.search(head, rest, re.IGNORECASE)
            e = re.search(rf"\b{end}\b", rest, re.IGNORECASE)
            if m and e and m.end() <= e.start():
                seg = rest[m.end():e.start()].strip("\n")
        if seg is None:
            raise PlcError("PLC4042", f"{what} of {self.p.spelling or self.p.name} has an IL "
                           "body whose text is not known here (a PLCopen source, or no source "
                           "text); export it from its textual SFC file, or write it in ST", loc)
        return seg + "\n"

    # -- the drawing ----------------------------------------------------------------------------
    def graph(self, sfc: ET.Element) -> None:
        ch = self.chart
        order = self.visit_order()
        rank = {n: i for i, n in enumerate(order)}
        leaving: dict[str, list[int]] = {s.name: [] for s in ch.steps}
        for k, t in enumerate(ch.transitions):
            for n, _ in t.sources:
                leaving[n].append(k)

        def direct(t: Transition, target: str) -> bool:  # drawn below all its sources
            return rank[target] > max(rank[n] for n, _ in t.sources)

        level: dict[str, int] = {}
        for n in order:
            feeders = [max(level[m] for m, _ in t.sources) for t in ch.transitions
                       if any(x == n for x, _ in t.targets) and direct(t, n)]
            level[n] = max(feeders) + 1 if feeders else (0 if self.steps[n].initial else
                                                         max(level.values(), default=-1) + 1)
        pos, tx = self.place(order, level, leaving, direct, last=False)
        if tx is None:  # a transition leaving several steps drawn under its last one
            pos, tx = self.place(order, level, leaving, direct, last=True)
        if tx is None:  # each transition in a column of its own, in declared order
            tx = [40 + k * BRANCH for k in range(len(ch.transitions))]
        # ids first: elements refer to each other in both directions
        step_id = {s.name: self.lid() for s in ch.steps}
        div_id = {n: self.lid() for n, ks in leaving.items() if len(ks) > 1}
        tr_id = [self.lid() for _ in ch.transitions]
        conv_id = {k: self.lid() for k, t in enumerate(ch.transitions) if len(t.sources) > 1}
        sdiv_id = {k: self.lid() for k, t in enumerate(ch.transitions) if len(t.targets) > 1}
        feeders: dict[str, list[str]] = {s.name: [] for s in ch.steps}
        feeder_x: dict[tuple[str, str], int] = {}  # (feeder, step) -> x of the wire
        jumps: list[tuple[str, str, int, int]] = []  # (from id, target, x, y)
        branch_x: dict[tuple[int, int], int] = {}  # (transition, target) -> x of its wire
        for k, t in enumerate(ch.transitions):
            src = tr_id[k] if k not in sdiv_id else sdiv_id[k]
            y = max(pos[m][1] for m, _ in t.sources) + STEP_H + 70
            for i, (n, _) in enumerate(t.targets):
                bx = pos[n][0] + STEP_W // 2 if direct(t, n) and k in sdiv_id else \
                    tx[k] + 10 + i * BRANCH
                branch_x[k, i] = bx
                if direct(t, n):
                    feeders[n].append(src)
                    feeder_x[src, n] = bx
                else:
                    jumps.append((src, n, bx - 6, y + (50 if k in sdiv_id else 30)))

        def out_point(n: str) -> str:
            return div_id.get(n, step_id[n])

        for s in ch.steps:
            x, y = pos[s.name]
            into = feeders[s.name]
            conv = self.lid() if len(into) > 1 else None
            if conv is not None:
                xs = [feeder_x[f, s.name] for f in into] + [x + STEP_W // 2]
                left = min(xs)
                el = sub(sfc, "selectionConvergence", localId=conv, height="1",
                         width=str(max(xs) - left))
                sub(el, "position", x=str(left), y=str(y - 12))
                for f in into:
                    self.point_in(el, [f], feeder_x[f, s.name] - left, 0)
                self.point_out(el, x + STEP_W // 2 - left, 1, formal=False)
            attrs = {"localId": step_id[s.name], "name": s.text or s.name}
            if s.initial:
                attrs["initialStep"] = "true"
            el = sub(sfc, "step", **attrs, height=str(STEP_H), width=str(STEP_W))
            sub(el, "position", x=str(x), y=str(y))
            if into:
                self.point_in(el, [conv] if conv else into, STEP_W // 2, 0)
            self.point_out(el, STEP_W // 2, STEP_H)
            if s.assocs:
                out = sub(el, "connectionPointOutAction", formalParameter="")
                sub(out, "relPosition", x=str(STEP_W), y=str(STEP_H // 2))
                self.action_block(sfc, s, step_id[s.name], x + STEP_W + 40, y)
            if s.name in div_id:
                ks = leaving[s.name]
                left = min(tx[k] for k in ks) + 10
                width = max(tx[k] for k in ks) + 10 - left
                el = sub(sfc, "selectionDivergence", localId=div_id[s.name], height="1",
                         width=str(width))
                sub(el, "position", x=str(left), y=str(y + STEP_H + 35))
                self.point_in(el, [step_id[s.name]], x + STEP_W // 2 - left, 0)
                for k in ks:
                    self.point_out(el, tx[k] + 10 - left, 1)
        for k, t in enumerate(ch.transitions):
            y = max(pos[m][1] for m, _ in t.sources) + STEP_H + 70
            ins = [out_point(n) for n, _ in t.sources]
            if k in conv_id:
                xs = [pos[m][0] + STEP_W // 2 for m, _ in t.sources] + [tx[k] + 10]
                left = min(xs)
                el = sub(sfc, "simultaneousConvergence", localId=conv_id[k], height="3",
                         width=str(max(xs) - left))
                sub(el, "position", x=str(left), y=str(y - 12))
                for f, bx in zip(ins, xs, strict=False):
                    self.point_in(el, [f], bx - left, 0)
                self.point_out(el, tx[k] + 10 - left, 3, formal=False)
                ins = [conv_id[k]]
            attrs = {"localId": tr_id[k], "height": "2", "width": "20"}
            if t.priority is not None:
                attrs["priority"] = str(t.priority)
            el = sub(sfc, "transition", **attrs)
            sub(el, "position", x=str(tx[k]), y=str(y))
            self.point_in(el, ins, 10, 0)
            self.point_out(el, 10, 2, formal=False)
            cond = sub(el, "condition")
            if t.name:
                sub(cond, "reference", name=visible(t.text or t.name or ""))
            else:
                assert t.cond is not None  # the checker: an unnamed transition has ':= e;'
                text_body(sub(sub(cond, "inline", name=""), "ST"), hide(st_expr(t.cond)))
            if k in sdiv_id:
                xs = [branch_x[k, i] for i in range(len(t.targets))] + [tx[k] + 10]
                left = min(xs)
                el = sub(sfc, "simultaneousDivergence", localId=sdiv_id[k], height="3",
                         width=str(max(xs) - left))
                sub(el, "position", x=str(left), y=str(y + 20))
                self.point_in(el, [tr_id[k]], tx[k] + 10 - left, 0)
                for i in range(len(t.targets)):
                    self.point_out(el, branch_x[k, i] - left, 3)
        for src, target, x, y in jumps:
            el = sub(sfc, "jumpStep", localId=self.lid(),
                     targetName=self.steps[target].text or target, height="13", width="12")
            sub(el, "position", x=str(x), y=str(y))
            self.point_in(el, [src], 6, 0)

    def visit_order(self) -> list[str]:
        """Steps in the order a reader meets them: from the initial step, following the
        transitions as declared (breadth first); steps not reached come last."""
        ch = self.chart
        seen: list[str] = [s.name for s in ch.steps if s.initial]
        i = 0
        while i < len(seen):
            for t in ch.transitions:
                if any(n == seen[i] for n, _ in t.sources):
                    for n, _ in t.targets:
                        if n not in seen:
                            seen.append(n)
            i += 1
        return seen + [s.name for s in ch.steps if s.name not in seen]

    def place(self, order: list[str], level: dict[str, int], leaving: dict[str, list[int]],
              direct, last: bool) -> tuple[dict[str, tuple[int, int]], list[int] | None]:
        """(x, y) of every step and x of every transition. The transitions a step leads to
        (those whose first preceding step it is, or ``last``) take one column each, left to
        right in declared order, starting under the step; a step goes in the column of the
        first transition that leads down to it, or the next free one of its row. The x are
        None when they would put rivals (transitions sharing a step, same priority) in another
        order than the declared one: the importer tries rivals left to right."""
        ch = self.chart
        rank = {n: i for i, n in enumerate(order)}

        def anchor(t: Transition) -> str:
            names = [n for n, _ in t.sources]
            return max(names, key=rank.__getitem__) if last else names[0]

        anchored = {n: [k for k in ks if anchor(ch.transitions[k]) == n]
                    for n, ks in leaving.items()}
        used: dict[int, set[int]] = {}
        col: dict[str, int] = {}
        tcol: dict[int, int] = {}
        for n in order:
            want = next((tcol[k] for k, t in enumerate(ch.transitions)
                         if k in tcol and any(x == n for x, _ in t.targets) and direct(t, n)), 0)
            row = used.setdefault(level[n], set())
            width = max(len(anchored[n]), 1)
            c = want
            while any(c + i in row for i in range(width)):
                c += 1
            row.update(range(c, c + width))
            col[n] = c
            for i, k in enumerate(anchored[n]):
                tcol[k] = c + i
        pos = {n: (40 + col[n] * COLUMN, 20 + level[n] * ROW) for n in order}
        xs = [40 + tcol[k] * COLUMN + STEP_W // 2 - 10 for k in range(len(ch.transitions))]
        for ks in leaving.values():
            for a, i in enumerate(ks):
                for j in ks[a + 1:]:
                    if ch.transitions[i].priority == ch.transitions[j].priority and xs[i] > xs[j]:
                        return pos, None
        return pos, xs

    # -- pieces ---------------------------------------------------------------------------------
    def action_block(self, sfc: ET.Element, s: Step, step: str, x: int, y: int) -> None:
        el = sub(sfc, "actionBlock", localId=self.lid(), height=str(30 * len(s.assocs)),
                 width="140")
        sub(el, "position", x=str(x), y=str(y))
        self.point_in(el, [step], 0, STEP_H // 2)
        for i, a in enumerate(s.assocs):
            attrs = {"localId": str(i), "qualifier": a.qualifier}
            if a.time is not None:
                attrs["duration"] = hide(st_expr(a.time))
            act = sub(el, "action", **attrs)
            sub(act, "relPosition", x="0", y=str(30 * i))
            sub(act, "reference", name=a.text or a.action)

    @staticmethod
    def point_in(el: ET.Element, refs: list[str], x: int, y: int) -> None:
        cpi = sub(el, "connectionPointIn")
        sub(cpi, "relPosition", x=str(x), y=str(y))
        for r in refs:
            sub(cpi, "connection", refLocalId=r)

    @staticmethod
    def point_out(el: ET.Element, x: int, y: int, *, formal: bool = True) -> None:
        """A ``connectionPointOut``; TC6 v2.01 gives ``formalParameter`` to those of a step and
        of the divergences only (a transition's or a convergence's has none: the XSD refuses
        it), and Beremiz writes ``formalParameter=""`` where it may."""
        attrs = {"formalParameter": ""} if formal else {}
        out = sub(el, "connectionPointOut", **attrs)
        sub(out, "relPosition", x=str(x), y=str(y))


__all__ = ["SfcWriter", "chart_names", "source_chart"]
