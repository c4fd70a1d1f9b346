"""LD and FBD networks as SVG, drawn from the network elements every front end makes
(:class:`plclab.lang.lower.network.Elem`): the text ladder format and PLCopen XML (LD and FBD)
go through the same drawing.

The layout is computed, not copied: an element's column is the length of the longest path of
wires feeding it; coils, output variables, jumps and returns stand in the last column, so the
right rail is one straight line for the whole POU; rows follow the wiring (each input pin on
the row of the output pin feeding it). Boxes are drawn as CODESYS and OpenPLC Editor draw them
(docs/adr/0048): the instance above, the type inside, every declared pin in declared order, each
operand at its pin; wires into one pin meet on one junction line; columns and boxes are as wide
as their measured text. With ``values`` (variable name -> value, e.g. from a Trace at a time),
contacts and coils that carry power are drawn green, wires carrying TRUE too, and each variable
shows its value, as an editor's online mode does.

>>> from plclab.viz.render_network import render_source
>>> svg = render_source('''PROGRAM P VAR a, q : BOOL; END_VAR
... |   a       q   |
... |---[ ]-----( )-|
... END_PROGRAM''', "p.ld", values={"A": True})
>>> svg.startswith("<svg") and "#1a7f37" in svg
True
"""

from __future__ import annotations

import functools
import re
from typing import Any
from xml.sax.saxutils import escape

from ..errors import PlcError
from ..lang import ast as A
from .ladder_svg import BOX, FONT, PAD, RAIL, WIRE, Svg
from .text_width import text_width

ROWH = 40  # height of a row (one pin)
ON = "#1a7f37"  # power flows / TRUE
ON_WIRE = f"stroke='{ON}' stroke-width='2.6' fill='none'"
SINKS = {"coil", "outvar", "jump", "return"}


def _txt(x: float, y: float, s: str, anchor: str = "start", extra: str = "") -> str:
    size = "" if "font-size" in extra else "font-size='12' "
    return (f"<text x='{x:.1f}' y='{y:.1f}' {FONT} {size}text-anchor='{anchor}' "
            f"{extra}>{escape(s)}</text>")


def _ln(x1: float, y1: float, x2: float, y2: float, style: str = WIRE) -> str:
    return f"<line x1='{x1:.1f}' y1='{y1:.1f}' x2='{x2:.1f}' y2='{y2:.1f}' {style}/>"


def _fmt(v: Any) -> str:
    if isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def _var_text(e) -> str:
    from ..lang.unparse import expr

    return expr(e.var) if e.var is not None else ""


