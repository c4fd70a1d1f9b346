"""An SFC chart drawn as SVG: steps (the initial one double-framed), transitions with their
conditions, action blocks with qualifiers, alternative and simultaneous branches, jumps, and the
active steps of a chosen moment highlighted.

Layout: steps in rows by their distance from the initial step (breadth first, transitions in
precedence order); a transition sits between the rows of its steps. A transition back to a row
above (a loop) ends in a jump arrow naming its target, as PLCopen's ``jumpStep``. Alternative
branches hang from a single horizontal line, simultaneous ones from a double line (IEC
61131-3, 2.6.3). Only :func:`render_sfc_svg` is public (the ``plclab render`` command calls it).

>>> from plclab.project import check_sources
>>> project, _ = check_sources([('''PROGRAM P VAR go : BOOL; lamp : BOOL; END_VAR
... INITIAL_STEP Idle: END_STEP
... STEP Run: lamp(N); END_STEP
... TRANSITION FROM Idle TO Run := go; END_TRANSITION
... TRANSITION FROM Run TO Idle := NOT go; END_TRANSITION
... END_PROGRAM''', "p.st")])
>>> svg = render_sfc_svg(project.pous["P"], values={"Run.X": True})
>>> svg.startswith("<svg") and 'class="step active"' in svg and "NOT go" in svg
True
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any
from xml.sax.saxutils import escape

from plclab.errors import PlcError
from plclab.lang.sfc_outline import evaluate, outline
from plclab.viz.text_width import text_width

STEP_W, STEP_H = 96, 32
GAP = 104  # vertical space between a row of steps (with their actions) and the next
COL = 340  # least horizontal distance between step columns (more when actions are wide)
SIDE = 170  # a second transition of a step (a loop, an abort) stands this far to the right
MARGIN = 30
QUAL_W = 38  # the qualifier's cell of an action block
JUMP_H = 20  # a jump arrow: line and head, from its start down to the tip
FONT = 12
ACTIVE = "#ffd54a"
ENABLED = "#e65100"


@dataclass
class _Node:
    name: str
    text: str
    initial: bool
    actions: list[dict[str, Any]]
    row: int = -1
    col: float = 0.0
    active: bool = False
    parent: str = ""  # the step that first leads to it (it is drawn under that step)
    cx: float = 0.0  # the centre of the step
    y: float = 0.0
    row_h: float = STEP_H  # the tallest step of its row, with its actions

    @property
    def h(self) -> float:
        """The step with its action block."""
        return max(STEP_H, 22.0 * len(self.actions))

    @property
    def w(self) -> float:
        """The step's frame: its name (bold) fits with room on both sides."""
        return max(STEP_W, _width(self.text, bold=True) + 24)

    @property
    def name_w(self) -> float:
        """The action-name cell of its action block: the widest name fits."""
        return max((_width(_action_label(a)) + 16 for a in self.actions), default=0.0)

    @property
    def right(self) -> float:
        """How far right of the step's centre its action block reaches."""
        return self.w / 2 + (18 + QUAL_W + self.name_w if self.actions else 0.0)


def _width(s: str, bold: bool = False) -> float:
    return text_width(s, FONT, "sans-bold" if bold else "sans")


