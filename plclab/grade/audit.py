"""``plclab lab audit LAB``: a lab's rubric tested by the wrong programs it must catch.

A rubric is only as good as the wrong programs it fails. The audit grades, with the hidden
scenarios,

* every program in ``mistakes/`` against its ``[[mistake]]`` bound,
* every program in ``variants/`` (correct, written another way): at least 95 %,
* *mutants* of each reference solution written in ST: one small change each, made on the
  AST and printed back as ST (:mod:`plclab.lang.unparse`): a condition negated, AND and OR
  swapped, a term of an AND/OR dropped (a seal-in or an interlock), a comparison moved by one
  (``>=`` for ``>``), a NOT removed, a constant or time preset halved or doubled, a statement
  deleted, SR for RS (and back), an edge detector's ``.Q`` replaced by its level.

A mutant whose plant signals equal the solution's in every scenario is *equivalent* (the
change does not change behaviour) and is not counted; one that does not compile is *invalid*.
So is one whose signals differ only by the PLC's own resolution, one scan (see
:func:`within_one_scan`): a ``>=`` turned into ``>`` on a step time makes the phase one scan
longer, which no requirement stated in seconds can tell from the solution (ADR 0049).

In a lab whose criteria state a control performance specification (``performance_spec =
true``: settling time, overshoot, steady-state error, recovery after a disturbance), a changed
constant that still meets every criterion is another valid *tuning* (a gain doubled, an
integral time halved): it is listed but not counted. A constant change that fails any part of
the specification, and every other operator, counts as before.
The **mutation score** is the share of behaviour-changing mutants that score at most
:data:`CAUGHT` of the lab's points. See docs/adr/0042-critical-criteria-and-mutation-audit.md.
"""

from __future__ import annotations

import copy
import dataclasses
import random
import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..lang import ast as A

CAUGHT = 0.7
"""A mutant scoring at most this share of the lab's points is caught."""
VARIANT_MIN = 0.95
"""A correct variant must score at least this share."""

_SWAP_CMP = {">": ">=", ">=": ">", "<": "<=", "<=": "<", "=": "<>", "<>": "="}
_LATCHES = {"SR": "RS", "RS": "SR"}
_LATCH_PINS = {"SR": {"S1": "S", "R": "R1"}, "RS": {"S": "S1", "R1": "R"}}
_EDGES = {"R_TRIG", "F_TRIG"}


@dataclass
class Mutant:
    """One change of a solution: what it is, where, and its ST text."""

    operator: str
    description: str
    line: int
    text: str
    score: float | None = None
    max_score: float = 0.0
    status: str = ""  # caught, survived, equivalent, tuning, invalid
    equivalence: str = ""  # for an equivalent mutant: "identical" or "one scan"

    @property
    def share(self) -> float:
        return (self.score or 0.0) / self.max_score if self.max_score else 0.0