class _Layout:
    """Columns, rows and pins of the elements of one POU's network."""

    def __init__(self, elems: list, values: dict[str, Any] | None,
                 pous: dict[str, Any] | None = None) -> None:
        self.elems = {e.id: e for e in elems}
        self.pous = pous or {}  # the POUs of the drawn file, by name
        self.values = {k.upper(): v for k, v in (values or {}).items()}
        self.consumers: dict[int, list] = {}
        for e in elems:
            for refs in e.inputs.values():
                for i, _ in refs:
                    self.consumers.setdefault(i, []).append(e)
        self.col: dict[int, int] = {}
        self.row: dict[int, int] = {}
        self.pin_off: dict[int, dict[str, int]] = {}
        self.power: dict[int, bool | None] = {}
        self.spelling: dict[str, str] = {}  # a pin (upper case) as its block declares it

    # -- structure ----------------------------------------------------------------------------
    def sources(self, e) -> list[tuple[str, int, str]]:
        """(input pin, source id, source pin) of ``e``, pins in order, left rail left out."""
        out = []
        for pin, refs in e.inputs.items():
            for i, sp in refs:
                if i >= 0 and self.elems[i].kind != "left":
                    out.append((pin, i, sp))
        return out

    def declared(self, type_name: str) -> tuple[list[str], list[str]] | None:
        """(inputs, outputs) of a block or function declared in the file or plclab's library;
        VAR_IN_OUT on both sides, as IEC 61131-3 draws them."""
        pou = self.pous.get(type_name.upper()) or _library_pous().get(type_name.upper())
        if pou is None:
            return None
        ins, outs = [], []
        for d in pou.decls:
            name = d.spelling or d.name
            self.spelling.setdefault(name.upper(), name)
            if d.section in ("VAR_INPUT", "VAR_IN_OUT"):
                ins.append(name.upper())
            if d.section in ("VAR_OUTPUT", "VAR_IN_OUT"):
                outs.append(name.upper())
        return ins, outs

    def arg_pins(self, e) -> list[str]:
        """The pin of each parameter written in a text box, in order: named ones by their
        name, positional ones by the function's formal parameters (IN1, IN2, ... for ADD, G,
        IN0, IN1 for SEL, K, IN0, IN1, ... for MUX)."""
        from ..lang.builtins import BUILTINS, conversion

        n = len(e.args)
        b = BUILTINS.get(e.type_name)
        if b is not None:
            params = list(b.params)
            if e.type_name == "MUX":
                params = ["K"] + [f"IN{i}" for i in range(max(n - 1, 2))]
            elif b.variadic:
                params += [f"IN{i + 1}" for i in range(len(params), n)]
        elif conversion(e.type_name) is not None:
            params = ["IN"]
        else:
            d = self.declared(e.type_name) if e.type_name else None
            params = d[0] if d is not None and e.kind == "func" else []
        params = params + [f"IN{i + 1}" for i in range(len(params), n)]
        return [(a.name or params[k]).upper() for k, a in enumerate(e.args)]

    def in_pins(self, e) -> list[str]:
        """The input pins of a box, top to bottom: the power flow's (LD), the wired ones, the
        ones given an operand, then the other declared inputs; [""] for other elements."""
        if e.kind not in BOXES:
            return [""]
        pins: list[str] = []
        if "" in e.inputs:
            pins.append(self.power_pins(e)[0].upper() if e.kind == "fb" else "EN")
        if "EN" in (p.upper() for p in e.inputs):
            pins.append("EN")
        if e.kind == "fb":  # a block's pins in the order it declares them, as editors draw
            d = self.declared(e.type_name)
            pins += [p for p in (d[0] if d is not None else []) if p not in pins]
        for p in e.inputs:
            if p and p.upper() not in pins:
                pins.append(p.upper())
        for a, p in zip(e.args, self.arg_pins(e), strict=True):
            if not a.output and p not in pins:
                pins.append(p)
        return pins or [""]

    def out_pins(self, e) -> list[str]:
        """The output pins of a box, top to bottom: the power flow's first (ENO of a function
        in a rung, then OUT), then the declared ones; [""] for other elements."""
        if e.kind == "cmp":
            return ["OUT"]
        if e.kind not in BOXES:
            return [""]
        outs = [p.upper() for p in getattr(e, "outs", []) or []]
        if not outs:
            if e.kind == "fb":
                known = self.power_pins(e) != ("EN", "ENO")
                outs = [self.power_pins(e)[1].upper()] if "" in e.inputs or known else \
                    [(e.out_pin or "OUT").upper()]
            else:
                outs = (["ENO"] if "" in e.inputs else []) + ["OUT"]
        if e.kind == "fb":  # declared order, as the inputs (ENO and the rung's pin first)
            d = self.declared(e.type_name)
            if d is not None:
                head = [p for p in outs[:1] if p == "ENO" or "" in e.inputs]
                outs = head + [p for p in d[1] if p not in head] + \
                    [p for p in outs if p not in head and p not in d[1]]
        for a, p in zip(e.args, self.arg_pins(e), strict=True):
            if a.output and p not in outs:
                outs.append(p)
        return outs

    def in_operands(self, e) -> dict[str, str]:
        """Input pin -> the operand written at it (a text box's parameters)."""
        from ..lang.unparse import expr

        return {p: expr(a.value) for a, p in zip(e.args, self.arg_pins(e), strict=True)
                if not a.output and a.value is not None}

    def out_operands(self, e) -> dict[str, str]:
        """Output pin -> the variable it writes (``ET=>x``; a function's ``-> x`` at OUT)."""
        from ..lang.unparse import expr

        out = {p: ("NOT " if a.negated else "") + expr(a.value)
               for a, p in zip(e.args, self.arg_pins(e), strict=True)
               if a.output and a.value is not None}
        if e.targets:
            out["OUT"] = ", ".join(expr(t) for t in e.targets)
        return out

    def pin_text(self, pin: str) -> str:
        return self.spelling.get(pin, pin)

    def power_pins(self, e) -> tuple[str, str]:
        """(input, output) pins that carry a ladder box's power flow: the block spec's, else
        the first BOOL input and output of the block's declaration (the file's or plclab's
        library), else EN/ENO."""
        from ..lang.builtins import BLOCKS

        b = BLOCKS.get(e.type_name)
        if b is not None and b.power:
            return b.power
        pou = self.pous.get(e.type_name) or _library_pous().get(e.type_name)
        if pou is not None:
            def first(section: str) -> str | None:
                return next((d.spelling or d.name for d in pou.decls if d.section == section and
                             isinstance(d.type, A.NamedTypeRef) and d.type.name == "BOOL"), None)
            i, o = first("VAR_INPUT"), first("VAR_OUTPUT")
            if i and o:
                return i, o
        return ("EN", "ENO")

    def columns(self) -> int:
        order = _topological(list(self.elems.values()), self)
        for e in order:
            srcs = [self.col[i] + 1 for _, i, _ in self.sources(e) if i in self.col]
            self.col[e.id] = max(srcs, default=0)
        last = max((c for i, c in self.col.items() if self.elems[i].kind not in SINKS),
                   default=0) + 1
        for e in order:
            if e.kind in SINKS:
                self.col[e.id] = last
        return last

    def rows(self) -> int:
        """Rows from the sinks back, as a tree: each element belongs to its first consumer;
        each input pin of a box stands on the row of the output that feeds it (the box grows),
        so wires run straight; the networks (sinks in order) stacked. Iterative."""
        order = [e for e in _topological(list(self.elems.values()), self) if e.kind != "left"]
        sinks = sorted((e for e in order if not self.consumers.get(e.id)),
                       key=lambda e: e.order)
        parent: dict[int, int] = {}
        kids: dict[int, list[tuple[str, int, str]]] = {}  # id -> (input pin, child, its pin)
        seen: set[int] = set()
        stack = [e.id for e in reversed(sinks)]
        while stack:
            i = stack.pop()
            if i in seen:
                continue
            seen.add(i)
            mine = []
            for pin, j, sp in self.sources(self.elems[i]):
                if j in seen or j in parent:
                    continue
                parent[j] = i
                mine.append((pin, j, sp))
            kids[i] = mine
            stack.extend(j for _, j, _ in reversed(mine))
        size: dict[int, int] = {}
        places: dict[int, list[tuple[int, int]]] = {}
        for e in order:  # sources first: children are sized before their parent
            self.pin_off[e.id], places[e.id], size[e.id] = self.offsets(e, kids.get(e.id, []),
                                                                        size)
        free, gap = 0, True
        for root in sinks:
            members, todo = [], [(root.id, 0)]
            while todo:
                i, r = todo.pop()
                members.append((i, r))
                todo.extend((j, r + off) for off, j in places.get(i, []))
            boxes = any(self.elems[i].kind in BOXES for i, _ in members)
            if boxes and not gap:
                free += 1  # room for the box titles above
            for i, r in members:
                self.row[i] = free + r
            free += size.get(root.id, 1) + (1 if boxes else 0)
            gap = boxes
        return free

    def out_row(self, e, pin: str) -> int:
        """The row of output ``pin`` of ``e``, counted from the row ``e`` is placed on."""
        base = self.pin_off.get(e.id, {}).get(self.in_pins(e)[0], 0)
        if e.kind not in BOXES:
            return base
        outs = self.out_pins(e)
        return base + (outs.index(pin.upper()) if pin and pin.upper() in outs else 0)

    def offsets(self, e, kids: list[tuple[str, int, str]], size: dict[int, int]):
        """(input pin -> row offset, (row offset, child) placements, rows taken) of ``e``:
        each pin on the row of the output of its first source."""
        pins = self.in_pins(e)
        by_pin: dict[str, list[tuple[int, str]]] = {}
        for pin, j, sp in kids:
            by_pin.setdefault(_pin_of(pin, pins), []).append((j, sp))
        pin_off: dict[str, int] = {}
        places: list[tuple[int, int]] = []
        nxt, free = 0, 0  # the next pin's row; the first row below the children so far
        for pin in pins:
            cur = max(nxt, free) if by_pin.get(pin) else nxt
            arrive = None
            for j, sp in by_pin.get(pin, []):
                if places and self.elems[j].kind in BOXES:
                    cur += 1  # a row for the title of a box under another child
                places.append((cur, j))
                if arrive is None:
                    arrive = cur + self.out_row(self.elems[j], sp)
                cur += size.get(j, 1)
            pin_off[pin] = nxt if arrive is None else arrive
            nxt = pin_off[pin] + 1
            free = max(free, cur)
        outs = len(self.out_pins(e)) if e.kind in BOXES else 1
        return pin_off, places, max(nxt, free, pin_off[pins[0]] + outs)

    def base(self, e) -> int:
        """The row of the first pin of ``e`` (the wire row of a contact, coil or variable)."""
        return self.row[e.id] + self.pin_off.get(e.id, {}).get(self.in_pins(e)[0], 0)

    def box_rows(self, e) -> int:
        """How many rows the box of ``e`` spans, from its first pin's row."""
        offs = self.pin_off.get(e.id, {})
        first = offs.get(self.in_pins(e)[0], 0)
        return max(max(offs.values(), default=0) - first + 1, len(self.out_pins(e)))

    # -- values -------------------------------------------------------------------------------
    def value_of(self, text: str) -> Any:
        return self.values.get(text.upper())

    def flows(self, e) -> bool | None:
        """Power flowing out of ``e`` (LD) or its BOOL output value, when values are known."""
        if not self.values:  # no values, no power flow drawn
            return None
        if e.id in self.power:
            return self.power[e.id]
        self.power[e.id] = None  # cycles: unknown
        k = e.kind
        if k == "left":
            out: bool | None = True
        elif k in ("contact", "coil", "conn"):
            ins = [self.flows(self.elems[i]) if i >= 0 else True
                   for i, _ in e.inputs.get("", [])]
            feed = True if any(x is True for x in ins) else (None if None in ins else False)
            if k == "contact":
                v = self.value_of(_var_text(e))
                cond = None if not isinstance(v, bool) or e.mode in ("P", "N") else \
                    (not v if e.mode == "/" else v)  # an edge: one scan, unknown from a value
                out = None if feed is None or cond is None else (feed and cond)
            else:
                out = feed
        elif k in ("invar", "inoutvar"):
            v = self.value_of(_var_text(e))
            out = v if isinstance(v, bool) else None
        elif k == "func" and e.type_name in ("AND", "OR", "XOR", "NOT"):
            ins = [self.flows(self.elems[i]) for refs in e.inputs.values() for i, _ in refs
                   if i >= 0]
            ins = [(not x) if x is not None and pin in e.neg_in else x
                   for pin, x in zip([p for p, refs in e.inputs.items() for _ in refs], ins,
                                     strict=False)]
            if None in ins or not ins:
                out = None
            elif e.type_name == "NOT":
                out = not ins[0]
            elif e.type_name == "AND":
                out = all(ins)
            elif e.type_name == "OR":
                out = any(ins)
            else:
                out = sum(bool(x) for x in ins) % 2 == 1
        elif k == "fb" and e.instance is not None:
            from ..lang.unparse import expr

            v = self.value_of(f"{expr(e.instance)}.{self.out_pins(e)[0]}")
            out = v if isinstance(v, bool) else None
        elif k == "func" and "" in e.inputs:  # EN -> ENO
            ins = [self.flows(self.elems[i]) if i >= 0 else True
                   for i, _ in e.inputs.get("", [])]
            out = True if any(x is True for x in ins) else (None if None in ins else False)
        else:
            out = None
        self.power[e.id] = out
        return out

    # -- sizes --------------------------------------------------------------------------------
    def label(self, e) -> str:
        """The variable of a contact, coil or variable box with its value when known."""
        name = _var_text(e)
        val = self.value_of(name) if name else None
        return name + (f" = {_fmt(val)}" if val is not None else "")

    def out_pin_label(self, e, pin: str) -> str:
        from ..lang.unparse import expr

        if e.instance is not None:
            v = self.value_of(f"{expr(e.instance)}.{pin}")
            if v is not None:
                return f"{self.pin_text(pin)} {_fmt(v)}"
        return self.pin_text(pin)

    def operand_label(self, text: str) -> str:
        """An operand with its value when it is a variable the values know."""
        v = self.value_of(text) if _VARIABLE.fullmatch(text) else None
        return text + (f" = {_fmt(v)}" if v is not None else "")

    def box_width(self, e) -> float:
        """Wide enough for the type, the instance name above, and on every row the input
        pin's name and the output pin's name side by side."""
        from ..lang.unparse import expr

        ins, outs = self.in_pins(e), self.out_pins(e)
        offs = self.pin_off.get(e.id, {})
        first = offs.get(ins[0], 0)
        left: dict[int, str] = {offs.get(p, n) - first: self.pin_text(p) for n, p in
                                enumerate(ins)}
        right = {n: self.out_pin_label(e, p) for n, p in enumerate(outs)}
        rows = set(left) | set(right)
        need = max((_tw(left.get(r, "")) + _tw(right.get(r, "")) + 20 for r in rows),
                   default=0)
        title = _tw(_box_title(e), bold=True) + 16
        inst = _tw(expr(e.instance)) + 4 if e.instance is not None and e.type_name else 0
        return max(72.0, need, title, inst)

    def width(self, e) -> float:
        """The width an element takes in its column (wire stubs of contacts and coils
        included)."""
        k = e.kind
        if k in BOXES:
            return self.box_width(e)
        if k in ("contact", "coil"):
            return max(64.0, _tw(self.label(e)) + 10)
        if k in ("invar", "outvar", "inoutvar"):
            return max(64.0, _tw(self.label(e)) + 20)
        if k in ("jump", "label", "return"):
            return _tw(_mark_text(e), bold=True) + 8
        return 20.0