@dataclass
class _Svg:
    parts: list[str] = field(default_factory=list)
    width: float = 0.0
    height: float = 0.0

    def grow(self, x: float, y: float) -> None:
        self.width = max(self.width, x)
        self.height = max(self.height, y)

    wires: list[tuple[float, float, float, float]] = field(default_factory=list)

    def line(self, x1: float, y1: float, x2: float, y2: float, cls: str = "wire") -> None:
        if cls == "wire":  # merged at the end: a line shared by two branches drawn once
            self.wires.append((round(x1, 2), round(y1, 2), round(x2, 2), round(y2, 2)))
            self.grow(max(x1, x2), max(y1, y2))
            return
        self.parts.append(f'<line class="{cls}" x1="{x1:g}" y1="{y1:g}" x2="{x2:g}" '
                          f'y2="{y2:g}"/>')
        self.grow(max(x1, x2), max(y1, y2))

    def rect(self, x: float, y: float, w: float, h: float, cls: str) -> None:
        self.parts.append(f'<rect class="{cls}" x="{x:g}" y="{y:g}" width="{w:g}" '
                          f'height="{h:g}"/>')
        self.grow(x + w, y + h)

    def text(self, x: float, y: float, s: str, cls: str = "label", anchor: str = "start"
             ) -> None:
        self.parts.append(f'<text class="{cls}" x="{x:g}" y="{y:g}" text-anchor="{anchor}">'
                          f"{escape(s)}</text>")
        w = _width(s, bold="name" in cls.split())
        self.grow(x + (w if anchor == "start" else w / 2), y + 4)


def render_sfc_svg(pou: Any, *, values: dict[str, Any] | None = None) -> str:
    """The chart of ``pou`` (a parsed POU with an SFC body, lowered or not) as an SVG
    document. ``values`` maps variable names (``"S1.X"``, ``"Main.S1.X"``, ``"go"``) to their
    values at one moment: active steps are highlighted, and a transition whose steps are all
    active is drawn in orange, with its condition's value when ``values`` has what it reads."""
    chart = _chart_of(pou)
    prefix = (getattr(pou, "spelling", "") or getattr(pou, "name", "")).upper() + "."
    vals: dict[str, Any] = {}
    for k, v in (values or {}).items():
        key = str(k).upper()
        vals[key[len(prefix):] if key.startswith(prefix) else key] = v
    o = outline(chart)
    # a jump arrow hanging from one bar must not end on the double line of another bar of the
    # same row, nor two double lines or two arrows' names lie on each other: such a line goes
    # lower (and the row's gap grows) until it is clear
    drops: dict[int, float] = {}
    extra: dict[int, float] = {}
    for _ in range(8):
        svg, doubles, hung = _draw(chart, o, vals, drops, extra)
        clash = _clash(doubles, hung)
        if clash is None:
            break
        k, need = clash
        row, lowered = next((d[1], d[5]) for d in doubles if d[0] == k)
        if lowered:  # under its bar: lower it, and the next row with it
            drops[k] = drops.get(k, 0.0) + need
            extra[row] = max(extra.get(row, 0.0), drops[k])
        else:  # just above its steps: they go down
            extra[row] = extra.get(row, 0.0) + need
    from plclab.viz.render_network import merge_segments

    svg.parts[:0] = [f'<line class="wire" x1="{x1:g}" y1="{y1:g}" x2="{x2:g}" y2="{y2:g}"/>'
                     for x1, y1, x2, y2 in merge_segments(svg.wires)]
    w, h = svg.width + MARGIN, svg.height + MARGIN
    head = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0f}" height="{h:.0f}" '
            f'viewBox="0 0 {w:.0f} {h:.0f}" font-family="DejaVu Sans, Arial, sans-serif" '
            f'font-size="{FONT}">')
    title = escape(f"SFC {getattr(pou, 'spelling', '') or getattr(pou, 'name', '')}")
    style = ("<style>.wire{stroke:#222;stroke-width:1.3;fill:none}"
             ".bar{stroke:#222;stroke-width:3.5}.bar.enabled{stroke:" + ENABLED + "}"
             ".frame{fill:#fff;stroke:#222;stroke-width:1.4}"
             ".step.active .frame,.frame.active{fill:" + ACTIVE + "}"
             ".inner{fill:none;stroke:#222;stroke-width:1.2}"
             ".act{fill:#fff;stroke:#555;stroke-width:1}.name{font-weight:bold}"
             ".cond{fill:#1a237e}.cond.enabled{fill:" + ENABLED + "}.qual{fill:#555}"
             ".jump{fill:#222}</style>")
    return "\n".join([head, f"<title>{title}</title>", style, *svg.parts, "</svg>"]) + "\n"




