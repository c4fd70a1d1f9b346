"""The checks of an SFC chart before it is lowered (codes PLC0150-PLC0159).

Names (undeclared step PLC0150, duplicates and clashes PLC0158, unknown action PLC0157), the
initial step (PLC0152), action associations (unknown qualifier PLC0153, time missing or not
allowed PLC0154, conflicting qualifiers PLC0156, a warning), transition conditions (PLC0159) and
the structure, found by exploring the chart's situations (sets of active steps) with every
condition taken as possibly TRUE: a step never active (PLC0151, warning) and a divergence closed
by the other kind of convergence (PLC0155, warning): parallel branches joined by an alternative
convergence activate a step twice; alternative branches joined by a simultaneous convergence
leave a transition that can never be enabled.
"""

from __future__ import annotations

from ...errors import Diagnostic, Location
from ...suggest import suggest
from .. import ast as A
from .. import types as T
from ..limits import MAX_SFC_STEPS
from .sfc_chart import Chart, Step
from .types import LoweringTypes

MAX_SITUATIONS = 4096  # explored situations; beyond, the structural checks are skipped
_TIMED = ("L", "D", "SD", "DS", "SL")
_QUALIFIERS = ("N", "R", "S", "P", "P1", "P0") + _TIMED
_STORED = ("S", "SD", "DS", "SL")


def check_chart(chart: Chart, pou: A.Pou, types: LoweringTypes) -> list[Diagnostic]:
    """Diagnostics for ``chart`` in ``pou`` (errors stop the lowering)."""
    out: list[Diagnostic] = []

    def err(code: str, msg: str, loc: Location, severity: str = "error") -> None:
        out.append(Diagnostic(code, msg, loc, severity))

    if len(chart.steps) > MAX_SFC_STEPS:
        err("PLC0311", f"the chart of {pou.spelling or pou.name} has {len(chart.steps)} steps; "
            f"plclab allows {MAX_SFC_STEPS} in one chart: split the sequence into several "
            "POUs (a chart per machine part) that hand over through variables", chart.loc)
        return out
    _names(chart, pou, err)
    steps = {s.name: s for s in chart.steps}
    initial = [s for s in chart.steps if s.initial]
    if not initial:
        err("PLC0152", f"the chart of {pou.spelling or pou.name} has no INITIAL_STEP; mark the "
            "step the sequence starts in with INITIAL_STEP", chart.loc)
    first: dict[str, Step] = {}  # one initial step per connected network (ADR 0053)
    part = _networks(chart)
    for s in initial:
        f = first.setdefault(part[s.name], s)
        if f is not s:
            err("PLC0152", f"second initial step {s.text} in the same SFC network (the first "
                f"is {f.text} at line {f.loc.line}); a network of steps and transitions has "
                "exactly one INITIAL_STEP: make this a STEP (separate networks, not linked "
                "by any transition, each have their own)", s.loc)
    for t in chart.transitions:
        for n, loc in t.sources + t.targets:
            if n not in steps:
                close = suggest(n, list(steps), n=1)
                hint = f"; did you mean {steps[close[0]].text}?" if close else \
                    "; declare it with STEP ... END_STEP"
                err("PLC0150", f"transition uses step '{t.spelling.get(n, n)}', which is not declared{hint}", loc)
        if t.cond is None and t.il is None and not t.pending and \
                not _assigns(t.body or [], t.name):
            what = t.name or "the transition"
            err("PLC0159", f"the body of transition {what} never assigns its condition; write "
                f"'{what} := <condition>;' in it, or use ':= <condition>;' after the TO steps",
                t.loc)
    _associations(chart, pou, types, err)
    if not any(d.severity == "error" for d in out) and initial:
        _structure(chart, err)
    return out


def _networks(chart: Chart) -> dict[str, str]:
    """Step name -> a representative of its SFC network: the steps linked by transitions
    (IEC 61131-3: a POU body may hold several networks, each with its own initial step, as
    Annex F's gravel example does)."""
    parent = {s.name: s.name for s in chart.steps}

    def find(n: str) -> str:
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n

    for t in chart.transitions:
        names = [n for n, _ in t.sources + t.targets if n in parent]
        for n in names[1:]:
            a, b = find(names[0]), find(n)
            if a != b:
                parent[b] = a
    return {n: find(n) for n in parent}


def _assigns(body: list[A.Stmt], name: str | None) -> bool:
    return name is not None and any(
        isinstance(s, A.Assign) and isinstance(s.target, A.Name) and s.target.name == name
        for s in A.walk_stmts(body))


def _names(chart: Chart, pou: A.Pou, err) -> None:
    seen: dict[str, tuple[str, Location]] = {}
    local = {d.name: d for d in pou.decls}
    elems = ([("step", s.name, s.loc) for s in chart.steps] +
             [("action", a.name, a.loc) for a in chart.actions] +
             [("transition", t.name, t.loc) for t in chart.transitions if t.name])
    for what, name, loc in elems:
        if name in seen:
            other, where = seen[name]
            err("PLC0158", f"'{name}' is already the name of a {other} (line {where.line}); "
                f"give this {what} another name", loc)
            continue
        seen[name] = (what, loc)
        if name in local:
            err("PLC0158", f"{what} '{name}' has the name of the variable declared at line "
                f"{local[name].loc.line}; rename one of them", loc)