BOXES = ("fb", "func", "cmp")
_VARIABLE = re.compile(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*)*")
LABEL = 12  # font size of names and pins
OPERAND = 11  # font size of the operands written at box pins


def _tw(s: str, size: float = LABEL, bold: bool = False) -> float:
    """Width of a text in the network's monospace font (bold is as wide)."""
    return text_width(s, size, "mono")


def _box_title(e) -> str:
    from ..lang.unparse import expr

    if e.type_name:
        return e.type_name
    return expr(e.instance) if e.instance is not None else "?"  # a METHOD call: inst.Method


def _mark_text(e) -> str:
    return {"jump": f">> {e.label}", "label": f"{e.label}:", "return": "RETURN"}.get(e.kind, "")


@functools.lru_cache(maxsize=1)
def _library_pous() -> dict[str, Any]:
    """plclab's library blocks written in ST (BLINKER, ...), by name."""
    from ..lang.frontends.st import parse_library

    return {p.name: p for f in parse_library() for p in f.pous}


def _pin_of(pin: str, pins: list[str]) -> str:
    """The drawn pin an input arrives at: a text box's power flow ("") at its first pin."""
    if pin == "":
        return pins[0]
    return pin.upper() if pin.upper() in pins else pins[-1]


def _topological(elems: list, lay: _Layout) -> list:
    from ..lang.lower.network import execution_order

    return execution_order(elems)