def _clash(doubles: list, hung: list) -> tuple[int, float] | None:
    """In one row's gap: a jump arrow (its tip or its target's name) on another bar's double
    line, two double lines on each other, or two arrows' names on each other; the transition
    whose double line goes lower, and by how much."""
    lines = {d[0]: d for d in doubles}
    for k, row, y, lo, hi, lowered in doubles:
        for owner, jrow, x, tip, width in hung:
            if owner != k and jrow == row and lo - 6 <= x + 10 + width and x <= hi + 6 \
                    and tip - 20 <= y <= tip + 8:
                return k, tip + 12 - y
        for k2, row2, y2, lo2, hi2, lowered2 in doubles:
            if k2 > k and row2 == row and abs(y2 - y) < 8 and min(hi, hi2) - max(lo, lo2) > -6:
                if lowered2:  # the later one under the earlier
                    return k2, y + 10 - y2
                if lowered:
                    return k, y2 + 10 - y
    for i, (k, row, x, tip, width) in enumerate(hung):
        for k2, row2, x2, tip2, width2 in hung[i + 1:]:
            if k2 != k and row2 == row and abs(tip2 - tip) < 16 and x - 8 < x2 + 10 + width2 \
                    and x2 - 8 < x + 10 + width:
                later = max((j for j in (k, k2) if j in lines), default=None)
                if later is not None:
                    return later, 24.0
    return None

def _draw(chart: Any, o: dict[str, Any], vals: dict[str, Any], drops: dict[int, float],
          extra: dict[int, float]) -> tuple[_Svg, list, list]:
    """The chart drawn with the double lines of ``drops`` lowered and the rows' gaps grown
    by ``extra``; its double lines (transition, row, y, x from, x to, hung under its bar) and
    hanging jump
    arrows (transition, row, x, tip y, width of the target's name)."""
    nodes = [_Node(s.name, s.text, s.initial, o["steps"][k]["actions"])
             for k, s in enumerate(chart.steps)]
    by_name = {n.name: n for n in nodes}
    for n in nodes:
        n.active = bool(vals.get(f"{n.text}.X".upper(), vals.get(f"{n.name}.X", False)))
    _place(nodes, chart, o, extra)
    for _ in range(len(nodes)):  # a step's bars spread right must stop before the next step
        bars = _bars(by_name, chart, o)
        crowded = _crowded(by_name, chart, bars)
        if crowded is None:
            break
        m, dx = crowded
        for n in nodes:  # that step's column and every column right of it move right
            if n.cx >= m.cx - 0.5:
                n.cx += dx
    svg = _Svg()
    for n in nodes:
        _step(svg, n)
    labels: list[tuple[float, float, str, str]] = []
    jumps: list[tuple[float, float, _Node, float, int, int]] = []
    doubles: list[tuple[int, int, float, float, float, int]] = []
    for k, t in enumerate(chart.transitions):
        _transition(svg, t, o["transitions"][k], by_name, vals, bars[k], labels, jumps,
                    k, drops.get(k, 0.0), doubles)
    lines = _conditions(svg, labels)
    hung = []
    for x, y, n, bar_y, k, row in jumps:  # below the condition written beside the arrow
        lines_here = lines.get((round(x), round(bar_y)), 0) if abs(y - bar_y) < 0.5 else 0
        length = max(JUMP_H, 14 * lines_here + 6)
        _jump(svg, x, y, n, length)
        hung.append((k, row, x, y + length, _width(n.text, bold=True)))
    return svg, doubles, hung


def _chart_of(pou: Any) -> Any:
    chart = getattr(pou, "sfc", None)
    if chart is None:
        for body in getattr(pou, "pending", None) or []:
            if getattr(body, "kind", "") == "SFC" and body.payload:
                chart = body.payload[0]
    if chart is None or not chart.steps:
        name = getattr(pou, "spelling", "") or getattr(pou, "name", "?")
        raise PlcError("PLC4050", f"{name} has no SFC body to draw; render_sfc_svg draws a "
                       "PROGRAM or FUNCTION_BLOCK written as steps and transitions "
                       "(textual SFC or a PLCopen <SFC> body)")
    return chart