@dataclass
class AuditReport:
    """What ``lab audit`` found for one lab."""

    lab_id: str
    max_score: float
    mutants: list[Mutant] = field(default_factory=list)
    mistakes: list[tuple[str, float, float]] = field(default_factory=list)  # file, score, bound
    variants: list[tuple[str, float]] = field(default_factory=list)  # file, score

    def counted(self) -> list[Mutant]:
        return [m for m in self.mutants if m.status in ("caught", "survived")]

    @property
    def mutation_score(self) -> float:
        """The share of behaviour-changing mutants the rubric catches (1.0 when none)."""
        n = self.counted()
        return sum(m.status == "caught" for m in n) / len(n) if n else 1.0

    @property
    def mistakes_ok(self) -> bool:
        return all(score <= bound + 1e-9 for _, score, bound in self.mistakes)

    @property
    def variants_ok(self) -> bool:
        return all(score >= VARIANT_MIN * self.max_score - 1e-9 for _, score in self.variants)

    def text(self) -> str:
        lines = [f"audit of {self.lab_id} ({self.max_score:g} points)"]
        for f, score, bound in self.mistakes:
            mark = "ok " if score <= bound + 1e-9 else "TOO HIGH"
            lines.append(f"  mistake  {f}: {score:g} (bound {bound:g}) {mark}")
        for f, score in self.variants:
            mark = "ok " if score >= VARIANT_MIN * self.max_score - 1e-9 else "TOO LOW"
            lines.append(f"  variant  {f}: {score:g} {mark}")
        by = {s: [m for m in self.mutants if m.status == s]
              for s in ("caught", "survived", "equivalent", "tuning", "invalid")}
        scan = sum(m.equivalence == "one scan" for m in by["equivalent"])
        lines.append(f"  mutants: {len(self.mutants)} ({len(by['caught'])} caught, "
                     f"{len(by['survived'])} survived, {len(by['equivalent'])} equivalent"
                     + (f" ({scan} within one scan)" if scan else "") +
                     (f", {len(by['tuning'])} other valid tunings" if by["tuning"] else "") +
                     f", {len(by['invalid'])} invalid)")
        for m in by["tuning"]:
            lines.append(f"  valid tuning, line {m.line}: [{m.operator}] {m.description} "
                         f"(meets the performance specification: {m.score:g}/{m.max_score:g})")
        for m in by["equivalent"]:
            if m.equivalence == "one scan":
                lines.append(f"  within one scan, line {m.line}: [{m.operator}] "
                             f"{m.description}")
        for m in by["survived"]:
            lines.append(f"  SURVIVED {m.score:g}/{m.max_score:g} line {m.line}: "
                         f"[{m.operator}] {m.description}")
        lines.append(f"mutation score: {self.mutation_score:.0%} "
                     f"({len(by['caught'])} of {len(self.counted())} behaviour-changing "
                     f"mutants score at most {CAUGHT:.0%})")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        return {"lab": self.lab_id, "max_score": self.max_score,
                "mutation_score": self.mutation_score, "mistakes_ok": self.mistakes_ok,
                "variants_ok": self.variants_ok,
                "mistakes": [{"file": f, "score": s, "bound": b} for f, s, b in self.mistakes],
                "variants": [{"file": f, "score": s} for f, s in self.variants],
                "mutants": [dataclasses.asdict(m) | {"text": None} for m in self.mutants]}


# ---------------------------------------------------------------------------- mutation sites


def _children(node: Any) -> Iterator[tuple[Any, str, int | None, Any]]:
    """(parent, field, index or None, child) for each AST child of ``node`` (lists and the
    (condition, body) pairs of IF and CASE included), in field order."""
    if not dataclasses.is_dataclass(node):
        return
    for f in dataclasses.fields(node):
        if f.name in ("loc", "ty", "sym", "target", "owner") and \
                not isinstance(node, A.Assign):
            continue
        v = getattr(node, f.name, None)
        if isinstance(v, list):
            for i, x in enumerate(v):
                if isinstance(x, tuple):
                    for y in x:
                        if isinstance(y, list):
                            for j, z in enumerate(y):
                                yield y, "", j, z
                        elif dataclasses.is_dataclass(y):
                            yield None, "", None, y  # read-only (a label, a condition)
                else:
                    yield v, "", i, x
        elif dataclasses.is_dataclass(v) and not isinstance(v, A.Location):
            yield node, f.name, None, v


def _walk(root: Any) -> Iterator[tuple[Any, str, int | None, Any]]:
    """Every node under ``root`` once (a METHOD's ``owner`` points back up: no cycles)."""
    stack = [(None, "", None, root)]
    seen: set[int] = set()
    while stack:
        item = stack.pop()
        if id(item[3]) in seen:
            continue
        seen.add(id(item[3]))
        yield item
        stack.extend(reversed(list(_children(item[3]))))


def _replace(parent: Any, fld: str, idx: int | None, new: Any) -> bool:
    if parent is None:
        return False
    if idx is not None:
        parent[idx] = new
    else:
        setattr(parent, fld, new)
    return True


def _conditions(root: Any) -> Iterator[tuple[Any, int, A.Expr]]:
    """(holder list, index, condition) of IF/ELSIF branches: a mutable slot for each."""
    for _p, _f, _i, n in _walk(root):
        if isinstance(n, A.If):
            for k, (cond, _body) in enumerate(n.branches):
                yield n.branches, k, cond