class _Wires:
    """Wire segments, merged before drawing: a segment drawn twice or two overlapping
    segments on one line become one line (one junction, never doubled lines)."""

    def __init__(self) -> None:
        self.segs: dict[bool, list[tuple[float, float, float, float]]] = {False: [], True: []}

    def add(self, x1: float, y1: float, x2: float, y2: float, live: bool = False) -> None:
        if abs(x1 - x2) < 0.05 and abs(y1 - y2) < 0.05:
            return
        self.segs[live].append((round(x1, 1), round(y1, 1), round(x2, 1), round(y2, 1)))

    def svg(self) -> list[str]:
        out = []
        for live in (False, True):
            style = ON_WIRE if live else WIRE
            out += [_ln(*s, style) for s in merge_segments(self.segs[live])]
        return out


Segment = tuple[float, float, float, float]  # x1, y1, x2, y2


def merge_segments(segs: list[Segment]) -> list[Segment]:
    """Overlapping or touching collinear horizontal and vertical segments joined into one."""
    lines: dict[tuple[str, float], list[tuple[float, float]]] = {}
    other = []
    for x1, y1, x2, y2 in segs:
        if y1 == y2:
            lines.setdefault(("h", y1), []).append((min(x1, x2), max(x1, x2)))
        elif x1 == x2:
            lines.setdefault(("v", x1), []).append((min(y1, y2), max(y1, y2)))
        else:
            other.append((x1, y1, x2, y2))
    out = []
    for (kind, at), spans in sorted(lines.items()):
        spans.sort()
        cur = list(spans[0])
        merged = []
        for a, b in spans[1:]:
            if a <= cur[1] + 0.05:
                cur[1] = max(cur[1], b)
            else:
                merged.append(cur)
                cur = [a, b]
        merged.append(cur)
        for a, b in merged:
            out.append((a, at, b, at) if kind == "h" else (at, a, at, b))
    return out + other