def _place(nodes: list[_Node], chart: Any, o: dict[str, Any],
           extra: dict[int, float] | None = None) -> None:
    """Rows: breadth first from the initial step; columns: in the order the steps are
    reached, each row starting under the leftmost step that leads to it."""
    by_name = {n.name: n for n in nodes}
    start = next((n for n in nodes if n.initial), nodes[0])
    start.row = 0
    order = [start]
    queue = [start]
    # the plain branches first; transitions with a PRIORITY (aborts, usually) to the right
    trans = sorted(chart.transitions, key=lambda t: t.priority is not None)
    while queue:
        cur = queue.pop(0)
        for t in trans:
            if cur.name not in {s for s, _ in t.sources}:
                continue
            for tgt, _ in t.targets:
                n = by_name.get(tgt)
                if n is not None and n.row < 0:
                    n.row, n.parent = cur.row + 1, cur.name
                    order.append(n)
                    queue.append(n)
    # a simultaneous convergence: the steps it leads to stand below the lowest step it joins
    # (and what follows them further down); a few rounds settle it
    for _ in range(len(nodes)):
        moved = False
        for t in chart.transitions:
            srcs = [by_name[s] for s, _ in t.sources if s in by_name]
            low = max((m.row for m in srcs), default=-1)
            for tgt, _ in t.targets:
                n = by_name.get(tgt)
                if n is None or n.parent not in {m.name for m in srcs}:
                    continue
                if len(srcs) > 1 and n.row <= low:
                    n.row, moved = low + 1, True
        for n in nodes:
            p = by_name.get(n.parent)
            if p is not None and n.row <= p.row:
                n.row, moved = p.row + 1, True
        if not moved:
            break
    last = max((n.row for n in nodes), default=0)
    for n in nodes:  # steps never reached (reported by the checks): a row of their own
        if n.row < 0:
            last += 1
            n.row = last
            order.append(n)
    # columns depth first along the tree of first arrivals: a branch keeps its column down
    # the chart, the next branch takes the next free column (no crossing wires in a tree)
    kids: dict[str, list[_Node]] = {}
    for n in order:
        if n.parent:
            kids.setdefault(n.parent, []).append(n)
    used: dict[int, list[float]] = {}
    free = [0.0]

    def column(n: _Node, c: float) -> None:
        while any(abs(c - x) < 0.5 for x in used.get(n.row, [])):
            c = free[0]
            free[0] += 1.0
        n.col = c
        free[0] = max(free[0], c + 1.0)
        used.setdefault(n.row, []).append(c)
        for k, child in enumerate(kids.get(n.name, [])):
            if k == 0:
                column(child, c)
            else:
                column(child, free[0])

    for n in order:
        if not n.parent:
            column(n, 0.0 if n is start else free[0])
    # each column as far right of the one before as its steps and action blocks need
    cols = sorted({int(n.col) for n in nodes})
    x = float(MARGIN)
    prev: list[_Node] = []
    for c in cols:
        here = [n for n in nodes if int(n.col) == c]
        half = max(n.w / 2 for n in here)
        reach = max((max(n.right, _reach(n, chart, o, by_name)) for n in prev), default=0.0)
        x = MARGIN + half if not prev else max(x + COL, x + reach + half + 60)
        for n in here:
            n.cx = x
        prev = here
    y = float(MARGIN)
    for r in range(max(n.row for n in nodes) + 1):
        row = [n for n in nodes if n.row == r]
        tall = max((n.h for n in row), default=STEP_H)
        for n in row:
            n.y, n.row_h = y, tall
        y += tall + GAP + (extra or {}).get(r, 0.0)