def sites(root: Any) -> list[tuple[str, str, int, Callable[[], bool]]]:
    """Every mutation of ``root`` (mutated in place when its function is called):
    ``(operator, description, line, apply)``, in a deterministic order."""
    from ..lang.unparse import expr as st

    out: list[tuple[str, str, int, Callable[[], bool]]] = []
    for holder, k, cond in _conditions(root):
        def neg(h=holder, k=k, c=cond) -> bool:
            h[k] = (A.Unary(c.loc, "NOT", c), h[k][1])
            return True
        out.append(("negate", f"IF {st(cond)} -> IF NOT ({st(cond)})", cond.loc.line, neg))
    for parent, fld, idx, n in list(_walk(root)):
        line = getattr(getattr(n, "loc", None), "line", 0)
        if isinstance(n, A.Binary) and n.op in ("AND", "OR"):
            other = "OR" if n.op == "AND" else "AND"

            def swap(n=n, other=other) -> bool:
                n.op = other
                return True
            out.append(("and-or", f"{st(n)} -> {st(dataclasses.replace(n, op=other))}",
                        line, swap))
            for keep, name in ((n.left, "left"), (n.right, "right")):
                def drop(p=parent, f=fld, i=idx, keep=keep) -> bool:
                    return _replace(p, f, i, keep)
                out.append(("drop-term", f"{st(n)} -> only the {name} term {st(keep)}",
                            line, drop))
        elif isinstance(n, A.Binary) and n.op in _SWAP_CMP:
            def cmp_(n=n) -> bool:
                n.op = _SWAP_CMP[n.op]
                return True
            out.append(("comparison",
                        f"{st(n)} -> {st(dataclasses.replace(n, op=_SWAP_CMP[n.op]))}",
                        line, cmp_))
        elif isinstance(n, A.Unary) and n.op == "NOT":
            def unnot(p=parent, f=fld, i=idx, x=n.operand) -> bool:
                return _replace(p, f, i, x)
            out.append(("remove-not", f"{st(n)} -> {st(n.operand)}", line, unnot))
        elif isinstance(n, A.Literal) and isinstance(n.value, int | float) and \
                not isinstance(n.value, bool) and n.value not in (0, 1):
            for factor, word in ((2, "doubled"), (0.5, "halved")):
                def scale(n=n, factor=factor) -> bool:
                    v = n.value * factor
                    n.value = int(v) if isinstance(n.value, int) else v
                    n.text = ""
                    return True
                out.append(("constant", f"{n.text or n.value} {word}", line, scale))
        elif isinstance(n, A.Assign | A.CallStmt) and idx is not None and \
                isinstance(parent, list):
            def delete(p=parent, i=idx) -> bool:
                p[i] = A.Empty(p[i].loc)
                return True
            what = st(n.target) + " := ..." if isinstance(n, A.Assign) else st(n.call)
            out.append(("delete", f"statement deleted: {what}", line, delete))
        elif isinstance(n, A.VarDecl) and isinstance(n.type, A.NamedTypeRef) and \
                n.type.name.upper() in _LATCHES:
            def latch(n=n, root=root) -> bool:
                old = n.type.name.upper()
                n.type.name = _LATCHES[old]
                pins = _LATCH_PINS[old]
                for _p, _f, _i, c in _walk(root):  # the calls name the other block's pins
                    if isinstance(c, A.Call) and isinstance(c.func, A.Name) and \
                            c.func.name.upper() == n.name.upper():
                        for a in c.args:
                            if a.name and a.name.upper() in pins:
                                a.name = pins[a.name.upper()]
                return True
            out.append(("latch", f"{n.name} : {n.type.name} -> "
                        f"{_LATCHES[n.type.name.upper()]}", line, latch))
    out += _edge_sites(root)
    return out


def _edge_sites(root: Any) -> list[tuple[str, str, int, Callable[[], bool]]]:
    """``trig.Q`` of an R_TRIG/F_TRIG replaced by the level it detects (CLK): the edge
    detector removed."""
    trigs = {n.name.upper() for _p, _f, _i, n in _walk(root)
             if isinstance(n, A.VarDecl) and isinstance(n.type, A.NamedTypeRef)
             and n.type.name.upper() in _EDGES}
    clk: dict[str, A.Expr] = {}
    for _p, _f, _i, n in _walk(root):
        if isinstance(n, A.Call) and isinstance(n.func, A.Name) and n.func.name.upper() in trigs:
            for a in n.args:
                if (a.name or "").upper() == "CLK" and a.value is not None:
                    clk[n.func.name.upper()] = a.value
    out = []
    for parent, fld, idx, n in list(_walk(root)):
        if isinstance(n, A.Member) and isinstance(n.obj, A.Name) and \
                n.obj.name.upper() in clk and n.field_name.upper() == "Q":
            level = clk[n.obj.name.upper()]

            def edge(p=parent, f=fld, i=idx, lv=level) -> bool:
                return _replace(p, f, i, copy.deepcopy(lv))
            out.append(("edge", f"{n.obj.name}.Q -> the level itself (no edge detector)",
                        n.loc.line, edge))
    return out