def render_elems(elems: list, title: str = "", values: dict[str, Any] | None = None,
                 ladder: bool = True, pous: dict[str, Any] | None = None) -> Svg:
    """Draw one POU's network elements; ``ladder``: with power rails; ``pous``: the file's POUs
    by name (the pins of its function blocks)."""
    lay = _Layout(elems, values, pous)
    last = lay.columns()
    nrows = lay.rows()
    drawn = [e for e in elems if e.kind != "left" and e.id in lay.row]
    # columns as wide as what they hold: operands left of the boxes, the widest element,
    # the output operands right of them
    ncol = last + 1
    lefts, widths, rights = [12.0] * ncol, [64.0] * ncol, [22.0] * ncol
    for e in drawn:
        c = lay.col[e.id]
        widths[c] = max(widths[c], lay.width(e))
        if e.kind in BOXES:
            ops = [lay.operand_label(t) for t in lay.in_operands(e).values()]
            lefts[c] = max([lefts[c]] + [_tw(t, OPERAND) + 14 for t in ops])
            outs = [lay.operand_label(t) for t in lay.out_operands(e).values()]
            rights[c] = max([rights[c]] + [_tw(t, OPERAND) + 14 for t in outs])
    x0 = PAD + (30 if ladder else 0)
    y0 = PAD + 28
    starts = [float(x0)]
    for c in range(ncol):
        starts.append(starts[c] + lefts[c] + widths[c] + rights[c] + 16)

    def x_left(e) -> float:
        return starts[lay.col[e.id]] + lefts[lay.col[e.id]]

    def w_of(e) -> float:
        return lay.width(e) if e.kind in BOXES or e.kind in ("invar", "outvar", "inoutvar") \
            else widths[lay.col[e.id]]

    def y_row(r: float) -> float:
        return y0 + r * ROWH + ROWH / 2

    def out_point(i: int, pin: str) -> tuple[float, float]:
        s = lay.elems[i]
        return x_left(s) + w_of(s), y_row(lay.row[i] + lay.out_row(s, pin))

    parts: list[str] = []
    wires = _Wires()
    if title:
        parts.append(_txt(PAD, PAD + 12, title, extra="font-weight='bold'"))
    right = starts[last] + lefts[last] + widths[last] + 24
    rail = x0 - 12
    for e in drawn:
        r = lay.row[e.id]
        xl = x_left(e)
        pins = lay.in_pins(e)
        offs = lay.pin_off.get(e.id, {})
        by_pin: dict[str, list[tuple[int, str]]] = {}
        for pin, refs in e.inputs.items():
            by_pin.setdefault(_pin_of(pin, pins), []).extend(refs)
        stagger = 0
        for pin, refs in by_pin.items():
            ty = y_row(r + offs.get(pin, 0))
            feeds = []
            for i, sp in refs:
                if i < 0 or lay.elems[i].kind == "left":
                    wires.add(rail, ty, xl, ty, bool(values))
                    continue
                sx, sy = out_point(i, sp)
                feeds.append((sx, sy, lay.flows(lay.elems[i]) is True, i))
            if not feeds:
                continue
            back = [f for f in feeds if f[0] > xl - 12]
            ahead = [f for f in feeds if f[0] <= xl - 12]
            for sx, sy, live, i in back:  # a wire back to the left (a loop): go below
                lo_c, hi_c = lay.col[e.id], lay.col.get(i, lay.col[e.id])
                top_r = min(lay.row.get(i, r), r)
                between = [x for x in drawn if lo_c <= lay.col.get(x.id, -1) <= hi_c and
                           top_r <= lay.row[x.id] <= r + lay.box_rows(e)]
                low = y_row(max(lay.base(x) + (lay.box_rows(x) if x.kind in BOXES else 1) - 1
                                for x in between)) + ROWH / 2
                mid = xl - 10
                for a in ((sx, sy, sx + 10, sy), (sx + 10, sy, sx + 10, low),
                          (sx + 10, low, mid, low), (mid, low, mid, ty), (mid, ty, xl, ty)):
                    wires.add(*a, live)
            if not ahead:
                continue
            # one junction: every source's wire ends on one vertical line, right after the
            # rightmost source (a second pin of the same box fed from another row beside it)
            needs_vertical = any(abs(sy - ty) > 0.5 for _, sy, _, _ in ahead)
            jx = max(sx for sx, _, _, _ in ahead) + 10 + (6 * stagger if needs_vertical else 0)
            jx = min(jx, xl - 6)
            stagger += needs_vertical
            for sx, sy, live, _ in ahead:
                wires.add(sx, sy, jx, sy, live)
            levels = sorted({sy for _, sy, _, _ in ahead} | {ty})
            for a, b in zip(levels, levels[1:], strict=False):
                far = [f for f in ahead if (f[1] <= a if b <= ty else f[1] >= b)]
                wires.add(jx, a, jx, b, any(f[2] for f in far))
            wires.add(jx, ty, xl, ty, any(f[2] for f in ahead))
        parts.append(_draw(e, lay, xl, w_of(e), y_row(lay.base(e))))
        if e.kind == "coil" and ladder:
            wires.add(xl + w_of(e), y_row(lay.base(e)), right, y_row(lay.base(e)),
                      lay.flows(e) is True)
    parts = wires.svg() + parts
    width = right + PAD + 24
    height = y0 + nrows * ROWH + PAD
    if ladder:
        parts.append(_ln(rail, y0, rail, y0 + nrows * ROWH, RAIL))
        if any(e.kind == "coil" for e in elems):
            parts.append(_ln(right, y0, right, y0 + nrows * ROWH, RAIL))
    body = "".join(parts)
    return Svg(f"<svg xmlns='http://www.w3.org/2000/svg' width='{width:.0f}' "
               f"height='{height:.0f}' viewBox='0 0 {width:.0f} {height:.0f}'>"
               f"<title>{escape(title or 'network')}</title>"
               f"<rect width='100%' height='100%' fill='white'/>{body}</svg>")