def _reach(n: _Node, chart: Any, o: dict[str, Any], nodes: dict[str, _Node]) -> float:
    """How far right of the step's centre its transitions reach: the bars beside the step
    (as :func:`_bars` places them) and their conditions on one line."""
    outs = sorted((k for k, t in enumerate(chart.transitions)
                   if [s for s, _ in t.sources] == [n.name]),
                  key=lambda k: chart.transitions[k].priority is not None)

    def child(k: int) -> bool:
        return any(m in nodes and nodes[m].parent == n.name and nodes[m].row > n.row
                   for m, _ in chart.transitions[k].targets)

    labels = [_width(_cond_label(chart.transitions[k], o["transitions"][k])) for k in outs]
    own = [w for k, w in zip(outs, labels, strict=True) if child(k) and len(outs) > 1][:1]
    side = [w for k, w in zip(outs, labels, strict=True) if not (child(k) and len(outs) > 1)]
    x, prev = 0.0, (own[0] if own else None)
    reach = 30 + prev if prev is not None else 0.0
    for w in side:
        if prev is not None:
            x += min(max(SIDE, prev + 64), 2 * SIDE)
        reach = max(reach, x + 20 + w + 10)
        prev = w
    return reach


def _bars(nodes: dict[str, _Node], chart: Any, o: dict[str, Any]) -> dict[int, float]:
    """The x of each transition's bar: under its step; a step's second and further
    transitions go down into the column of the step they lead to (when drawn under this
    step), else beside the step, far enough right for the condition of the bar before."""
    out: dict[int, float] = {}
    owner: dict[float, int] = {}
    for n in nodes.values():
        outs = [k for k, t in enumerate(chart.transitions)
                if [s for s, _ in t.sources] == [n.name]]
        taken: list[float] = []
        for k in sorted(outs, key=lambda k: chart.transitions[k].priority is not None):
            t = chart.transitions[k]
            fwd = [nodes[m] for m, _ in t.targets if m in nodes and nodes[m].row > n.row]
            x = _x(n)
            if len(outs) > 1 and fwd and fwd[0].parent == n.name:
                x = _x(fwd[0])
            while any(abs(x - u) < 1 for u in taken):
                last = max(taken)
                before = chart.transitions[owner[last]]
                room = _width(_cond_label(before, o["transitions"][owner[last]])) + 64
                x = last + min(max(SIDE, room), 2 * SIDE)
                while any(abs(x - m.cx) < 12 for m in nodes.values() if m is not n):
                    x += 12  # not beside another column's wire, which may pass this row
            taken.append(x)
            owner[x] = k
            out[k] = x
    for k, t in enumerate(chart.transitions):
        if k not in out:  # a simultaneous convergence: under the steps it joins
            srcs = [nodes[s] for s, _ in t.sources if s in nodes]
            low = max((m.row for m in srcs), default=0)
            fwd = [nodes[m] for m, _ in t.targets if m in nodes and nodes[m].row > low]
            pts = fwd if len(fwd) == 1 else srcs
            x = sum(_x(m) for m in pts) / max(len(pts), 1)
            row = [out[j] for j, u in enumerate(chart.transitions) if j in out and
                   max((nodes[m].row for m, _ in u.sources if m in nodes), default=0) == low]
            while any(abs(x - u) < SIDE for u in row):  # not on a bar of the same row
                x = max(u for u in row if abs(x - u) < SIDE) + SIDE + 1
                while any(0.5 < abs(x - m.cx) < 12 for m in nodes.values()):
                    x += 12  # nor beside another column's wire, which may pass this row
            out[k] = x
    return out



def _crowded(nodes: dict[str, _Node], chart: Any, bars: dict[int, float]
             ) -> tuple[_Node, float] | None:
    """A step standing on or just right of a bar of another step of its row (a step's
    further transitions spread right past the column of a step it leads to), and how far
    it must move right; None when every bar has room for its condition."""
    for k, t in enumerate(chart.transitions):
        srcs = [nodes[s] for s, _ in t.sources if s in nodes]
        if len(srcs) != 1:
            continue
        n = srcs[0]
        for m in nodes.values():
            if m.row != n.row or m.cx <= n.cx + 0.5 or bars[k] < m.cx - m.w / 2 - 400:
                continue
            room = m.cx - m.w / 2 - (bars[k] + 100)
            if room < 0 and bars[k] > n.cx + 0.5:
                return m, -room
    return None

