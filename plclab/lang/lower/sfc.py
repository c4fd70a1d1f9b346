"""SFC charts -> the core AST: step records, transitions, ACTION_CONTROL blocks, action bodies.

A chart comes from the textual SFC of a PROGRAM or FUNCTION_BLOCK body
(:mod:`plclab.lang.frontends.sfc_text`) as a :class:`~plclab.lang.ast.PendingBody` of kind
``"SFC"`` holding one :class:`Chart`. Lowering checks it (:mod:`.sfc_checks`) and writes plain
statements, in this order every scan (docs/adr/0016-sfc-semantics.md):

0. **step times**: ``S.T`` of every active step follows a hidden ``SFC_TIMER`` started when
   ``S`` was activated, the initial step's at the POU instance's creation (the virtual clock,
   sampled once per scan; IEC 61131-3 ed.2 2.6.2, ed.3 6.7.2);
1. **transitions** on the step flags at the start of the scan: ``__SFC_TR<k>`` is TRUE when all
   preceding steps are active, no transition of higher precedence took one of them, and the
   condition is TRUE (precedence: ``PRIORITY`` ascending, then declaration order);
2. **evolution**: every fired transition deactivates its preceding steps, then every fired
   transition activates its following steps (activation wins), sets their ``T`` to 0 and
   restarts their timers;
3. **actions**: one ``ACTION_CONTROL`` (plclab/runtime/sfclib.st) per action, fed with the OR of
   the active steps' associations per qualifier; an action body runs while its ``A`` output is
   TRUE (``Q``, plus one final scan); a Boolean action's variable takes ``Q``.

A step ``S`` becomes a variable ``S : SFC_STEP`` (``S.X``, ``S.T`` readable anywhere in the
POU, and from tests as ``Main.S.X``); a declared action ``A1`` becomes ``A1 : ACTION_CONTROL``
(``A1.Q``, ``A1.A``). Hidden names start with ``__SFC_``.
"""

from __future__ import annotations

from ...errors import Diagnostic, Location
from .. import ast as A
from .il import Instr, lower_il
from .network import lower_network
from .sfc_chart import Assoc, Chart, Step
from .sfc_checks import check_chart
from .types import LoweringTypes

TIMED = ("L", "D", "SD", "DS", "SL")
QUALIFIERS = ("N", "R", "S", "P", "P1", "P0") + TIMED
# qualifier -> ACTION_CONTROL input (S is S0 there: IEC ed. 2, figure 14)
_INPUT = {"N": "N", "R": "R", "S": "S0", "L": "L", "D": "D", "P": "P", "P1": "P1",
          "P0": "P0", "SD": "SD", "DS": "DS", "SL": "SL"}
MAX_TIME_NS = 2147483647000000  # T#24d20h31m23s647ms: the step timer's preset


def lower_sfc(pou: A.Pou, payload: list[Chart], types: LoweringTypes) -> list[Diagnostic]:
    """Check the chart and translate it into ``pou.body`` and hidden declarations."""
    chart = payload[0]
    diags = check_chart(chart, pou, types)
    if any(d.severity == "error" for d in diags):
        for d in pou.decls:  # the body stays empty: no "never used" on top of the error
            d.used = True
        return diags
    low = _Lowering(pou, chart, types)
    low.run()
    pou.sfc = chart
    return diags + low.diags


# -- small AST builders -----------------------------------------------------------------------
def _name(n: str, loc: Location, text: str = "") -> A.Name:
    return A.Name(loc, n, text=text or n)


def _flag(step: str, field_name: str, loc: Location, text: str = "") -> A.Member:
    return A.Member(loc, _name(step, loc, text), field_name, text=field_name)


def _bool(v: bool, loc: Location) -> A.Literal:
    return A.Literal(loc, v, "BOOL", text="TRUE" if v else "FALSE")


def _time(ns: int, loc: Location) -> A.Literal:
    text = "T#24d20h31m23s647ms" if ns == MAX_TIME_NS else f"T#{ns // 1_000_000}ms"
    return A.Literal(loc, ns, "TIME", "TIME", text)


def _any(terms: list[A.Expr], op: str, loc: Location) -> A.Expr:
    out = terms[0]
    for t in terms[1:]:
        out = A.Binary(loc, op, out, t)
    return out


def _call(inst: str, args: list[tuple[str, A.Expr]], loc: Location) -> A.CallStmt:
    return A.CallStmt(loc, A.Call(loc, _name(inst, loc),
                                  [A.Arg(loc, k, v) for k, v in args]))


def _decl(name: str, type_name: str, loc: Location, init: A.Expr | None = None,
          spelling: str = "", section: str = "VAR") -> A.VarDecl:
    return A.VarDecl(loc, name, A.NamedTypeRef(loc, type_name), init, section=section,
                     spelling=spelling or name)


