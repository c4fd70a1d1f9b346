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

STEP_W, STEP_H = 96, 32
GAP = 92  # vertical space between a row of steps (with their actions) and the next
COL = 340  # horizontal distance between step columns
SIDE = 170  # a second transition of a step (a loop, an abort) stands this far to the right
MARGIN = 30
CHAR_W = 6.6  # average width of a character at FONT px
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
    y: float = 0.0
    row_h: float = STEP_H  # the tallest step of its row, with its actions

    @property
    def h(self) -> float:
        """The step with its action block."""
        return max(STEP_H, 22.0 * len(self.actions))


@dataclass
class _Svg:
    parts: list[str] = field(default_factory=list)
    width: float = 0.0
    height: float = 0.0

    def grow(self, x: float, y: float) -> None:
        self.width = max(self.width, x)
        self.height = max(self.height, y)

    def line(self, x1: float, y1: float, x2: float, y2: float, cls: str = "wire") -> None:
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
        w = len(s) * CHAR_W
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
    nodes = [_Node(s.name, s.text, s.initial, o["steps"][k]["actions"])
             for k, s in enumerate(chart.steps)]
    by_name = {n.name: n for n in nodes}
    for n in nodes:
        n.active = bool(vals.get(f"{n.text}.X".upper(), vals.get(f"{n.name}.X", False)))
    _place(nodes, chart)
    bars = _bars(by_name, chart)
    svg = _Svg()
    for n in nodes:
        _step(svg, n)
    labels: list[tuple[float, float, str, str]] = []
    for k, t in enumerate(chart.transitions):
        _transition(svg, t, o["transitions"][k], by_name, vals, bars[k], labels)
    _conditions(svg, labels)
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


def _place(nodes: list[_Node], chart: Any) -> None:
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
    y = float(MARGIN)
    for r in range(max(n.row for n in nodes) + 1):
        row = [n for n in nodes if n.row == r]
        tall = max((n.h for n in row), default=STEP_H)
        for n in row:
            n.y, n.row_h = y, tall
        y += tall + GAP


def _bars(nodes: dict[str, _Node], chart: Any) -> dict[int, float]:
    """The x of each transition's bar: under its step; a step's second and further
    transitions go down into the column of the step they lead to (when drawn under this
    step), else beside the step."""
    out: dict[int, float] = {}
    for n in nodes.values():
        outs = [k for k, t in enumerate(chart.transitions)
                if [s for s, _ in t.sources] == [n.name]]
        taken: list[float] = []
        side = 0
        for k in sorted(outs, key=lambda k: chart.transitions[k].priority is not None):
            t = chart.transitions[k]
            fwd = [nodes[m] for m, _ in t.targets if m in nodes and nodes[m].row > n.row]
            x = _x(n)
            if len(outs) > 1 and fwd and fwd[0].parent == n.name:
                x = _x(fwd[0])
            while any(abs(x - u) < 1 for u in taken):
                side += 1
                x = _x(n) + side * SIDE
            taken.append(x)
            out[k] = x
    for k, t in enumerate(chart.transitions):
        if k not in out:  # a simultaneous convergence: under the steps it joins
            srcs = [nodes[s] for s, _ in t.sources if s in nodes]
            low = max((m.row for m in srcs), default=0)
            fwd = [nodes[m] for m, _ in t.targets if m in nodes and nodes[m].row > low]
            pts = fwd if len(fwd) == 1 else srcs
            out[k] = sum(_x(m) for m in pts) / max(len(pts), 1)
    return out


def _x(n: _Node) -> float:
    return MARGIN + n.col * COL + STEP_W / 2


def _y(n: _Node) -> float:
    return n.y