def _x(n: _Node) -> float:
    return n.cx


def _y(n: _Node) -> float:
    return n.y


def _step(svg: _Svg, n: _Node) -> None:
    y, w = _y(n), n.w
    x = _x(n) - w / 2
    cls = "step active" if n.active else "step"
    svg.parts.append(f'<g class="{cls}" data-step="{escape(n.text)}">')
    svg.rect(x, y, w, STEP_H, "frame active" if n.active else "frame")
    if n.initial:  # IEC: the initial step has a double frame
        svg.rect(x + 3.5, y + 3.5, w - 7, STEP_H - 7, "inner")
    svg.text(_x(n), y + STEP_H / 2 + 4, n.text, "name", "middle")
    svg.parts.append("</g>")
    if not n.actions:
        return
    ax = x + w + 18
    svg.line(x + w, y + STEP_H / 2, ax, y + STEP_H / 2)
    qual_w, name_w = QUAL_W, n.name_w
    for k, a in enumerate(n.actions):
        ay = y + k * 22
        svg.rect(ax, ay, qual_w, 22, "act")
        svg.rect(ax + qual_w, ay, name_w, 22, "act")
        svg.text(ax + qual_w / 2, ay + 15, a["qualifier"], "qual", "middle")
        svg.text(ax + qual_w + 7, ay + 15, _action_label(a))


def _conditions(svg: _Svg, labels: list[tuple[float, float, str, str]]
                ) -> dict[tuple[int, int], int]:
    """Each condition right of its bar, wrapped so that it stops before the next bar of the
    same height; the number of lines of each, by its bar's (x, y)."""
    out: dict[tuple[int, int], int] = {}
    for x, y, text, cls in labels:
        right = min((x2 for x2, y2, _, _ in labels if abs(y2 - y) < 1 and x2 > x + 1),
                    default=None)
        room = right - x - 44 if right is not None else 1e9
        wrapped = _wrap(text, max(room, 100.0))
        out[(round(x), round(y))] = len(wrapped)
        for k, line in enumerate(wrapped):
            svg.text(x + 20, y + 4 + 14 * k, line, cls)
    return out


def _wrap(text: str, width: float) -> list[str]:
    """Words into lines no wider than ``width`` px (a longer word stands alone)."""
    lines: list[str] = []
    cur = ""
    for word in text.split(" "):
        if cur and _width(f"{cur} {word}") > width:
            lines.append(cur)
            cur = word
        else:
            cur = f"{cur} {word}" if cur else word
    return lines + [cur] if cur else lines


def _action_label(a: dict[str, Any]) -> str:
    return f"{a['action']}, {a['time']}" if a.get("time") else a["action"]


