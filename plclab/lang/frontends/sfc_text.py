"""Textual SFC (IEC 61131-3 ed. 2, B.1.6) in a PROGRAM or FUNCTION_BLOCK body -> a chart.

```
INITIAL_STEP S0: END_STEP
STEP S1: Fill(N); Heater(L, T#2s); END_STEP
TRANSITION T1 (PRIORITY := 1) FROM S0 TO S1 := Start; END_TRANSITION
TRANSITION FROM S1 TO (S2, S3) := Full; END_TRANSITION       (* simultaneous divergence *)
TRANSITION Ready FROM (S2, S3) TO S0                          (* a body assigning the name *)
    Ready := Done2 AND Done3;
END_TRANSITION
ACTION Fill: Valve := TRUE; END_ACTION                        (* ST or IL body *)
```

**When is a body SFC?** (:func:`is_sfc_body`) When it starts with ``INITIAL_STEP``, ``STEP``
or ``ACTION`` followed by a name, or ``TRANSITION`` followed by a name, ``FROM`` or ``(``. These
words are not reserved elsewhere (a variable may be called ``step``): ST never puts a name after
a name. A transition's condition is ``:= expression;``, ``:`` and IL lines, or ST statements
that assign the transition's name.

The chart is kept as a :class:`~plclab.lang.ast.PendingBody` of kind ``"SFC"``;
:mod:`plclab.lang.lower.sfc` checks and lowers it. The host parser is passed in.
"""

from __future__ import annotations

from ...errors import Location
from .. import ast as A
from ..lexer import Token
from ..lower.sfc_chart import Action, Assoc, Chart, Step, Transition
from ..parsing import ParseAbort
from .il_lines import is_il_body, parse_il_body

SFC_WORDS = ("INITIAL_STEP", "STEP", "TRANSITION", "ACTION")
_ENDS = ("END_STEP", "END_TRANSITION", "END_ACTION")
_BODY_ENDS = {"END_PROGRAM", "END_FUNCTION", "END_FUNCTION_BLOCK", "EOF", "PROGRAM", "FUNCTION",
              "FUNCTION_BLOCK", "TYPE", "VAR_GLOBAL", "CONFIGURATION", "TEST"}


def is_sfc_body(p) -> bool:
    """Does the body at the parser's position start with an SFC element?"""
    t = p.tok
    if t.kind != "IDENT" or t.value not in SFC_WORDS:
        return False
    nxt = p.peek()
    if t.value == "TRANSITION":
        return nxt.kind in ("IDENT", "(")
    return nxt.kind == "IDENT"


def _word(p, value: str) -> bool:
    return p.tok.kind == "IDENT" and p.tok.value == value


def parse_sfc_body(p, end_kw: str) -> A.PendingBody:
    """Parse steps, transitions and actions up to ``end_kw``; return the chart as a pending
    body for :mod:`plclab.lang.lower`."""
    where = p.loc()
    if end_kw == "END_FUNCTION":
        p.error("PLC0010", "a FUNCTION keeps nothing from one call to the next, so it cannot "
                "hold an SFC chart; write the chart in a FUNCTION_BLOCK or a PROGRAM")
    _mark_ends(p, end_kw)
    chart = Chart(where)
    while p.tok.kind not in _BODY_ENDS and p.tok.kind != end_kw:
        start = p.i
        try:
            if _word(p, "INITIAL_STEP") or _word(p, "STEP"):
                chart.steps.append(_step(p))
            elif _word(p, "TRANSITION"):
                chart.transitions.append(_transition(p))
            elif _word(p, "ACTION"):
                chart.actions.append(_action(p))
            else:
                p.fail_expected("STEP, INITIAL_STEP, TRANSITION or ACTION (an SFC body holds "
                                "only these; statements belong inside an ACTION)")
        except ParseAbort:
            if p.i == start:
                p.advance()
            while (p.tok.kind not in _BODY_ENDS and p.tok.kind != end_kw
                   and not (p.tok.kind == "IDENT" and p.tok.value in SFC_WORDS)):
                p.advance()
    return A.PendingBody("SFC", [chart], where)


def _mark_ends(p, end_kw: str) -> None:
    """Turn the words END_STEP, END_TRANSITION and END_ACTION of this body into keywords, so
    that statement lists stop there (elsewhere they stay ordinary names)."""
    j = p.i
    toks = p.toks
    while toks[j].kind not in _BODY_ENDS and toks[j].kind != end_kw:
        t = toks[j]
        if t.kind == "IDENT" and t.value in _ENDS:
            toks[j] = Token(str(t.value), t.value, t.text, t.line, t.col)
        j += 1