def _step(svg: _Svg, n: _Node) -> None:
    x, y = _x(n) - STEP_W / 2, _y(n)
    w = max(STEP_W, len(n.text) * CHAR_W + 20)
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
    qual_w = 38
    name_w = max(len(_action_label(a)) * CHAR_W + 14 for a in n.actions)
    for k, a in enumerate(n.actions):
        ay = y + k * 22
        svg.rect(ax, ay, qual_w, 22, "act")
        svg.rect(ax + qual_w, ay, name_w, 22, "act")
        svg.text(ax + qual_w / 2, ay + 15, a["qualifier"], "qual", "middle")
        svg.text(ax + qual_w + 7, ay + 15, _action_label(a))


def _conditions(svg: _Svg, labels: list[tuple[float, float, str, str]]) -> None:
    """Each condition right of its bar, wrapped so that it stops before the next bar of the
    same height."""
    for x, y, text, cls in labels:
        right = min((x2 for x2, y2, _, _ in labels if abs(y2 - y) < 1 and x2 > x + 1),
                    default=None)
        room = int((right - x - 44) / CHAR_W) if right is not None else 10_000
        for k, line in enumerate(_wrap(text, max(room, 12))):
            svg.text(x + 20, y + 4 + 14 * k, line, cls)


def _wrap(text: str, width: int) -> list[str]:
    lines: list[str] = []
    cur = ""
    for word in text.split(" "):
        if cur and len(cur) + 1 + len(word) > width:
            lines.append(cur)
            cur = word
        else:
            cur = f"{cur} {word}" if cur else word
    return lines + [cur] if cur else lines


def _action_label(a: dict[str, Any]) -> str:
    return f"{a['action']}, {a['time']}" if a.get("time") else a["action"]


def _transition(svg: _Svg, t: Any, ot: dict[str, Any], nodes: dict[str, _Node],
                vals: dict[str, Any], bar_x: float, labels: list) -> None:
    srcs = [nodes[s] for s, _ in t.sources if s in nodes]
    tgts = [nodes[s] for s, _ in t.targets if s in nodes]
    if not srcs:
        return
    row = max(n.row for n in srcs)
    forward = [n for n in tgts if n.row > row]
    jumps = [n for n in tgts if n.row <= row]
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
    label = ot["condition"]
    if t.priority is not None:
        label = f"[{t.priority}] {label}"
    if value is not None:
        label += f" = {'TRUE' if value else 'FALSE'}"
    labels.append((bar_x, bar_y, label, "cond enabled" if enabled else "cond"))
    # from the bar down to the following steps
    below = bar_y + 16
    if len(forward) == 1 and not jumps:
        n = forward[0]
        if abs(_x(n) - bar_x) < 0.5:
            svg.line(bar_x, bar_y, bar_x, _y(n))
        else:  # an alternative convergence: a single line above the step
            top = _y(n) - 14
            svg.line(bar_x, bar_y, bar_x, top)
            svg.line(bar_x, top, _x(n), top)
            svg.line(_x(n), top, _x(n), _y(n))
    elif forward or len(jumps) > 1:  # a simultaneous divergence: a double line
        ends = [_x(n) for n in forward] + [bar_x + 60 * (j + 1) for j in range(len(jumps))]
        lo, hi = min(ends + [bar_x]), max(ends + [bar_x])
        svg.line(bar_x, bar_y, bar_x, below)
        svg.line(lo, below, hi, below)
        svg.line(lo, below + 3, hi, below + 3)
        for n in forward:
            svg.line(_x(n), below + 3, _x(n), _y(n))
        for j, n in enumerate(jumps):
            _jump(svg, bar_x + 60 * (j + 1), below + 3, n)
    if not forward and len(jumps) == 1:
        _jump(svg, bar_x, bar_y, jumps[0])


def _jump(svg: _Svg, x: float, y: float, n: _Node) -> None:
    """An arrow down to the name of the step the transition activates (PLCopen jumpStep)."""
    svg.line(x, y, x, y + 26)
    svg.parts.append(f'<path class="jump" d="M{x - 6:g},{y + 20:g} L{x + 6:g},{y + 20:g} '
                     f'L{x:g},{y + 30:g} Z"/>')
    svg.text(x + 10, y + 30, n.text, "name")