def _draw(e, lay: _Layout, xl: float, w: float, y: float) -> str:
    """One element from xl, ``w`` wide, its (first) wire at height y."""
    k = e.kind
    xr = xl + w
    mid = (xl + xr) / 2
    live = lay.flows(e) is True
    color = ON if live else "#222"
    if k in ("contact", "coil"):
        style = f"stroke='{color}' stroke-width='2' fill='none'"
        fed = any(lay.flows(lay.elems[i]) is True if i >= 0 else lay.values
                  for i, _ in e.inputs.get("", []))
        out = [_ln(xl, y, mid - 9, y, ON_WIRE if fed else WIRE),
               _ln(mid + 9, y, xr, y, ON_WIRE if live else WIRE)]
        if k == "contact":
            out += [_ln(mid - 9, y - 11, mid - 9, y + 11, style),
                    _ln(mid + 9, y - 11, mid + 9, y + 11, style)]
        else:
            out.append(f"<path d='M{mid - 6:.1f},{y - 11:.1f} A11,11 0 0 0 {mid - 6:.1f},"
                       f"{y + 11:.1f} M{mid + 6:.1f},{y - 11:.1f} A11,11 0 0 1 {mid + 6:.1f},"
                       f"{y + 11:.1f}' {style}/>")
        mark = {"/": "/", "P": "P", "N": "N", "S": "S", "R": "R"}.get(e.mode, "")
        if mark:
            out.append(_txt(mid, y + 4, mark, "middle", f"fill='{color}'"))
        out.append(_txt(mid, y - 15, lay.label(e), "middle",
                        "class='name' fill='#0b3d91'"))
        return "".join(out)
    if k in BOXES:
        return _box(e, lay, xl, w, y)
    if k in ("invar", "outvar", "inoutvar"):
        return (f"<rect class='var' x='{xl:.1f}' y='{y - 11:.1f}' width='{w:.1f}' height='22' "
                f"rx='11' stroke='{color}' fill='#fffbe6'/>" +
                _txt(mid, y + 4, lay.label(e), "middle"))
    if k == "conn":
        return f"<circle cx='{mid:.1f}' cy='{y:.1f}' r='3' fill='#222'/>" + _ln(xl, y, xr, y)
    if k in ("jump", "label", "return"):
        return _txt(xl, y + 4, _mark_text(e), extra="font-weight='bold' fill='#8a3ffc'")
    return ""