def mutants(text: str, filename: str = "solution.st", limit: int | None = None,
            seed: int = 0) -> list[Mutant]:
    """The mutants of an ST program: one per site (at most ``limit``, a seeded sample that
    keeps every operator represented)."""
    from ..lang.frontends.st import parse_st
    from ..lang.unparse import unparse

    base = parse_st(text, filename)
    sfc = sfc_mutants(text)
    # an SFC is lowered to ST with internal names that a program may not write: its mutants
    # come from the SFC text (steps, transitions and their conditions) instead
    found = [] if sfc else sites(base)
    if limit is not None and len(sfc) + len(found) > limit:
        keep = min(len(sfc), limit if not found else max(2, limit // 6))
        sfc = sorted(random.Random(seed).sample(sfc, keep), key=lambda m: (m.line, m.description))
        limit = max(0, limit - keep)
    order = list(range(len(found)))
    if limit is not None and len(order) > limit:
        rng = random.Random(seed)
        by_op: dict[str, list[int]] = {}
        for k in order:
            by_op.setdefault(found[k][0], []).append(k)
        for ks in by_op.values():
            rng.shuffle(ks)
        order = []
        while len(order) < limit:  # round robin over the operators
            for ks in by_op.values():
                if ks and len(order) < limit:
                    order.append(ks.pop())
        order.sort()
    out = []
    for k in order:
        tree = copy.deepcopy(base)
        op, desc, line, apply = sites(tree)[k]
        if not apply():
            continue
        try:
            src = unparse(tree)
        except Exception:  # noqa: BLE001 - a mutant that cannot be printed is skipped
            continue
        out.append(Mutant(op, desc, line, src))
    return out + sfc


_STEP = re.compile(r"^(\s*(?:INITIAL_)?STEP\s+\w+\s*:)(.*?)(END_STEP)", re.I | re.M)
_ASSOC = re.compile(r"\w+\s*\([^()]*\)\s*;")
_TRANS = re.compile(r"^(\s*TRANSITION\b(?:\s*\w+)?(?:\s*\(\s*PRIORITY\s*:=\s*\d+\s*\))?"
                    r"[^\n:]*:=)(.*?)(;\s*END_TRANSITION)", re.I | re.M)


def sfc_mutants(text: str) -> list[Mutant]:
    """Mutants of an SFC written in ST text (steps and transitions are kept as text in the
    tree): a step loses one of its actions; a transition's condition is negated or always
    TRUE (the step is left at once)."""
    out: list[Mutant] = []

    def line_of(pos: int) -> int:
        return text.count("\n", 0, pos) + 1

    for m in _STEP.finditer(text):
        for a in _ASSOC.finditer(m.group(2)):
            start, end = m.start(2) + a.start(), m.start(2) + a.end()
            out.append(Mutant("sfc-action", f"{m.group(1).strip()} {a.group(0)} -> action removed",
                              line_of(start), text[:start] + text[end:]))
    for m in _TRANS.finditer(text):
        cond = m.group(2).strip()
        if not cond or "\n" in cond:
            continue
        s, e = m.start(2), m.end(2)
        head = m.group(1).strip()
        for new, word in ((f" NOT ({cond})", "negated"), (" TRUE", "always TRUE")):
            if new.strip().upper() == cond.upper():
                continue
            out.append(Mutant("sfc-transition", f"{head} {cond} -> {new.strip()} ({word})",
                              line_of(s), text[:s] + new + text[e:]))
        for op, changed in _expr_mutants(cond):
            out.append(Mutant(op, f"{head} {cond} -> {changed}", line_of(s),
                              text[:s] + " " + changed + text[e:]))
    return out


def _expr_mutants(cond: str) -> list[tuple[str, str]]:
    """The AST operators (AND/OR, a dropped term, comparisons, NOT, constants) applied to one
    expression given as text: ``(operator, mutated expression)``."""
    from ..lang.frontends.st import parse_st
    from ..lang.unparse import expr as st

    wrap = f"PROGRAM _M\nVAR _x : BOOL; END_VAR\n_x := {cond};\nEND_PROGRAM\n"
    try:
        base = parse_st(wrap, "_m.st")
    except Exception:  # noqa: BLE001 - a condition the parser cannot take alone: no mutants
        return []
    out: list[tuple[str, str]] = []
    seen = {st(_the_value(base))}
    for k, (op, _d, _l, _a) in enumerate(sites(base)):
        if op in ("negate", "delete", "latch", "edge"):
            continue
        tree = copy.deepcopy(base)
        if not sites(tree)[k][3]():
            continue
        text = st(_the_value(tree))
        if text not in seen:
            seen.add(text)
            out.append((op, text))
    return out


def _the_value(tree: Any) -> Any:
    for _p, _f, _i, n in _walk(tree):
        if isinstance(n, A.Assign):
            return n.value
    raise LookupError("no assignment")


# ---------------------------------------------------------------------------- the audit


def _signals(trace: Any) -> dict[str, Any]:
    return {n: trace[n] for n in trace.signals}


@dataclass
class Run:
    """What one scenario's trace shows the audit: its plant signals, the row times, the
    trace's end and the time resolution (one PLC scan, or one row where rows are sparser)."""

    signals: dict[str, Any]
    time: Any
    t_end: float
    resolution: float
    outputs: list[str] = field(default_factory=list)  # the signals the program drives

    @classmethod
    def of(cls, trace: Any) -> Run:
        scan = float(trace.meta.get("scan") or 0.0)
        sig = _signals(trace)
        outs = sorted({r.get("signal") for r in trace.io if r.get("direction") == "out"}
                      & set(sig))
        return cls(sig, trace.time, float(trace.t_end), max(scan, trace.period),
                   outs or sorted(sig))


def _runs(x: Any, time: Any, t_end: float) -> tuple[list[Any], list[float]]:
    """Run-length code of one column: the values in order and how long each lasted."""
    import numpy as np

    if len(x) == 0:
        return [], []
    cut = np.nonzero(x[1:] != x[:-1])[0] + 1
    starts = np.concatenate(([0], cut))
    ends = [float(time[k]) for k in cut] + [t_end]
    return [x[k] for k in starts], [e - float(time[k]) for k, e in zip(starts, ends, strict=True)]


def _close_runs(va: list[Any], da: list[float], vb: list[Any], db: list[float],
                tol: float) -> bool:
    """Same values in the same order, each lasting as long within ``tol``; a last run of at
    most ``tol`` that only one side has (an edge pushed past the end) is left out."""
    if len(va) == len(vb) + 1 and da[-1] <= tol:
        va, da = va[:-1], da[:-1]
    elif len(vb) == len(va) + 1 and db[-1] <= tol:
        vb, db = vb[:-1], db[:-1]
    # the last run is cut by the end of the trace: how long it lasts is not the program's
    return len(va) == len(vb) and all(_equal(x, y) for x, y in zip(va, vb, strict=True)) and \
        all(abs(x - y) <= tol for x, y in zip(da[:-1], db[:-1], strict=True))


def _equal(x: Any, y: Any) -> bool:
    import numpy as np

    return bool(np.all(np.asarray(x) == np.asarray(y)))


def within_one_scan(a: Run, b: Run) -> bool:
    """Whether trace ``a`` shows what ``b`` shows at the PLC's time resolution: every signal
    takes the same values in the same order, each value lasting as long as in ``b`` within
    one scan (the last value, cut by the end of the run, excepted); and the program's outputs
    together go through the same combinations in the same order (two output edges that fall
    together in ``b`` fall together in ``a``: no lamp goes out one scan before the next one
    lights, no order is swapped). An input edge of the plant that fell on the same scan as an
    output edge may come a scan apart: which of two things a scan apart came first is below
    the resolution.

    An edge may thus move by a scan, and a phase last a scan longer or shorter, also once in
    every cycle (the phases stay right, their start drifts). A preset off by a few scans, an
    extra or a missing edge, a new combination of outputs, or an analog signal that moves
    differently is a change of behaviour."""
    import numpy as np

    if a.signals.keys() != b.signals.keys():
        return False
    tol = max(a.resolution, b.resolution) * (1 + 1e-6) + 1e-9
    for name in b.signals:
        if not _close_runs(*_runs(a.signals[name], a.time, a.t_end),
                           *_runs(b.signals[name], b.time, b.t_end), tol):
            return False

    def states(r: Run) -> list[tuple[Any, ...]]:
        cols = [np.asarray(r.signals[n]) for n in b.outputs]
        rows = list(zip(*(c.tolist() for c in cols), strict=True)) if cols else []
        return [s for k, s in enumerate(rows) if k == 0 or s != rows[k - 1]]

    sa, sb = states(a), states(b)
    if sa == sb:
        return True
    # an edge pushed past the end: the last combination of the longer side is the extra one
    return sa[:-1] == sb or sb[:-1] == sa


def _same(a: dict[str, Any], b: dict[str, Any]) -> bool:
    import numpy as np

    if a.keys() != b.keys():
        return False
    return all(len(a[k]) == len(b[k]) and np.array_equal(a[k], b[k]) for k in a)


_JOB: dict[str, Any] = {}


def _grade_mutant(k: int) -> tuple[int, str, float, float]:
    """In a worker: grade mutant k of ``_JOB`` (caught, survived, equivalent or invalid)."""
    from .engine import grade_sources

    lab, m, base = _JOB["lab"], _JOB["mutants"][k], _JOB["base"]
    res = grade_sources(lab, [(m.text, "mutant.st")], media_dir=None, rrd=False,
                        keep_traces=True)
    if res.status != "ok":
        return k, "invalid", 0.0, res.max_score
    if all(name in base and _same(_signals(tr), base[name].signals)
           for name, tr in res.traces.items()):
        return k, "equivalent", res.score, res.max_score
    if all(name in base and within_one_scan(Run.of(tr), base[name])
           for name, tr in res.traces.items()):
        return k, "equivalent:one scan", res.score, res.max_score
    caught = res.score <= CAUGHT * res.max_score + 1e-9
    return k, "caught" if caught else "survived", res.score, res.max_score


def classify(m: Mutant, status: str, score: float, top: float,
             performance_spec: bool = False) -> None:
    """Record a graded mutant's outcome (``status`` as :func:`_grade_mutant` gives it, e.g.
    ``equivalent:one scan``). In a lab with a performance specification a constant change
    that meets every criterion is another valid tuning (``tuning``), not a survivor."""
    status, _, how = status.partition(":")
    m.status, m.score, m.max_score = status, score, top
    if status == "equivalent":
        m.equivalence = how or "identical"
    elif status == "survived" and performance_spec and m.operator == "constant" and \
            score >= top - 1e-9:
        m.status = "tuning"


def audit(lab: Any, *, limit: int | None = 60, seed: int = 0, jobs: int = 1,
          solutions: list[Path] | None = None) -> AuditReport:
    """Audit ``lab`` (see the module text). ``limit`` caps the mutants of each solution."""
    from .engine import grade_sources

    report = AuditReport(lab.id, lab.max_score)
    for spec in lab.mistakes:
        path = lab.path / "mistakes" / spec.file
        res = grade_sources(lab, [(path.read_text(encoding="utf-8"), spec.file)],
                            media_dir=None, rrd=False)
        report.mistakes.append((spec.file, res.score, spec.max_score))
    for path in lab.files("variants") if (lab.path / "variants").is_dir() else []:
        res = grade_sources(lab, [(path.read_text(encoding="utf-8"), path.name)],
                            media_dir=None, rrd=False)
        report.variants.append((path.name, res.score))
    for sol in solutions or [p for p in lab.files("solution") if p.suffix.lower() == ".st"]:
        text = sol.read_text(encoding="utf-8")
        base_res = grade_sources(lab, [(text, sol.name)], media_dir=None, rrd=False,
                                 keep_traces=True)
        base = {n: Run.of(t) for n, t in base_res.traces.items()}
        ms = mutants(text, sol.name, limit, seed)
        _JOB.update(lab=lab, mutants=ms, base=base)
        try:
            if jobs > 1 and len(ms) > 1:
                import multiprocessing

                with multiprocessing.get_context("fork").Pool(jobs) as pool:
                    results = pool.map(_grade_mutant, range(len(ms)), chunksize=1)
            else:
                results = [_grade_mutant(k) for k in range(len(ms))]
        finally:
            _JOB.clear()
        for k, status, score, top in results:
            classify(ms[k], status, score, top, getattr(lab, "performance_spec", False))
        report.mutants += ms
    return report