def transition_order(chart: Chart) -> list[int]:
    """Indices of the chart's transitions by precedence: ``PRIORITY`` ascending (a
    transition without one after all that have one), then declaration order."""
    big = 1 << 62
    return sorted(range(len(chart.transitions)),
                  key=lambda k: (chart.transitions[k].priority
                                 if chart.transitions[k].priority is not None else big, k))


class _Lowering:
    def __init__(self, pou: A.Pou, chart: Chart, types: LoweringTypes) -> None:
        self.pou, self.chart, self.types = pou, chart, types
        self.text: dict[str, str] = {}
        self.out: list[A.Stmt] = []
        self.decls: list[A.VarDecl] = []
        self.diags: list[Diagnostic] = []

    def run(self) -> None:
        ch = self.chart
        for s in ch.steps:
            init = (A.StructInit(s.loc, [("X", _bool(True, s.loc), s.loc)]) if s.initial
                    else None)
            self.decls.append(_decl(s.name, "SFC_STEP", s.loc, init, s.text))
            self.decls.append(_decl(f"__SFC_TMR_{s.name}", "SFC_TIMER", s.loc))
        self.text = {s.name: s.text for s in ch.steps}
        order = transition_order(ch)
        self.step_times()
        for k in order:
            self.transition(k)
        self.evolution(order)
        self.actions()
        self.pou.body = self.out
        self.pou.decls.extend(sorted(self.decls, key=lambda d: d.section == "VAR_TEMP"))

    def flag(self, step: str, field_name: str, loc: Location) -> A.Member:
        """``S.X`` / ``S.T`` with the step's name as written."""
        return _flag(step, field_name, loc, self.text.get(step, ""))

    # 1. transitions -----------------------------------------------------------------------
    def transition(self, k: int) -> None:
        t = self.chart.transitions[k]
        loc = t.loc
        fired = f"__SFC_TR{k}"
        self.decls.append(_decl(fired, "BOOL", loc, section="VAR_TEMP"))
        enabled: list[A.Expr] = [self.flag(n, "X", l) for n, l in t.sources]
        # a step gives its token to one transition only: the first by precedence
        for j in self.earlier_rivals(k):
            enabled.append(A.Unary(loc, "NOT", _name(f"__SFC_TR{j}", loc)))
        body: list[A.Stmt] = []
        if t.cond is not None:
            cond: A.Expr = t.cond
            if t.name:  # a named transition keeps its condition readable
                body.append(A.Assign(loc, _name(t.name, loc), cond))
                cond = _name(t.name, loc)
        else:
            assert t.name is not None
            body.extend(self.sub_statements(t.pending))  # an LD/FBD network writing the name
            body.extend(t.body or [])
            if t.il is not None:
                body.extend(self.il_statements(t.il + [
                    Instr(loc, "ST", "ST", args=[_name(t.name, loc)], operand=t.name)]))
            cond = _name(t.name, loc)
        body.append(A.Assign(loc, _name(fired, loc), cond))
        self.out.append(A.Assign(loc, _name(fired, loc), _bool(False, loc)))
        self.out.append(A.If(loc, [(_any(enabled, "AND", loc), body)]))
        if t.name:
            self.decls.append(_decl(t.name, "BOOL", loc, spelling=t.text))

    def earlier_rivals(self, k: int) -> list[int]:
        """Transitions of higher precedence that share a preceding step with transition k
        (found through an index of the steps: linear in the chart, issue 30)."""
        if getattr(self, "_rival_index", None) is None:
            order = transition_order(self.chart)
            by_step: dict[str, list[int]] = {}
            for j in order:
                for n, _ in self.chart.transitions[j].sources:
                    by_step.setdefault(n, []).append(j)
            self._rival_index = ({j: i for i, j in enumerate(order)}, by_step)
        pos, by_step = self._rival_index
        mine = {n for n, _ in self.chart.transitions[k].sources}
        rivals = {j for n in mine for j in by_step.get(n, ()) if pos[j] < pos[k]}
        return sorted(rivals, key=pos.__getitem__)

    # 2. evolution -------------------------------------------------------------------------
    def evolution(self, order: list[int]) -> None:
        for k in order:
            t = self.chart.transitions[k]
            self.out.append(A.If(t.loc, [(_name(f"__SFC_TR{k}", t.loc), [
                A.Assign(l, self.flag(n, "X", l), _bool(False, l)) for n, l in t.sources])]))
        for k in order:
            t = self.chart.transitions[k]
            act: list[A.Stmt] = []
            for n, l in t.targets:  # activation wins; the step's time restarts now
                act.append(A.Assign(l, self.flag(n, "X", l), _bool(True, l)))
                act.append(A.Assign(l, self.flag(n, "T", l), _time(0, l)))
                act.append(_call(f"__SFC_TMR_{n}", [("IN", _bool(False, l))], l))
                act.append(_call(f"__SFC_TMR_{n}", [("IN", _bool(True, l))], l))
            self.out.append(A.If(t.loc, [(_name(f"__SFC_TR{k}", t.loc), act)]))

    def step_times(self) -> None:
        for s in self.chart.steps:
            loc = s.loc
            tmr = f"__SFC_TMR_{s.name}"
            self.out.append(_call(tmr, [("IN", self.flag(s.name, "X", loc))], loc))
            self.out.append(A.If(loc, [(self.flag(s.name, "X", loc), [
                A.Assign(loc, self.flag(s.name, "T", loc),
                         A.Member(loc, _name(tmr, loc), "ET", text="ET"))])]))

    # 3. actions ---------------------------------------------------------------------------
    def actions(self) -> None:
        declared = {a.name: a for a in self.chart.actions}
        used: dict[str, list[tuple[Step, Assoc]]] = {}
        for s in self.chart.steps:
            for a in s.assocs:
                used.setdefault(a.action, []).append((s, a))
        names = [a.name for a in self.chart.actions] + [n for n in used if n not in declared]
        for name in names:
            action = declared.get(name)
            if action is None:  # a Boolean action: the variable follows Q
                loc = used[name][0][1].loc
                inst = f"__SFC_AC_{name}"
            else:
                loc, inst = action.loc, name
            self.decls.append(_decl(inst, "ACTION_CONTROL", loc,
                                    spelling=action.text if action else ""))
            self.control(inst, used.get(name, []), loc)
            if action is None:
                self.out.append(A.Assign(loc, _name(name, loc, used[name][0][1].text),
                                         A.Member(loc, _name(inst, loc), "Q", text="Q")))
            else:
                body = (self.il_statements(action.il) if action.il is not None
                        else action.body + self.sub_statements(action.pending))
                self.out.append(A.If(loc, [(A.Member(loc, _name(inst, loc), "A", text="A"),
                                            body)]))

    def control(self, inst: str, assocs: list[tuple[Step, Assoc]], loc: Location) -> None:
        """The ACTION_CONTROL call: per qualifier, the OR of the flags of the steps that
        associate it; T from the active step's timed association (the last one that was)."""
        by_input: dict[str, list[A.Expr]] = {}
        timed = [(s, a) for s, a in assocs if a.time is not None]
        for s, a in assocs:
            by_input.setdefault(_INPUT[a.qualifier], []).append(self.flag(s.name, "X", a.loc))
        if len(timed) > 1:
            for s, a in timed:
                assert a.time is not None
                self.out.append(A.If(a.loc, [(self.flag(s.name, "X", a.loc), [A.Assign(
                    a.loc, A.Member(a.loc, _name(inst, a.loc), "T", text="T"),
                    A.copy_expr(a.time))])]))
        args = [(k, _any(v, "OR", loc)) for k, v in by_input.items()]
        if len(timed) == 1 and timed[0][1].time is not None:
            args.append(("T", A.copy_expr(timed[0][1].time)))
        self.out.append(_call(inst, args, loc))

    def il_statements(self, instrs: list[Instr]) -> list[A.Stmt]:
        """IL lines as statements (hidden ``__CR_*`` variables shared with the POU)."""
        jumps = [x for x in instrs if x.op == "LABEL" or x.op.startswith(("JMP", "RET"))]
        if jumps:  # the body runs inside an IF: a jump could not leave it
            self.diags.append(Diagnostic(
                "PLC0145", f"{jumps[0].text or 'a label'} in an IL action or transition: jumps, "
                "labels and RET are not supported there; write the choice in ST (IF ... "
                "END_IF) or with JMP-free IL (S, R, conditional CALC)", jumps[0].loc))
            return []
        return self.sub_statements([A.PendingBody("IL", instrs, self.pou.loc)])

    def sub_statements(self, pending: list[A.PendingBody]) -> list[A.Stmt]:
        """Bodies still to lower (IL, LD/FBD networks of a PLCopen chart) as statements; their
        hidden variables are shared with the POU."""
        if not pending:
            return []
        tmp = A.Pou(self.pou.loc, self.pou.kind, self.pou.name,
                    list(self.pou.decls) + self.decls, [], self.pou.return_type,
                    self.pou.spelling)
        known = {id(d) for d in tmp.decls}
        lowerings = {"IL": lower_il, "NETWORK": lower_network}
        out: list[A.Stmt] = []
        for body in pending:
            tmp.body = []
            self.diags.extend(lowerings[body.kind](tmp, body.payload, self.types))
            out.extend(tmp.body)
        have = {d.name for d in self.pou.decls} | {d.name for d in self.decls}
        for d in tmp.decls:
            if id(d) not in known and d.name not in have:
                self.decls.append(d)
                have.add(d.name)
        return out