def _box(e, lay: _Layout, xl: float, w: float, y: float) -> str:
    """A block as CODESYS and OpenPLC Editor draw it: the instance above, the type inside at
    the top, input pins left and output pins right, each with the operand written at it."""
    from ..lang.unparse import expr

    ins, outs = lay.in_pins(e), lay.out_pins(e)
    offs = lay.pin_off.get(e.id, {})
    first = offs.get(ins[0], 0)
    h = (lay.box_rows(e) - 1) * ROWH + 40
    top = y - 27
    xr = xl + w
    name = escape(_box_title(e))
    out = [f"<g class='box' data-type='{name}' data-elem='{e.id}'>",
           f"<rect x='{xl:.1f}' y='{top:.1f}' width='{w:.1f}' height='{h:.1f}' rx='3' {BOX}/>",
           _txt(xl + w / 2, top + 12, _box_title(e), "middle",
                "class='type' font-weight='bold' fill='#1f4e8c'")]
    if e.instance is not None and e.type_name:
        out.append(_txt(xl + w / 2, top - 4, expr(e.instance), "middle",
                        "class='instance' fill='#0b3d91'"))
    ops_in, ops_out = lay.in_operands(e), lay.out_operands(e)
    for n, p in enumerate(ins):
        py = y + (offs.get(p, n) - first) * ROWH
        out.append(_txt(xl + 4, py + 4, lay.pin_text(p), extra=f"class='pin in' data-pin='{p}'"))
        if p in e.neg_in:  # the IEC negation circle on the pin
            out.append(f"<circle cx='{xl - 4:.1f}' cy='{py:.1f}' r='4' fill='white' "
                       "stroke='#1f4e8c' stroke-width='1.4'/>")
        if p in ops_in:
            out.append(_ln(xl - 8, py, xl, py))
            out.append(_txt(xl - 6, py - 4, lay.operand_label(ops_in[p]), "end",
                            f"class='operand in' data-pin='{p}' font-size='{OPERAND}' "
                            "fill='#0b3d91'"))
    for n, p in enumerate(outs):
        py = y + n * ROWH
        out.append(_txt(xr - 4, py + 4, lay.out_pin_label(e, p), "end",
                        f"class='pin out' data-pin='{p}'"))
        if p in ops_out:
            out.append(_ln(xr, py, xr + 8, py))
            out.append(_txt(xr + 6, py - 4, lay.operand_label(ops_out[p]),
                            extra=f"class='operand out' data-pin='{p}' font-size='{OPERAND}' "
                            "fill='#0b3d91'"))
    out.append("</g>")
    return "".join(out)