def _transition(svg: _Svg, t: Any, ot: dict[str, Any], nodes: dict[str, _Node],
                vals: dict[str, Any], bar_x: float, labels: list, jumps: list, k: int = 0,
                drop: float = 0.0, doubles: list | None = None) -> None:
    srcs = [nodes[s] for s, _ in t.sources if s in nodes]
    tgts = [nodes[s] for s, _ in t.targets if s in nodes]
    if not srcs:
        return
    row = max(n.row for n in srcs)
    forward = [n for n in tgts if n.row > row]
    back = [n for n in tgts if n.row <= row]
    bottom = max(_y(n) + n.row_h for n in srcs)
    bar_y = bottom + 44
    # from the steps down to the bar: one step straight, several steps (simultaneous
    # convergence) joined by a double line
    if len(srcs) == 1:
        s = srcs[0]
        if abs(_x(s) - bar_x) < 0.5:
            svg.line(_x(s), _y(s) + STEP_H, bar_x, bar_y)
        else:  # an alternative divergence: a single horizontal line under the step
            svg.line(_x(s), _y(s) + STEP_H, _x(s), bottom + 14)
            svg.line(_x(s), bottom + 14, bar_x, bottom + 14)
            svg.line(bar_x, bottom + 14, bar_x, bar_y)
    else:
        yj = bar_y - 16
        lo = min([_x(n) for n in srcs] + [bar_x])
        hi = max([_x(n) for n in srcs] + [bar_x])
        for s in srcs:
            svg.line(_x(s), _y(s) + STEP_H, _x(s), yj - 3)
        svg.line(lo, yj - 3, hi, yj - 3)
        svg.line(lo, yj, hi, yj)
        svg.line(bar_x, yj, bar_x, bar_y)
    enabled = bool(srcs) and all(n.active for n in srcs)
    value = None
    if t.cond is not None and vals:
        value = evaluate(t.cond, lambda p: vals.get(p.upper()))
    cls = "bar enabled" if enabled else "bar"
    svg.line(bar_x - 14, bar_y, bar_x + 14, bar_y, cls)
    label = _cond_label(t, ot)
    if value is not None:
        label += f" = {'TRUE' if value else 'FALSE'}"
    labels.append((bar_x, bar_y, label, "cond enabled" if enabled else "cond"))
    # from the bar down to the following steps
    below = bar_y + 16 + drop
    if forward and not back:  # a simultaneous divergence's double line just above its steps,
        below = min(_y(n) for n in forward) - 20  # clear of jumps hanging from other bars
    if len(forward) == 1 and not back:
        n = forward[0]
        if abs(_x(n) - bar_x) < 0.5:
            svg.line(bar_x, bar_y, bar_x, _y(n))
        else:  # an alternative convergence: a single line above the step
            top = _y(n) - 8  # below a simultaneous double line (-20, -17) before it
            svg.line(bar_x, bar_y, bar_x, top)
            svg.line(bar_x, top, _x(n), top)
            svg.line(_x(n), top, _x(n), _y(n))
    elif forward or len(back) > 1:  # a simultaneous divergence: a double line
        spots = []  # each jump right of the steps and their actions, and of the jump before
        x = max([bar_x] + [_x(n) + n.right - 40 for n in forward])
        for n in back:
            x += max(60.0, _width(spots[-1][1].text, bold=True) + 36) if spots else 60.0
            spots.append((x, n))
        ends = [_x(n) for n in forward] + [x for x, _ in spots]
        lo, hi = min(ends + [bar_x]), max(ends + [bar_x])
        svg.line(bar_x, bar_y, bar_x, below)
        svg.line(lo, below, hi, below)
        svg.line(lo, below + 3, hi, below + 3)
        if doubles is not None:
            doubles.append((k, row, below, lo, hi, bool(back)))
        for n in forward:
            svg.line(_x(n), below + 3, _x(n), _y(n))
        for j, n in enumerate(back):
            jumps.append((spots[j][0], below + 3, n, bar_y, k, row))
    if not forward and len(back) == 1:
        jumps.append((bar_x, bar_y, back[0], bar_y, k, row))


def _cond_label(t: Any, ot: dict[str, Any]) -> str:
    """A transition's condition as drawn, its priority first."""
    return f"[{t.priority}] {ot['condition']}" if t.priority is not None else ot["condition"]


def _jump(svg: _Svg, x: float, y: float, n: _Node, length: float = JUMP_H) -> None:
    """An arrow down to the name of the step the transition activates (PLCopen jumpStep):
    short, so that it ends well above the lines that join the branches before the next row."""
    svg.line(x, y, x, y + length - 8)
    svg.parts.append(f'<path class="jump" d="M{x - 6:g},{y + length - 10:g} '
                     f'L{x + 6:g},{y + length - 10:g} L{x:g},{y + length:g} Z" '
                     f'data-target="{escape(n.text)}"/>')
    svg.text(x + 10, y + length - 1, n.text, "name jump-target")