def _name(p, what: str) -> tuple[str, str, Location]:
    t = p.expect("IDENT", what)
    return str(t.value), t.text, p.loc(t)


def _close(p, kw: str, opener: str, head: Token) -> None:
    if not p.accept(kw):
        p.fail_expected(f"{kw} to close the {opener} at line {head.line}")
    p.accept(";")


def _step(p) -> Step:
    head = p.advance()
    name, text, loc = _name(p, f"a step name after {head.text}")
    p.expect(":", f"':' after the step name {text}")
    step = Step(loc, name, text, initial=head.value == "INITIAL_STEP")
    while p.tok.kind == "IDENT":
        aname, atext, aloc = _name(p, "an action name")
        assoc = Assoc(aloc, aname, atext)
        p.expect("(", f"'(' and a qualifier after the action {atext}, e.g. {atext}(N)")
        if p.tok.kind == "IDENT":
            assoc.qualifier = str(p.advance().value)
        if p.accept(","):
            if p.tok.kind == "IDENT" and p.peek().kind in (",", ")") and \
                    assoc.qualifier not in ("L", "D", "SD", "DS", "SL"):
                p.advance()  # an indicator variable (IEC): shown by editors, not needed here
            else:
                assoc.time = p.expr()
        while p.accept(","):  # indicator variables
            p.expect("IDENT", "an indicator variable name")
        p.expect(")", f"')' to close the association of {atext}")
        p.expect(";", f"';' after {atext}(...)")
        step.assocs.append(assoc)
    _close(p, "END_STEP", f"step {text}", head)
    return step


def _steps(p, after: str, spelling: dict[str, str]) -> list[tuple[str, Location]]:
    if p.accept("("):
        out = [_name(p, f"a step name after {after} (")]
        while p.accept(","):
            out.append(_name(p, "a step name"))
        p.expect(")", f"')' to close the list of steps after {after}")
    else:
        out = [_name(p, f"a step name (or a list in parentheses) after {after}")]
    spelling.update((n, text) for n, text, _ in out)
    return [(n, loc) for n, _, loc in out]


def _transition(p) -> Transition:
    head = p.advance()
    name, text = None, ""
    if p.tok.kind == "IDENT" and p.tok.value != "FROM":
        t = p.advance()
        name, text = str(t.value), t.text
    priority = None
    if p.accept("("):
        t = p.tok
        if not (t.kind == "IDENT" and t.value == "PRIORITY"):
            p.fail_expected("PRIORITY := n in the parentheses after TRANSITION")
        p.advance()
        p.expect(":=", "':=' after PRIORITY")
        n = p.expect("INT", "a priority number (0 is the highest)")
        priority = int(n.value)
        p.expect(")", "')' after the priority")
    if not _word(p, "FROM"):
        p.fail_expected("FROM and the steps the transition leaves")
    p.advance()
    spelling: dict[str, str] = {}
    sources = _steps(p, "FROM", spelling)
    if not (p.accept("TO") or (_word(p, "TO") and p.advance())):
        p.fail_expected("TO and the steps the transition activates")
    targets = _steps(p, "TO", spelling)
    tr = Transition(p.loc(head), name, sources, targets, priority, spelling=spelling, text=text)
    if p.accept(":="):
        tr.cond = p.expr()
        p.expect(";", "';' after the transition condition")
    elif p.accept(":"):
        if name is None:
            p.fail_expected("':=' and a condition (an IL condition needs a transition name)")
        tr.il = parse_il_body(p, "END_TRANSITION").payload
    else:
        if name is None:
            p.fail_expected("':=' and the transition condition")
        tr.body = p.stmt_list({"END_TRANSITION"})
    _close(p, "END_TRANSITION", "TRANSITION", head)
    return tr


def _action(p) -> Action:
    head = p.advance()
    name, text, loc = _name(p, "an action name after ACTION")
    p.expect(":", f"':' after the action name {text}")
    action = Action(loc, name, text)
    if is_il_body(p, "END_ACTION"):
        action.il = parse_il_body(p, "END_ACTION").payload
    else:
        action.body = p.stmt_list({"END_ACTION"})
    _close(p, "END_ACTION", f"action {text}", head)
    return action