def parse_source(text: str, file: str):
    """One source file parsed by its front end, not lowered (networks stay elements); the
    first error as a PlcError."""
    from ..lang.frontends.registry import for_file

    src, diags = for_file(file).parse(text, file)
    errors = [d for d in diags if d.severity == "error"]
    if errors:
        raise PlcError(errors[0].code, errors[0].message, errors[0].location, diagnostics=diags)
    return src


def _networks(src) -> list[tuple[Any, list]]:
    out = []
    for p in src.pous:
        nets = [b for b in p.pending if b.kind == "NETWORK"]
        if nets:
            out.append((p, [e for b in nets for e in b.payload]))
    return out


def network_pous(text: str, file: str) -> list[tuple[Any, list]]:
    """(POU, its network elements) for each LD/FBD POU of a source (parsed, not lowered)."""
    return _networks(parse_source(text, file))


def render_source(text: str, file: str, pou: str | None = None,
                  values: dict[str, Any] | None = None) -> Svg:
    """The network of POU ``pou`` (default: the first LD/FBD POU) of a source as SVG."""
    src = parse_source(text, file)
    chosen = [(p, els) for p, els in _networks(src) if pou is None or p.name == pou.upper()]
    if not chosen:
        raise PlcError("PLC4040", f"{file} has no LD or FBD body" + (
            f" named {pou}" if pou else "") + "; plclab render draws LD and FBD networks, SFC "
            "charts and ST/IL listings: name a POU with --pou")
    p, els = chosen[0]
    return render_elems(els, f"{p.kind} {p.spelling or p.name} ({p.language})", values,
                        ladder=p.language != "FBD", pous={q.name: q for q in src.pous})