def _associations(chart: Chart, pou: A.Pou, types: LoweringTypes, err) -> None:
    actions = {a.name for a in chart.actions}
    steps = {s.name for s in chart.steps}
    uses: dict[str, list[tuple[str, str, A.Expr | None, Location]]] = {}
    for s in chart.steps:
        in_step: dict[str, str] = {}
        for a in s.assocs:
            q = a.qualifier
            if q not in _QUALIFIERS:
                close = suggest(q, list(_QUALIFIERS), n=1)
                hint = f"did you mean {close[0]}? " if close else ""
                err("PLC0153", f"'{q}' is not an action qualifier; {hint}use one of "
                    f"{', '.join(_QUALIFIERS)}", a.loc)
                continue
            if q in _TIMED and a.time is None:
                err("PLC0154", f"qualifier {q} needs a duration: write {a.text}({q}, T#2s)",
                    a.loc)
            elif q not in _TIMED and a.time is not None:
                err("PLC0154", f"qualifier {q} takes no duration; remove it, or use a timed "
                    f"qualifier ({', '.join(_TIMED)})", a.loc)
            if a.action not in actions:
                if a.action in steps:
                    err("PLC0157", f"'{a.text}' is a step, not an action; associate an ACTION "
                        "or a BOOL variable", a.loc)
                    continue
                ty = types.expr_type(A.Name(a.loc, a.action, text=a.text), pou)
                if types.decl_of(A.Name(a.loc, a.action, text=a.text), pou) is None:
                    close = suggest(a.action, sorted(actions), n=1)
                    hint = f"did you mean {close[0]}? " if close else ""
                    err("PLC0157", f"action '{a.text}' is not declared; {hint}declare it with "
                        f"ACTION {a.text}: ... END_ACTION, or associate a BOOL variable",
                        a.loc)
                    continue
                if ty is not None and ty is not T.BOOL:
                    err("PLC0157", f"'{a.text}' is not a BOOL variable, so it cannot be a "
                        "Boolean action; declare an ACTION or use a BOOL", a.loc)
                    continue
            if a.action in in_step:
                err("PLC0156", f"step {s.text} associates action {a.text} twice ({in_step[a.action]}"
                    f" and {q}); keep one association", a.loc, "warning")
            in_step[a.action] = q
            uses.setdefault(a.action, []).append((s.text, q, a.time, a.loc))
    for name, us in uses.items():
        stored = [u for u in us if u[1] in _STORED]
        if stored and not any(u[1] == "R" for u in us):
            err("PLC0156", f"action {name} is stored ({stored[0][1]} in step {stored[0][0]}) "
                "but no step resets it with R: it stays active for ever; add an R association",
                stored[0][3], "warning")
        durations = {A.expr_text(u[2]) for u in us if u[2] is not None}
        if len(durations) > 1:
            err("PLC0156", f"action {name} has timed associations with different durations "
                f"({', '.join(sorted(durations))}); one ACTION_CONTROL has one T, so the last "
                "active step's duration applies", us[-1][3], "warning")


def _structure(chart: Chart, err) -> None:
    """Explore the situations reachable from the initial one, firing one transition at a time
    with any condition (interleaving is enough to find reachable steps and double
    activations); report unreachable steps, unsafe convergences, dead simultaneous ones."""
    trans = [(frozenset(n for n, _ in t.sources), frozenset(n for n, _ in t.targets), t)
             for t in chart.transitions]
    start = frozenset(s.name for s in chart.steps if s.initial)
    seen = {start}
    todo = [start]
    active: set[str] = set(start)
    fired: set[int] = set()
    unsafe: dict[int, str] = {}
    by_step: dict[str, list[int]] = {}  # a transition is found through its source steps
    for k, (src, _dst, _t) in enumerate(trans):
        for n in src:
            by_step.setdefault(n, []).append(k)
    while todo:
        m = todo.pop()
        for k in sorted({k for n in m for k in by_step.get(n, ())}):
            src, dst, _ = trans[k]
            if not src <= m:
                continue
            fired.add(k)
            rest = m - src
            double = dst & rest
            if double and k not in unsafe:
                unsafe[k] = sorted(double)[0]
            nxt = rest | dst
            if nxt not in seen:
                if len(seen) >= MAX_SITUATIONS:
                    return
                seen.add(nxt)
                todo.append(nxt)
                active |= nxt
    for s in chart.steps:
        if s.name not in active:
            err("PLC0151", f"step {s.text} can never become active: no transition leads to it "
                "from the initial step; connect it or remove it", s.loc, "warning")
    for k, (src, _dst, t) in enumerate(trans):
        if k in unsafe:
            err("PLC0155", f"this transition activates step {unsafe[k]} while it may still be "
                "active: parallel branches (FROM x TO (a, b)) must end in a simultaneous "
                "convergence (FROM (a2, b2) TO y), not in separate transitions", t.loc,
                "warning")
        elif k not in fired and len(src) > 1 and src <= active:
            err("PLC0155", f"steps {', '.join(sorted(src))} are never active together, so this "
                "simultaneous convergence can never fire: alternative branches end in separate "
                "transitions (FROM a2 TO y; FROM b2 TO y)", t.loc, "warning")
